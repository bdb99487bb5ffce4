//! `hull`: the control-net box (convex hull property of the tensor product; valid for NURBS
//! surfaces because every weight is > 0). Inner bounds: the four corner values.

use super::{corner_values, enclosure, net_box, SurfaceEncloser};
use crate::enclose::{Enclosure, Guarantee, Termination};
use crate::surface::model::NurbsSurface;

/// The box of the control net.
#[derive(Debug, Clone, Copy, Default)]
pub struct NetHull;

impl SurfaceEncloser for NetHull {
    fn name(&self) -> &'static str {
        "hull"
    }
    fn guarantee(&self) -> Guarantee {
        Guarantee::Verified
    }
    fn enclose_prepared(&self, s: &NurbsSurface) -> Enclosure {
        let corners = corner_values(s);
        let inner: Vec<(f64, f64)> = (0..s.dim())
            .map(|j| {
                corners
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), c| {
                        (lo.min(c[j].sup()), hi.max(c[j].inf()))
                    })
            })
            .collect();
        enclosure(
            self.name(),
            true,
            net_box(s, &inner, Termination::Direct, 4),
        )
    }
}
