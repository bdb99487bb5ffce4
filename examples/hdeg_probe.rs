//! Probe of the interval Newton strategy on a curve file (release build):
//! `cargo run --release --example hdeg_probe -- FILE [strategy]`. Prints per coordinate the
//! bounds, gaps, stats and the candidates that attain the outer bounds.
use nurbs_box::enclose::strategy_by_name;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let bytes = std::fs::read(&args[1]).expect("read");
    let c = nurbs_box::io::parse_curve(&bytes).expect("parse");
    if let (Some(a), Some(b)) = (args.get(3), args.get(4)) {
        let t = nurbs_box::TightEval::new(&c);
        let j: usize = args[2].parse().unwrap();
        println!(
            "{:?}",
            t.coord_over(j, a.parse().unwrap(), b.parse().unwrap())
        );
        return;
    }
    if args.get(2).map(String::as_str) == Some("seg") {
        let hs = nurbs_box::HSpline::<nurbs_box::Ddi>::from_curve(&c);
        for k in [c.degree(), c.degree() + 5, c.num_points() - 1] {
            let s = hs.bezier_segment(k);
            let m = s
                .pts
                .iter()
                .map(|x| x.rad() / x.hi().abs().max(1e-300))
                .fold(0.0, f64::max);
            println!("span {k}: max rel rad {m:e}");
        }
        return;
    }
    if args.get(2).map(String::as_str) == Some("mono") {
        let hs = nurbs_box::HSpline::<inari::Interval>::from_curve(&c);
        let (mut n, mut m) = (0, 0);
        for k in c.degree()..c.num_points() {
            let s = hs.bezier_segment(k);
            let h = s.hdim();
            let d: Vec<_> = (0..s.degree)
                .map(|i| s.pts[(i + 1) * h] - s.pts[i * h])
                .collect();
            n += 1;
            if d.iter().all(|x| x.inf() > 0.0) || d.iter().all(|x| x.sup() < 0.0) {
                m += 1;
            }
        }
        println!("{m} of {n} spans monotone by Bezier points");
        return;
    }
    if args.get(2).map(String::as_str) == Some("tseg") {
        let hs = nurbs_box::HSpline::<inari::Interval>::from_curve(&c);
        let t0 = Instant::now();
        let mut acc = 0.0;
        for k in c.degree()..c.num_points() {
            acc += hs.bezier_segment(k).pts[3].inf();
        }
        println!("interval {:?} {acc}", t0.elapsed());
        let hs = nurbs_box::HSpline::<nurbs_box::Ddi>::from_curve(&c);
        let t0 = Instant::now();
        for k in c.degree()..c.num_points() {
            acc += hs.bezier_segment(k).pts[3].hi();
        }
        println!("ddi {:?} {acc}", t0.elapsed());
        let hs = nurbs_box::HSpline::<f64>::from_curve(&c);
        let t0 = Instant::now();
        for k in c.degree()..c.num_points() {
            acc += hs.bezier_segment(k).pts[3];
        }
        println!("f64 {:?} {acc}", t0.elapsed());
        return;
    }
    let name = args.get(2).map_or("newton", |s| s.as_str());
    let s = strategy_by_name(name, None).expect("strategy");
    let t0 = Instant::now();
    let e = s.enclose(&c);
    println!("{name}: {:.3} s", t0.elapsed().as_secs_f64());
    for (j, cb) in e.coords.iter().enumerate() {
        println!(
            "coord {j}: lo {:e} inner_lo {:e} hi {:e} inner_hi {:e} gap {:e} {:?}",
            cb.lo,
            cb.inner_lo,
            cb.hi,
            cb.inner_hi,
            cb.gap(),
            cb.termination
        );
        println!("  stats {:?}", cb.stats);
        println!("  argmin {:?}", cb.argmin);
        println!("  argmax {:?}", cb.argmax);
    }
}

#[allow(dead_code)]
fn unused() {}
#[allow(dead_code)]
fn probe_over() {}
