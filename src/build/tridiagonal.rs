//! Tridiagonal linear systems by the Thomas algorithm (Gaussian elimination without pivoting in LU
//! form; lab course "B-Spline-Kurven", sec. 2.4, "konzentrierter Gaußscher Algorithmus").

use thiserror::Error;

/// Why a tridiagonal system could not be solved.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum TridiagonalError {
    /// The diagonals or the right-hand side have inconsistent lengths.
    #[error("tridiagonal system: diagonals of lengths {a}, {b}, {c} and a right-hand side of {rhs} values with {ncols} columns do not fit together (expected n, n, n and n * ncols)")]
    Shape {
        /// sub-diagonal length
        a: usize,
        /// diagonal length
        b: usize,
        /// super-diagonal length
        c: usize,
        /// right-hand side length
        rhs: usize,
        /// number of right-hand side columns
        ncols: usize,
    },
    /// A pivot b_k - a_k v_k vanished or was not finite: elimination without pivoting breaks
    /// down (the matrix is singular or far from diagonally dominant).
    #[error("tridiagonal system: pivot {row} is {value} (singular or not diagonally dominant)")]
    ZeroPivot {
        /// the row (0-based)
        row: usize,
        /// the pivot value
        value: f64,
    },
}

/// Solve A X = D in place for a tridiagonal n x n matrix A with sub-diagonal `a` (a[0] is not
/// used), diagonal `b` and super-diagonal `c` (c[n-1] is not used); `rhs` holds D row-major with
/// `ncols` columns (one per coordinate; the lab course "B-Spline-Kurven": "this system must be
/// solved for each coordinate"; the factorisation is shared) and is overwritten by X.
///
/// Algorithm (lab course "B-Spline-Kurven", sec. 2.4, compact form):
/// v_1 := a_1 := c_n := y_0 := 0;
/// for k = 1..n: z_k := 1/(b_k - a_k v_k), v_{k+1} := z_k c_k, y_k := z_k (d_k - a_k y_{k-1});
/// x_n := y_n, x_k := y_k - v_{k+1} x_{k+1}. Here the products with z_k are written as
/// divisions by the pivot (one rounding fewer). No pivoting: the source shows stability for
/// diagonally dominant matrices with positive diagonal; the B-spline collocation rows of
/// [`crate::build::interpolate`] are totally positive, for which elimination without pivoting is stable
/// as well (de Boor & Pinkus 1977). A pivot that is zero or not finite is an error.
///
/// Cost O(n * ncols), memory O(n) besides the right-hand side. Plain f64, no guarantee.
pub fn solve_tridiagonal(
    a: &[f64],
    b: &[f64],
    c: &[f64],
    rhs: &mut [f64],
    ncols: usize,
) -> Result<(), TridiagonalError> {
    let n = b.len();
    if a.len() != n || c.len() != n || ncols == 0 || rhs.len() != n * ncols {
        return Err(TridiagonalError::Shape {
            a: a.len(),
            b: n,
            c: c.len(),
            rhs: rhs.len(),
            ncols,
        });
    }
    // v[k] holds v_{k+1} of the source (the super-diagonal of U), 0-based.
    let mut v = vec![0.0; n];
    for k in 0..n {
        let (ak, vk) = if k == 0 { (0.0, 0.0) } else { (a[k], v[k - 1]) };
        let piv = b[k] - ak * vk;
        if piv == 0.0 || !piv.is_finite() {
            return Err(TridiagonalError::ZeroPivot { row: k, value: piv });
        }
        v[k] = if k + 1 < n { c[k] / piv } else { 0.0 };
        for j in 0..ncols {
            let prev = if k == 0 {
                0.0
            } else {
                rhs[(k - 1) * ncols + j]
            };
            rhs[k * ncols + j] = (rhs[k * ncols + j] - ak * prev) / piv;
        }
    }
    for k in (0..n.saturating_sub(1)).rev() {
        for j in 0..ncols {
            rhs[k * ncols + j] -= v[k] * rhs[(k + 1) * ncols + j];
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_system_by_hand() {
        // [2 1 0; 1 3 1; 0 1 2] x = [3, 5, 3] has x = [1, 1, 1]; second column doubled.
        let a = [0.0, 1.0, 1.0];
        let b = [2.0, 3.0, 2.0];
        let c = [1.0, 1.0, 0.0];
        let mut d = [3.0, 6.0, 5.0, 10.0, 3.0, 6.0];
        solve_tridiagonal(&a, &b, &c, &mut d, 2).unwrap();
        for (i, x) in d.iter().enumerate() {
            let want = if i % 2 == 0 { 1.0 } else { 2.0 };
            assert!((x - want).abs() < 1e-15, "{d:?}");
        }
    }

    #[test]
    fn errors_are_typed() {
        let mut d = [1.0, 1.0];
        assert!(matches!(
            solve_tridiagonal(&[0.0, 1.0], &[0.0, 1.0], &[1.0, 0.0], &mut d, 1),
            Err(TridiagonalError::ZeroPivot { row: 0, .. })
        ));
        // [1 1; 1 1] is singular: the second pivot is 0
        assert!(matches!(
            solve_tridiagonal(&[0.0, 1.0], &[1.0, 1.0], &[1.0, 0.0], &mut d, 1),
            Err(TridiagonalError::ZeroPivot { row: 1, .. })
        ));
        assert!(matches!(
            solve_tridiagonal(&[0.0], &[1.0, 1.0], &[1.0, 0.0], &mut d, 1),
            Err(TridiagonalError::Shape { .. })
        ));
        let mut e: [f64; 0] = [];
        solve_tridiagonal(&[], &[], &[], &mut e, 1).unwrap();
    }
}
