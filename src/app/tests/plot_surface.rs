//! The surface pictures: the star and a sphere render without error, are not blank, are
//! deterministic, colour scalars, and a plane cut of a tetrahedral grid is drawn.

use crate::app::plot::surface::{
    render_surfaces_rgb, render_tet_cut_rgb, CutPlane, SurfacePanel, View,
};
use crate::app::plot::RgbImage;
use anisomesh::levelset::{icosphere, radial_surface, StarSurface};
use anisomesh::mesh3::Mesh3;
use anisomesh::DVec3;

/// Standard deviation of the grey level over all pixels.
fn variance(img: &RgbImage) -> f64 {
    let grey: Vec<f64> = img
        .pixels
        .chunks_exact(3)
        .map(|c| (c[0] as f64 + c[1] as f64 + c[2] as f64) / 3.0)
        .collect();
    let mean = grey.iter().sum::<f64>() / grey.len() as f64;
    grey.iter().map(|g| (g - mean).powi(2)).sum::<f64>() / grey.len() as f64
}

/// Fraction of pixels that are not white.
fn covered(img: &RgbImage) -> f64 {
    let n = img
        .pixels
        .chunks_exact(3)
        .filter(|c| c != &[255, 255, 255])
        .count();
    n as f64 / (img.width * img.height) as f64
}

#[test]
fn star_and_sphere_render_deterministically() {
    let star = radial_surface(DVec3::ZERO, |d| StarSurface::PAPER.radius_towards(d), 4);
    let sphere = icosphere(3);
    let scalars: Vec<f64> = sphere.points.iter().map(|p| p.z).collect();
    let view = View {
        size: 200,
        wireframe: true,
        ..View::default()
    };
    let panels = [
        SurfacePanel {
            surface: &star,
            scalars: None,
            title: "star".into(),
        },
        SurfacePanel {
            surface: &sphere,
            scalars: Some(&scalars),
            title: "sphere".into(),
        },
    ];
    let img = render_surfaces_rgb(&panels, &view).unwrap();
    // Two panels and a colour bar.
    assert_eq!(img.height, 200);
    assert!(img.width > 400, "{}", img.width);
    assert!(variance(&img) > 500.0, "variance {}", variance(&img));
    assert!(
        img.distinct_colours() > 500,
        "{} colours",
        img.distinct_colours()
    );
    let again = render_surfaces_rgb(&panels, &view).unwrap();
    assert_eq!(img, again, "rendering is not deterministic");
    // The sphere panel shows the colour map: yellow at its top (z up, seen from above) and
    // blue-green lower down. Scan the panel's middle column.
    let column: Vec<[u8; 3]> = (0..200).map(|y| img.pixel(300, y)).collect();
    assert!(
        column
            .iter()
            .any(|c| c[0] > 150 && c[1] > 150 && c[2] < 100),
        "no yellow"
    );
    assert!(
        column.iter().any(|c| c[2] > c[1] + 20 && c[2] > c[0] + 20),
        "no blue"
    );

    // Orthographic and perspective views of a plain sphere cover a sensible part of the panel.
    for perspective in [false, true] {
        let view = View {
            size: 160,
            perspective,
            ..View::default()
        };
        let panel = SurfacePanel {
            surface: &sphere,
            scalars: None,
            title: String::new(),
        };
        let img = render_surfaces_rgb(&[panel], &view).unwrap();
        let c = covered(&img);
        assert!(
            (0.3..0.7).contains(&c),
            "perspective {perspective}: coverage {c}"
        );
    }
}

#[test]
fn bad_input_is_an_error() {
    let sphere = icosphere(1);
    let short = vec![0.0; 3];
    let panel = SurfacePanel {
        surface: &sphere,
        scalars: Some(&short),
        title: String::new(),
    };
    assert!(render_surfaces_rgb(&[panel], &View::default()).is_err());
    assert!(render_surfaces_rgb(&[], &View::default()).is_err());
}

#[test]
fn tet_cut_is_drawn_and_coloured() {
    let mesh = Mesh3::kuhn_box(DVec3::splat(-1.0), DVec3::ONE, [6; 3]).unwrap();
    let values: Vec<f64> = (0..mesh.tets.len())
        .map(|t| mesh.tet_points(t).iter().sum::<DVec3>().x)
        .collect();
    let plane = CutPlane {
        point: DVec3::new(0.0, 0.0, 0.1),
        normal: DVec3::Z,
    };
    let view = View {
        size: 240,
        wireframe: true,
        ..View::facing(DVec3::Z)
    };
    let img = render_tet_cut_rgb(&mesh, &plane, &values, "cut", &view).unwrap();
    // The 2 × 2 square cut fills about a quarter of panel and colour bar.
    assert!(covered(&img) > 0.15, "coverage {}", covered(&img));
    assert!(img.distinct_colours() > 50);
    let again = render_tet_cut_rgb(&mesh, &plane, &values, "cut", &view).unwrap();
    assert_eq!(img, again);
    let away = CutPlane {
        point: DVec3::new(0.0, 0.0, 5.0),
        normal: DVec3::Z,
    };
    assert!(render_tet_cut_rgb(&mesh, &away, &values, "", &view).is_err());
    assert!(render_tet_cut_rgb(&mesh, &plane, &values[1..], "", &view).is_err());
}
