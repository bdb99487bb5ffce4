//! SVG plots of the reproduction harness (plotters). Measuring and plotting are joined only by
//! the rows the harness computed; every plot carries a provenance footer.

use nurbs_box::enclose::{CandidateKind, Enclosure};
use nurbs_box::NurbsCurve;
use plotters::prelude::*;
use std::path::Path;

const COLORS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

type Res = Result<(), Box<dyn std::error::Error>>;

fn report(path: &Path, r: Res) {
    if let Err(e) = r {
        eprintln!("warning: could not draw {}: {e}", path.display());
    }
}

fn footer(area: &DrawingArea<SVGBackend, plotters::coord::Shift>, foot: &str) -> Res {
    area.draw(&Text::new(
        foot.to_string(),
        (10, 4),
        ("sans-serif", 11).into_font().color(&BLACK.mix(0.7)),
    ))?;
    Ok(())
}

fn range(v: impl Iterator<Item = f64>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for x in v.filter(|x| x.is_finite()) {
        lo = lo.min(x);
        hi = hi.max(x);
    }
    if lo.partial_cmp(&hi).is_none_or(|o| o.is_gt()) {
        (0.0, 1.0)
    } else if lo == hi {
        (lo - 0.5 - lo.abs() * 0.1, hi + 0.5 + hi.abs() * 0.1)
    } else {
        (lo, hi)
    }
}

/// Time per curve (µs, log scale) against a size parameter, one line per strategy.
pub fn time_plot(
    path: &Path,
    title: &str,
    xlabel: &str,
    series: &[(String, Vec<(f64, f64)>)],
    logx: bool,
    foot: &str,
) {
    let r = (|| -> Res {
        let root = SVGBackend::new(path, (960, 640)).into_drawing_area();
        root.fill(&WHITE)?;
        let (main, foot_area) = root.split_vertically(615);
        footer(&foot_area, foot)?;
        let (x0, x1) = range(series.iter().flat_map(|s| s.1.iter().map(|p| p.0)));
        let (y0, y1) = range(
            series
                .iter()
                .flat_map(|s| s.1.iter().map(|p| p.1))
                .filter(|&y| y > 0.0),
        );
        let (y0, y1) = (y0 / 2.0, y1 * 2.0);
        let mut b = ChartBuilder::on(&main);
        b.caption(title, ("sans-serif", 20))
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70);
        macro_rules! draw {
            ($chart:expr) => {{
                let mut chart = $chart;
                chart
                    .configure_mesh()
                    .x_desc(xlabel)
                    .y_desc("time per curve [µs] (median)")
                    .draw()?;
                for (i, (name, pts)) in series.iter().enumerate() {
                    let c = COLORS[i % COLORS.len()];
                    let pts: Vec<(f64, f64)> = pts.iter().copied().filter(|p| p.1 > 0.0).collect();
                    chart
                        .draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))?
                        .label(name.as_str())
                        .legend(move |(x, y)| {
                            PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                        });
                    chart.draw_series(pts.iter().map(|p| Circle::new(*p, 3, c.filled())))?;
                }
                chart
                    .configure_series_labels()
                    .position(SeriesLabelPosition::UpperLeft)
                    .border_style(BLACK)
                    .background_style(WHITE.mix(0.85))
                    .draw()?;
            }};
        }
        if logx {
            draw!(b.build_cartesian_2d((x0 / 1.5..x1 * 1.5).log_scale(), (y0..y1).log_scale())?);
        } else {
            draw!(b.build_cartesian_2d(x0 - 0.5..x1 + 0.5, (y0..y1).log_scale())?);
        }
        root.present()?;
        Ok(())
    })();
    report(path, r);
}

/// A log-axis tick label: 1, 10, 100, then 1e3, 1e4, ... (no long digit strings).
fn log_label(v: f64) -> String {
    if v < 1000.0 {
        format!("{}", v.round())
    } else {
        let e = v.log10().round() as i32;
        if (v / 10f64.powi(e) - 1.0).abs() < 1e-6 {
            format!("1e{e}")
        } else {
            format!("{v:.0e}")
        }
    }
}

/// Empirical distribution functions, one step line per series: the share of values <= x, on
/// a log(1 + x) axis (x = 0 is the left edge). `data`: (name, values >= 0; +inf allowed,
/// counted but drawn at the right edge).
pub fn ecdf_plot(path: &Path, title: &str, xlabel: &str, data: &[(String, Vec<f64>)], foot: &str) {
    let r = (|| -> Res {
        let root = SVGBackend::new(path, (1040, 680)).into_drawing_area();
        root.fill(&WHITE)?;
        let (main, foot_area) = root.split_vertically(650);
        footer(&foot_area, foot)?;
        let xmax = data
            .iter()
            .flat_map(|d| d.1.iter())
            .copied()
            .filter(|x| x.is_finite())
            .fold(1.0f64, f64::max);
        let right = (xmax + 1.0) * 3.0;
        let mut chart = ChartBuilder::on(&main)
            .caption(title, ("sans-serif", 20))
            .margin(20)
            .margin_right(40)
            .x_label_area_size(55)
            .y_label_area_size(80)
            .build_cartesian_2d((1.0f64..right).log_scale(), 0.0f64..1.02)?;
        chart
            .configure_mesh()
            .x_desc(xlabel)
            .y_desc("share of bounds with distance <= x")
            .x_label_formatter(&|x| log_label(*x))
            .y_label_formatter(&|y| format!("{:.0}%", y * 100.0))
            .axis_desc_style(("sans-serif", 15))
            .label_style(("sans-serif", 13))
            .draw()?;
        for (i, (name, vals)) in data.iter().enumerate() {
            let c = COLORS[i % COLORS.len()];
            let mut v: Vec<f64> = vals.iter().map(|x| x.max(0.0)).collect();
            v.sort_by(f64::total_cmp);
            let n = v.len().max(1) as f64;
            // steps: at each distinct value the share jumps to (count <= value) / n
            let mut pts = vec![(1.0, 0.0)];
            let mut k = 0;
            while k < v.len() {
                let x = v[k];
                let mut m = k;
                while m < v.len() && v[m] == x {
                    m += 1;
                }
                let px = if x.is_finite() { 1.0 + x } else { right };
                let prev = pts.last().map_or(0.0, |p| p.1);
                pts.push((px, prev));
                pts.push((px, m as f64 / n));
                k = m;
            }
            pts.push((right, pts.last().map_or(0.0, |p| p.1)));
            chart
                .draw_series(LineSeries::new(pts, c.stroke_width(2)))?
                .label(format!("{name} ({} bounds)", vals.len()))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerRight)
            .border_style(BLACK)
            .background_style(WHITE.mix(0.9))
            .label_font(("sans-serif", 13))
            .draw()?;
        root.present()?;
        Ok(())
    })();
    report(path, r);
}

fn sample(c: &NurbsCurve, n: usize) -> Vec<(f64, Vec<f64>)> {
    let (a, b) = c.domain();
    (0..=n)
        .map(|i| {
            let u = a + (b - a) * i as f64 / n as f64;
            (u, c.point::<f64>(u.min(b)).unwrap_or_default())
        })
        .collect()
}

fn extremum_points(enc: &Enclosure, j: usize) -> Vec<(f64, bool)> {
    let cb = &enc.coords[j];
    cb.argmin
        .iter()
        .map(|e| (e, false))
        .chain(cb.argmax.iter().map(|e| (e, true)))
        .filter(|(e, _)| e.kind != CandidateKind::ControlPoint)
        .map(|(e, is_max)| (0.5 * (e.u_lo + e.u_hi), is_max))
        .collect()
}

/// The thesis's figure (listing `main`): the curve, its control polygon, the box and the points
/// where each coordinate reaches its extremum.
pub fn curve_figure(path: &Path, c: &NurbsCurve, enc: &Enclosure, foot: &str) {
    let r = (|| -> Res {
        let root = SVGBackend::new(path, (900, 760)).into_drawing_area();
        root.fill(&WHITE)?;
        let (main, foot_area) = root.split_vertically(735);
        footer(&foot_area, foot)?;
        let pts = sample(c, 2000);
        let ctrl = c.control_points();
        let (x0, x1) = range(
            ctrl.iter()
                .map(|p| p[0])
                .chain([enc.coords[0].lo, enc.coords[0].hi]),
        );
        let (y0, y1) = range(
            ctrl.iter()
                .map(|p| p[1])
                .chain([enc.coords[1].lo, enc.coords[1].hi]),
        );
        let (mx, my) = ((x1 - x0) * 0.05, (y1 - y0) * 0.05);
        let mut chart = ChartBuilder::on(&main)
            .caption(
                format!(
                    "NURBS curve (p = {}, {} points) and its {} box",
                    c.degree(),
                    c.num_points(),
                    enc.strategy
                ),
                ("sans-serif", 20),
            )
            .margin(15)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x0 - mx..x1 + mx, y0 - my..y1 + my)?;
        chart.configure_mesh().x_desc("x").y_desc("y").draw()?;
        chart
            .draw_series(LineSeries::new(
                ctrl.iter().map(|p| (p[0], p[1])),
                BLACK.mix(0.35),
            ))?
            .label("control polygon")
            .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.mix(0.35)));
        chart.draw_series(
            ctrl.iter()
                .map(|p| Circle::new((p[0], p[1]), 3, BLACK.mix(0.35).filled())),
        )?;
        chart
            .draw_series(LineSeries::new(
                pts.iter().map(|(_, p)| (p[0], p[1])),
                COLORS[0].stroke_width(2),
            ))?
            .label("curve")
            .legend(|(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], COLORS[0].stroke_width(2))
            });
        let (bx, by) = (&enc.coords[0], &enc.coords[1]);
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(bx.lo, by.lo), (bx.hi, by.hi)],
                COLORS[3].stroke_width(2),
            )))?
            .label(format!("{} box", enc.strategy))
            .legend(|(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], COLORS[3].stroke_width(2))
            });
        for j in 0..2 {
            let marks: Vec<(f64, f64)> = extremum_points(enc, j)
                .into_iter()
                .filter_map(|(u, _)| c.point::<f64>(u).ok())
                .map(|p| (p[0], p[1]))
                .collect();
            chart.draw_series(
                marks
                    .into_iter()
                    .map(|p| Circle::new(p, 6, COLORS[2].filled())),
            )?;
        }
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.85))
            .draw()?;
        root.present()?;
        Ok(())
    })();
    report(path, r);
}

/// One panel per coordinate function C_j(u), with its box bounds and extrema marked.
pub fn coordinate_functions(path: &Path, c: &NurbsCurve, enc: &Enclosure, foot: &str) {
    let r = (|| -> Res {
        let d = c.dim();
        let root = SVGBackend::new(path, (960, 320 * d as u32 + 25)).into_drawing_area();
        root.fill(&WHITE)?;
        let (main, foot_area) = root.split_vertically(320 * d as u32);
        footer(&foot_area, foot)?;
        let panels = main.split_evenly((d, 1));
        let pts = sample(c, 2000);
        let (a, b) = c.domain();
        for (j, panel) in panels.iter().enumerate() {
            let cb = &enc.coords[j];
            let (y0, y1) = range(pts.iter().map(|(_, p)| p[j]).chain([cb.lo, cb.hi]));
            let m = (y1 - y0) * 0.08;
            let mut chart = ChartBuilder::on(panel)
                .caption(
                    format!("C_{}(u) with its extrema ({} box)", j + 1, enc.strategy),
                    ("sans-serif", 16),
                )
                .margin(10)
                .x_label_area_size(35)
                .y_label_area_size(60)
                .build_cartesian_2d(a..b, y0 - m..y1 + m)?;
            chart.configure_mesh().x_desc("u").draw()?;
            chart.draw_series(LineSeries::new(
                pts.iter().map(|(u, p)| (*u, p[j])),
                COLORS[0].stroke_width(2),
            ))?;
            for v in [cb.lo, cb.hi] {
                chart.draw_series(LineSeries::new(vec![(a, v), (b, v)], COLORS[3].mix(0.7)))?;
            }
            for (u, is_max) in extremum_points(enc, j) {
                let v = if is_max { cb.hi } else { cb.lo };
                chart.draw_series(std::iter::once(Circle::new((u, v), 5, COLORS[2].filled())))?;
            }
        }
        root.present()?;
        Ok(())
    })();
    report(path, r);
}

/// A surface as iso-curves (u = const and v = const, `n` each) projected to the coordinates
/// (`a`, `b`), its control net points, and the boxes of `encs` (one rectangle each).
pub fn surface_figure(
    path: &Path,
    s: &nurbs_box::NurbsSurface,
    encs: &[Enclosure],
    (a, b): (usize, usize),
    foot: &str,
) {
    let r = (|| -> Res {
        let root = SVGBackend::new(path, (900, 760)).into_drawing_area();
        root.fill(&WHITE)?;
        let (main, foot_area) = root.split_vertically(735);
        footer(&foot_area, foot)?;
        let ((u0, u1), (v0, v1)) = s.domain();
        let n = 12;
        let m = 200;
        let at = |t: usize, k: usize| t as f64 / k as f64;
        let mut lines: Vec<Vec<(f64, f64)>> = Vec::new();
        for i in 0..=n {
            for dir in 0..2 {
                let line = (0..=m)
                    .filter_map(|k| {
                        let (u, v) = if dir == 0 {
                            (u0 + (u1 - u0) * at(i, n), v0 + (v1 - v0) * at(k, m))
                        } else {
                            (u0 + (u1 - u0) * at(k, m), v0 + (v1 - v0) * at(i, n))
                        };
                        s.point::<f64>(u.min(u1), v.min(v1))
                            .ok()
                            .map(|p| (p[a], p[b]))
                    })
                    .collect();
                lines.push(line);
            }
        }
        let net: Vec<(f64, f64)> = (0..s.rows())
            .flat_map(|i| (0..s.cols()).map(move |j| (i, j)))
            .map(|(i, j)| (s.control_point(i, j)[a], s.control_point(i, j)[b]))
            .collect();
        let bx = |e: &Enclosure, j: usize| [e.coords[j].lo, e.coords[j].hi];
        let (x0, x1) = range(
            net.iter()
                .map(|p| p.0)
                .chain(encs.iter().flat_map(|e| bx(e, a))),
        );
        let (y0, y1) = range(
            net.iter()
                .map(|p| p.1)
                .chain(encs.iter().flat_map(|e| bx(e, b))),
        );
        let (mx, my) = ((x1 - x0) * 0.05, (y1 - y0) * 0.05);
        let names = ["x", "y", "z"];
        let mut chart = ChartBuilder::on(&main)
            .caption(
                format!(
                    "NURBS surface (degrees {}, {}; {} x {} net): iso-curves in the {}-{} projection and its boxes",
                    s.degree_u(),
                    s.degree_v(),
                    s.rows(),
                    s.cols(),
                    names.get(a).unwrap_or(&"?"),
                    names.get(b).unwrap_or(&"?")
                ),
                ("sans-serif", 18),
            )
            .margin(15)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(x0 - mx..x1 + mx, y0 - my..y1 + my)?;
        chart
            .configure_mesh()
            .x_desc(*names.get(a).unwrap_or(&"?"))
            .y_desc(*names.get(b).unwrap_or(&"?"))
            .draw()?;
        for (k, l) in lines.into_iter().enumerate() {
            let s = chart.draw_series(LineSeries::new(l, COLORS[0].mix(0.8)))?;
            if k == 0 {
                s.label("iso-curves u, v = const")
                    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], COLORS[0]));
            }
        }
        chart
            .draw_series(
                net.iter()
                    .map(|&p| Circle::new(p, 3, BLACK.mix(0.4).filled())),
            )?
            .label("control net")
            .legend(|(x, y)| Circle::new((x + 10, y), 3, BLACK.mix(0.4).filled()));
        for (k, e) in encs.iter().enumerate() {
            let c = COLORS[(3 + k) % COLORS.len()];
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [
                        (e.coords[a].lo, e.coords[b].lo),
                        (e.coords[a].hi, e.coords[b].hi),
                    ],
                    c.stroke_width(2),
                )))?
                .label(format!("{} box", e.strategy))
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.85))
            .draw()?;
        root.present()?;
        Ok(())
    })();
    report(path, r);
}
