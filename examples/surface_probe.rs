use nurbs_box::surface::gen::families;
use nurbs_box::surface::{surface_strategy_by_name, SURFACE_STRATEGY_NAMES};
fn main() {
    for (name, s, _) in families() {
        for st in SURFACE_STRATEGY_NAMES {
            let e = surface_strategy_by_name(st, None).unwrap();
            let t = std::time::Instant::now();
            let r = e.enclose(&s);
            let el = t.elapsed();
            let gaps: Vec<f64> = r.coords.iter().map(|c| c.gap() / s.coord_scale(0).max(1e-300)).collect();
            println!("{name:16} {st:7} {:?} lo {:?} hi {:?} gap/scale {:?} term {:?} {:?}", el, r.lo(), r.hi(), gaps, r.termination(), r.stats().subdivisions);
        }
    }
}
