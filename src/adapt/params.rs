//! The parameters the operators of every dimension read: length bounds, quality floor, curve
//! tolerance, insertion switch and the metric interpolation at new vertices.

/// Parameters the operators read (copied from [`super::AdaptOptions`]; the same for every dimension).
#[derive(Debug, Clone, Copy)]
pub(crate) struct OpParams {
    /// Edges shorter than this (metric length) are collapsed.
    pub l_min: f64,
    /// Edges longer than this are split.
    pub l_max: f64,
    /// Quality floor: an operation may not create an element with `Q_ani` above this unless the
    /// elements it replaces were already worse.
    pub q_max: f64,
    /// Distance a collapsing curve vertex may lie off the segment that replaces its two curve
    /// edges (twice the area it removes, per unit length). 0: only exactly collinear vertices
    /// of a boundary or interface curve are removed.
    pub curve_tol: f64,
    /// Insert new vertices with the anisotropic Delaunay kernel (`insert.rs`) where possible
    /// instead of plain edge splits.
    pub insertion: bool,
    /// How the metric at a new or moved vertex is interpolated when no source provides it.
    pub interpolation: MetricInterpolation,
}

/// Interpolation of the vertex metric at new or moved vertices (when the metric source has
/// none: a metric read from a file, or given only at the input vertices).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub enum MetricInterpolation {
    /// Log-Euclidean mean ([`crate::metric::interpolate_log`]): sizes vary geometrically.
    #[default]
    LogEuclidean,
    /// Sizes vary linearly in the simultaneous-reduction basis ([`crate::metric::lerp_sizes`],
    /// the rule of MMG's `interpmet22`): between a fine and a coarse metric the sizes grow much
    /// faster, so a metric known only on a coarse background yields far fewer vertices.
    LinearSizes,
}
