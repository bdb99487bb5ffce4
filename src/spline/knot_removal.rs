//! Knot removal and inverse knot insertion (thesis sec. 4.2.2 "Entfernen von Knoten" and
//! sec. 4.2.1 "Umgekehrte Knoteneinfügung"; The NURBS Book, Piegl & Tiller, sec. 5.4 and
//! algorithm A5.8 `RemoveCurveKnot`).
//!
//! * [`HSpline::remove_knot_once`] — one removal of a knot, generic over [`Scalar`] (f64,
//!   intervals, MPFR): the new control points of eqs. (5.28)/(5.29) from both ends of the
//!   affected range, and the mismatch that decides whether the knot is removable (A5.8's
//!   distance test).
//! * [`HSpline::remove_knot`] — A5.8 itself: remove a knot up to `num` times while the
//!   mismatch stays within a tolerance (homogeneous coordinates, as in A5.8).
//! * [`NurbsCurve::remove_knot`] — the verified version: remove as often as the curve allows
//!   within a tolerance on the *curve*, with a verified bound on how far the result is from
//!   the original ([`removal_error_bound`]), reported in [`KnotRemoval`].
//! * [`NurbsCurve::inverse_insertion_knot`] — the knot whose insertion creates a given point on
//!   a leg of the control polygon.

use crate::error::EvalError;
use crate::num::{iv, Scalar};
use crate::spline::bspline::HSpline;
use crate::spline::curve::NurbsCurve;
use crate::spline::knots::multiplicity;
use inari::Interval;
use thiserror::Error;

/// Why a knot cannot be removed, or an inverse insertion is not defined.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum KnotRemovalError {
    /// The knot is NaN or infinite.
    #[error("knot: expected a finite number, got {value}")]
    NonFiniteKnot {
        /// the value given
        value: f64,
    },
    /// The value is not in the knot vector.
    #[error("knot: {value} is not a knot of the curve")]
    KnotNotPresent {
        /// the value given
        value: f64,
    },
    /// Only knots strictly inside the domain can be removed (the end knots define it).
    #[error("knot: {value} is not strictly inside the domain [{start}, {end}]; only interior knots can be removed")]
    NotInterior {
        /// the value given
        value: f64,
        /// domain start
        start: f64,
        /// domain end
        end: f64,
    },
    /// A tolerance that is negative or not finite.
    #[error("tol: expected a finite number >= 0, got {value}")]
    InvalidTolerance {
        /// the value given
        value: f64,
    },
    /// Inverse insertion: no leg P_{i-1} P_i with this index.
    #[error("leg: expected an index 1..={max} (the leg from control point i-1 to i), got {index}")]
    LegIndex {
        /// the index given
        index: usize,
        /// the last control point index n
        max: usize,
    },
    /// Inverse insertion: the point has the wrong dimension or is not finite.
    #[error("point: expected {expected} finite coordinates, got {got:?}")]
    InvalidPoint {
        /// the curve's dimension
        expected: usize,
        /// the point given
        got: Vec<f64>,
    },
    /// Inverse insertion: P_{i-1} = P_i, so the leg has no interior points to create.
    #[error("leg {index}: control points {} and {index} coincide", index - 1)]
    DegenerateLeg {
        /// the leg index i
        index: usize,
    },
    /// Inverse insertion: the knot found lies outside the domain (unclamped curve).
    #[error(transparent)]
    Domain(#[from] EvalError),
}

impl KnotRemovalError {
    /// A short machine-readable kind, used in JSON error records.
    pub fn kind(&self) -> &'static str {
        match self {
            KnotRemovalError::NonFiniteKnot { .. } => "non_finite_knot",
            KnotRemovalError::KnotNotPresent { .. } => "knot_not_present",
            KnotRemovalError::NotInterior { .. } => "knot_not_interior",
            KnotRemovalError::InvalidTolerance { .. } => "invalid_tolerance",
            KnotRemovalError::LegIndex { .. } => "leg_index",
            KnotRemovalError::InvalidPoint { .. } => "invalid_point",
            KnotRemovalError::DegenerateLeg { .. } => "degenerate_leg",
            KnotRemovalError::Domain(e) => e.kind(),
        }
    }
}

/// Check that u is an interior knot of (knots, p, n + 1 points); returns (r, s): the last index
/// of u and its multiplicity.
fn interior_knot(
    knots: &[f64],
    p: usize,
    npts: usize,
    u: f64,
) -> Result<(usize, usize), KnotRemovalError> {
    if !u.is_finite() {
        return Err(KnotRemovalError::NonFiniteKnot { value: u });
    }
    let s = multiplicity(knots, u);
    if s == 0 {
        return Err(KnotRemovalError::KnotNotPresent { value: u });
    }
    let (start, end) = (knots[p], knots[npts]);
    if !(start < u && u < end) {
        return Err(KnotRemovalError::NotInterior {
            value: u,
            start,
            end,
        });
    }
    Ok((knots.partition_point(|&x| x <= u) - 1, s))
}

impl<S: Scalar> HSpline<S> {
    /// Remove the interior knot u once (The NURBS Book sec. 5.4, eqs. (5.28)/(5.29), one pass
    /// of the loop of A5.8 `RemoveCurveKnot`; thesis sec. 4.2.2). Returns the spline on the
    /// knot vector without one copy of u, and the mismatch (one value per homogeneous row)
    /// that is zero exactly when u was removable, i.e. when the result is the same curve.
    ///
    /// With r the last index of u, s its multiplicity and alpha_i = (u - u_i) / (u_{i+p+1} -
    /// u_i), the p - s + 1 points P_{r-p} .. P_{r-s} are replaced by p - s new points Q with
    /// P_i = alpha_i Q_i + (1 - alpha_i) Q_{i-1} (knot insertion, eq. 4.12, read backwards).
    /// As in A5.8 the equations are solved from both ends toward the middle (the thesis's two
    /// recursions for Q_i):
    ///
    /// ```text
    /// left:  Q_i     = Q_{i-1} + (P_i - Q_{i-1}) / alpha_i          (i = r-p, r-p+1, ...)
    /// right: Q_{j-1} = Q_j + (P_j - Q_j) / (1 - alpha_j)            (j = r-s, r-s-1, ...)
    /// ```
    ///
    /// (the inverse of the corner-cutting step lo + a (hi - lo) of insertion, with one
    /// rounding fewer than (P_i - (1 - alpha_i) Q_{i-1}) / alpha_i; 1 - alpha_j is formed as
    /// the knot-difference quotient (u_{j+p+1} - u) / (u_{j+p+1} - u_j)). The left values are
    /// kept up to Q_{fout-1}, the right ones from Q_fout on, fout = floor((2r - s - p) / 2), as
    /// A5.8 keeps them. Mismatch: where the two recursions meet, either the two values of the
    /// middle point differ (p - s odd) or the unused middle equation is violated (p - s even;
    /// A5.8's two cases of `Distance4D`). A knot of multiplicity p + 1 (a jump) is removable
    /// when the two points at the jump coincide; the left one is kept.
    ///
    /// All alphas lie strictly in (0, 1) (u_i < u < u_{i+p+1} on the affected range), so no
    /// denominator is zero. For intervals the result encloses, for every real curve enclosed
    /// by the input, the exact result of the same formulas (inclusion isotonicity); in
    /// particular the exact control points before an insertion when the input encloses the
    /// inserted ones.
    pub fn remove_knot_once(&self, u: f64) -> Result<(HSpline<S>, Vec<S>), KnotRemovalError> {
        let p = self.degree;
        let h = self.hdim();
        let n1 = self.npts();
        let (r, s) = interior_knot(&self.knots, p, n1, u)?;
        // interior: the first copy of u has index >= p + 1, the last <= n, so first >= 1 and
        // last + 1 <= n below.
        let first = r - p;
        let last = r + 1 - s; // one past r - s, kept non-negative for s = p + 1
        let pt = |i: usize| &self.pts[i * h..(i + 1) * h];
        let us = S::from_f64(u);
        let alpha = |i: usize| -> (S, S) {
            let (ui, uj) = (
                S::from_f64(self.knots[i]),
                S::from_f64(self.knots[i + p + 1]),
            );
            let den = uj.clone() - ui.clone();
            ((us.clone() - ui) / den.clone(), (uj - us.clone()) / den)
        };
        // L = (r - s) - first = p - s, in -1 ..= p - 1; `it` steps from each side.
        let l = p as isize - s as isize;
        let it = ((l + 1) / 2) as usize;
        // lv[k] = Q_{first-1+k} (left), rv[k] = Q_{last-1-k} (right; rv[0] = P_{r-s+1}).
        let mut lv: Vec<Vec<S>> = vec![pt(first - 1).to_vec()];
        let mut rv: Vec<Vec<S>> = vec![pt(last).to_vec()];
        for k in 1..=it {
            let i = first - 1 + k;
            let (a, _) = alpha(i);
            let prev = &lv[k - 1];
            let q = (0..h)
                .map(|c| prev[c].clone() + (pt(i)[c].clone() - prev[c].clone()) / a.clone())
                .collect();
            lv.push(q);
            let j = last - k; // the equation of P_j, j = r - s + 1 - k
            let (_, b) = alpha(j);
            let next = &rv[k - 1];
            let q = (0..h)
                .map(|c| next[c].clone() + (pt(j)[c].clone() - next[c].clone()) / b.clone())
                .collect();
            rv.push(q);
        }
        let mismatch: Vec<S> = if l % 2 != 0 {
            // p - s odd (or -1): both sides computed the middle point Q_{fout}
            (0..h)
                .map(|c| lv[it][c].clone() - rv[it][c].clone())
                .collect()
        } else {
            // p - s even: the middle equation P_fout = alpha Q_fout + (1 - alpha) Q_{fout-1}
            let fout = first + it;
            let (a, _) = alpha(fout);
            (0..h)
                .map(|c| pt(fout)[c].clone() - S::lerp(&a, &lv[it][c], &rv[it][c]))
                .collect()
        };
        // fout - first = floor(L / 2) left points, last - 1 - fout + 1 = ceil(L / 2) right ones.
        let nleft = if l < 0 { 0 } else { (l / 2) as usize };
        let nright = if l < 0 { 0 } else { l as usize - nleft };
        let mut pts = Vec::with_capacity((n1 - 1) * h);
        pts.extend_from_slice(&self.pts[..first * h]);
        for q in &lv[1..=nleft] {
            pts.extend_from_slice(q);
        }
        for q in rv[1..=nright].iter().rev() {
            pts.extend_from_slice(q);
        }
        // the unchanged tail P_{r-s+1} .. P_n; for s = p + 1 (l = -1) P_first is dropped
        // (it coincides with P_{first-1} when the knot is removable)
        let tail = if l < 0 { last + 1 } else { last };
        pts.extend_from_slice(&self.pts[tail * h..]);
        let mut knots = self.knots.clone();
        knots.remove(r);
        Ok((
            HSpline {
                knots,
                pts,
                ..self.clone_shape()
            },
            mismatch,
        ))
    }

    /// The NURBS Book A5.8 `RemoveCurveKnot`: remove the interior knot u up to `num` times,
    /// as long as each removal's mismatch (see [`HSpline::remove_knot_once`]) has magnitude
    /// <= `tol` in every homogeneous row (A5.8's test, in the max norm; for a verified test
    /// of the Cartesian curve use [`NurbsCurve::remove_knot`]). Returns the spline and how
    /// often u was removed.
    pub fn remove_knot(
        &self,
        u: f64,
        num: usize,
        tol: f64,
    ) -> Result<(HSpline<S>, usize), KnotRemovalError> {
        let mut cur = self.clone();
        interior_knot(&cur.knots, cur.degree, cur.npts(), u)?;
        for t in 0..num {
            if multiplicity(&cur.knots, u) == 0 {
                return Ok((cur, t));
            }
            let (next, mis) = cur.remove_knot_once(u)?;
            if mis.iter().any(|x| {
                let m = x.to_interval().mag();
                m.is_nan() || m > tol
            }) {
                return Ok((cur, t));
            }
            cur = next;
        }
        Ok((cur, num))
    }

    fn clone_shape(&self) -> HSpline<S> {
        HSpline {
            degree: self.degree,
            knots: Vec::new(),
            dim: self.dim,
            rational: self.rational,
            pts: Vec::new(),
        }
    }
}

/// The result of [`NurbsCurve::remove_knot`].
#[derive(Debug, Clone, PartialEq)]
pub struct KnotRemoval {
    /// the curve after removal (the input curve when nothing was removed)
    pub curve: NurbsCurve,
    /// the knot
    pub knot: f64,
    /// its multiplicity before removal
    pub multiplicity: usize,
    /// how often removal was asked for (capped at the multiplicity)
    pub requested: usize,
    /// how often it was removed
    pub removed: usize,
    /// per coordinate j: a verified bound on max_u |C_j(u) - C'_j(u)| between the input curve
    /// C and the result C' over the domain (both exact as their f64 data define them); all
    /// zeros when nothing was removed
    pub error_bound: Vec<f64>,
}

impl NurbsCurve {
    /// Remove the interior knot u as often as possible, at most `times` times, such that the
    /// curve moves by at most `tol` in every coordinate: for the result C',
    /// |C_j(u) - C'_j(u)| <= tol for all u in the domain and all j, verified (see
    /// [`removal_error_bound`]). `tol = 0` removes only what leaves the exact curve unchanged;
    /// a removal that merely undoes an insertion gives back the control points before the
    /// insertion, bit for bit where the f64 arithmetic of the removal is exact (e.g. dyadic
    /// knots and data), within rounding otherwise.
    ///
    /// Each step is one [`HSpline::remove_knot_once`] in f64 (The NURBS Book A5.8), accepted
    /// when the resulting curve is valid and its verified distance to the *input* curve (not
    /// to the previous step, so errors cannot accumulate unseen) is within `tol`; the first
    /// step that fails stops the removal, as in A5.8.
    pub fn remove_knot(
        &self,
        u: f64,
        times: usize,
        tol: f64,
    ) -> Result<KnotRemoval, KnotRemovalError> {
        if !(tol.is_finite() && tol >= 0.0) {
            return Err(KnotRemovalError::InvalidTolerance { value: tol });
        }
        let (_, s) = interior_knot(self.knots(), self.degree(), self.num_points(), u)?;
        let requested = times.min(s);
        let mut out = KnotRemoval {
            curve: self.clone(),
            knot: u,
            multiplicity: s,
            requested,
            removed: 0,
            error_bound: vec![0.0; self.dim()],
        };
        let mut cur = HSpline::<f64>::from_curve(self);
        for _ in 0..requested {
            let (next, _) = cur.remove_knot_once(u)?;
            let Some(c) = crate::spline::refine::to_curve(&next) else {
                break;
            };
            let Some(bound) = removal_error_bound(self, &c) else {
                break;
            };
            if bound.iter().any(|&b| b.is_nan() || b > tol) {
                break;
            }
            cur = next;
            out.curve = c;
            out.removed += 1;
            out.error_bound = bound;
        }
        Ok(out)
    }

    /// Inverse knot insertion (thesis sec. 4.2.1): the knot û whose single insertion creates
    /// the point `q` on the leg P_{i-1} P_i of the control polygon (1 <= i <= n). With
    /// s = w_{i-1} |q - P_{i-1}| / (w_{i-1} |q - P_{i-1}| + w_i |P_i - q|) the new homogeneous
    /// point is (1 - s) P^w_{i-1} + s P^w_i, whose Cartesian point is q when q lies on the
    /// leg, and û = u_i + s (u_{i+p} - u_i) (so that alpha_i of eq. 4.14 is s). For a q off the
    /// leg the distances still give an s in [0, 1]: the created point is then the point of the
    /// leg that divides it in the same ratio. The knot is computed in f64 (rounded);
    /// inserting it creates q up to that rounding.
    pub fn inverse_insertion_knot(&self, i: usize, q: &[f64]) -> Result<f64, KnotRemovalError> {
        let n = self.num_points() - 1;
        if !(1..=n).contains(&i) {
            return Err(KnotRemovalError::LegIndex { index: i, max: n });
        }
        if q.len() != self.dim() || q.iter().any(|x| !x.is_finite()) {
            return Err(KnotRemovalError::InvalidPoint {
                expected: self.dim(),
                got: q.to_vec(),
            });
        }
        let dist =
            |a: &[f64], b: &[f64]| a.iter().zip(b).fold(0.0f64, |acc, (x, y)| acc.hypot(x - y));
        let (p0, p1) = (self.control_point(i - 1), self.control_point(i));
        if p0 == p1 {
            return Err(KnotRemovalError::DegenerateLeg { index: i });
        }
        let a = self.weight(i - 1) * dist(q, p0);
        let b = self.weight(i) * dist(p1, q);
        let s = if a + b == 0.0 { 0.0 } else { a / (a + b) };
        let k = self.knots();
        let p = self.degree();
        let uhat = k[i] + s * (k[i + p] - k[i]);
        // rounding may leave the segment [u_i, u_{i+p}] by an ulp: clamp
        let uhat = uhat.clamp(k[i], k[i + p]);
        crate::spline::eval::check_domain(self.domain(), uhat)?;
        Ok(uhat)
    }
}

/// A verified bound, per coordinate j, on max_u |C_j(u) - R_j(u)| over the domain, for a curve
/// `reduced` R whose knot vector is that of `original` C with some copies of one or more knots
/// left out (the result of knot removal). `None` when the knot vectors are not nested that way
/// or the domains differ.
///
/// Method: the left-out knots are inserted back into R in interval arithmetic (the generic
/// A5.1 kernel [`HSpline::insert_knot`], outward rounded), which gives enclosures Q^w_i of the
/// exact control points of R on C's knot vector. Then, with e_A[j] = max_i |P^w_ij - Q^w_ij|,
/// e_w = max_i |w_i - w^R_i| (0 for polynomial curves), M_j = max_i |R-control point_ij| and
/// w_min = min_i w_i of C:
///
/// ```text
/// C_j - R_j = ((A_j - A^R_j) - R_j (w - w^R)) / w,   so   |C_j - R_j| <= (e_A[j] + M_j e_w) / w_min
/// ```
///
/// because the B-splines on C's knots are non-negative and sum to one on the domain (so
/// |A_j - A^R_j| <= e_A[j], |w - w^R| <= e_w, w >= w_min), and R lies in the convex hull of
/// its control points (positive weights), so |R_j| <= M_j. For a polynomial curve this is the
/// classical bound max_i |P_ij - Q_ij| (The NURBS Book sec. 5.4, the reasoning behind
/// eq. (5.30)). Every quantity is an interval; the bound is its upper end.
pub fn removal_error_bound(original: &NurbsCurve, reduced: &NurbsCurve) -> Option<Vec<f64>> {
    if original.degree() != reduced.degree()
        || original.dim() != reduced.dim()
        || original.domain() != reduced.domain()
    {
        return None;
    }
    let p = original.degree();
    let mut r = HSpline::<Interval>::from_curve(reduced);
    if original.is_rational() && !r.rational {
        r = with_weight_row(r);
    }
    // Insert back every knot whose multiplicity differs, in value order.
    let ok = original.knots();
    let mut u_prev = f64::NAN;
    for &u in ok {
        if u == u_prev {
            continue;
        }
        u_prev = u;
        let (mo, mr) = (multiplicity(ok, u), multiplicity(&r.knots, u));
        if mr > mo {
            return None;
        }
        if mr < mo {
            r = reinsert(&r, u, mo - mr, p)?;
        }
    }
    if r.knots != ok {
        return None;
    }
    let o = HSpline::<Interval>::from_curve(original);
    let h = o.hdim();
    let d = o.dim;
    // mag of an outward-rounded difference: an upper bound on |P^w_ic - Q^w_ic|
    let mut e = vec![0.0f64; h];
    for (a, b) in o.pts.chunks(h).zip(r.pts.chunks(h)) {
        for c in 0..h {
            e[c] = e[c].max((a[c] - b[c]).mag());
        }
    }
    if !o.rational {
        return Some(e);
    }
    let wmin = (0..original.num_points())
        .map(|i| original.weight(i))
        .fold(f64::INFINITY, f64::min);
    let ew = e[d];
    Some(
        (0..d)
            .map(|j| {
                let m = (0..reduced.num_points())
                    .map(|i| reduced.control_point(i)[j].abs())
                    .fold(0.0f64, f64::max);
                ((iv::point(e[j]) + iv::point(m) * iv::point(ew)) / iv::point(wmin)).sup()
            })
            .collect(),
    )
}

/// A non-rational spline with an explicit weight row of ones (the reduced curve of a rational
/// curve may have lost its weights when they all became 1).
fn with_weight_row(r: HSpline<Interval>) -> HSpline<Interval> {
    let d = r.dim;
    let mut pts = Vec::with_capacity(r.pts.len() / d * (d + 1));
    for c in r.pts.chunks(d) {
        pts.extend_from_slice(c);
        pts.push(iv::point(1.0));
    }
    HSpline {
        rational: true,
        pts,
        ..r
    }
}

/// Insert u `k` times (A5.1); up to multiplicity p + 1, where the last copy duplicates the
/// point at u (a C^0 joint split into a jump that is not one: the same curve).
fn reinsert(r: &HSpline<Interval>, u: f64, k: usize, p: usize) -> Option<HSpline<Interval>> {
    let m = multiplicity(&r.knots, u);
    if m + k > p + 1 {
        return None;
    }
    let to_p = k.min(p.saturating_sub(m));
    let mut out = r.insert_knot(u, to_p);
    if multiplicity(&out.knots, u) < m + to_p {
        return None; // u outside the domain: insert_knot ignored it
    }
    if m + k == p + 1 {
        let h = out.hdim();
        let last = out.knots.partition_point(|&x| x <= u) - 1; // last index of u
        let j = last - p; // the point at u (multiplicity p)
        let dup = out.pts[j * h..(j + 1) * h].to_vec();
        out.pts.splice(j * h..j * h, dup);
        out.knots.insert(last + 1, u);
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cubic() -> NurbsCurve {
        NurbsCurve::new(
            3,
            vec![0., 0., 0., 0., 1., 2., 3., 3., 3., 3.],
            vec![
                vec![0., 0.],
                vec![1., 4.],
                vec![2., -2.],
                vec![5., 3.],
                vec![6., 1.],
                vec![8., 0.],
            ],
            None,
        )
        .unwrap()
    }

    #[test]
    fn exact_insertion_is_undone_bit_for_bit() {
        let c = cubic();
        let mut exact_cases = 0;
        for (u, r) in [(1.5, 1), (1.5, 2), (1.5, 3), (2.0, 1), (2.0, 2), (0.5, 3)] {
            let ins = c.insert_knot(u, r).unwrap();
            // was the f64 insertion exact? (the interval insertion gives singletons)
            let hi = HSpline::<Interval>::from_curve(&c).insert_knot(u, r);
            let exact = hi.pts.iter().all(|x| x.inf() == x.sup());
            let rem = ins.remove_knot(u, r, 0.0).unwrap();
            if exact {
                exact_cases += 1;
                assert_eq!(rem.removed, r, "u={u} r={r}");
                assert_eq!(rem.curve, c, "u={u} r={r}");
                assert_eq!(rem.error_bound, vec![0.0, 0.0]);
            }
            // rounded insertion: removable within a few ulps, and close to the original
            let rem = ins.remove_knot(u, r, 1e-13).unwrap();
            assert_eq!(rem.removed, r, "u={u} r={r}");
            assert_eq!(rem.curve.knots(), c.knots());
            for (a, b) in rem.curve.points_flat().iter().zip(c.points_flat()) {
                assert!((a - b).abs() <= 1e-13, "u={u} r={r}: {a} vs {b}");
            }
            assert!(rem.error_bound.iter().all(|&b| b <= 1e-13));
        }
        // u = 1.5: all alphas are dyadic (3/4, 1/2, 1/4, ...), the round trip is exact
        assert!(exact_cases >= 3, "{exact_cases}");
    }

    #[test]
    fn a_needed_knot_stays() {
        let c = cubic();
        let rem = c.remove_knot(1.0, 1, 0.0).unwrap();
        assert_eq!((rem.removed, rem.requested, rem.multiplicity), (0, 1, 1));
        assert_eq!(rem.curve, c);
        // a generous tolerance removes it, and the bound says by how much the curve moved
        let rem = c.remove_knot(1.0, 1, 10.0).unwrap();
        assert_eq!(rem.removed, 1);
        assert!(rem.error_bound.iter().all(|&b| b > 0.0 && b <= 10.0));
    }

    #[test]
    fn errors_are_typed() {
        let c = cubic();
        let k = |u: f64| c.remove_knot(u, 1, 0.0).unwrap_err().kind();
        assert_eq!(k(1.25), "knot_not_present");
        assert_eq!(k(0.0), "knot_not_interior");
        assert_eq!(k(3.0), "knot_not_interior");
        assert_eq!(k(f64::NAN), "non_finite_knot");
        assert_eq!(
            c.remove_knot(1.0, 1, -1.0).unwrap_err().kind(),
            "invalid_tolerance"
        );
        assert_eq!(
            c.inverse_insertion_knot(0, &[0., 0.]).unwrap_err().kind(),
            "leg_index"
        );
        assert_eq!(
            c.inverse_insertion_knot(1, &[0.]).unwrap_err().kind(),
            "invalid_point"
        );
    }

    #[test]
    fn inverse_insertion_creates_the_point() {
        // thesis sec. 4.2 example: U = {0,0,0,0,0.5,1,1,1,1}; inserting 0.1 gives the new
        // point Q_2 = (2.7, 4) on the leg P_1 P_2 (alpha_2 = 0.1, eq. 4.14); the inverse
        // insertion finds 0.1 back from that point.
        let c = NurbsCurve::new(
            3,
            vec![0., 0., 0., 0., 0.5, 1., 1., 1., 1.],
            vec![
                vec![1., 1.],
                vec![2.5, 4.],
                vec![4.5, 4.],
                vec![5.5, 1.],
                vec![7.5, 1.],
            ],
            None,
        )
        .unwrap();
        let u = c.inverse_insertion_knot(2, &[2.7, 4.]).unwrap();
        assert!((u - 0.1).abs() < 1e-15, "{u}");
        let ins = c.insert_knot(u, 1).unwrap();
        let q = ins.control_point(2);
        assert!(
            (q[0] - 2.7).abs() < 1e-14 && (q[1] - 4.).abs() < 1e-14,
            "{q:?}"
        );
        // rational: the created Cartesian point is q, though s is not the length ratio
        let w = NurbsCurve::new(
            2,
            vec![0., 0., 0., 1., 2., 2., 2.],
            vec![vec![0., 0.], vec![4., 0.], vec![4., 4.], vec![0., 4.]],
            Some(vec![1., 3., 1., 2.]),
        )
        .unwrap();
        let u = w.inverse_insertion_knot(2, &[4., 1.]).unwrap();
        let ins = w.insert_knot(u, 1).unwrap();
        assert!((0..ins.num_points()).any(|i| {
            let p = ins.control_point(i);
            (p[0] - 4.).abs() < 1e-14 && (p[1] - 1.).abs() < 1e-14
        }));
        assert_eq!(
            w.inverse_insertion_knot(1, &[1., 1., 1.])
                .unwrap_err()
                .kind(),
            "invalid_point"
        );
    }
}
