//! The operator workspace: cached qualities stay exact through the passes and renumberings.

use crate::adapt::params::{MetricInterpolation, OpParams};
use crate::adapt::tri::Ctx;
use crate::adapt::tri::{collapse, flip, refine, smooth};
use crate::geom::DVec2;
use crate::mesh::{GridPattern, Mesh2};
use crate::metric::Sym2;
use std::sync::atomic::Ordering::Relaxed;

/// Every quality the operators cached (computed by a check and stored on apply, or carried
/// through a renumbering) is bit-equal to a fresh [`Ctx::q`], in both quality modes.
#[test]
fn cached_qualities_are_exact() {
    for exact in [false, true] {
        let mut mesh =
            Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 9, 9, GridPattern::default()).unwrap();
        let mut metric: Vec<Sym2> = mesh
            .points
            .iter()
            .map(|p| {
                let d = (p.y - 0.4 - 0.3 * p.x * p.x).abs();
                Sym2::from_sizes([0.08, 0.004 + 0.5 * d], DVec2::new(1.0, 0.6 * p.x))
            })
            .collect();
        let mut fields: Vec<Vec<f64>> = Vec::new();
        let params = OpParams {
            l_min: std::f64::consts::FRAC_1_SQRT_2,
            l_max: std::f64::consts::SQRT_2,
            q_max: 5.0,
            curve_tol: 0.0,
            insertion: true,
            interpolation: MetricInterpolation::LinearSizes,
        };
        let mut ctx = Ctx::new(&mut mesh, &mut metric, &mut fields, None, params);
        if exact {
            ctx = ctx.exact_quality();
        }
        let mut ops = 0;
        for round in 0..12 {
            ops += refine::pass(&mut ctx) + flip::pass(&mut ctx);
            if round % 3 == 2 {
                ops += collapse::pass(&mut ctx) + smooth::pass(&mut ctx);
                ctx.renumber_spatially();
            }
        }
        assert!(ops > 500, "too little work to test: {ops} operations");
        let mut known = 0;
        for t in 0..ctx.mesh.n_tris() {
            let q = f64::from_bits(ctx.tq[t].load(Relaxed));
            if ctx.mesh.is_deleted(t) || q.is_nan() {
                continue;
            }
            known += 1;
            let fresh = ctx.q(ctx.mesh.tris[t]);
            assert_eq!(
                q.to_bits(),
                fresh.to_bits(),
                "exact {exact}, tri {t}: {q} vs {fresh}"
            );
        }
        assert!(known > ctx.mesh.n_tris() / 2, "only {known} cached");
        ctx.mesh.check().unwrap();
    }
}
