//! EXPERIMENT (for the lead; delete once decided): point-enclosure width of interval de Boor
//! with the thesis's convex-combination form a*(R1 - R2) + R2 (thesis sec. 5.1, used by
//! `HSpline::eval_span`) versus (1 - a)*R2 + a*R1 with 1 - a formed directly as
//! (u_{i+p+1-r} - u) / (u_{i+p+1-r} - u_i), and versus the intersection of both.
//! For a point parameter the thesis form widens every level by a factor up to 1 + 2a
//! (up to 3^p overall); the other form keeps the width ~ rounding.
//! This is a second copy of the de Boor triangle on purpose (the alternative under test).
//!
//! Run: `cargo run --release --example convex_form`

use inari::Interval;
use nurbs_box::gen::{self, GenParams};
use nurbs_box::scalar::{iv, ulp};
use nurbs_box::{project, HSpline};
use rand::Rng;
/// de Boor on span k at the point u, with the alternative form (and optionally intersected).
fn eval_alt(h: &HSpline<Interval>, k: usize, u: f64, both: bool) -> Vec<Interval> {
    let p = h.degree;
    let hd = h.hdim();
    let mut out: Vec<Interval> = h.pts[(k - p) * hd..(k + 1) * hd].to_vec();
    let uu = iv::point(u);
    for r in 1..=p {
        for j in (r..=p).rev() {
            let i = k - p + j;
            let a = (uu - iv::point(h.knots[i]))
                / (iv::point(h.knots[i + p + 1 - r]) - iv::point(h.knots[i]));
            let b = (iv::point(h.knots[i + p + 1 - r]) - uu)
                / (iv::point(h.knots[i + p + 1 - r]) - iv::point(h.knots[i]));
            for c in 0..hd {
                let hi = out[j * hd + c];
                let lo = out[(j - 1) * hd + c];
                let v = b * lo + a * hi;
                out[j * hd + c] = if both {
                    v.intersection(a * (hi - lo) + lo)
                } else {
                    v
                };
            }
        }
    }
    out.drain(..p * hd);
    project(out, h.dim, h.rational)
}
fn main() {
    for p in [3usize, 5, 10, 20] {
        for rat in [0.0, 1.0] {
            let params = GenParams {
                degree: p..=p,
                rational: rat,
                ..GenParams::default()
            };
            let mut r = gen::rng(1);
            let (mut w0, mut w1, mut w2) = (vec![], vec![], vec![]);
            for _ in 0..500 {
                let c = gen::random_curve(&mut r, &params);
                let h = HSpline::<Interval>::from_curve(&c);
                let (a, b) = c.domain();
                for _ in 0..20 {
                    let u = r.random_range(a..=b);
                    let k = c.find_span(u);
                    let e0: Vec<Interval> = c.point(u).unwrap();
                    let e1 = eval_alt(&h, k, u, false);
                    let e2 = eval_alt(&h, k, u, true);
                    for j in 0..c.dim() {
                        let s = ulp(c.coord_scale(j));
                        w0.push(e0[j].wid() / s);
                        w1.push(e1[j].wid() / s);
                        w2.push(e2[j].wid() / s);
                    }
                }
            }
            for w in [&mut w0, &mut w1, &mut w2] {
                w.sort_by(f64::total_cmp);
            }
            let q = |w: &Vec<f64>, f: f64| w[((w.len() - 1) as f64 * f) as usize];
            println!("p={p} rational={rat}: thesis form median {:.1} max {:.1} | (1-a)lo+a hi median {:.1} max {:.1} | both median {:.1} max {:.1}", q(&w0,0.5), q(&w0,1.0), q(&w1,0.5), q(&w1,1.0), q(&w2,0.5), q(&w2,1.0));
        }
    }
}
