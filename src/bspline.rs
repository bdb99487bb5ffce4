//! B-spline curves in homogeneous coordinates, generic over the number type: the one copy of
//! de Boor corner cutting, basis functions, derivative control points, knot insertion and
//! Bézier extraction that the whole crate uses, for f64, intervals and MPFR alike.

use crate::curve::NurbsCurve;
use crate::knots::find_span;
use crate::scalar::Scalar;

/// A (non-rational) B-spline curve whose control points have `hdim` coordinates of type `S`.
///
/// A NURBS curve is represented by its homogeneous form Pw_i = (w_i P_i, w_i) (thesis eq. 3.7,
/// helper `H`): then `hdim = dim + 1` and the last row is the weight function w(u). For a
/// non-rational curve the weight row is left out (`rational == false`, w = 1).
/// Knots are f64 and exact: all knot differences are formed in `S`.
#[derive(Debug, Clone)]
pub struct HSpline<S> {
    /// degree (may reach 0 for high derivatives)
    pub degree: usize,
    /// knot vector, `npts + degree + 1` values
    pub knots: Vec<f64>,
    /// number of Cartesian coordinates d
    pub dim: usize,
    /// whether the last row is the weight row (hdim = dim + 1)
    pub rational: bool,
    /// control points, row-major, `hdim` values each
    pub pts: Vec<S>,
}

impl<S: Scalar> HSpline<S> {
    /// Homogeneous form of a NURBS curve (thesis helper `H`, eq. 3.7). For intervals the products
    /// w_i * P_ij are outward rounded, so the spline encloses the exact homogeneous curve.
    pub fn from_curve(c: &NurbsCurve) -> Self {
        let dim = c.dim();
        let rational = c.is_rational();
        let hdim = dim + rational as usize;
        let mut pts = Vec::with_capacity(c.num_points() * hdim);
        for i in 0..c.num_points() {
            let w = c.weight(i);
            for &x in c.control_point(i) {
                if rational {
                    pts.push(S::from_f64(w) * S::from_f64(x));
                } else {
                    pts.push(S::from_f64(x));
                }
            }
            if rational {
                pts.push(S::from_f64(w));
            }
        }
        HSpline {
            degree: c.degree(),
            knots: c.knots().to_vec(),
            dim,
            rational,
            pts,
        }
    }

    /// Coordinates per control point.
    #[inline]
    pub fn hdim(&self) -> usize {
        self.dim + self.rational as usize
    }

    /// Number of control points.
    #[inline]
    pub fn npts(&self) -> usize {
        self.pts.len() / self.hdim()
    }

    /// Exact span index of an f64 parameter.
    #[inline]
    pub fn span(&self, u: f64) -> usize {
        find_span(&self.knots, self.degree, self.npts() - 1, u)
    }

    /// de Boor corner cutting on span `k` (see [`corner_cut`]), all homogeneous rows, written
    /// into `out` (`hdim` values). For an interval `u` inside [u_k, u_{k+1}] the result encloses
    /// the curve over all of `u`.
    pub fn eval_span(&self, k: usize, u: &S, out: &mut Vec<S>) {
        let p = self.degree;
        let h = self.hdim();
        out.clear();
        out.extend_from_slice(&self.pts[(k - p) * h..(k + 1) * h]);
        corner_cut(&self.knots, p, k, u, h, out);
        out.drain(..p * h);
    }

    /// Like [`HSpline::eval_span`] but only for the homogeneous rows listed in `rows` (e.g. one
    /// coordinate and the weight row), without allocating once `buf` has grown: the values are
    /// returned as the slice `buf[p * rows.len()..]`, in the order of `rows`.
    pub fn eval_span_rows<'b>(
        &self,
        k: usize,
        u: &S,
        rows: &[usize],
        buf: &'b mut Vec<S>,
    ) -> &'b [S] {
        let p = self.degree;
        let h = self.hdim();
        let nr = rows.len();
        buf.clear();
        for i in k - p..=k {
            buf.extend(rows.iter().map(|&r| self.pts[i * h + r].clone()));
        }
        corner_cut(&self.knots, p, k, u, nr, buf);
        &buf[p * nr..]
    }

    /// Evaluate at an f64 parameter (span found exactly).
    pub fn eval(&self, u: f64) -> Vec<S> {
        let mut out = Vec::new();
        self.eval_span(self.span(u), &S::from_f64(u), &mut out);
        out
    }

    /// Derivative as a B-spline of degree p - 1 on knots u_1 .. u_{m-1} (thesis eq. 2.7):
    /// Q_i = p (P_{i+1} - P_i) / (u_{i+p+1} - u_{i+1}). A zero denominator means N_{i,p-1} == 0,
    /// and Q_i is set to 0 (the 0/0 := 0 convention of def. 1.2).
    /// The span index of u in the derivative is one less than in `self`.
    pub fn derivative(&self) -> HSpline<S> {
        let p = self.degree;
        let h = self.hdim();
        let n = self.npts();
        if p == 0 || n < 2 {
            // derivative of a piecewise constant: zero (no knots inside a span)
            return HSpline {
                degree: 0,
                knots: self.knots.clone(),
                dim: self.dim,
                rational: self.rational,
                pts: vec![S::zero(); self.pts.len()],
            };
        }
        let mut pts = Vec::with_capacity((n - 1) * h);
        let pp = S::from_usize(p);
        for i in 0..n - 1 {
            let d = self.knots[i + p + 1] - self.knots[i + 1];
            if d == 0.0 {
                pts.extend(std::iter::repeat_with(S::zero).take(h));
                continue;
            }
            let f =
                pp.clone() / (S::from_f64(self.knots[i + p + 1]) - S::from_f64(self.knots[i + 1]));
            for c in 0..h {
                pts.push(
                    f.clone() * (self.pts[(i + 1) * h + c].clone() - self.pts[i * h + c].clone()),
                );
            }
        }
        HSpline {
            degree: p - 1,
            knots: self.knots[1..self.knots.len() - 1].to_vec(),
            dim: self.dim,
            rational: self.rational,
            pts,
        }
    }

    /// The Bézier segment of span k (u_k < u_{k+1}) in homogeneous form, by clamping the local
    /// curve (p + 1 points, 2p + 2 knots, one span) at both ends with Boehm knot insertion
    /// (NURBS Book A5.1 CurveKnotIns applied locally; equivalent to A5.6 DecomposeCurve for one
    /// segment). Works for clamped and unclamped knot vectors alike. O(p^2).
    pub fn bezier_segment(&self, k: usize) -> BezierSeg<S> {
        let p = self.degree;
        let h = self.hdim();
        let mut q: Vec<S> = self.pts[(k - p) * h..(k + 1) * h].to_vec();
        let mut t: Vec<f64> = self.knots[k - p..=k + p + 1].to_vec();
        clamp_left(p, h, &mut t, &mut q);
        // Mirror: reversed points, knots t'_j = -t_{2p+1-j}; clamp, mirror back. Negation is exact.
        reverse_points(h, &mut q);
        let mut tr: Vec<f64> = t.iter().rev().map(|x| -x).collect();
        clamp_left(p, h, &mut tr, &mut q);
        reverse_points(h, &mut q);
        BezierSeg {
            a: self.knots[k],
            b: self.knots[k + 1],
            degree: p,
            dim: self.dim,
            rational: self.rational,
            pts: q,
        }
    }

    /// Insert the knot u `r` times (NURBS Book A5.1 CurveKnotIns; thesis eqs. 4.12, 4.15/4.16).
    /// Requires u in the domain and r + (current multiplicity) <= p; extra insertions are
    /// ignored. The new points are convex combinations alpha*(Q_i - Q_{i-1}) + Q_{i-1}.
    pub fn insert_knot(&self, u: f64, r: usize) -> HSpline<S> {
        let p = self.degree;
        let h = self.hdim();
        let k = self.span(u);
        let s = crate::knots::multiplicity(&self.knots, u);
        let r = r.min(p.saturating_sub(s));
        if r == 0 {
            return self.clone();
        }
        let (knots, pts) = knot_ins(p, h, &self.knots, &self.pts, k, s, u, r);
        HSpline {
            degree: p,
            knots,
            dim: self.dim,
            rational: self.rational,
            pts,
        }
    }

    /// Bézier decomposition (NURBS Book A5.6 DecomposeCurve): one segment per non-empty span of
    /// the domain, in order.
    pub fn decompose(&self) -> Vec<BezierSeg<S>> {
        let p = self.degree;
        let n = self.npts() - 1;
        (p..=n)
            .filter(|&k| self.knots[k] < self.knots[k + 1])
            .map(|k| self.bezier_segment(k))
            .collect()
    }
}

/// A Bézier segment over [a, b] in homogeneous coordinates (local parameter t in [0, 1]).
#[derive(Debug, Clone)]
pub struct BezierSeg<S> {
    /// parameter interval start in the original curve
    pub a: f64,
    /// parameter interval end
    pub b: f64,
    /// degree
    pub degree: usize,
    /// Cartesian dimension
    pub dim: usize,
    /// whether the last row is the weight row
    pub rational: bool,
    /// p + 1 homogeneous control points, row-major
    pub pts: Vec<S>,
}

impl<S: Scalar> BezierSeg<S> {
    /// Coordinates per control point.
    #[inline]
    pub fn hdim(&self) -> usize {
        self.dim + self.rational as usize
    }

    /// de Casteljau evaluation at local t (seed 004; all rows): the first point of the right
    /// half of the split at t.
    pub fn eval_local(&self, t: &S) -> Vec<S> {
        let h = self.hdim();
        let (_, mut right) = self.split_points(t);
        right.truncate(h);
        right
    }

    /// de Casteljau subdivision (seed 004) at local t: the control points of the halves over
    /// [0, t] and [t, 1]. Convex combinations in the a*(R1-R2)+R2 form. For intervals (also an
    /// interval t) both halves enclose the exact halves for every real t in `t` (each new point
    /// is a polynomial in t and the old points; inclusion isotonicity).
    pub fn split_points(&self, t: &S) -> (Vec<S>, Vec<S>) {
        let h = self.hdim();
        let p = self.degree;
        let mut b = self.pts.clone();
        let mut left = Vec::with_capacity(b.len());
        let mut right = vec![S::zero(); b.len()];
        left.extend_from_slice(&b[0..h]);
        right[p * h..(p + 1) * h].clone_from_slice(&b[p * h..(p + 1) * h]);
        for r in 1..=p {
            for i in 0..=p - r {
                for c in 0..h {
                    let lo = b[i * h + c].clone();
                    let hi = b[(i + 1) * h + c].clone();
                    b[i * h + c] = t.clone() * (hi - lo.clone()) + lo;
                }
            }
            left.extend_from_slice(&b[0..h]);
            right[(p - r) * h..(p - r + 1) * h].clone_from_slice(&b[(p - r) * h..(p - r + 1) * h]);
        }
        (left, right)
    }

    /// de Casteljau split at local t into the segments over [0, t] and [t, 1] (the parameter
    /// bounds a, b of the halves are f64 approximations of the split point).
    pub fn split(&self, t: f64) -> (BezierSeg<S>, BezierSeg<S>) {
        let (left, right) = self.split_points(&S::from_f64(t));
        let m = self.a + t * (self.b - self.a);
        (
            BezierSeg {
                b: m,
                pts: left,
                ..self.clone_meta()
            },
            BezierSeg {
                a: m,
                pts: right,
                ..self.clone_meta()
            },
        )
    }

    /// The one-coordinate segment of Cartesian coordinate j: rows (w P_j, w), or (P_j).
    pub fn coord(&self, j: usize) -> BezierSeg<S> {
        let h = self.hdim();
        let mut pts = Vec::with_capacity((self.degree + 1) * (1 + self.rational as usize));
        for c in self.pts.chunks(h) {
            pts.push(c[j].clone());
            if self.rational {
                pts.push(c[self.dim].clone());
            }
        }
        BezierSeg {
            dim: 1,
            pts,
            ..self.clone_meta()
        }
    }

    fn clone_meta(&self) -> BezierSeg<S> {
        BezierSeg {
            a: self.a,
            b: self.b,
            degree: self.degree,
            dim: self.dim,
            rational: self.rational,
            pts: Vec::new(),
        }
    }
}

fn reverse_points<S: Clone>(h: usize, q: &mut [S]) {
    let n = q.len() / h;
    for i in 0..n / 2 {
        for c in 0..h {
            q.swap(i * h + c, (n - 1 - i) * h + c);
        }
    }
}

/// Clamp a one-span local curve (p + 1 points, knots t_0..t_{2p+1}, span index p) at its left
/// end t_p by inserting t_p until its multiplicity is p, then dropping the leading points and
/// knots that no longer influence the span.
fn clamp_left<S: Scalar>(p: usize, h: usize, t: &mut Vec<f64>, q: &mut Vec<S>) {
    let u = t[p];
    let s = t[..=p].iter().rev().take_while(|&&x| x == u).count();
    if s >= p {
        return;
    }
    let r = p - s;
    let (nt, nq) = knot_ins(p, h, t, q, p, s, u, r);
    *t = nt[r..].to_vec();
    *q = nq[r * h..].to_vec();
}

/// NURBS Book A5.1 CurveKnotIns: insert u (in span k, multiplicity s) r times, r + s <= p.
/// Returns the new knots and points.
#[allow(clippy::too_many_arguments)]
fn knot_ins<S: Scalar>(
    p: usize,
    h: usize,
    up: &[f64],
    pw: &[S],
    k: usize,
    s: usize,
    u: f64,
    r: usize,
) -> (Vec<f64>, Vec<S>) {
    let np = pw.len() / h - 1;
    let nq = np + r;
    let mut uq = Vec::with_capacity(up.len() + r);
    uq.extend_from_slice(&up[..=k]);
    uq.extend(std::iter::repeat_n(u, r));
    uq.extend_from_slice(&up[k + 1..]);
    let mut qw: Vec<S> = vec![S::zero(); (nq + 1) * h];
    qw[..(k - p + 1) * h].clone_from_slice(&pw[..(k - p + 1) * h]);
    for i in k - s..=np {
        qw[(i + r) * h..(i + r + 1) * h].clone_from_slice(&pw[i * h..(i + 1) * h]);
    }
    let mut rw: Vec<S> = pw[(k - p) * h..(k - s + 1) * h].to_vec();
    let us = S::from_f64(u);
    let mut l = 0;
    for j in 1..=r {
        l = k - p + j;
        for i in 0..=p - j - s {
            let alpha = (us.clone() - S::from_f64(up[l + i]))
                / (S::from_f64(up[i + k + 1]) - S::from_f64(up[l + i]));
            for c in 0..h {
                let lo = rw[i * h + c].clone();
                let hi = rw[(i + 1) * h + c].clone();
                rw[i * h + c] = alpha.clone() * (hi - lo.clone()) + lo;
            }
        }
        qw[l * h..(l + 1) * h].clone_from_slice(&rw[0..h]);
        let e = k + r - j - s;
        qw[e * h..(e + 1) * h].clone_from_slice(&rw[(p - j - s) * h..(p - j - s + 1) * h]);
    }
    for i in l + 1..k - s {
        qw[i * h..(i + 1) * h].clone_from_slice(&rw[(i - l) * h..(i - l + 1) * h]);
    }
    (uq, qw)
}

/// de Boor corner cutting (thesis CurvePntByCornerCut, NURBS Book A5.1-style triangle) in place
/// on `buf`, which holds the p + 1 local control points P_{k-p} .. P_k of span k with `h` rows
/// each; afterwards the value at `u` is in `buf[p * h..(p + 1) * h]`.
///
/// Each step is the convex combination written as alpha*(R1 - R2) + R2 (thesis sec. 5.1),
/// which in interval arithmetic overestimates less than alpha*R1 + (1 - alpha)*R2.
/// The denominators u_{i+p+1-r} - u_i are >= u_{k+1} - u_k > 0, so never zero.
/// For an interval `u` inside [u_k, u_{k+1}] the result encloses the piece over all of `u`
/// (the polynomial piece is the same there; inclusion isotonicity of interval arithmetic).
pub fn corner_cut<S: Scalar>(knots: &[f64], p: usize, k: usize, u: &S, h: usize, buf: &mut [S]) {
    // alpha for level r, position j (i = k - p + j): (u - u_i) / (u_{i+p+1-r} - u_i)
    for r in 1..=p {
        for j in (r..=p).rev() {
            let i = k - p + j;
            let a = (u.clone() - S::from_f64(knots[i]))
                / (S::from_f64(knots[i + p + 1 - r]) - S::from_f64(knots[i]));
            for c in 0..h {
                buf[j * h + c] = S::lerp(&a, &buf[(j - 1) * h + c], &buf[j * h + c]);
            }
        }
    }
}

/// All non-zero basis functions N_{k-p,p}(u) .. N_{k,p}(u) on span k (NURBS Book A2.2
/// BasisFuns; thesis CurvePoint2). The denominator right[r+1] + left[j-r] is formed directly as
/// the knot difference u_{k+r+1} - u_{k+1-j+r} (no u in it), which avoids the interval
/// dependency problem; it is > 0 for a non-empty span.
pub fn basis_funs<S: Scalar>(knots: &[f64], k: usize, u: &S, p: usize) -> Vec<S> {
    let mut n = vec![S::zero(); p + 1];
    n[0] = S::one();
    let mut left = vec![S::zero(); p + 1];
    let mut right = vec![S::zero(); p + 1];
    for j in 1..=p {
        left[j] = u.clone() - S::from_f64(knots[k + 1 - j]);
        right[j] = S::from_f64(knots[k + j]) - u.clone();
        let mut saved = S::zero();
        for r in 0..j {
            let temp =
                n[r].clone() / (S::from_f64(knots[k + r + 1]) - S::from_f64(knots[k + 1 - j + r]));
            n[r] = saved + right[r + 1].clone() * temp.clone();
            saved = left[j - r].clone() * temp;
        }
        n[j] = saved;
    }
    n
}
