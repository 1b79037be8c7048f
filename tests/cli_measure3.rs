//! `anisomesh measure MESH --against REF.mesh --sol U.sol` on tetrahedra: the zero level of a
//! sphere on a fine Kuhn mesh against the same sphere on a coarse one (both directions of the
//! sampled interface distance, the enclosed volumes), the mesh against itself, and the default
//! level set (the reference's interpolated at the measured vertices by point location).

use anisomesh::io::{self, Medit3, Sol};
use anisomesh::mesh3::Mesh3;
use anisomesh::DVec3;
use std::path::{Path, PathBuf};

mod common;
use common::{anisomesh_ok, s, scratch};

fn tmp(name: &str) -> PathBuf {
    scratch("cli-measure3").join(name)
}

const R: f64 = 0.3;

/// The Kuhn mesh `n³` of the unit cube and the sphere's distance at its vertices, as files.
fn sphere_case(n: usize) -> (PathBuf, PathBuf) {
    let mesh = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [n; 3]).unwrap();
    let m = Medit3 {
        points: mesh.points.clone(),
        point_ref: vec![0; mesh.points.len()],
        tets: mesh.tets.clone(),
        tet_ref: mesh.tet_ref.clone(),
        ..Medit3::default()
    };
    let (mp, up) = (
        tmp(&format!("sphere{n}.mesh")),
        tmp(&format!("sphere{n}.sol")),
    );
    io::write_medit3(&mp, &m).unwrap();
    let u: Vec<f64> = mesh
        .points
        .iter()
        .map(|p| (*p - DVec3::new(0.5, 0.47, 0.52)).length() - R)
        .collect();
    io::write_sol(&up, &Sol::scalar_dim(3, u)).unwrap();
    (mp, up)
}

fn against(mesh: &Path, reference: &Path, u: &Path, own: Option<&Path>) -> serde_json::Value {
    let mut args = vec![
        "measure",
        s(mesh),
        "--against",
        s(reference),
        "--sol",
        s(u),
        "--json",
    ];
    if let Some(v) = own {
        args.extend(["--level-set", s(v)]);
    }
    let v: serde_json::Value = serde_json::from_str(&anisomesh_ok(&args)).unwrap();
    v["against"].clone()
}

#[test]
fn measure_against_a_sphere_on_tetrahedra() {
    let (coarse, uc) = sphere_case(10);
    let (fine, uf) = sphere_case(24);
    let exact = 4.0 / 3.0 * std::f64::consts::PI * R.powi(3);
    // Against itself: nothing to measure.
    let z = against(&fine, &fine, &uf, None);
    assert!(z["hausdorff"].as_f64().unwrap() < 1e-10, "{z}");
    assert!(z["relative_area_error"].as_f64().unwrap() < 1e-10, "{z}");
    // Two P1 approximations of the same sphere: each lies within about L² / (6 R) of the sphere
    // (facet sag, L the longest edge, the cube diagonal √3 h of a Kuhn cell), plus as much for
    // the crossing points on the edges; the distance between them is bounded by the sum.
    let z = against(&fine, &coarse, &uc, Some(&uf));
    let (to, from) = (
        z["to_reference_max"].as_f64().unwrap(),
        z["from_reference_max"].as_f64().unwrap(),
    );
    let (vf, vc) = (
        z["area"].as_f64().unwrap(),
        z["reference_area"].as_f64().unwrap(),
    );
    eprintln!(
        "sphere 24^3 against 10^3: to {to:.3e}, from {from:.3e}; volumes {vf:.6} {vc:.6} (exact \
         {exact:.6}), relative error {:.3e}",
        z["relative_area_error"].as_f64().unwrap()
    );
    let (lc, lf) = (3f64.sqrt() / 10.0, 3f64.sqrt() / 24.0);
    let bound = (lc * lc + lf * lf) / (3.0 * R);
    assert!(
        to > 1e-4 && from > 1e-4 && to.max(from) < bound,
        "{z} vs {bound}"
    );
    assert!((vf - exact).abs() < 0.02 * exact && (vc - exact).abs() < 0.08 * exact);
    assert!(
        (vf - vc).abs() > (vf - exact).abs(),
        "the coarse sphere is the less accurate"
    );
    let rel = z["relative_area_error"].as_f64().unwrap();
    assert!((rel - (vf - vc).abs() / vc).abs() < 1e-14);
    // Default: the coarse level set interpolated at the fine vertices (point location): its
    // zero level follows the coarse one more closely than the fine mesh's own sphere does.
    let z = against(&fine, &coarse, &uc, None);
    eprintln!("coarse level set on the fine mesh: {z}");
    assert!(z["hausdorff"].as_f64().unwrap() < to.max(from), "{z}");
    assert!(
        z["relative_area_error"].as_f64().unwrap() < rel / 2.0,
        "{z}"
    );
}
