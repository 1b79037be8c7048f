//! Small private helper of `advect`: the degree-4 Dunavant rule in barycentric form, which the
//! L2 projection composes with sub-triangles.

/// A quadrature rule on the reference triangle: barycentric points and weights summing to 1.
pub(crate) struct TriRule {
    pub pts: &'static [[f64; 3]],
    pub w: &'static [f64],
}

const A1: f64 = 0.445_948_490_915_965;
const B1: f64 = 1.0 - 2.0 * A1;
const A2: f64 = 0.091_576_213_509_771;
const B2: f64 = 1.0 - 2.0 * A2;
const W1: f64 = 0.223_381_589_678_011;
const W2: f64 = 0.109_951_743_655_322;

/// Dunavant's 6-point rule, exact for polynomials of degree 4.
pub(crate) const DUNAVANT4: TriRule = TriRule {
    pts: &[
        [B1, A1, A1],
        [A1, B1, A1],
        [A1, A1, B1],
        [B2, A2, A2],
        [A2, B2, A2],
        [A2, A2, B2],
    ],
    w: &[W1, W1, W1, W2, W2, W2],
};
