//! Seeded random NURBS curves that seek out the nasty cases: clustered and multiple knots,
//! unclamped knot vectors, tiny and huge weights, flat coordinates, near-degenerate cubics,
//! extrema exactly at knots, extreme magnitudes and high degrees.
//!
//! Used by the property tests and by the reproduction harness (`thesis_curve_1d`,
//! `thesis_curve_2d_nurbs` for the knot-count and degree sweeps of thesis ch. 6, its two
//! timing tables).
//!
//! Everything is deterministic given the RNG (use [`rng`] for a seeded ChaCha8 generator).
//! Every curve returned is valid by construction (the constructor is called and its `Ok` is
//! asserted; the test `every_family_is_valid_over_many_seeds` checks this over many seeds).

use crate::error::CurveError;
use crate::spline::curve::NurbsCurve;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::ops::RangeInclusive;

/// The seeded RNG used throughout (ChaCha8: portable, reproducible across platforms).
pub fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

/// How the knot vector is built.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KnotStyle {
    /// p + 1 equal end knots, equally spaced interior knots.
    ClampedUniform,
    /// p + 1 equal end knots, random sorted interior knots.
    ClampedRandom,
    /// clamped, with clusters of spans down to 1e-12 of the domain length
    Clustered,
    /// clamped, interior knots of multiplicity 1 ..= p + 1 (p + 1: discontinuous curve)
    Multiple,
    /// no end multiplicity: strictly increasing knots with random gaps
    Unclamped,
}

/// Parameters of [`random_curve`]. Ranges are inclusive; probabilities in [0, 1].
#[derive(Debug, Clone)]
pub struct GenParams {
    /// degree p
    pub degree: RangeInclusive<usize>,
    /// number of control points beyond the minimum p + 1
    pub extra_points: RangeInclusive<usize>,
    /// Cartesian dimension
    pub dim: RangeInclusive<usize>,
    /// probability that the curve is rational
    pub rational: f64,
    /// weights are 10^x with x uniform in this range
    pub weight_log10: (f64, f64),
    /// knot styles, one chosen uniformly per curve
    pub knot_styles: Vec<KnotStyle>,
    /// each coordinate gets a scale 10^x, x uniform in this range
    pub coord_log10: (f64, f64),
    /// probability that a coordinate gets a large common offset (values 10^(0..4) times its
    /// scale, varying by +-1 scale: cancellation)
    pub coord_offset: f64,
    /// probability that the parameter domain is shifted and scaled (not [0, 1])
    pub domain_shift: f64,
    /// probability that one coordinate is constant on a run of >= p + 1 control points
    /// (constant on whole spans), a third of those on all points
    pub flat: f64,
    /// probability of a mirror-symmetric curve (knots u -> -u, P_i = P_{n-i}, w_i = w_{n-i})
    /// whose middle is a knot: the derivative vanishes exactly at that knot
    pub symmetric: f64,
}

impl Default for GenParams {
    /// Moderate curves: degree 1..=5, up to 8 extra points, dimension 1..=3, half rational with
    /// weights in [0.1, 10], clamped or unclamped knots, unit coordinates.
    fn default() -> Self {
        GenParams {
            degree: 1..=5,
            extra_points: 0..=8,
            dim: 1..=3,
            rational: 0.5,
            weight_log10: (-1.0, 1.0),
            knot_styles: vec![
                KnotStyle::ClampedUniform,
                KnotStyle::ClampedRandom,
                KnotStyle::Unclamped,
            ],
            coord_log10: (0.0, 0.0),
            coord_offset: 0.0,
            domain_shift: 0.0,
            flat: 0.0,
            symmetric: 0.0,
        }
    }
}

/// Named families of test curves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// clamped uniform knots, moderate everything
    ClampedUniform,
    /// spans down to 1e-12 relative
    ClusteredKnots,
    /// interior multiplicities up to p + 1
    MultipleKnots,
    /// unclamped knot vectors
    Unclamped,
    /// weights 1e-6 .. 1e6
    ExtremeWeights,
    /// a coordinate constant on whole spans (or everywhere)
    FlatCoordinates,
    /// cubics whose derivative has a (near) double root, near-coincident control points
    NearDegenerateCubic,
    /// symmetric curves: the extremum of a coordinate lies exactly at a knot
    ExtremaAtKnots,
    /// coordinates of magnitude 1e-300 .. 1e300
    ExtremeMagnitudes,
    /// degree 10 ..= 40
    HighDegree,
    /// everything at once (moderate degree)
    Mixed,
    /// the corners of the f64 range: knots near ±f64::MAX whose differences overflow,
    /// subnormal knots among huge ones, coordinates at ±f64::MAX and at subnormal sizes
    RangeLimits,
}

impl Family {
    /// All families but [`Family::RangeLimits`], whose curves break plain-f64 properties (f64
    /// evaluation overflows there): the property tests draw from these; the range tests and
    /// the tightness table add `RangeLimits` explicitly.
    pub const ALL: [Family; 11] = [
        Family::ClampedUniform,
        Family::ClusteredKnots,
        Family::MultipleKnots,
        Family::Unclamped,
        Family::ExtremeWeights,
        Family::FlatCoordinates,
        Family::NearDegenerateCubic,
        Family::ExtremaAtKnots,
        Family::ExtremeMagnitudes,
        Family::HighDegree,
        Family::Mixed,
    ];

    /// Short snake_case name.
    pub fn name(self) -> &'static str {
        match self {
            Family::ClampedUniform => "clamped_uniform",
            Family::ClusteredKnots => "clustered_knots",
            Family::MultipleKnots => "multiple_knots",
            Family::Unclamped => "unclamped",
            Family::ExtremeWeights => "extreme_weights",
            Family::FlatCoordinates => "flat_coordinates",
            Family::NearDegenerateCubic => "near_degenerate_cubic",
            Family::ExtremaAtKnots => "extrema_at_knots",
            Family::ExtremeMagnitudes => "extreme_magnitudes",
            Family::HighDegree => "high_degree",
            Family::Mixed => "mixed",
            Family::RangeLimits => "range_limits",
        }
    }

    /// The generator parameters of the family ([`Family::NearDegenerateCubic`] has its own
    /// construction; its parameters are only used for the extra coordinates).
    pub fn params(self) -> GenParams {
        let d = GenParams::default();
        match self {
            Family::ClampedUniform => GenParams {
                knot_styles: vec![KnotStyle::ClampedUniform],
                ..d
            },
            Family::ClusteredKnots => GenParams {
                degree: 1..=6,
                extra_points: 2..=12,
                knot_styles: vec![KnotStyle::Clustered],
                ..d
            },
            Family::MultipleKnots => GenParams {
                extra_points: 1..=10,
                knot_styles: vec![KnotStyle::Multiple],
                ..d
            },
            Family::Unclamped => GenParams {
                knot_styles: vec![KnotStyle::Unclamped],
                domain_shift: 0.5,
                ..d
            },
            Family::ExtremeWeights => GenParams {
                rational: 1.0,
                weight_log10: (-6.0, 6.0),
                knot_styles: vec![
                    KnotStyle::ClampedUniform,
                    KnotStyle::ClampedRandom,
                    KnotStyle::Unclamped,
                    KnotStyle::Multiple,
                ],
                ..d
            },
            Family::FlatCoordinates => GenParams {
                extra_points: 1..=10,
                flat: 1.0,
                knot_styles: vec![
                    KnotStyle::ClampedUniform,
                    KnotStyle::ClampedRandom,
                    KnotStyle::Unclamped,
                    KnotStyle::Multiple,
                ],
                ..d
            },
            Family::NearDegenerateCubic => GenParams {
                degree: 3..=3,
                dim: 1..=2,
                ..d
            },
            Family::ExtremaAtKnots => GenParams {
                symmetric: 1.0,
                extra_points: 1..=9,
                knot_styles: vec![KnotStyle::ClampedUniform, KnotStyle::ClampedRandom],
                ..d
            },
            Family::ExtremeMagnitudes => GenParams {
                coord_log10: (-300.0, 300.0),
                weight_log10: (-0.5, 0.5),
                ..d
            },
            Family::HighDegree => GenParams {
                degree: 10..=40,
                extra_points: 0..=6,
                dim: 1..=2,
                weight_log10: (-0.5, 0.5),
                knot_styles: vec![
                    KnotStyle::ClampedUniform,
                    KnotStyle::ClampedRandom,
                    KnotStyle::Unclamped,
                ],
                ..d
            },
            Family::Mixed => GenParams {
                degree: 1..=7,
                extra_points: 0..=10,
                weight_log10: (-3.0, 3.0),
                knot_styles: vec![
                    KnotStyle::ClampedUniform,
                    KnotStyle::ClampedRandom,
                    KnotStyle::Clustered,
                    KnotStyle::Multiple,
                    KnotStyle::Unclamped,
                ],
                coord_log10: (-3.0, 3.0),
                coord_offset: 0.2,
                domain_shift: 0.3,
                flat: 0.2,
                symmetric: 0.2,
                ..d
            },
            // (built by `range_limit_curve`; these are its degree and size ranges)
            Family::RangeLimits => GenParams {
                degree: 1..=4,
                extra_points: 0..=6,
                rational: 1.0 / 3.0,
                weight_log10: (-3.0, 3.0),
                ..d
            },
        }
    }

    /// A random curve of this family.
    pub fn curve(self, rng: &mut impl Rng) -> NurbsCurve {
        match self {
            Family::NearDegenerateCubic => near_degenerate_cubic(rng),
            Family::RangeLimits => range_limit_curve(rng),
            f => random_curve(rng, &f.params()),
        }
    }
}

/// A curve at the corners of the f64 range ([`Family::RangeLimits`]): degree 1..=4, up to 6
/// extra points, dimension 1..=3, a third rational (weights 1e-3 .. 1e3). Knots are one of:
/// clamped at ±f64::MAX with interior knots drawn from subnormals (k 2^-1074), zero, ordinary
/// values and fractions of ±f64::MAX (spans and knot differences that overflow); [0, MAX]
/// with subnormal interior knots; an unclamped vector spread over [-MAX, MAX]; a domain of a
/// few subnormals. Coordinates are ordinary, at or near ±f64::MAX, subnormal, or a mix.
pub fn range_limit_curve(rng: &mut impl Rng) -> NurbsCurve {
    const M: f64 = f64::MAX;
    let sub = |k: u64| f64::from_bits(k);
    loop {
        let p = rng.random_range(1..=4usize);
        let npts = p + 1 + rng.random_range(0..=6usize);
        let dim = rng.random_range(1..=3usize);
        let ni = npts - p - 1;
        let m = npts + p;
        let interior = |rng: &mut dyn rand::RngCore| -> f64 {
            match rng.random_range(0..6) {
                0 => sub(rng.random_range(1..8)),
                1 => 0.0,
                2 => rng.random_range(-2.0..2.0),
                3 => M * rng.random_range(-1.0..1.0),
                4 => -sub(rng.random_range(1..8)),
                _ => M * rng.random_range(0.1..1.0),
            }
        };
        let knots: Vec<f64> = match rng.random_range(0..4) {
            0 => {
                let mut v: Vec<f64> = (0..ni).map(|_| interior(rng)).collect();
                v.sort_by(f64::total_cmp);
                let mut k = vec![-M; p + 1];
                k.extend(v);
                k.extend(std::iter::repeat_n(M, p + 1));
                k
            }
            1 => {
                let mut v: Vec<f64> = (0..ni)
                    .map(|_| match rng.random_range(0..3) {
                        0 => sub(rng.random_range(1..16)),
                        1 => M * rng.random_range(0.0..1.0),
                        _ => rng.random_range(0.0..4.0),
                    })
                    .collect();
                v.sort_by(f64::total_cmp);
                let mut k = vec![0.0; p + 1];
                k.extend(v);
                k.extend(std::iter::repeat_n(M, p + 1));
                k
            }
            2 => {
                let mut v: Vec<f64> = (0..=m).map(|_| M * rng.random_range(-1.0..1.0)).collect();
                v[rng.random_range(0..=m)] = sub(1);
                v.sort_by(f64::total_cmp);
                v
            }
            _ => {
                let mut v: Vec<f64> = (0..ni).map(|_| sub(rng.random_range(1..64))).collect();
                v.sort_by(f64::total_cmp);
                let mut k = vec![0.0; p + 1];
                k.extend(v);
                k.extend(std::iter::repeat_n(sub(64), p + 1));
                k
            }
        };
        let style: Vec<u8> = (0..dim).map(|_| rng.random_range(0..4)).collect();
        let pts: Vec<Vec<f64>> = (0..npts)
            .map(|_| {
                style
                    .iter()
                    .map(|&s| match s {
                        0 => rng.random_range(-5.0..5.0),
                        1 => match rng.random_range(0..3) {
                            0 => M,
                            1 => -M,
                            _ => M * rng.random_range(-1.0..1.0),
                        },
                        2 => {
                            sub(rng.random_range(0..4096))
                                * if rng.random_bool(0.5) { 1.0 } else { -1.0 }
                        }
                        _ => match rng.random_range(0..3) {
                            0 => M * rng.random_range(-1.0..1.0),
                            1 => sub(rng.random_range(0..4096)),
                            _ => rng.random_range(-1.0..1.0),
                        },
                    })
                    .collect()
            })
            .collect();
        let weights = rng
            .random_bool(1.0 / 3.0)
            .then(|| (0..npts).map(|_| log_uniform(rng, (-3.0, 3.0))).collect());
        // (the constructor rejects an empty domain or a multiplicity above p + 1: draw again)
        if let Ok(c) = NurbsCurve::new(p, knots, pts, weights) {
            return c;
        }
    }
}

/// A curve of a uniformly chosen family, with the family.
pub fn nasty_curve(rng: &mut impl Rng) -> (Family, NurbsCurve) {
    let f = Family::ALL[rng.random_range(0..Family::ALL.len())];
    (f, f.curve(rng))
}

fn pick<T: Copy>(rng: &mut impl Rng, v: &[T]) -> T {
    v[rng.random_range(0..v.len())]
}

fn log_uniform(rng: &mut impl Rng, (a, b): (f64, f64)) -> f64 {
    10f64.powf(rng.random_range(a.min(b)..=a.max(b)))
}

/// A random valid curve drawn according to `params`.
pub fn random_curve(rng: &mut impl Rng, params: &GenParams) -> NurbsCurve {
    let p = rng.random_range(params.degree.clone()).max(1);
    let npts = p + 1 + rng.random_range(params.extra_points.clone());
    let dim = rng.random_range(params.dim.clone()).max(1);
    let n = npts - 1;
    let symmetric = rng.random_bool(params.symmetric.clamp(0.0, 1.0));
    let style = if params.knot_styles.is_empty() {
        KnotStyle::ClampedUniform
    } else {
        pick(rng, &params.knot_styles)
    };
    let knots = if symmetric {
        symmetric_knots(rng, p, n, style)
    } else {
        let t = unit_knots(rng, p, n, style);
        // Clustered knots may be 1e-12 apart: an affine map could merge them, so only
        // well-separated styles are shifted.
        if style != KnotStyle::Clustered && rng.random_bool(params.domain_shift.clamp(0.0, 1.0)) {
            shift_domain(rng, t)
        } else {
            t
        }
    };
    // Control points: coordinate j has scale s_j and maybe a common offset.
    let mut pts = vec![0.0; npts * dim];
    for j in 0..dim {
        let s = log_uniform(rng, params.coord_log10);
        let off = if rng.random_bool(params.coord_offset.clamp(0.0, 1.0)) {
            log_uniform(rng, (0.0, 4.0)) * if rng.random_bool(0.5) { 1.0 } else { -1.0 }
        } else {
            0.0
        };
        for i in 0..npts {
            pts[i * dim + j] = s * (off + rng.random_range(-1.0..=1.0));
        }
    }
    if rng.random_bool(params.flat.clamp(0.0, 1.0)) {
        let j = rng.random_range(0..dim);
        let (start, len) = if rng.random_bool(1.0 / 3.0) {
            (0, npts)
        } else {
            let len = rng.random_range(p + 1..=npts);
            (rng.random_range(0..=npts - len), len)
        };
        let v = pts[start * dim + j];
        for i in start..start + len {
            pts[i * dim + j] = v;
        }
    }
    let mut weights = rng.random_bool(params.rational.clamp(0.0, 1.0)).then(|| {
        (0..npts)
            .map(|_| log_uniform(rng, params.weight_log10))
            .collect::<Vec<f64>>()
    });
    if symmetric {
        for i in 0..npts / 2 {
            for j in 0..dim {
                pts[(n - i) * dim + j] = pts[i * dim + j];
            }
            if let Some(w) = weights.as_mut() {
                w[n - i] = w[i];
            }
        }
        // Half of the time make the middle the extreme of coordinate 0 (so the box's bound is
        // attained exactly at the middle knot).
        if rng.random_bool(0.5) {
            let m = pts.iter().step_by(dim).fold(0.0f64, |a, x| a.max(x.abs()));
            for i in [n / 2, n - n / 2] {
                pts[i * dim] = 2.0 * m + 1.0;
            }
        }
    }
    NurbsCurve::from_flat(p, dim, knots, pts, weights).expect("generator builds valid curves")
}

/// Knots on [0, 1] (clamped styles) or an increasing run (unclamped), n + p + 2 values.
fn unit_knots(rng: &mut impl Rng, p: usize, n: usize, style: KnotStyle) -> Vec<f64> {
    let m = n + p + 1;
    let ni = n - p; // interior knots of a clamped vector
    let clamped = |interior: Vec<f64>| {
        let mut k = vec![0.0; p + 1];
        k.extend(interior);
        k.extend(std::iter::repeat_n(1.0, p + 1));
        k
    };
    match style {
        KnotStyle::ClampedUniform => {
            clamped((1..=ni).map(|i| i as f64 / (ni + 1) as f64).collect())
        }
        KnotStyle::ClampedRandom => {
            let mut v: Vec<f64> = (0..ni).map(|_| rng.random_range(0.001..0.999f64)).collect();
            v.sort_by(f64::total_cmp);
            // Equal draws are improbable; nudging them apart keeps validity unconditional.
            for i in 1..v.len() {
                if v[i] <= v[i - 1] {
                    v[i] = f64::from_bits(v[i - 1].to_bits() + 1);
                }
            }
            clamped(v)
        }
        KnotStyle::Clustered => {
            // ni + 1 gaps; some are 10^-(3..12) of the others; cumulative sums normalised.
            let gaps: Vec<f64> = (0..=ni)
                .map(|_| {
                    if rng.random_bool(0.5) {
                        10f64.powf(-rng.random_range(3.0..=12.0))
                    } else {
                        rng.random_range(0.5..=1.5)
                    }
                })
                .collect();
            let total: f64 = gaps.iter().sum();
            let mut acc = 0.0;
            let mut v = Vec::with_capacity(ni);
            for g in &gaps[..ni] {
                acc += g;
                // acc / total < 1: the last gap is positive and sums are monotone
                v.push((acc / total).min(1.0));
            }
            // Relative gaps >= 1e-12 / (ni + 1) stay distinct in f64 (>> 2^-52), but keep the
            // vector valid regardless: strictly increase and stay below 1.
            for i in 0..v.len() {
                let prev = if i == 0 { 0.0 } else { v[i - 1] };
                if v[i] <= prev {
                    v[i] = f64::from_bits(prev.to_bits() + 1);
                }
            }
            if v.last().is_some_and(|&x| x >= 1.0) {
                // cannot happen for these gap sizes; fall back to uniform for validity
                return unit_knots(rng, p, n, KnotStyle::ClampedUniform);
            }
            clamped(v)
        }
        KnotStyle::Multiple => {
            // group the ni interior knots into runs of multiplicity 1 ..= p + 1
            let mut mults = Vec::new();
            let mut left = ni;
            while left > 0 {
                let k = rng.random_range(1..=left.min(p + 1));
                mults.push(k);
                left -= k;
            }
            let nd = mults.len();
            let mut v = Vec::with_capacity(ni);
            for (i, &k) in mults.iter().enumerate() {
                let x = (i + 1) as f64 / (nd + 1) as f64;
                v.extend(std::iter::repeat_n(x, k));
            }
            clamped(v)
        }
        KnotStyle::Unclamped => {
            let mut v = Vec::with_capacity(m + 1);
            let mut x = 0.0;
            for _ in 0..=m {
                v.push(x);
                x += rng.random_range(0.5..=1.5);
            }
            // sometimes clamp one end only
            if rng.random_bool(0.25) {
                for i in 0..p {
                    v[i] = v[p];
                }
            }
            v
        }
    }
}

/// Affine map of the knots to [o, o + L] with o up to +-1e4 and L in 1e-3 .. 1e3 (monotone in
/// f64; only for knot vectors whose distinct values are well separated).
fn shift_domain(rng: &mut impl Rng, t: Vec<f64>) -> Vec<f64> {
    let l = log_uniform(rng, (-3.0, 3.0));
    let o = rng.random_range(-1.0..=1.0) * log_uniform(rng, (0.0, 4.0));
    let (a, b) = (t[0], *t.last().unwrap());
    let shifted: Vec<f64> = t.iter().map(|&x| o + l * ((x - a) / (b - a))).collect();
    // Keep validity unconditional: the map must not merge distinct knots.
    let distinct = |v: &[f64]| v.windows(2).filter(|w| w[0] != w[1]).count();
    if distinct(&shifted) == distinct(&t) {
        shifted
    } else {
        t
    }
}

/// Knots symmetric about 0 (u_i = -u_{m-i}, negation is exact) on [-1, 1] with 0 as an
/// interior knot whenever n - p allows (an odd count needs it; an even count gets 0 twice or,
/// for p = 1, as the middle pair).
fn symmetric_knots(rng: &mut impl Rng, p: usize, n: usize, style: KnotStyle) -> Vec<f64> {
    let ni = n - p;
    // multiplicity of 0: parity of ni, at least 1 when possible, at most p + 1 and ni
    let mut z = ni % 2;
    if z == 0 && ni >= 2 && p >= 1 {
        z = 2.min(p + 1);
    }
    let half = (ni - z) / 2;
    let mut pos: Vec<f64> = match style {
        KnotStyle::ClampedRandom => (0..half).map(|_| rng.random_range(0.01..0.99)).collect(),
        _ => (1..=half).map(|i| i as f64 / (half + 1) as f64).collect(),
    };
    pos.sort_by(f64::total_cmp);
    for i in 1..pos.len() {
        if pos[i] <= pos[i - 1] {
            pos[i] = f64::from_bits(pos[i - 1].to_bits() + 1);
        }
    }
    let mut k = vec![-1.0; p + 1];
    k.extend(pos.iter().rev().map(|x| -x));
    k.extend(std::iter::repeat_n(0.0, z));
    k.extend(pos.iter().copied());
    k.extend(std::iter::repeat_n(1.0, p + 1));
    k
}

/// Cubics whose first derivative has a double root (exactly, or split into a close pair, or a
/// close complex pair), and cusp-like curves with near-coincident inner control points;
/// sometimes refined into several spans by knot insertion.
pub fn near_degenerate_cubic(rng: &mut impl Rng) -> NurbsCurve {
    let dim = rng.random_range(1..=2usize);
    // C'(t) / 3 = d0 (1-t)^2 + 2 d1 (1-t) t + d2 t^2 with d1^2 = d0 d2 (1+eps)^2: a double root
    // at t = a / (a + b) for eps = 0.
    let a = rng.random_range(1..=8) as f64 / 4.0;
    let b = rng.random_range(1..=8) as f64 / 4.0;
    let eps = match rng.random_range(0..3) {
        0 => 0.0,
        1 => 10f64.powf(-rng.random_range(1.0..=15.0)),
        _ => -(10f64.powf(-rng.random_range(1.0..=15.0))),
    };
    let sgn = if rng.random_bool(0.5) { 1.0 } else { -1.0 };
    let (d0, d1, d2) = (sgn * a * a, -sgn * a * b * (1.0 + eps), sgn * b * b);
    let c0 = rng.random_range(-1.0..=1.0);
    let mut pts = vec![
        vec![c0],
        vec![c0 + d0],
        vec![c0 + d0 + d1],
        vec![c0 + d0 + d1 + d2],
    ];
    if dim == 2 {
        for q in pts.iter_mut() {
            q.push(rng.random_range(-1.0..=1.0));
        }
    }
    if rng.random_bool(0.3) {
        // cusp: the two inner points nearly coincide (in every coordinate)
        let t = 10f64.powf(-rng.random_range(0.0..=14.0));
        pts[2] = pts[1].iter().map(|x| x + t).collect();
    }
    let rational = rng.random_bool(0.3);
    let weights = rational.then(|| (0..4).map(|_| rng.random_range(0.5..=2.0)).collect());
    let c = NurbsCurve::new(3, vec![0., 0., 0., 0., 1., 1., 1., 1.], pts, weights)
        .expect("generator builds valid curves");
    if rng.random_bool(0.3) {
        let u = rng.random_range(0.1..0.9);
        let r = rng.random_range(1..=3);
        c.insert_knot(u, r).expect("u lies in the domain")
    } else {
        c
    }
}

/// A curve at the edges of the driver's lane (`enclose::lane::Simple::of`): a single
/// polynomial Bézier segment of degree 2 or 3, a spline (polynomial or rational) of degree 2
/// to 5 with up to five spans, or a polyline of up to eight spans (jumps at double knots; a
/// quarter of the splines and polylines unclamped), dimension 1 to 4, whose data sit where
/// the lane's windows and fast proofs end: coordinates scaled by 2^e with e at the coordinate
/// window's edges (2^-82 .. 2^80, sometimes times 2 - 2^-52); domains of a few subnormals, a
/// few ulps of 1, ±2^999 and [2^999, 2^999 + 2^949] besides ordinary ones; weights at 2^-100
/// and just below 2^100, spread over up to 2^12 (exactly, alternating, in a third of the
/// draws; else up to just below 2^13, past the lane's limit); integer and dyadic data (exact
/// ties), coordinates tangent to zero (quadratics with b^2 = a c rounded), symmetric control
/// polygons (an extremum at the middle, often a knot), repeated points, clustered and repeated
/// interior knots (multiplicity up to p, two on a polyline: a jump), ulp jitter. `None` where
/// the draw is no valid curve (the constructor's typed error), which the caller skips.
pub fn lane_edge_curve(rng: &mut impl Rng) -> Option<NurbsCurve> {
    let pow2 = |e: i32| 2f64.powi(e);
    let family = rng.random_range(0..7u32);
    let p: usize = match family {
        0 | 1 => rng.random_range(2..=3),
        6 => 1,
        _ => rng.random_range(2..=5),
    };
    let d = rng.random_range(1..=4usize);
    let spans = match family {
        0 => 1,
        6 => rng.random_range(1..=8usize),
        _ => rng.random_range(1..=5usize),
    };
    let n = p + spans - 1;
    let kind = rng.random_range(0..4u32);
    let e = pick(rng, &[79, -80, -81, 78, 80, -82, 0, 0]);
    let scale = pow2(e)
        * if rng.random_bool(0.2) {
            2.0 - f64::EPSILON
        } else {
            1.0
        };
    let mut pts: Vec<Vec<f64>> = vec![vec![0.0; d]; n + 1];
    for x in pts.iter_mut().flatten() {
        *x = scale
            * match kind {
                0 => rng.random_range(-1.0..1.0),
                1 => rng.random_range(-8i32..8) as f64 / 4.0,
                2 => rng.random_range(-1.0..1.0) * pow2(rng.random_range(-60..0)),
                _ => pick(rng, &[0.0, 1.0, -1.0, 0.5, 0.25, 3.0]),
            };
    }
    if family == 0 && p == 2 && rng.random_bool(0.3) {
        // tangent to zero: (a, -sqrt(a c), c) rounded, min ~ 0 at an interior parameter
        let (a, c): (f64, f64) = (rng.random_range(0.1..4.0), rng.random_range(0.1..4.0));
        pts[0][0] = a * scale;
        pts[1][0] = -(a * c).sqrt() * scale;
        pts[2][0] = c * scale;
    }
    if rng.random_bool(0.3) {
        // symmetric: the extremum at the middle parameter
        for i in 0..=n / 2 {
            pts[n - i] = pts[i].clone();
        }
    }
    if rng.random_bool(0.2) && n >= 2 {
        let i = rng.random_range(0..n);
        pts[i + 1] = pts[i].clone();
    }
    if rng.random_bool(0.3) {
        for x in pts.iter_mut().flatten() {
            let k = rng.random_range(-3i32..=3);
            for _ in 0..k.unsigned_abs() {
                if *x != 0.0 {
                    *x = if k > 0 { x.next_up() } else { x.next_down() };
                }
            }
        }
    }
    let sub = |k: u64| f64::from_bits(k);
    let (a, b) = match rng.random_range(0..9) {
        0 => (0.0, 1.0),
        1 => (-1.0, 1.0),
        2 => (1e6, 1e6 + 1.0),
        3 => (0.0, sub(rng.random_range(1..20))),
        4 => (1.0, 1.0f64.next_up().next_up().next_up()),
        5 => (-pow2(999), pow2(999)),
        6 => (pow2(999), pow2(999) + pow2(949)),
        7 => (
            -sub(rng.random_range(1..2000)),
            sub(rng.random_range(1..2000)),
        ),
        _ => (0.0, pow2(rng.random_range(-30..30))),
    };
    let mut inner: Vec<f64> = (1..spans)
        .map(|i| {
            if rng.random_bool(0.5) {
                a + (b - a) * i as f64 / spans as f64
            } else {
                a + (b - a) * rng.random_range(0.0..1.0)
            }
        })
        .collect();
    inner.sort_by(f64::total_cmp);
    if rng.random_bool(0.2) && !inner.is_empty() {
        // clustered
        let c = inner[0];
        for (i, u) in inner.iter_mut().enumerate() {
            *u = c + (b - a) * 1e-9 * i as f64;
        }
        inner.sort_by(f64::total_cmp);
    }
    if rng.random_bool(0.2) && !inner.is_empty() {
        // repeated, up to multiplicity p (a polyline's double knot: a jump)
        let u = inner[0];
        for v in inner.iter_mut().take(rng.random_range(1..=p.max(2))) {
            *v = u;
        }
        inner.sort_by(f64::total_cmp);
    }
    let mut knots = vec![a; p + 1];
    knots.extend(inner);
    knots.extend(vec![b; p + 1]);
    if family != 0 && rng.random_bool(0.25) {
        // unclamped: the outer knots spread beyond the domain [u_p, u_{n+1}] = [a, b]
        let h = (b - a) / spans as f64;
        let m = knots.len();
        for i in 0..p {
            knots[i] = a - (p - i) as f64 * h;
            knots[m - 1 - i] = b + (p - i) as f64 * h;
        }
    }
    let weights = (family >= 4 && (family != 6 || rng.random_bool(0.5))).then(|| {
        let spread = rng.random_range(0..13);
        let base = match rng.random_range(0..4) {
            0 => pow2(-100),
            1 => pow2(99 - spread),
            _ => pow2(rng.random_range(-99..88)),
        };
        let alternate = rng.random_bool(0.3);
        (0..=n)
            .map(|i| {
                if alternate {
                    base * pow2(spread * (i % 2) as i32)
                } else {
                    base * pow2(rng.random_range(0..=spread)) * rng.random_range(1.0..2.0)
                }
            })
            .collect()
    });
    NurbsCurve::new(p, knots, pts, weights).ok()
}

/// The 1-D curve of the thesis's knot-count sweep (thesis ch. 6, first timing table: p = 3,
/// n = 4 .. 100): `n_plus_1` control values uniform in [-1, 1] from `seed`, clamped uniform
/// knots on [0, 1].
pub fn thesis_curve_1d(
    n_plus_1: usize,
    degree: usize,
    seed: u64,
) -> Result<NurbsCurve, CurveError> {
    let mut r = rng(seed);
    let vals: Vec<f64> = (0..n_plus_1).map(|_| r.random_range(-1.0..=1.0)).collect();
    NurbsCurve::from_flat(degree, 1, clamped_uniform(n_plus_1, degree)?, vals, None)
}

/// The 2-D NURBS curve of the thesis's degree sweep (thesis ch. 6, second table: "10 Punkte",
/// i.e. n = 10, 11 control points, p = 2 .. 10): coordinates uniform in [-1, 1], weights
/// uniform in [0.5, 2], clamped uniform knots on [0, 1].
pub fn thesis_curve_2d_nurbs(degree: usize, seed: u64) -> Result<NurbsCurve, CurveError> {
    thesis_curve_2d_nurbs_with(11, degree, seed)
}

/// As [`thesis_curve_2d_nurbs`] with `npts` control points (the harness continues the degree
/// sweep beyond p = 10 with 21 points).
pub fn thesis_curve_2d_nurbs_with(
    npts: usize,
    degree: usize,
    seed: u64,
) -> Result<NurbsCurve, CurveError> {
    let mut r = rng(seed);
    let pts: Vec<f64> = (0..2 * npts).map(|_| r.random_range(-1.0..=1.0)).collect();
    let w: Vec<f64> = (0..npts).map(|_| r.random_range(0.5..=2.0)).collect();
    NurbsCurve::from_flat(degree, 2, clamped_uniform(npts, degree)?, pts, Some(w))
}

/// The 9-point rational quadratic unit circle (NURBS Book ex. 7.2; knots 0, 1/4, 1/2, 3/4, 1
/// doubled inside, weights 1 and sqrt(2)/2 rounded to f64, so the curve is a circle only to
/// ~1e-16).
pub fn nurbs_circle() -> NurbsCurve {
    let s = std::f64::consts::FRAC_1_SQRT_2;
    NurbsCurve::new(
        2,
        vec![0., 0., 0., 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1., 1., 1.],
        vec![
            vec![1., 0.],
            vec![1., 1.],
            vec![0., 1.],
            vec![-1., 1.],
            vec![-1., 0.],
            vec![-1., -1.],
            vec![0., -1.],
            vec![1., -1.],
            vec![1., 0.],
        ],
        Some(vec![1., s, 1., s, 1., s, 1., s, 1.]),
    )
    .expect("the circle data are valid")
}

/// Clamped uniform knots on [0, 1] for `npts` points of degree p (typed error if npts < p + 1
/// or p = 0).
fn clamped_uniform(npts: usize, p: usize) -> Result<Vec<f64>, CurveError> {
    if p == 0 {
        return Err(CurveError::InvalidDegree(0));
    }
    if npts < p + 1 {
        return Err(CurveError::TooFewControlPoints {
            degree: p,
            needed: p + 1,
            got: npts,
        });
    }
    let ni = npts - p - 1;
    let mut k = vec![0.0; p + 1];
    k.extend((1..=ni).map(|i| i as f64 / (ni + 1) as f64));
    k.extend(std::iter::repeat_n(1.0, p + 1));
    Ok(k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_family_is_valid_over_many_seeds() {
        // random_curve / near_degenerate_cubic assert validity internally (expect).
        for f in Family::ALL {
            let mut r = rng(0x5eed ^ f as u64);
            for _ in 0..400 {
                let c = f.curve(&mut r);
                assert!(c.degree() >= 1);
                let (a, b) = c.domain();
                assert!(a < b);
            }
        }
    }

    #[test]
    fn families_have_their_features() {
        let mut r = rng(1);
        let mut seen_disc = false;
        let mut seen_tiny_span = false;
        let mut seen_flat_all = false;
        let mut seen_extreme_w = false;
        for _ in 0..300 {
            let c = Family::MultipleKnots.curve(&mut r);
            seen_disc |= c.interior_knots().iter().any(|&(_, m)| m == c.degree() + 1);
            let c = Family::ClusteredKnots.curve(&mut r);
            let (a, b) = c.domain();
            seen_tiny_span |= c
                .breakpoints()
                .windows(2)
                .any(|w| w[1] - w[0] < 1e-10 * (b - a));
            let c = Family::FlatCoordinates.curve(&mut r);
            seen_flat_all |= (0..c.dim()).any(|j| {
                let v: Vec<f64> = c.control_points().iter().map(|q| q[j]).collect();
                v.iter().all(|&x| x == v[0])
            });
            let c = Family::ExtremeWeights.curve(&mut r);
            let w = c.weights().unwrap();
            seen_extreme_w |= w.iter().any(|&x| x < 1e-4) && w.iter().any(|&x| x > 1e4);
        }
        assert!(seen_disc && seen_tiny_span && seen_flat_all && seen_extreme_w);
    }

    #[test]
    fn symmetric_curves_are_symmetric_with_a_middle_knot() {
        let mut r = rng(7);
        for _ in 0..200 {
            let c = Family::ExtremaAtKnots.curve(&mut r);
            let k = c.knots();
            let m = k.len() - 1;
            assert!((0..=m).all(|i| k[i] == -k[m - i]));
            if c.num_points() - c.degree() >= 2 {
                assert!(k.contains(&0.0), "{k:?}");
            }
            for u in [0.1, 0.37, 0.9] {
                let x: Vec<f64> = c.point(u).unwrap();
                let y: Vec<f64> = c.point(-u).unwrap();
                for j in 0..c.dim() {
                    assert!((x[j] - y[j]).abs() <= 1e-12 * (1.0 + x[j].abs()));
                }
            }
        }
    }

    #[test]
    fn thesis_curves() {
        let c = thesis_curve_1d(101, 3, 42).unwrap();
        assert_eq!((c.num_points(), c.degree(), c.dim()), (101, 3, 1));
        assert_eq!(c, thesis_curve_1d(101, 3, 42).unwrap());
        assert_ne!(c, thesis_curve_1d(101, 3, 43).unwrap());
        for p in 2..=10 {
            let c = thesis_curve_2d_nurbs(p, 9).unwrap();
            assert_eq!((c.num_points(), c.degree(), c.dim()), (11, p, 2));
            assert!(c.is_rational());
        }
        assert_eq!(
            thesis_curve_1d(3, 3, 0).unwrap_err().kind(),
            "too_few_control_points"
        );
        assert_eq!(
            thesis_curve_2d_nurbs(0, 0).unwrap_err().kind(),
            "invalid_degree"
        );
        assert!(thesis_curve_2d_nurbs(11, 0).is_err());
    }

    #[test]
    fn near_degenerate_cubic_has_a_flat_inflection() {
        // with eps = 0 the derivative has a double root: check min |C'| over samples is tiny
        // for at least some seeds
        let mut r = rng(3);
        let mut hits = 0;
        for _ in 0..100 {
            let c = near_degenerate_cubic(&mut r);
            let m = (0..=2000)
                .map(|i| c.derivative::<f64>(i as f64 / 2000.0, 1).unwrap()[0].abs())
                .fold(f64::INFINITY, f64::min);
            hits += (m < 1e-3) as usize;
        }
        assert!(hits > 20, "{hits}");
    }
}
