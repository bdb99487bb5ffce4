//! Curves whose extrema are exactly doubles or near-ties (within 2^-60 .. 2^-110 relative of a
//! double, on either side), for the optimality certificates (`enclose::certify`): the cases
//! where the optimal double bound is hardest to prove.
//!
//! Constructions (every one exact in f64 data; the extremum is derived in the comments):
//!
//! * [`TieKind::SymmetricQuadratic`]: Bézier P0 = P2 = a, P1 = b (b > a): C(1/2) = (a + b)/2,
//!   the maximum, at the dyadic u = 1/2; a, b with few significant bits, so (a + b)/2 is a
//!   double.
//! * [`TieKind::SymmetricCubic`]: P0 = P3 = a, P1 = P2 = b: C(1/2) = (a + 3b)/4.
//! * [`TieKind::NearTieQuadratic`]: P0 = e0, P1 = 1, P2 = e2 (times ±2^k): the maximum of a
//!   quadratic Bézier, (P0 P2 - P1^2)/(P0 - 2 P1 + P2) = (1 - e0 e2)/(2 - e0 - e2)
//!   = 1/2 + (e0 + e2)/4 + O(e^2), at a non-dyadic u* near 1/2; |e0|, |e2| ~ 2^-r with r in
//!   60..=110 and random signs, so the extremum is within ~2^-r relative above or below the
//!   double ±2^(k-1).
//! * [`TieKind::NearTieCubic`]: P0 = e0, P1 = P2 = 1, P3 = e3 (times ±2^k), so that
//!   x(t) = 3 t (1 - t) + e0 (1 - t)^3 + e3 t^3, with its maximum 3/4 + (e0 + e3)/8 + O(e^2)
//!   near t = 1/2: within ~2^-r relative of the double ±3 2^(k-2) (r in 60..=110, random
//!   signs), at a root of the quadratic x' (an irrational parameter in general).
//! * [`TieKind::ScaledCircle`]: the 9-point rational circle (NURBS Book ex. 7.2) with centre
//!   c and radius r of few bits: max x = c + r, min y = c - r, ... attained at knots.
//! * [`TieKind::KnotCorner`]: a quadratic B-spline with a double interior knot (C0 there)
//!   whose control point at the knot is the maximum: the value at the knot is that control
//!   point exactly.
//! * [`TieKind::UnclampedEnd`]: an unclamped quadratic whose maximum is at a domain end (not a
//!   control point).

use crate::spline::curve::NurbsCurve;
use rand::Rng;

/// The kinds of constructed curves (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TieKind {
    /// max (a + b)/2 at u = 1/2
    SymmetricQuadratic,
    /// max (a + 3b)/4 at u = 1/2
    SymmetricCubic,
    /// max within 2^-60 .. 2^-110 relative of a double, at a non-dyadic parameter
    NearTieQuadratic,
    /// a cubic's max within 2^-60 .. 2^-110 relative of a double
    NearTieCubic,
    /// rational circle: extrema exactly c ± r at knots
    ScaledCircle,
    /// maximum at a C0 knot, equal to a control point
    KnotCorner,
    /// maximum at an unclamped domain end
    UnclampedEnd,
}

impl TieKind {
    /// All kinds.
    pub const ALL: [TieKind; 7] = [
        TieKind::SymmetricQuadratic,
        TieKind::SymmetricCubic,
        TieKind::NearTieQuadratic,
        TieKind::NearTieCubic,
        TieKind::ScaledCircle,
        TieKind::KnotCorner,
        TieKind::UnclampedEnd,
    ];

    /// A short name (tables, messages).
    pub fn name(self) -> &'static str {
        match self {
            TieKind::SymmetricQuadratic => "sym_quadratic",
            TieKind::SymmetricCubic => "sym_cubic",
            TieKind::NearTieQuadratic => "near_tie",
            TieKind::NearTieCubic => "near_tie_cubic",
            TieKind::ScaledCircle => "circle",
            TieKind::KnotCorner => "knot_corner",
            TieKind::UnclampedEnd => "unclamped_end",
        }
    }

    /// A random curve of this kind.
    pub fn curve(self, rng: &mut impl Rng) -> NurbsCurve {
        // a double with `bits` significant bits and exponent in [-e, e]
        let few = |rng: &mut dyn rand::RngCore, bits: u32, e: i32| -> f64 {
            let m = rng.random_range(1u64..(1u64 << bits)) as f64;
            let s = if rng.random_bool(0.5) { -1.0 } else { 1.0 };
            s * m * 2f64.powi(rng.random_range(-e..=e) - bits as i32)
        };
        let bez = |pts: Vec<Vec<f64>>, w: Option<Vec<f64>>| {
            let p = pts.len() - 1;
            let mut k = vec![0.0; p + 1];
            k.extend(vec![1.0; p + 1]);
            NurbsCurve::new(p, k, pts, w).expect("valid Bézier data")
        };
        match self {
            TieKind::SymmetricQuadratic => {
                let (a, b) = (few(rng, 20, 8), few(rng, 20, 8));
                let (y0, y1) = (few(rng, 20, 8), few(rng, 20, 8));
                bez(vec![vec![a, y0], vec![b, y1], vec![a, y0]], None)
            }
            TieKind::SymmetricCubic => {
                let (a, b) = (few(rng, 20, 8), few(rng, 20, 8));
                let y = [few(rng, 20, 4), few(rng, 20, 4), few(rng, 20, 4)];
                bez(
                    vec![vec![a, y[0]], vec![b, y[1]], vec![b, y[2]], vec![a, y[0]]],
                    None,
                )
            }
            TieKind::NearTieQuadratic | TieKind::NearTieCubic => {
                let s = 2f64.powi(rng.random_range(-20..=20));
                let mut e = || {
                    let r = rng.random_range(60..=110);
                    let m = rng.random_range(1..=7) as f64;
                    let sg = if rng.random_bool(0.5) { -1.0 } else { 1.0 };
                    sg * m * 2f64.powi(-r)
                };
                let (e0, e2) = (e(), e());
                let sign = if rng.random_bool(0.5) { -1.0 } else { 1.0 };
                // 1-D plus a harmless second coordinate (a line)
                let x = if self == TieKind::NearTieQuadratic {
                    vec![e0, 1.0, e2]
                } else {
                    vec![e0, 1.0, 1.0, e2]
                };
                let n = x.len() - 1;
                let pts = x
                    .iter()
                    .enumerate()
                    .map(|(i, &v)| vec![sign * s * v, i as f64 / n as f64])
                    .collect();
                bez(pts, None)
            }
            TieKind::ScaledCircle => {
                let (cx, cy, r) = (few(rng, 12, 6), few(rng, 12, 6), few(rng, 12, 6).abs());
                let c = crate::testkit::gen::nurbs_circle();
                let pts: Vec<Vec<f64>> = c
                    .control_points()
                    .into_iter()
                    .map(|p| vec![cx + r * p[0], cy + r * p[1]])
                    .collect();
                NurbsCurve::new(2, c.knots().to_vec(), pts, c.weights().map(<[f64]>::to_vec))
                    .expect("valid circle data")
            }
            TieKind::KnotCorner => {
                let (a, b, top) = (few(rng, 16, 4), few(rng, 16, 4), few(rng, 16, 4));
                let top = top.abs() + a.abs().max(b.abs()) + 1.0;
                NurbsCurve::new(
                    2,
                    vec![0., 0., 0., 0.5, 0.5, 1., 1., 1.],
                    vec![
                        vec![a, 0.0],
                        vec![a.max(b), 1.0],
                        vec![top, 2.0],
                        vec![b.min(a), 3.0],
                        vec![b, 4.0],
                    ],
                    None,
                )
                .expect("valid corner data")
            }
            TieKind::UnclampedEnd => {
                let y: Vec<f64> = (0..4).map(|_| few(rng, 20, 4)).collect();
                NurbsCurve::new(
                    2,
                    vec![0., 1., 2., 3., 4., 5., 6.],
                    vec![
                        vec![y[0], 0.0],
                        vec![y[1], 1.0],
                        vec![y[2], 2.0],
                        vec![y[3], 3.0],
                    ],
                    None,
                )
                .expect("valid unclamped data")
            }
        }
    }
}

/// A random constructed curve of a random kind.
pub fn tie_curve(rng: &mut impl Rng) -> (TieKind, NurbsCurve) {
    let k = TieKind::ALL[rng.random_range(0..TieKind::ALL.len())];
    (k, k.curve(rng))
}
