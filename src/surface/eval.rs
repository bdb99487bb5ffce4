//! Surface evaluation, generic over [`Scalar`]: points and partial derivatives S^(k,l)
//! (thesis sec. 2.4; The NURBS Book A3.5 / A3.6 for the tensor-product B-spline, A4.3 / A4.4
//! for the rational quotient), Bézier patch extraction and subdivision.
//!
//! Everything runs on the curve kernels of [`crate::spline`]: a net is a B-spline *curve in u
//! whose control points are whole rows* (`hdim = cols * h`), so one call of the curve's de Boor
//! corner cutting, derivative control points (thesis eq. 2.7), Boehm knot insertion or Bézier
//! extraction acts on every column at once; the v direction is the same on the transposed net.

use crate::error::EvalError;
use crate::num::{binom, Ddi, Scalar};
use crate::spline::bspline::{corner_cut, HSpline};
use crate::spline::de_casteljau_split;
use crate::spline::find_span;
use crate::surface::model::NurbsSurface;
use inari::Interval;

/// A tensor-product B-spline net in homogeneous coordinates: `rows x cols` points of `h` values
/// (w P, w for a rational surface, P otherwise), degrees `p`, `q`, knots `ku`, `kv`.
#[derive(Debug, Clone)]
pub struct Net<S> {
    /// degree along u
    pub p: usize,
    /// degree along v
    pub q: usize,
    /// knots along u (`rows + p + 1`)
    pub ku: Vec<f64>,
    /// knots along v (`cols + q + 1`)
    pub kv: Vec<f64>,
    /// number of rows
    pub rows: usize,
    /// number of columns
    pub cols: usize,
    /// values per point
    pub h: usize,
    /// points, `[(i * cols + j) * h + c]`
    pub pts: Vec<S>,
}

impl<S: Scalar> Net<S> {
    /// The homogeneous net of a surface, P_ij w_ij and w_ij (thesis eq. 3.7 per point; for
    /// intervals the products are outward rounded, so the net encloses the exact one).
    pub fn of(s: &NurbsSurface) -> Self {
        Net {
            p: s.degree_u(),
            q: s.degree_v(),
            ku: s.knots_u().to_vec(),
            kv: s.knots_v().to_vec(),
            rows: s.rows(),
            cols: s.cols(),
            h: s.dim() + s.is_rational() as usize,
            pts: Self::points(s),
        }
    }

    /// The homogeneous points of [`Net::of`] alone (row-major, `dim + rational` values each),
    /// without copies of the knot vectors.
    pub fn points(s: &NurbsSurface) -> Vec<S> {
        let rational = s.is_rational();
        if !rational {
            // (the stored coordinates as they are, in their order)
            return s.points_flat().iter().map(|&x| S::from_f64(x)).collect();
        }
        let h = s.dim() + rational as usize;
        let mut pts = Vec::with_capacity(s.rows() * s.cols() * h);
        for i in 0..s.rows() {
            for j in 0..s.cols() {
                let w = s.weight(i, j);
                for &x in s.control_point(i, j) {
                    pts.push(if rational {
                        S::from_f64(w) * S::from_f64(x)
                    } else {
                        S::from_f64(x)
                    });
                }
                if rational {
                    pts.push(S::from_f64(w));
                }
            }
        }
        pts
    }

    /// The net as a curve in u whose control points are the rows (`cols * h` values each).
    fn as_u_curve(&self) -> HSpline<S> {
        HSpline {
            degree: self.p,
            knots: self.ku.clone(),
            dim: self.cols * self.h,
            rational: false,
            pts: self.pts.clone(),
        }
    }

    fn from_u_curve(c: HSpline<S>, q: usize, kv: Vec<f64>, h: usize) -> Self {
        let cols = c.dim / h;
        Net {
            p: c.degree,
            q,
            rows: c.pts.len() / c.dim.max(1),
            ku: c.knots,
            kv,
            cols,
            h,
            pts: c.pts,
        }
    }

    /// u and v exchanged.
    pub fn transposed(&self) -> Self {
        let h = self.h;
        let mut pts = Vec::with_capacity(self.pts.len());
        for j in 0..self.cols {
            for i in 0..self.rows {
                let k = (i * self.cols + j) * h;
                pts.extend_from_slice(&self.pts[k..k + h]);
            }
        }
        Net {
            p: self.q,
            q: self.p,
            ku: self.kv.clone(),
            kv: self.ku.clone(),
            rows: self.cols,
            cols: self.rows,
            h,
            pts,
        }
    }

    /// The net of d/du (thesis eq. 2.7 applied to the rows: the curve kernel
    /// [`HSpline::derivative`]); degree p - 1, knots u_1 .. u_{m-1}.
    pub fn du(&self) -> Self {
        Net::from_u_curve(
            self.as_u_curve().derivative(),
            self.q,
            self.kv.clone(),
            self.h,
        )
    }

    /// The net of d/dv (the same on the transposed net).
    pub fn dv(&self) -> Self {
        self.transposed().du().transposed()
    }

    /// Span of u (exact, [`find_span`]).
    pub fn span_u(&self, u: f64) -> usize {
        find_span(&self.ku, self.p, self.rows - 1, u)
    }
    /// Span of v.
    pub fn span_v(&self, v: f64) -> usize {
        find_span(&self.kv, self.q, self.cols - 1, v)
    }

    /// The homogeneous point at (u, v) in spans (`ku`, `kv`): de Boor corner cutting in u on
    /// the (p + 1) x (q + 1) block (all q + 1 columns at once, `corner_cut` with `(q+1) h`
    /// rows), then in v on the resulting row (the tensor-product form of NURBS Book A3.5). For
    /// interval u, v inside the closed spans the result encloses the patch over all of them.
    pub fn eval_block(&self, ku: usize, kv: usize, u: &S, v: &S) -> Vec<S> {
        let (p, q, h) = (self.p, self.q, self.h);
        let w = (q + 1) * h;
        let mut buf = Vec::with_capacity((p + 1) * w);
        for i in ku - p..=ku {
            let k = (i * self.cols + kv - q) * h;
            buf.extend_from_slice(&self.pts[k..k + w]);
        }
        corner_cut(&self.ku, p, ku, u, w, &mut buf);
        let mut row = buf.split_off(p * w);
        corner_cut(&self.kv, q, kv, v, h, &mut row);
        row.split_off(q * h)
    }

    /// Bézier patch of spans (`ku`, `kv`) (both non-empty), by the curve's Bézier extraction
    /// (Boehm knot insertion, NURBS Book A5.1 / A5.6) in u on the rows, then in v on the
    /// transposed result. Coefficient `[(r * (q + 1) + c) * h ..]`, r along u.
    pub fn bezier_patch(&self, ku: usize, kv: usize) -> Patch<S> {
        let seg = self.as_u_curve().bezier_segment(ku);
        let strip = Net::from_u_curve(
            HSpline {
                degree: seg.degree,
                knots: vec![seg.a; self.p + 1]
                    .into_iter()
                    .chain(vec![seg.b; self.p + 1])
                    .collect(),
                dim: seg.dim,
                rational: false,
                pts: seg.pts,
            },
            self.q,
            self.kv.clone(),
            self.h,
        );
        let t = strip.transposed();
        let segv = t.as_u_curve().bezier_segment(kv);
        let t2 = Net {
            p: self.q,
            q: self.p,
            ku: Vec::new(),
            kv: Vec::new(),
            rows: self.q + 1,
            cols: self.p + 1,
            h: self.h,
            pts: segv.pts,
        };
        let back = t2.transposed();
        Patch {
            u: (self.ku[ku], self.ku[ku + 1]),
            v: (self.kv[kv], self.kv[kv + 1]),
            p: self.p,
            q: self.q,
            h: self.h,
            pts: back.pts,
        }
    }

    /// Insert the knot u `r` times along u (the curve's Boehm insertion, NURBS Book A5.1, on
    /// the rows: NURBS Book A5.3 SurfaceKnotIns in u). In interval arithmetic the new net
    /// encloses the exact one; `u` must lie in the u domain.
    pub fn insert_knot_u(&self, u: f64, r: usize) -> Self {
        Net::from_u_curve(
            self.as_u_curve().insert_knot(u, r),
            self.q,
            self.kv.clone(),
            self.h,
        )
    }

    /// Insert the knot v `r` times along v (on the transposed net).
    pub fn insert_knot_v(&self, v: f64, r: usize) -> Self {
        self.transposed().insert_knot_u(v, r).transposed()
    }

    /// The non-empty spans along u: indices k with u_k < u_{k+1}, p <= k <= n.
    pub fn spans_u(&self) -> Vec<usize> {
        (self.p..self.rows)
            .filter(|&k| self.ku[k] < self.ku[k + 1])
            .collect()
    }
    /// The non-empty spans along v.
    pub fn spans_v(&self) -> Vec<usize> {
        (self.q..self.cols)
            .filter(|&k| self.kv[k] < self.kv[k + 1])
            .collect()
    }
}

/// A Bézier patch over [u.0, u.1] x [v.0, v.1] in homogeneous coordinates (local parameters in
/// [0, 1]^2): (p + 1) x (q + 1) coefficients of `h` values, `[(r * (q + 1) + c) * h + k]`.
#[derive(Debug, Clone)]
pub struct Patch<S> {
    /// parameter range along u
    pub u: (f64, f64),
    /// parameter range along v
    pub v: (f64, f64),
    /// degree along u
    pub p: usize,
    /// degree along v
    pub q: usize,
    /// values per coefficient
    pub h: usize,
    /// coefficients
    pub pts: Vec<S>,
}

impl<S: Scalar> Patch<S> {
    /// de Casteljau subdivision at local t along u (the curve kernel
    /// [`de_casteljau_split`] on the rows, `(q + 1) h` values each); the parameter ranges of
    /// the halves are f64 approximations of the split point (bookkeeping only).
    pub fn split_u(&self, t: f64) -> (Patch<S>, Patch<S>) {
        let (l, r) = de_casteljau_split(&self.pts, (self.q + 1) * self.h, &S::from_f64(t));
        let m = self.u.0 + t * (self.u.1 - self.u.0);
        (
            Patch {
                u: (self.u.0, m),
                pts: l,
                ..self.meta()
            },
            Patch {
                u: (m, self.u.1),
                pts: r,
                ..self.meta()
            },
        )
    }

    /// de Casteljau subdivision at local t along v (on the transposed coefficients).
    pub fn split_v(&self, t: f64) -> (Patch<S>, Patch<S>) {
        let (l, r) = self.transposed().split_u(t);
        (l.transposed(), r.transposed())
    }

    fn transposed(&self) -> Patch<S> {
        let h = self.h;
        let mut pts = Vec::with_capacity(self.pts.len());
        for c in 0..=self.q {
            for r in 0..=self.p {
                let k = (r * (self.q + 1) + c) * h;
                pts.extend_from_slice(&self.pts[k..k + h]);
            }
        }
        Patch {
            u: self.v,
            v: self.u,
            p: self.q,
            q: self.p,
            h,
            pts,
        }
    }

    fn meta(&self) -> Patch<S> {
        Patch {
            u: self.u,
            v: self.v,
            p: self.p,
            q: self.q,
            h: self.h,
            pts: Vec::new(),
        }
    }

    /// Coefficient (r, c), `h` values.
    pub fn coef(&self, r: usize, c: usize) -> &[S] {
        let k = (r * (self.q + 1) + c) * self.h;
        &self.pts[k..k + self.h]
    }
}

/// Precomputed homogeneous derivative nets A^(a,b), w^(a,b) for a <= K, b <= L (thesis
/// sec. 2.4: the partial derivatives of a tensor product are tensor products of the
/// directions' derivative control points, NURBS Book A3.6), and the rational quotient
/// (NURBS Book A4.4).
#[derive(Debug, Clone)]
pub struct SurfaceEval<S> {
    /// `levels[a][b]`: the net of d^(a+b)/du^a dv^b (`None`: identically zero, a > p or b > q)
    levels: Vec<Vec<Option<Net<S>>>>,
    dim: usize,
    rational: bool,
    domain: ((f64, f64), (f64, f64)),
}

impl<S: Scalar> SurfaceEval<S> {
    /// Derivative nets up to order `k` in u and `l` in v (only those with a + b <= `total`).
    pub fn new(s: &NurbsSurface, k: usize, l: usize, total: usize) -> Self {
        let base = Net::<S>::of(s);
        let mut levels: Vec<Vec<Option<Net<S>>>> = Vec::with_capacity(k + 1);
        let mut row_start = Some(base);
        for a in 0..=k {
            let mut row: Vec<Option<Net<S>>> = Vec::with_capacity(l + 1);
            let mut cur = row_start.clone();
            for b in 0..=l {
                if a + b > total || a > s.degree_u() || b > s.degree_v() {
                    row.push(None);
                    continue;
                }
                row.push(cur.clone());
                cur = cur.map(|n| n.dv());
            }
            levels.push(row);
            row_start = row_start.filter(|_| a < s.degree_u()).map(|n| n.du());
        }
        SurfaceEval {
            levels,
            dim: s.dim(),
            rational: s.is_rational(),
            domain: s.domain(),
        }
    }

    /// The base net (A, w).
    pub fn net(&self) -> &Net<S> {
        self.levels[0][0].as_ref().expect("level 0 exists")
    }

    /// S^(a,b) (Cartesian, `dim` values) for a <= k, b <= l, a + b <= total (`orders` =
    /// (k, l, total); the others
    /// `None`), at (u, v) in the spans (`ku`, `kv`) of the surface. For interval u, v inside
    /// the closed spans every value encloses the derivative over all of them.
    ///
    /// Rational surfaces (NURBS Book A4.4, thesis eq. 3.10 in two variables):
    /// S^(k,l) = (A^(k,l) - sum_{(i,j) != (0,0), i <= k, j <= l} C(k,i) C(l,j) w^(i,j)
    /// S^(k-i,l-j)) / w; binomials up to 50 are exact in f64.
    pub fn derivs_in_span(
        &self,
        ku: usize,
        kv: usize,
        u: &S,
        v: &S,
        (k, l, total): (usize, usize, usize),
    ) -> Vec<Vec<Option<Vec<S>>>> {
        let h = self.dim + self.rational as usize;
        let hom: Vec<Vec<Option<Vec<S>>>> = (0..=k)
            .map(|a| {
                (0..=l)
                    .map(|b| {
                        if a + b > total {
                            return None;
                        }
                        Some(match self.levels.get(a).and_then(|r| r.get(b)) {
                            Some(Some(n)) => n.eval_block(ku - a, kv - b, u, v),
                            _ => vec![S::zero(); h],
                        })
                    })
                    .collect()
            })
            .collect();
        if !self.rational {
            return hom;
        }
        let d = self.dim;
        let w0 = hom[0][0].as_ref().expect("(0,0)")[d].clone();
        let mut out: Vec<Vec<Option<Vec<S>>>> = vec![vec![None; l + 1]; k + 1];
        for a in 0..=k {
            for b in 0..=l {
                let Some(ab) = &hom[a][b] else { continue };
                let mut v: Vec<S> = ab[..d].to_vec();
                for i in 0..=a {
                    for j in 0..=b {
                        if i == 0 && j == 0 {
                            continue;
                        }
                        let wij = hom[i][j].as_ref().expect("inside the triangle")[d].clone();
                        let f = S::from_f64(binom(a, i) * binom(b, j)) * wij;
                        let prev = out[a - i][b - j].as_ref().expect("computed before");
                        for (c, vc) in v.iter_mut().enumerate() {
                            *vc = vc.clone() - f.clone() * prev[c].clone();
                        }
                    }
                }
                for vc in v.iter_mut() {
                    *vc = vc.clone() / w0.clone();
                }
                out[a][b] = Some(v);
            }
        }
        out
    }

    /// S^(k,l)(u, v) at f64 parameters in the domain (k, l within the precomputed orders).
    pub fn derivative(&self, u: f64, v: f64, k: usize, l: usize) -> Result<Vec<S>, EvalError> {
        let ((a, b), (c, d)) = self.domain;
        crate::spline::eval::check_domain((a, b), u)?;
        crate::spline::eval::check_domain((c, d), v)?;
        let n = self.net();
        let mut all = self.derivs_in_span(
            n.span_u(u),
            n.span_v(v),
            &S::from_f64(u),
            &S::from_f64(v),
            (k, l, k + l),
        );
        Ok(all[k][l].take().expect("requested"))
    }
}

impl NurbsSurface {
    /// S(u, v) in any [`Scalar`] (tensor de Boor in homogeneous coordinates); with
    /// `S = Interval` a verified enclosure of the exact point.
    pub fn point<S: Scalar>(&self, u: f64, v: f64) -> Result<Vec<S>, EvalError> {
        self.derivative(u, v, 0, 0)
    }

    /// The partial derivative d^(k+l) S / du^k dv^l at (u, v) in any [`Scalar`]. At a knot the
    /// value is that of the span starting there (the right limit), at the right end of the
    /// domain the left limit, as for curves.
    pub fn derivative<S: Scalar>(
        &self,
        u: f64,
        v: f64,
        k: usize,
        l: usize,
    ) -> Result<Vec<S>, EvalError> {
        SurfaceEval::<S>::new(self, k, l, k + l).derivative(u, v, k, l)
    }

    /// Verified enclosure of S^(k,l)(u, v) at exact f64 parameters: interval arithmetic
    /// intersected with rigorous double-double intervals ([`Ddi`]), both enclosures of the
    /// same value, so about one ulp wide for points.
    pub fn enclose_derivative(
        &self,
        u: f64,
        v: f64,
        k: usize,
        l: usize,
    ) -> Result<Vec<Interval>, EvalError> {
        let a: Vec<Interval> = self.derivative(u, v, k, l)?;
        let b: Vec<Ddi> = self.derivative(u, v, k, l)?;
        Ok(a.into_iter()
            .zip(b)
            .map(|(x, y)| {
                let m = x.intersection(y.to_interval());
                if m.is_empty() {
                    x
                } else {
                    m
                }
            })
            .collect())
    }

    /// All Bézier patches of the surface (one per pair of non-empty spans) in any [`Scalar`];
    /// for a verified type each encloses the exact patch coefficients.
    pub fn bezier_patches<S: Scalar>(&self) -> Vec<Patch<S>> {
        let n = Net::<S>::of(self);
        let (su, sv) = (n.spans_u(), n.spans_v());
        let mut out = Vec::with_capacity(su.len() * sv.len());
        for &ku in &su {
            // extract the strip once per u span, then its v patches
            for &kv in &sv {
                out.push(n.bezier_patch(ku, kv));
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::num::iv;

    /// Bilinear patch S(u, v) = (u, v, u v) on [0, 1]^2.
    pub(crate) fn bilinear() -> NurbsSurface {
        NurbsSurface::new(
            1,
            1,
            vec![0., 0., 1., 1.],
            vec![0., 0., 1., 1.],
            vec![
                vec![vec![0., 0., 0.], vec![0., 1., 0.]],
                vec![vec![1., 0., 0.], vec![1., 1., 1.]],
            ],
            None,
        )
        .unwrap()
    }

    /// A rational patch of the unit sphere (an octant-like piece): the quarter circle in u
    /// (degree 2, weights 1, 1/sqrt2, 1) swept as a quarter circle of latitude in v.
    pub(crate) fn sphere_patch() -> NurbsSurface {
        let r = std::f64::consts::FRAC_1_SQRT_2;
        // meridian (x, z) quarter circle from the equator to the pole: (1,0),(1,1),(0,1)
        let mer = [(1.0, 0.0, 1.0), (1.0, 1.0, r), (0.0, 1.0, 1.0)];
        // rotation about z by a quarter circle: (1,0),(1,1),(0,1) in (x, y)
        let rot = [(1.0, 0.0, 1.0), (1.0, 1.0, r), (0.0, 1.0, 1.0)];
        let mut net = Vec::new();
        let mut w = Vec::new();
        for &(x, z, wm) in &mer {
            let mut row = Vec::new();
            let mut wr = Vec::new();
            for &(c, s, wr0) in &rot {
                row.push(vec![x * c, x * s, z]);
                wr.push(wm * wr0);
            }
            net.push(row);
            w.push(wr);
        }
        NurbsSurface::new(
            2,
            2,
            vec![0., 0., 0., 1., 1., 1.],
            vec![0., 0., 0., 1., 1., 1.],
            net,
            Some(w),
        )
        .unwrap()
    }

    #[test]
    fn bilinear_closed_form_and_derivatives() {
        let s = bilinear();
        for i in 0..=8 {
            for j in 0..=8 {
                let (u, v) = (i as f64 / 8.0, j as f64 / 8.0);
                assert_eq!(s.point::<f64>(u, v).unwrap(), vec![u, v, u * v]);
                assert_eq!(s.derivative::<f64>(u, v, 1, 0).unwrap(), vec![1., 0., v]);
                assert_eq!(s.derivative::<f64>(u, v, 0, 1).unwrap(), vec![0., 1., u]);
                assert_eq!(s.derivative::<f64>(u, v, 1, 1).unwrap(), vec![0., 0., 1.]);
                assert_eq!(s.derivative::<f64>(u, v, 2, 0).unwrap(), vec![0., 0., 0.]);
                let e = s.enclose_derivative(u, v, 0, 0).unwrap();
                assert!(e[2].contains(u * v));
            }
        }
        assert_eq!(
            s.point::<f64>(1.5, 0.0).unwrap_err().kind(),
            "param_out_of_domain"
        );
    }

    #[test]
    fn rational_sphere_patch_lies_on_the_sphere() {
        let s = sphere_patch();
        for i in 0..=10 {
            for j in 0..=10 {
                let (u, v) = (i as f64 / 10.0, j as f64 / 10.0);
                let e = s.enclose_derivative(u, v, 0, 0).unwrap();
                let r2 = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
                assert!(r2.contains(1.0), "{u} {v} {} {}", r2.inf(), r2.sup());
                assert!(r2.wid() < 1e-14);
                // tangents are orthogonal to the position (|S|^2 = 1 => S . S_u = 0)
                let du: Vec<f64> = s.derivative(u, v, 1, 0).unwrap();
                let dv: Vec<f64> = s.derivative(u, v, 0, 1).unwrap();
                let p: Vec<f64> = s.point(u, v).unwrap();
                let dot = |a: &[f64]| a.iter().zip(&p).map(|(x, y)| x * y).sum::<f64>();
                assert!(dot(&du).abs() < 1e-13 && dot(&dv).abs() < 1e-13);
                // the mixed derivative against a central difference of S_u in v
                if (1..10).contains(&j) {
                    let hh = 1e-6;
                    let a: Vec<f64> = s.derivative(u, v + hh, 1, 0).unwrap();
                    let b: Vec<f64> = s.derivative(u, v - hh, 1, 0).unwrap();
                    let m: Vec<f64> = s.derivative(u, v, 1, 1).unwrap();
                    for c in 0..3 {
                        assert!(((a[c] - b[c]) / (2.0 * hh) - m[c]).abs() < 1e-6);
                    }
                }
            }
        }
        // the pole row collapses to one point: S(1, v) = (0, 0, 1) exactly
        for j in 0..=4 {
            let p: Vec<f64> = s.point(1.0, j as f64 / 4.0).unwrap();
            assert_eq!(p, vec![0., 0., 1.]);
        }
    }

    #[test]
    fn partition_of_unity_and_boundary_is_the_row_curve() {
        // the 1-D surface with all control points 1 is identically 1 (sum N_i N_j = 1)
        let knots = vec![0., 0., 0., 0.3, 0.6, 1., 1., 1.];
        let kv = vec![0., 0., 0., 0., 0.5, 1., 1., 1., 1.];
        let net: Vec<Vec<Vec<f64>>> = vec![vec![vec![1.0]; 5]; 5];
        let w: Vec<Vec<f64>> = (0..5)
            .map(|i| (0..5).map(|j| 1.0 + ((i * 7 + j * 3) % 5) as f64).collect())
            .collect();
        let s = NurbsSurface::new(2, 3, knots.clone(), kv.clone(), net, Some(w)).unwrap();
        for i in 0..=12 {
            for j in 0..=12 {
                let e = s
                    .enclose_derivative(i as f64 / 12.0, j as f64 / 12.0, 0, 0)
                    .unwrap();
                assert!(e[0].contains(1.0) && e[0].wid() < 1e-15);
                let d = s
                    .enclose_derivative(i as f64 / 12.0, j as f64 / 12.0, 1, 1)
                    .unwrap();
                assert!(d[0].contains(0.0) && d[0].wid() < 1e-12);
            }
        }
        // a general surface: at the clamped boundary u = 0 the surface is the row-0 curve
        let s = crate::surface::gen::random_surface(7, 3, 2, 3, true);
        let c = s.row_curve(0);
        let ((a, _), _) = s.domain();
        for j in 0..=10 {
            let v = j as f64 / 10.0;
            let x: Vec<f64> = s.point(a, v).unwrap();
            let y: Vec<f64> = c.point(v).unwrap();
            for k in 0..3 {
                assert!((x[k] - y[k]).abs() < 1e-13);
            }
        }
    }

    #[test]
    fn knot_insertion_keeps_the_surface() {
        let s = crate::surface::gen::random_surface(5, 2, 3, 2, true);
        let n = Net::<Interval>::of(&s);
        let m = n.insert_knot_u(0.37, 2).insert_knot_v(0.61, 1);
        assert_eq!((m.rows, m.cols), (n.rows + 2, n.cols + 1));
        for i in 0..=6 {
            for j in 0..=6 {
                let (u, v) = (i as f64 / 6.0, j as f64 / 6.0);
                let a = n.eval_block(n.span_u(u), n.span_v(v), &iv::point(u), &iv::point(v));
                let b = m.eval_block(m.span_u(u), m.span_v(v), &iv::point(u), &iv::point(v));
                for (x, y) in a.iter().zip(&b) {
                    // both enclose the same exact homogeneous point
                    assert!(!x.intersection(*y).is_empty(), "{u} {v}");
                    assert!(y.wid() < 1e-13);
                }
            }
        }
    }

    #[test]
    fn patches_and_interval_boxes_enclose_samples() {
        let s = crate::surface::gen::random_surface(3, 2, 3, 2, true);
        let patches = s.bezier_patches::<Interval>();
        let e = SurfaceEval::<Interval>::new(&s, 1, 1, 2);
        let n = e.net().clone();
        for pa in &patches {
            // the patch's corner coefficients are the surface's corner values
            let corner: Vec<f64> = s.point(pa.u.0, pa.v.0).unwrap();
            let c = pa.coef(0, 0);
            let w = c[3];
            for k in 0..3 {
                assert!(
                    (c[k] / w).contains(corner[k]) || ((c[k] / w).mid() - corner[k]).abs() < 1e-12
                );
            }
            let (l, r) = pa.split_u(0.5);
            let (l2, _) = r.split_v(0.25);
            assert!(l.u.1 == r.u.0 && l2.v.1 < pa.v.1);
            // an interval box in the patch encloses sampled values and derivatives
            let ku = n.span_u(0.5 * (pa.u.0 + pa.u.1));
            let kv = n.span_v(0.5 * (pa.v.0 + pa.v.1));
            let bu = iv::span(pa.u.0, pa.u.1);
            let bv = iv::span(pa.v.0, pa.v.1);
            let encl = e.derivs_in_span(ku, kv, &bu, &bv, (1, 1, 2));
            for i in 0..=4 {
                for j in 0..=4 {
                    let u = pa.u.0 + (pa.u.1 - pa.u.0) * i as f64 / 4.0;
                    let v = pa.v.0 + (pa.v.1 - pa.v.0) * j as f64 / 4.0;
                    let f: Vec<Interval> = e
                        .derivs_in_span(ku, kv, &iv::point(u), &iv::point(v), (1, 1, 2))
                        .into_iter()
                        .flatten()
                        .flatten()
                        .flatten()
                        .collect();
                    let g: Vec<Interval> =
                        encl.iter().flatten().flatten().flatten().copied().collect();
                    for (a, b) in f.iter().zip(&g) {
                        assert!(b.inf() <= a.inf() && a.sup() <= b.sup());
                    }
                }
            }
        }
    }
}
