//! Deterministic test surfaces (no `rand` needed, so the default build's tests, benches and
//! experiments share them): a small linear congruential generator drives random nets.

use crate::surface::model::NurbsSurface;

/// A tiny deterministic generator (Knuth's MMIX LCG, top 53 bits).
#[derive(Debug, Clone)]
pub struct Lcg(pub u64);

impl Lcg {
    /// A uniform f64 in [0, 1).
    pub fn next_f64(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    /// A uniform f64 in [a, b).
    pub fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next_f64()
    }
}

/// A clamped knot vector on [0, 1] for `n` control points of degree `p`, with sorted random
/// interior knots.
pub fn clamped_knots(g: &mut Lcg, p: usize, n: usize) -> Vec<f64> {
    let mut inner: Vec<f64> = (0..n - p - 1).map(|_| g.range(0.05, 0.95)).collect();
    inner.sort_by(f64::total_cmp);
    let mut k = vec![0.0; p + 1];
    k.extend(inner);
    k.extend(vec![1.0; p + 1]);
    k
}

/// A random 3-D surface of degrees (p, q) with (p + 1 + extra) x (q + 1 + extra) control points
/// in [-1, 1]^3, clamped knots, weights in [0.5, 2] if `rational`.
pub fn random_surface(seed: u64, p: usize, q: usize, extra: usize, rational: bool) -> NurbsSurface {
    let mut g = Lcg(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03);
    let (rows, cols) = (p + 1 + extra, q + 1 + extra);
    let ku = clamped_knots(&mut g, p, rows);
    let kv = clamped_knots(&mut g, q, cols);
    let net: Vec<Vec<Vec<f64>>> = (0..rows)
        .map(|_| {
            (0..cols)
                .map(|_| (0..3).map(|_| g.range(-1.0, 1.0)).collect())
                .collect()
        })
        .collect();
    let w = rational.then(|| {
        (0..rows)
            .map(|_| (0..cols).map(|_| g.range(0.5, 2.0)).collect())
            .collect()
    });
    NurbsSurface::new(p, q, ku, kv, net, w).expect("a valid random surface")
}
