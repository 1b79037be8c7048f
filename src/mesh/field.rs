//! Validation of P1 fields: one value per vertex of a mesh, every value finite.

use crate::error::{Error, Result};

/// Checks that the P1 field `u` named `name` holds exactly `n_points` values, all finite.
///
/// The [`Error::InvalidField`] names the field and the first bad vertex: for a short field the
/// first vertex without a value, for a long one the first value without a vertex, otherwise the
/// first vertex whose value is NaN or infinite.
pub fn check_p1_field(n_points: usize, u: &[f64], name: &str) -> Result<()> {
    let bad = |msg: String| {
        Err(Error::InvalidField {
            name: name.into(),
            msg,
        })
    };
    let n = n_points;
    if u.len() < n {
        return bad(format!(
            "{} values for {n} vertices: vertex {} has no value",
            u.len(),
            u.len()
        ));
    }
    if u.len() > n {
        return bad(format!(
            "{} values for {n} vertices: value {n} has no vertex",
            u.len()
        ));
    }
    match u.iter().position(|x| !x.is_finite()) {
        Some(v) => bad(format!("vertex {v} has the non-finite value {}", u[v])),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn msg(r: Result<()>) -> String {
        match r {
            Err(Error::InvalidField { name, msg }) => format!("{name}: {msg}"),
            other => panic!("expected InvalidField, got {other:?}"),
        }
    }

    #[test]
    fn accepts_a_finite_field_of_the_right_length() {
        assert!(check_p1_field(3, &[0.0, -1.5, 2.0], "u").is_ok());
        assert!(check_p1_field(0, &[], "u").is_ok());
    }

    #[test]
    fn names_the_field_and_the_first_bad_vertex() {
        assert_eq!(
            msg(check_p1_field(4, &[0.0; 2], "phi")),
            "phi: 2 values for 4 vertices: vertex 2 has no value"
        );
        assert_eq!(
            msg(check_p1_field(2, &[0.0; 3], "phi")),
            "phi: 3 values for 2 vertices: value 2 has no vertex"
        );
        let u = [0.0, 1.0, f64::INFINITY, f64::NAN];
        assert_eq!(
            msg(check_p1_field(4, &u, "level set")),
            "level set: vertex 2 has the non-finite value inf"
        );
    }
}
