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

/// A Bézier patch of degrees (p, q) on [0, 1]^2 from its coefficient net (and weights).
pub fn bezier_patch(
    p: usize,
    q: usize,
    net: Vec<Vec<Vec<f64>>>,
    weights: Option<Vec<Vec<f64>>>,
) -> NurbsSurface {
    let k = |d: usize| {
        let mut v = vec![0.0; d + 1];
        v.extend(vec![1.0; d + 1]);
        v
    };
    NurbsSurface::new(p, q, k(p), k(q), net, weights).expect("a valid Bézier patch")
}

/// The net (x, y, z) with x, y the identity parametrisation (Bernstein coefficients r/p, c/q)
/// and z_rc given.
fn graph(p: usize, q: usize, z: impl Fn(usize, usize) -> f64) -> Vec<Vec<Vec<f64>>> {
    (0..=p)
        .map(|r| {
            (0..=q)
                .map(|c| vec![r as f64 / p as f64, c as f64 / q as f64, z(r, c)])
                .collect()
        })
        .collect()
}

/// Quarter circle (x, y, w) from angle `a - 45°` to `a + 45°` on the unit circle as a rational
/// quadratic Bézier curve (weights 1, cos 45°, 1).
fn arc(a: f64) -> [(f64, f64, f64); 3] {
    let h = std::f64::consts::FRAC_PI_4;
    let r = std::f64::consts::FRAC_1_SQRT_2;
    let m = 1.0 / r; // the middle control point is at distance 1 / cos 45°
    [
        ((a - h).cos(), (a - h).sin(), 1.0),
        (m * a.cos(), m * a.sin(), r),
        ((a + h).cos(), (a + h).sin(), 1.0),
    ]
}

/// `s` with the knot `t` inserted once in the u direction (Boehm's algorithm, The NURBS Book
/// A5.3 per column; polynomial surfaces only): the same surface on one more span. On dyadic
/// data and knots the affine combinations are exact in f64.
pub fn insert_knot_u(s: &NurbsSurface, t: f64) -> NurbsSurface {
    assert!(!s.is_rational(), "insert_knot_u: polynomial surfaces only");
    let (p, kn) = (s.degree_u(), s.knots_u());
    let k = kn.partition_point(|&x| x <= t) - 1; // t in [u_k, u_{k+1})
    let old = s.control_points();
    let net: Vec<Vec<Vec<f64>>> = (0..=old.len())
        .map(|i| {
            if i + p <= k {
                old[i].clone()
            } else if i > k {
                old[i - 1].clone()
            } else {
                let a = (t - kn[i]) / (kn[i + p] - kn[i]);
                (0..old[i].len())
                    .map(|c| {
                        (0..old[i][c].len())
                            .map(|j| a * old[i][c][j] + (1.0 - a) * old[i - 1][c][j])
                            .collect()
                    })
                    .collect()
            }
        })
        .collect();
    let mut knots = kn.to_vec();
    knots.insert(k + 1, t);
    NurbsSurface::new(p, s.degree_v(), knots, s.knots_v().to_vec(), net, None)
        .expect("knot insertion keeps the surface valid")
}

/// z = -36 (u^2 + v^2 - 1/2)^2 as a degree (4, 4) Bézier patch (exact dyadic Bernstein
/// coefficients): maximum 0 on the circle arc u^2 + v^2 = 1/2 (a ridge along a curve),
/// minimum -81 at (1, 1). Not among [`families`] yet: the fast path's chord proof leaves
/// O(W^4) on a curved ridge, so the maximum side ends at the work limit, a sound bound some
/// 1e-5 above 0 (see `Prover::ridge_line`).
pub fn ridge_circle() -> NurbsSurface {
    let circ = [
        [-9.0, -9.0, -3.0, 9.0, -9.0],
        [-9.0, -9.0, -3.0, 9.0, -9.0],
        [-3.0, -3.0, 1.0, 9.0, -15.0],
        [9.0, 9.0, 9.0, 9.0, -27.0],
        [-9.0, -9.0, -15.0, -27.0, -81.0],
    ];
    bezier_patch(4, 4, graph(4, 4, |r, c| circ[r][c]), None)
}

/// Named test surfaces with known extremes, for the tests, the harness and the benches:
/// `(name, surface, exact box as (lo, hi) per coordinate where known in closed form)`.
#[allow(clippy::type_complexity)]
pub fn families() -> Vec<(&'static str, NurbsSurface, Option<Vec<(f64, f64)>>)> {
    let unit = Some(vec![(0.0, 1.0); 3]);
    let mut out = Vec::new();
    // S = (u, v, u v)
    out.push((
        "bilinear",
        bezier_patch(1, 1, graph(1, 1, |r, c| (r * c) as f64), None),
        unit.clone(),
    ));
    // z = (u - 1/2)^2 - (v - 1/2)^2: a saddle at the centre, extremes on the boundary
    let a = [0.25, -0.25, 0.25];
    out.push((
        "saddle",
        bezier_patch(2, 2, graph(2, 2, |r, c| a[r] - a[c]), None),
        Some(vec![(0.0, 1.0), (0.0, 1.0), (-0.25, 0.25)]),
    ));
    // z = 16 u (1 - u) v (1 - v): an interior maximum 1 at (1/2, 1/2), net maximum 4
    out.push((
        "bump",
        bezier_patch(
            2,
            2,
            graph(2, 2, |r, c| if r == 1 && c == 1 { 4.0 } else { 0.0 }),
            None,
        ),
        unit.clone(),
    ));
    // z = 4 u (1 - u): a ridge (maximum 1 on the whole line u = 1/2)
    out.push((
        "ridge",
        bezier_patch(
            2,
            1,
            graph(2, 1, |r, _| if r == 1 { 2.0 } else { 0.0 }),
            None,
        ),
        unit.clone(),
    ));
    // z = g(u) with Bernstein coefficients 0, 1.3, 0.7, 0.2: a ridge on a non-dyadic line
    // (its value is not a float), constant along v
    let g = [0.0, 1.3, 0.7, 0.2];
    out.push((
        "ridge_cubic",
        bezier_patch(3, 2, graph(3, 2, |r, _| g[r]), None),
        None,
    ));
    // a cylinder patch: (cos t, sin t) for t in [-45°, 45°] along u (rational quadratic arc),
    // the axis along v: a rational ridge x = 1 (up to the rounding of the data) at u = 1/2
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let section = [(h, -h, 1.0), (2.0 * h, 0.0, h), (h, h, 1.0)];
    out.push((
        "cylinder",
        bezier_patch(
            2,
            1,
            section
                .iter()
                .map(|&(x, y, _)| (0..2).map(|c| vec![x, y, c as f64]).collect())
                .collect(),
            Some(section.iter().map(|&(_, _, w)| vec![w; 2]).collect()),
        ),
        None,
    ));
    // an octant of the unit sphere: the row at u = 1 collapses to the pole (0, 0, 1)
    let mer = [
        (1.0, 0.0, 1.0),
        (1.0, 1.0, std::f64::consts::FRAC_1_SQRT_2),
        (0.0, 1.0, 1.0),
    ];
    let rot = mer;
    let (mut net, mut w) = (Vec::new(), Vec::new());
    for &(x, z, wm) in &mer {
        net.push(rot.iter().map(|&(c, s, _)| vec![x * c, x * s, z]).collect());
        w.push(rot.iter().map(|&(_, _, wr)| wm * wr).collect());
    }
    out.push((
        "sphere_pole",
        bezier_patch(2, 2, net, Some(w)),
        unit.clone(),
    ));
    // a torus patch (R = 2, r = 1) around the outer equator: x has an interior maximum 3 at
    // (1/2, 1/2), a rational patch
    let (tube, rot) = (arc(0.0), arc(0.0));
    let (mut net, mut w) = (Vec::new(), Vec::new());
    for &(ct, st, wt) in &tube {
        let rho = 2.0 + ct; // (ρ, z) = (R + r cos θ, r sin θ) in homogeneous form per point
        net.push(
            rot.iter()
                .map(|&(c, s, _)| vec![rho * c, rho * s, st])
                .collect(),
        );
        w.push(rot.iter().map(|&(_, _, wr)| wt * wr).collect());
    }
    let h = std::f64::consts::FRAC_1_SQRT_2;
    out.push((
        "torus",
        bezier_patch(2, 2, net, Some(w)),
        Some(vec![((2.0 + h) * h, 3.0), (-3.0 * h, 3.0 * h), (-h, h)]),
    ));
    // Ridges not along parameter lines (the maximum, or the minimum of a valley, on a whole
    // curve of the domain: a non-isolated critical set). Every net below is the exact
    // Bernstein form of the closed form (dyadic coefficients), so the ridge is exact.
    // z = 1 - (u - v)^2: maximum 1 on the diagonal
    let diag = [[1.0, 1.0, 0.0], [1.0, 1.5, 1.0], [0.0, 1.0, 1.0]];
    out.push((
        "ridge_diagonal",
        bezier_patch(2, 2, graph(2, 2, |r, c| diag[r][c]), None),
        unit.clone(),
    ));
    // z = (u + v - 1)^2: minimum 0 on the anti-diagonal (a valley)
    let valley = [[1.0, 0.0, 0.0], [0.0, -0.5, 0.0], [0.0, 0.0, 1.0]];
    out.push((
        "valley_antidiagonal",
        bezier_patch(2, 2, graph(2, 2, |r, c| valley[r][c]), None),
        unit.clone(),
    ));
    // z = 1 - (u - v / 2 - 1 / 4)^2: maximum 1 on a line of slope 1/2, minimum 7/16 at the
    // corners (1, 0) and (0, 1)
    let rot = [[15.0, 13.0, 7.0], [19.0, 21.0, 19.0], [7.0, 13.0, 15.0]];
    out.push((
        "ridge_rotated",
        bezier_patch(2, 2, graph(2, 2, |r, c| rot[r][c] / 16.0), None),
        Some(vec![(0.0, 1.0), (0.0, 1.0), (7.0 / 16.0, 1.0)]),
    ));
    // z = 24 (s - s^3), s = (u + v) / 2: maximum 16 / sqrt 3 (not a float) on the line
    // u + v = 2 / sqrt 3 (not a float line), minimum 0 at the corners (0, 0) and (1, 1)
    let cub = [
        [0.0, 4.0, 8.0, 9.0],
        [4.0, 8.0, 11.0, 10.0],
        [8.0, 11.0, 12.0, 8.0],
        [9.0, 10.0, 8.0, 0.0],
    ];
    out.push((
        "ridge_irrational",
        bezier_patch(3, 3, graph(3, 3, |r, c| cub[r][c]), None),
        Some(vec![(0.0, 1.0), (0.0, 1.0), (0.0, 16.0 / 3f64.sqrt())]),
    ));
    // the diagonal ridge on 3 x 2 spans (knots 1/2, 3/4 in u, 1/4 in v, inserted exactly:
    // every ratio (t - u_i) / (u_{i+p} - u_i) is dyadic): the ridge crosses the knot lines
    let mut spans = bezier_patch(2, 2, graph(2, 2, |r, c| diag[r][c]), None);
    for t in [0.5, 0.75] {
        spans = insert_knot_u(&spans, t);
    }
    spans = insert_knot_u(&spans.transposed(), 0.25).transposed();
    out.push(("ridge_diagonal_spans", spans, unit.clone()));
    out.push(("random_bicubic", random_surface(1, 3, 3, 0, false), None));
    out.push(("random_rational", random_surface(2, 3, 2, 3, true), None));
    // unclamped (uniform) knots in both directions
    let s = random_surface(3, 2, 3, 2, false);
    let uni = |n: usize| (0..n).map(|i| i as f64).collect::<Vec<_>>();
    let us = NurbsSurface::new(
        2,
        3,
        uni(s.rows() + 3),
        uni(s.cols() + 4),
        s.control_points(),
        None,
    )
    .expect("valid");
    out.push(("unclamped", us, None));
    // a kink: knot 0.5 of multiplicity p = 2 in u
    let net: Vec<Vec<Vec<f64>>> = (0..5)
        .map(|i| {
            (0..3)
                .map(|j| {
                    vec![
                        i as f64,
                        j as f64,
                        [0.0, 1.0, 3.0, 1.0, 0.0][i] - j as f64 * 0.5,
                    ]
                })
                .collect()
        })
        .collect();
    out.push((
        "kink",
        NurbsSurface::new(
            2,
            2,
            vec![0., 0., 0., 0.5, 0.5, 1., 1., 1.],
            vec![0., 0., 0., 1., 1., 1.],
            net,
            None,
        )
        .expect("valid"),
        None,
    ));
    // extreme magnitudes
    let big = random_surface(4, 2, 2, 1, true);
    let scaled = |f: f64| {
        let net: Vec<Vec<Vec<f64>>> = big
            .control_points()
            .into_iter()
            .map(|r| {
                r.into_iter()
                    .map(|p| p.into_iter().map(|x| x * f).collect())
                    .collect()
            })
            .collect();
        NurbsSurface::new(
            2,
            2,
            big.knots_u().to_vec(),
            big.knots_v().to_vec(),
            net,
            big.weights_nested(),
        )
        .expect("valid")
    };
    out.push(("huge", scaled(1e300), None));
    // weights from 1e-150 to 1e150 (the homogeneous products span 1e-300 .. 1e300)
    let w: Vec<Vec<f64>> = (0..big.rows())
        .map(|i| {
            (0..big.cols())
                .map(|j| if (i + j) % 2 == 0 { 1e150 } else { 1e-150 })
                .collect()
        })
        .collect();
    out.push((
        "extreme_weights",
        NurbsSurface::new(
            2,
            2,
            big.knots_u().to_vec(),
            big.knots_v().to_vec(),
            big.control_points(),
            Some(w),
        )
        .expect("valid"),
        None,
    ));
    out.push(("tiny", scaled(1e-300), None));
    out
}
