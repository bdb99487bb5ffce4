//! Float first, prove after: the fast path of the surface strategies `bezier` and `newton`
//! (not in the thesis; the surface counterpart of the curve side's `Newton::fast_path`).
//!
//! Per coordinate j and side (the maximum of sign * S_j; the minimum is the maximum of -S_j,
//! negation is exact) on every Bézier patch of the surface, in the patch's local parameters
//! t in [0, 1]^2:
//!
//! 1. **Candidates.** The patch corners (their Bernstein coefficients are the surface values
//!    there: exact at a clamped domain corner, else the intersection of the double-double
//!    and the interval extraction), the maxima of the four boundary curves (a polynomial
//!    cubic's in closed form, [`edge_candidate`]; else f64 Newton iterations, 1-D) and f64
//!    Newton iterations for an interior critical point (2-D), seeded at the largest
//!    coefficient. The candidates whose f64 value is within 1e-12 of the best are evaluated
//!    in double-double intervals ([`Ddi`], ~2^-100 relative; or exactly in interval
//!    arithmetic at a short dyadic point near them, when the value there is a float): the
//!    lower ends are attained values (the inner bound), the largest upper end is the bound
//!    `ub` to prove. Nothing about soundness depends on how the candidates were found.
//! 2. **Vertex test** (Zettler & Garloff 1998). If every patch's coefficient ratios
//!    a_rc / w_rc (enclosed) are <= the best corner value, the surface is (convex hull
//!    property: tensor Bernstein polynomials are >= 0 and sum to 1, weights > 0) and the side
//!    is done, exact when the corner value is. Counted in [`Stats::fast_exits`].
//! 3. **Proof** that F = A_j - ub w <= 0 on every patch (A_j, w the homogeneous numerator and
//!    the weight; w > 0, so F <= 0 iff S_j <= ub; for a polynomial patch F = S_j - ub), by a
//!    best-first quadtree (largest coefficient first) over f64 Bernstein coefficients with an
//!    a-priori error bound (the coefficients of a piece are within `ea` / `ew` of the exact
//!    ones; see [`Piece::split`]). A piece is done when
//!    * its coefficients are <= 0, rounding included: F <= 0 there (convex hull property);
//!    * F is monotone towards a side of the patch that the piece touches (the differences of
//!      its coefficients along that direction have one sign, so F_t has that sign on the
//!      piece): its maximum over the piece is on that side, where F <= 0 is proven by the
//!      curve side's root-isolating proof for a polynomial boundary curve of degree 2 or 3
//!      ([`Prover::edge_segment`]), else by the same procedure on the boundary curve (1-D
//!      pieces; their own sides are patch corners, candidates, so <= `ub`); monotone along
//!      both directions towards a corner of the patch, its maximum is that corner (<= `ub`),
//!      and no boundary curve is needed. (A child of a split whose coefficients prove it is
//!      settled at the split.)
//!    * it is **strictly concave**: the Bernstein coefficients of the Hessian of F prove
//!      -H(x) >= mu I (mu > 0) for every x in the piece (scaled Gershgorin bound). Then for
//!      any c in the piece Taylor's formula with the integral remainder gives
//!      F(x) <= F(c) + g (x - c) - mu |x - c|^2 / 2 (g = grad F(c)), whose maximum over the
//!      piece is separable per direction ([`Prover::concave`]). c is a box-constrained f64
//!      maximiser, F(c) and g are `Ddi` enclosures: near the maximum the correction is at the
//!      rounding level and the bound is F(c) + ~2^-100. A maximiser that provably beats `ub`
//!      raises it (every earlier proof stays valid: F only decreases as `ub` grows).
//!    * it lies on a **ridge**: F is strictly concave along one parameter direction d and
//!      constant (or nearly so) along the other, so no piece across the ridge is strictly
//!      concave in both. Then F(x) <= F(c_d, x_o) + F_d(c_d, x_o) (x_d - c_d) - mu |x_d - c_d|^2 / 2
//!      for a maximiser c_d along d, and the iso-line functions F(c_d, .), F_d(c_d, .) are
//!      bounded by their `Ddi` Bernstein coefficients over the piece ([`Prover::ridge`]); on
//!      an exact ridge this is the ridge value plus rounding, so a ridge ends in a tight
//!      proven bound without the general search.
//!
//!    Everything else is halved (both directions) up to [`MAX_DEPTH`] levels and [`BUDGET`]
//!    pieces per side. If the proof fails (a ridge not along a parameter line; a flat or
//!    tiny coordinate; a missed candidate), it is retried once with `ub` one ulp higher,
//!    then the side falls back to the strategy's general search ([`Stats::fast_fallbacks`]). A proven side counts in
//!    [`Stats::fast_proofs`]; its gap is the width of the best candidate's enclosure rounded
//!    outward: one ulp, or 0 when the value is a float.
//!
//! Restrictions (else no fast path): degrees <= [`MAX_DEGREE`] (fixed-size arrays on the
//! stack, no allocation per piece), and no interior knot of multiplicity degree + 1 (then the
//! surface is continuous and every patch's corner and boundary values are values the surface
//! takes, so they are attained).

use crate::enclose::Stats;
use crate::num::ddi::{up, Ddi, U1};
use crate::num::{iv, Mr, Scalar};
use crate::surface::model::NurbsSurface;
use inari::Interval;
use smallvec::SmallVec;

/// Highest degree (per direction) of the fast path.
pub(crate) const MAX_DEGREE: usize = 5;
const MAXN: usize = (MAX_DEGREE + 1) * (MAX_DEGREE + 1);
/// Unit roundoff u = 2^-53.
const UNIT: f64 = f64::EPSILON / 2.0;
/// Deepest halving of a piece.
const MAX_DEPTH: u32 = 12;
/// Pieces per side (all patches together).
const BUDGET: u32 = 600;

/// The surface prepared for the fast path: its Bézier patches' homogeneous coefficients in
/// `Ddi` (enclosures of the exact ones; the net itself for a single clamped patch).
#[derive(Debug, Clone)]
pub(crate) struct FastSurface {
    p: usize,
    q: usize,
    dim: usize,
    rational: bool,
    /// per patch `[(r * (q + 1) + c) * h + k]`, h = dim + rational
    patches: Vec<Vec<Ddi>>,
    /// (patch, coefficient index): the corner coefficients that are a clamped domain
    /// corner, where the surface is the control point exactly (the only non-zero basis
    /// products are N_r N_c = 1; the weights cancel). A `Ddi` quotient w P / w would come out
    /// an ulp wider on each side.
    exact: SmallVec<[(usize, usize); 4]>,
    /// the points of `exact`, `dim` coordinates each (inline up to 4-D: no allocation)
    exact_pts: SmallVec<[f64; 16]>,
    /// per patch, corner (0, 0), (0, q), (p, 0), (p, q) and coordinate: the corner value from
    /// the interval (inari) extraction (several patches only), intersected with the `Ddi` one:
    /// both enclose the same value, and interval knot insertion stays exact on dyadic data,
    /// where `Ddi` always carries a radius
    corner_iv: Vec<Interval>,
}

/// Whether some knot strictly inside the domain [kn[p], kn[n + 1]] has multiplicity p + 1.
fn has_jump(kn: &[f64], p: usize, n: usize) -> bool {
    let (a, b) = (kn[p], kn[n + 1]);
    kn.windows(p + 1)
        .any(|w| w[0] > a && w[0] < b && w.iter().all(|&x| x == w[0]))
}

/// Whether the knots of one direction are those of a single Bézier segment: n = p, the first
/// p + 1 and the last p + 1 knots equal.
fn single_segment(kn: &[f64], p: usize, n: usize) -> bool {
    n == p && kn[..=p].iter().all(|&x| x == kn[0]) && kn[p + 1..].iter().all(|&x| x == kn[p + 1])
}

impl FastSurface {
    /// `None` when the fast path does not apply (see the module docs).
    pub(crate) fn new(s: &NurbsSurface) -> Option<FastSurface> {
        let (p, q) = (s.degree_u(), s.degree_v());
        if p > MAX_DEGREE || q > MAX_DEGREE {
            return None;
        }
        let (ku, kv) = (s.knots_u(), s.knots_v());
        if has_jump(ku, p, s.rows() - 1) || has_jump(kv, q, s.cols() - 1) {
            return None;
        }
        let mut corner_iv = Vec::new();
        let single = single_segment(ku, p, s.rows() - 1) && single_segment(kv, q, s.cols() - 1);
        let patches = if single {
            // the net is the Bézier patch: (w P, w) with exact double-word products
            vec![crate::surface::eval::Net::<Ddi>::points(s)]
        } else {
            let h = s.dim() + s.is_rational() as usize;
            for pa in s.bezier_patches::<Interval>() {
                for (r, c) in [(0, 0), (0, q), (p, 0), (p, q)] {
                    let x = pa.coef(r, c);
                    for j in 0..s.dim() {
                        corner_iv.push(if s.is_rational() {
                            x[j] / x[h - 1]
                        } else {
                            x[j]
                        });
                    }
                }
            }
            s.bezier_patches::<Ddi>()
                .into_iter()
                .map(|pa| pa.pts)
                .collect()
        };
        // patches run over the u spans, then the v spans (`bezier_patches`)
        let nv = (q..s.cols()).filter(|&k| kv[k] < kv[k + 1]).count();
        let np = patches.len();
        let ((a, b), (c, d)) = s.domain();
        let (mut exact, mut exact_pts) = (SmallVec::new(), SmallVec::new());
        for (u, ul, at_u) in [(a, false, 0), (b, true, 1)] {
            for (v, vl, at_v) in [(c, false, 0), (d, true, 1)] {
                // (a single clamped segment per direction: the domain corners are the net's
                // corner points, rows 0 and p, columns 0 and q, as the general look-up finds)
                let rk = if single {
                    (Some(at_u * p), Some(at_v * q))
                } else {
                    (s.exact_row_at(u, ul), s.exact_column_at(v, vl))
                };
                if let (Some(r), Some(k)) = rk {
                    let patch =
                        if at_u == 0 { 0 } else { np - nv } + if at_v == 0 { 0 } else { nv - 1 };
                    let i = (at_u * p) * (q + 1) + at_v * q;
                    exact.push((patch, i));
                    exact_pts.extend_from_slice(s.control_point(r, k));
                }
            }
        }
        Some(FastSurface {
            p,
            q,
            dim: s.dim(),
            rational: s.is_rational(),
            patches,
            exact,
            exact_pts,
            corner_iv,
        })
    }

    /// The coefficient ratio a_i / w_i of patch k (sign-adjusted grid `g` of coordinate j),
    /// enclosed: exact at a clamped domain corner.
    fn ratio<const N: usize>(
        &self,
        k: usize,
        g: &DdGrid<N>,
        i: usize,
        j: usize,
        sign: f64,
    ) -> Interval {
        if let Some(m) = self.exact.iter().position(|e| e.0 == k && e.1 == i) {
            return iv::point(sign * self.exact_pts[m * self.dim + j]);
        }
        let r = g.ratio(i, self.rational);
        let (p, q) = (self.p, self.q);
        let corner = [0, q, p * (q + 1), p * (q + 1) + q]
            .iter()
            .position(|&c| c == i);
        match corner {
            Some(c) if !self.corner_iv.is_empty() => {
                let x = self.corner_iv[(k * 4 + c) * self.dim + j];
                let x = if sign < 0.0 { -x } else { x };
                let m = r.intersection(x);
                if m.is_empty() {
                    r
                } else {
                    m
                }
            }
            _ => r,
        }
    }

    /// The `Ddi` grids (sign * A_j, w) of patch k.
    fn dd_grid<const N: usize>(&self, k: usize, j: usize, sign: f64) -> DdGrid<N> {
        let h = self.dim + self.rational as usize;
        let n = (self.p + 1) * (self.q + 1);
        let mut a = [Ddi::exact(0.0); N];
        let mut w = [Ddi::exact(1.0); N];
        let pts = &self.patches[k];
        for i in 0..n {
            let x = pts[i * h + j];
            a[i] = if sign < 0.0 { -x } else { x };
            if self.rational {
                w[i] = pts[i * h + self.dim];
            }
        }
        DdGrid { a, w }
    }

    /// The maximum of sign * S_j over the surface, proven: `Some((outer, attained))` with
    /// sign * S_j <= outer everywhere and sign * S_j >= attained somewhere, and a strict
    /// witness w (sign * S_j > w somewhere; -inf if none: from a candidate's `Ddi` value,
    /// [`Ddi::strictly_below`]): `(outer, attained, w)`; `None` if the fast path could not prove it
    /// (the caller's general search runs then). Counts the side in `st` (fast exit, fast
    /// proof or fallback).
    pub(crate) fn side(&self, j: usize, sign: f64, st: &mut Stats) -> Option<(f64, f64, f64)> {
        // fixed-size arrays: 16 coefficients up to bicubic, else MAXN (less to copy)
        let r = if (self.p + 1) * (self.q + 1) <= 16 {
            self.side_inner::<16>(j, sign, st)
        } else {
            self.side_inner::<MAXN>(j, sign, st)
        };
        if r.is_none() {
            st.fast_fallbacks += 1;
        }
        r
    }

    fn side_inner<const N: usize>(
        &self,
        j: usize,
        sign: f64,
        st: &mut Stats,
    ) -> Option<(f64, f64, f64)> {
        let n = [self.p, self.q];
        let mut grids: SmallVec<[DdGrid<N>; 1]> = SmallVec::new();
        for k in 0..self.patches.len() {
            grids.push(self.dd_grid(k, j, sign));
        }
        // corners: values the surface takes (continuous surface), and the vertex test
        let (mut lo, mut hi, mut wit) = (f64::NEG_INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
        let mut vertex = true;
        let mut coef_max = SmallVec::<[f64; 1]>::new();
        let corners = [
            0,
            self.q,
            self.p * (self.q + 1),
            self.p * (self.q + 1) + self.q,
        ];
        for (k, g) in grids.iter().enumerate() {
            let mut corner_max = f64::NEG_INFINITY;
            for i in corners {
                let x = self.ratio(k, g, i, j, sign);
                lo = lo.max(x.inf());
                hi = hi.max(x.sup());
                corner_max = corner_max.max(if x.sup().is_nan() {
                    f64::INFINITY
                } else {
                    x.sup()
                });
            }
            // (the corners as above; the other coefficients need no exact-corner lookup)
            let m = (0..(self.p + 1) * (self.q + 1))
                .filter(|i| !corners.contains(i))
                .map(|i| g.ratio_sup(i, self.rational))
                .fold(corner_max, |m, x| {
                    if x.is_nan() {
                        f64::INFINITY
                    } else {
                        m.max(x)
                    }
                });
            coef_max.push(m);
        }
        for &m in &coef_max {
            vertex &= m <= hi;
        }
        if !(lo.is_finite() && hi.is_finite()) {
            return None;
        }
        if vertex {
            st.fast_exits += 1;
            return Some((hi, lo, f64::NEG_INFINITY));
        }
        // candidates on the patches the vertex test did not settle
        // (pushed and filled in place: a grid, a piece and the candidates are hundreds of
        // bytes each)
        let mut roots: SmallVec<[Piece<N>; 1]> = SmallVec::new();
        for g in &grids {
            roots.push(Piece::root(g, n, self.rational)?);
        }
        let mut cands: SmallVec<[[Option<Cand>; 5]; 1]> = SmallVec::new();
        for k in 0..grids.len() {
            cands.push([None; 5]);
            let cs = &mut cands[k];
            if coef_max[k] > hi {
                let root = &roots[k];
                for (e, c) in cs.iter_mut().enumerate().take(4) {
                    if root.edge_max(e) > hi {
                        *c = edge_candidate(root, e, self.rational);
                        st.newton_iterations += 1;
                    }
                }
                cs[4] = newton(root, self.rational);
                st.newton_iterations += 1;
            }
        }
        // the tight (`Ddi`) values of the candidates that may be the best (f64 estimates)
        let best = cands
            .iter()
            .flatten()
            .flatten()
            .fold(hi, |m, c| m.max(c.est));
        let near = 1e-12 * best.abs().max(hi.abs());
        for (k, cs) in cands.iter_mut().enumerate() {
            for (slot, c) in cs.iter_mut().enumerate() {
                let Some(c) = c else { continue };
                if c.est >= best - near {
                    // (the boundary curve's grid for an edge candidate; pieces and grids are
                    // copied only where they are needed)
                    let ge = (slot < 4).then(|| grids[k].edge(slot, n));
                    let g = ge.as_ref().unwrap_or(&grids[k]);
                    let mut m = n;
                    if slot < 4 {
                        m[slot / 2] = 0;
                    }
                    let dd = tight_derivs(g, m, c.t, self.rational);
                    let val = value_of(&dd, self.rational);
                    wit = wit.max(dd_value(&dd, self.rational).strictly_below());
                    c.dd = Some(dd);
                    let scale = if slot < 4 {
                        roots[k].edge_max_abs(slot)
                    } else {
                        roots[k].max_abs()
                    };
                    let exact = if near_float(&dd, self.rational, scale) {
                        if slot < 4 {
                            let root = roots[k].edge(slot);
                            snapped(g, root.n, c.t, &root)
                        } else {
                            snapped(g, n, c.t, &roots[k])
                        }
                    } else {
                        None
                    };
                    match exact {
                        // an exact value at least as good: attained, and the bound to prove
                        Some((_, [a, w])) if (a[0] / w[0]).inf() >= val.inf() => {
                            let v = (a[0] / w[0]).inf();
                            lo = lo.max(v);
                            hi = hi.max(v);
                        }
                        _ => {
                            lo = lo.max(val.inf());
                            hi = hi.max(val.sup());
                        }
                    }
                }
            }
        }
        if !(lo.is_finite() && hi.is_finite()) {
            return None;
        }
        let mut budget = BUDGET;
        let wit0 = wit;
        for first in [hi, hi.next_up()] {
            wit = wit0;
            let (mut ub, mut at) = (first, lo);
            let mut ok = true;
            for k in 0..grids.len() {
                if coef_max[k] <= ub {
                    continue;
                }
                let mut pr = Prover {
                    rational: self.rational,
                    ub,
                    lo: at,
                    wit,
                    budget: &mut budget,
                    edges: [None; 4],
                    cands: &cands[k],
                    found: SmallVec::new(),
                    searches: 4,
                    st: &mut *st,
                };
                ok = pr.prove(&roots[k], 4, &grids[k]);
                (ub, at, wit) = (pr.ub, pr.lo, pr.wit);
                if !ok {
                    break;
                }
            }
            if ok {
                st.fast_proofs += 1;
                return Some((ub, at, wit));
            }
        }
        None
    }
}

/// `Ddi` coefficient grids of one patch for one coordinate side: sign * A_j and w.
#[derive(Clone, Copy)]
struct DdGrid<const N: usize> {
    a: [Ddi; N],
    w: [Ddi; N],
}

impl<const N: usize> DdGrid<N> {
    /// The first `cnt` coefficients of A and w as intervals (their hulls), for the interval
    /// passes that can be exact where `Ddi` always carries a radius.
    fn hulls(&self, cnt: usize) -> (SmallVec<[Interval; MAXN]>, SmallVec<[Interval; MAXN]>) {
        (0..cnt)
            .map(|i| (self.a[i].to_interval(), self.w[i].to_interval()))
            .unzip()
    }

    /// The grid of boundary curve e of a patch of degrees n (see [`Piece::edge`]).
    fn edge(&self, e: usize, n: [usize; 2]) -> DdGrid<N> {
        let mut g = *self;
        let len = if e < 2 { n[1] + 1 } else { n[0] + 1 };
        for k in 0..len {
            let i = edge_index(e, n, k);
            g.a[k] = self.a[i];
            g.w[k] = self.w[i];
        }
        g
    }

    /// The upper end of [`DdGrid::ratio`]: a polynomial patch's exact finite coefficient
    /// (a single f64 h) without building the interval (its `sup` is h, or +0 for h = -0).
    fn ratio_sup(&self, i: usize, rational: bool) -> f64 {
        let a = self.a[i];
        if !rational && a.lo() == 0.0 && a.rad() == 0.0 && a.hi().is_finite() {
            return a.hi() + 0.0;
        }
        self.ratio(i, rational).sup()
    }

    /// The coefficient ratio a_i / w_i, enclosed (a value of the surface at a patch corner).
    fn ratio(&self, i: usize, rational: bool) -> Interval {
        if rational {
            (self.a[i] / self.w[i]).to_interval()
        } else {
            self.a[i].to_interval()
        }
    }
}

/// A candidate point t of a patch (local parameters).
#[derive(Debug, Clone, Copy)]
struct Cand {
    t: [f64; 2],
    /// the f64 estimate of its value
    est: f64,
    /// `Ddi` enclosures of A, w and their first derivatives there ([`tight_derivs`]), once
    /// computed
    dd: Option<[[Ddi; 3]; 2]>,
}

/// A box of a patch's parameter space with the f64 Bernstein coefficients of sign * A_j and w
/// over it (grid `(n[0] + 1) x (n[1] + 1)`, index `r (n[1] + 1) + c`, r along u; a direction
/// with n = 0 is fixed: a boundary curve), each within `ea` / `ew` of the exact coefficient.
#[derive(Clone, Copy)]
struct Piece<const N: usize> {
    /// parameter ranges in the patch's local coordinates (exact for the patch sides: a piece
    /// touches side 0 / 1 iff its range starts at 0.0 / ends at 1.0)
    t: [(f64, f64); 2],
    n: [usize; 2],
    a: [f64; N],
    w: [f64; N],
    ea: f64,
    ew: f64,
    rational: bool,
    /// every coefficient of `a` and `w` is finite: true for [`Piece::root`] (it checks) and
    /// [`Piece::edge`] (a subset of the root's), and for the halves of a split of a finite
    /// piece whose coefficients are at most f64::MAX / 4 in magnitude (each de Casteljau
    /// step b + t (b' - b), t in [0, 1], has |b' - b| <= 2 M' and a result within a factor
    /// 1 + 9u of a convex combination, so over <= MAX_DEGREE levels every intermediate stays
    /// below 2 M (1 + 50 u)^2 < f64::MAX); false: not known, [`Piece::f_values`] checks
    finite: bool,
    depth: u32,
    /// the degrees of the patch (for evaluations at points of the patch)
    full: [usize; 2],
    /// the largest coefficient ratio (f64; set with the coefficients by [`Piece::root`],
    /// [`Piece::edge`] and [`Piece::split_into`]): the search order, and for a polynomial
    /// piece the largest coefficient that [`Piece::excluded`] tests
    prio: f64,
}

/// The layout of a de Casteljau split of a coefficient grid along one direction: `lines`
/// lines of coefficients `stride` apart, the lines `lstride` apart, split at t.
struct Lines {
    lines: usize,
    stride: usize,
    lstride: usize,
    t: f64,
}

impl Lines {
    /// de Casteljau on every line (degree D1 - 1, a constant so that the loops unroll):
    /// the halves into `lo` / `hi`; returns the largest |coefficient| M of `src` read (see
    /// [`Piece::split_into`] for the error bound, which this routine's arithmetic is:
    /// b_i + t (b_{i+1} - b_i) per step), and the largest coefficient written to `lo` and to
    /// `hi` (a NaN is skipped, as `f64::max` does in [`Piece::max_coef`]; the comparisons
    /// below compile to single max instructions, `f64::max` to a NaN-checking sequence).
    #[inline(always)]
    fn split<const D1: usize, const N: usize>(
        &self,
        src: &[f64; N],
        lo: &mut [f64; N],
        hi: &mut [f64; N],
    ) -> [f64; 3] {
        let (t, stride) = (self.t, self.stride);
        let mut m = 0.0f64;
        let (mut ml, mut mh) = (f64::NEG_INFINITY, f64::NEG_INFINITY);
        for k in 0..self.lines {
            let base = k * self.lstride;
            let mut b = [0.0f64; D1];
            for (i, x) in b.iter_mut().enumerate() {
                *x = src[base + i * stride];
                raise(&mut m, x.abs());
            }
            lo[base] = b[0];
            hi[base + (D1 - 1) * stride] = b[D1 - 1];
            raise(&mut ml, b[0]);
            raise(&mut mh, b[D1 - 1]);
            for lev in 1..D1 {
                for i in 0..D1 - lev {
                    b[i] += t * (b[i + 1] - b[i]);
                }
                lo[base + lev * stride] = b[0];
                hi[base + (D1 - 1 - lev) * stride] = b[D1 - 1 - lev];
                raise(&mut ml, b[0]);
                raise(&mut mh, b[D1 - 1 - lev]);
            }
        }
        [m, ml, mh]
    }
}

/// The split of [`Lines::split`] for a grid of R x C coefficients (index r C + c) with both
/// sizes constants (the bicubic patch and its boundary curves): the same arithmetic
/// b_i + t (b_{i+1} - b_i) on the same values, so the same results, but on whole rows
/// (`dir` 0) or columns (`dir` 1) at a time, which the compiler unrolls and vectorises; the
/// maxima are the same maxima, taken per lane first.
#[inline(always)]
fn split_grid<const R: usize, const C: usize, const N: usize>(
    src: &[f64; N],
    dir: usize,
    t: f64,
    lo: &mut [f64; N],
    hi: &mut [f64; N],
) -> [f64; 3] {
    /// de Casteljau on D vectors of L lanes: `b[i]` is line i along the split direction;
    /// `put(level, lo_vector, hi_vector)` stores level k of both halves (lo: index k, hi:
    /// index D - 1 - k); returns the lane maxima of |b|, of lo and of hi.
    #[inline(always)]
    fn run<const D: usize, const L: usize>(
        mut b: [[f64; L]; D],
        t: f64,
        mut put: impl FnMut(usize, &[f64; L], &[f64; L]),
    ) -> [[f64; L]; 3] {
        let mut m = [[0.0f64; L]; 3];
        m[1] = [f64::NEG_INFINITY; L];
        m[2] = [f64::NEG_INFINITY; L];
        for row in &b {
            for (x, y) in m[0].iter_mut().zip(row) {
                raise(x, y.abs());
            }
        }
        for lev in 0..D {
            if lev > 0 {
                for i in 0..D - lev {
                    let nx = b[i + 1];
                    for (x, y) in b[i].iter_mut().zip(nx) {
                        *x += t * (y - *x);
                    }
                }
            }
            let (l, h) = (b[0], b[D - 1 - lev]);
            for k in 0..L {
                raise(&mut m[1][k], l[k]);
                raise(&mut m[2][k], h[k]);
            }
            put(lev, &l, &h);
        }
        m
    }
    /// The lane maxima of [`run`] reduced to `[m, ml, mh]`.
    fn reduce<const L: usize>(m: [[f64; L]; 3]) -> [f64; 3] {
        let mut out = [0.0, f64::NEG_INFINITY, f64::NEG_INFINITY];
        for (o, lanes) in out.iter_mut().zip(m) {
            for x in lanes {
                raise(o, x);
            }
        }
        out
    }
    if dir == 0 {
        let b: [[f64; C]; R] = std::array::from_fn(|r| std::array::from_fn(|c| src[r * C + c]));
        reduce(run::<R, C>(b, t, |k, l, h| {
            lo[k * C..(k + 1) * C].copy_from_slice(l);
            hi[(R - 1 - k) * C..(R - k) * C].copy_from_slice(h);
        }))
    } else {
        let b: [[f64; R]; C] = std::array::from_fn(|c| std::array::from_fn(|r| src[r * C + c]));
        reduce(run::<C, R>(b, t, |k, l, h| {
            for r in 0..R {
                lo[r * C + k] = l[r];
                hi[r * C + C - 1 - k] = h[r];
            }
        }))
    }
}

/// m = max(m, x) for a running maximum m that is not NaN, skipping a NaN x (as `f64::max`
/// does) by a comparison: one max instruction, where `f64::max` is a NaN-checking sequence
/// (the maxima of the proof's inner loops).
#[inline(always)]
fn raise(m: &mut f64, x: f64) {
    if x > *m {
        *m = x;
    }
}

/// Index of coefficient k of boundary curve e (0: u = 0, 1: u = 1, 2: v = 0, 3: v = 1) in
/// the grid of a patch of degrees n.
fn edge_index(e: usize, n: [usize; 2], k: usize) -> usize {
    match e {
        0 => k,
        1 => n[0] * (n[1] + 1) + k,
        2 => k * (n[1] + 1),
        _ => k * (n[1] + 1) + n[1],
    }
}

/// f64 value and error bound of an enclosure: the centre hi + lo is within |lo| + rad of
/// every enclosed real, and RN(hi + lo) = hi is within |lo| of the centre.
fn f64_of(x: Ddi) -> (f64, f64) {
    (x.hi(), x.lo().abs() + x.rad())
}

impl<const N: usize> Piece<N> {
    /// The whole patch.
    fn root(g: &DdGrid<N>, n: [usize; 2], rational: bool) -> Option<Piece<N>> {
        let cnt = (n[0] + 1) * (n[1] + 1);
        let mut pc = Piece {
            t: [(0.0, 1.0), (0.0, 1.0)],
            n,
            a: [0.0; N],
            w: [1.0; N],
            ea: 0.0,
            ew: 0.0,
            rational,
            // (returned only if every coefficient is finite, below)
            finite: true,
            depth: 0,
            full: n,
            prio: 0.0,
        };
        // (the maxima in locals: a chain through the piece's fields in memory was slow)
        let (mut ea, mut ew) = (0.0f64, 0.0f64);
        for i in 0..cnt {
            let (x, e) = f64_of(g.a[i]);
            pc.a[i] = x;
            ea = ea.max(e);
            if rational {
                let (x, e) = f64_of(g.w[i]);
                pc.w[i] = x;
                ew = ew.max(e);
            }
        }
        // (a sum of two nonnegative f64 rounded up: Lemma B of `num::ddi`)
        pc.ea = up(ea);
        pc.ew = up(ew);
        pc.prio = pc.max_coef();
        (pc.a[..cnt].iter().all(|x| x.is_finite()) && pc.w[..cnt].iter().all(|x| x.is_finite()))
            .then_some(pc)
    }

    fn count(&self) -> usize {
        (self.n[0] + 1) * (self.n[1] + 1)
    }

    /// Boundary curve e of the patch (0: u = 0, 1: u = 1, 2: v = 0, 3: v = 1) as a 1-D piece
    /// (its coefficients are the patch's boundary row / column: exactly the curve's Bézier
    /// coefficients). Only for the root piece.
    fn edge(&self, e: usize) -> Piece<N> {
        let [n0, n1] = self.n;
        let (dir, at) = (e / 2, if e % 2 == 0 { 0.0 } else { 1.0 });
        let mut n = self.n;
        n[dir] = 0;
        let mut t = self.t;
        t[dir] = (at, at);
        // (built afresh, not copied: only the curve's coefficients are read)
        let mut pc = Piece {
            t,
            n,
            a: [0.0; N],
            w: [1.0; N],
            ea: self.ea,
            ew: self.ew,
            rational: self.rational,
            finite: self.finite,
            depth: self.depth,
            full: n,
            prio: 0.0,
        };
        let len = if dir == 0 { n1 + 1 } else { n0 + 1 };
        for k in 0..len {
            pc.a[k] = self.a[edge_index(e, self.n, k)];
            pc.w[k] = self.w[edge_index(e, self.n, k)];
        }
        pc.prio = pc.max_coef();
        pc
    }

    /// The point of the piece below its largest coefficient (the Greville-like abscissa
    /// i / n): a seed for Newton's method.
    fn argmax_point(&self) -> [f64; 2] {
        let n = self.n;
        let bi = (0..self.count())
            .max_by(|&x, &y| (self.a[x] / self.w[x]).total_cmp(&(self.a[y] / self.w[y])))
            .unwrap_or(0);
        let (r, c) = (bi / (n[1] + 1), bi % (n[1] + 1));
        let at = |k: usize, i: usize| {
            let (a, b) = self.t[k];
            if n[k] == 0 {
                a
            } else {
                a + (b - a) * (i as f64 / n[k] as f64)
            }
        };
        [at(0, r), at(1, c)]
    }

    /// The largest |coefficient ratio| (f64; a scale only).
    fn max_abs(&self) -> f64 {
        (0..self.count())
            .map(|i| (self.a[i] / self.w[i]).abs())
            .fold(0.0, f64::max)
    }

    /// The largest coefficient ratio of boundary curve e (the `max_coef` of
    /// [`Piece::edge`], without building the curve's piece).
    fn edge_max(&self, e: usize) -> f64 {
        self.edge_ratios(e).fold(f64::NEG_INFINITY, f64::max)
    }

    /// The `max_abs` of [`Piece::edge`], without building the curve's piece.
    fn edge_max_abs(&self, e: usize) -> f64 {
        self.edge_ratios(e).map(f64::abs).fold(0.0, f64::max)
    }

    /// The coefficient ratios of boundary curve e, in order.
    fn edge_ratios(&self, e: usize) -> impl Iterator<Item = f64> + '_ {
        let len = if e < 2 { self.n[1] + 1 } else { self.n[0] + 1 };
        (0..len).map(move |k| {
            let i = edge_index(e, self.n, k);
            self.a[i] / self.w[i]
        })
    }

    fn max_coef(&self) -> f64 {
        let cnt = self.count();
        if !self.rational {
            // (w = 1: no divisions)
            return self.a[..cnt].iter().fold(f64::NEG_INFINITY, |mut m, &x| {
                raise(&mut m, x);
                m
            });
        }
        (0..cnt).fold(f64::NEG_INFINITY, |mut m, i| {
            raise(&mut m, self.a[i] / self.w[i]);
            m
        })
    }

    /// de Casteljau subdivision along `dir` at the local parameter `t` in [0, 1], an f64
    /// within `delta` of the exact split parameter tau: the pieces over [0, tau] and [tau, 1]
    /// of this piece's range (ranges: bookkeeping, the sides stay exact).
    ///
    /// Error bound. Every exact intermediate point is a convex combination of the exact
    /// coefficients, computed ones within e of them, all of magnitude <= M (the largest
    /// computed |coefficient|; the growth below over 2 * MAX_DEGREE levels stays under a
    /// factor 1 + 2^-40). One step r = fl(fl(t fl(b - a)) + a) against the exact
    /// a + tau (b - a): the inputs contribute (1 - tau) e + tau e = e, the parameter
    /// |t - tau| |b - a| <= 2 delta M, the three roundings u (|b - a| + |t (b - a)| + |r|)
    /// <= 5.01 u M plus eta (2^-1074, the underflow error of the product). A split of degree
    /// n has n levels: e' = e + n ((2 delta + 6 u) M + 2 eta), rounded up (Lemma B of
    /// `num::ddi`).
    ///
    /// The halves are written into `l` and `r` (any pieces of the same patch: every field is
    /// set but the weights of a polynomial piece, which are 1 in every piece of it, as
    /// [`Piece::root`] and [`Piece::edge`] made them), so the caller can split straight into
    /// the slots of its work list (a `Piece` is a few hundred bytes; copies of it were a
    /// fifth of the proof's cost).
    #[inline]
    fn split_into(&self, dir: usize, t: f64, delta: f64, l: &mut Piece<N>, r: &mut Piece<N>) {
        for x in [&mut *l, &mut *r] {
            x.t = self.t;
            x.n = self.n;
            x.ea = self.ea;
            x.ew = self.ew;
            x.rational = self.rational;
            x.depth = self.depth + 1;
            x.full = self.full;
        }
        let n = self.n[dir];
        let [_, n1] = self.n;
        let (stride, lines, lstride) = if dir == 0 {
            (n1 + 1, n1 + 1, 1)
        } else {
            (1, self.n[0] + 1, n1 + 1)
        };
        let grow = |e: f64, m: f64| {
            up(e + n as f64 * ((2.0 * delta + 6.0 * UNIT) * m * (1.0 + 1e-12) + 2e-323))
        };
        // (the degree as a constant, so that the loops unroll; n <= MAX_DEGREE = 5, the
        // fast path's restriction)
        let run = |src: &[f64; N], lo: &mut [f64; N], hi: &mut [f64; N]| {
            let g = Lines {
                lines,
                stride,
                lstride,
                t,
            };
            match (self.n, n) {
                ([3, 3], _) => split_grid::<4, 4, N>(src, dir, t, lo, hi),
                ([3, 0], _) => split_grid::<4, 1, N>(src, dir, t, lo, hi),
                ([0, 3], _) => split_grid::<1, 4, N>(src, dir, t, lo, hi),
                (_, 0) => g.split::<1, N>(src, lo, hi),
                (_, 1) => g.split::<2, N>(src, lo, hi),
                (_, 2) => g.split::<3, N>(src, lo, hi),
                (_, 3) => g.split::<4, N>(src, lo, hi),
                (_, 4) => g.split::<5, N>(src, lo, hi),
                _ => g.split::<{ MAX_DEGREE + 1 }, N>(src, lo, hi),
            }
        };
        let [ma, pl, pr] = run(&self.a, &mut l.a, &mut r.a);
        l.ea = grow(self.ea, ma);
        r.ea = l.ea;
        l.finite = self.finite && ma <= f64::MAX / 4.0;
        if self.rational {
            let [mw, _, _] = run(&self.w, &mut l.w, &mut r.w);
            l.ew = grow(self.ew, mw);
            r.ew = l.ew;
            l.finite &= mw <= f64::MAX / 4.0;
            l.prio = l.max_coef();
            r.prio = r.max_coef();
        } else {
            // (the largest coefficients, found while they were written)
            l.prio = pl;
            r.prio = pr;
        }
        r.finite = l.finite;
        let (a, b) = self.t[dir];
        let m = (a + t * (b - a)).clamp(a, b);
        l.t[dir] = (a, m);
        r.t[dir] = (m, b);
    }

    /// The coefficients g of a polynomial that has F's derivatives, and their error bound:
    /// the a themselves (polynomial: F = A - ub), or f = fl(a - ub w) (rational; error
    /// ea + |ub| ew + U1 |f| + eta, the FMA's rounding). `None` if not finite.
    fn f_values<'a>(&'a self, ub: f64, f: &'a mut [f64; N]) -> Option<(&'a [f64; N], f64)> {
        let cnt = self.count();
        if !self.rational {
            // (a split may overflow near +-f64::MAX; every test below needs finite
            // coefficients: `f64::max` would skip a NaN; known for most pieces, `finite`)
            return (self.ea.is_finite()
                && (self.finite || self.a[..cnt].iter().all(|x| x.is_finite())))
            .then_some((&self.a, self.ea));
        }
        let mut m = 0.0f64;
        for (i, fi) in f.iter_mut().enumerate().take(cnt) {
            *fi = (-ub).mul_add(self.w[i], self.a[i]);
            if !fi.is_finite() {
                return None;
            }
            m = m.max(fi.abs());
        }
        Some((f, up(self.ea + ub.abs() * self.ew + U1 * m)))
    }

    /// Whether F <= 0 on the piece by its coefficients (convex hull property): polynomial
    /// a_i + ea <= ub (the sum rounded up), rational f_i + E <= 0 (the sign of a sum of two
    /// floats is exact).
    fn excluded(&self, f: &[f64; N], e: f64, ub: f64) -> bool {
        if !self.rational {
            // (f = a: its largest coefficient is `prio`, kept with the coefficients)
            return (self.prio + e).next_up() <= ub;
        }
        let m = f[..self.count()]
            .iter()
            .fold(f64::NEG_INFINITY, |m, &x| m.max(x));
        m + e <= 0.0
    }

    /// Whether F is non-increasing (`down`) / non-decreasing along `dir` on the piece: every
    /// difference d of neighbouring coefficients along `dir` has that sign (the exact one
    /// within 2 e + U1 |d| of the computed one); the Bernstein coefficients of F_t are n d.
    fn monotone(&self, f: &[f64; N], e: f64, dir: usize, down: bool) -> bool {
        // (constant sizes for the bicubic patch and its boundary curves: the loops unroll)
        match self.n {
            [3, 3] => monotone_in(f, e, dir, down, [3, 3]),
            [3, 0] => monotone_in(f, e, dir, down, [3, 0]),
            [0, 3] => monotone_in(f, e, dir, down, [0, 3]),
            n => monotone_in(f, e, dir, down, n),
        }
    }

    /// mu > 0 with -H(x) >= mu I for every x in the piece (H the Hessian of F in the piece's
    /// own parameters s in [0, 1]^k over its free directions), or `None`.
    ///
    /// The Bernstein coefficients of F_uu, F_uv, F_vv are n0 (n0 - 1) D_uu, n0 n1 D_uv,
    /// n1 (n1 - 1) D_vv (second differences of the coefficients; each computed one within
    /// 4 e + 9 u M of the exact one: three roundings of magnitudes <= 2M, 2M, 4M), so their
    /// ranges over the piece are enclosed (convex hull property). With alpha >= a0 > 0,
    /// gamma >= c0 > 0 the diagonal of -H and |beta| <= b0 its off-diagonal entry, the
    /// eigenvalues of -H are those of D^-1 (-H) D, D = diag(1, r), whose Gershgorin discs
    /// give lambda_min >= min(a0 - b0 r, c0 - b0 / r) for any r > 0 (r = sqrt(a0 / c0) makes
    /// both equal when a0 c0 > b0^2). All in interval arithmetic.
    fn concavity(&self, f: &[f64; N], e: f64) -> Option<f64> {
        self.concavity_from(f, e, self.second_maxima(f))
    }

    /// [`Piece::second_max`] along both directions (`None` for a fixed one).
    fn second_maxima(&self, f: &[f64; N]) -> [Option<f64>; 2] {
        [0, 1].map(|d| (self.n[d] > 0).then(|| self.second_max(f, d)).flatten())
    }

    /// [`Piece::concavity`] from the [`Piece::second_maxima`] `s` of f.
    fn concavity_from(&self, f: &[f64; N], e: f64, s: [Option<f64>; 2]) -> Option<f64> {
        let [n0, n1] = self.n;
        let at = |r: usize, c: usize| f[r * (n1 + 1) + c];
        // (the signs first: most pieces fail there, before any error bound; then one error
        // bound for all second differences)
        let m0 = match n0 {
            0 => None,
            _ => Some(s[0]?),
        };
        let m1 = match n1 {
            0 => None,
            _ => Some(s[1]?),
        };
        let err = self.second_error(f, e);
        if !err.is_finite() {
            return None;
        }
        let a0 = match m0 {
            None => None,
            Some(mx) => Some(self.curvature_within(mx, err, 0)?),
        };
        let c0 = match m1 {
            None => None,
            Some(mx) => Some(self.curvature_within(mx, err, 1)?),
        };
        match (a0, c0) {
            (Some(a), None) | (None, Some(a)) => Some(a),
            (Some(a), Some(c)) => {
                let kk = iv::point((n0 * n1) as f64);
                let mut dm = 0.0f64;
                for r in 0..n0 {
                    for c in 0..n1 {
                        let d = (at(r + 1, c + 1) - at(r + 1, c)) - (at(r, c + 1) - at(r, c));
                        dm = dm.max(d.abs());
                    }
                }
                // |(d + pm) k| <= (|d| + err) k
                let b0 = ((iv::point(dm) + iv::point(err)) * kk).sup();
                let rr = (a / c).sqrt();
                if !(rr.is_finite() && rr > 0.0) {
                    return None;
                }
                let (ai, ci, bi, ri) = (iv::point(a), iv::point(c), iv::point(b0), iv::point(rr));
                let mu = (ai - bi * ri).inf().min((ci - bi / ri).inf());
                (mu > 0.0).then_some(mu)
            }
            (None, None) => None,
        }
    }

    /// The error bound of a computed second difference of the coefficients f (each within e
    /// of the exact one): 4 e + 9 u M (see [`Piece::concavity`]); infinite if some f is not
    /// finite.
    fn second_error(&self, f: &[f64; N], e: f64) -> f64 {
        let cnt = self.count();
        let m = f[..cnt].iter().fold(0.0f64, |mut m, x| {
            if x.is_finite() {
                raise(&mut m, x.abs());
                m
            } else {
                f64::INFINITY
            }
        });
        up(4.0 * e + 9.0 * UNIT * m)
    }

    /// a > 0 with F_dd <= -a on the whole piece (d = `dir`, in the piece's own parameter),
    /// or `None`: the Bernstein coefficients of F_dd are n (n - 1) times the second
    /// differences of the coefficients along d (each within [`Piece::second_error`] of the
    /// exact one), and F_dd lies in their hull.
    fn curvature(&self, f: &[f64; N], e: f64, dir: usize) -> Option<f64> {
        let mx = self.second_max(f, dir)?;
        let err = self.second_error(f, e);
        if !err.is_finite() {
            return None;
        }
        self.curvature_within(mx, err, dir)
    }

    /// The largest computed second difference of the coefficients along `dir`; `None` for a
    /// degree below 2, and as soon as one difference is not < 0 (or NaN): then
    /// (d + err) k >= 0 for every err >= 0 and [`Piece::curvature_within`] would fail.
    fn second_max(&self, f: &[f64; N], dir: usize) -> Option<f64> {
        if self.n[dir] < 2 {
            return None;
        }
        // (constant sizes as in [`Piece::monotone`])
        match self.n {
            [3, 3] => second_max_in(f, dir, [3, 3]),
            [3, 0] => second_max_in(f, dir, [3, 0]),
            [0, 3] => second_max_in(f, dir, [0, 3]),
            n => second_max_in(f, dir, n),
        }
    }

    /// [`Piece::curvature`] from the largest second difference `mx` along `dir`
    /// ([`Piece::second_max`]) and the finite error bound `err` of the second differences.
    fn curvature_within(&self, mx: f64, err: f64, dir: usize) -> Option<f64> {
        let nd = self.n[dir];
        // ((d + err) k is increasing in d for k > 0: the largest d first)
        let h = ((iv::point(mx) + iv::point(err)) * iv::point((nd * (nd - 1)) as f64)).sup();
        (h < 0.0).then_some(-h)
    }
}

/// [`Piece::monotone`] on a grid of degrees n (inlined, so that constant degrees unroll).
#[inline(always)]
fn monotone_in<const N: usize>(
    f: &[f64; N],
    e: f64,
    dir: usize,
    down: bool,
    n: [usize; 2],
) -> bool {
    let [n0, n1] = n;
    let step = if dir == 0 { n1 + 1 } else { 1 };
    for r in 0..=n0 {
        for c in 0..=n1 {
            if (dir == 0 && r == n0) || (dir == 1 && c == n1) {
                continue;
            }
            let i = r * (n1 + 1) + c;
            let d = f[i + step] - f[i];
            let m = up(2.0 * e + U1 * d.abs());
            let ok = if down { d + m <= 0.0 } else { d - m >= 0.0 };
            if !ok {
                return false;
            }
        }
    }
    true
}

/// [`Piece::second_max`] on a grid of degrees n, `n[dir] >= 2` (inlined, as [`monotone_in`]).
#[inline(always)]
fn second_max_in<const N: usize>(f: &[f64; N], dir: usize, n: [usize; 2]) -> Option<f64> {
    let [n0, n1] = n;
    let step = if dir == 0 { n1 + 1 } else { 1 };
    let mut mx = f64::NEG_INFINITY;
    for r in 0..=n0 {
        for c in 0..=n1 {
            if (dir == 0 && r + 2 > n0) || (dir == 1 && c + 2 > n1) {
                continue;
            }
            let i = r * (n1 + 1) + c;
            let d = (f[i + 2 * step] - f[i + step]) - (f[i + step] - f[i]);
            if d >= 0.0 || d.is_nan() {
                return None;
            }
            raise(&mut mx, d);
        }
    }
    Some(mx)
}

/// Value and partial derivatives of one Bernstein polynomial at t (de Casteljau; NURBS Book
/// A1.5): `[p, p', p'']`, the derivatives from the second-to-last levels of the pyramid
/// (p' = n (c_1 - c_0) at level n - 1, p'' = n (n - 1) (b_2 - 2 b_1 + b_0) at level n - 2;
/// Farin, derivatives of a Bézier curve). For verified types every result encloses the exact
/// one. `b` is overwritten. Derivatives of order above `ORDER` are not computed (0): the
/// `Ddi` and interval evaluations need the value and the gradient only. (The degree is
/// dispatched to a constant, [`bern2_fixed`], so that the loops unroll: this is the inner
/// loop of every Newton iteration.)
fn bern2<S: Scalar + Copy, const ORDER: usize>(b: &mut [S], t: S) -> [S; 3] {
    fn fixed<S: Scalar + Copy, const D1: usize, const ORDER: usize>(b: &mut [S], t: S) -> [S; 3] {
        bern2_fixed::<S, D1, ORDER>(b.try_into().expect("length D1"), t)
    }
    match b.len() {
        1 => [b[0], S::zero(), S::zero()],
        2 => fixed::<S, 2, ORDER>(b, t),
        3 => fixed::<S, 3, ORDER>(b, t),
        4 => fixed::<S, 4, ORDER>(b, t),
        5 => fixed::<S, 5, ORDER>(b, t),
        _ => fixed::<S, { MAX_DEGREE + 1 }, ORDER>(b, t),
    }
}

/// [`bern2`] for degree n = D1 - 1 >= 1.
#[inline(always)]
fn bern2_fixed<S: Scalar + Copy, const D1: usize, const ORDER: usize>(
    b: &mut [S; D1],
    t: S,
) -> [S; 3] {
    // lo + t (hi - lo) as one Horner step (one fused, enclosed step for `Ddi`: over at most
    // 2 MAX_DEGREE levels its radius growth is immaterial; plain arithmetic for f64)
    #[inline(always)]
    fn step<S: Scalar + Copy>(t: &S, lo: &S, hi: &S) -> S {
        S::horner_step(&(*hi - *lo), t, lo)
    }
    let n = D1 - 1;
    for lev in 1..n.saturating_sub(1) {
        for i in 0..=n - lev {
            b[i] = step(&t, &b[i], &b[i + 1]);
        }
    }
    let d2 = if n >= 2 && ORDER >= 2 {
        S::from_usize(n * (n - 1)) * ((b[2] - b[1]) - (b[1] - b[0]))
    } else {
        S::zero()
    };
    if n >= 2 {
        b[0] = step(&t, &b[0], &b[1]);
        b[1] = step(&t, &b[1], &b[2]);
    }
    let d1 = if ORDER >= 1 {
        S::from_usize(n) * (b[1] - b[0])
    } else {
        S::zero()
    };
    [step(&t, &b[0], &b[1]), d1, d2]
}

/// The tensor Bernstein polynomial with coefficients `c` (grid `(n[0] + 1) x (n[1] + 1)`) at
/// t: `[f, f_u, f_v, f_uu, f_uv, f_vv]` (generic over the number type: f64 for the Newton
/// iterations, `Ddi` for the values the proofs use), the derivatives of order above `ORDER`
/// not computed (0). The v direction first on every row, then u on the results; a boundary
/// curve (a degree 0) is one curve evaluation, the derivatives across it 0.
fn eval2<S: Scalar + Copy, const ORDER: usize>(c: &[S], n: [usize; 2], t: [f64; 2]) -> [S; 6] {
    if n == [3, 3] {
        return eval2_grid::<S, 4, 4, ORDER>(c, t);
    }
    let z = S::zero();
    let (tu, tv) = (S::from_f64(t[0]), S::from_f64(t[1]));
    if n[0] == 0 || n[1] == 0 {
        let (d, tc) = if n[0] == 0 { (1, tv) } else { (0, tu) };
        let mut b = [z; MAX_DEGREE + 1];
        b[..=n[d]].copy_from_slice(&c[..=n[d]]);
        let [f, fd, fdd] = bern2::<S, ORDER>(&mut b[..=n[d]], tc);
        return if d == 0 {
            [f, fd, z, fdd, z, z]
        } else {
            [f, z, fd, z, z, fdd]
        };
    }
    let mut g = [[z; MAX_DEGREE + 1]; 3];
    let mut row = [z; MAX_DEGREE + 1];
    for r in 0..=n[0] {
        row[..=n[1]].copy_from_slice(&c[r * (n[1] + 1)..(r + 1) * (n[1] + 1)]);
        let [v, dv, dvv] = bern2::<S, ORDER>(&mut row[..=n[1]], tv);
        g[0][r] = v;
        g[1][r] = dv;
        g[2][r] = dvv;
    }
    let [f, fu, fuu] = bern2::<S, ORDER>(&mut g[0][..=n[0]], tu);
    // (f_v and f_uv from the v derivatives, f_vv from the second ones: one order less each)
    let (fv, fuv) = match ORDER {
        0 => (z, z),
        1 => (bern2::<S, 0>(&mut g[1][..=n[0]], tu)[0], z),
        _ => {
            let [fv, fuv, _] = bern2::<S, 1>(&mut g[1][..=n[0]], tu);
            (fv, fuv)
        }
    };
    let fvv = if ORDER >= 2 {
        bern2::<S, 0>(&mut g[2][..=n[0]], tu)[0]
    } else {
        z
    };
    [f, fu, fv, fuu, fuv, fvv]
}

/// [`eval2`] on a grid of R x C coefficients (degrees R - 1, C - 1 >= 1) with both sizes
/// constants (the bicubic patch): the same steps on the same values ([`bern2_fixed`] per
/// row, then on the columns of the results), so the same results, without the run-time
/// lengths.
#[inline(always)]
fn eval2_grid<S: Scalar + Copy, const R: usize, const C: usize, const ORDER: usize>(
    c: &[S],
    t: [f64; 2],
) -> [S; 6] {
    let z = S::zero();
    let (tu, tv) = (S::from_f64(t[0]), S::from_f64(t[1]));
    let mut g = [[z; R]; 3];
    for r in 0..R {
        let mut row: [S; C] = std::array::from_fn(|k| c[r * C + k]);
        let [v, dv, dvv] = bern2_fixed::<S, C, ORDER>(&mut row, tv);
        g[0][r] = v;
        g[1][r] = dv;
        g[2][r] = dvv;
    }
    let [f, fu, fuu] = bern2_fixed::<S, R, ORDER>(&mut g[0], tu);
    let (fv, fuv) = match ORDER {
        0 => (z, z),
        1 => (bern2_fixed::<S, R, 0>(&mut g[1], tu)[0], z),
        _ => {
            let [fv, fuv, _] = bern2_fixed::<S, R, 1>(&mut g[1], tu);
            (fv, fuv)
        }
    };
    let fvv = if ORDER >= 2 {
        bern2_fixed::<S, R, 0>(&mut g[2], tu)[0]
    } else {
        z
    };
    [f, fu, fv, fuu, fuv, fvv]
}

/// S = A / w and its derivatives up to order 2 from those of A and w (NURBS Book A4.4 in two
/// variables): S_u = (A_u - S w_u) / w, S_uu = (A_uu - 2 S_u w_u - S w_uu) / w,
/// S_uv = (A_uv - S_u w_v - S_v w_u - S w_uv) / w.
fn quotient<S: Scalar + Copy>(a: [S; 6], w: [S; 6]) -> [S; 6] {
    let s = a[0] / w[0];
    let su = (a[1] - s * w[1]) / w[0];
    let sv = (a[2] - s * w[2]) / w[0];
    let two = S::from_f64(2.0);
    let suu = (a[3] - two * su * w[1] - s * w[3]) / w[0];
    let suv = (a[4] - su * w[2] - sv * w[1] - s * w[4]) / w[0];
    let svv = (a[5] - two * sv * w[2] - s * w[5]) / w[0];
    [s, su, sv, suu, suv, svv]
}

/// The candidate of boundary curve e of the root piece (0: u = 0, 1: u = 1, 2: v = 0,
/// 3: v = 1): a polynomial cubic curve's local maximum in closed form, else [`newton`] on
/// the curve's piece. With d_i = b_{i+1} - b_i the derivative of x(s) = sum b_i B_i^3(s) is
/// 3 (d_0 (1 - s)^2 + 2 d_1 s (1 - s) + d_2 s^2) = 3 q(s), q(s) = d_0 + 2 (d_1 - d_0) s +
/// (d_0 - 2 d_1 + d_2) s^2 (Farin, *Curves and Surfaces for CAGD*, derivatives of a Bézier
/// curve); a cubic has at most one local maximum, the root of q where q' < 0 (x'' = 3 q'),
/// the point [`newton`] converges to when it converges. Its f64 roots come from the
/// cancellation-free quadratic formula of the curve side. (An estimate only, as Newton's:
/// soundness never depends on it.)
fn edge_candidate<const N: usize>(root: &Piece<N>, e: usize, rational: bool) -> Option<Cand> {
    let len = if e < 2 { root.n[1] + 1 } else { root.n[0] + 1 };
    if rational || len != 4 {
        return newton(&root.edge(e), rational);
    }
    let mut b: [f64; 4] = std::array::from_fn(|k| root.a[edge_index(e, root.n, k)]);
    let d = [b[1] - b[0], b[2] - b[1], b[3] - b[2]];
    let (c0, c1, c2) = (d[0], 2.0 * (d[1] - d[0]), d[0] - 2.0 * d[1] + d[2]);
    let (r, nr) = crate::enclose::root_estimates(c0, c1, c2);
    let s = r[..nr]
        .iter()
        .copied()
        .find(|&s| (0.0..=1.0).contains(&s) && 2.0 * c2 * s + c1 < 0.0)?;
    let at = if e % 2 == 0 { 0.0 } else { 1.0 };
    let t = if e < 2 { [at, s] } else { [s, at] };
    let est = bern2::<f64, 0>(&mut b, s)[0];
    est.is_finite().then_some(Cand { t, est, dd: None })
}

/// f64 Newton iterations for a local maximum of sign * S_j on the piece `pc` (the root patch
/// or one of its boundary curves), from the largest coefficient;
/// the point's value enclosed in `Ddi` from the patch grid `g`. `None` if the iteration
/// leaves the piece or does not settle at a point with a negative definite f64 Hessian.
/// (An estimate only: soundness never depends on it.)
fn newton<const N: usize>(pc: &Piece<N>, rational: bool) -> Option<Cand> {
    let n = pc.n;
    let cnt = pc.count();
    let (mut best, mut bi) = (f64::NEG_INFINITY, 0);
    for i in 0..cnt {
        let x = pc.a[i] / pc.w[i];
        if x > best {
            best = x;
            bi = i;
        }
    }
    let (r, c) = (bi / (n[1] + 1), bi % (n[1] + 1));
    let mut t = [pc.t[0].0, pc.t[1].0];
    if n[0] > 0 {
        t[0] = (r as f64 / n[0] as f64).clamp(0.05, 0.95);
    }
    if n[1] > 0 {
        t[1] = (c as f64 / n[1] as f64).clamp(0.05, 0.95);
    }
    newton_from(pc, rational, t)
}

/// [`newton`] from the point t of the patch (the free directions of the root piece `pc`
/// move, in [0, 1]; its coefficients are the f64 centres of the patch's or the boundary
/// curve's).
fn newton_from<const N: usize>(pc: &Piece<N>, rational: bool, mut t: [f64; 2]) -> Option<Cand> {
    let free = [pc.t[0].0 != pc.t[0].1, pc.t[1].0 != pc.t[1].1];
    // evaluate on the whole patch grid (a boundary curve is the patch at a fixed side)
    let (pn, fa, fw) = (pc.n, &pc.a, &pc.w);
    let mut ok = false;
    for _ in 0..24 {
        let a = eval2::<f64, 2>(&fa[..], pn, t);
        let d = if rational {
            quotient(a, eval2::<f64, 2>(&fw[..], pn, t))
        } else {
            a
        };
        let (su, sv, suu, suv, svv) = (d[1], d[2], d[3], d[4], d[5]);
        let step = match free {
            [true, true] => {
                let det = suu * svv - suv * suv;
                if !(det > 0.0 && suu < 0.0) {
                    return None;
                }
                [-(svv * su - suv * sv) / det, -(suu * sv - suv * su) / det]
            }
            [true, false] => {
                if suu >= 0.0 || suu.is_nan() {
                    return None;
                }
                [-su / suu, 0.0]
            }
            [false, true] => {
                if svv >= 0.0 || svv.is_nan() {
                    return None;
                }
                [0.0, -sv / svv]
            }
            [false, false] => return None,
        };
        let nt = [t[0] + step[0], t[1] + step[1]];
        if !(nt.iter().all(|x| x.is_finite() && (0.0..=1.0).contains(x))) {
            return None;
        }
        // quadratic convergence: after a step below 1e-9 the point is within ~1e-18 of the
        // maximiser, the rounding level of t in [0, 1]
        t = nt;
        if step.iter().all(|s| s.abs() <= 1e-9) {
            ok = true;
            break;
        }
    }
    let a = eval2::<f64, 0>(&fa[..], pn, t);
    let est = if rational {
        a[0] / eval2::<f64, 0>(&fw[..], pn, t)[0]
    } else {
        a[0]
    };
    (ok && est.is_finite()).then_some(Cand { t, est, dd: None })
}

/// sign * S_j at the point t of the patch (grid `g`, degrees n), enclosed in `Ddi` (one
/// rounding outward at the end: one ulp wide, or a float).
fn tight_value<const N: usize>(
    g: &DdGrid<N>,
    n: [usize; 2],
    t: [f64; 2],
    rational: bool,
) -> Interval {
    value_of(&tight_jets::<N, 0>(g, n, t, rational), rational)
}

/// The `Ddi` enclosures of sign * A_j and w and their first derivatives at t:
/// `[[A, A_u, A_v], [w, w_u, w_v]]` (w = 1 for a polynomial patch).
fn tight_derivs<const N: usize>(
    g: &DdGrid<N>,
    n: [usize; 2],
    t: [f64; 2],
    rational: bool,
) -> [[Ddi; 3]; 2] {
    tight_jets::<N, 1>(g, n, t, rational)
}

/// [`tight_derivs`] with the derivatives up to `ORDER` (<= 1) computed, the others 0.
fn tight_jets<const N: usize, const ORDER: usize>(
    g: &DdGrid<N>,
    n: [usize; 2],
    t: [f64; 2],
    rational: bool,
) -> [[Ddi; 3]; 2] {
    let first = |x: [Ddi; 6]| [x[0], x[1], x[2]];
    let a = first(eval2::<Ddi, ORDER>(&g.a[..], n, t));
    let w = if rational {
        first(eval2::<Ddi, ORDER>(&g.w[..], n, t))
    } else {
        [Ddi::exact(1.0), Ddi::exact(0.0), Ddi::exact(0.0)]
    };
    [a, w]
}

/// c rounded to a multiple of 2^-30 inside the piece, and the interval (inari) enclosures
/// of A, w and their first derivatives there (as [`tight_derivs`]), if the value A / w comes
/// out a single float (exact).
#[allow(clippy::type_complexity)]
fn snapped<const N: usize>(
    g: &DdGrid<N>,
    n: [usize; 2],
    c: [f64; 2],
    pc: &Piece<N>,
) -> Option<([f64; 2], [[Interval; 3]; 2])> {
    let snap =
        |k: usize| ((c[k] * 1_073_741_824.0).round() / 1_073_741_824.0).clamp(pc.t[k].0, pc.t[k].1);
    let cs = [snap(0), snap(1)];
    let [a, w] = point_jets(g, n, cs, pc.rational, Ddi::to_interval);
    let val = a[0] / w[0];
    (val.inf() == val.sup() && val.sup().is_finite()).then_some((cs, [a, w]))
}

/// A `Ddi` coefficient as a midpoint-radius enclosure ([`Mr`]: rigorous, a few ulps wider
/// than inari's intervals and never exact, but without inari's change of the rounding mode
/// per operation), for [`point_jets`] where a few ulps do not matter.
fn mr_of(x: &Ddi) -> Mr {
    let i = x.to_interval();
    Mr::from_bounds(i.inf(), i.sup())
}

/// The enclosures of sign * A_j and w and their first derivatives at t, as [`tight_derivs`]
/// but in the verified number type S on the coefficients `of(c)` (enclosures of the grid's
/// `Ddi` coefficients c). With inari intervals on their hulls (`of` = `to_interval`): exact
/// on dyadic data at a short dyadic t, else a few ulps wide.
fn point_jets<S: Scalar + Copy, const N: usize>(
    g: &DdGrid<N>,
    n: [usize; 2],
    t: [f64; 2],
    rational: bool,
    of: impl Fn(&Ddi) -> S,
) -> [[Interval; 3]; 2] {
    let cnt = (n[0] + 1) * (n[1] + 1);
    let first = |x: [S; 6]| [0, 1, 2].map(|k| x[k].to_interval());
    let hull = |x: &[Ddi; N]| {
        let mut h = [S::zero(); N];
        for i in 0..cnt {
            h[i] = of(&x[i]);
        }
        h
    };
    let a = first(eval2::<S, 1>(&hull(&g.a)[..cnt], n, t));
    let w = if rational {
        first(eval2::<S, 1>(&hull(&g.w)[..cnt], n, t))
    } else {
        [iv::point(1.0), iv::point(0.0), iv::point(0.0)]
    };
    [a, w]
}

/// Whether the `Ddi` value A / w at a candidate is within 2^-70 (relative to the value or to
/// `scale`, the largest |coefficient|) of a float: only then can the value at a nearby short
/// dyadic point be a float, so only then is [`snapped`] (interval evaluation, the costlier
/// part of a candidate) tried. A filter for tightness only: soundness never depends on it.
fn near_float(d: &[[Ddi; 3]; 2], rational: bool, scale: f64) -> bool {
    let v = if rational { d[0][0] / d[1][0] } else { d[0][0] };
    let off = v.lo().abs() + v.rad();
    off.is_finite() && off <= f64::powi(2.0, -70) * v.hi().abs().max(scale)
}

/// Whether F looks like a ridge along the direction o other than d: its second differences
/// along d are all negative, and those along o and the mixed ones are negligible against
/// them (f64 estimates; the filter of [`Prover::ridge`], no soundness role: the proof takes
/// its curvature from [`Piece::curvature`]).
fn flat_across<const N: usize>(pc: &Piece<N>, f: &[f64; N], d: usize) -> bool {
    let [n0, n1] = pc.n;
    let (nd, no) = (pc.n[d], pc.n[1 - d]);
    if nd < 2 {
        return false;
    }
    let at = |r: usize, c: usize| f[r * (n1 + 1) + c];
    let second = |r: usize, c: usize, along: usize| {
        if along == 0 {
            (at(r + 2, c) - at(r + 1, c)) - (at(r + 1, c) - at(r, c))
        } else {
            (at(r, c + 2) - at(r, c + 1)) - (at(r, c + 1) - at(r, c))
        }
    };
    let fits = |r: usize, c: usize, along: usize| {
        if along == 0 {
            r + 2 <= n0
        } else {
            c + 2 <= n1
        }
    };
    // (separate passes, each ending early: most pieces fail the first one)
    let mut dd = f64::NEG_INFINITY;
    for r in 0..=n0 {
        for c in 0..=n1 {
            if fits(r, c, d) {
                dd = dd.max(second(r, c, d));
                if dd >= 0.0 {
                    return false;
                }
            }
        }
    }
    let limit = 1e-6 * (-dd) * (nd * (nd - 1)) as f64;
    let (ko, km) = ((no * no.saturating_sub(1)) as f64, (n0 * n1) as f64);
    for r in 0..=n0 {
        for c in 0..=n1 {
            let mut k = 0.0;
            if r < n0 && c < n1 {
                k += km * ((at(r + 1, c + 1) - at(r + 1, c)) - (at(r, c + 1) - at(r, c))).abs();
            }
            if fits(r, c, 1 - d) {
                k += ko * second(r, c, 1 - d).abs();
            }
            // (each term alone must be negligible; NaN fails)
            if k > limit || k.is_nan() {
                return false;
            }
        }
    }
    true
}

/// Whether the f64 Hessian of F at the piece's centre (coefficients `f`) is nearly singular,
/// det H >= -(H_uu^2 + 2 H_uv^2 + H_vv^2) / 20: the filter of [`Prover::ridge_line`] (on a
/// ridge H is rank one up to the distance from the ridge; no soundness role).
fn ridge_like<const N: usize>(pc: &Piece<N>, f: &[f64; N]) -> bool {
    let h = eval2::<f64, 2>(&f[..pc.count()], pc.n, [0.5, 0.5]);
    let (a, b, c) = (h[3], h[4], h[5]);
    a * c - b * b >= -(a * a + 2.0 * b * b + c * c) / 20.0
}

/// The Bernstein coefficients, over the range `range` of the other direction o, of the
/// iso-line functions F(c, .) and F_d(c, .) at x_d = c (F = A - ub w from the patch grid `g`
/// of degrees n, derivatives in the patch parameter), enclosed in `Ddi`: de Casteljau
/// along d at c (with the derivative, [`bern2`]) on every line of the grid, then
/// subdivision along o at the range's ends (exact parameters, the second one a `Ddi`
/// quotient: every result encloses the exact coefficients; `spline::bezier`).
/// (Generic over the number type: `Ddi`, or intervals, which stay exact on dyadic data at a
/// short dyadic c where `Ddi` always carries a radius.)
#[allow(clippy::type_complexity)]
fn iso_line<S: Scalar + Copy>(
    ga: &[S],
    gw: &[S],
    n: [usize; 2],
    d: usize,
    c: f64,
    ub: f64,
    range: (f64, f64),
) -> Option<(Vec<S>, Vec<S>)> {
    let (nd, no) = (n[d], n[1 - d]);
    let stride = n[1] + 1;
    let (tc, ub) = (S::from_f64(c), S::from_f64(ub));
    let mut fv = Vec::with_capacity(no + 1);
    let mut fd = Vec::with_capacity(no + 1);
    for k in 0..=no {
        let idx = |i: usize| {
            if d == 0 {
                i * stride + k
            } else {
                k * stride + i
            }
        };
        let mut ba = [S::zero(); MAX_DEGREE + 1];
        let mut bw = [S::zero(); MAX_DEGREE + 1];
        for i in 0..=nd {
            ba[i] = ga[idx(i)];
            bw[i] = gw[idx(i)];
        }
        let [va, da, _] = bern2::<S, 1>(&mut ba[..=nd], tc);
        let [vw, dw, _] = bern2::<S, 1>(&mut bw[..=nd], tc);
        fv.push(va - ub * vw);
        fd.push(da - ub * dw);
    }
    let (o0, o1) = range;
    let restrict = |mut x: Vec<S>| -> Vec<S> {
        if o1 < 1.0 {
            x = crate::spline::bezier::de_casteljau_split(&x, 1, &S::from_f64(o1)).0;
        }
        if o0 > 0.0 {
            let t = S::from_f64(o0) / S::from_f64(o1);
            x = crate::spline::bezier::de_casteljau_split(&x, 1, &t).1;
        }
        x
    };
    (o0 < o1).then(|| (restrict(fv), restrict(fd)))
}

/// The blossom values f(a^(n - i), b^i), i = 0..=n, of the Bernstein polynomial with
/// coefficients `x` (degree n = x.len() - 1): the Bernstein coefficients of f over the
/// parameter segment from a to b (a > b allowed: the reversed segment). By the blossoming
/// principle (Farin, *Curves and Surfaces for CAGD*, sec. on blossoms; Ramshaw 1989) the
/// blossom is de Casteljau's algorithm with one parameter per level, here n - i levels at a
/// and i at b: no split parameter (b - a) / (1 - a) to round, so in interval arithmetic on
/// dyadic data at short dyadic a, b the results are exact; for verified types each result
/// encloses the exact one (inclusion isotonicity).
fn blossom_ends<S: Scalar + Copy>(x: &[S], a: f64, b: f64) -> SmallVec<[S; MAX_DEGREE + 1]> {
    let n = x.len() - 1;
    let (ta, tb) = (S::from_f64(a), S::from_f64(b));
    (0..=n)
        .map(|i| {
            let mut c: SmallVec<[S; MAX_DEGREE + 1]> = x.iter().copied().collect();
            for lev in 1..=n {
                let t = if lev <= n - i { &ta } else { &tb };
                for k in 0..=n - lev {
                    c[k] = S::horner_step(&(c[k + 1] - c[k]), t, &c[k]);
                }
            }
            c[0]
        })
        .collect()
}

/// The Bernstein coefficients (degree n0 + n1) of the tensor Bernstein polynomial `c` (grid
/// of degrees n, row-major in u) restricted to the segment from (a0, a1) to (b0, b1) of the
/// patch: first the coefficients over the parameter box with those corners
/// ([`blossom_ends`] along both directions), on which the segment is the diagonal
/// s_u = s_v = s; then B_r^{n0}(s) B_c^{n1}(s) = [C(n0, r) C(n1, c) / C(n0 + n1, r + c)]
/// B_{r+c}^{n0+n1}(s) (the product of Bernstein polynomials; Farin, sec. on degree
/// elevation), so coefficient k is sum over r + c = k of C(n0, r) C(n1, c) b_rc divided by
/// C(n0 + n1, k) (a convex combination: the weights sum to 1 by Vandermonde's identity).
/// Integer weights and one division per coefficient: exact in interval arithmetic where the
/// quotient is a float (a ridge value 0).
fn segment_coefs<S: Scalar + Copy>(
    c: &[S],
    n: [usize; 2],
    a: [f64; 2],
    b: [f64; 2],
) -> SmallVec<[S; 2 * MAX_DEGREE + 1]> {
    let (n0, n1) = (n[0], n[1]);
    let mut rows: SmallVec<[SmallVec<[S; MAX_DEGREE + 1]>; MAX_DEGREE + 1]> = (0..=n0)
        .map(|r| blossom_ends(&c[r * (n1 + 1)..(r + 1) * (n1 + 1)], a[1], b[1]))
        .collect();
    for k in 0..=n1 {
        let col: SmallVec<[S; MAX_DEGREE + 1]> = rows.iter().map(|r| r[k]).collect();
        for (r, x) in blossom_ends(&col, a[0], b[0]).into_iter().enumerate() {
            rows[r][k] = x;
        }
    }
    // (C(n, k) for n <= 2 MAX_DEGREE: small integers, exact)
    let binom = |n: usize, k: usize| (0..k).fold(1usize, |x, i| x * (n - i) / (i + 1));
    (0..=n0 + n1)
        .map(|k| {
            let mut s = S::zero();
            for r in k.saturating_sub(n1)..=k.min(n0) {
                s = s + S::from_usize(binom(n0, r) * binom(n1, k - r)) * rows[r][k - r];
            }
            s / S::from_usize(binom(n0 + n1, k))
        })
        .collect()
}

/// The coefficients of F = A - ub w (patch grid `ga`, `gw` of degrees n) and of F_d (the
/// derivative along d in the patch parameter, degrees n with n_d one less: n_d times the
/// differences along d; Farin, derivatives of a Bézier patch) restricted to the segment from
/// `a` to `b` ([`segment_coefs`]); `None` if a degree along d is below 2.
#[allow(clippy::type_complexity)]
fn segment_lines<S: Scalar + Copy>(
    ga: &[S],
    gw: &[S],
    n: [usize; 2],
    d: usize,
    ub: f64,
    (a, b): ([f64; 2], [f64; 2]),
) -> Option<(
    SmallVec<[S; 2 * MAX_DEGREE + 1]>,
    SmallVec<[S; 2 * MAX_DEGREE + 1]>,
)> {
    if n[d] < 2 {
        return None;
    }
    let ubs = S::from_f64(ub);
    let cnt = (n[0] + 1) * (n[1] + 1);
    let f: SmallVec<[S; MAXN]> = (0..cnt).map(|i| ga[i] - ubs * gw[i]).collect();
    let mut m = n;
    m[d] -= 1;
    let nd = S::from_usize(n[d]);
    let fd: SmallVec<[S; MAXN]> = (0..=m[0])
        .flat_map(|r| (0..=m[1]).map(move |c| (r, c)))
        .map(|(r, c)| {
            let (r1, c1) = if d == 0 { (r + 1, c) } else { (r, c + 1) };
            nd * (f[r1 * (n[1] + 1) + c1] - f[r * (n[1] + 1) + c])
        })
        .collect();
    Some((segment_coefs(&f, n, a, b), segment_coefs(&fd, m, a, b)))
}

/// A / w enclosed.
fn value_of(d: &[[Ddi; 3]; 2], rational: bool) -> Interval {
    dd_value(d, rational).to_interval()
}

/// A / w in `Ddi`.
fn dd_value(d: &[[Ddi; 3]; 2], rational: bool) -> Ddi {
    if rational {
        d[0][0] / d[1][0]
    } else {
        d[0][0]
    }
}

/// The proof of F <= 0 on one patch; `ub` may rise (a concave piece's maximiser beats it),
/// which keeps every earlier proof valid (F = A - ub w only decreases as ub grows).
struct Prover<'a, const N: usize> {
    rational: bool,
    ub: f64,
    /// the best attained value found on the way
    lo: f64,
    /// the best strict witness found on the way ([`Ddi::strictly_below`])
    wit: f64,
    budget: &'a mut u32,
    /// proven boundary curves (0: u = 0, 1: u = 1, 2: v = 0, 3: v = 1)
    edges: [Option<bool>; 4],
    cands: &'a [Option<Cand>; 5],
    /// candidates found during the proof
    found: SmallVec<[Cand; 4]>,
    /// Newton searches left for them
    searches: u32,
    st: &'a mut Stats,
}

impl<const N: usize> Prover<'_, N> {
    /// F <= 0 on the piece `root` (the patch, `slot` 4, or its boundary curve `slot`).
    ///
    /// The pieces live in `pool` and never move: the open list holds their indices, a
    /// settled piece's slot is reused, and a split writes its halves straight into slots (a
    /// `Piece` is a few hundred bytes; moving pieces in and out of a work list was a quarter
    /// of the proof's cost).
    fn prove(&mut self, root: &Piece<N>, slot: usize, g: &DdGrid<N>) -> bool {
        let free = [root.n[0] > 0, root.n[1] > 0];
        let mut pool: SmallVec<[Piece<N>; 12]> = SmallVec::new();
        pool.push(*root);
        // (the open pieces' priorities kept beside their slots: the choice below reads no
        // piece)
        let mut open: SmallVec<[(f64, usize); 16]> = SmallVec::new();
        open.push((root.prio, 0));
        let mut spare: SmallVec<[usize; 16]> = SmallVec::new();
        // a free slot (a new one holds the root's fields and blank coefficients, weights 1
        // as every polynomial piece has them, until a split writes it: no copy of the
        // root's coefficients)
        let take = |pool: &mut SmallVec<[Piece<N>; 12]>, spare: &mut SmallVec<[usize; 16]>| {
            spare.pop().unwrap_or_else(|| {
                pool.push(Piece {
                    a: [0.0; N],
                    w: [1.0; N],
                    ..*root
                });
                pool.len() - 1
            })
        };
        // best first (the largest coefficient): the pieces around the maximum are refined
        // first, so `ub` reaches it before the others are judged against it
        while let Some(k) = {
            let best = (0..open.len()).max_by(|&x, &y| open[x].0.total_cmp(&open[y].0));
            best.map(|i| open.swap_remove(i).1)
        } {
            if *self.budget == 0 {
                return false;
            }
            *self.budget -= 1;
            self.st.subdivisions += 1;
            match self.settle(&pool[k], root, slot, g, free) {
                None => return false,
                Some(true) => {
                    spare.push(k);
                    continue;
                }
                Some(false) => {}
            }
            let depth = pool[k].depth;
            if depth >= MAX_DEPTH {
                return false;
            }
            // the children, split straight into their slots
            let kids: SmallVec<[usize; 4]> = match free {
                [true, true] => {
                    // u halves into a, b; then a's v halves into k (free again) and c, b's
                    // into a (free again) and d
                    let (a, b) = (take(&mut pool, &mut spare), take(&mut pool, &mut spare));
                    let [x, l, r] = pool.get_disjoint_mut([k, a, b]).expect("distinct slots");
                    x.split_into(0, 0.5, 0.0, l, r);
                    let c = take(&mut pool, &mut spare);
                    let [x, l, r] = pool.get_disjoint_mut([a, k, c]).expect("distinct slots");
                    x.split_into(1, 0.5, 0.0, l, r);
                    let d = take(&mut pool, &mut spare);
                    let [x, l, r] = pool.get_disjoint_mut([b, a, d]).expect("distinct slots");
                    x.split_into(1, 0.5, 0.0, l, r);
                    spare.push(b);
                    [k, c, a, d].into_iter().collect()
                }
                _ => {
                    let dir = if free[0] { 0 } else { 1 };
                    let (a, b) = (take(&mut pool, &mut spare), take(&mut pool, &mut spare));
                    let [x, l, r] = pool.get_disjoint_mut([k, a, b]).expect("distinct slots");
                    x.split_into(dir, 0.5, 0.0, l, r);
                    spare.push(k);
                    [a, b].into_iter().collect()
                }
            };
            for i in kids {
                pool[i].depth = depth + 1;
                // A child that its coefficients already prove (most of them) is settled here,
                // as `settle` would first (the same tests; `ub` only grows, so a child
                // excluded now would be excluded when chosen later), counted as one step of
                // the budget; the others wait in the open list.
                let mut buf = [0.0f64; N];
                let done = *self.budget > 0
                    && pool[i]
                        .f_values(self.ub, &mut buf)
                        .is_some_and(|(f, e)| pool[i].excluded(f, e, self.ub));
                if done {
                    *self.budget -= 1;
                    self.st.subdivisions += 1;
                    spare.push(i);
                } else {
                    open.push((pool[i].prio, i));
                }
            }
        }
        true
    }

    /// One piece of [`Prover::prove`]: `Some(true)` if F <= 0 on it is proven (coefficients,
    /// monotone towards a proven side, concave, ridge), `Some(false)` if it is to be split,
    /// `None` if the proof fails (coefficients not finite).
    fn settle(
        &mut self,
        pc: &Piece<N>,
        root: &Piece<N>,
        slot: usize,
        g: &DdGrid<N>,
        free: [bool; 2],
    ) -> Option<bool> {
        let mut buf = [0.0f64; N];
        // (the ub of f: a curvature bound from f holds for F = A - ub_f w only)
        let ub_f = self.ub;
        let (f, e) = pc.f_values(ub_f, &mut buf)?;
        if pc.excluded(f, e, self.ub) {
            return Some(true);
        }
        // monotone towards the sides of the patch the piece touches (the ranges are exact
        // at the patch sides)
        let mut mono = [[false; 2]; 2];
        for d in (0..2).filter(|&d| free[d]) {
            mono[d][0] = pc.t[d].0 == 0.0 && pc.monotone(f, e, d, true);
            mono[d][1] = pc.t[d].1 == 1.0 && pc.monotone(f, e, d, false);
        }
        // Monotone along both directions, towards sides s_u and s_v: for x in the piece,
        // F(x) <= F(x on s_u) <= F(the corner of s_u and s_v), a patch corner, <= ub (a
        // candidate): no boundary curve to prove.
        if mono[0].contains(&true) && mono[1].contains(&true) {
            return Some(true);
        }
        for d in (0..2).filter(|&d| free[d]) {
            for (end, down) in [(0usize, true), (1, false)] {
                if mono[d][end] {
                    // a boundary curve's sides are patch corners (<= ub: candidates)
                    let ub0 = self.ub;
                    let mut done = slot < 4 || self.edge(root, 2 * d + end, g);
                    // (the edge proof may raise ub; for a rational patch F = A - ub w
                    // then changes shape, so its monotonicity is checked again)
                    if done && self.ub != ub0 && self.rational {
                        let mut b2 = [0.0f64; N];
                        done = pc
                            .f_values(self.ub, &mut b2)
                            .is_some_and(|(f2, e2)| pc.monotone(f2, e2, d, down));
                    }
                    if done {
                        return Some(true);
                    }
                }
            }
        }
        // (the second differences once: a ridge along d needs them all < 0 along d, as
        // [`Piece::curvature`] checks, so without such a direction it is not tried)
        let sm = pc.second_maxima(f);
        if let Some(mu) = pc.concavity_from(f, e, sm) {
            if self.concave(pc, root, slot, (mu, ub_f), g) {
                return Some(true);
            }
        } else if sm.iter().any(Option::is_some) && self.ridge(pc, root, (f, e, ub_f), g, sm) {
            return Some(true);
        } else if pc.depth >= 2 && self.searches > 0 && pc.max_coef() > self.ub {
            // a maximum the first candidates missed: Newton from this piece's centre
            self.searches -= 1;
            if let Some(c) = newton_from(root, self.rational, pc.argmax_point()) {
                self.attain_at(g, pc, c.t);
                self.found.push(c);
            }
        }
        Some(false)
    }

    /// F <= 0 on boundary curve e of the patch (cached).
    fn edge(&mut self, root: &Piece<N>, e: usize, g: &DdGrid<N>) -> bool {
        if let Some(ok) = self.edges[e] {
            return ok;
        }
        let ok = self.edge_segment(root, e, g) || self.prove(&root.edge(e), e, &g.edge(e, root.n));
        self.edges[e] = Some(ok);
        ok
    }

    /// F <= 0 on boundary curve e of a polynomial patch of degree 2 or 3 along it, by the
    /// curve side's root-isolating proof ([`crate::enclose::raw_sides`]: proven signs of the
    /// derivative at test points around its f64 roots, a Taylor bound over each bracket, all
    /// on the curve's `Ddi` coefficients, the patch grid's boundary row): its proven maximum
    /// of sign * S_j is <= ub, so F = sign * S_j - ub <= 0 there. Its attained value is one of
    /// the surface (continuous: no jump knot, see [`FastSurface::new`]). `false` where that
    /// proof does not apply or does not reach `ub`; then the general procedure runs.
    fn edge_segment(&mut self, root: &Piece<N>, e: usize, g: &DdGrid<N>) -> bool {
        let len = if e < 2 { root.n[1] + 1 } else { root.n[0] + 1 };
        if self.rational || !(3..=4).contains(&len) {
            return false;
        }
        let c: [Ddi; 4] = std::array::from_fn(|k| g.a[edge_index(e, root.n, k.min(len - 1))]);
        let seg = crate::enclose::Segment {
            c: &c[..len],
            a: 0.0,
            b: 1.0,
            end_kinds: [crate::enclose::CandidateKind::EndPoint; 2],
            right_attained: true,
        };
        let Some([mx, _]) = crate::enclose::raw_sides(&seg, [true, false]) else {
            return false;
        };
        self.lo = self.lo.max(mx.attained);
        mx.upper <= self.ub
    }

    /// F <= 0 on a piece P where -H >= mu I (mu in the piece's own parameters): for any c in
    /// P, Taylor's formula with the integral remainder gives, for x in P (convex),
    /// F(x) <= F(c) + g (x - c) - mu_t |x - c|^2 / 2 with g = grad F(c) and mu_t = mu / W^2
    /// (W the piece's width in the patch parameters, the same in both directions: pieces are
    /// halved in both). The right side is separable: per free direction k the maximum of
    /// g_k d - mu_t d^2 / 2 over d in [lo_k - c_k, hi_k - c_k] is 0 if g_k has the sign that
    /// points out of the box at d = 0's side... in general it is at most g_k^2 / (2 mu_t), and
    /// it is the value at the end d_e when g_k / mu_t lies beyond d_e (the parabola still
    /// rises there); with d >= 0 and d <= 0 taken separately, each with the extreme g_k of
    /// that sign. c is an f64 estimate of the maximiser of S over P (box-constrained Newton,
    /// [`constrained_max`]), so near the maximum the terms are at the rounding level and the
    /// bound is F(c) + ~2^-100; F(c), g are `Ddi` enclosures. If S(c) beats `ub`, `ub` is
    /// raised to it first (and `lo` records the attained value). (`mu` holds for
    /// F = A - ub0 w, ub0 the ub the piece's coefficients were computed with; after a raise
    /// of ub it is computed again, [`Prover::mu_after_raise`].)
    fn concave(
        &mut self,
        pc: &Piece<N>,
        root: &Piece<N>,
        slot: usize,
        (mu, ub0): (f64, f64),
        g: &DdGrid<N>,
    ) -> bool {
        let inside = |c: &Cand| (0..2).all(|k| pc.t[k].0 <= c.t[k] && c.t[k] <= pc.t[k].1);
        let seed = self.cands[slot]
            .iter()
            .chain(self.found.iter())
            .find(|c| inside(c))
            .copied();
        let (c, est) = constrained_max(pc, root, self.rational, seed.map(|c| c.t));
        self.st.newton_iterations += 1;
        let pn = pc.full;
        let free = [pc.n[0] > 0, pc.n[1] > 0];
        let wd = (0..2)
            .filter(|&k| free[k])
            .map(|k| iv::point(pc.t[k].1) - iv::point(pc.t[k].0))
            .fold(Interval::EMPTY, |x, y| x.convex_hull(y));
        // f64 pre-check (no soundness role): skip the `Ddi` work where the bound would
        // clearly fail (a point below ub whose quadratic bound clearly exceeds it). As in
        // [`Prover::bound`], a direction where c sits on a side of the piece with the
        // gradient pointing out of it adds nothing (the parabola falls into the piece): a
        // concave piece beside the maximum, whose maximum is on its side, is proven here
        // instead of being halved again.
        let clear = {
            let w2 = wd.sup() * wd.sup();
            let q: f64 = (0..2)
                .filter(|&k| free[k])
                .map(|k| {
                    let g = est[1 + k];
                    if (c[k] >= pc.t[k].1 && g > 0.0) || (c[k] <= pc.t[k].0 && g < 0.0) {
                        0.0
                    } else {
                        g / mu * g * w2 * 0.5
                    }
                })
                .sum();
            let scale = self.ub.abs().max(est[0].abs());
            if est[0] <= self.ub && est[0] - self.ub + q > 1e-12 * scale {
                return false;
            }
            // (the bound clearly holds: a margin far above the rounding of f64 intervals)
            est[0] - self.ub + q < -1e-9 * scale
        };
        // (the candidate's own enclosures when c did not move)
        let [a, w] = match seed.and_then(|s| s.dd.filter(|_| s.t == c)) {
            Some(dd) => dd,
            None => {
                // Where the bound clearly holds (a piece beside the maximum), midpoint-radius
                // interval arithmetic at c is tight enough and costs a fraction of `Ddi`; the
                // same bound, from enclosures of F(c) and grad F(c) as below.
                if clear {
                    let [ai, wi] = point_jets(g, pn, c, self.rational, mr_of);
                    let ub = iv::point(self.ub);
                    // (w = 1, w_u = w_v = 0 for a polynomial patch: the same enclosures
                    // without the interval operations that would give them exactly)
                    let (val, fc, gr) = if self.rational {
                        (
                            ai[0] / wi[0],
                            ai[0] - ub * wi[0],
                            [1, 2].map(|k| ai[k] - ub * wi[k]),
                        )
                    } else {
                        (ai[0], ai[0] - ub, [ai[1], ai[2]])
                    };
                    if !val.is_empty() {
                        self.lo = self.lo.max(val.inf());
                    }
                    if self
                        .mu_after_raise(pc, mu, ub0, None)
                        .is_some_and(|mu| self.bound(pc, c.map(iv::point), mu, wd, fc, gr, free))
                    {
                        return true;
                    }
                }
                tight_derivs(g, pn, c, self.rational)
            }
        };
        let vd = dd_value(&[a, w], self.rational);
        self.wit = self.wit.max(vd.strictly_below());
        let val = vd.to_interval();
        if val.is_empty() || !val.sup().is_finite() {
            return false;
        }
        self.lo = self.lo.max(val.inf());
        // (raised only past a value provably above it: an enclosure that merely reaches above
        // it is left to the bound, so an exact float maximum keeps its exact bound)
        if val.inf() > self.ub {
            self.ub = val.sup();
        }
        let ub = Ddi::exact(self.ub);
        let fc = (a[0] - ub * w[0]).to_interval();
        let gr = [1, 2].map(|k| (a[k] - ub * w[k]).to_interval());
        let Some(mu) = self.mu_after_raise(pc, mu, ub0, None) else {
            return false;
        };
        if self.bound(pc, c.map(iv::point), mu, wd, fc, gr, free) {
            return true;
        }
        // A maximum that is a float at a short dyadic point (a bump's top at t = 1/2): there
        // interval arithmetic can be exact, F(c) = 0 and g = 0, where `Ddi` always carries a
        // radius.
        if !near_float(&[a, w], self.rational, pc.max_abs()) {
            return false;
        }
        let Some((cs, [ai, wi])) = snapped(g, pn, c, pc) else {
            return false;
        };
        let v = (ai[0] / wi[0]).sup();
        self.lo = self.lo.max(v);
        self.ub = self.ub.max(v);
        let ub = iv::point(self.ub);
        let fc = ai[0] - ub * wi[0];
        let gr = [1, 2].map(|k| ai[k] - ub * wi[k]);
        let Some(mu) = self.mu_after_raise(pc, mu, ub0, None) else {
            return false;
        };
        self.bound(pc, cs.map(iv::point), mu, wd, fc, gr, free)
    }

    /// The curvature bound mu of a piece (of F = A - ub0 w: [`Piece::concavity`], or
    /// [`Piece::curvature`] along `dir`) valid for the current `ub`: unchanged for a
    /// polynomial patch (F'' = S'' does not depend on ub) or if ub did not move; else
    /// computed again, since F'' = A'' - ub w'' changes with ub.
    fn mu_after_raise(&self, pc: &Piece<N>, mu: f64, ub0: f64, dir: Option<usize>) -> Option<f64> {
        if !self.rational || self.ub == ub0 {
            return Some(mu);
        }
        let mut buf = [0.0f64; N];
        let (f, e) = pc.f_values(self.ub, &mut buf)?;
        match dir {
            None => pc.concavity(f, e),
            Some(d) => pc.curvature(f, e, d),
        }
    }

    /// F <= 0 on a 2-D piece where F is strictly concave along one direction d only: a
    /// ridge, where S_j is constant (or nearly so) along the other direction o, so that no
    /// piece across it is strictly concave in both directions and [`Prover::concave`] never
    /// applies. Tried only where the curvature along o and the mixed one are negligible
    /// against the curvature along d (a filter, no soundness role).
    ///
    /// For x in the piece and c_d in its d range, F_dd <= -mu_t on the segment from
    /// (c_d, x_o) to x (the piece is a box), so Taylor's formula with the integral
    /// remainder gives F(x) <= F(c_d, x_o) + F_d(c_d, x_o) (x_d - c_d) - mu_t (x_d - c_d)^2 / 2
    /// (mu_t = mu / W_d^2 in the patch parameter). The iso-line functions F(c_d, .) and
    /// F_d(c_d, .) are polynomials in x_o whose Bernstein coefficients over the piece's o
    /// range are enclosed in `Ddi` ([`iso_line`]: de Casteljau along d at c_d on every line
    /// of the patch grid, then de Casteljau subdivision along o at exact parameters); their
    /// hulls bound F(c_d, x_o) from above and F_d(c_d, x_o) on both sides, and the separable
    /// maximum over x_d is that of [`Prover::bound`] with d the only free direction. On an
    /// exact ridge the iso-line coefficients are all the ridge value, so the bound is the
    /// ridge value plus the rounding of its enclosure. c_d is an f64 maximiser of S along d at
    /// the middle of the o range (any c_d in the range is valid); its value is attained and
    /// raises `ub` when it provably beats it. (`f`, `e` are the piece's coefficients of
    /// F = A - ub0 w; after a raise of ub the curvature is computed again,
    /// [`Prover::mu_after_raise`]; `sm` their [`Piece::second_maxima`]: a direction d
    /// without them has a second difference >= 0 along d, where the curvature fails.)
    fn ridge(
        &mut self,
        pc: &Piece<N>,
        root: &Piece<N>,
        (f, e, ub0): (&[f64; N], f64, f64),
        g: &DdGrid<N>,
        sm: [Option<f64>; 2],
    ) -> bool {
        if pc.n[0] == 0 || pc.n[1] == 0 || root.n != pc.full {
            return false;
        }
        let mus: [Option<f64>; 2] =
            std::array::from_fn(|d| sm[d].and_then(|_| pc.curvature(f, e, d)));
        // along a parameter line first (cheaper), then along a chord where the piece looks
        // like a ridge (a filter, no soundness role: the f64 Hessian at the piece's centre is
        // nearly singular, det H >= -|H|^2 / 20; a saddle piece of a random patch is not, and
        // the chord's set-up would cost more than the halving that settles it)
        (0..2).any(|d| {
            mus[d]
                .is_some_and(|mu| flat_across(pc, f, d) && self.ridge_axis(pc, root, d, mu, ub0, g))
        }) || (mus.iter().any(Option::is_some) && ridge_like(pc, f))
            && (0..2).any(|d| mus[d].is_some_and(|mu| self.ridge_line(pc, root, d, mu, ub0, g)))
    }

    /// A value the surface attains at the patch parameter t (`tight_value`, double double):
    /// its lower end raises the attained value `lo`, and it raises `ub` when it provably
    /// exceeds it. `false`, with nothing recorded, for an empty or unbounded enclosure.
    fn attain_at(&mut self, g: &DdGrid<N>, pc: &Piece<N>, t: [f64; 2]) -> bool {
        let val = tight_value(g, pc.full, t, self.rational);
        if val.is_empty() || !val.sup().is_finite() {
            return false;
        }
        self.lo = self.lo.max(val.inf());
        if val.inf() > self.ub {
            self.ub = val.sup();
        }
        true
    }

    /// [`Prover::ridge`] along the parameter direction o other than d (curvature `mu` along
    /// d for F = A - ub0 w).
    fn ridge_axis(
        &mut self,
        pc: &Piece<N>,
        root: &Piece<N>,
        d: usize,
        mu: f64,
        ub0: f64,
        g: &DdGrid<N>,
    ) -> bool {
        self.st.newton_iterations += 1;
        let o = 1 - d;
        let mid = |k: usize| 0.5 * pc.t[k].0 + 0.5 * pc.t[k].1;
        let t = max_along(root, d, [mid(0), mid(1)], pc.t[d]);
        if !self.attain_at(g, pc, t) {
            return false;
        }
        let cnt = (pc.full[0] + 1) * (pc.full[1] + 1);
        let lines = iso_line(&g.a[..cnt], &g.w[..cnt], pc.full, d, t[d], self.ub, pc.t[o]);
        let Some(mu) = self.mu_after_raise(pc, mu, ub0, Some(d)) else {
            return false;
        };
        if self.ridge_bound(pc, t, d, mu, lines) {
            return true;
        }
        // a ridge value that is a float (a short dyadic c_d on dyadic data): interval
        // arithmetic can be exact there, where `Ddi` always carries a radius
        let dd = tight_derivs(g, pc.full, t, self.rational);
        if !near_float(&dd, self.rational, pc.max_abs()) {
            return false;
        }
        let Some((cs, [ai, wi])) = snapped(g, pc.full, t, pc) else {
            return false;
        };
        let v = (ai[0] / wi[0]).sup();
        self.lo = self.lo.max(v);
        self.ub = self.ub.max(v);
        let (ga, gw) = g.hulls(cnt);
        let lines = iso_line(&ga, &gw, pc.full, d, cs[d], self.ub, pc.t[o]);
        let Some(mu) = self.mu_after_raise(pc, mu, ub0, Some(d)) else {
            return false;
        };
        self.ridge_bound(pc, cs, d, mu, lines)
    }

    /// The bound of [`Prover::ridge`] from the iso-line coefficients `lines` (F(c_d, .) and
    /// F_d(c_d, .) over the piece's o range) at c: whether it is <= 0 ([`Prover::line_bound`]
    /// with the chord the iso-line itself).
    fn ridge_bound<S: Scalar>(
        &self,
        pc: &Piece<N>,
        c: [f64; 2],
        d: usize,
        mu: f64,
        lines: Option<(Vec<S>, Vec<S>)>,
    ) -> bool {
        lines.is_some_and(|(fv, fd)| self.line_bound(pc, d, mu, (c[d], c[d]), &fv, &fd))
    }

    /// F <= 0 on a 2-D piece crossed by a ridge that is not along a parameter line (a
    /// diagonal or rotated line, a curve): F is strictly concave along one parameter
    /// direction d on the piece, -F_dd >= mu_t (mu_t = mu / W_d^2 in the patch parameter,
    /// [`Piece::curvature`]), and nothing is assumed along the other direction o.
    ///
    /// Take the segment L from a = (a_d, o_lo) to b = (b_d, o_hi) with a_d, b_d in the
    /// piece's d range (f64 maximisers of S along d on the piece's two o sides,
    /// [`max_along`]: on a straight ridge L is the ridge up to rounding). Every x of the
    /// piece has the point l = L(s) with l_o = x_o (L spans the o range), and the segment from
    /// l to x runs along d inside the piece (a box, l_d between a_d and b_d). Taylor's formula
    /// with the integral remainder along it gives
    /// F(x) <= F(l) + F_d(l) (x_d - l_d) - mu_t (x_d - l_d)^2 / 2 <= F(l) + F_d(l)^2 / (2 mu_t)
    /// (the maximum of the parabola over all x_d). So F <= max_L F + max_L |F_d|^2 / (2 mu_t)
    /// on the piece, with both maxima bounded by the Bernstein coefficients of F and F_d
    /// restricted to L ([`segment_lines`], convex hull property), enclosed in `Ddi` (or in
    /// intervals on the patch grid's hulls: exact on dyadic data with a float ridge value at
    /// dyadic ends). On a straight ridge F_d = 0 on L up to rounding and F <= the ridge value
    /// up to rounding; on a curved ridge the chord leaves the ridge by O(W^2), the excess is
    /// O(W^4) and the piece is halved until it is below the rounding. (Not in the thesis; the
    /// Taylor bound as in [`Prover::ridge`], along a chord instead of a parameter line.)
    fn ridge_line(
        &mut self,
        pc: &Piece<N>,
        root: &Piece<N>,
        d: usize,
        mu: f64,
        ub0: f64,
        g: &DdGrid<N>,
    ) -> bool {
        let o = 1 - d;
        let (lo, hi) = pc.t[d];
        // the ridge's d position on the piece's two o sides, not clamped to the piece
        // (the piece's d range widened by its width on both sides)
        let w = hi - lo;
        let ridge_at = |x_o: f64| {
            let mut t = [0.0; 2];
            (t[d], t[o]) = (0.5 * lo + 0.5 * hi, x_o);
            max_along(root, d, t, (lo - w, hi + w))[d]
        };
        let (o0, o1) = pc.t[o];
        let (r0, r1) = (ridge_at(o0), ridge_at(o1));
        self.st.newton_iterations += 1;
        // The o range cut where the line through the two ridge points crosses a d side of
        // the piece: on each part the chord is that line clamped into the piece (inside,
        // or along the side the ridge lies beyond). Any cut points and any chord ends in
        // the piece give a valid bound; these make it tight.
        let mut cuts: SmallVec<[f64; 4]> = SmallVec::new();
        cuts.push(o0);
        if r1 != r0 {
            for side in [lo, hi] {
                let s = o0 + (side - r0) / (r1 - r0) * (o1 - o0);
                if s > o0 && s < o1 {
                    cuts.push(s);
                }
            }
        }
        cuts.push(o1);
        cuts.sort_by(f64::total_cmp);
        let at = |x_o: f64| {
            let x_d = if r1 == r0 {
                r0
            } else {
                r0 + (x_o - o0) / (o1 - o0) * (r1 - r0)
            };
            let mut t = [0.0; 2];
            (t[d], t[o]) = (if x_d.is_nan() { lo } else { x_d.clamp(lo, hi) }, x_o);
            t
        };
        let parts: SmallVec<[([f64; 2], [f64; 2]); 3]> =
            cuts.windows(2).map(|c| (at(c[0]), at(c[1]))).collect();
        // f64 pre-check (no soundness role): skip the verified work where the bound
        // clearly fails
        let scale = self.ub.abs().max(pc.max_abs());
        let cnt = (pc.full[0] + 1) * (pc.full[1] + 1);
        let clear = parts.iter().all(|&ends| {
            segment_lines::<f64>(&root.a[..cnt], &root.w[..cnt], pc.full, d, self.ub, ends)
                .is_some_and(|(fv, fd)| {
                    let gm = fd.iter().fold(0.0f64, |m, x| m.max(x.abs()));
                    let fm = fv.iter().fold(f64::NEG_INFINITY, |m, &x| m.max(x));
                    // (the unconstrained parabola: an over-estimate of the bound below)
                    fm + gm * gm * w * w / (2.0 * mu) <= 1e-12 * scale || fm <= 1e-12 * scale
                })
        });
        if !clear {
            return false;
        }
        // the value at a ridge point is attained (and raises ub when it provably beats it)
        if !self.attain_at(g, pc, parts[0].0) {
            return false;
        }
        let Some(mu) = self.mu_after_raise(pc, mu, ub0, Some(d)) else {
            return false;
        };
        parts
            .iter()
            .all(|&ends| self.chord_bound(pc, d, mu, ends, g))
    }

    /// F <= 0 on the slab of the piece over the o range of the chord `ends` (points of the
    /// piece), F_dd <= -mu / W_d^2 on the piece: [`Prover::line_bound`] on the coefficients of
    /// F and F_d along the chord in `Ddi`, then (a float ridge value on dyadic data) in
    /// interval arithmetic on the hulls of the grid's coefficients, which can be exact where
    /// `Ddi` always carries a radius.
    fn chord_bound(
        &self,
        pc: &Piece<N>,
        d: usize,
        mu: f64,
        ends: ([f64; 2], [f64; 2]),
        g: &DdGrid<N>,
    ) -> bool {
        let cnt = (pc.full[0] + 1) * (pc.full[1] + 1);
        let cd = (ends.0[d], ends.1[d]);
        segment_lines(&g.a[..cnt], &g.w[..cnt], pc.full, d, self.ub, ends)
            .is_some_and(|(fv, fd)| self.line_bound(pc, d, mu, cd, &fv, &fd))
            || {
                let (ga, gw) = g.hulls(cnt);
                segment_lines(&ga, &gw, pc.full, d, self.ub, ends)
                    .is_some_and(|(fv, fd)| self.line_bound(pc, d, mu, cd, &fv, &fd))
            }
    }

    /// The bound of [`Prover::ridge_line`] on the slab of the piece over the o range of the
    /// chord `ends`, from the coefficients of F and F_d on the chord: [`Prover::bound`] along
    /// d with the expansion point anywhere between the chord's d ends, F(l) <= max F and
    /// F_d(l) in the hull of the F_d coefficients, over the slab's x_d (the whole d range of
    /// the piece): whether it is <= 0, rounding included.
    #[allow(clippy::type_complexity)]
    fn line_bound<S: Scalar>(
        &self,
        pc: &Piece<N>,
        d: usize,
        mu: f64,
        ends: (f64, f64),
        fv: &[S],
        fd: &[S],
    ) -> bool {
        let hull = |c: &[S]| {
            c.iter()
                .map(|x| x.to_interval())
                .fold(Interval::EMPTY, |h, x| h.convex_hull(x))
        };
        let (fh, gh) = (hull(fv), hull(fd));
        if fh.is_empty() || !fh.sup().is_finite() || !gh.is_common_interval() {
            return false;
        }
        let wd = iv::point(pc.t[d].1) - iv::point(pc.t[d].0);
        let mut c = [Interval::EMPTY; 2];
        c[d] = iv::point(ends.0).convex_hull(iv::point(ends.1));
        let mut gr = [Interval::EMPTY; 2];
        gr[d] = gh;
        let mut free = [false; 2];
        free[d] = true;
        self.bound(pc, c, mu, wd, iv::point(fh.sup()), gr, free)
    }

    /// The bound of [`Prover::concave`] at c from F(c) and grad F(c) (enclosures), mu and
    /// the piece width `wd`, over the directions `free`: whether it is <= 0. (`c[k]` may be
    /// an interval: the bound then holds for expansion points anywhere in it, as
    /// [`Prover::ridge_line`] needs; the distances to the piece's sides are enclosed over it.)
    #[allow(clippy::too_many_arguments)]
    fn bound(
        &self,
        pc: &Piece<N>,
        c: [Interval; 2],
        mu: f64,
        wd: Interval,
        fc: Interval,
        gr: [Interval; 2],
        free: [bool; 2],
    ) -> bool {
        let mut_ = iv::point(mu) / wd.sqr();
        let half = iv::point(0.5);
        let mut bound = fc;
        for k in (0..2).filter(|&k| free[k]) {
            let g = gr[k];
            let dlo = iv::point(pc.t[k].0) - c[k];
            let dhi = iv::point(pc.t[k].1) - c[k];
            // max over d in [0, dhi] with g_hi, over d in [dlo, 0] with g_lo
            let side = |gx: f64, de: Interval, up_side: bool| -> f64 {
                let gi = iv::point(gx);
                if (up_side && gx <= 0.0) || (!up_side && gx >= 0.0) {
                    return 0.0;
                }
                let beyond = if up_side {
                    (gi / mut_).inf() >= de.sup()
                } else {
                    (gi / mut_).sup() <= de.inf()
                };
                if beyond {
                    // the parabola still rises at the end: its value there (max over the
                    // enclosure of the end)
                    (gi * de - half * mut_ * de.sqr()).sup()
                } else {
                    (gi / mut_ * gi * half).sup()
                }
            };
            let phi = side(g.sup(), dhi, true).max(side(g.inf(), dlo, false));
            bound += iv::point(phi);
        }
        bound.sup() <= 0.0
    }
}

/// An f64 estimate of the maximiser of sign * S_j along direction d through t, in `range`
/// (Newton iterations on S_d, clamped; the patch polynomial extends beyond [0, 1]). Only an estimate: the proofs that use
/// it ([`Prover::ridge`], [`Prover::ridge_line`]) hold for any point of the range.
fn max_along<const N: usize>(
    root: &Piece<N>,
    d: usize,
    mut t: [f64; 2],
    range: (f64, f64),
) -> [f64; 2] {
    for _ in 0..16 {
        let a = eval2::<f64, 2>(&root.a[..], root.n, t);
        let dv = if root.rational {
            quotient(a, eval2::<f64, 2>(&root.w[..], root.n, t))
        } else {
            a
        };
        let (g1, g2) = (dv[1 + d], dv[3 + 2 * d]);
        if g2 >= 0.0 || g2.is_nan() {
            break;
        }
        let nt = (t[d] - g1 / g2).clamp(range.0, range.1);
        if !nt.is_finite() {
            break;
        }
        let moved = (nt - t[d]).abs() > 4.0 * f64::EPSILON;
        t[d] = nt;
        if !moved {
            break;
        }
    }
    t
}

/// An f64 estimate of the maximiser of sign * S_j over the piece: Newton iterations on the
/// free directions, clamped to the piece, with a direction fixed at a side where the
/// gradient points out of the piece (box-constrained Newton). Only an estimate: any point of
/// the piece gives a valid bound in [`Prover::concave`].
fn constrained_max<const N: usize>(
    pc: &Piece<N>,
    root: &Piece<N>,
    rational: bool,
    seed: Option<[f64; 2]>,
) -> ([f64; 2], [f64; 3]) {
    let (pn, fa, fw) = (root.n, &root.a, &root.w);
    let mid = |k: usize| 0.5 * pc.t[k].0 + 0.5 * pc.t[k].1;
    let mut t = seed.unwrap_or([mid(0), mid(1)]);
    let free = [pc.n[0] > 0, pc.n[1] > 0];
    let mut est = [f64::NAN; 3];
    for _ in 0..12 {
        let a = eval2::<f64, 2>(&fa[..], pn, t);
        let d = if rational {
            quotient(a, eval2::<f64, 2>(&fw[..], pn, t))
        } else {
            a
        };
        est = [d[0], d[1], d[2]];
        let gr = [d[1], d[2]];
        let mut act = free;
        for k in 0..2 {
            if free[k] && ((t[k] <= pc.t[k].0 && gr[k] < 0.0) || (t[k] >= pc.t[k].1 && gr[k] > 0.0))
            {
                act[k] = false;
            }
        }
        let step = match act {
            [true, true] => {
                let det = d[3] * d[5] - d[4] * d[4];
                [
                    -(d[5] * gr[0] - d[4] * gr[1]) / det,
                    -(d[3] * gr[1] - d[4] * gr[0]) / det,
                ]
            }
            [true, false] => [-gr[0] / d[3], 0.0],
            [false, true] => [0.0, -gr[1] / d[5]],
            [false, false] => break,
        };
        if !step.iter().all(|x| x.is_finite()) {
            break;
        }
        let mut moved = false;
        for k in 0..2 {
            if act[k] {
                let nt = (t[k] + step[k]).clamp(pc.t[k].0, pc.t[k].1);
                moved |= (nt - t[k]).abs() > 4.0 * f64::EPSILON;
                t[k] = nt;
            }
        }
        if !moved {
            break;
        }
    }
    for (k, x) in t.iter_mut().enumerate() {
        *x = x.clamp(pc.t[k].0, pc.t[k].1);
    }
    (t, est)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::surface::gen::{families, random_surface};
    use crate::surface::SurfaceEncloser;

    /// Every proven side against dense verified samples (outer) and the `newton` strategy's
    /// outer box (inner bounds are attained, so they lie inside every verified box).
    fn check(s: &NurbsSurface, tally: &mut [u64; 3]) {
        let Some(f) = FastSurface::new(s) else {
            return;
        };
        let newton = crate::surface::enclose::SurfaceNewton {
            fast_path: false,
            ..Default::default()
        }
        .enclose(s);
        let ((a, b), (c, d)) = s.domain();
        for j in 0..s.dim() {
            for sign in [1.0, -1.0] {
                let mut st = Stats::default();
                let r = f.side(j, sign, &mut st);
                tally[0] += st.fast_exits;
                tally[1] += st.fast_proofs;
                tally[2] += st.fast_fallbacks;
                let Some((ub, at, wit)) = r else { continue };
                assert!(at <= ub && wit <= ub, "{at} {wit} {ub}");
                let cb = &newton.coords[j];
                let (nlo, nhi) = if sign > 0.0 {
                    (cb.inner_hi, cb.hi)
                } else {
                    (-cb.inner_lo, -cb.lo)
                };
                // the exact maximum M: nlo <= M <= nhi, at <= M <= ub, wit < M
                assert!(
                    at <= nhi && nlo <= ub && wit < nhi,
                    "{j} {sign}: [{at}, {ub}] (witness {wit}) vs [{nlo}, {nhi}]"
                );
                let n = 24;
                for i in 0..=n {
                    for k in 0..=n {
                        let u = a + (b - a) * i as f64 / n as f64;
                        let v = c + (d - c) * k as f64 / n as f64;
                        let x = s.enclose_derivative(u.min(b), v.min(d), 0, 0).unwrap()[j];
                        let y = if sign > 0.0 { x.inf() } else { -x.sup() };
                        assert!(y <= ub, "{j} {sign} at ({u}, {v}): {y} > {ub}");
                    }
                }
                let gap = (ub - at) / crate::num::ulp(s.coord_scale(j));
                // (one ulp: a double-double value rounded outward; two where the first bound
                // did not close and the retry one ulp higher did)
                assert!(gap <= 2.0, "{j} {sign}: gap {gap} ulps");
            }
        }
    }

    /// The proof of F <= 0 (z coordinate, maximum side) on patch 0 of `s` against `ub`,
    /// without candidates: whether it succeeds.
    fn proves(s: &NurbsSurface, ub: f64) -> bool {
        let f = FastSurface::new(s).expect("fast path applies");
        let g = f.dd_grid::<MAXN>(0, 2, 1.0);
        let root = Piece::root(&g, [f.p, f.q], f.rational).expect("finite");
        let (mut budget, mut st) = (BUDGET, Stats::default());
        let cands = [None; 5];
        let mut pr = Prover {
            rational: f.rational,
            ub,
            lo: f64::NEG_INFINITY,
            wit: f64::NEG_INFINITY,
            budget: &mut budget,
            edges: [None; 4],
            cands: &cands,
            found: SmallVec::new(),
            searches: 0,
            st: &mut st,
        };
        pr.prove(&root, 4, &g) && pr.ub == ub
    }

    /// The chord proof ([`Prover::ridge_line`]) never proves a bound below the maximum: on the
    /// curved ridge (maximum 0 on an arc, the chords between ridge points leave it), on the
    /// straight ones, and on a chord off the ridge, where only the F_d^2 / (2 mu) term covers
    /// the points between chord and ridge. Mutation tried: dropping the F_d term in
    /// [`Prover::line_bound`] (gr[d] = 0) proves 0.95 on the off-ridge chord (this test
    /// fails). A bound above the maximum is proven (on the straight ridges exactly at the
    /// maximum, a float).
    #[test]
    fn ridge_chords_prove_no_bound_below_the_maximum() {
        let fam = families();
        let get = |n: &str| fam.iter().find(|f| f.0 == n).unwrap().1.clone();
        let circle = crate::surface::gen::ridge_circle();
        for ub in [-1e-3, -1e-4, -1e-6] {
            assert!(!proves(&circle, ub), "circle {ub}");
        }
        assert!(proves(&circle, 1e-3));
        for name in ["ridge_diagonal", "ridge_rotated"] {
            let s = get(name);
            assert!(!proves(&s, 1.0 - 1e-9), "{name}");
            assert!(proves(&s, 1.0), "{name}");
        }
        // A chord off the ridge: z = 1 - (u - v)^2 on the whole patch (F_uu = -2), the chord
        // from (0.3, 0) to (1, 0.7) parallel to the ridge, where z = 0.91. The bound
        // 0.91 + F_u^2 / (2 mu) = 0.91 + 0.36 / 4 = 1 must not prove ub = 0.95 (dropping the
        // F_d term in `line_bound` does), and proves ub = 1 + 1e-9.
        let s = get("ridge_diagonal");
        let f = FastSurface::new(&s).unwrap();
        let g = f.dd_grid::<MAXN>(0, 2, 1.0);
        let root = Piece::root(&g, [2, 2], false).unwrap();
        let mut buf = [0.0; MAXN];
        let (fv, e) = root.f_values(0.95, &mut buf).unwrap();
        let mu = root.curvature(fv, e, 0).unwrap();
        let (mut budget, mut st, cands) = (BUDGET, Stats::default(), [None; 5]);
        for (ub, want) in [(0.95, false), (1.0 + 1e-9, true)] {
            let pr = Prover {
                rational: false,
                ub,
                lo: f64::NEG_INFINITY,
                wit: f64::NEG_INFINITY,
                budget: &mut budget,
                edges: [None; 4],
                cands: &cands,
                found: SmallVec::new(),
                searches: 0,
                st: &mut st,
            };
            let ok = pr.chord_bound(&root, 0, mu, ([0.3, 0.0], [1.0, 0.7]), &g);
            assert_eq!(ok, want, "off-ridge chord, ub {ub}");
        }
    }

    #[test]
    fn proven_sides_are_sound_and_tight() {
        let mut tally = [0u64; 3];
        for seed in 0..8 {
            for (p, extra) in [(1, 0), (2, 0), (3, 0), (3, 2), (2, 3), (4, 1)] {
                for rational in [false, true] {
                    check(&random_surface(seed, p, p, extra, rational), &mut tally);
                }
            }
        }
        for (_, s, _) in families() {
            check(&s, &mut tally);
        }
        eprintln!("fast exits / proofs / fallbacks: {tally:?}");
        // nearly every side is proven (the ridge and a few rational sides fall back)
        assert!(tally[1] > 50 * tally[2], "{tally:?}");
    }

    /// Bicubic patches whose extremes sit at a corner (with a larger interior coefficient,
    /// so that the vertex test fails and the corner rule of [`Prover::settle`] proves the
    /// side), on an edge (the closed-form candidates of [`edge_candidate`]) or inside, with
    /// random perturbations: every proven side against exact rational values of the patch
    /// on a grid ([`crate::num::Exact`], the same Bernstein evaluation in exact arithmetic)
    /// and against [`check`] (dense verified samples, the general search); a maximum at a
    /// corner is proven exactly (bound = attained value = the corner's coefficient).
    #[test]
    fn corner_edge_and_interior_extrema_against_exact_values() {
        use crate::num::Exact;
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let mut tally = [0u64; 3];
        let mut corner_proofs = 0;
        for case in 0..96 {
            let kind = case % 4;
            let noise = if case % 8 < 4 { 0.0 } else { 0.02 };
            let mut z = [[0.0f64; 4]; 4];
            for (r, row) in z.iter_mut().enumerate() {
                for (c, x) in row.iter_mut().enumerate() {
                    let (u, v) = (r as f64 / 3.0, c as f64 / 3.0);
                    *x = match kind {
                        // falling away from the corner (0, 0), a bump of the coefficients at
                        // (1, 1) above it
                        0 => 1.0 - 0.25 * (u + v) + if (r, c) == (1, 1) { 0.4 } else { 0.0 },
                        // a ridge-free hump across the edge u = 0, largest at v ~ 0.6
                        1 => 1.0 - 0.5 * u - 2.0 * (v - 0.6) * (v - 0.6),
                        // an interior maximum
                        2 => 1.0 - 2.0 * (u - 0.4) * (u - 0.4) - 2.0 * (v - 0.55) * (v - 0.55),
                        // random
                        _ => rng.random_range(-1.0..1.0),
                    } + noise * rng.random_range(-1.0..1.0);
                }
            }
            let net: Vec<Vec<Vec<f64>>> = (0..4)
                .map(|r| {
                    (0..4)
                        .map(|c| vec![r as f64 / 3.0, c as f64 / 3.0, z[r][c]])
                        .collect()
                })
                .collect();
            let s = crate::surface::gen::bezier_patch(3, 3, net, None);
            check(&s, &mut tally);
            let f = FastSurface::new(&s).expect("a bicubic patch");
            let coefs: Vec<Exact> = z.iter().flatten().map(|&x| Exact::of(x)).collect();
            for sign in [1.0, -1.0] {
                let mut st = Stats::default();
                let Some((ub, at, _)) = f.side(2, sign, &mut st) else {
                    continue;
                };
                let n = 32;
                for i in 0..=n {
                    for k in 0..=n {
                        let t = [i as f64 / n as f64, k as f64 / n as f64];
                        // sum_rc B_r(u) B_c(v) z_rc, B_i = binom(3, i) t^i (1 - t)^(3 - i)
                        let basis = |t: f64| -> Vec<Exact> {
                            let (a, b) = (Exact::of(t), Exact::of(1.0) - Exact::of(t));
                            let pw = |x: &Exact, k: usize| {
                                (0..k).fold(Exact::of(1.0), |p, _| p * x.clone())
                            };
                            (0..4)
                                .map(|i| {
                                    Exact::of([1.0, 3.0, 3.0, 1.0][i]) * pw(&a, i) * pw(&b, 3 - i)
                                })
                                .collect()
                        };
                        let (bu, bv) = (basis(t[0]), basis(t[1]));
                        let x = (0..16).fold(Exact::of(0.0), |acc, i| {
                            acc + bu[i / 4].clone() * bv[i % 4].clone() * coefs[i].clone()
                        });
                        let x = if sign > 0.0 { x } else { -x };
                        assert_ne!(
                            x.cmp_f64(ub),
                            Some(std::cmp::Ordering::Greater),
                            "case {case} sign {sign} at {t:?}: above {ub}"
                        );
                    }
                }
                if kind == 0 && sign > 0.0 && noise == 0.0 {
                    assert_eq!((ub, at), (1.0, 1.0), "case {case}");
                    corner_proofs += st.fast_proofs;
                }
            }
        }
        assert!(
            corner_proofs > 0 && tally[1] > 50 * tally[2].max(1),
            "{tally:?}"
        );
    }

    /// [`split_grid`] (the constant-size split) writes the same halves and maxima, bit for
    /// bit, as [`Lines::split`] (the general one), on random and special values (signed
    /// zeros, subnormals, infinities, NaN: the maxima skip a NaN alike).
    #[test]
    fn grid_split_matches_the_general_split() {
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let special = [
            0.0,
            -0.0,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NAN,
            1e300,
            -1e-310,
        ];
        // (any NaN for a NaN: the payload depends on the operand order, which the compiler
        // may swap in a commutative operation; no proof reads a NaN coefficient)
        let same = |x: &[f64], y: &[f64]| {
            x.iter()
                .zip(y)
                .all(|(a, b)| a.to_bits() == b.to_bits() || (a.is_nan() && b.is_nan()))
        };
        for case in 0..3000 {
            let mut src = [0.0f64; 16];
            for x in src.iter_mut() {
                *x = if case % 7 == 0 && rng.random_bool(0.2) {
                    special[rng.random_range(0..special.len())]
                } else {
                    rng.random_range(-1.0..1.0) * 10f64.powi(rng.random_range(-3..4))
                };
            }
            let t = if case % 3 == 0 {
                0.5
            } else {
                rng.random_range(0.0..1.0)
            };
            // (degrees [3, 3] along both directions, and the boundary curves [3, 0], [0, 3])
            for (n, dir) in [([3, 3], 0), ([3, 3], 1), ([3, 0], 0), ([0, 3], 1)] {
                let (stride, lines, lstride) = if dir == 0 {
                    (n[1] + 1, n[1] + 1, 1)
                } else {
                    (1, n[0] + 1, n[1] + 1)
                };
                let g = Lines {
                    lines,
                    stride,
                    lstride,
                    t,
                };
                let (mut l1, mut h1, mut l2, mut h2) = ([9.0; 16], [9.0; 16], [9.0; 16], [9.0; 16]);
                let m1 = g.split::<4, 16>(&src, &mut l1, &mut h1);
                let m2 = match n {
                    [3, 3] => split_grid::<4, 4, 16>(&src, dir, t, &mut l2, &mut h2),
                    [3, 0] => split_grid::<4, 1, 16>(&src, dir, t, &mut l2, &mut h2),
                    _ => split_grid::<1, 4, 16>(&src, dir, t, &mut l2, &mut h2),
                };
                assert!(same(&m1, &m2), "{n:?} {dir}: {m1:?} {m2:?}");
                assert!(same(&l1, &l2) && same(&h1, &h2), "{n:?} {dir} {src:?}");
            }
        }
    }
}
