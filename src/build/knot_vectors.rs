//! Knot vector generators: uniform clamped and unclamped vectors ("Uniform Non Rational B-Splines",
//! sec. 2.2 and its `createNodeVector` listing) and the interpolation knots with triple end knots
//! (lab course "B-Spline-Kurven", eqs. 8-9).
//!
//! The uniform vectors use the integers 0, 1, 2, ... as in the source: they are exact in f64
//! (up to 2^53), so the knot differences formed by the kernels are exact too.

use crate::error::CurveError;

fn check(degree: usize, npts: usize) -> Result<(), CurveError> {
    if degree == 0 {
        return Err(CurveError::InvalidDegree(0));
    }
    let needed = degree
        .checked_add(1)
        .ok_or(CurveError::InvalidDegree(degree as u64))?;
    if npts < needed {
        return Err(CurveError::TooFewControlPoints {
            degree,
            needed,
            got: npts,
        });
    }
    Ok(())
}

/// The uniform clamped knot vector for `npts` control points of degree p ("Uniform Non Rational
/// B-Splines", sec. 2.2: KV = [t_0 = ... = t_p, t_{p+1}, ..., t_{m}, t_{m+1} = ... = t_{m+p}]):
/// p + 1 zeros, the interior knots 1, 2, ..., npts - p - 1, and p + 1 copies of npts - p. The
/// domain is [0, npts - p]; the curve interpolates its first and last control points.
///
/// Errors: degree 0, or fewer than p + 1 points.
pub fn uniform_clamped(degree: usize, npts: usize) -> Result<Vec<f64>, CurveError> {
    check(degree, npts)?;
    let last = (npts - degree) as f64;
    let mut k = Vec::with_capacity(npts + degree + 1);
    k.extend(std::iter::repeat_n(0.0, degree + 1));
    k.extend((1..npts - degree).map(|i| i as f64));
    k.extend(std::iter::repeat_n(last, degree + 1));
    Ok(k)
}

/// The uniform unclamped ("floating") knot vector 0, 1, ..., npts + p for `npts` control points of
/// degree p. The domain is [p, npts]; the curve does not in general pass through its end control
/// points ("Uniform Non Rational B-Splines", sec. 2.1, the curves that "end shortly before the last
/// control point").
///
/// Errors: degree 0, or fewer than p + 1 points.
pub fn uniform_unclamped(degree: usize, npts: usize) -> Result<Vec<f64>, CurveError> {
    check(degree, npts)?;
    Ok((0..npts + degree + 1).map(|i| i as f64).collect())
}

/// Knots of the cubic interpolating spline for data parameters t̂_0 < ... < t̂_m (lab course
/// "B-Spline-Kurven", eq. 8: t_{i+3} = t̂_i, and eq. 9: triple end knots, here made fourfold to
/// give the full clamped vector of m + 3 control points, m + 7 knots). The caller guarantees that
/// the parameters are finite and strictly increasing.
pub fn interpolation_knots(params: &[f64]) -> Vec<f64> {
    let (first, last) = (params[0], params[params.len() - 1]);
    let mut k = Vec::with_capacity(params.len() + 6);
    k.extend([first; 3]);
    k.extend_from_slice(params);
    k.extend([last; 3]);
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spline::curve::NurbsCurve;

    #[test]
    fn source_examples() {
        // "Uniform Non Rational B-Splines", sec. 2.2, Bsp 1: (0, 0, 0, 1, 2, 3, 3, 3) for n = 2
        // with five points
        assert_eq!(
            uniform_clamped(2, 5).unwrap(),
            vec![0., 0., 0., 1., 2., 3., 3., 3.]
        );
        // Bsp 3: the cubic Bézier curve (0, 0, 0, 0, 1, 1, 1, 1)
        assert_eq!(
            uniform_clamped(3, 4).unwrap(),
            vec![0., 0., 0., 0., 1., 1., 1., 1.]
        );
        assert_eq!(
            uniform_unclamped(2, 3).unwrap(),
            vec![0., 1., 2., 3., 4., 5.]
        );
        assert_eq!(uniform_clamped(0, 4).unwrap_err().kind(), "invalid_degree");
        assert_eq!(
            uniform_unclamped(3, 3).unwrap_err().kind(),
            "too_few_control_points"
        );
        assert_eq!(
            uniform_clamped(usize::MAX, 3).unwrap_err().kind(),
            "invalid_degree"
        );
    }

    #[test]
    fn generated_vectors_make_valid_curves_with_the_stated_domain() {
        for p in 1..6 {
            for n in p + 1..p + 8 {
                let pts = vec![vec![0.0]; n];
                let c =
                    NurbsCurve::new(p, uniform_clamped(p, n).unwrap(), pts.clone(), None).unwrap();
                assert_eq!(c.domain(), (0.0, (n - p) as f64));
                let c = NurbsCurve::new(p, uniform_unclamped(p, n).unwrap(), pts, None).unwrap();
                assert_eq!(c.domain(), (p as f64, n as f64));
            }
        }
        assert_eq!(
            interpolation_knots(&[0., 1., 3.]),
            vec![0., 0., 0., 0., 1., 3., 3., 3., 3.]
        );
    }
}
