//! Knot-vector queries: exact span search, multiplicity, non-differentiable knots, and the
//! spans an interval parameter straddles. No epsilons anywhere: comparisons are exact.

use crate::spline::curve::NurbsCurve;

/// Index k of the knot span containing u: `u_k <= u < u_{k+1}`, `p <= k <= n`, with the
/// last non-empty span at the right end of the domain (NURBS Book A2.1 FindSpan, made exact).
///
/// `u` outside the domain is clamped to the first / last span (callers check the domain).
/// `n` is the index of the last control point, so `knots.len() == n + p + 2`.
#[inline]
pub fn find_span(knots: &[f64], p: usize, n: usize, u: f64) -> usize {
    if u >= knots[n + 1] {
        // Right end: the last non-empty span k <= n (exists since the domain is non-empty).
        let mut k = n;
        while k > p && knots[k] >= knots[n + 1] {
            k -= 1;
        }
        return k;
    }
    if u <= knots[p] {
        // Left end (or below): the first non-empty span.
        let mut k = p;
        while k < n && knots[k + 1] <= knots[p] {
            k += 1;
        }
        return k;
    }
    // Largest k in [p, n] with knots[k] <= u; then u < knots[k+1] since u < knots[n+1].
    p + knots[p + 1..=n].partition_point(|&x| x <= u)
}

/// Multiplicity of the value u in the knot vector (0 if u is not a knot). Thesis FindSpanMult.
pub fn multiplicity(knots: &[f64], u: f64) -> usize {
    let lo = knots.partition_point(|&x| x < u);
    let hi = knots.partition_point(|&x| x <= u);
    hi - lo
}

impl NurbsCurve {
    /// Exact span index of u (see [`find_span`]).
    #[inline]
    pub fn find_span(&self, u: f64) -> usize {
        find_span(self.knots(), self.degree(), self.num_points() - 1, u)
    }

    /// The distinct knot values strictly inside the domain, with multiplicities.
    pub fn interior_knots(&self) -> Vec<(f64, usize)> {
        let (a, b) = self.domain();
        let mut out: Vec<(f64, usize)> = Vec::new();
        for &u in self.knots() {
            if u > a && u < b {
                match out.last_mut() {
                    Some((v, m)) if *v == u => *m += 1,
                    _ => out.push((u, 1)),
                }
            }
        }
        out
    }

    /// Interior knots where the curve need not be differentiable: multiplicity >= p
    /// (thesis ch. 6: C is C^{p-k} at a knot of multiplicity k).
    pub fn non_differentiable_knots(&self) -> Vec<f64> {
        let p = self.degree();
        self.interior_knots()
            .into_iter()
            .filter(|&(_, m)| m >= p)
            .map(|(u, _)| u)
            .collect()
    }

    /// The domain cut at the non-differentiable knots: closed pieces on which C is C^1.
    pub fn smooth_pieces(&self) -> Vec<(f64, f64)> {
        let (a, b) = self.domain();
        let mut cuts = vec![a];
        cuts.extend(self.non_differentiable_knots());
        cuts.push(b);
        cuts.windows(2).map(|w| (w[0], w[1])).collect()
    }

    /// Distinct knot values in the closed domain (the span breakpoints).
    pub fn breakpoints(&self) -> Vec<f64> {
        let (a, b) = self.domain();
        let mut v: Vec<f64> = vec![a];
        for &u in self.knots() {
            if u > *v.last().unwrap() && u <= b {
                v.push(u);
            }
        }
        v
    }

    /// The non-empty spans that [a, b] (clipped to the domain) meets, as
    /// `(span index, max(a, u_k), min(b, u_{k+1}))`. Empty if [a, b] misses the domain.
    pub fn spans_straddled(&self, a: f64, b: f64) -> Vec<(usize, f64, f64)> {
        let (d0, d1) = self.domain();
        let (a, b) = (a.max(d0), b.min(d1));
        let mut out = Vec::new();
        // also when a or b is NaN
        if a.partial_cmp(&b).is_none_or(|o| o.is_gt()) {
            return out;
        }
        let kn = self.knots();
        let mut k = self.find_span(a);
        loop {
            let lo = a.max(kn[k]);
            let hi = b.min(kn[k + 1]);
            out.push((k, lo, hi));
            if kn[k + 1] >= b || k + 1 >= self.num_points() {
                break;
            }
            // next non-empty span
            k += 1;
            while kn[k + 1] <= kn[k] {
                k += 1;
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn span_search_exact() {
        let u = [0., 0., 0., 0.5, 0.5, 1., 1., 1.];
        // p = 2, n = 4
        assert_eq!(find_span(&u, 2, 4, 0.0), 2);
        assert_eq!(find_span(&u, 2, 4, 0.49999999999999994), 2);
        assert_eq!(find_span(&u, 2, 4, 0.5), 4);
        assert_eq!(find_span(&u, 2, 4, 1.0), 4);
        assert_eq!(multiplicity(&u, 0.5), 2);
        assert_eq!(multiplicity(&u, 0.3), 0);
    }

    #[test]
    fn span_search_unclamped() {
        let u = [0., 1., 2., 3., 4., 5., 6., 7.]; // p = 3, n = 3, domain [3, 4]
        assert_eq!(find_span(&u, 3, 3, 3.0), 3);
        assert_eq!(find_span(&u, 3, 3, 4.0), 3);
        assert_eq!(find_span(&u, 3, 3, 3.7), 3);
    }

    #[test]
    fn straddled_spans() {
        let c = NurbsCurve::new(
            2,
            vec![0., 0., 0., 0.25, 0.5, 0.5, 1., 1., 1.],
            vec![vec![0.]; 6],
            None,
        )
        .unwrap();
        let s = c.spans_straddled(0.1, 0.6);
        assert_eq!(s, vec![(2, 0.1, 0.25), (3, 0.25, 0.5), (5, 0.5, 0.6)]);
        assert_eq!(c.non_differentiable_knots(), vec![0.5]);
        assert_eq!(c.spans_straddled(1.0, 1.0), vec![(5, 1.0, 1.0)]);
    }
}
