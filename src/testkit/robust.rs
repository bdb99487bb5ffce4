//! Robustness tooling: a decoder that turns arbitrary bytes into (mostly valid, often extreme)
//! curves, and a checker that runs every strategy on a curve and reports any broken guarantee.
//! Shared by the cargo-fuzz targets (`fuzz/`), the long-run harness (`experiments/robust_run.rs`)
//! and the regression tests (`tests/robust.rs`), so a fuzz finding replays exactly in a plain
//! `cargo test`.
//!
//! The decoder is structured (every byte means something about the curve: degree, dimension,
//! knot pattern, magnitudes, weights, raw f64 bit patterns), so coverage-guided fuzzing
//! explores the curve space instead of the JSON grammar; invalid results (NaN bits, wrong
//! counts) are typed [`CurveError`]s, which is part of what is tested.

use crate::enclose::{
    all_strategies, all_strategies_with, BoxEncloser, Enclosure, Guarantee, Settings,
};
use crate::error::CurveError;
use crate::spline::curve::NurbsCurve;
use crate::surface::{NurbsSurface, SurfaceError};
use crate::testkit::validate::{check_containment, dense_params};

/// Reads bytes from the front; zeros once exhausted (so every input decodes).
struct Cursor<'a> {
    d: &'a [u8],
}

impl Cursor<'_> {
    fn u8(&mut self) -> u8 {
        match self.d.split_first() {
            Some((&b, rest)) => {
                self.d = rest;
                b
            }
            None => 0,
        }
    }
    fn f64_bits(&mut self) -> f64 {
        let mut b = [0u8; 8];
        for x in &mut b {
            *x = self.u8();
        }
        f64::from_bits(u64::from_le_bytes(b))
    }
    /// 10^x with x = (byte - 128) * range / 128
    fn pow10(&mut self, range: f64) -> f64 {
        10f64.powf((f64::from(self.u8()) - 128.0) * range / 128.0)
    }
}

/// Limits of [`curve_from_bytes`], so that one fuzz input stays fast to enclose.
pub const MAX_DECODED_DEGREE: usize = 40;
/// See [`MAX_DECODED_DEGREE`].
pub const MAX_DECODED_DIM: usize = 10;
/// See [`MAX_DECODED_DEGREE`].
pub const MAX_DECODED_EXTRA_POINTS: usize = 31;

/// Decode a curve from arbitrary bytes (the structured fuzz target's input).
///
/// Layout (bytes past the end read as 0): degree, dimension, number of extra points, flags
/// (rational, knot style), a magnitude and an offset per coordinate, then per control point and
/// coordinate one byte (255: 8 raw bytes of f64 bits; 254: repeat the previous point's value,
/// which makes flat coordinates), weights (one byte each: 10^(-6..6); 255: raw bits), knot
/// gaps (one byte each, for the raw knot style). The result is whatever [`NurbsCurve::new`]
/// says about the decoded numbers.
pub fn curve_from_bytes(data: &[u8]) -> Result<NurbsCurve, CurveError> {
    let mut r = Cursor { d: data };
    let b0 = r.u8();
    let p = if b0 >= 240 {
        11 + usize::from(r.u8()) % (MAX_DECODED_DEGREE - 10)
    } else {
        1 + usize::from(b0) % 6
    };
    let b1 = r.u8();
    let dim = if b1 % 16 == 15 {
        MAX_DECODED_DIM
    } else {
        1 + usize::from(b1) % 3
    };
    let extra = usize::from(r.u8()) % (MAX_DECODED_EXTRA_POINTS + 1);
    let flags = r.u8();
    let npts = p + 1 + extra;
    // per coordinate: scale 10^(-300..300) (or 1), offset (cancellation)
    let mut scale = vec![1.0; dim];
    let mut offset = vec![0.0; dim];
    for j in 0..dim {
        let s = r.u8();
        scale[j] = if s < 128 {
            1.0
        } else {
            10f64.powf((f64::from(s) - 192.0) * 300.0 / 64.0)
        };
        let o = r.u8();
        offset[j] = if o < 200 {
            0.0
        } else {
            (f64::from(o) - 200.0) * 1e3
        };
    }
    let mut pts = vec![0.0; npts * dim];
    for i in 0..npts {
        for j in 0..dim {
            let v = r.u8();
            pts[i * dim + j] = match v {
                255 => r.f64_bits(),
                254 if i > 0 => pts[(i - 1) * dim + j],
                // the range limits: ±f64::MAX, a signed subnormal
                253 => {
                    if r.u8() % 2 == 0 {
                        f64::MAX
                    } else {
                        -f64::MAX
                    }
                }
                252 => {
                    let b = r.u8();
                    let x = f64::from_bits(u64::from(b >> 1));
                    if b % 2 == 0 {
                        x
                    } else {
                        -x
                    }
                }
                _ => scale[j] * (offset[j] + (f64::from(v) - 127.0) / 64.0),
            };
        }
    }
    let weights = (flags & 1 == 1).then(|| {
        (0..npts)
            .map(|_| {
                let w = r.u8();
                if w == 255 {
                    r.f64_bits()
                } else {
                    10f64.powf((f64::from(w) - 127.0) * 6.0 / 127.0)
                }
            })
            .collect::<Vec<f64>>()
    });
    let m = npts + p; // last knot index
    let ni = npts - p - 1; // interior knots of a clamped vector
    let knots: Vec<f64> = match (flags >> 1) % 6 {
        // clamped uniform
        0 => (0..=m)
            .map(|i| (i.saturating_sub(p).min(ni + 1)) as f64 / (ni + 1) as f64)
            .collect(),
        // unclamped uniform, shifted
        1 => {
            let o = r.pow10(4.0) - 1.0;
            (0..=m).map(|i| o + i as f64).collect()
        }
        // raw bits for every knot (mostly invalid: tests the validation)
        2 => (0..=m).map(|_| r.f64_bits()).collect(),
        // the range limits: clamped at ±f64::MAX, interior knots from bytes among subnormals,
        // zero, ordinary values and fractions of ±f64::MAX (knot differences that overflow)
        5 => {
            let mut v: Vec<f64> = (0..ni)
                .map(|_| {
                    let b = r.u8();
                    match b {
                        0..=31 => f64::from_bits(u64::from(b) + 1),
                        32..=63 => -f64::from_bits(u64::from(b) - 31),
                        64..=95 => 0.0,
                        96..=159 => (f64::from(b) - 128.0) / 16.0,
                        _ => f64::MAX * ((f64::from(b) - 208.0) / 48.0),
                    }
                })
                .collect();
            v.sort_by(f64::total_cmp);
            let lo = if flags & 0x80 == 0 { -f64::MAX } else { 0.0 };
            let mut k = vec![lo; p + 1];
            k.extend(v.into_iter().map(|u| u.max(lo)));
            k.extend(std::iter::repeat_n(f64::MAX, p + 1));
            k
        }
        // gaps from bytes: 0 (multiplicity), 1e-12 .. 1 scaled, clamped ends; domain scale
        style => {
            let dom = r.pow10(300.0);
            let mut v = vec![0.0; p + 1];
            let mut x = 0.0f64;
            for _ in 0..ni {
                let g = r.u8();
                x += match g {
                    0..=63 => 0.0,
                    64..=95 => 1e-12,
                    _ => f64::from(g) / 64.0,
                };
                v.push(x);
            }
            let end = x + 1.0;
            v.extend(std::iter::repeat_n(end, p + 1));
            if style == 4 {
                // unclamped ends: spread the end knots
                for (k, u) in v.iter_mut().enumerate().take(p) {
                    *u = -((p - k) as f64);
                }
                for k in 0..p {
                    v[m - k] = end + (p - k) as f64;
                }
            }
            v.iter().map(|u| u * dom).collect()
        }
    };
    NurbsCurve::new(
        p,
        knots,
        pts.chunks(dim).map(<[f64]>::to_vec).collect(),
        weights,
    )
}

/// Parameters for a soundness check: the dense parameters of [`dense_params`] (ends, every
/// knot, `per_span` points per span) plus `extra` fractions in [0, 1] of the domain.
pub fn check_params(c: &NurbsCurve, per_span: usize, extra: &[f64]) -> Vec<f64> {
    let mut v = dense_params(c, per_span);
    let (a, b) = c.domain();
    for &t in extra {
        if (0.0..=1.0).contains(&t) {
            v.push((a + t * (b - a)).clamp(a, b));
        }
    }
    v
}

/// A broken guarantee found by [`check_strategy`].
#[derive(Debug, Clone, PartialEq)]
pub struct Violation {
    /// strategy name
    pub strategy: &'static str,
    /// what is wrong
    pub what: String,
}

/// Check the guarantees of one enclosure of `c` (see `enclose/mod.rs`): one coordinate box per
/// dimension; for a verified result no NaN, lo <= inner_lo and inner_hi <= hi, and no proven
/// containment miss at `params` (interval evaluation, [`check_containment`]).
pub fn check_enclosure(
    c: &NurbsCurve,
    e: &Enclosure,
    guarantee: Guarantee,
    params: &[f64],
) -> Result<(), String> {
    if !check_boxes(e, c.dim(), guarantee)? {
        return Ok(());
    }
    let r = check_containment(c, e, params);
    if let Some(m) = r.misses.first() {
        return Err(format!(
            "containment miss at u = {:e} (bits {:#x}), coordinate {}: value in [{:e}, {:e}], box [{:e}, {:e}] ({} misses)",
            m.param,
            m.param.to_bits(),
            m.coord,
            m.value_lo,
            m.value_hi,
            m.bound_lo,
            m.bound_hi,
            r.misses.len()
        ));
    }
    Ok(())
}

/// The checks of an enclosure that need no evaluation (curves and surfaces): one box per
/// coordinate; for a verified strategy (`Ok(true)`: go on with containment) the flag, no
/// NaN, no inner bound outside the outer box.
fn check_boxes(e: &Enclosure, dim: usize, guarantee: Guarantee) -> Result<bool, String> {
    if e.coords.len() != dim {
        return Err(format!(
            "{} coordinate boxes for dimension {dim}",
            e.coords.len()
        ));
    }
    if guarantee != Guarantee::Verified {
        return Ok(false);
    }
    if !e.verified {
        return Err("a verified strategy returned verified = false".into());
    }
    for (j, cb) in e.coords.iter().enumerate() {
        let nan = [cb.lo, cb.hi, cb.inner_lo, cb.inner_hi]
            .iter()
            .any(|x| x.is_nan());
        // inner_lo < lo would claim a value below the lower bound (a contradiction); inner_lo
        // above hi is merely a weak claim (every value is <= hi), likewise for inner_hi.
        if nan || cb.inner_lo < cb.lo || cb.inner_hi > cb.hi {
            return Err(format!(
                "coordinate {j}: contradictory bounds: lo {:e} inner_lo {:e} inner_hi {:e} hi {:e}",
                cb.lo, cb.inner_lo, cb.inner_hi, cb.hi
            ));
        }
    }
    Ok(true)
}

/// Run `s` on `c` and check the result ([`check_enclosure`]).
pub fn check_strategy(
    s: &dyn BoxEncloser,
    c: &NurbsCurve,
    params: &[f64],
) -> Result<Enclosure, Violation> {
    let e = s.enclose(c);
    check_enclosure(c, &e, s.guarantee(), params).map_err(|what| Violation {
        strategy: s.name(),
        what,
    })?;
    Ok(e)
}

/// Run every registered strategy ([`all_strategies`], default tolerance) on `c` and check each
/// result at [`check_params`]`(c, per_span, extra)`. Returns every violation found.
pub fn check_all_strategies(c: &NurbsCurve, per_span: usize, extra: &[f64]) -> Vec<Violation> {
    check_strategies(&all_strategies(None), c, per_span, extra)
}

/// [`check_all_strategies`] with the given strategies.
pub fn check_strategies(
    strategies: &[Box<dyn BoxEncloser>],
    c: &NurbsCurve,
    per_span: usize,
    extra: &[f64],
) -> Vec<Violation> {
    let params = check_params(c, per_span, extra);
    strategies
        .iter()
        .filter_map(|s| check_strategy(s.as_ref(), c, &params).err())
        .collect()
}

/// A strategy without the driver: [`BoxEncloser::enclose`] runs its `enclose_prepared` on
/// the curve as given (no rescaling, no span pieces, no range facts), so that tests see the
/// strategy's own arithmetic, whose intermediates may overflow and must stay sound anyway.
pub struct Raw(pub Box<dyn BoxEncloser>);

impl BoxEncloser for Raw {
    fn name(&self) -> &'static str {
        self.0.name()
    }
    fn guarantee(&self) -> Guarantee {
        self.0.guarantee()
    }
    fn enclose_prepared(&self, c: &NurbsCurve) -> Enclosure {
        self.0.enclose_prepared(c)
    }
    fn enclose(&self, c: &NurbsCurve) -> Enclosure {
        self.0.enclose_prepared(c)
    }
}

/// The verified registered strategies as [`Raw`] (without the driver).
pub fn raw_strategies() -> Vec<Box<dyn BoxEncloser>> {
    all_strategies(None)
        .into_iter()
        .filter(|s| s.guarantee() == Guarantee::Verified)
        .map(|s| Box::new(Raw(s)) as Box<dyn BoxEncloser>)
        .collect()
}

/// Every registered strategy with a work budget a hundred times smaller than the default: a
/// fuzzer then runs many more inputs per second and reaches the limit fallbacks (which must
/// be sound too) far more often.
pub fn low_limit_strategies() -> Vec<Box<dyn BoxEncloser>> {
    all_strategies_with(&Settings {
        tol: None,
        max_work: crate::enclose::DEFAULT_MAX_WORK / 100,
    })
}

/// Surfaces larger than this (net size times (p + 1)(q + 1) times dimension) are decoded but
/// not enclosed by the surface target (one input must stay fast).
pub const MAX_SURFACE_WORK: usize = 20_000;

/// Decode a NURBS surface from arbitrary bytes (the surface fuzz target's input): the first
/// byte splits the rest into two parts, each decoded by [`curve_from_bytes`] into a curve
/// C (along u) and D (along v), so surfaces inherit every extreme of the curve decoder
/// (degrees, knot patterns with multiplicities, unclamped and overflowing knots, magnitudes,
/// raw bits, weights). The net is the translational one, P_ij = a_i + b_j over the common
/// dimensions, with weights alpha_i beta_j; then one byte per net point (read from the end
/// of the data) may replace P_ij by the value of a neighbour (flat runs, hence ridges: a
/// curve D with zero points makes S constant along v) or perturb it. `None` when either
/// curve is invalid; otherwise whatever [`NurbsSurface::new`] says.
pub fn surface_from_bytes(data: &[u8]) -> Option<Result<NurbsSurface, SurfaceError>> {
    let (&b0, rest) = data.split_first()?;
    let cut = usize::from(b0) * rest.len() / 256;
    let cu = curve_from_bytes(&rest[..cut]).ok()?;
    let cv = curve_from_bytes(&rest[cut..]).ok()?;
    let dim = cu.dim().min(cv.dim());
    let (n, m) = (cu.num_points(), cv.num_points());
    let mut tail = rest.iter().rev();
    let zero_v = b0 % 7 == 3;
    let mut net: Vec<Vec<Vec<f64>>> = (0..n)
        .map(|i| {
            (0..m)
                .map(|j| {
                    (0..dim)
                        .map(|k| {
                            let b = if zero_v { 0.0 } else { cv.control_point(j)[k] };
                            cu.control_point(i)[k] + b
                        })
                        .collect()
                })
                .collect()
        })
        .collect();
    for i in 0..n {
        for j in 0..m {
            match tail.next().copied().unwrap_or(0) {
                // the neighbour's value: flat runs along v / u
                250 if j > 0 => net[i][j] = net[i][j - 1].clone(),
                251 if i > 0 => net[i][j] = net[i - 1][j].clone(),
                b @ 240..=249 => {
                    for x in &mut net[i][j] {
                        *x += (f64::from(b) - 244.0) / 8.0;
                    }
                }
                _ => {}
            }
        }
    }
    let weights = (cu.weights().is_some() || cv.weights().is_some()).then(|| {
        (0..n)
            .map(|i| (0..m).map(|j| cu.weight(i) * cv.weight(j)).collect())
            .collect()
    });
    Some(NurbsSurface::new(
        cu.degree(),
        cv.degree(),
        cu.knots().to_vec(),
        cv.knots().to_vec(),
        net,
        weights,
    ))
}

/// The surface in the JSON form of `enclose` (for a finding's message).
pub fn surface_json(s: &NurbsSurface) -> String {
    serde_json::json!({
        "degree_u": s.degree_u(),
        "degree_v": s.degree_v(),
        "knots_u": s.knots_u(),
        "knots_v": s.knots_v(),
        "control_points": s.control_points(),
        "weights": s.weights_nested(),
    })
    .to_string()
}

/// Parameters at which a surface target checks containment: a 9 x 9 grid over the domain,
/// the distinct knots inside it in each direction (where pieces meet), and pairs decoded
/// from `extra` (fractions of the domain).
fn surface_params(s: &NurbsSurface, extra: &[f64]) -> Vec<(f64, f64)> {
    let ((a, b), (c, d)) = s.domain();
    let along = |lo: f64, hi: f64, kn: &[f64]| -> Vec<f64> {
        let mut v: Vec<f64> = (0..=8)
            .map(|i| (lo + (hi - lo) * (i as f64 / 8.0)).clamp(lo, hi))
            .filter(|x| x.is_finite())
            .collect();
        v.extend(kn.iter().copied().filter(|&k| k > lo && k < hi));
        v.extend(extra.iter().map(|f| (lo + (hi - lo) * f).clamp(lo, hi)));
        v.retain(|x| x.is_finite());
        v.sort_by(f64::total_cmp);
        v.dedup();
        v
    };
    let (us, vs) = (along(a, b, s.knots_u()), along(c, d, s.knots_v()));
    us.iter()
        .flat_map(|&u| vs.iter().map(move |&v| (u, v)))
        .collect()
}

/// Check a surface enclosure: one box per coordinate, a verified strategy says so, no NaN,
/// no inner bound outside the outer box (a contradiction), and no sampled point (verified
/// interval evaluation) provably outside the box.
pub fn check_surface_enclosure(
    s: &NurbsSurface,
    e: &Enclosure,
    guarantee: Guarantee,
    params: &[(f64, f64)],
) -> Result<(), String> {
    if !check_boxes(e, s.dim(), guarantee)? {
        return Ok(());
    }
    for (j, cb) in e.coords.iter().enumerate() {
        // (a strict witness lies inside the box: the surface reaches a value < witness_lo,
        // none below lo)
        if cb.witness_lo <= cb.lo || cb.witness_hi >= cb.hi {
            return Err(format!("coordinate {j}: a witness outside the box"));
        }
        // (a flag needs an attained bound or a strict witness within one ulp of it)
        if (cb.optimal_lo && cb.inner_lo != cb.lo && cb.witness_lo > cb.lo.next_up())
            || (cb.optimal_hi && cb.inner_hi != cb.hi && cb.witness_hi < cb.hi.next_down())
        {
            return Err(format!(
                "coordinate {j}: an optimal flag on a bound neither attained nor witnessed"
            ));
        }
    }
    for &(u, v) in params {
        let Ok(x) = s.enclose_derivative(u, v, 0, 0) else {
            continue;
        };
        for (j, (xj, cb)) in x.iter().zip(&e.coords).enumerate() {
            if !xj.is_empty() && (xj.inf() > cb.hi || xj.sup() < cb.lo) {
                return Err(format!(
                    "containment miss at ({u:e}, {v:e}), coordinate {j}: value in [{:e}, {:e}], box [{:e}, {:e}]",
                    xj.inf(),
                    xj.sup(),
                    cb.lo,
                    cb.hi
                ));
            }
        }
    }
    Ok(())
}

/// The fuzz target bodies, as plain functions (they panic on a violation, which is what a
/// fuzzer reports; tests call them on the committed corpus).
pub mod targets {
    use super::*;
    use crate::io::{read_curves, write_enclosure_record, write_error_record};

    /// Curves this large are parsed but not enclosed by the fuzz targets (one input must stay
    /// fast; large curves are covered by the tests).
    pub const MAX_WORK: usize = 4000;

    fn small(c: &NurbsCurve) -> bool {
        c.num_points() * (c.degree() + 1) * c.dim() <= MAX_WORK
    }

    /// JSON text -> parse (both stream forms) -> every strategy, checked, and every record
    /// written.
    pub fn json(data: &[u8]) {
        let mut out = Vec::new();
        for (i, r) in read_curves(data) {
            match r {
                Ok(c) if small(&c) => {
                    let v = check_all_strategies(&c, 3, &[]);
                    assert!(
                        v.is_empty(),
                        "curve {i}: {v:?}\n{}",
                        crate::io::curve_to_json(&c)
                    );
                    for s in all_strategies(None) {
                        write_enclosure_record(&mut out, i, &s.enclose(&c), false);
                    }
                }
                Ok(_) => {}
                Err(e) => {
                    assert!(!e.to_string().is_empty());
                    write_error_record(&mut out, i, "", e.kind(), &e.to_string());
                }
            }
        }
    }

    /// Structured bytes -> curve ([`curve_from_bytes`]) -> every strategy (the first byte
    /// chooses the registered, the [`raw_strategies`] or the [`low_limit_strategies`]), checked
    /// against sampled interval evaluations (dense parameters plus parameters decoded from
    /// the tail).
    pub fn structured(data: &[u8]) {
        let Ok(c) = curve_from_bytes(data) else {
            return;
        };
        if !small(&c) {
            return;
        }
        // the last bytes pick extra parameters
        let extra: Vec<f64> = data
            .iter()
            .rev()
            .take(8)
            .map(|&b| f64::from(b) / 255.0)
            .collect();
        let strategies = match data.first().map_or(0, |b| b % 4) {
            0 => all_strategies(None),
            1 => raw_strategies(),
            _ => low_limit_strategies(),
        };
        let v = check_strategies(&strategies, &c, 4, &extra);
        assert!(v.is_empty(), "{v:?}\n{}", crate::io::curve_to_json(&c));
    }

    /// Structured bytes -> surface ([`surface_from_bytes`]) -> every surface strategy (the
    /// first byte chooses default settings or a work limit of one), checked at a grid, the
    /// knot lines and parameters decoded from the tail ([`check_surface_enclosure`]).
    pub fn surface(data: &[u8]) {
        let Some(Ok(s)) = surface_from_bytes(data) else {
            return;
        };
        let work = s.rows() * s.cols() * (s.degree_u() + 1) * (s.degree_v() + 1) * s.dim();
        if work > MAX_SURFACE_WORK {
            return;
        }
        let extra: Vec<f64> = data
            .iter()
            .rev()
            .take(6)
            .map(|&b| f64::from(b) / 255.0)
            .collect();
        let settings = if data.first().is_some_and(|b| b % 4 == 1) {
            Settings {
                max_work: 1,
                ..Settings::default()
            }
        } else {
            Settings::default()
        };
        let params = surface_params(&s, &extra);
        for st in crate::surface::enclose::all_surface_strategies(&settings) {
            let e = st.enclose(&s);
            if let Err(what) = check_surface_enclosure(&s, &e, st.guarantee(), &params) {
                panic!("{}: {what}\n{}", st.name(), surface_json(&s));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decoder_reaches_the_interesting_cases() {
        let mut valid = 0;
        let mut seen_rational = false;
        let mut seen_high = false;
        let mut seen_10d = false;
        let mut seed = 0x9e3779b97f4a7c15u64;
        for _ in 0..2000 {
            let bytes: Vec<u8> = (0..120)
                .map(|_| {
                    seed ^= seed << 13;
                    seed ^= seed >> 7;
                    seed ^= seed << 17;
                    seed as u8
                })
                .collect();
            if let Ok(c) = curve_from_bytes(&bytes) {
                valid += 1;
                seen_rational |= c.is_rational();
                seen_high |= c.degree() > 10;
                seen_10d |= c.dim() == 10;
            }
        }
        assert!(valid > 1000, "{valid}");
        assert!(seen_rational && seen_high && seen_10d);
        assert!(curve_from_bytes(&[]).is_ok());
    }
}
