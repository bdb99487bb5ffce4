//! [`TightEval`]: verified point and small-box evaluation of single coordinates, about one ulp
//! (of the coordinate scale) wide — the precision layer under the verified box strategies.
//!
//! # Method
//!
//! Per polynomial piece (knot span [a, b]) the homogeneous curve (w_i P_i, w_i) is converted
//! once, lazily, into *Taylor coefficients* at either span end, in [`Ddi`] (rigorous
//! double-double): the Bézier points of the span come from the generic Boehm knot insertion
//! ([`HSpline::bezier_segment`], NURBS Book A5.1/A5.6), and the monomial form of a Bézier
//! curve `B(t) = sum_k binom(p, k) Δ^k Q_0 t^k` (forward differences; Farin, *Curves and
//! Surfaces for CAGD*, the monomial form in the Bézier chapter) is followed by the
//! substitution t = s / (b - a). Every coefficient is an enclosure of the exact one (`Ddi` is
//! inclusion-isotone), about 2^-100 relative wide. Evaluation is Horner's rule with the fused
//! step [`Ddi::mul_add`] at s = u - a or s = b - u, whichever is smaller (both exact
//! double-words), so it costs p multiply-adds and no division (one for rational curves), and
//! an exact value at a span end (s = 0) stays exact.
//!
//! * [`TightEval::coord_at`]: `C_j(u)` in `Ddi`, rounded outward once: one ulp wide, or a
//!   single float when the exact value is one.
//! * [`TightEval::coord_over`] encloses C_j over a box X = [lo, hi] per polynomial piece (boxes
//!   straddling knots are split there; when the box ends at an interior knot the right-continuous
//!   value there is added, which matters for discontinuous curves). With m the midpoint and
//!   h = u - m, |h| <= r:
//!   - the second-order Taylor form `C(X) ⊆ C(m) + C'(m) h + C''(X) h^2 / 2` (Moore 1966;
//!     Neumaier, *Interval Methods for Systems of Equations*, 1990, sec. 2.3), its extremal
//!     side sharpened by completing the square ([`taylor_bounds`]). `C(m)`, `C'(m)` are `Ddi`
//!     values at the point m, `C''(X)` the `Ddi` Horner value over the set m ± r. Near a
//!     critical point the correction is far below an ulp and the bound is `C(m)` rounded
//!     outward;
//!   - if `C'(m) + C''(X) h` excludes 0, C_j is monotone on X and the result is the hull of the
//!     point enclosures at lo and hi (the best possible);
//!   - boxes wider than 1/256 of their span use the generic kernels instead: interval de Boor
//!     over X ([`CurveEval::derivs_in_span`]) in the mean-value form `C(m) + C'(X) h` and the
//!     Taylor form, intersected with the naive enclosure `C(X)`.
//!
//! Rational curves: C = A / w, C' = (A' - w' C) / w, C'' = (A'' - 2 w' C' - w'' C) / w
//! (thesis eq. 3.10 / NURBS Book eq. 4.8), evaluated in `Ddi`.
//! Overflow anywhere makes a `Ddi` ENTIRE; then the generic interval kernels are used, so the
//! result is never wrong (possibly loose, possibly ENTIRE).
//!
//! Cost (2-D cubic Bézier, `cargo run --release --bin tight_speed`): `coord_at` ~50 ns,
//! `coord_over` on a small box ~150 ns, the lazily built span data ~600 ns once per curve.

use crate::num::ddi::{dist_up, up, Ddi};
use crate::num::{iv, pool, Scalar};
use crate::spline::bspline::HSpline;
use crate::spline::curve::NurbsCurve;
use crate::spline::eval::CurveEval;
use inari::Interval;
use std::sync::OnceLock;

/// Highest derivative order kept in the Taylor coefficients.
const ORDERS: usize = 3;

/// From this degree on the span expansions start from the Bézier points with `Ddi`'s own
/// running bounds ([`HSpline::bezier_segment_tight`]) rather than the double-word extraction's
/// (`num::dw`, a few times wider): the power form amplifies the points' radii by up to 2^p,
/// and above degree ~32 that difference shows in near-ties (measured: `tightness --family
/// high_degree --curves 1000`, two seeds, no bound lost against the `Ddi` extraction with
/// this threshold; with none, 2 to 4 of 3000).
const TAYLOR_TIGHT_FROM: usize = 32;

/// The most spans one sweep of Boehm insertion extracts ([`TightEval::swept`]): the sweep's
/// saving grows with the block (one end's insertion per span instead of two), the chain of
/// roundings behind a span's points with its place in the block.
const SWEEP_BLOCK: usize = 8;

/// Below this degree every evaluation in a span expands at its left end, whichever end is
/// nearer: Horner's terms c_k s^k over the whole span (s <= b - a) are at most
/// binom(p, k) 2^k max |Q_i|, so the rounding of the double-double evaluation stays below
/// 3^p 2^-104 <= 2^-80 of the points' scale (the nearer end bounds it by 2^p 2^-104), still
/// far below an ulp; and a span needs one expansion instead of two (each O(p^2) double-double
/// operations per row). Measured (callgrind): `bezier` on one degree-10 span -9.9% instructions,
/// on the `mixed` family -2.2%; `tightness`: no bound or certificate lost.
const ONE_END_BELOW: usize = 16;

/// Most bisection levels in `coord_over` when the sign of C'' over the box is unknown.
const MAX_BISECT: u32 = 4;

/// Boxes wider than this fraction of their span go to the generic interval kernels.
const WIDE: f64 = 1.0 / 256.0;

/// Taylor coefficients of every homogeneous row at one end of a span, for d^l/du^l, l < 3:
/// row r, order l, power k at `coef[(r * ORDERS + l) * (p + 1) + k]`, k <= p - l. The variable is
/// s = u - a at the left end, s = b - u at the right end; the right end's order-l coefficients
/// carry the factor (-1)^l, so both give derivatives with respect to u.
#[derive(Debug, Clone)]
struct Taylor {
    coef: Vec<Ddi>,
}

/// What [`TightEval::end_form`] returns for a box [lo, hi] and its end e.
#[derive(Debug, Clone, Copy)]
pub(crate) struct EndForm {
    /// C_j(e), enclosed
    pub value: Ddi,
    /// an upper bound of |C_j'(e)|
    pub slope: f64,
    /// C_j''([lo, hi]), enclosed
    pub second: Interval,
    /// {C_j(u) : u in [lo, hi]}, enclosed
    pub range: Interval,
}

/// Lazily computed data of one knot span.
#[derive(Debug, Default)]
struct SpanSlot {
    left: OnceLock<Option<Taylor>>,
    right: OnceLock<Option<Taylor>>,
    /// the span's double-double Bézier points, shared by both expansions
    seg: OnceLock<Vec<Ddi>>,
    /// from degree [`TAYLOR_TIGHT_FROM`] on, the same points from the cheaper extraction
    /// ([`TightEval::bezier_points`]; below it `seg` serves both)
    fast: OnceLock<Vec<Ddi>>,
}

/// The generic evaluators per coordinate (coordinate j as a 1-D NURBS curve with the same
/// weights), for wide boxes and as the fallback after overflow.
#[derive(Debug, Clone)]
struct CoordEval {
    ddi: CurveEval<Ddi>,
    ival: CurveEval<Interval>,
}

/// Verified, ~1-ulp-tight evaluation of the coordinates of one curve. Cheap to build (the
/// per-span data are computed on first use); `Send + Sync`.
#[derive(Debug)]
pub struct TightEval<'a> {
    curve: &'a NurbsCurve,
    spans: Vec<SpanSlot>,
    hom: OnceLock<HSpline<Ddi>>,
    generic: OnceLock<Vec<CoordEval>>,
    /// whether [`TightEval::bezier_points`] extracts blocks of spans ([`TightEval::sweeping`])
    sweep: bool,
}

/// The slots go back to this thread's pool (emptied there) for the next curve, and so do the
/// vectors of their Bézier points (a sweep fills one per span: a batch of splines allocated
/// and freed one per span and curve before).
impl Drop for TightEval<'_> {
    fn drop(&mut self) {
        for slot in &mut self.spans {
            for cell in [&mut slot.seg, &mut slot.fast] {
                if let Some(v) = cell.take() {
                    pool::give(v);
                }
            }
        }
        pool::give(std::mem::take(&mut self.spans));
    }
}

pool::pooled!(SpanSlot => SPAN_SLOT_POOL);

/// Horner's rule in `Ddi`: the shared [`crate::num::horner`] (whose `Ddi` step is the fused
/// [`Ddi::mul_add`]), with the point or set `s` by value.
#[inline]
fn horner(c: &[Ddi], s: Ddi) -> Ddi {
    crate::num::horner(c, &s)
}

/// The polynomial P(s) = sum c_k s^k over the set s0 ± r by the mean value form: for s in
/// that set, P(s) - P(x0) = P'(xi) (s - x0) with x0 in s0 and xi between them, so
/// P(s) in P(s0) + P'(s0 ± r) [-r, r], P' = sum k c_k s^(k-1) by Horner over the set (the
/// factors k are exact). Every operation is a `Ddi` enclosure.
fn horner_centred(c: &[Ddi], s0: Ddi, r: f64) -> Ddi {
    let v = horner(c, s0);
    let n = c.len();
    if n <= 1 {
        return v;
    }
    let s = s0.widen(r);
    let k = |i: usize| Ddi::exact(i as f64);
    let d = (1..n - 1)
        .rev()
        .fold(c[n - 1] * k(n - 1), |acc, i| acc.mul_add(s, c[i] * k(i)));
    d.mul_add(Ddi::from_bounds(-r, r), v)
}

/// C, C', C'' from homogeneous values (rational: thesis eq. 3.10 for orders 0..=2) in `Ddi`.
/// `a[l]`, `w[l]` are the l-th derivatives of the coordinate row and the weight row; only the
/// first `n` orders are computed (n <= 3). For n > 1 the reciprocal 1/w is formed once and
/// multiplied (one division instead of n; every step is an enclosure, so this stays sound).
///
/// A separate copy of the quotient rule on purpose: the generic one,
/// [`crate::spline::eval::quotient_rule`], divides every order by w and multiplies by the
/// binomials; this hot path (`coord_at`, `coord_over`, ~50 ns) uses one reciprocal and the
/// fused [`Ddi::mul_add`], which is tighter and cheaper, and changing it would change results.
#[inline]
fn rational_derivs(a: [Ddi; ORDERS], w: Option<[Ddi; ORDERS]>, n: usize) -> [Ddi; ORDERS] {
    let Some(w) = w else { return a };
    let mut c = [Ddi::exact(0.0); ORDERS];
    if n <= 1 {
        c[0] = a[0] / w[0];
        return c;
    }
    let inv = Ddi::exact(1.0) / w[0];
    c[0] = a[0] * inv;
    c[1] = (-w[1]).mul_add(c[0], a[1]) * inv;
    if n > 2 {
        let t = (-w[2]).mul_add(c[0], a[2]);
        c[2] = (Ddi::exact(-2.0) * w[1]).mul_add(c[1], t) * inv;
    }
    c
}

/// The polynomial of row r, derivative order l in a coefficient table of degree p (length
/// p + 1 - l, empty if l > p); layout as in [`Taylor`].
#[inline]
fn poly<S>(coef: &[S], p: usize, r: usize, l: usize) -> &[S] {
    let n = p + 1;
    let start = (r * ORDERS + l) * n;
    &coef[start..start + n.saturating_sub(l)]
}

impl Taylor {
    /// Coefficients from the Bézier points `q` (row-major, `p + 1` points of `h` rows) ordered
    /// from the expansion point, over a span of length `len` (exact double-word), with
    /// derivative sign `sign` (+1 left, -1 right). `None` if anything overflowed.
    fn from_bezier(q: &[Ddi], p: usize, h: usize, len: Ddi, sign: f64) -> Option<Taylor> {
        let n = p + 1;
        // scale[k] = binom(p, k) / len^k, with 1/len formed once (exact for a power of two).
        // The binomials are the shared `binom_s`: exact f64 integers where f64 is (all k for
        // p <= 56), else enclosed by the recurrence in Ddi. The length scaling is folded into
        // them (one product per coefficient), which is why this is not `bernstein_to_power`.
        let inv = Ddi::exact(1.0) / len;
        let mut scale = Vec::with_capacity(n);
        let mut invk = Ddi::exact(1.0);
        for k in 0..=p {
            if k > 0 {
                invk = invk * inv;
            }
            scale.push(crate::num::binom_s::<Ddi>(p, k) * invk);
        }
        let mut coef = vec![Ddi::exact(0.0); h * ORDERS * n];
        let mut d = vec![Ddi::exact(0.0); n];
        for r in 0..h {
            for (i, di) in d.iter_mut().enumerate() {
                *di = q[i * h + r];
            }
            // In-place forward differences: afterwards d[k] = Δ^k Q_0.
            crate::spline::bezier::forward_differences(&mut d);
            // c_k = binom(p, k) Δ^k Q_0 / len^k = Δ^k Q_0 * scale[k].
            for k in 0..=p {
                coef[r * ORDERS * n + k] = d[k] * scale[k];
            }
            // Order l: c^(l)_k = c_{k+l} (k+1) ... (k+l) sign^l.
            for l in 1..ORDERS.min(p + 1) {
                for k in 0..=p - l {
                    let prev = coef[(r * ORDERS + l - 1) * n + k + 1];
                    coef[(r * ORDERS + l) * n + k] = prev * Ddi::exact(sign * (k + 1) as f64);
                }
            }
        }
        if coef.iter().any(Ddi::is_entire) {
            None
        } else {
            Some(Taylor { coef })
        }
    }
}

impl<'a> TightEval<'a> {
    /// Build for a curve (clones it; everything else is computed lazily on first use).
    pub fn new(curve: &'a NurbsCurve) -> Self {
        // (the slots' vector from this thread's pool, `num::pool`, handed back on drop: at
        // 128 bytes a slot it is a large block for the allocator, whose requests of that size
        // first consolidate its free lists)
        let mut spans = pool::take(curve.num_points());
        spans.resize_with(curve.num_points(), SpanSlot::default);
        TightEval {
            curve,
            spans,
            hom: OnceLock::new(),
            generic: OnceLock::new(),
            sweep: false,
        }
    }

    /// [`TightEval::new`] for a caller that asks for the Bézier points of most spans (the
    /// searches of the Newton and Bézier strategies): [`TightEval::bezier_points`] then extracts up to
    /// [`SWEEP_BLOCK`] spans at once by one sweep of Boehm insertion (NURBS Book A5.6), about
    /// half the per-span cost; for a caller that needs a few spans it would be wasted work.
    pub fn sweeping(curve: &'a NurbsCurve) -> Self {
        let mut t = TightEval::new(curve);
        t.sweep = true;
        t
    }

    /// The curve this evaluator was built for.
    pub fn curve(&self) -> &NurbsCurve {
        self.curve
    }

    fn generic(&self) -> &[CoordEval] {
        self.generic.get_or_init(|| {
            (0..self.curve.dim())
                .map(|j| {
                    let c1 = self.curve.coordinate_curve(j);
                    CoordEval {
                        ddi: CurveEval::new(&c1, 1),
                        ival: CurveEval::new(&c1, 2),
                    }
                })
                .collect()
        })
    }

    /// The double-double Bézier points of span k of the homogeneous curve (row-major: p + 1
    /// points of `dim + rational` rows, (w_i P_i, w_i) or P_i), each enclosing the exact one
    /// (Boehm knot insertion, NURBS Book A5.1, via [`HSpline::bezier_segment`]), built on first
    /// use and shared by the span's two Taylor expansions.
    fn span_points(&self, k: usize) -> &[Ddi] {
        // The power form amplifies the Bézier points' radii by up to (1 + 2s/len)^p: 2^p
        // from the nearer end (s <= len/2), 3^p from the left end below ONE_END_BELOW
        // (s <= len; 3^15 ~ 2^24 on the double-word radii of p 2^-99 of the scale, times the
        // chain of at most SWEEP_BLOCK spans where `bezier_points` swept them). From degree
        // TAYLOR_TIGHT_FROM on the points come from the extraction with `Ddi`'s own, tighter
        // running bounds.
        let tight = self.curve.degree() >= TAYLOR_TIGHT_FROM;
        self.spans[k].seg.get_or_init(|| self.extract(k, tight))
    }

    /// The cached points of span k in the slot `cell` picks, filled on first use together with
    /// those of the following non-empty spans whose slots are empty (up to [`SWEEP_BLOCK`] in
    /// all) by one sweep of Boehm insertion (`HSpline::bezier_sweep`, NURBS Book A5.6: about
    /// half the per-span extraction's cost from the block's second span on; enclosures of the
    /// same exact points), end points that are exactly doubles made exact.
    fn swept(&self, k: usize, cell: impl Fn(&SpanSlot) -> &OnceLock<Vec<Ddi>>) -> &[Ddi] {
        if let Some(v) = cell(&self.spans[k]).get() {
            return v;
        }
        let hs = self.hom.get_or_init(|| HSpline::from_curve(self.curve));
        let kn = self.curve.knots();
        let n = self.curve.num_points() - 1;
        let p = self.curve.degree();
        if (k + 1 - p..=k).all(|i| kn[i] == kn[k]) && (k + 1..=k + p).all(|i| kn[i] == kn[k + 1]) {
            // A span already in Bézier form (u_{k-p+1} = ... = u_k, u_{k+1} = ... = u_{k+p}):
            // on it the basis functions N_{k-p,p} .. N_{k,p} are the Bernstein polynomials of
            // degree p (NURBS Book sec. 2.2), so its Bézier points are its homogeneous control
            // points themselves, with their enclosures; the sweep would insert no knot and
            // return them unchanged (a single clamped segment, a piecewise Bézier spline).
            let h = hs.hdim();
            let mut pts = pool::take(h * (p + 1));
            pts.extend_from_slice(&hs.pts[(k - p) * h..(k + 1) * h]);
            crate::spline::fraction_free::snap_exact_ends(self.curve, k, &mut pts);
            let _ = cell(&self.spans[k]).set(pts);
            return cell(&self.spans[k]).get().expect("just set");
        }
        // (the run of empty slots from k: non-empty spans only, stopping at a filled one)
        let (mut count, mut i) = (1, k + 1);
        while count < SWEEP_BLOCK && i <= n && cell(&self.spans[i]).get().is_none() {
            count += (kn[i] < kn[i + 1]) as usize;
            i += 1;
        }
        hs.bezier_sweep(k, count, &mut |i, q| {
            let slot = cell(&self.spans[i]);
            if slot.get().is_none() {
                let mut pts = pool::take(q.len());
                pts.extend_from_slice(q);
                crate::spline::fraction_free::snap_exact_ends(self.curve, i, &mut pts);
                // (another thread may have filled it meanwhile: either enclosure is sound)
                let _ = slot.set(pts);
            }
        });
        cell(&self.spans[k])
            .get()
            .expect("the sweep emits its first span")
    }

    /// The span's double-double Bézier points as [`TightEval::span_points`], for uses that do
    /// not go through the power form (convex combinations such as de Casteljau or the VS
    /// algorithm keep the points' radii, Σ B_i r_i <= max r_i): from the double-word
    /// extraction with its a-priori bound at every degree (`num::dw`, where its guard holds),
    /// cached; below [`TAYLOR_TIGHT_FROM`] the very points of the expansions. The Newton
    /// strategy's per-coordinate Bernstein forms and candidate values start from them
    /// (`newton::bernstein::SpanPoly`), and the Bézier strategy's `Mr` segments, span filter
    /// and fast paths, instead of each one's own knot insertion.
    pub(crate) fn bezier_points(&self, k: usize) -> &[Ddi] {
        // (extracted in blocks by one sweep for a caller that asks for most spans' points,
        // `TightEval::sweeping`; else one span at a time)
        match (self.curve.degree() < TAYLOR_TIGHT_FROM, self.sweep) {
            (true, false) => self.span_points(k),
            (true, true) => self.swept(k, |s| &s.seg),
            (false, false) => self.spans[k].fast.get_or_init(|| self.extract(k, false)),
            (false, true) => self.swept(k, |s| &s.fast),
        }
    }

    /// The extraction of span k's points alone (`tight`: with `Ddi`'s running bounds; else the
    /// type's faster route, the double words of `num::dw`), its end points that are exactly
    /// doubles made exact (an extremum at an unclamped end or a knot is then not straddled).
    fn extract(&self, k: usize, tight: bool) -> Vec<Ddi> {
        let hs = self.hom.get_or_init(|| HSpline::from_curve(self.curve));
        let mut pts = if tight {
            hs.bezier_segment_tight(k).pts
        } else {
            hs.bezier_segment(k).pts
        };
        crate::spline::fraction_free::snap_exact_ends(self.curve, k, &mut pts);
        pts
    }

    /// Taylor data of span k at its left (`right == false`) or right end.
    fn taylor(&self, k: usize, right: bool) -> Option<&Taylor> {
        let slot = &self.spans[k];
        let cell = if right { &slot.right } else { &slot.left };
        cell.get_or_init(|| {
            let pts = self.span_points(k);
            let hs = self.hom.get_or_init(|| HSpline::from_curve(self.curve));
            let (p, h) = (hs.degree, hs.hdim());
            let len = Ddi::diff(hs.knots[k + 1], hs.knots[k]);
            if right {
                let mut q = pts.to_vec();
                crate::spline::bspline::reverse_points(h, &mut q);
                Taylor::from_bezier(&q, p, h, len, -1.0)
            } else {
                Taylor::from_bezier(pts, p, h, len, 1.0)
            }
        })
        .as_ref()
    }

    /// C_j^(l)(s) for `from <= l < n` (the lower orders are left 0 for a non-rational curve;
    /// a rational one needs them all for eq. 3.10), from a span's Taylor coefficients at the
    /// point or set `s` (the expansion end's variable).
    #[inline]
    fn derivs(&self, t: &Taylor, j: usize, s: Ddi, from: usize, n: usize) -> [Ddi; ORDERS] {
        self.derivs_by(t, j, from, n, |c| horner(c, s))
    }

    /// [`TightEval::derivs`] over the set s0 ± r by the mean value form of each polynomial
    /// ([`horner_centred`]): at high degree the power form evaluated over a set directly
    /// loses ~2^p relative, where this loses only the derivative's spread times r.
    fn derivs_centred(
        &self,
        t: &Taylor,
        j: usize,
        s0: Ddi,
        r: f64,
        from: usize,
        n: usize,
    ) -> [Ddi; ORDERS] {
        self.derivs_by(t, j, from, n, |c| horner_centred(c, s0, r))
    }

    /// The body of [`TightEval::derivs`] with the polynomial evaluation `eval`.
    fn derivs_by(
        &self,
        t: &Taylor,
        j: usize,
        from: usize,
        n: usize,
        eval: impl Fn(&[Ddi]) -> Ddi,
    ) -> [Ddi; ORDERS] {
        let p = self.curve.degree();
        let rational = self.curve.is_rational();
        let first = if rational { 0 } else { from };
        let mut a = [Ddi::exact(0.0); ORDERS];
        for (l, al) in a.iter_mut().enumerate().take(n).skip(first) {
            *al = eval(poly(&t.coef, p, j, l));
        }
        let w = rational.then(|| {
            let d = self.curve.dim();
            let mut w = [Ddi::exact(0.0); ORDERS];
            for (l, wl) in w.iter_mut().enumerate().take(n) {
                *wl = eval(poly(&t.coef, p, d, l));
            }
            w
        });
        rational_derivs(a, w, n)
    }

    /// C_j''(X) of a rational curve from the homogeneous rows over the set `s` and given
    /// enclosures `cx` of C_j(X) and `c1x` of C_j'(X): (A'' - 2 w' C' - w'' C) / w (eq. 3.10).
    fn c2_from(&self, t: &Taylor, j: usize, s: Ddi, cx: Ddi, c1x: Ddi) -> Ddi {
        let p = self.curve.degree();
        let d = self.curve.dim();
        let a2 = horner(poly(&t.coef, p, j, 2), s);
        let w0 = horner(poly(&t.coef, p, d, 0), s);
        let w1 = horner(poly(&t.coef, p, d, 1), s);
        let w2 = horner(poly(&t.coef, p, d, 2), s);
        let num = (Ddi::exact(-2.0) * w1).mul_add(c1x, (-w2).mul_add(cx, a2));
        num / w0
    }

    /// Which end of span k to expand at for parameter m, and the exact variable there: the
    /// nearer end, and below degree [`ONE_END_BELOW`] always the left one (one expansion per
    /// span instead of two).
    #[inline]
    fn side(&self, k: usize, m: f64) -> (bool, Ddi) {
        let kn = self.curve.knots();
        let (a, b) = (kn[k], kn[k + 1]);
        if self.curve.degree() < ONE_END_BELOW || m - a <= b - m {
            (false, Ddi::diff(m, a))
        } else {
            (true, Ddi::diff(b, m))
        }
    }

    /// `C_j(u)` of piece k at the f64 point u, in `Ddi` (ENTIRE after overflow).
    fn ddi_at(&self, j: usize, k: usize, u: f64) -> Ddi {
        let (right, s) = self.side(k, u);
        match self.taylor(k, right) {
            Some(t) => self.derivs(t, j, s, 0, 1)[0],
            None => Ddi::ENTIRE,
        }
    }

    /// Verified enclosure of `C_j(u)` at the exact f64 parameter `u` (which should lie in the
    /// domain; outside it the end pieces are extended). The span is found exactly; the value is
    /// computed in [`Ddi`] and rounded outward once, so the interval is a single float or one
    /// ulp wide, except after overflow (then it is what interval de Boor gives, possibly
    /// ENTIRE — never wrong).
    ///
    /// # Panics
    /// If `j >= dim` (as indexing does).
    pub fn coord_at(&self, j: usize, u: f64) -> Interval {
        self.coord_at_tight(j, u).0
    }

    /// [`TightEval::coord_at`], and the double-double enclosure behind it where there is one
    /// (`None` at a clamped end, whose value is exact, and where the generic fallback ran):
    /// about 2^-100 relative wide, so that callers can derive strict witnesses from it
    /// ([`Ddi::strictly_below`]) where the f64 interval is an ulp wide.
    pub fn coord_at_tight(&self, j: usize, u: f64) -> (Interval, Option<Ddi>) {
        if !u.is_finite() {
            return (Interval::ENTIRE, None); // no value to enclose; the safe answer
        }
        // At a clamped domain end the value is the end control point exactly
        // (`NurbsCurve::clamped_ends`): no span expansion is built for it.
        let (a, b) = self.curve.domain();
        if u == a || u == b {
            let cl = self.curve.clamped_ends();
            if u == a && cl[0] {
                return (iv::point(self.curve.control_point(0)[j]), None);
            }
            if u == b && cl[1] {
                let last = self.curve.num_points() - 1;
                return (iv::point(self.curve.control_point(last)[j]), None);
            }
        }
        let k = self.curve.find_span(u);
        let kn = self.curve.knots();
        let v = if u == kn[k] || u == kn[k + 1] {
            self.end_value(j, k, u == kn[k + 1])
        } else {
            self.ddi_at(j, k, u)
        };
        if !v.is_entire() {
            return (v.to_interval(), Some(v));
        }
        (self.generic_at(j, k, u), None)
    }

    /// `C_j` at an end of span k (the right end if `right`), in `Ddi`: the piece there is its
    /// first (last) Bézier point, x / w or x ([`TightEval::bezier_points`]; the value the
    /// expansion at that end gives, s = 0, without building it). At u = u_k this is the
    /// curve's value (the span found for u_k is the one starting there: right-continuous);
    /// at u_{k+1} it is the limit from the left (the curve's value unless u_{k+1} is a jump).
    /// At a clamped domain end it is the end control point exactly
    /// (`NurbsCurve::clamped_ends`; the quotient of the Bézier points would be an enclosure
    /// an ulp wide).
    pub(crate) fn end_value(&self, j: usize, k: usize, right: bool) -> Ddi {
        let c = &self.curve;
        let (kn, (a, b), cl) = (c.knots(), c.domain(), c.clamped_ends());
        if !right && cl[0] && kn[k] == a {
            return Ddi::exact(c.control_point(0)[j]);
        }
        if right && cl[1] && kn[k + 1] == b {
            return Ddi::exact(c.control_point(c.num_points() - 1)[j]);
        }
        let pts = self.bezier_points(k);
        let (p, d) = (self.curve.degree(), self.curve.dim());
        let h = d + self.curve.is_rational() as usize;
        let i = if right { p } else { 0 };
        let x = pts[i * h + j];
        if self.curve.is_rational() {
            x / pts[i * h + d]
        } else {
            x
        }
    }

    /// Fallback for `coord_at`: generic de Boor in `Ddi`, then in intervals.
    fn generic_at(&self, j: usize, k: usize, u: f64) -> Interval {
        let g = &self.generic()[j];
        let v = g.ddi.derivs_in_span(k, &Ddi::exact(u), 0)[0][0];
        if !v.is_entire() {
            return v.to_interval();
        }
        g.ival.derivs_in_span(k, &iv::point(u), 0)[0][0]
    }

    /// All coordinates of C(u) (see [`TightEval::coord_at`]).
    pub fn point(&self, u: f64) -> Vec<Interval> {
        (0..self.curve.dim()).map(|j| self.coord_at(j, u)).collect()
    }

    /// Verified enclosure of `{C_j(u) : u in [a, b]}` (clipped to the domain; EMPTY if [a, b] is
    /// empty or misses the domain). Made for small boxes around critical points (about one ulp
    /// wide then), valid for any box. Boxes straddling knots are split there and the pieces'
    /// enclosures hulled, so discontinuities of C' (or C) are handled.
    ///
    /// # Panics
    /// If `j >= dim` (as indexing does).
    pub fn coord_over(&self, j: usize, a: f64, b: f64) -> Interval {
        if a.is_nan() || b.is_nan() || a > b {
            return Interval::EMPTY;
        }
        let (d0, d1) = self.curve.domain();
        let kn = self.curve.knots();
        // Common case without allocation: [a, b] inside one span of the domain.
        let k = self.curve.find_span(a);
        let mut acc = if a >= d0 && b <= d1 && b <= kn[k + 1] {
            self.piece_over(j, k, a, b)
        } else {
            self.curve
                .spans_straddled(a, b)
                .into_iter()
                .fold(Interval::EMPTY, |acc, (k, lo, hi)| {
                    acc.convex_hull(self.piece_over(j, k, lo, hi))
                })
        };
        // If b is an interior knot, C(b) is the value of the next piece (right-continuous basis
        // functions); at a knot of multiplicity p + 1 that differs from the left piece's limit,
        // which is all the pieces above cover. Add it (exact point value).
        if a < b && b > d0 && b < d1 && kn[kn.partition_point(|&x| x < b)] == b {
            acc = acc.convex_hull(self.coord_at(j, b));
        }
        acc
    }

    /// Enclosure of piece k of C_j over [lo, hi] (inside the closed span).
    fn piece_over(&self, j: usize, k: usize, lo: f64, hi: f64) -> Interval {
        self.piece_over_depth(j, k, lo, hi, 0)
    }

    /// [`TightEval::piece_over`] with the bisection depth so far (see below).
    fn piece_over_depth(&self, j: usize, k: usize, lo: f64, hi: f64, depth: u32) -> Interval {
        if lo == hi {
            let v = self.ddi_at(j, k, lo);
            return if v.is_entire() {
                self.generic_at(j, k, lo)
            } else {
                v.to_interval()
            };
        }
        let kn = self.curve.knots();
        let m = (lo + 0.5 * (hi - lo)).clamp(lo, hi);
        if hi - lo > WIDE * (kn[k + 1] - kn[k]) {
            return self.piece_over_generic(j, k, lo, hi, m);
        }
        let (right, sm) = self.side(k, m);
        let Some(t) = self.taylor(k, right) else {
            return self.piece_over_generic(j, k, lo, hi, m);
        };
        // R >= max |u - m| over X; the parameter set is s in sm ± R (same for both ends, the
        // map u -> b - u is an isometry), and h = u - m in H = 0 ± R.
        let r = dist_up(m, lo).max(dist_up(hi, m));
        let hset = Ddi::from_bounds(-r, r);
        let pm = self.derivs(t, j, sm, 0, 2);
        let mut c2 = self.derivs(t, j, sm.widen(r), 2, 3)[2];
        if c2.is_entire() {
            // (the power form over the set lost too much, e.g. a weight enclosure holding 0
            // at high degree: its mean value form instead)
            c2 = self.derivs_centred(t, j, sm, r, 2, 3)[2];
        }
        let (cm, c1m) = (pm[0], pm[1]);
        if cm.is_entire() || c1m.is_entire() || c2.is_entire() {
            return self.piece_over_generic(j, k, lo, hi, m);
        }
        // Mean-value form for C' itself: C'(X) ⊆ C'(m) + C''(X) H. No zero: monotone on X, and
        // the range is exactly between C(lo) and C(hi).
        if Ddi::abs_lower(c2.mul_add(hset, c1m)).is_some() {
            let (f, g) = (self.ddi_at(j, k, lo), self.ddi_at(j, k, hi));
            if !f.is_entire() && !g.is_entire() {
                return f.to_interval().convex_hull(g.to_interval());
            }
        }
        let mut c2i = c2.to_interval();
        // Whether the quadratic term can show at the ulp level of C(m) at all.
        let visible = |c: Interval| {
            c.inf().abs().max(c.sup().abs()) * r * r > cm.hi().abs() * f64::EPSILON * 0.25
        };
        if self.curve.is_rational() && visible(c2i) {
            c2i = self.second_refined(t, j, (sm.widen(r), hset), (cm, c1m), c2i);
        }
        // If the sign of C'' over X is unknown (near an inflection, or C''(X) overestimated, as
        // for rational curves with widely spread weights) the quadratic term cannot be
        // sharpened by completing the square; when it would show at the ulp level of C(m),
        // bisect (at most MAX_BISECT levels, so at most 2^MAX_BISECT pieces): each half is
        // either monotone (exact hull of its end values) or has a 4 times smaller term.
        if c2i.contains(0.0) && depth < MAX_BISECT && visible(c2i) {
            return self
                .piece_over_depth(j, k, lo, m, depth + 1)
                .convex_hull(self.piece_over_depth(j, k, m, hi, depth + 1));
        }
        let (tl, tu) = taylor_bounds(c1m.abs_upper(), c2i, r);
        (cm + Ddi::from_bounds(tl, tu)).to_interval()
    }

    /// A rational curve's C_j''(X) sharpened: eq. 3.10 over the set S of the expansion's
    /// variable (`sx`) divides wide homogeneous enclosures by each other and overestimates C''
    /// badly when the weights vary much. Re-evaluate
    /// C''(X) ⊆ (A''(S) - 2 W'(S) C'(X) - W''(S) C(X)) / W(S) with the much tighter
    /// C'(X) ⊆ C'(m) + C''(X) H and C(X) ⊆ C(m) + C'(m) H + C''(X) H^2 / 2 (Taylor about m,
    /// `(cm, c1m)` enclosing C(m), C'(m), H ∋ u - m for u in X), and intersect (both enclose
    /// C''(X)). Two rounds.
    #[inline]
    fn second_refined(
        &self,
        t: &Taylor,
        j: usize,
        (sx, hset): (Ddi, Ddi),
        (cm, c1m): (Ddi, Ddi),
        mut c2i: Interval,
    ) -> Interval {
        for _ in 0..2 {
            let c2d = Ddi::from_interval(c2i);
            let c1x = c2d.mul_add(hset, c1m);
            let cx = c1m.mul_add(hset, cm) + c2d * hset * hset * Ddi::exact(0.5);
            let refined = self.c2_from(t, j, sx, cx, c1x).to_interval();
            let both = c2i.intersection(refined);
            if both.is_empty() {
                break;
            }
            c2i = both;
        }
        c2i
    }

    /// The second-order Taylor form of piece k of C_j over [lo, hi] (inside the closed span)
    /// centred at one of its ends e (`at_hi`: e = hi, else e = lo) instead of its middle:
    /// C(X) ⊆ C(e) + C'(e) H + C''(X) H^2 / 2 with H = X - e ⊆ [-r, r], r >= hi - lo, bounded
    /// as in `coord_over` ([`taylor_bounds`]: completing the square where C'' has a sign).
    /// Made for a box that ends at an extremum where C_j' vanishes (a symmetric curve's
    /// extremum at a knot): there |C'(e)| is an enclosure of 0, and where C'' has the sign of
    /// the extremum over the box the bound is C(e) to about an ulp however wide the box
    /// (about the middle it exceeds C(e) by up to |C''| (hi - lo)^2 / 8). `None` after an
    /// overflow or for a box outside the span.
    pub(crate) fn end_form(
        &self,
        j: usize,
        k: usize,
        lo: f64,
        hi: f64,
        at_hi: bool,
    ) -> Option<EndForm> {
        let kn = self.curve.knots();
        if !(lo < hi && kn[k] <= lo && hi <= kn[k + 1]) {
            return None;
        }
        let e = if at_hi { hi } else { lo };
        let (right, se) = self.side(k, e);
        let t = self.taylor(k, right)?;
        // r >= hi - lo = max |u - e| over X; h = u - e lies in H = [-r, 0] (e = hi) or [0, r],
        // and the expansion's variable in se + H (s = u - a) or se - H (s = b - u at the right
        // end). One-sided sets: a symmetric one would reach beyond the span, where a rational
        // curve's weight polynomial may vanish.
        let r = dist_up(hi, lo);
        let hset = if at_hi {
            Ddi::from_bounds(-r, 0.0)
        } else {
            Ddi::from_bounds(0.0, r)
        };
        let sx = se + if right { -hset } else { hset };
        let pe = self.derivs(t, j, se, 0, 2);
        let (ce, c1e) = (pe[0], pe[1]);
        if ce.is_entire() || c1e.is_entire() {
            return None;
        }
        let c2 = self.derivs(t, j, sx, 2, 3)[2];
        let mut c2i = if c2.is_entire() {
            Interval::ENTIRE
        } else {
            c2.to_interval()
        };
        if c2i.contains(0.0) {
            // (the power form over a wide set loses ~2^p, and a rational curve's weight over it
            // may hold 0: the generic interval de Boor derivatives over X instead, where the
            // weight is a convex combination of positive weights; both enclose C''(X))
            let e = self.generic()[j]
                .ival
                .derivs_in_span(k, &iv::span(lo, hi), 2);
            c2i = c2i.intersection(e[2][0]);
        }
        if c2i.is_empty() || c2i.is_entire() {
            return None;
        }
        if self.curve.is_rational() {
            c2i = self.second_refined(t, j, (sx, hset), (ce, c1e), c2i);
        }
        let g = c1e.abs_upper();
        let (tl, tu) = taylor_bounds(g, c2i, r);
        // (each end on its own: C(e) + [tl, tu] as one midpoint-radius `Ddi` would round its
        // upper end at the scale of the wide lower one)
        let range = iv::span(
            (ce + Ddi::exact(tl)).lower_end(),
            (ce + Ddi::exact(tu)).upper_end(),
        );
        (g.is_finite() && !range.is_empty()).then_some(EndForm {
            value: ce,
            slope: g,
            second: c2i,
            range,
        })
    }

    /// Wide boxes and overflow: generic interval de Boor over X (C, C', C''), Ddi at m; the
    /// mean-value form and the Taylor form, intersected with the naive enclosure C(X).
    fn piece_over_generic(&self, j: usize, k: usize, lo: f64, hi: f64, m: f64) -> Interval {
        let g = &self.generic()[j];
        let e = g.ival.derivs_in_span(k, &iv::span(lo, hi), 2);
        let (c0x, c1x, c2x) = (e[0][0], e[1][0], e[2][0]);
        let d = g.ddi.derivs_in_span(k, &Ddi::exact(m), 1);
        let (cm, c1m) = (d[0][0], d[1][0].to_interval());
        if cm.is_entire() {
            return c0x;
        }
        let r = dist_up(m, lo).max(dist_up(hi, m));
        let g = c1m.inf().abs().max(c1m.sup().abs());
        let (tl, tu) = taylor_bounds(g, c2x, r);
        // Mean-value form: C(u) - C(m) = C'(xi)(u - m), xi in X.
        let mv = c1x * iv::span(-r, r);
        let t = iv::span(tl, tu).intersection(mv);
        finish(cm, t, c0x)
    }
}

/// Bounds [L, U] of T(h) = c1 h + c2 h^2 / 2 over |h| <= r, |c1| <= `g`, c2 in `c2`: the
/// second-order Taylor remainder form C(u) - C(m) = C'(m) h + C''(xi) h^2 / 2 with c1 ∋ C'(m),
/// c2 ∋ C''(X) (Moore 1966; Neumaier 1990 sec. 2.3). NaN/infinite input gives (-inf, inf).
///
/// With G = g >= max|c1|: |c1 h| <= G r and c2 h^2 / 2 lies in [min(inf c2, 0), max(sup c2, 0)] r^2/2.
/// Completing the square on the extremal side: for fixed h, T <= max(c1 h) + sup(c2) h^2 / 2;
/// if sup(c2) = -κ < 0, maximising over h >= 0 and h <= 0 separately gives T <= G^2 / (2κ)
/// (symmetrically T >= -G^2 / (2 inf c2) if inf c2 > 0). This is what makes a box around a
/// maximum tight even when r is not tiny: the excess is C'(m)^2 / (2|C''|), second order in the
/// distance of m from the critical point. All arithmetic is `Ddi` (rigorous), rounded outward.
fn taylor_bounds(g: f64, c2: Interval, r: f64) -> (f64, f64) {
    let (c2p, c2n) = (c2.sup().max(0.0), (-c2.inf()).max(0.0));
    if !(g.is_finite() && c2p.is_finite() && c2n.is_finite() && r.is_finite()) {
        return (f64::NEG_INFINITY, f64::INFINITY);
    }
    // Upper bounds by Lemma B (ddi.rs): each `up` covers one sum of products of two f64.
    // r is raised to >= 2^-1000 so that 0.5 r is exact.
    let r = r.max(2f64.powi(-1000));
    let r2h = up(r * (0.5 * r)); // >= r^2 / 2
    let mut u = up(g * r + c2p * r2h);
    let mut l = -up(g * r + c2n * r2h);
    if c2.sup() < 0.0 {
        // κ = -sup(c2) = min |c2| > 0 (not max: a larger κ would give a smaller, wrong bound).
        // q = up(0.5 up(G / κ)) >= G / (2κ) (two single-operation uses of Lemma B; no
        // overflow of 2κ), and up(G q) >= G^2 / (2κ).
        let q = up(0.5 * up(g / -c2.sup()));
        u = u.min(up(g * q));
    }
    if c2.inf() > 0.0 {
        let q = up(0.5 * up(g / c2.inf()));
        l = l.max(-up(g * q));
    }
    (l, u)
}

/// `C(m) + T` rounded outward once, intersected with `naive`. An empty T or result cannot
/// happen in exact arithmetic (every set here contains C(m) + 0 resp. the true range); if
/// rounding ever produced one, `naive` is returned rather than a guess.
fn finish(cm: Ddi, t: Interval, naive: Interval) -> Interval {
    if t.is_empty() {
        return naive;
    }
    let out = (cm + Ddi::from_interval(t))
        .to_interval()
        .intersection(naive);
    if out.is_empty() {
        naive
    } else {
        out
    }
}

impl NurbsCurve {
    /// Coordinate j as a 1-D NURBS curve (same degree, knots and weights).
    ///
    /// # Panics
    /// If `j >= dim`.
    pub fn coordinate_curve(&self, j: usize) -> NurbsCurve {
        let pts: Vec<f64> = (0..self.num_points())
            .map(|i| self.control_point(i)[j])
            .collect();
        NurbsCurve::from_flat(
            self.degree(),
            1,
            self.knots().to_vec(),
            pts,
            self.weights().map(|w| w.to_vec()),
        )
        .expect("a coordinate of a valid curve is a valid 1-D curve")
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    /// The mean value form of a polynomial over a set encloses the exact values (rationals)
    /// at points of the set, and at degree 30 it stays finite and narrow where Horner over
    /// the set itself (the power form's coefficients alternate and grow like binomials)
    /// does not.
    #[test]
    fn centred_horner_encloses_exact_values_and_beats_plain_horner() {
        use crate::num::exact::Exact;
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        for _ in 0..50 {
            let p = rng.random_range(1..=30usize);
            // power-form coefficients of (1 - 2s)^p-like size: binomials times 2^k
            let c: Vec<f64> = (0..=p)
                .map(|k| {
                    let b = crate::num::binom_s::<f64>(p, k) * 2f64.powi(k as i32);
                    b * rng.random_range(-1.0..1.0)
                })
                .collect();
            let cd: Vec<Ddi> = c.iter().map(|&x| Ddi::exact(x)).collect();
            let s0 = rng.random_range(0.0..0.5);
            let r = 2f64.powi(-rng.random_range(10..30));
            let centred = horner_centred(&cd, Ddi::exact(s0), r);
            assert!(!centred.is_entire());
            let iv = centred.to_interval();
            // (interior points: their rounding, half an ulp of s0, stays far inside the set)
            for i in 1..=7 {
                let s = s0 - r + 2.0 * r * i as f64 / 8.0;
                let mut v = Exact::of(0.0);
                for &ck in c.iter().rev() {
                    v = v * Exact::of(s) + Exact::of(ck);
                }
                assert!(
                    !v.gt_f64(iv.sup()) && v.cmp_f64(iv.inf()).is_some_and(|o| o.is_ge()),
                    "p={p}: P({s:e}) outside [{:e}, {:e}]",
                    iv.inf(),
                    iv.sup()
                );
            }
            if p == 30 {
                let plain = horner(&cd, Ddi::exact(s0).widen(r)).to_interval();
                assert!(iv.wid() <= plain.wid(), "p=30: centred wider than plain");
            }
        }
    }

    /// Width of an interval in ulps of `scale` (ulp(scale) = spacing of floats at scale).
    fn ulps(x: Interval, scale: f64) -> f64 {
        let ulp = f64::from_bits(scale.to_bits() + 1) - scale;
        (x.sup() - x.inf()) / ulp
    }

    #[test]
    fn circle_is_unit_within_rounded_weight() {
        let c = crate::spline::eval::tests::circle();
        let t = TightEval::new(&c);
        for i in 0..=1000 {
            let u = i as f64 / 1000.0;
            let p = t.point(u);
            for x in &p {
                assert!(ulps(*x, 1.0) <= 1.0, "u={u}: {x:?}");
            }
            let r2 = p[0] * p[0] + p[1] * p[1];
            // The weight sqrt(2)/2 is rounded: |C|^2 = 1 only up to ~1e-16.
            assert!(
                r2.inf() <= 1.0 + 1e-16 && r2.sup() >= 1.0 - 1e-16,
                "u={u}: {r2:?}"
            );
            let naive: Vec<Interval> = c.point(u).unwrap();
            for (x, y) in p.iter().zip(&naive) {
                assert!(!x.intersection(*y).is_empty());
            }
        }
        // Exact values stay exact: the knots of multiplicity p give control points.
        for (u, x, y) in [
            (0.0, 1.0, 0.0),
            (0.25, 0.0, 1.0),
            (0.5, -1.0, 0.0),
            (1.0, 1.0, 0.0),
        ] {
            assert_eq!(t.point(u), vec![iv::point(x), iv::point(y)], "u={u}");
        }
    }

    #[test]
    fn dyadic_cubic_bezier_is_exact() {
        // Small integer control points and t = k/64: every Bernstein term is exact in f64, so
        // the exact value is a float and the enclosure must be that single float.
        let pts = [3.0, -7.0, 11.0, 2.0];
        let c = NurbsCurve::new(
            3,
            vec![0., 0., 0., 0., 1., 1., 1., 1.],
            pts.iter().map(|&x| vec![x]).collect(),
            None,
        )
        .unwrap();
        let t = TightEval::new(&c);
        for k in 0..=64 {
            let u = k as f64 / 64.0;
            // Bernstein form sum_i binom(3, i) (1-u)^(3-i) u^i P_i, exact for these data.
            let b: f64 = (0..4)
                .map(|i| {
                    [1.0, 3.0, 3.0, 1.0][i]
                        * (1.0 - u).powi(3 - i as i32)
                        * u.powi(i as i32)
                        * pts[i]
                })
                .sum();
            let v = t.coord_at(0, u);
            assert!(v.contains(b), "u={u}: {b} not in {v:?}");
            assert!(ulps(v, 11.0) <= 1.0, "u={u}: {v:?}");
        }
    }

    /// A random curve: degree 1..=10, clamped or not, rational or not, knots with repeats.
    pub(crate) fn random_curve(rng: &mut ChaCha8Rng, dim: usize) -> NurbsCurve {
        let p = rng.random_range(1..=10usize);
        let n = p + 1 + rng.random_range(0..6usize);
        let clamped = rng.random_bool(0.5);
        let mut knots: Vec<f64> = Vec::new();
        while knots.len() < n + p + 1 {
            let x: f64 = rng.random_range(0.0..1.0);
            let reps = if rng.random_bool(0.2) { 2 } else { 1 };
            for _ in 0..reps {
                knots.push(x);
            }
        }
        knots.truncate(n + p + 1);
        knots.sort_by(f64::total_cmp);
        if clamped {
            for i in 0..=p {
                knots[i] = 0.0;
                let m = knots.len();
                knots[m - 1 - i] = 1.0;
            }
        }
        let pts: Vec<Vec<f64>> = (0..n)
            .map(|_| (0..dim).map(|_| rng.random_range(-10.0..10.0)).collect())
            .collect();
        let w = if rng.random_bool(0.5) {
            Some(
                (0..n)
                    .map(|_| 10f64.powf(rng.random_range(-2.0..2.0)))
                    .collect(),
            )
        } else {
            None
        };
        NurbsCurve::new(p, knots, pts, w).unwrap_or_else(|_| random_curve(rng, dim))
    }

    #[test]
    fn coord_at_encloses_naive_samples_and_is_tight() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        for _ in 0..200 {
            let c = random_curve(&mut rng, 2);
            let t = TightEval::new(&c);
            let (a, b) = c.domain();
            for i in 0..=20 {
                let u = (a + (b - a) * i as f64 / 20.0).min(b);
                let naive: Vec<Interval> = c.point(u).unwrap();
                for (j, nj) in naive.iter().enumerate() {
                    let v = t.coord_at(j, u);
                    assert!(!v.intersection(*nj).is_empty(), "{c:?} u={u}");
                    assert!(ulps(v, c.coord_scale(j)) <= 2.0, "{v:?} vs scale");
                }
            }
        }
    }

    #[test]
    fn coord_over_near_a_maximum_is_one_ulp() {
        // y(t) of a cubic Bézier with a maximum inside; locate it by f64 Newton, then a small
        // box around it must be enclosed within ~1 ulp and contain every sampled point value.
        let c = NurbsCurve::new(
            3,
            vec![0., 0., 0., 0., 1., 1., 1., 1.],
            vec![
                vec![0.0, 0.0],
                vec![1.0, 2.0],
                vec![2.0, 1.7],
                vec![3.0, -0.5],
            ],
            None,
        )
        .unwrap();
        let t = TightEval::new(&c);
        let f = CurveEval::<f64>::new(&c, 2);
        let mut u = 0.5;
        for _ in 0..50 {
            let d = f.derivs(u, 2).unwrap();
            u -= d[1][1] / d[2][1];
        }
        for w in [0.0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-4] {
            let (a, b) = (u - w, u + w);
            let box_ = t.coord_over(1, a, b);
            assert!(
                ulps(box_, c.coord_scale(1)) <= 2.0 || w >= 1e-6,
                "w={w}: {box_:?}"
            );
            // the upper end is the maximum: within one ulp of the point value at u
            let at = t.coord_at(1, u);
            assert!(
                box_.sup() <= f64::from_bits(at.sup().to_bits() + 1),
                "w={w}"
            );
            for i in 0..=100 {
                let s = a + (b - a) * i as f64 / 100.0;
                // coord_at(s) = [RD, RU] of the exact C(s): inside the box iff the box holds C(s)
                assert!(t.coord_at(1, s.clamp(a, b)).subset(box_), "w={w} s={s}");
            }
        }
    }

    #[test]
    fn coord_over_is_sound_on_random_boxes() {
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        for _ in 0..100 {
            let c = random_curve(&mut rng, 1);
            let t = TightEval::new(&c);
            let (a, b) = c.domain();
            for _ in 0..10 {
                let x: f64 = rng.random_range(a..b);
                let w = (b - a) * 10f64.powf(rng.random_range(-16.0..0.0));
                let (lo, hi) = (x, (x + w).min(b));
                let e = t.coord_over(0, lo, hi);
                let naive = c.enclose_point(iv::span(lo, hi)).unwrap()[0];
                // Not looser than naive interval de Boor (up to the rounding of the Taylor
                // form, 2 ulps of the scale).
                let slack = 2.0 * f64::EPSILON * c.coord_scale(0);
                assert!(
                    e.inf() >= naive.inf() - slack && e.sup() <= naive.sup() + slack,
                    "{e:?} looser than naive {naive:?}"
                );
                for i in 0..=50 {
                    let s = (lo + (hi - lo) * i as f64 / 50.0).min(hi);
                    // The exact C(s) lies in coord_at(s); it must lie in e too.
                    assert!(!t.coord_at(0, s).intersection(e).is_empty(), "s={s}");
                    #[cfg(feature = "mpfr")]
                    {
                        let x: Vec<rug::Float> = c.point(s).unwrap();
                        assert!(
                            e.inf() <= x[0] && x[0] <= e.sup(),
                            "s={s}: {e:?} misses {}",
                            x[0]
                        );
                    }
                }
            }
        }
    }

    /// A rational quadratic in 3-D, mirror-symmetric about u = 0 (a simple knot, C1 there),
    /// from the `extrema_at_knots` test family: its first and third coordinates have their
    /// minimum at u = 0, the second its maximum.
    pub(crate) fn symmetric_at_a_knot() -> NurbsCurve {
        let p0 = vec![
            0.9180048576902702,
            -0.46806430741524396,
            0.16494573052517847,
        ];
        let p1 = vec![
            0.8054290257000831,
            -0.25600300026892686,
            -0.6415474811181174,
        ];
        let p2 = vec![-0.3054533290473014, 0.6098559001330548, -0.984613714466708];
        let (w0, w1, w2) = (0.5528577113252439, 3.6825903093062817, 0.6912429388865053);
        let k = 0.8147563086639935;
        NurbsCurve::new(
            2,
            vec![-1.0, -1.0, -1.0, -k, 0.0, k, 1.0, 1.0, 1.0],
            vec![p0.clone(), p1.clone(), p2.clone(), p2, p1, p0],
            Some(vec![w0, w1, w2, w2, w1, w0]),
        )
        .unwrap()
    }

    /// The Taylor form about a box's end ([`TightEval::end_form`]) on random boxes ending at
    /// span ends (widths 2^-50 of the span to the whole span): its range holds every sampled
    /// value (and, with `mpfr`, the 256-bit values), its `second` every sampled C'' enclosure
    /// (interval de Boor at the point), its `slope` bounds |C'(e)|, and its value is C(e).
    #[test]
    fn end_form_is_sound_on_random_boxes_at_span_ends() {
        let mut rng = ChaCha8Rng::seed_from_u64(21);
        let mut formed = 0;
        for case in 0..150 {
            // (every fifth curve of degree 16 to 20, whose spans expand at the nearer end:
            // the right end's variable runs against u)
            let c = if case % 5 == 0 {
                let p = rng.random_range(16..=20usize);
                let n = p + 1 + rng.random_range(0..3usize);
                let mut kn = vec![0.0; p + 1];
                let mut inner: Vec<f64> =
                    (0..n - p - 1).map(|_| rng.random_range(0.1..0.9)).collect();
                inner.sort_by(f64::total_cmp);
                kn.extend(inner);
                kn.extend(vec![1.0; p + 1]);
                let pts = (0..n)
                    .map(|_| vec![rng.random_range(-10.0..10.0)])
                    .collect();
                let w = rng.random_bool(0.5).then(|| {
                    (0..n)
                        .map(|_| 10f64.powf(rng.random_range(-1.0..1.0)))
                        .collect()
                });
                NurbsCurve::new(p, kn, pts, w).unwrap()
            } else {
                random_curve(&mut rng, 1)
            };
            let t = TightEval::new(&c);
            let iv_eval = CurveEval::<Interval>::new(&c, 2);
            let kn = c.knots().to_vec();
            let p = c.degree();
            for k in p..c.num_points() {
                let (a, b) = (kn[k], kn[k + 1]);
                if a >= b {
                    continue;
                }
                for at_hi in [false, true] {
                    let w = (b - a) * 2f64.powf(-rng.random_range(0.0..50.0));
                    let (lo, hi) = if at_hi {
                        ((b - w).max(a), b)
                    } else {
                        (a, (a + w).min(b))
                    };
                    let Some(f) = t.end_form(0, k, lo, hi, at_hi) else {
                        continue;
                    };
                    formed += 1;
                    let e = if at_hi { hi } else { lo };
                    let d = iv_eval.derivs_in_span(k, &iv::point(e), 1);
                    assert!(!f.value.to_interval().intersection(d[0][0]).is_empty());
                    assert!(f.slope >= d[1][0].mig(), "{} < |{:?}|", f.slope, d[1][0]);
                    for i in 0..=16 {
                        let s = (lo + (hi - lo) * i as f64 / 16.0).clamp(lo, hi);
                        let v = t.coord_at(0, s);
                        // (at a knot coord_at is the next piece's value: use span k's own)
                        let own = iv_eval.derivs_in_span(k, &iv::point(s), 2);
                        assert!(
                            !own[0][0].intersection(f.range).is_empty()
                                && (s == b || !v.intersection(f.range).is_empty()),
                            "{c:?} k={k} [{lo}, {hi}] s={s}: {:?} misses {:?}",
                            (f.range.inf(), f.range.sup()),
                            (v.inf(), v.sup())
                        );
                        assert!(
                            !own[2][0].intersection(f.second).is_empty(),
                            "C'' at {s} outside {:?}",
                            (f.second.inf(), f.second.sup())
                        );
                        #[cfg(feature = "mpfr")]
                        if s < b || k + 1 == c.num_points() {
                            let x: Vec<rug::Float> = c.point(s).unwrap();
                            assert!(f.range.inf() <= x[0] && x[0] <= f.range.sup(), "s={s}");
                        }
                    }
                }
            }
        }
        assert!(formed > 200, "only {formed} forms");
    }

    /// At a symmetric curve's extremum at a knot (C' = 0 there), the form about the knot bounds
    /// a box a hundredth of the span wide within two ulps of C(knot), with C'' of one sign.
    #[test]
    fn end_form_at_a_knot_extremum_is_within_two_ulps() {
        let c = symmetric_at_a_knot();
        let t = TightEval::new(&c);
        let top = t.coord_at(1, 0.0);
        let ulp = f64::EPSILON * c.coord_scale(1);
        let w = 0.8147563086639935 / 100.0;
        for (k, lo, hi, at_hi) in [(3, -w, 0.0, true), (4, 0.0, w, false)] {
            let f = t.end_form(1, k, lo, hi, at_hi).expect("a form");
            assert!(f.second.sup() < 0.0, "C'' has its sign");
            assert!(
                f.range.sup() - top.sup() <= 2.0 * ulp,
                "{} vs {}",
                f.range.sup(),
                top.sup()
            );
        }
    }

    #[test]
    fn discontinuous_curve_boxes_contain_both_sides() {
        // Interior knot of multiplicity p + 1 = 3: a jump at u = 0.5 from P2 to P3.
        let c = NurbsCurve::new(
            2,
            vec![0., 0., 0., 0.5, 0.5, 0.5, 1., 1., 1.],
            vec![vec![0.], vec![1.], vec![1.], vec![5.], vec![6.], vec![7.]],
            None,
        )
        .unwrap();
        let t = TightEval::new(&c);
        assert_eq!(t.coord_at(0, 0.5), iv::point(5.0));
        for (a, b) in [(0.4, 0.5), (0.5 - 1e-12, 0.5), (0.45, 0.55), (0.5, 0.6)] {
            let e = t.coord_over(0, a, b);
            assert!(e.contains(5.0), "[{a}, {b}]: {e:?}");
            if a < 0.5 {
                // the left piece approaches 1 (not attained at u = 0.5, but enclosed)
                assert!(
                    e.inf() <= 1.0 - 0.0 && e.sup() >= 1.0 - 1e-9,
                    "[{a}, {b}]: {e:?}"
                );
            }
        }
    }

    /// Values at knots come from the span's end Bézier points (`TightEval::end_value`): on
    /// random curves they meet the span expansion's value (`ddi_at`) and interval de Boor's
    /// (`generic_at`, an independent kernel) at every knot of the domain, and stay within two
    /// ulps. (Fails with the wrong end point or row.)
    #[test]
    fn knot_values_are_the_span_end_points() {
        let mut rng = ChaCha8Rng::seed_from_u64(31);
        let mut checked = 0;
        for _ in 0..300 {
            let dim = rng.random_range(1..=3usize);
            let c = random_curve(&mut rng, dim);
            let t = TightEval::new(&c);
            let (a, b) = c.domain();
            let mut us: Vec<f64> = c
                .knots()
                .iter()
                .copied()
                .filter(|&u| a <= u && u <= b)
                .collect();
            us.dedup();
            for &u in &us {
                let k = c.find_span(u);
                for j in 0..dim {
                    let (v, d) = t.coord_at_tight(j, u);
                    let Some(d) = d else { continue };
                    let meet = |x: Interval| !x.intersection(v).is_empty();
                    assert!(meet(t.ddi_at(j, k, u).to_interval()), "{c:?} u={u} j={j}");
                    assert!(meet(t.generic_at(j, k, u)), "{c:?} u={u} j={j}");
                    let scale = (0..c.num_points())
                        .map(|i| c.control_point(i)[j].abs())
                        .fold(0.0, f64::max);
                    // (two: a value that is exactly a double with a radius of a few subnormals,
                    // from a division, rounds out to both neighbours)
                    assert!(
                        ulps(d.to_interval(), scale) <= 2.0,
                        "{c:?} u={u} j={j} {d:?}"
                    );
                    checked += 1;
                }
            }
        }
        assert!(checked > 1000, "{checked}");
    }

    /// A span already in Bézier form (its end knots of multiplicity >= p) takes its
    /// homogeneous control points as its Bézier points without a sweep (`TightEval::swept`):
    /// on piecewise Bézier splines of degree 1 to 12 (interior knots of multiplicity p, some
    /// of them lower, so that both routes run), rational or not, every span's points from
    /// the sweeping evaluator meet the `Ddi` extraction's (`HSpline::bezier_segment`, an
    /// independent route: both enclose the exact points), value by value, and a span in
    /// Bézier form gets exact points. Fails with the wrong block of control points or a span
    /// taken for Bézier form that is not.
    #[test]
    fn spans_in_bezier_form_are_their_control_points() {
        let mut rng = ChaCha8Rng::seed_from_u64(47);
        let (mut shortcut, mut swept) = (0, 0);
        for it in 0..200 {
            let p = 1 + it % 12;
            let dim = 1 + it % 3;
            let pieces = rng.random_range(1..=4usize);
            let mut knots = vec![0.0; p + 1];
            for i in 1..pieces {
                // (multiplicity p, or lower for some knots)
                let m = if rng.random_bool(0.7) {
                    p
                } else {
                    rng.random_range(1..=p)
                };
                knots.extend(std::iter::repeat_n(i as f64 * 0.75, m));
            }
            knots.extend(std::iter::repeat_n(pieces as f64 * 0.75, p + 1));
            let n = knots.len() - p - 1;
            let pts: Vec<Vec<f64>> = (0..n)
                .map(|_| (0..dim).map(|_| rng.random_range(-4.0..4.0)).collect())
                .collect();
            let w = rng
                .random_bool(0.5)
                .then(|| (0..n).map(|_| rng.random_range(0.25..4.0)).collect());
            let c = NurbsCurve::new(p, knots, pts, w).unwrap();
            let t = TightEval::sweeping(&c);
            let hs = HSpline::<Ddi>::from_curve(&c);
            let kn = c.knots();
            for k in p..n {
                if kn[k] == kn[k + 1] {
                    continue;
                }
                let bez = (k + 1 - p..=k).all(|i| kn[i] == kn[k])
                    && (k + 1..=k + p).all(|i| kn[i] == kn[k + 1]);
                let got = t.bezier_points(k);
                let want = hs.bezier_segment(k).pts;
                assert_eq!(got.len(), want.len());
                for (i, (g, w)) in got.iter().zip(&want).enumerate() {
                    let meet = !g.to_interval().intersection(w.to_interval()).is_empty();
                    assert!(meet, "{c:?} span {k} value {i}: {g:?} vs {w:?}");
                    if bez {
                        assert_eq!(g.rad(), 0.0, "{c:?} span {k} value {i}: {g:?}");
                    }
                }
                if bez {
                    shortcut += 1;
                } else {
                    swept += 1;
                }
            }
        }
        assert!(shortcut > 100 && swept > 20, "{shortcut} {swept}");
    }

    #[test]
    fn clamped_ends_are_exact_control_points() {
        // rational, clamped: C(a) = P_0 and C(b) = P_n exactly (no rounding of w P / w)
        let c = NurbsCurve::new(
            2,
            vec![0., 0., 0., 0.3, 1., 1., 1.],
            vec![
                vec![0.1, 3.0],
                vec![1.0, -2.0],
                vec![2.5, 0.7],
                vec![1.0 / 3.0, 0.2],
            ],
            Some(vec![0.7, 3.0, 0.01, 1.3]),
        )
        .unwrap();
        let t = TightEval::new(&c);
        assert_eq!(t.coord_at(0, 0.0), iv::point(0.1));
        assert_eq!(t.coord_at(1, 1.0), iv::point(0.2));
        // unclamped ends: an enclosure of the de Boor value (the generic path), not a
        // control point
        let u = NurbsCurve::new(
            2,
            vec![0., 1., 2., 3., 4., 5., 6.],
            vec![vec![0.0], vec![1.0], vec![4.0], vec![2.0]],
            None,
        )
        .unwrap();
        let (a, b) = u.domain();
        let tu = TightEval::new(&u);
        // C(2) = (P_0 + P_1) / 2 = 0.5 and C(4) = (P_2 + P_3) / 2 = 3 (uniform quadratic)
        assert!(tu.coord_at(0, a).contains(0.5) && tu.coord_at(0, a).wid() < 1e-15);
        assert!(tu.coord_at(0, b).contains(3.0) && tu.coord_at(0, b).wid() < 1e-15);
    }

    #[test]
    fn taylor_bounds_hold_at_every_sampled_point() {
        // T(h) = c1 h + c2 h^2 / 2 for |c1| <= g and c2 at the ends (T is linear in both) and
        // h on a grid plus the vertex -c1/c2: every value must lie in the bounds.
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        for _ in 0..20000 {
            let mut v = |s: f64| rng.random_range(-1.0..1.0) * 10f64.powf(s);
            let (a, b) = (v(0.0), v(-3.0));
            let c1 = iv::span(a.min(a + b), a.max(a + b));
            let (p, q) = (v(1.0), v(-1.0));
            let c2 = iv::span(p.min(p + q), p.max(p + q));
            let r = v(0.0).abs();
            let g = c1.inf().abs().max(c1.sup().abs());
            let (l, u) = taylor_bounds(g, c2, r);
            for x in [c1.inf(), c1.sup(), -g, g] {
                for y in [c2.inf(), c2.sup()] {
                    let mut hs: Vec<f64> =
                        (0..=40).map(|i| -r + 2.0 * r * i as f64 / 40.0).collect();
                    if y != 0.0 && (x / y).abs() <= r {
                        hs.push(-x / y);
                    }
                    for h in hs {
                        let t = x * h + y * h * h / 2.0;
                        // f64 evaluation of T: allow its own rounding (relative 1e-15)
                        let tol = 1e-15 * (x.abs() * r + y.abs() * r * r);
                        assert!(
                            l <= t + tol && t - tol <= u,
                            "{c1:?} {c2:?} r={r} h={h}: {t} not in [{l}, {u}]"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn huge_coordinates_and_extreme_weights_stay_sound() {
        let c = NurbsCurve::new(
            3,
            vec![0., 0., 0., 0., 0.5, 1., 1., 1., 1.],
            vec![
                vec![1e300, -1e-300],
                vec![-1.5e300, 3e-300],
                vec![1.7e308, 0.0],
                vec![-1e300, 1e-300],
                vec![1e299, 2e-300],
            ],
            Some(vec![1e-6, 1e6, 1.0, 1e6, 1e-6]),
        )
        .unwrap();
        let t = TightEval::new(&c);
        for i in 0..=64 {
            let u = i as f64 / 64.0;
            let p = t.point(u);
            let naive: Vec<Interval> = c.point(u).unwrap();
            for j in 0..2 {
                assert!(!p[j].is_empty());
                assert!(!p[j].intersection(naive[j]).is_empty() || naive[j].is_empty());
            }
            let o = t.coord_over(0, u, (u + 1e-3).min(1.0));
            assert!(p[0].subset(o) || !p[0].intersection(o).is_empty());
        }
    }

    /// Extreme scales: coordinates scaled by 10^±300, weights spread over 10^±6. coord_at must
    /// contain the 256-bit value (or be ENTIRE after overflow) and be <= 2 ulps of the scale
    /// wide when finite.
    #[cfg(feature = "mpfr")]
    #[test]
    fn coord_at_extreme_scales_mpfr() {
        let mut rng = ChaCha8Rng::seed_from_u64(14);
        let (mut entire, mut total) = (0, 0);
        for _ in 0..200 {
            let c0 = random_curve(&mut rng, 1);
            let f = 10f64.powi(rng.random_range(-300..=300));
            let pts: Vec<f64> = c0.points_flat().iter().map(|x| x * f).collect();
            let w: Vec<f64> = (0..c0.num_points())
                .map(|_| 10f64.powf(rng.random_range(-6.0..6.0)))
                .collect();
            let c =
                NurbsCurve::from_flat(c0.degree(), 1, c0.knots().to_vec(), pts, Some(w)).unwrap();
            let t = TightEval::new(&c);
            let (a, b) = c.domain();
            for _ in 0..10 {
                let u = rng.random_range(a..=b);
                let x: Vec<rug::Float> = c.point(u).unwrap();
                let v = t.coord_at(0, u);
                total += 1;
                if v.is_entire() {
                    entire += 1;
                    continue;
                }
                assert!(
                    v.inf() <= x[0] && x[0] <= v.sup(),
                    "{c:?} u={u}: {v:?} misses {}",
                    x[0]
                );
                assert!(
                    ulps(v, c.coord_scale(0)) <= 2.0,
                    "{v:?} scale {}",
                    c.coord_scale(0)
                );
            }
        }
        println!("extreme scales: {entire} of {total} ENTIRE");
        assert!(entire * 10 < total);
    }

    /// Boxes of several widths around the critical points of random curves: containment of the
    /// 256-bit values at sampled parameters, and the extremal side within one ulp (of the
    /// coordinate scale) of the point value at the critical point.
    #[cfg(feature = "mpfr")]
    #[test]
    fn coord_over_at_critical_points_mpfr() {
        let mut rng = ChaCha8Rng::seed_from_u64(12);
        let mut worst: f64 = 0.0;
        let mut count = 0;
        for case in 0..300 {
            let c = random_curve(&mut rng, 1);
            // every other curve at an extreme scale: coordinates * 10^±300, weights 10^±6
            let c = if case % 2 == 0 {
                c
            } else {
                let f = 10f64.powi(rng.random_range(-300..=300));
                let pts: Vec<f64> = c.points_flat().iter().map(|x| x * f).collect();
                let w: Vec<f64> = (0..c.num_points())
                    .map(|_| 10f64.powf(rng.random_range(-6.0..6.0)))
                    .collect();
                NurbsCurve::from_flat(c.degree(), 1, c.knots().to_vec(), pts, Some(w)).unwrap()
            };
            let t = TightEval::new(&c);
            let f = CurveEval::<f64>::new(&c, 2);
            let (a, b) = c.domain();
            for i in 0..8 {
                // f64 Newton on C' from a start point; keep it if it converged inside the span.
                let mut u = a + (b - a) * (i as f64 + 0.5) / 8.0;
                let k0 = c.find_span(u);
                let (s0, s1) = (c.knots()[k0], c.knots()[k0 + 1]);
                for _ in 0..60 {
                    let d = f.derivs(u, 2).unwrap();
                    u = (u - d[1][0] / d[2][0]).clamp(s0, s1);
                }
                let d = f.derivs(u, 2).unwrap();
                if !(u > s0 && u < s1) || d[1][0].abs() > 1e-9 * c.coord_scale(0) {
                    continue;
                }
                let scale = c.coord_scale(0);
                let ulp = f64::EPSILON * scale;
                let at = t.coord_at(0, u);
                for w in [0.0, 1e-15, 1e-12, 1e-9, 1e-7] {
                    let (lo, hi) = ((u - w).max(s0), (u + w).min(s1));
                    let e = t.coord_over(0, lo, hi);
                    for i in 0..=20 {
                        let s = (lo + (hi - lo) * i as f64 / 20.0).min(hi);
                        let x: Vec<rug::Float> = c.point(s).unwrap();
                        assert!(
                            e.inf() <= x[0] && x[0] <= e.sup(),
                            "{c:?} [{lo}, {hi}]: {e:?} misses {} at {s}",
                            x[0]
                        );
                    }
                    // extremal side: a max (C'' < 0) has its top near C(u), a min its bottom
                    let excess = if d[2][0] < 0.0 {
                        e.sup() - at.sup()
                    } else {
                        at.inf() - e.inf()
                    };
                    // Where the second-order term over the box, |C''| w^2 / 2, is below an ulp
                    // the box must be within 2 ulps on the extremal side.
                    if d[2][0].abs() * w * w <= ulp {
                        worst = worst.max(excess / ulp);
                        assert!(
                            excess <= 2.0 * ulp,
                            "w={w} C''={} scale={scale}: excess {} ulps",
                            d[2][0],
                            excess / ulp
                        );
                    }
                    count += 1;
                }
            }
        }
        println!("coord_over at critical points: {count} boxes, worst extremal excess {worst:.3} ulps of scale");
        assert!(count > 100);
    }

    /// Against 256-bit MPFR on random curves: containment always, width <= 2 ulps of the
    /// coordinate scale; prints the width distribution (run with --nocapture).
    #[cfg(feature = "mpfr")]
    #[test]
    fn coord_at_contains_mpfr_and_width_stats() {
        let mut rng = ChaCha8Rng::seed_from_u64(9);
        let mut widths: Vec<f64> = Vec::new();
        for _ in 0..300 {
            let c = random_curve(&mut rng, 2);
            let t = TightEval::new(&c);
            let (a, b) = c.domain();
            for _ in 0..20 {
                let u = rng.random_range(a..=b);
                let exact: Vec<rug::Float> = c.point(u).unwrap();
                for (j, x) in exact.iter().enumerate() {
                    let v = t.coord_at(j, u);
                    assert!(
                        v.inf() <= *x && *x <= v.sup(),
                        "{c:?} u={u} j={j}: {v:?} misses {x}"
                    );
                    let w = ulps(v, c.coord_scale(j));
                    assert!(w <= 2.0, "width {w} ulps at u={u}");
                    widths.push(w);
                }
            }
        }
        widths.sort_by(f64::total_cmp);
        println!(
            "coord_at width in ulps of coord scale: median {:.3}, p90 {:.3}, max {:.3} (n = {})",
            widths[widths.len() / 2],
            widths[widths.len() * 9 / 10],
            widths[widths.len() - 1],
            widths.len()
        );
    }
}
