//! Point-enclosure tightness: the width of the interval enclosure of C_j(u) at f64 parameters
//! u, in ulps of the coordinate scale (the largest |control point coordinate| of coordinate
//! j), over many random curves of every generator family.
//!
//! Run: `cargo run --release --example point_width [curves_per_family] [params_per_curve]`
//! (defaults 2000 and 20; seed fixed, so the numbers are reproducible).

use inari::Interval;
use nurbs_box::gen::{self, Family, GenParams};
use nurbs_box::scalar::ulp;
use nurbs_box::NurbsCurve;
use rand::Rng;

struct Dist {
    v: Vec<f64>,
    unbounded: usize,
}

impl Dist {
    fn add(&mut self, c: &NurbsCurve, e: &[Interval]) {
        for (j, x) in e.iter().enumerate() {
            let w = x.sup() - x.inf();
            if w.is_finite() {
                self.v.push(w / ulp(c.coord_scale(j)));
            } else {
                self.unbounded += 1;
            }
        }
    }
    fn row(&mut self, name: &str) {
        self.v.sort_by(f64::total_cmp);
        let q = |f: f64| self.v[((self.v.len() - 1) as f64 * f).round() as usize];
        println!(
            "{name:<24} {:>8} {:>10.1} {:>10.1} {:>10.1} {:>12.1} {:>9}",
            self.v.len(),
            q(0.5),
            q(0.9),
            q(0.99),
            q(1.0),
            self.unbounded
        );
    }
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let curves = args.first().copied().unwrap_or(2000);
    let per = args.get(1).copied().unwrap_or(20);
    println!("point-enclosure width in ulps of the coordinate scale ({curves} curves x {per} parameters per row)");
    println!(
        "{:<24} {:>8} {:>10} {:>10} {:>10} {:>12} {:>9}",
        "family", "samples", "median", "p90", "p99", "max", "unbounded"
    );
    let mut rows: Vec<(String, GenParams)> = vec![("moderate (p<=5)".into(), GenParams::default())];
    for p in [3usize, 10, 20] {
        rows.push((
            format!("non-rational p={p}"),
            GenParams {
                degree: p..=p,
                rational: 0.0,
                ..GenParams::default()
            },
        ));
    }
    for (name, params) in rows {
        let mut r = gen::rng(1);
        let mut d = Dist {
            v: Vec::new(),
            unbounded: 0,
        };
        for _ in 0..curves {
            let c = gen::random_curve(&mut r, &params);
            let (a, b) = c.domain();
            for _ in 0..per {
                let u = r.random_range(a..=b);
                d.add(&c, &c.point::<Interval>(u).unwrap());
            }
        }
        d.row(&name);
    }
    for f in Family::ALL {
        let mut r = gen::rng(2);
        let mut d = Dist {
            v: Vec::new(),
            unbounded: 0,
        };
        for _ in 0..curves {
            let c = f.curve(&mut r);
            let (a, b) = c.domain();
            for _ in 0..per {
                let u = r.random_range(a..=b);
                d.add(&c, &c.point::<Interval>(u).unwrap());
            }
        }
        d.row(f.name());
    }
}
