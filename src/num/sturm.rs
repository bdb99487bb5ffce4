//! Exact sign decisions for a polynomial with integer coefficients on [0, 1], by Sturm
//! sequences: whether f <= 0 on the whole interval, or an exact point where f > 0.
//!
//! This decides what subdivision of the Bernstein coefficients cannot: a maximum of f that is
//! exactly 0 at an irrational or non-dyadic point (a double root of f, a curve touching its
//! bound there), or a maximum a hair below or above 0, where the pieces would have to shrink
//! below the gap's square root before their coefficients show a sign.
//!
//! Sturm's theorem (Sturm 1835; in the form of Basu, Pollack, Roy, *Algorithms in Real
//! Algebraic Geometry*, Thm. 2.50, which needs no square-free assumption): for a polynomial
//! F != 0 and a < b with F(a) F(b) != 0, the number of distinct real roots of F in (a, b) is
//! Var(a) - Var(b), where Var(x) counts the sign changes (zeros dropped) of the sequence
//! S_0 = F, S_1 = F', S_{i+1} = -rem(S_{i-1}, S_i) evaluated at x. Multiplying any element by
//! a positive factor changes no sign, so each remainder is taken as a pseudo-remainder with the
//! positive multiplier |lc(S_i)|^(deg S_{i-1} - deg S_i + 1) and divided by a positive
//! factor: from degree [`SUBRESULTANT_MIN_DEGREE`] on (or for coefficients longer than
//! [`SUBRESULTANT_MIN_BITS`]) the subresultant recurrence's (Collins 1967, Brown & Traub
//! 1971), below it its content (the primitive pseudo-remainder sequence,
//! Collins 1967, whose gcds of coefficients were 85% of a degree-20 end game): all integers,
//! no rational arithmetic.
//!
//! Between consecutive distinct roots F has one sign, so F <= 0 on [0, 1] iff F is <= 0 at the
//! ends and at points between its roots; the roots are isolated by splitting at dyadic points
//! with the same counts (halving, or geometrically next to an end of [0, 1]:
//! [`split_point`]), and an interval holding one root is decided by the signs at its two ends
//! (F keeps the end's sign up to the root).

use num_bigint::{BigInt, Sign};
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

/// What [`at_most_zero`] showed for f on [0, 1].
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Decision {
    /// f <= 0 at every point of [0, 1]
    AtMost,
    /// f(s) > 0 at this s in [0, 1] (exactly)
    Above(BigRational),
    /// not decided within the bisection budget
    Undecided,
}

/// Bisections of [`at_most_zero`] at most (each halves one interval: roots 2^-MAX_BISECTIONS
/// apart are separated, deeper ones left undecided).
const MAX_BISECTIONS: usize = 4096;

/// The power form of the Bernstein polynomial sum b_i B_{i,p}(s) with integer coefficients:
/// a_k = binom(p, k) Δ^k b_0 (forward differences; Farin's monomial form of a Bézier curve), so
/// f(s) = sum a_k s^k, integers again.
pub(crate) fn power_form(b: &[BigInt]) -> Vec<BigInt> {
    let Some(p) = b.len().checked_sub(1) else {
        return Vec::new();
    };
    let mut d = b.to_vec();
    let mut a = Vec::with_capacity(p + 1);
    for k in 0..=p {
        // binom(p, k) as an integer (exact: the product of k consecutive integers over k!)
        let mut c = BigInt::one();
        for i in 0..k {
            c = c * BigInt::from(p - i) / BigInt::from(i + 1);
        }
        a.push(c * &d[0]);
        for i in 0..p - k {
            d[i] = &d[i + 1] - &d[i];
        }
    }
    a
}

/// Whether f(s) = sum a_k s^k (integer coefficients, power form) is <= 0 on [0, 1]; see the
/// module docs.
pub(crate) fn at_most_zero(a: &[BigInt]) -> Decision {
    let mut f = a.to_vec();
    trim(&mut f);
    if f.is_empty() {
        return Decision::AtMost; // f = 0
    }
    let half = BigRational::new(BigInt::one(), BigInt::from(2));
    let (zero, one) = (BigRational::zero(), BigRational::one());
    // the ends: f(0) = a_0, f(1) = sum a_k
    if f[0].is_positive() {
        return Decision::Above(zero);
    }
    if sum(&f).is_positive() {
        return Decision::Above(one);
    }
    // Divide out the roots at the ends: f = s^m (s - 1)^r F with F(0) F(1) != 0. On (0, 1)
    // s^m > 0 and (s - 1)^r has the sign (-1)^r, so f and (-1)^r F have the same sign there;
    // F is replaced by (-1)^r F. (Exact divisions: the constant term is 0, the sum is 0.)
    while f.len() > 1 && f[0].is_zero() {
        f.remove(0);
    }
    let mut flip = false;
    while f.len() > 1 && sum(&f).is_zero() {
        // synthetic division by (s - 1): q_{n-1} = a_n, q_{k-1} = a_k + q_k
        let n = f.len() - 1;
        let mut q = vec![BigInt::zero(); n];
        q[n - 1] = f[n].clone();
        for k in (1..n).rev() {
            q[k - 1] = &f[k] + &q[k];
        }
        f = q;
        flip = !flip;
    }
    if flip {
        f.iter_mut().for_each(|x| *x = -&*x);
    }
    if f.len() == 1 {
        // F a non-zero constant (f(0) = 0 or f(1) = 0 was divided out, or f itself constant)
        return if f[0].is_negative() {
            Decision::AtMost
        } else {
            Decision::Above(half)
        };
    }
    let seq = sturm_sequence(&f);
    // a dyadic point n / 2^e and its data: Var, and the sign of F there
    let at = |n: &BigInt, e: u64| -> (usize, Sign) {
        let signs: Vec<Sign> = seq.iter().map(|s| sign_at(s, n, e)).collect();
        (variations(&signs), signs[0])
    };
    let (n0, n1) = (BigInt::zero(), BigInt::one());
    let (v0, s0) = at(&n0, 0);
    let (v1, s1) = at(&n1, 0);
    // (F(0), F(1) != 0 by construction)
    // intervals (n_a / 2^e, n_b / 2^e) with their Var and F signs at the ends
    let mut stack = vec![(n0, n1, 0u64, (v0, s0), (v1, s1))];
    let mut bisections = 0usize;
    while let Some((na, nb, e, (va, sa), (vb, sb))) = stack.pop() {
        let roots = va.saturating_sub(vb);
        let interior = |n: &BigInt| n.is_positive() && *n < (BigInt::one() << e);
        let dy = |n: BigInt| crate::num::exact::dyadic(n, e);
        // one sign on [a, b] (no root inside): that of F(a)
        if roots == 0 {
            if sa == Sign::Plus {
                // F > 0 on [a, b]: the midpoint, inside (0, 1)
                return Decision::Above(crate::num::exact::dyadic(&na + &nb, e + 1));
            }
            continue;
        }
        // one root r inside: F has F(a)'s sign on [a, r) and F(b)'s on (r, b]
        if roots == 1 && sa == Sign::Minus && sb == Sign::Minus {
            continue;
        }
        if roots == 1 && sa == Sign::Plus && interior(&na) {
            return Decision::Above(dy(na));
        }
        if roots == 1 && sb == Sign::Plus && interior(&nb) {
            return Decision::Above(dy(nb));
        }
        // bisect (at a point that is no root of F: among 1/2, 1/2 + 2^-k of the interval,
        // at most deg F are roots)
        bisections += 1;
        if bisections > MAX_BISECTIONS {
            return Decision::Undecided;
        }
        // (first at the split point of `split_point`, geometric next to an end of [0, 1]; if
        // F vanishes there, from the midpoint as below)
        if let Some((m, em)) = split_point(&na, &nb, e) {
            let (vm, sm) = at(&m, em);
            if sm != Sign::NoSign {
                let s = em - e;
                stack.push((&na << s, m.clone(), em, (va, sa), (vm, sm)));
                stack.push((m, &nb << s, em, (vm, sm), (vb, sb)));
                continue;
            }
        }
        let (na, nb) = (na << 1u64, nb << 1u64);
        let mut e = e + 1;
        let mut m = (&na + &nb) >> 1u64;
        let mut k = 0u64;
        let (mut na, mut nb) = (na, nb);
        let (vm, sm) = loop {
            let r = at(&m, e);
            if r.1 != Sign::NoSign {
                break r;
            }
            // F(m) = 0: m moves right, to 3/4, 7/8, ... of [a, b] (each on a finer grid)
            k += 1;
            if k > f.len() as u64 + 1 {
                return Decision::Undecided;
            }
            na <<= 1u64;
            nb <<= 1u64;
            e += 1;
            m = (m << 1u64) + ((&nb - &na) >> (k + 1));
        };
        stack.push((na.clone(), m.clone(), e, (va, sa), (vm, sm)));
        stack.push((m, nb, e, (vm, sm), (vb, sb)));
    }
    Decision::AtMost
}

/// A split point m / 2^em strictly inside (na / 2^e, nb / 2^e) (0 <= na < nb <= 2^e) that
/// approaches an end of [0, 1] geometrically, or `None` for the midpoint.
///
/// Why: the roots that [`at_most_zero`] must separate can lie within 2^-1000 of an end of
/// [0, 1] (a range-limit curve: control values near f64::MAX next to subnormal ones put the
/// maximum of a span's piece ~2^-1025 from its end), where halving takes one bisection per bit
/// of that distance, each evaluating the whole sequence at a point of as many bits (~1,000
/// bisections, 2-6 ms per decision, four decisions per bound). Here the interval [0, 2^-k]
/// splits at 2^-2k, an interval [a, b] with b >= 8a > 0 at a power of two near sqrt(a b) (and
/// the same for the distances to 1): a distance of 2^-D takes ~log2 D splits to reach, then
/// halving separates what lies there. Any split point strictly inside keeps the bisection's
/// counts and decisions exact (Sturm's theorem holds on every sub-interval; a split point
/// that is a root of F is handled by the caller), so this changes only where it looks.
fn split_point(na: &BigInt, nb: &BigInt, e: u64) -> Option<(BigInt, u64)> {
    let one = BigInt::one() << e;
    // (the distances of the ends from 1: b' = 1 - a, a' = 1 - b, mirrored back below)
    let (da, db) = (&one - nb, &one - na);
    // (l, r): the ends' numerators measured from the nearer end of [0, 1], 0 or 1
    let near_one = da < *na;
    let (l, r) = if near_one { (&da, &db) } else { (na, nb) };
    let (m, em) = if l.is_zero() && r.is_one() && e >= 1 {
        // [0, 2^-e] -> 2^-2e
        (BigInt::one(), 2 * e)
    } else if l.is_positive() && *r >= l * 8u32 {
        // a power of two 2^(c - 1), c = (bits(l) + bits(r)) / 2: bits(r) >= bits(l) + 3 makes
        // bits(l) + 1 <= c <= bits(r) - 2, so l < 2^bits(l) <= 2^(c - 1) < 2^(bits(r) - 1) <= r
        let c = (l.bits() + r.bits()) / 2;
        (BigInt::one() << (c - 1), e)
    } else {
        return None;
    };
    Some(if near_one {
        ((BigInt::one() << em) - m, em)
    } else {
        (m, em)
    })
}

/// Exact Newton iterates towards a critical point of the quotient a / w (power forms with
/// integer coefficients, w > 0 where it matters) from s0: the roots of h = a' w - a w' (the
/// quotient rule's numerator; h = a' w for a constant w), s <- s - h(s) / h'(s) with
/// h' = a'' w - a w'', each iterate rounded to the dyadic grid 2^-bits for bits = `from_bits`,
/// twice that, ... and last `max_bits` (Newton doubles the correct digits per step, so the grid keeps the iterates'
/// length near what they have earned). Only points to try: every use of them evaluates the
/// quotient exactly there. Stops at an exact root of h, a zero h', or a fixed point; iterates
/// outside [0, 1] are dropped.
pub(crate) fn newton_critical(
    a: &[BigInt],
    w: &[BigInt],
    s0: &BigRational,
    (from_bits, max_bits): (u64, u64),
) -> Vec<BigRational> {
    let h = sub(&mul(&derivative(a), w), &mul(a, &derivative(w)));
    let dhp = sub(
        &mul(&derivative(&derivative(a)), w),
        &mul(a, &derivative(&derivative(w))),
    );
    let mut out = Vec::new();
    // s = n / q, q > 0, unreduced (a reduction's gcd of long integers would cost more than
    // the whole step)
    let (mut n, mut q) = (s0.numer().clone(), s0.denom().clone());
    if q.is_negative() {
        (n, q) = (-n, -q);
    }
    let mut bits = from_bits.min(max_bits);
    while q.is_positive() {
        // h(s) = hn / q^dh, h'(s) = dn / q^dd (Horner in integers)
        let (hn, dh) = eval_scaled(&h, &n, &q);
        if hn.is_zero() {
            break;
        }
        let (dn, dd) = eval_scaled(&dhp, &n, &q);
        if dn.is_zero() {
            break;
        }
        // s - h(s) / h'(s) = (n dn q^dh - hn q^(dd + 1)) / (q^(dh + 1) dn)
        let qp = |e: usize| num_traits::pow(q.clone(), e);
        let mut num = &n * &dn * qp(dh) - &hn * qp(dd + 1);
        let mut den = qp(dh + 1) * &dn;
        if den.is_negative() {
            (num, den) = (-num, -den);
        }
        // the nearest point of the grid 2^-bits: floor((2 num 2^bits + den) / (2 den))
        let m = ((num << (bits + 1)) + &den).div_floor(&(den << 1u64));
        let one = BigInt::one() << bits;
        let same = &m * &q == &n << bits;
        if same || m.is_negative() || m > one {
            break;
        }
        out.push(BigRational::new_raw(m.clone(), one.clone()));
        (n, q) = (m, one);
        if bits >= max_bits {
            break;
        }
        bits = (2 * bits).min(max_bits);
    }
    out
}

/// a(n / q) q^deg a = sum a_k n^k q^(deg - k), and deg a (Horner in integers; q > 0; a power
/// of two q, the dyadic points of the Newton grid and of the Sturm bisection, by shifts).
fn eval_scaled(a: &[BigInt], n: &BigInt, q: &BigInt) -> (BigInt, usize) {
    let Some(d) = a.len().checked_sub(1) else {
        return (BigInt::zero(), 0);
    };
    let pow2 = q.trailing_zeros().filter(|&e| e + 1 == q.bits());
    let mut acc = a[d].clone();
    let mut qk = BigInt::one();
    for k in (0..d).rev() {
        let term = match pow2 {
            Some(e) => &a[k] << (e * (d - k) as u64),
            None => {
                qk *= q;
                &a[k] * &qk
            }
        };
        acc = acc * n + term;
    }
    (acc, d)
}

/// The derivative of a power form.
fn derivative(a: &[BigInt]) -> Vec<BigInt> {
    a.iter()
        .enumerate()
        .skip(1)
        .map(|(k, x)| x * BigInt::from(k))
        .collect()
}

/// The product of two power forms (empty: 0).
fn mul(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let mut c = vec![BigInt::zero(); a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            c[i + j] += x * y;
        }
    }
    c
}

/// a - b.
fn sub(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    let mut c = vec![BigInt::zero(); a.len().max(b.len())];
    for (i, x) in a.iter().enumerate() {
        c[i] += x;
    }
    for (i, x) in b.iter().enumerate() {
        c[i] -= x;
    }
    c
}

/// gcd(f, f') of the power form f (integer coefficients), up to a non-zero constant factor: the
/// last element of its Sturm sequence (Euclid's algorithm on the primitive pseudo-remainders;
/// empty for f = 0, a constant for a constant f or a square-free one).
pub(crate) fn gcd_with_derivative(a: &[BigInt]) -> Vec<BigInt> {
    let mut f = a.to_vec();
    trim(&mut f);
    if f.len() <= 1 {
        return f;
    }
    sturm_sequence(&f).pop().unwrap_or_default()
}

/// Drops leading zero coefficients (the highest powers).
fn trim(f: &mut Vec<BigInt>) {
    while f.last().is_some_and(Zero::is_zero) {
        f.pop();
    }
}

fn sum(f: &[BigInt]) -> BigInt {
    f.iter().sum()
}

/// The Sturm sequence of F (degree >= 1) as a signed pseudo-remainder sequence (module docs):
/// each element a positive multiple of the classical one.
fn sturm_sequence(f: &[BigInt]) -> Vec<Vec<BigInt>> {
    let long = f.iter().map(BigInt::bits).max().unwrap_or(0) > SUBRESULTANT_MIN_BITS;
    sturm_sequence_with(f, long || f.len() > SUBRESULTANT_MIN_DEGREE).0
}

/// Coefficients longer than this take the subresultant recurrence at any degree, their first
/// two elements divided by their common power of two alone: the gcds of the primitive parts
/// cost ~O(bits^2) each, and on the range-limit curves (coefficients of ~2,100 bits from data
/// at 2^±1074 and 2^1023, degree 3-4) they were ~80% of a decision.
const SUBRESULTANT_MIN_BITS: u64 = 512;

/// From this degree of F on, the elements after the first two are divided by the subresultant
/// recurrence's factors, below it by their contents (the primitive pseudo-remainder sequence).
/// Measured in wall time: on the tangent curves of degree <= 8 of the far-tie tests the
/// subresultant elements, longer than the primitive ones and divided by multi-word divisors,
/// made the whole enclosure ~7% slower (with ~11% fewer instructions); on random tangencies of
/// degree 20-30 it was 1.6x faster than the primitive sequence.
const SUBRESULTANT_MIN_DEGREE: usize = 12;

/// [`sturm_sequence`] (`subresultant`: by the subresultant recurrence, else by contents), and
/// whether every division of the subresultant recurrence was exact (no element taken as a
/// primitive part after the first two).
fn sturm_sequence_with(f: &[BigInt], subresultant: bool) -> (Vec<Vec<BigInt>>, bool) {
    let df: Vec<BigInt> = f
        .iter()
        .enumerate()
        .skip(1)
        .map(|(k, x)| x * BigInt::from(k))
        .collect();
    // (the first two as primitive parts, or, for the subresultant recurrence, which needs no
    // primitive start, divided by their common power of two: a positive factor either way)
    let start = |x: Vec<BigInt>| {
        if subresultant {
            without_common_twos(x)
        } else {
            primitive(x)
        }
    };
    let mut seq = vec![start(f.to_vec()), start(df)];
    // The subresultant recurrence (Collins 1967, Brown & Traub 1971; Cohen, *A Course in
    // Computational Algebraic Number Theory*, Alg. 3.3.1) on the magnitudes: with g = h = 1 at
    // first, each pseudo-remainder of A by B (degrees differing by d) is divisible by
    // |g| |h|^d exactly, then g = |lc(B)|, h = g^d / h^(d - 1). Our elements differ from that
    // sequence's at most by their signs (a pseudo-remainder of -A or -B is +- that of A and
    // B, and g, h are taken as magnitudes), so the divisions are exact here too, and they are
    // by positive numbers: each element stays a positive multiple of the classical one. No
    // contents are taken (their gcds cost more than the sequence). A division that is not
    // exact (it cannot be) switches to the primitive parts for the rest of the sequence, as
    // does `subresultant` false (below SUBRESULTANT_MIN_DEGREE).
    let (mut g, mut h) = (BigInt::one(), BigInt::one());
    let mut subresultant = subresultant;
    loop {
        let n = seq.len();
        let (a, b) = (&seq[n - 2], &seq[n - 1]);
        let d = (a.len() - b.len()) as u32;
        let mut r = pseudo_remainder(a, b);
        trim(&mut r);
        if r.is_empty() {
            break;
        }
        let lc_b = b[b.len() - 1].abs();
        r.iter_mut().for_each(|x| *x = -&*x);
        if subresultant {
            let div = &g * h.pow(d);
            let mut q = Vec::with_capacity(r.len());
            for x in &r {
                let (y, rem) = x.div_rem(&div);
                if !rem.is_zero() {
                    break;
                }
                q.push(y);
            }
            if q.len() == r.len() {
                seq.push(q);
                g = lc_b;
                h = if d == 0 { h } else { g.pow(d) / h.pow(d - 1) };
                continue;
            }
            subresultant = false;
        }
        seq.push(primitive(r));
    }
    (seq, subresultant)
}

/// x divided by the largest power of two that divides every coefficient (a positive factor).
fn without_common_twos(mut x: Vec<BigInt>) -> Vec<BigInt> {
    let tz = x
        .iter()
        .filter_map(BigInt::trailing_zeros)
        .min()
        .unwrap_or(0);
    if tz > 0 {
        x.iter_mut().for_each(|c| *c >>= tz);
    }
    x
}

/// x divided by the gcd of its coefficients (a positive factor).
fn primitive(mut x: Vec<BigInt>) -> Vec<BigInt> {
    // The coefficients from the shortest up, each first reduced modulo the running gcd g
    // (Euclid's step, one division: gcd(g, c) = gcd(g, c mod g)), so that the binary gcd of
    // num-integer, whose steps each remove about one bit of its longer operand, runs on
    // operands no longer than g; a coefficient that g divides (every one, once g is the
    // content) costs that division alone. Before, each coefficient went into the binary gcd
    // whole: at degree 20-30 those gcds were 85% of an end game of 20-100 ms. (Stopping at 1.)
    let mut order: Vec<usize> = (0..x.len()).filter(|&i| !x[i].is_zero()).collect();
    order.sort_by_key(|&i| x[i].bits());
    let mut g = BigInt::zero();
    for &i in &order {
        let c = &x[i];
        g = if g.is_zero() {
            c.abs()
        } else {
            let r = c % &g;
            if r.is_zero() {
                g
            } else {
                g.gcd(&r)
            }
        };
        if g.is_one() {
            return x;
        }
    }
    if !g.is_zero() && !g.is_one() {
        x.iter_mut().for_each(|c| *c = &*c / &g);
    }
    x
}

/// The remainder of |lc(b)|^(deg a - deg b + 1) a by b (deg a >= deg b >= 0 not required: a
/// of lower degree is its own remainder): a positive multiple of rem(a, b), in integers.
fn pseudo_remainder(a: &[BigInt], b: &[BigInt]) -> Vec<BigInt> {
    let mut r = a.to_vec();
    trim(&mut r);
    let nb = b.len() - 1;
    let lc = &b[nb];
    if r.len() < b.len() {
        return r;
    }
    let steps = r.len() - nb;
    // classical pseudo-division: r <- lc r - r_top x^(i - nb) b, giving lc^steps a mod b
    while r.len() > nb {
        let top = r.pop().unwrap_or_default();
        let i = r.len(); // the popped power
        for x in r.iter_mut() {
            *x *= lc;
        }
        for (k, bk) in b[..nb].iter().enumerate() {
            r[i - nb + k] -= &top * bk;
        }
    }
    // (lc^steps a mod b: negative multiple when lc < 0 and steps odd)
    if lc.is_negative() && steps % 2 == 1 {
        r.iter_mut().for_each(|x| *x = -&*x);
    }
    r
}

/// The sign of s(n / 2^e) ([`eval_scaled`]: the same sign, times 2^(e deg)).
fn sign_at(s: &[BigInt], n: &BigInt, e: u64) -> Sign {
    eval_scaled(s, n, &(BigInt::one() << e)).0.sign()
}

/// Sign changes in a sequence of signs, zeros dropped.
fn variations(signs: &[Sign]) -> usize {
    let mut last = Sign::NoSign;
    let mut v = 0;
    for &s in signs {
        if s == Sign::NoSign {
            continue;
        }
        if last != Sign::NoSign && s != last {
            v += 1;
        }
        last = s;
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_traits::ToPrimitive;
    use rand::{Rng, SeedableRng};

    /// The subresultant recurrence's divisions are exact (no fallback to primitive parts) and
    /// give the primitive sequence's elements up to positive factors: random integer
    /// polynomials of degree 2 to 24 (coefficients up to 2^60, some with repeated factors,
    /// some whose degrees drop by more than one along the sequence), against the primitive
    /// pseudo-remainder sequence computed beside it.
    #[test]
    fn subresultant_divisions_are_exact() {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(38);
        for case in 0..300 {
            let n = r.random_range(2..=24usize);
            let mut f: Vec<BigInt> = (0..=n)
                .map(|_| BigInt::from(r.random_range(-(1i64 << 60)..(1i64 << 60))))
                .collect();
            match case % 4 {
                // a common factor (the subresultant start is not primitive)
                3 => f.iter_mut().for_each(|c| *c *= (3 * 5 * 7) << 9),
                // a square factor: f g^2
                1 => {
                    let g = big(&[r.random_range(-9..9), r.random_range(1..9)]);
                    f = mul(&f, &mul(&g, &g));
                }
                // sparse: only even powers (degree drops of two in the sequence)
                2 => f
                    .iter_mut()
                    .skip(1)
                    .step_by(2)
                    .for_each(|c| *c = BigInt::zero()),
                _ => {}
            }
            trim(&mut f);
            if f.len() < 2 {
                continue;
            }
            let (seq, exact) = sturm_sequence_with(&f, true);
            assert!(exact, "case {case}");
            // the primitive signed pseudo-remainder sequence
            let df = derivative(&f);
            let mut prim = vec![primitive(f.clone()), primitive(df)];
            loop {
                let k = prim.len();
                let mut rem = pseudo_remainder(&prim[k - 2], &prim[k - 1]);
                trim(&mut rem);
                if rem.is_empty() {
                    break;
                }
                rem.iter_mut().for_each(|x| *x = -&*x);
                prim.push(primitive(rem));
            }
            assert_eq!(seq.len(), prim.len(), "case {case}");
            for (a, b) in seq.iter().zip(&prim) {
                let pa = primitive(a.clone());
                assert_eq!(&pa, b, "case {case}");
            }
        }
    }

    fn big(v: &[i64]) -> Vec<BigInt> {
        v.iter().map(|&x| BigInt::from(x)).collect()
    }

    /// f(s) exactly at a rational s (Horner).
    fn value(a: &[BigInt], s: &BigRational) -> BigRational {
        a.iter().rev().fold(BigRational::zero(), |acc, c| {
            acc * s + BigRational::from_integer(c.clone())
        })
    }

    /// The power form against the Bernstein value at a few rationals.
    #[test]
    fn power_form_matches_bernstein_values() {
        let b = big(&[3, -7, 2, 11, -5]);
        let a = power_form(&b);
        for (n, d) in [(0, 1), (1, 3), (1, 2), (5, 7), (1, 1)] {
            let s = BigRational::new(BigInt::from(n), BigInt::from(d));
            let p = b.len() - 1;
            let mut bern = BigRational::zero();
            for (i, bi) in b.iter().enumerate() {
                let c = (0..i).fold(BigInt::one(), |c, k| {
                    c * BigInt::from(p - k) / BigInt::from(k + 1)
                });
                let one = BigRational::one();
                let mut term = BigRational::from_integer(c * bi);
                for _ in 0..i {
                    term *= &s;
                }
                for _ in i..p {
                    term *= &one - &s;
                }
                bern += term;
            }
            assert_eq!(value(&a, &s), bern);
        }
    }

    /// Exact ties and near-ties at irrational and non-dyadic points, decided without
    /// subdivision: -(s^2 - 1/2)^2 (double root at 1/sqrt 2), -(3s - 1)^2 (s + 1), the same
    /// moved by +-2^-200 (a hair above: a witness; below: at most 0), roots at the ends.
    #[test]
    fn ties_and_near_ties_are_decided() {
        // -(2 s^2 - 1)^2 = -(4 s^4 - 4 s^2 + 1)
        let irr = big(&[-1, 0, 4, 0, -4]);
        assert_eq!(at_most_zero(&irr), Decision::AtMost);
        let cub = mul(&big(&[-1, 3]), &mul(&big(&[-1, 3]), &big(&[1, 1])));
        let cub: Vec<BigInt> = cub.iter().map(|x| -x).collect();
        assert_eq!(at_most_zero(&cub), Decision::AtMost);
        for base in [irr, cub] {
            let eps = BigInt::one();
            let shift = 200u64;
            let scaled: Vec<BigInt> = base.iter().map(|x| x << shift).collect();
            let mut up = scaled.clone();
            up[0] += &eps;
            match at_most_zero(&up) {
                Decision::Above(s) => assert!(value(&up, &s).is_positive()),
                d => panic!("{d:?}"),
            }
            let mut dn = scaled.clone();
            dn[0] -= &eps;
            assert_eq!(at_most_zero(&dn), Decision::AtMost);
        }
        // roots at both ends: -s (1 - s) <= 0, s (1 - s) is not; s^2 (s - 1) <= 0
        assert_eq!(at_most_zero(&big(&[0, -1, 1])), Decision::AtMost);
        assert!(matches!(
            at_most_zero(&big(&[0, 1, -1])),
            Decision::Above(_)
        ));
        assert_eq!(at_most_zero(&big(&[0, 0, -1, 1])), Decision::AtMost);
        assert_eq!(at_most_zero(&big(&[])), Decision::AtMost);
        assert_eq!(at_most_zero(&big(&[-3])), Decision::AtMost);
        assert_eq!(at_most_zero(&big(&[0])), Decision::AtMost);
    }

    /// Roots 2^-5000 from an end of [0, 1], farther than the bisection budget of halving
    /// reaches (one bisection per bit: undecided before the geometric split points), decided:
    /// a bump above 0 between two roots at 2^-5000 and 3 2^-5001 from 0 or from 1 (a witness
    /// between them), and a double root there (f <= 0).
    #[test]
    fn roots_next_to_the_ends_are_decided() {
        let d = 5000u64;
        // r1 = 2 / 2^(d+1), r2 = 3 / 2^(d+1): 2^(2d+2) (-(s - r1)(s - r2))
        //   = -2^(2d+2) s^2 + 5 2^(d+1) s - 6
        let bump = vec![
            BigInt::from(-6),
            BigInt::from(5) << (d + 1),
            -(BigInt::one() << (2 * d + 2)),
        ];
        // -(2^d s - 1)^2 = -2^(2d) s^2 + 2^(d+1) s - 1: a double root at 2^-d
        let double = vec![
            BigInt::from(-1),
            BigInt::one() << (d + 1),
            -(BigInt::one() << (2 * d)),
        ];
        // s -> 1 - s: a(1 - s) for a quadratic a0 + a1 s + a2 s^2
        let mirror = |a: &[BigInt]| {
            vec![
                &a[0] + &a[1] + &a[2],
                -&a[1] - (&a[2] << 1u64),
                a[2].clone(),
            ]
        };
        for f in [bump.clone(), mirror(&bump)] {
            match at_most_zero(&f) {
                Decision::Above(s) => assert!(value(&f, &s).is_positive()),
                x => panic!("{x:?}"),
            }
        }
        for f in [double.clone(), mirror(&double)] {
            assert_eq!(at_most_zero(&f), Decision::AtMost);
        }
    }

    /// Every split point lies strictly inside its interval, on random intervals near and away
    /// from the ends of [0, 1].
    #[test]
    fn split_points_lie_inside() {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        let mut geometric = 0;
        for _ in 0..20_000 {
            let e = r.random_range(0..200u64);
            let one = BigInt::one() << e;
            let pick = |r: &mut rand_chacha::ChaCha8Rng| -> BigInt {
                match r.random_range(0..4) {
                    0 => BigInt::zero(),
                    1 => one.clone(),
                    2 => BigInt::one() << r.random_range(0..=e),
                    _ => &one - (BigInt::one() << r.random_range(0..=e)),
                }
            };
            let (a, b) = (pick(&mut r), pick(&mut r));
            let (na, nb) = if a < b { (a, b) } else { (b, a) };
            if na >= nb {
                continue;
            }
            if let Some((m, em)) = split_point(&na, &nb, e) {
                geometric += 1;
                assert!(em >= e);
                let s = em - e;
                assert!((&na << s) < m && m < (&nb << s), "{na} {nb} {e}: {m} {em}");
            }
        }
        assert!(geometric > 3_000, "{geometric}");
    }

    /// Random products of linear and quadratic factors with roots inside and outside [0, 1],
    /// clustered roots, double roots: the decision against dense exact sampling (a witness
    /// must have f > 0; `AtMost` must agree with f <= 0 at 501 points and at the roots'
    /// neighbourhoods, which the construction knows).
    #[test]
    fn decisions_match_the_construction() {
        let mut r = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let mut above = 0;
        let mut at_most = 0;
        for _ in 0..400 {
            // f = c prod (q_i s - p_i)^m_i, roots p_i / q_i
            let mut f = big(&[if r.random_bool(0.5) { 1 } else { -1 }]);
            let mut roots: Vec<(f64, u32)> = Vec::new();
            for _ in 0..r.random_range(1..=4) {
                let q: i64 = r.random_range(1..=40);
                let p: i64 = r.random_range(-10..=50);
                let m = r.random_range(1..=2);
                for _ in 0..m {
                    f = mul(&f, &big(&[-p, q]));
                }
                roots.push((p as f64 / q as f64, m));
            }
            let d = at_most_zero(&f);
            // the truth: f <= 0 on [0, 1] iff f <= 0 at the sample points and just beside
            // every root inside
            let mut pts: Vec<BigRational> = (0..=500)
                .map(|i| BigRational::new(BigInt::from(i), BigInt::from(500)))
                .collect();
            for &(x, _) in &roots {
                for dx in [-1e-6, 1e-6] {
                    let y = x + dx;
                    if (0.0..=1.0).contains(&y) {
                        pts.push(BigRational::from_float(y).unwrap());
                    }
                }
            }
            let truth = pts.iter().all(|s| !value(&f, s).is_positive());
            match d {
                Decision::AtMost => {
                    assert!(truth, "{f:?}");
                    at_most += 1;
                }
                Decision::Above(s) => {
                    assert!(
                        value(&f, &s).is_positive(),
                        "{f:?} at {}",
                        s.to_f64().unwrap()
                    );
                    assert!(s >= BigRational::zero() && s <= BigRational::one());
                    above += 1;
                }
                Decision::Undecided => panic!("undecided {f:?}"),
            }
        }
        assert!(above > 60 && at_most > 60, "{above} {at_most}");
    }
}
