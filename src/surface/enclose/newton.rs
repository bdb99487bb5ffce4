//! `newton`: the thesis's candidate method (ch. 6) carried over to surfaces.
//!
//! Float first (not in the thesis): every side goes through the proofs of module `fast`
//! (shared with `bezier`); if all are proven, that is the result; otherwise the search below
//! runs for the whole surface and the proven sides keep the tighter of both (sound) results.
//!
//! The extrema of S_j over the closed domain lie (a) on the four boundary curves, (b) on the
//! lines where S is not differentiable (knots of multiplicity >= the degree in u or v), or
//! (c) at interior critical points, grad S_j = 0, of the cells between those lines (S is C^1
//! there). So:
//!
//! * **Lines.** Every boundary and knot line whose iso-curve is exactly a row or column of the
//!   net ([`NurbsSurface::exact_row_at`]: a clamped end, or a knot of multiplicity >= p) is
//!   that [`crate::NurbsCurve`], enclosed by the curve `newton` strategy itself (its driver,
//!   candidates and certificates). Its outer bounds are outer material; its inner bounds are
//!   attained where the row is the surface's value (not for the left limit at a knot of
//!   multiplicity p + 1). An unclamped boundary has no exact row; it is searched below as a
//!   degenerate box (one side of zero width, the 1-D version of the same tests).
//! * **Corners.** The four domain corners, enclosed exactly ([`super::corner_values`]).
//! * **Interior.** Branch and bound over parameter boxes inside one Bézier span pair, all
//!   coordinates and both sides at once. On a box X: the enclosures of S, grad S and the
//!   Hessian over X (the tensor de Boor of [`crate::surface::SurfaceEval`] with an enclosure
//!   of X as parameters, in rigorous midpoint-radius arithmetic [`crate::Mr`]), the value at the centre c in double-double intervals ([`crate::Ddi`]), and the
//!   value enclosure V = S(X) ∩ (S(c) + S_u(X)(X_u - c_u) + S_v(X)(X_v - c_v)) (mean value form).
//!   A side of S_j is dropped on X when V cannot beat the best attained value (its lower
//!   bound is kept), when 0 is not in S_j,u(X) or S_j,v(X) (no critical point in X), or when
//!   the Krawczyk operator K(X) = c - Y g(c) + (I - Y H(X))(X - c) (g = grad S_j, H its
//!   Hessian enclosure, Y ~ mid(H)^-1) misses X (no zero of g in X). If K(X) lies in the
//!   interior of X, g has exactly one zero in X (Krawczyk 1969; Moore's theorem); the box is
//!   contracted X <- K(X) ∩ X to a few ulps and its value enclosure is the candidate. Boxes
//!   that stay undecided are bisected in the direction that contributes most to the width of
//!   V (so a ridge, a line of critical points where Krawczyk can never decide, is cut into
//!   thin strips across it rather than squares).
//! * **Bounded work.** A coordinate that ends at a limit is intersected with the `bezier`
//!   strategy's bounds (both sound; see `enclose_prepared`). At the box budget or the depth limit the undecided boxes are enclosed
//!   by their interval values V (the parent's, already computed): still sound, and tight
//!   where the boxes are small (a ridge ends in strips of width 2^-depth of its span, whose
//!   mean value enclosures exceed the ridge value by O(width^2)), never the control-net box.

use super::{coord_box, corner_values, enclosure, SurfaceEncloser};
use crate::enclose::{Enclosure, Guarantee, Newton, Settings, Stats, Termination};
use crate::num::{iv, Ddi, Mr, Scalar};
use crate::surface::eval::SurfaceEval;
use crate::surface::model::NurbsSurface;
use crate::BoxEncloser;
use inari::Interval;
use std::collections::VecDeque;

/// The surface Newton strategy.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceNewton {
    /// the curve strategy for the boundary and knot-line curves
    pub curve: Newton,
    /// relative tolerance: a box whose value cannot beat the best attained value by more
    /// than `tol * scale` is settled
    pub tol: f64,
    /// budget of interior box evaluations (all coordinates together) for a bicubic patch,
    /// scaled to the degree (see `scaled_budget`)
    pub max_boxes: u64,
    /// deepest bisection (halvings of a span side)
    pub max_depth: u32,
    /// float first, prove after (the `fast` module, shared with `bezier`); the search below
    /// runs only if some side is not proven there. Off only for comparisons.
    pub fast_path: bool,
}

impl Default for SurfaceNewton {
    fn default() -> Self {
        SurfaceNewton {
            curve: Newton::default(),
            tol: f64::EPSILON,
            max_boxes: 4000,
            max_depth: 44,
            fast_path: true,
        }
    }
}

impl SurfaceNewton {
    /// With the registry's settings (tolerance for the surface and its curves).
    pub fn with_settings(s: &Settings) -> Self {
        let d = SurfaceNewton::default();
        SurfaceNewton {
            curve: s.newton(),
            tol: s
                .tol
                .filter(|t| t.is_finite() && *t >= 0.0)
                .unwrap_or(d.tol),
            ..d
        }
    }
}

/// Per target (coordinate j, side): signed so that both sides are minimisations of sign * S_j.
#[derive(Debug, Clone, Copy)]
struct Target {
    /// outer lower bound of sign * S_j
    lo: f64,
    /// sign * S_j attains a value <= best
    best: f64,
    term: Termination,
}

#[derive(Debug, Clone)]
struct Cell {
    u: (f64, f64),
    v: (f64, f64),
    ku: usize,
    kv: usize,
    du: u32,
    dv: u32,
    /// targets (2 j + side) still open on this box
    alive: Vec<usize>,
    /// the parent's value enclosures (all coordinates), valid on this box
    parent: Vec<Interval>,
}

enum Kraw {
    Excluded,
    Unique(Interval, Interval),
    Unknown,
}

fn sign_of(t: usize) -> f64 {
    if t % 2 == 0 {
        1.0
    } else {
        -1.0
    }
}

fn signed(x: Interval, s: f64) -> Interval {
    if s > 0.0 {
        x
    } else {
        -x
    }
}

/// Krawczyk's operator for g = (S_u, S_v) on X = xu x xv with g(c) at the exact centre c and
/// the Jacobian (the Hessian of S_j) enclosed over X. Any real Y gives a valid operator: every
/// zero of g in X lies in K(X); K(X) in the interior of X proves exactly one.
fn krawczyk(xu: Interval, xv: Interval, c: (f64, f64), g: [Interval; 2], h: [Interval; 3]) -> Kraw {
    let (m00, m01, m11) = (h[0].mid(), h[1].mid(), h[2].mid());
    let det = m00 * m11 - m01 * m01;
    if !(det.is_finite() && det != 0.0) {
        return Kraw::Unknown;
    }
    let y = [[m11 / det, -m01 / det], [-m01 / det, m00 / det]];
    if y.iter().flatten().any(|x| !x.is_finite()) {
        return Kraw::Unknown;
    }
    let p = iv::point;
    let jm = [[h[0], h[1]], [h[1], h[2]]];
    let dx = [xu - p(c.0), xv - p(c.1)];
    let mut k = [Interval::EMPTY; 2];
    for r in 0..2 {
        let yg = p(y[r][0]) * g[0] + p(y[r][1]) * g[1];
        let mut acc = p([c.0, c.1][r]) - yg;
        for col in 0..2 {
            let yj = p(y[r][0]) * jm[0][col] + p(y[r][1]) * jm[1][col];
            let m = p(if r == col { 1.0 } else { 0.0 }) - yj;
            acc += m * dx[col];
        }
        k[r] = acc;
    }
    let (a, b) = (k[0].intersection(xu), k[1].intersection(xv));
    if a.is_empty() || b.is_empty() {
        return Kraw::Excluded;
    }
    let inside = |k: Interval, x: Interval| k.inf() > x.inf() && k.sup() < x.sup();
    if inside(k[0], xu) && inside(k[1], xv) {
        Kraw::Unique(a, b)
    } else {
        Kraw::Unknown
    }
}

/// What one box evaluation gives: per coordinate V (value over X), S(c) tight, gradient and
/// Hessian over X, gradient at c.
struct BoxEval {
    value: Vec<Interval>,
    centre: Vec<Interval>,
    grad: Vec<[Interval; 2]>,
    hess: Vec<[Interval; 3]>,
    grad_c: Vec<[Interval; 2]>,
    c: (f64, f64),
}

struct Evaluators {
    /// box enclosures in rigorous midpoint-radius f64 ([`Mr`], ~10x faster than `Interval`
    /// in the corner cutting, a few ulps wider), converted to intervals
    fast: SurfaceEval<Mr>,
    /// the same in `Interval` (a few ulps tighter), for boxes below 2^-15 of their span in
    /// a direction, where the last ulps are decided
    tight: SurfaceEval<Interval>,
    dd: SurfaceEval<Ddi>,
}

type Grid<S> = Vec<Vec<Option<Vec<S>>>>;

fn to_intervals(g: Grid<Mr>) -> Grid<Interval> {
    g.into_iter()
        .map(|r| {
            r.into_iter()
                .map(|o| o.map(|x| x.iter().map(Scalar::to_interval).collect()))
                .collect()
        })
        .collect()
}

impl Evaluators {
    fn eval(&self, xu: Interval, xv: Interval, ku: usize, kv: usize) -> BoxEval {
        let c = (xu.mid(), xv.mid());
        let c = (c.0.clamp(xu.inf(), xu.sup()), c.1.clamp(xv.inf(), xv.sup()));
        let net = self.fast.net();
        let small = |x: Interval, k: &[f64], i: usize| {
            x.wid() <= (0.5 * k[i + 1] - 0.5 * k[i]) * 2f64.powi(-15)
        };
        let (all, at) = if small(xu, &net.ku, ku) || small(xv, &net.kv, kv) {
            let (pu, pv) = (iv::point(c.0), iv::point(c.1));
            (
                self.tight.derivs_in_span(ku, kv, &xu, &xv, (2, 2, 2)),
                self.tight.derivs_in_span(ku, kv, &pu, &pv, (1, 1, 1)),
            )
        } else {
            let (bu, bv) = (
                Mr::from_bounds(xu.inf(), xu.sup()),
                Mr::from_bounds(xv.inf(), xv.sup()),
            );
            let (cu, cv) = (Mr::from_f64(c.0), Mr::from_f64(c.1));
            (
                to_intervals(self.fast.derivs_in_span(ku, kv, &bu, &bv, (2, 2, 2))),
                to_intervals(self.fast.derivs_in_span(ku, kv, &cu, &cv, (1, 1, 1))),
            )
        };
        let dd =
            self.dd
                .derivs_in_span(ku, kv, &Ddi::from_f64(c.0), &Ddi::from_f64(c.1), (0, 0, 0));
        let g = |a: usize, b: usize| all[a][b].as_ref().expect("a + b <= 2");
        let d = g(0, 0).len();
        let sc: Vec<Interval> = (0..d)
            .map(|j| {
                let x = at[0][0].as_ref().expect("value")[j];
                let m = x.intersection(dd[0][0].as_ref().expect("value")[j].to_interval());
                if m.is_empty() {
                    x
                } else {
                    m
                }
            })
            .collect();
        let (du, dv) = (xu - iv::point(c.0), xv - iv::point(c.1));
        let value = (0..d)
            .map(|j| {
                let mv = sc[j] + g(1, 0)[j] * du + g(0, 1)[j] * dv;
                let m = g(0, 0)[j].intersection(mv);
                if m.is_empty() {
                    g(0, 0)[j]
                } else {
                    m
                }
            })
            .collect();
        let gc = |a: usize, b: usize, j: usize| at[a][b].as_ref().expect("a + b <= 1")[j];
        BoxEval {
            value,
            centre: sc,
            grad: (0..d).map(|j| [g(1, 0)[j], g(0, 1)[j]]).collect(),
            hess: (0..d)
                .map(|j| [g(2, 0)[j], g(1, 1)[j], g(0, 2)[j]])
                .collect(),
            grad_c: (0..d).map(|j| [gc(1, 0, j), gc(0, 1, j)]).collect(),
            c,
        }
    }
}

/// The parameter lines enclosed as curves (clamped domain sides and knot lines of
/// multiplicity >= the degree), per direction.
struct Covered {
    u: Vec<f64>,
    v: Vec<f64>,
}

impl Covered {
    fn covers_u(&self, x: f64) -> bool {
        self.u.contains(&x)
    }
    fn covers_v(&self, y: f64) -> bool {
        self.v.contains(&y)
    }
}

fn cuts(a: f64, b: f64, kinks: &[f64], unclamped: [bool; 2]) -> Vec<f64> {
    let mut v: Vec<f64> = kinks.to_vec();
    if !unclamped[0] {
        v.push(a);
    }
    if !unclamped[1] {
        v.push(b);
    }
    v
}

/// A point candidate (the end of a monotone degenerate box): its verified value.
fn point_min(s: &NurbsSurface, u: f64, v: f64, t: usize, x: &mut Target, st: &mut Stats) {
    st.point_evaluations += 1;
    let e = s
        .enclose_derivative(u, v, 0, 0)
        .map(|p| signed(p[t / 2], sign_of(t)))
        .unwrap_or(Interval::ENTIRE);
    x.lo = x.lo.min(e.inf());
    x.best = x.best.min(e.sup());
}

impl SurfaceNewton {
    /// The boundary and knot-line curves (outer bounds; inner bounds where attained).
    fn lines(&self, s: &NurbsSurface, tg: &mut [Target], st: &mut [Stats]) -> [bool; 4] {
        let ((a, b), (c, d)) = s.domain();
        let t = s.transposed();
        let mut unclamped = [false; 4];
        for (dir, surf) in [(0, s), (1, &t)] {
            let ((lo, hi), _) = surf.domain();
            let mut cuts = vec![lo];
            cuts.extend(if dir == 0 {
                s.kink_knots_u()
            } else {
                s.kink_knots_v()
            });
            cuts.push(hi);
            let mut rows: Vec<(usize, bool)> = Vec::new();
            for &x in &cuts {
                let right = surf.exact_row_at(x, false);
                let left = surf.exact_row_at(x, true);
                if x == lo && right.is_none() {
                    unclamped[2 * dir] = true;
                }
                if x == hi && left.is_none() {
                    unclamped[2 * dir + 1] = true;
                }
                // attained: the value at x (the right row; at the domain end, the left one)
                for (r, att) in [(right, true), (left, x == hi)] {
                    if let Some(r) = r {
                        match rows.iter_mut().find(|e| e.0 == r) {
                            Some(e) => e.1 |= att,
                            None => rows.push((r, att)),
                        }
                    }
                }
            }
            for (r, attained) in rows {
                let e = self.curve.enclose(&surf.row_curve(r));
                for (j, cb) in e.coords.iter().enumerate() {
                    st[j].add(&cb.stats);
                    for (side, sg) in [(0, 1.0), (1, -1.0)] {
                        let x = &mut tg[2 * j + side];
                        let (lo, inner) = if sg > 0.0 {
                            (cb.lo, cb.inner_lo)
                        } else {
                            (-cb.hi, -cb.inner_hi)
                        };
                        x.lo = x.lo.min(lo);
                        if attained {
                            x.best = x.best.min(inner);
                        }
                        if !matches!(cb.termination, Termination::Converged | Termination::Direct) {
                            x.term = cb.termination;
                        }
                    }
                }
            }
        }
        let _ = (a, b, c, d);
        unclamped
    }

    /// The interior search (see the module docs).
    fn interior(&self, s: &NurbsSurface, unclamped: [bool; 4], tg: &mut [Target], st: &mut Stats) {
        let ev = Evaluators {
            fast: SurfaceEval::new(s, 2, 2, 2),
            tight: SurfaceEval::new(s, 2, 2, 2),
            dd: SurfaceEval::new(s, 0, 0, 0),
        };
        let net = ev.fast.net();
        let (su, sv) = (net.spans_u(), net.spans_v());
        let ((a, b), (c, d)) = s.domain();
        let (ku_, kv_) = (&net.ku, &net.kv);
        let dim = s.dim();
        let scale: Vec<f64> = (0..dim).map(|j| s.coord_scale(j)).collect();
        let all: Vec<usize> = (0..2 * dim).collect();
        let entire = vec![Interval::ENTIRE; dim];
        let mut q: VecDeque<Cell> = VecDeque::new();
        let mut push = |u: (f64, f64), v: (f64, f64), ku: usize, kv: usize| {
            q.push_back(Cell {
                u,
                v,
                ku,
                kv,
                du: 0,
                dv: 0,
                alive: all.clone(),
                parent: entire.clone(),
            })
        };
        for &ku in &su {
            for &kv in &sv {
                push((ku_[ku], ku_[ku + 1]), (kv_[kv], kv_[kv + 1]), ku, kv);
            }
        }
        // unclamped boundaries: degenerate boxes along them
        for (side, x) in [(0usize, a), (1, b)] {
            if unclamped[side] {
                let ku = net.span_u(x);
                for &kv in &sv {
                    push((x, x), (kv_[kv], kv_[kv + 1]), ku, kv);
                }
            }
        }
        for (side, y) in [(2usize, c), (3, d)] {
            if unclamped[side] {
                let kv = net.span_v(y);
                for &ku in &su {
                    push((ku_[ku], ku_[ku + 1]), (y, y), ku, kv);
                }
            }
        }
        let lines = Covered {
            u: cuts(a, b, &s.kink_knots_u(), [unclamped[0], unclamped[1]]),
            v: cuts(c, d, &s.kink_knots_v(), [unclamped[2], unclamped[3]]),
        };
        let mut boxes = 0u64;
        let budget = super::scaled_budget(self.max_boxes, s);
        while let Some(cell) = q.pop_front() {
            if boxes >= budget {
                // budget spent: the parent's enclosures of what is left (sound)
                for &t in &cell.alive {
                    let x = &mut tg[t];
                    x.lo = x.lo.min(signed(cell.parent[t / 2], sign_of(t)).inf());
                    x.term = Termination::WorkLimit;
                }
                continue;
            }
            boxes += 1;
            let xu = iv::span(cell.u.0, cell.u.1);
            let xv = iv::span(cell.v.0, cell.v.1);
            let e = ev.eval(xu, xv, cell.ku, cell.kv);
            st.point_evaluations += 2;
            st.derivative_evaluations += 1;
            let (fu, fv) = (cell.u.0 == cell.u.1, cell.v.0 == cell.v.1);
            let mut alive = Vec::new();
            let mut reduced: Vec<Cell> = Vec::new();
            for &t in &cell.alive {
                let (j, sg) = (t / 2, sign_of(t));
                let x = &mut tg[t];
                x.best = x.best.min(signed(e.centre[j], sg).sup());
                let vs = signed(e.value[j], sg);
                if vs.inf() >= x.best - self.tol * scale[j] {
                    x.lo = x.lo.min(vs.inf());
                    continue;
                }
                let [gu, gv] = e.grad[j];
                // Monotone in u on X (signed S_u >= 0 or <= 0, zero allowed): for every v the
                // minimum over [u0, u1] is at one side, so the minimum over X is on that edge
                // of X. A covered line (a clamped boundary or a knot line, enclosed as a
                // curve) drops X; otherwise the edge is searched as a degenerate box. The same
                // in v; on a degenerate box the minimum is at an end point.
                let (su, sv) = (signed(gu, sg), signed(gv, sg));
                let mono = |g: Interval, x0: f64, x1: f64| {
                    if g.inf() >= 0.0 {
                        Some(x0)
                    } else if g.sup() <= 0.0 {
                        Some(x1)
                    } else {
                        None
                    }
                };
                if let Some(x) = mono(su, cell.u.0, cell.u.1).filter(|_| !fu) {
                    if fv {
                        point_min(s, x, cell.v.0, t, &mut tg[t], st);
                    } else if !lines.covers_u(x) {
                        reduced.push(Cell {
                            u: (x, x),
                            alive: vec![t],
                            parent: e.value.clone(),
                            ..cell.clone()
                        });
                    }
                    continue;
                }
                if let Some(y) = mono(sv, cell.v.0, cell.v.1).filter(|_| !fv) {
                    if fu {
                        point_min(s, cell.u.0, y, t, &mut tg[t], st);
                    } else if !lines.covers_v(y) {
                        reduced.push(Cell {
                            v: (y, y),
                            alive: vec![t],
                            parent: e.value.clone(),
                            ..cell.clone()
                        });
                    }
                    continue;
                }
                let zero_u = fu || gu.contains(0.0);
                let zero_v = fv || gv.contains(0.0);
                if !(zero_u && zero_v) {
                    continue; // no critical point (of the open cell, or of the line) in X
                }
                if !fu && !fv {
                    match krawczyk(xu, xv, e.c, e.grad_c[j], e.hess[j]) {
                        Kraw::Excluded => {
                            st.newton_iterations += 1;
                            continue;
                        }
                        Kraw::Unique(ru, rv) => {
                            st.newton_iterations += 1;
                            let tol = self.tol * scale[j];
                            let (refined, evals) =
                                self.refine(&ev, j, sg, tol, ru, rv, cell.ku, cell.kv, st);
                            // the contraction's evaluations count against the budget too
                            boxes += evals;
                            if let Some(v) = refined {
                                let x = &mut tg[t];
                                x.lo = x.lo.min(signed(v.0, sg).inf());
                                x.best = x.best.min(signed(v.1, sg).sup());
                                continue;
                            }
                            // not contracted to the tolerance: bisect as undecided
                        }
                        Kraw::Unknown => st.newton_iterations += 1,
                    }
                }
                alive.push(t);
            }
            q.extend(reduced);
            if alive.is_empty() {
                continue;
            }
            let deep_u = fu || cell.du >= self.max_depth;
            let deep_v = fv || cell.dv >= self.max_depth;
            if deep_u && deep_v {
                for &t in &alive {
                    let x = &mut tg[t];
                    x.lo = x.lo.min(signed(e.value[t / 2], sign_of(t)).inf());
                    if x.term == Termination::Converged {
                        x.term = Termination::DepthLimit;
                    }
                }
                continue;
            }
            // the direction whose term contributes most to the width of V
            let wu = xu.wid();
            let wv = xv.wid();
            let (mut cu, mut cv) = (0.0f64, 0.0f64);
            for &t in &alive {
                cu = cu.max(e.grad[t / 2][0].mag() * wu);
                cv = cv.max(e.grad[t / 2][1].mag() * wv);
            }
            let split_u = if deep_v {
                true
            } else if deep_u {
                false
            } else if cu != cv {
                cu > cv
            } else {
                cell.du <= cell.dv
            };
            st.subdivisions += 1;
            let halves = if split_u {
                // halves first: no overflow for knots near ±f64::MAX; m stays in the box
                let m = (0.5 * cell.u.0 + 0.5 * cell.u.1).clamp(cell.u.0, cell.u.1);
                [((cell.u.0, m), cell.v), ((m, cell.u.1), cell.v)]
            } else {
                let m = (0.5 * cell.v.0 + 0.5 * cell.v.1).clamp(cell.v.0, cell.v.1);
                [(cell.u, (cell.v.0, m)), (cell.u, (m, cell.v.1))]
            };
            for (u, v) in halves {
                q.push_back(Cell {
                    u,
                    v,
                    ku: cell.ku,
                    kv: cell.kv,
                    du: cell.du + split_u as u32,
                    dv: cell.dv + !split_u as u32,
                    alive: alive.clone(),
                    parent: e.value.clone(),
                });
            }
        }
    }

    /// Contract a box proved to hold exactly one zero of grad S_j (X <- K(X) ∩ X while it
    /// shrinks): (value enclosure over the final box, tight value at its centre), or `None`
    /// if the value enclosure is still wider than `tol` beyond the centre value (the caller
    /// bisects then).
    #[allow(clippy::too_many_arguments)]
    fn refine(
        &self,
        ev: &Evaluators,
        j: usize,
        sg: f64,
        tol: f64,
        mut xu: Interval,
        mut xv: Interval,
        ku: usize,
        kv: usize,
        st: &mut Stats,
    ) -> (Option<(Interval, Interval)>, u64) {
        let mut e = ev.eval(xu, xv, ku, kv);
        let mut evals = 1;
        let settled = |e: &BoxEval| {
            let (v, c) = (signed(e.value[j], sg), signed(e.centre[j], sg));
            v.inf() >= c.sup() - tol
        };
        // contract while Krawczyk shrinks the box (quadratically near the zero), then judge
        for _ in 0..60 {
            st.newton_iterations += 1;
            st.derivative_evaluations += 1;
            match krawczyk(xu, xv, e.c, e.grad_c[j], e.hess[j]) {
                Kraw::Unique(a, b) => {
                    let shrunk = a.wid() < xu.wid() || b.wid() < xv.wid();
                    xu = a;
                    xv = b;
                    e = ev.eval(xu, xv, ku, kv);
                    evals += 1;
                    if !shrunk {
                        break;
                    }
                }
                // the zero is in the current box already (proved on a larger one)
                _ => break,
            }
        }
        (settled(&e).then_some((e.value[j], e.centre[j])), evals)
    }
}

impl SurfaceEncloser for SurfaceNewton {
    fn name(&self) -> &'static str {
        "newton"
    }
    fn guarantee(&self) -> Guarantee {
        Guarantee::Verified
    }
    fn enclose_prepared(&self, s: &NurbsSurface) -> Enclosure {
        let t0 = crate::enclose::Clock::start();
        let d = s.dim();
        // Float first: every side proven by the fast path, or the search below for all
        // (then the proven sides keep the tighter of both results; both are sound).
        let mut fast_st = vec![Stats::default(); d];
        let fast: Vec<[Option<(f64, f64, f64)>; 2]> = match self
            .fast_path
            .then(|| super::fast::FastSurface::new(s))
            .flatten()
        {
            Some(f) => (0..d)
                .map(|j| {
                    let st = &mut fast_st[j];
                    [f.side(j, -1.0, st), f.side(j, 1.0, st)]
                })
                .collect(),
            None => vec![[None, None]; d],
        };
        if fast.iter().flatten().all(Option::is_some) {
            let coords = (0..d)
                .map(|j| {
                    let [(nlo, nilo, wlo), (hi, ihi, whi)] = fast[j].map(|x| x.expect("proven"));
                    let mut st = fast_st[j];
                    if j == 0 {
                        st.time_total = t0.elapsed();
                    }
                    let mut cb = coord_box(-nlo, hi, -nilo, ihi, st, Termination::Converged);
                    (cb.witness_lo, cb.witness_hi) = (-wlo, whi);
                    cb
                })
                .collect();
            return enclosure(self.name(), true, coords);
        }
        let mut tg = vec![
            Target {
                lo: f64::INFINITY,
                best: f64::INFINITY,
                term: Termination::Converged,
            };
            2 * d
        ];
        let mut st = vec![Stats::default(); d];
        let unclamped = self.lines(s, &mut tg, &mut st);
        for (k, cv) in corner_values(s).into_iter().enumerate() {
            let _ = k;
            for (j, x) in cv.into_iter().enumerate() {
                for side in 0..2 {
                    let t = &mut tg[2 * j + side];
                    let y = signed(x, sign_of(side));
                    t.lo = t.lo.min(y.inf());
                    t.best = t.best.min(y.sup());
                }
            }
        }
        let mut shared = Stats::default();
        self.interior(s, unclamped, &mut tg, &mut shared);
        st[0].add(&shared);
        st[0].time_total = t0.elapsed();
        let mut coords: Vec<_> = (0..d)
            .map(|j| {
                let (mn, mx) = (tg[2 * j], tg[2 * j + 1]);
                let term = match mn.term {
                    Termination::Converged => mx.term,
                    t => t,
                };
                coord_box(mn.lo, -mx.lo, mn.best, -mx.best, st[j], term)
            })
            .collect();
        // A coordinate left at a work limit is intersected with the Bézier strategy's bounds
        // (both boxes are verified outer bounds, both inner bounds attained values): its
        // coefficient-ratio bounds need no derivatives and stay tight where the interval
        // derivatives of a badly conditioned rational surface are too wide to decide anything.
        if coords
            .iter()
            .any(|c| c.termination != Termination::Converged)
        {
            let b = super::BezierPatches::default().enclose_prepared(s);
            for (c, bc) in coords.iter_mut().zip(&b.coords) {
                if c.termination == Termination::Converged {
                    continue;
                }
                c.lo = c.lo.max(bc.lo);
                c.hi = c.hi.min(bc.hi);
                c.inner_lo = c.inner_lo.min(bc.inner_lo);
                c.inner_hi = c.inner_hi.max(bc.inner_hi);
                c.stats.add(&bc.stats);
            }
        }
        for (j, c) in coords.iter_mut().enumerate() {
            c.stats.add(&fast_st[j]);
            if let Some((nlo, nilo, wlo)) = fast[j][0] {
                c.lo = c.lo.max(-nlo);
                c.inner_lo = c.inner_lo.min(-nilo);
                c.witness_lo = c.witness_lo.min(-wlo);
            }
            if let Some((hi, ihi, whi)) = fast[j][1] {
                c.hi = c.hi.min(hi);
                c.inner_hi = c.inner_hi.max(ihi);
                c.witness_hi = c.witness_hi.max(whi);
            }
        }
        enclosure(self.name(), true, coords)
    }
}
