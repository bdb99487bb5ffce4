//! Optimality certificates in the experiments (shared by `reproduce` and `tightness`): counting
//! certified, optimal and falsely certified bounds, and timing a strategy with and without its
//! certificate in the same run.
//!
//! A bound is *certified* when the driver set `optimal_lo` / `optimal_hi` (a proof that lo =
//! RD(min C_j), hi = RU(max C_j); `enclose::certify`). Against the 256-bit reference (feature
//! `mpfr`) a bound is *optimal* when it equals the optimal double
//! (`reference::optimal_bound`), and a certificate is *false* when its bound is not the
//! reference's rounding (`reference::false_certificate`; must never happen).

use nurbs_box::enclose::drive_with;
use nurbs_box::{BoxEncloser, Enclosure, NurbsCurve};
use std::hint::black_box;
use std::time::{Duration, Instant};

/// Counts over bounds (two per coordinate and curve).
#[derive(Default, Clone, Copy, Debug)]
pub struct CertCounts {
    /// bounds seen
    pub bounds: usize,
    /// bounds with a certificate (`optimal_lo` / `optimal_hi` true)
    pub certified: usize,
    /// bounds compared against the reference (0 without it)
    pub vs_reference: usize,
    /// of those, bounds equal to the optimal double
    pub optimal: usize,
    /// of those, certificates whose bound is not the reference's rounding
    pub false_cert: usize,
}

impl CertCounts {
    /// The certificates of `e` (always available, no reference needed).
    pub fn of(e: &Enclosure) -> Self {
        let mut k = CertCounts::default();
        for cb in &e.coords {
            k.bounds += 2;
            k.certified += cb.optimal_lo as usize + cb.optimal_hi as usize;
        }
        k
    }

    /// The certificates of `e` checked against the reference box `rb` of `c`; `each(bound,
    /// optimal double)` sees every bound.
    #[cfg(feature = "mpfr")]
    pub fn against(
        c: &NurbsCurve,
        e: &Enclosure,
        rb: &nurbs_box::testkit::reference::ReferenceBox,
        mut each: impl FnMut(f64, f64),
    ) -> Self {
        use nurbs_box::testkit::reference::{false_certificate, optimal_bound};
        let mut k = CertCounts::of(e);
        for (j, cb) in e.coords.iter().enumerate() {
            let sc = c.coord_scale(j);
            for (bound, exact, up, flag) in [
                (cb.lo, &rb.lo[j], false, cb.optimal_lo),
                (cb.hi, &rb.hi[j], true, cb.optimal_hi),
            ] {
                let opt = optimal_bound(exact, sc, up);
                each(bound, opt);
                k.vs_reference += 1;
                k.optimal += (bound == opt) as usize;
                k.false_cert += (flag && false_certificate(bound, exact, sc, up)) as usize;
            }
        }
        k
    }

    pub fn add(&mut self, o: &CertCounts) {
        self.bounds += o.bounds;
        self.certified += o.certified;
        self.vs_reference += o.vs_reference;
        self.optimal += o.optimal;
        self.false_cert += o.false_cert;
    }

    /// Share of certified bounds in percent, `-` without bounds.
    pub fn certified_pct(&self) -> String {
        pct(self.certified, self.bounds)
    }

    /// Share of optimal bounds among those compared with the reference, `-` without any.
    pub fn optimal_pct(&self) -> String {
        pct(self.optimal, self.vs_reference)
    }
}

/// `100 k / n` with two decimals (`-` for n = 0).
pub fn pct(k: usize, n: usize) -> String {
    if n == 0 {
        "-".to_string()
    } else {
        format!("{:.2}", 100.0 * k as f64 / n as f64)
    }
}

/// The cost of certification in percent: time with it over time without, minus 1 (0 when
/// nothing was timed).
pub fn cost_pct(on: Duration, off: Duration) -> f64 {
    let off = off.as_secs_f64();
    if off > 0.0 {
        100.0 * (on.as_secs_f64() / off - 1.0)
    } else {
        0.0
    }
}

impl OnOff {
    /// The fastest round with and without certification: on a shared machine other jobs only
    /// ever add time, so the minimum is the steadiest estimate of a deterministic call.
    pub fn fastest(&self) -> (Duration, Duration) {
        let min = |v: &[Duration]| v.iter().copied().min().unwrap_or_default();
        (min(&self.on), min(&self.off))
    }
}

/// How [`time_on_off`] repeats: rounds of one batch with the certificate, then one batch
/// without, until at least `min_rounds` rounds and `min_total` wall time (at most `max_rounds`,
/// and no new round once `max_total` has elapsed: at least one round);
/// a batch repeats the call until `batch` has elapsed (at least once, at most `max_batch`).
#[derive(Clone, Copy, Debug)]
pub struct Timing {
    pub batch: Duration,
    pub max_batch: u32,
    pub min_rounds: usize,
    pub max_rounds: usize,
    pub min_total: Duration,
    pub max_total: Duration,
}

/// Times of one strategy on one curve: per round the mean time per call of the batch with the
/// certificate (`s.enclose(c)` = `drive_with(s, c, true)`) and of the batch without
/// (`drive_with(s, c, false)`), and the enclosure of the last certified call.
pub struct OnOff {
    pub on: Vec<Duration>,
    pub off: Vec<Duration>,
    pub enc: Enclosure,
}

/// Time `s` on `c` with and without certification, alternating in rounds so that drift (other
/// jobs, frequency) hits both alike; odd rounds run the batch without the certificate first, so
/// that neither side always meets the cold caches.
pub fn time_on_off(s: &dyn BoxEncloser, c: &NurbsCurve, t: Timing) -> OnOff {
    let mut enc = None;
    let batch = |certify: bool, enc: &mut Option<Enclosure>| {
        let t0 = Instant::now();
        let mut n = 0u32;
        while n == 0 || (t0.elapsed() < t.batch && n < t.max_batch) {
            let e = drive_with(s, black_box(c), certify);
            if certify {
                *enc = Some(e);
            } else {
                black_box(e);
            }
            n += 1;
        }
        t0.elapsed() / n
    };
    let (mut on, mut off) = (Vec::new(), Vec::new());
    let start = Instant::now();
    while on.is_empty()
        || (on.len() < t.max_rounds
            && start.elapsed() < t.max_total
            && (on.len() < t.min_rounds || start.elapsed() < t.min_total))
    {
        if on.len() % 2 == 0 {
            on.push(batch(true, &mut enc));
            off.push(batch(false, &mut enc));
        } else {
            off.push(batch(false, &mut enc));
            on.push(batch(true, &mut enc));
        }
    }
    OnOff {
        on,
        off,
        enc: enc.expect("at least one certified call"),
    }
}
