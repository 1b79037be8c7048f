//! Checks on whole metric fields.

use super::Sym2;
use crate::error::{Error, Result};

/// An error unless `metric` has exactly `n_points` entries, all finite and symmetric positive
/// definite. The error names the first bad vertex ([`Error::InvalidMetric`]) or the length
/// mismatch ([`Error::InvalidField`]).
pub fn validate_field(metric: &[Sym2], n_points: usize) -> Result<()> {
    if metric.len() != n_points {
        return Err(Error::InvalidField {
            name: "metric".into(),
            msg: format!(
                "{} tensors for {} vertices (need one per vertex)",
                metric.len(),
                n_points
            ),
        });
    }
    metric
        .iter()
        .enumerate()
        .try_for_each(|(v, m)| m.validate(v))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_the_first_bad_vertex() {
        let mut f = vec![Sym2::IDENTITY; 5];
        assert!(validate_field(&f, 5).is_ok());
        assert!(matches!(
            validate_field(&f, 6),
            Err(Error::InvalidField { .. })
        ));
        f[3] = Sym2::new(1.0, 2.0, 1.0);
        f[4] = Sym2::new(f64::NAN, 0.0, 1.0);
        match validate_field(&f, 5) {
            Err(Error::InvalidMetric { vertex, .. }) => assert_eq!(vertex, 3),
            other => panic!("expected an invalid metric at 3, got {other:?}"),
        }
    }
}
