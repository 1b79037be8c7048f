//! A plain closure as a 2D implicit function ([`Shape`]) for [`super::BuildSpec`].

use crate::geom::DVec2;
use crate::levelset::Shape;

/// The implicit function `u = f(p)` (negative inside) with derivatives by central differences
/// ([`Shape::gradient`], [`Shape::hessian`]). `f` need not be a distance function; back ends
/// redistance after building.
pub struct FnShape<F> {
    name: String,
    f: F,
}

impl<F: Fn(DVec2) -> f64 + Send + Sync> FnShape<F> {
    /// The implicit function `f`, called `name` in reports.
    pub fn new(name: impl Into<String>, f: F) -> Self {
        FnShape {
            name: name.into(),
            f,
        }
    }
}

impl<F: Fn(DVec2) -> f64 + Send + Sync> Shape for FnShape<F> {
    fn distance(&self, p: DVec2) -> f64 {
        (self.f)(p)
    }
    fn name(&self) -> String {
        self.name.clone()
    }
    fn is_distance(&self) -> bool {
        false
    }
}
