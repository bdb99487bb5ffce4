//! The NURBS curve model: validated data, domain, dimension.

use crate::error::CurveError;

/// A NURBS curve C(u) = sum N_{i,p}(u) w_i P_i / sum N_{i,p}(u) w_i (thesis def. 3.1).
///
/// Invariants established by [`NurbsCurve::new`] (see `docs/formats.md`):
/// degree p >= 1; n + 1 >= p + 1 control points, all of one dimension d >= 1, finite;
/// exactly n + p + 2 finite, non-decreasing knots, no value repeated more than p + 1 times;
/// weights (if any) finite and > 0; the domain [u_p, u_{n+1}] has positive length.
/// The curve is the one the f64 values define exactly; every guarantee refers to it.
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsCurve {
    degree: usize,
    dim: usize,
    knots: Vec<f64>,
    /// Control points, row-major: point i is `points[i*dim .. (i+1)*dim]`.
    points: Vec<f64>,
    /// `None` for a non-rational curve (all weights 1).
    weights: Option<Vec<f64>>,
}

impl NurbsCurve {
    /// Validate and build a curve from nested control points.
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        control_points: Vec<Vec<f64>>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, CurveError> {
        let dim = control_points.first().map_or(0, |p| p.len());
        if let Some(i) = control_points.iter().position(|p| p.is_empty()) {
            return Err(CurveError::ZeroDimension { index: i });
        }
        if let Some((i, p)) = control_points
            .iter()
            .enumerate()
            .find(|(_, p)| p.len() != dim)
        {
            return Err(CurveError::DimensionMismatch {
                index: i,
                expected: dim,
                got: p.len(),
            });
        }
        let mut flat = Vec::with_capacity(control_points.len() * dim);
        for p in &control_points {
            flat.extend_from_slice(p);
        }
        Self::from_flat(degree, dim.max(1), knots, flat, weights)
    }

    /// Validate and build a curve from row-major control point coordinates of dimension `dim`.
    pub fn from_flat(
        degree: usize,
        dim: usize,
        knots: Vec<f64>,
        points: Vec<f64>,
        weights: Option<Vec<f64>>,
    ) -> Result<Self, CurveError> {
        if degree == 0 {
            return Err(CurveError::InvalidDegree(0));
        }
        if dim == 0 {
            return Err(CurveError::ZeroDimension { index: 0 });
        }
        if points.len() % dim != 0 {
            return Err(CurveError::DimensionMismatch {
                index: points.len() / dim,
                expected: dim,
                got: points.len() % dim,
            });
        }
        let np = points.len() / dim;
        // Checked arithmetic: a huge degree (say 10^9 from JSON) must give an error, not an
        // overflow or a huge allocation.
        let needed = degree
            .checked_add(1)
            .ok_or(CurveError::InvalidDegree(degree as u64))?;
        if np < needed {
            return Err(CurveError::TooFewControlPoints {
                degree,
                needed,
                got: np,
            });
        }
        if let Some(k) = points.iter().position(|x| !x.is_finite()) {
            return Err(CurveError::NonFiniteCoordinate {
                index: k / dim,
                coord: k % dim,
                value: points[k],
            });
        }
        let expected = np + degree + 1;
        if knots.len() != expected {
            return Err(CurveError::KnotCount {
                expected,
                got: knots.len(),
            });
        }
        if let Some(k) = knots.iter().position(|x| !x.is_finite()) {
            return Err(CurveError::NonFiniteKnot {
                index: k,
                value: knots[k],
            });
        }
        let mut run_start = 0;
        for k in 1..knots.len() {
            if knots[k] < knots[k - 1] {
                return Err(CurveError::DecreasingKnots {
                    index: k,
                    value: knots[k],
                    previous: knots[k - 1],
                });
            }
            if knots[k] != knots[k - 1] {
                run_start = k;
            } else if k - run_start + 1 > degree + 1 {
                return Err(CurveError::KnotMultiplicity {
                    index: run_start,
                    value: knots[k],
                    multiplicity: k - run_start + 1,
                    max: degree + 1,
                });
            }
        }
        if let Some(w) = &weights {
            if w.len() != np {
                return Err(CurveError::WeightCount {
                    expected: np,
                    got: w.len(),
                });
            }
            if let Some(i) = w.iter().position(|x| !(x.is_finite() && *x > 0.0)) {
                return Err(CurveError::InvalidWeight {
                    index: i,
                    value: w[i],
                });
            }
        }
        let n = np - 1;
        if knots[degree] >= knots[n + 1] {
            return Err(CurveError::EmptyDomain {
                p: degree,
                n,
                start: knots[degree],
                end: knots[n + 1],
            });
        }
        // All weights 1 is the non-rational case: drop them so the kernels skip the w row.
        let weights = weights.filter(|w| w.iter().any(|&x| x != 1.0));
        Ok(NurbsCurve {
            degree,
            dim,
            knots,
            points,
            weights,
        })
    }

    /// Degree p.
    #[inline]
    pub fn degree(&self) -> usize {
        self.degree
    }
    /// Dimension d of the control points.
    #[inline]
    pub fn dim(&self) -> usize {
        self.dim
    }
    /// Number of control points n + 1.
    #[inline]
    pub fn num_points(&self) -> usize {
        // (validation fixes m + 1 = n + p + 2 knots, and nothing changes a curve after it:
        // no integer division by the dimension on this hot path)
        debug_assert_eq!(
            self.knots.len() - self.degree - 1,
            self.points.len() / self.dim
        );
        self.knots.len() - self.degree - 1
    }
    /// The knot vector u_0 .. u_m.
    #[inline]
    pub fn knots(&self) -> &[f64] {
        &self.knots
    }
    /// Control point i.
    #[inline]
    pub fn control_point(&self, i: usize) -> &[f64] {
        &self.points[i * self.dim..(i + 1) * self.dim]
    }
    /// All control point coordinates, row-major.
    #[inline]
    pub fn points_flat(&self) -> &[f64] {
        &self.points
    }
    /// Control points as nested vectors.
    pub fn control_points(&self) -> Vec<Vec<f64>> {
        self.points.chunks(self.dim).map(|c| c.to_vec()).collect()
    }
    /// Weights, `None` if the curve is non-rational (all weights 1).
    #[inline]
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }
    /// Weight of control point i.
    #[inline]
    pub fn weight(&self, i: usize) -> f64 {
        self.weights.as_ref().map_or(1.0, |w| w[i])
    }
    /// Whether the curve has non-unit weights.
    #[inline]
    pub fn is_rational(&self) -> bool {
        self.weights.is_some()
    }
    /// The parameter domain [u_p, u_{n+1}].
    #[inline]
    pub fn domain(&self) -> (f64, f64) {
        (self.knots[self.degree], self.knots[self.num_points()])
    }
    /// The exact range (min, max) of coordinate j over the control points `points` (indices):
    /// the control-point box of those points (convex hull property, thesis prop. 2.1; min and
    /// max of f64 data involve no rounding). The one copy of this kernel.
    pub fn coord_range(&self, j: usize, points: std::ops::RangeInclusive<usize>) -> (f64, f64) {
        crate::num::min_max(points.map(|i| self.points[i * self.dim + j]))
    }

    /// Coordinate scale: the largest |control point coordinate| of coordinate j (at least the
    /// smallest positive normal, so it can be used as a divisor).
    pub fn coord_scale(&self, j: usize) -> f64 {
        self.points
            .iter()
            .skip(j)
            .step_by(self.dim)
            .fold(f64::MIN_POSITIVE, |m, x| m.max(x.abs()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ok() -> (usize, Vec<f64>, Vec<Vec<f64>>) {
        (
            2,
            vec![0., 0., 0., 0.5, 1., 1., 1.],
            vec![vec![0., 0.], vec![1., 2.], vec![2., -1.], vec![3., 0.]],
        )
    }

    #[test]
    fn valid_curve() {
        let (p, k, c) = ok();
        let cu = NurbsCurve::new(p, k, c, Some(vec![1.; 4])).unwrap();
        assert!(!cu.is_rational());
        assert_eq!(cu.domain(), (0.0, 1.0));
        assert_eq!(cu.control_point(2), &[2., -1.]);
    }

    #[test]
    fn each_invalid_case_is_typed() {
        let (p, k, c) = ok();
        let e = |r: Result<NurbsCurve, CurveError>| r.unwrap_err().kind();
        assert_eq!(
            e(NurbsCurve::new(0, k.clone(), c.clone(), None)),
            "invalid_degree"
        );
        assert_eq!(
            e(NurbsCurve::new(p, k[1..].to_vec(), c.clone(), None)),
            "knot_count"
        );
        let mut kk = k.clone();
        kk[3] = f64::NAN;
        assert_eq!(
            e(NurbsCurve::new(p, kk, c.clone(), None)),
            "non_finite_knot"
        );
        let mut kk = k.clone();
        kk[3] = -1.0;
        assert_eq!(
            e(NurbsCurve::new(p, kk, c.clone(), None)),
            "decreasing_knots"
        );
        let mut cc = c.clone();
        cc[1] = vec![1.0];
        assert_eq!(
            e(NurbsCurve::new(p, k.clone(), cc, None)),
            "dimension_mismatch"
        );
        let mut cc = c.clone();
        cc[2][1] = f64::INFINITY;
        assert_eq!(
            e(NurbsCurve::new(p, k.clone(), cc, None)),
            "non_finite_coordinate"
        );
        assert_eq!(
            e(NurbsCurve::new(
                p,
                k.clone(),
                c.clone(),
                Some(vec![1., 0., 1., 1.])
            )),
            "invalid_weight"
        );
        assert_eq!(
            e(NurbsCurve::new(p, k.clone(), c.clone(), Some(vec![1.; 3]))),
            "weight_count"
        );
        assert_eq!(
            e(NurbsCurve::new(p, vec![0.; 7], c.clone(), None)),
            "knot_multiplicity"
        );
        assert_eq!(
            e(NurbsCurve::new(
                2,
                vec![0., 0., 1., 1., 2., 2.],
                vec![vec![0.]; 3],
                None
            )),
            "empty_domain"
        );
        assert_eq!(
            e(NurbsCurve::new(p, k.clone(), vec![vec![0.]; 2], None)),
            "too_few_control_points"
        );
        assert_eq!(e(NurbsCurve::new(usize::MAX, k, c, None)), "invalid_degree");
    }

    #[test]
    fn messages_name_field_and_position() {
        let (p, mut k, c) = ok();
        k[4] = 0.1;
        let m = NurbsCurve::new(p, k, c, None).unwrap_err().to_string();
        assert!(m.contains("knots[4]"), "{m}");
    }
}
