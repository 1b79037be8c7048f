//! `anisomesh info FILE [--sol METRIC]`: what is in a mesh file and how good its elements are.

use anisomesh::io::{self, AnyFile, SolField};
use anisomesh::metric::{quality_stats, QualityStats, Sym2};
use anisomesh::{Error, Mesh2, Result};
use std::collections::BTreeMap;
use std::path::Path;

/// Prints counts, bounding box, labels and quality statistics of `file`.
pub fn run(file: &Path, sol: Option<&Path>) -> Result<()> {
    match io::read_any(file)? {
        AnyFile::Mesh2(mesh) => mesh2(file, &mesh, sol),
        AnyFile::Medit3(m) => {
            println!("{}: 3D Medit mesh", file.display());
            println!("  vertices      {}", m.points.len());
            println!("  tetrahedra    {}", m.tets.len());
            println!("  triangles     {}", m.tris.len());
            println!("  regions       {:?}", label_counts(&m.tet_ref));
            Ok(())
        }
        AnyFile::Sol(s) => {
            println!("{}: solution file, dimension {}", file.display(), s.dim);
            for (i, f) in s.fields.iter().enumerate() {
                let kind = match f {
                    SolField::Scalar(_) => "scalar",
                    SolField::Vector(_) => "vector",
                    SolField::Tensor2(_) | SolField::Tensor3(_) => "symmetric tensor",
                };
                println!("  field {i}: {kind}, {} vertices", f.len());
            }
            Ok(())
        }
        AnyFile::Surface(s) => {
            println!("{}: surface", file.display());
            println!("  vertices      {}", s.points.len());
            println!("  triangles     {}", s.tris.len());
            // A closed surface: its orientation repair, volume and area; otherwise why not.
            match anisomesh::levelset::TriangulatedShape::from_mesh(&s) {
                Ok(shape) => {
                    println!(
                        "  closed        yes, {} component(s), {} triangles re-oriented",
                        shape.components(),
                        shape.flipped_triangles()
                    );
                    println!("  volume        {:.10}", shape.volume());
                    println!("  area          {:.10}", shape.area());
                }
                Err(e) => println!("  closed        no: {e}"),
            }
            Ok(())
        }
    }
}

fn label_counts(labels: &[i32]) -> BTreeMap<i32, usize> {
    let mut counts = BTreeMap::new();
    for &l in labels {
        *counts.entry(l).or_insert(0) += 1;
    }
    counts
}

fn mesh2(file: &Path, mesh: &Mesh2, sol: Option<&Path>) -> Result<()> {
    mesh.check()?;
    println!("{}: 2D triangle mesh", file.display());
    println!("  vertices      {}", mesh.n_points());
    println!("  triangles     {}", mesh.n_live_tris());
    println!("  edges         {}", mesh.edges().len());
    if let Some((lo, hi)) = mesh.bounding_box() {
        println!(
            "  bounding box  [{:.6}, {:.6}] x [{:.6}, {:.6}]",
            lo.x, hi.x, lo.y, hi.y
        );
    }
    println!("  area          {:.10}", mesh.area());
    let boundary: Vec<i32> = mesh.boundary_edges().iter().map(|e| e.2).collect();
    println!(
        "  boundary      {} edges, labels {:?}",
        boundary.len(),
        label_counts(&boundary)
    );
    println!("  sub-domains   {:?}", label_counts(&mesh.tri_ref));
    println!(
        "  corners       {}, required vertices {}",
        mesh.corner.iter().filter(|&&c| c).count(),
        mesh.required.iter().filter(|&&c| c).count()
    );
    let euclid = vec![Sym2::IDENTITY; mesh.n_points()];
    print_quality(
        "shape quality (Euclidean Q_ani, 1 = equilateral)",
        &quality_stats(mesh, &euclid),
        false,
    );
    if let Some(sol_path) = sol {
        let s = io::read_sol_for(sol_path, mesh.n_points())?;
        let metric = s
            .fields
            .iter()
            .find_map(|f| match f {
                SolField::Tensor2(m) => Some(m.clone()),
                _ => None,
            })
            .ok_or_else(|| {
                Error::InvalidInput(format!(
                    "{}: no symmetric tensor field (metric) in this .sol",
                    sol_path.display()
                ))
            })?;
        anisomesh::metric::validate_field(&metric, mesh.n_points())?;
        print_quality("quality in the metric", &quality_stats(mesh, &metric), true);
    }
    Ok(())
}

fn print_quality(title: &str, q: &QualityStats, lengths: bool) {
    println!("  {title}:");
    println!(
        "    Q_ani mean {:.4}, max {:.4} (triangle {})",
        q.q_ani_mean, q.q_ani_max, q.worst_tri
    );
    if lengths {
        println!(
            "    edge lengths in [1/sqrt2, sqrt2]: {:.2}% (min {:.3}, max {:.3})",
            100.0 * q.edge_length_in_range,
            q.edge_length_min,
            q.edge_length_max
        );
    }
    let total: usize = q.q_ani_histogram.iter().map(|h| h.1).sum();
    let mut line = String::from("    histogram:");
    for (upper, count) in &q.q_ani_histogram {
        if *count > 0 {
            line += &format!(
                " <={upper}: {:.1}%",
                100.0 * *count as f64 / total.max(1) as f64
            );
        }
    }
    println!("{line}");
}
