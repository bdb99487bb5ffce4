//! The NURBS surface model: validated data, domain, iso-curves (thesis def. 2.2 and 3.2).

use crate::error::CurveError;
use crate::spline::curve::NurbsCurve;
use crate::spline::knots::find_span;
use std::fmt;
use thiserror::Error;

/// A parameter direction of a surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dir {
    /// along u (the rows `control_points[i]`, degree p, `knots_u`)
    U,
    /// along v (the columns `control_points[..][j]`, degree q, `knots_v`)
    V,
}

impl Dir {
    fn suffix(self) -> &'static str {
        match self {
            Dir::U => "u",
            Dir::V => "v",
        }
    }
}

/// Why a surface description is not a valid NURBS surface (see `docs/formats.md`).
///
/// The rules of one direction (degree, knot vector, domain) are the curve rules, checked by the
/// curve's own validation and reported as [`SurfaceError::Direction`] with the curve's kinds;
/// every message names the field and position (`knots_u[3]`, `control_points[2][1]`).
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum SurfaceError {
    /// A rule of one direction's degree / knot vector (the curve's [`CurveError`]).
    #[error("{}", direction_message(*dir, error))]
    Direction {
        /// which direction
        dir: Dir,
        /// the curve rule that failed (its field names refer to a curve)
        error: CurveError,
    },
    /// Rows of different lengths.
    #[error("control_points[{row}]: has {got} points, but control_points[0] has {expected}; every row of the net must have the same length")]
    RaggedNet {
        /// the offending row
        row: usize,
        /// length of row 0
        expected: usize,
        /// length of this row
        got: usize,
    },
    /// A control point with no coordinates.
    #[error("control_points[{i}][{j}]: a point needs at least one coordinate")]
    ZeroDimension {
        /// row
        i: usize,
        /// column
        j: usize,
    },
    /// Points of different dimensions.
    #[error(
        "control_points[{i}][{j}]: has {got} coordinates, but control_points[0][0] has {expected}"
    )]
    DimensionMismatch {
        /// row
        i: usize,
        /// column
        j: usize,
        /// dimension of P_00
        expected: usize,
        /// dimension of this point
        got: usize,
    },
    /// NaN or infinite coordinate.
    #[error("control_points[{i}][{j}][{coord}]: expected a finite number, got {value}")]
    NonFiniteCoordinate {
        /// row
        i: usize,
        /// column
        j: usize,
        /// coordinate
        coord: usize,
        /// the value
        value: f64,
    },
    /// `weights` not of the net's shape.
    #[error("{}: expected {expected} {}, got {got}", row.map_or("weights".to_string(), |r| format!("weights[{r}]")), if row.is_some() { "weights (one per point of the row)" } else { "rows of weights (one per row of the net)" })]
    WeightCount {
        /// `None`: the number of rows is wrong; `Some(i)`: row i has the wrong length
        row: Option<usize>,
        /// expected count
        expected: usize,
        /// count given
        got: usize,
    },
    /// Non-positive, NaN or infinite weight.
    #[error("weights[{i}][{j}]: expected a finite number > 0, got {value}")]
    InvalidWeight {
        /// row
        i: usize,
        /// column
        j: usize,
        /// the value
        value: f64,
    },
}

/// The curve message with the surface's field names: `degree` -> `degree_u`, `knots` ->
/// `knots_u`, counts in rows / columns.
fn direction_message(dir: Dir, e: &CurveError) -> String {
    let s = dir.suffix();
    let along = match dir {
        Dir::U => "rows (control_points[i])",
        Dir::V => "columns (control_points[..][j])",
    };
    match e {
        CurveError::InvalidDegree(d) => format!("degree_{s}: expected an integer >= 1, got {d}"),
        CurveError::TooFewControlPoints {
            degree,
            needed,
            got,
        } => format!(
            "control_points: degree_{s} = {degree} needs at least {needed} {along}, got {got}"
        ),
        CurveError::KnotCount { expected, got } => {
            format!("knots_{s}: expected {expected} knots ({along} + degree_{s} + 1), got {got}")
        }
        other => {
            let m = other.to_string();
            let m = m.replace("knots[", &format!("knots_{s}["));
            match m.strip_prefix("knots:") {
                Some(rest) => format!("knots_{s}:{rest}"),
                None => m,
            }
        }
    }
}

impl SurfaceError {
    /// A short machine-readable kind, used in JSON error records (the curve kinds for the
    /// rules of one direction, `ragged_net` for rows of different lengths).
    pub fn kind(&self) -> &'static str {
        match self {
            SurfaceError::Direction { error, .. } => error.kind(),
            SurfaceError::RaggedNet { .. } => "ragged_net",
            SurfaceError::ZeroDimension { .. } => "zero_dimension",
            SurfaceError::DimensionMismatch { .. } => "dimension_mismatch",
            SurfaceError::NonFiniteCoordinate { .. } => "non_finite_coordinate",
            SurfaceError::WeightCount { .. } => "weight_count",
            SurfaceError::InvalidWeight { .. } => "invalid_weight",
        }
    }
}

/// A NURBS surface S(u, v) = sum_ij N_{i,p}(u) N_{j,q}(v) w_ij P_ij / sum_ij N_{i,p}(u)
/// N_{j,q}(v) w_ij (thesis def. 3.2; def. 2.2 for w = 1) over the domain
/// [u_p, u_{n+1}] x [v_q, v_{m+1}].
///
/// Invariants established by [`NurbsSurface::new`]: in each direction the curve rules hold
/// (degree >= 1, at least degree + 1 control points, exactly n + p + 2 finite non-decreasing
/// knots, no value repeated more than p + 1 times, a domain of positive length); the net is
/// rectangular, (n + 1) x (m + 1) points of one dimension d >= 1, finite; weights (if any) of
/// the net's shape, finite and > 0. The surface is the one the f64 values define exactly.
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsSurface {
    p: usize,
    q: usize,
    dim: usize,
    rows: usize,
    cols: usize,
    knots_u: Vec<f64>,
    knots_v: Vec<f64>,
    /// P_ij at `points[(i * cols + j) * dim ..][..dim]`
    points: Vec<f64>,
    /// w_ij at `weights[i * cols + j]`; `None` when all weights are 1
    weights: Option<Vec<f64>>,
}

impl NurbsSurface {
    /// Validate and build a surface from the nested net `control_points[i][j]` (i along u).
    pub fn new(
        degree_u: usize,
        degree_v: usize,
        knots_u: Vec<f64>,
        knots_v: Vec<f64>,
        control_points: Vec<Vec<Vec<f64>>>,
        weights: Option<Vec<Vec<f64>>>,
    ) -> Result<Self, SurfaceError> {
        let rows = control_points.len();
        let cols = control_points.first().map_or(0, Vec::len);
        if let Some((row, r)) = control_points
            .iter()
            .enumerate()
            .find(|(_, r)| r.len() != cols)
        {
            return Err(SurfaceError::RaggedNet {
                row,
                expected: cols,
                got: r.len(),
            });
        }
        let dim = control_points
            .first()
            .and_then(|r| r.first())
            .map_or(1, Vec::len);
        let mut points = Vec::with_capacity(rows * cols * dim);
        for (i, r) in control_points.iter().enumerate() {
            for (j, pt) in r.iter().enumerate() {
                if pt.is_empty() {
                    return Err(SurfaceError::ZeroDimension { i, j });
                }
                if pt.len() != dim {
                    return Err(SurfaceError::DimensionMismatch {
                        i,
                        j,
                        expected: dim,
                        got: pt.len(),
                    });
                }
                if let Some(c) = pt.iter().position(|x| !x.is_finite()) {
                    return Err(SurfaceError::NonFiniteCoordinate {
                        i,
                        j,
                        coord: c,
                        value: pt[c],
                    });
                }
                points.extend_from_slice(pt);
            }
        }
        // The rules of each direction are the curve rules: checked by the curve's validation
        // on a 1-D curve with that direction's degree, knots and number of points.
        let check = |dir, p, knots: &[f64], count| {
            NurbsCurve::from_flat(p, 1, knots.to_vec(), vec![0.0; count], None)
                .map(|_| ())
                .map_err(|error| SurfaceError::Direction { dir, error })
        };
        check(Dir::U, degree_u, &knots_u, rows)?;
        check(Dir::V, degree_v, &knots_v, cols)?;
        let weights = match weights {
            None => None,
            Some(w) => {
                if w.len() != rows {
                    return Err(SurfaceError::WeightCount {
                        row: None,
                        expected: rows,
                        got: w.len(),
                    });
                }
                let mut flat = Vec::with_capacity(rows * cols);
                for (i, r) in w.iter().enumerate() {
                    if r.len() != cols {
                        return Err(SurfaceError::WeightCount {
                            row: Some(i),
                            expected: cols,
                            got: r.len(),
                        });
                    }
                    if let Some(j) = r.iter().position(|x| !(x.is_finite() && *x > 0.0)) {
                        return Err(SurfaceError::InvalidWeight { i, j, value: r[j] });
                    }
                    flat.extend_from_slice(r);
                }
                // all weights 1: the polynomial case (the kernels skip the weight row)
                flat.iter().any(|&x| x != 1.0).then_some(flat)
            }
        };
        Ok(NurbsSurface {
            p: degree_u,
            q: degree_v,
            dim,
            rows,
            cols,
            knots_u,
            knots_v,
            points,
            weights,
        })
    }

    /// Degree p (along u).
    pub fn degree_u(&self) -> usize {
        self.p
    }
    /// Degree q (along v).
    pub fn degree_v(&self) -> usize {
        self.q
    }
    /// Dimension d of the control points.
    pub fn dim(&self) -> usize {
        self.dim
    }
    /// Number of rows n + 1 (along u).
    pub fn rows(&self) -> usize {
        self.rows
    }
    /// Number of columns m + 1 (along v).
    pub fn cols(&self) -> usize {
        self.cols
    }
    /// The knot vector U.
    pub fn knots_u(&self) -> &[f64] {
        &self.knots_u
    }
    /// The knot vector V.
    pub fn knots_v(&self) -> &[f64] {
        &self.knots_v
    }
    /// Control point P_ij.
    pub fn control_point(&self, i: usize, j: usize) -> &[f64] {
        let k = (i * self.cols + j) * self.dim;
        &self.points[k..k + self.dim]
    }
    /// All coordinates, row-major (i, then j, then the coordinate).
    pub fn points_flat(&self) -> &[f64] {
        &self.points
    }
    /// Weight w_ij.
    pub fn weight(&self, i: usize, j: usize) -> f64 {
        self.weights.as_ref().map_or(1.0, |w| w[i * self.cols + j])
    }
    /// Whether some weight differs from 1.
    pub fn is_rational(&self) -> bool {
        self.weights.is_some()
    }
    /// The domain ((u_p, u_{n+1}), (v_q, v_{m+1})).
    pub fn domain(&self) -> ((f64, f64), (f64, f64)) {
        (
            (self.knots_u[self.p], self.knots_u[self.rows]),
            (self.knots_v[self.q], self.knots_v[self.cols]),
        )
    }
    /// The net as nested vectors `[i][j][coord]`.
    pub fn control_points(&self) -> Vec<Vec<Vec<f64>>> {
        (0..self.rows)
            .map(|i| {
                (0..self.cols)
                    .map(|j| self.control_point(i, j).to_vec())
                    .collect()
            })
            .collect()
    }
    /// The weights as nested vectors, `None` if all are 1.
    pub fn weights_nested(&self) -> Option<Vec<Vec<f64>>> {
        self.weights
            .as_ref()
            .map(|w| w.chunks(self.cols).map(<[f64]>::to_vec).collect())
    }
    /// Exact (min, max) of coordinate j over the whole net: the control-net box (convex hull
    /// property of the tensor product, weights > 0; min / max of f64 data are exact).
    pub fn coord_range(&self, j: usize) -> (f64, f64) {
        crate::num::min_max(self.points.iter().skip(j).step_by(self.dim).copied())
    }
    /// The largest |coordinate j| over the net (at least the smallest positive normal).
    pub fn coord_scale(&self, j: usize) -> f64 {
        let (lo, hi) = self.coord_range(j);
        lo.abs().max(hi.abs()).max(f64::MIN_POSITIVE)
    }

    /// The same surface with u and v exchanged (S'(v, u) = S(u, v)): rows become columns.
    pub fn transposed(&self) -> NurbsSurface {
        let (r, c, d) = (self.rows, self.cols, self.dim);
        let mut points = Vec::with_capacity(self.points.len());
        for j in 0..c {
            for i in 0..r {
                points.extend_from_slice(self.control_point(i, j));
            }
        }
        let weights = self.weights.as_ref().map(|w| {
            (0..c)
                .flat_map(|j| (0..r).map(move |i| w[i * c + j]))
                .collect()
        });
        NurbsSurface {
            p: self.q,
            q: self.p,
            dim: d,
            rows: c,
            cols: r,
            knots_u: self.knots_v.clone(),
            knots_v: self.knots_u.clone(),
            points,
            weights,
        }
    }

    /// Row i of the net as a curve in v (degree q, knots V, points P_i0 .. P_im with their
    /// weights). Valid by construction: the v rules were checked for the surface.
    pub fn row_curve(&self, i: usize) -> NurbsCurve {
        let k = i * self.cols;
        let pts = self.points[k * self.dim..(k + self.cols) * self.dim].to_vec();
        let w = self.weights.as_ref().map(|w| w[k..k + self.cols].to_vec());
        NurbsCurve::from_flat(self.q, self.dim, self.knots_v.clone(), pts, w)
            .expect("a row of a valid surface is a valid curve")
    }

    /// Column j of the net as a curve in u.
    pub fn column_curve(&self, j: usize) -> NurbsCurve {
        self.transposed().row_curve(j)
    }

    /// The row whose curve *is* the iso-curve S(u*, .), if there is one: at u* the only
    /// non-zero basis function N_{r,p}(u*) = 1 when p knots equal u* next to the span
    /// (a clamped domain end, or an interior knot of multiplicity >= p). `from_left`: the left
    /// limit u -> u*- (the last span ending at u*), else the value at u* (the span starting at
    /// u*; at the right end of the domain, the last span). `None` if no row is exact there.
    pub fn exact_row_at(&self, u: f64, from_left: bool) -> Option<usize> {
        exact_index_at(&self.knots_u, self.p, self.rows - 1, u, from_left)
    }

    /// [`NurbsSurface::exact_row_at`] along v: the column whose curve is S(., v*).
    pub fn exact_column_at(&self, v: f64, from_left: bool) -> Option<usize> {
        exact_index_at(&self.knots_v, self.q, self.cols - 1, v, from_left)
    }

    /// The distinct knot values strictly inside the u domain with multiplicity >= p: the lines
    /// u = u* where S need not be differentiable in u (C^{p-m} at multiplicity m).
    pub fn kink_knots_u(&self) -> Vec<f64> {
        self.column_curve(0).non_differentiable_knots()
    }

    /// The same along v (multiplicity >= q).
    pub fn kink_knots_v(&self) -> Vec<f64> {
        self.row_curve(0).non_differentiable_knots()
    }
}

/// The control point index r with N_{r,p}(u*) = 1 on knots `kn` (n + 1 points), see
/// [`NurbsSurface::exact_row_at`].
fn exact_index_at(kn: &[f64], p: usize, n: usize, u: f64, from_left: bool) -> Option<usize> {
    let (a, b) = (kn[p], kn[n + 1]);
    if !(a..=b).contains(&u) {
        return None;
    }
    if !from_left && u < b {
        // the span k with u_k <= u < u_{k+1}; N_{k-p,p}(u) = 1 iff u_{k-p+1} = .. = u_k = u
        let k = find_span(kn, p, n, u);
        return kn[k + 1 - p..=k].iter().all(|&x| x == u).then_some(k - p);
    }
    if u <= a {
        return None; // no left limit at the start
    }
    // the last span k with u_k < u <= u_{k+1}; N_{k,p}(u-) = 1 iff u_{k+1} = .. = u_{k+p} = u
    let k = (p..=n).rev().find(|&k| kn[k] < u && kn[k + 1] >= u)?;
    (kn[k + 1] == u && kn[k + 1..=k + p].iter().all(|&x| x == u)).then_some(k)
}

impl fmt::Display for Dir {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.suffix())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(crate) fn net(rows: usize, cols: usize) -> Vec<Vec<Vec<f64>>> {
        (0..rows)
            .map(|i| {
                (0..cols)
                    .map(|j| vec![i as f64, j as f64, (i * j) as f64])
                    .collect()
            })
            .collect()
    }

    #[test]
    fn valid_and_transposed() {
        let s = NurbsSurface::new(
            2,
            1,
            vec![0., 0., 0., 1., 1., 1.],
            vec![0., 0., 1., 1.],
            net(3, 2),
            Some(vec![vec![1., 1.], vec![0.5, 0.5], vec![1., 1.]]),
        )
        .unwrap();
        assert!(s.is_rational());
        assert_eq!(s.domain(), ((0., 1.), (0., 1.)));
        let t = s.transposed();
        assert_eq!(t.control_point(1, 2), s.control_point(2, 1));
        assert_eq!(t.weight(0, 1), 0.5);
        assert_eq!(t.transposed(), s);
        assert_eq!(s.row_curve(2).control_point(1), &[2., 1., 2.]);
        assert_eq!(s.column_curve(1).control_point(2), &[2., 1., 2.]);
        assert_eq!(s.exact_row_at(0.0, false), Some(0));
        assert_eq!(s.exact_row_at(1.0, true), Some(2));
        assert_eq!(s.exact_row_at(0.5, false), None);
    }

    #[test]
    fn errors_are_typed_and_positioned() {
        let k2 = vec![0., 0., 0., 1., 1., 1.];
        let k1 = vec![0., 0., 1., 1.];
        let e = |r: Result<NurbsSurface, SurfaceError>| {
            let e = r.unwrap_err();
            (e.kind(), e.to_string())
        };
        let mut ragged = net(3, 2);
        ragged[1].pop();
        let (k, m) = e(NurbsSurface::new(
            2,
            1,
            k2.clone(),
            k1.clone(),
            ragged,
            None,
        ));
        assert_eq!(k, "ragged_net");
        assert!(m.starts_with("control_points[1]"), "{m}");
        let mut bad = net(3, 2);
        bad[2][1][0] = f64::NAN;
        let (k, m) = e(NurbsSurface::new(2, 1, k2.clone(), k1.clone(), bad, None));
        assert_eq!(k, "non_finite_coordinate");
        assert!(m.starts_with("control_points[2][1][0]"), "{m}");
        let (k, m) = e(NurbsSurface::new(
            2,
            1,
            k2[1..].to_vec(),
            k1.clone(),
            net(3, 2),
            None,
        ));
        assert_eq!(k, "knot_count");
        assert!(m.starts_with("knots_u:"), "{m}");
        let mut kv = k1.clone();
        kv[2] = -1.0;
        let (k, m) = e(NurbsSurface::new(2, 1, k2.clone(), kv, net(3, 2), None));
        assert_eq!(k, "decreasing_knots");
        assert!(
            m.starts_with("knots_v[2]") && m.contains("knots_v[1]"),
            "{m}"
        );
        let (k, m) = e(NurbsSurface::new(
            0,
            1,
            k2.clone(),
            k1.clone(),
            net(3, 2),
            None,
        ));
        assert_eq!((k, m.starts_with("degree_u")), ("invalid_degree", true));
        let (k, _) = e(NurbsSurface::new(
            2,
            1,
            k2.clone(),
            k1.clone(),
            net(3, 2),
            Some(vec![vec![1., 1.]; 2]),
        ));
        assert_eq!(k, "weight_count");
        let (k, m) = e(NurbsSurface::new(
            2,
            1,
            k2.clone(),
            k1.clone(),
            net(3, 2),
            Some(vec![vec![1., 1.], vec![1., 0.], vec![1., 1.]]),
        ));
        assert_eq!(k, "invalid_weight");
        assert!(m.starts_with("weights[1][1]"), "{m}");
        let mut dm = net(3, 2);
        dm[1][0].push(1.0);
        let (k, m) = e(NurbsSurface::new(2, 1, k2.clone(), k1.clone(), dm, None));
        assert_eq!(k, "dimension_mismatch");
        assert!(m.starts_with("control_points[1][0]"), "{m}");
        let (k, m) = e(NurbsSurface::new(
            2,
            1,
            k2.clone(),
            k1.clone(),
            net(2, 2),
            None,
        ));
        assert!(
            k == "too_few_control_points" || k == "knot_count",
            "{k} {m}"
        );
        let (k, _) = e(NurbsSurface::new(
            2,
            1,
            k2,
            vec![0., 1., 1., 2.],
            net(3, 2),
            None,
        ));
        assert_eq!(k, "empty_domain");
        let (k, _) = e(NurbsSurface::new(
            usize::MAX,
            1,
            vec![],
            vec![],
            vec![],
            None,
        ));
        assert!(!k.is_empty());
    }
}
