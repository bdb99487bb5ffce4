//! Experiment: how good are the glyph boxes fonts store?
//!
//! Every glyph outline of a font becomes NURBS curves (`nurbs_box::font`), each curve gets a
//! verified box, the boxes are hulled per glyph, and the font's stored `glyf` box is compared
//! side by side with the certified bracket [outer, inner] of the exact box:
//! a side is *loose* when the stored value lies outside the outer box (by `loose_by`), *too
//! small* when it lies inside the inner box (it cuts off part of the outline, by
//! `too_small_by`), *exact* when stored = outer = inner, and *undecided* otherwise (stored
//! value inside the certified gap).
//!
//! Usage: `cargo run --release --bin font_boxes -- [FONT] [--strategy S] [--out DIR]`
//! (default font tests/data/DejaVuSansMono.ttf, strategy: the first registered of newton,
//! bezier, hull; output results/font_boxes.csv and results/font_boxes.svg).

use nurbs_box::enclose::strategy_by_name;
use nurbs_box::font::{glyph_boxes, GlyphBox};
use nurbs_box::testkit::report::Provenance;
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::time::Instant;

const SIDES: [&str; 4] = ["xmin", "ymin", "xmax", "ymax"];

#[derive(Default, Clone, Copy)]
struct SideCount {
    loose: usize,
    too_small: usize,
    exact: usize,
    undecided: usize,
    max_loose: f64,
    max_small: f64,
}

fn classify(g: &GlyphBox, s: usize) -> Option<&'static str> {
    let st = g.stored_bbox?[s];
    let (o, i) = (g.outer()[s], g.inner()[s]);
    Some(if g.loose_by[s] > 0.0 {
        "loose"
    } else if g.too_small_by[s] > 0.0 {
        "too_small"
    } else if st == o && o == i {
        "exact"
    } else {
        "undecided"
    })
}

/// Stored side minus verified outer side, outward positive (loose > 0, inside < 0).
fn signed_offset(g: &GlyphBox, s: usize) -> Option<f64> {
    let st = g.stored_bbox?[s];
    let o = g.outer()[s];
    Some(if s < 2 { o - st } else { st - o })
}

/// The control-point box rounded outward to integers.
fn control_rounded(b: [f64; 4]) -> [f64; 4] {
    [b[0].floor(), b[1].floor(), b[2].ceil(), b[3].ceil()]
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut font = PathBuf::from("tests/data/DejaVuSansMono.ttf");
    let mut strategy_name: Option<String> = None;
    let mut out_dir = PathBuf::from("results");
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--strategy" => strategy_name = it.next().cloned(),
            "--out" => {
                out_dir = it
                    .next()
                    .map(PathBuf::from)
                    .ok_or("--out needs a directory")?
            }
            _ => font = PathBuf::from(a),
        }
    }
    let strategy = match &strategy_name {
        Some(n) => strategy_by_name(n, None).ok_or_else(|| format!("unknown strategy {n}"))?,
        None => ["newton", "bezier", "hull"]
            .iter()
            .find_map(|n| strategy_by_name(n, None))
            .ok_or("no strategy registered")?,
    };
    let bytes = std::fs::read(&font)?;
    let t0 = Instant::now();
    let boxes = glyph_boxes(&bytes, strategy.as_ref())?;
    let secs = t0.elapsed().as_secs_f64();
    let prov = Provenance::collect();

    let mut counts = [SideCount::default(); 4];
    let mut glyphs_loose = 0;
    let mut glyphs_small = 0;
    let mut with_stored = 0;
    let mut unverified = 0;
    let mut max_gap: f64 = 0.0;
    let mut curves = 0;
    // glyphs whose stored box is the control-point box rounded outward (what tools that
    // bound all on- and off-curve points store), and those where it is not
    let mut stored_is_control = 0;
    for g in &boxes {
        curves += g.curves;
        unverified += !g.verified as usize;
        for s in 0..4 {
            max_gap = max_gap.max((g.outer()[s] - g.inner()[s]).abs());
        }
        if g.stored_bbox.is_none() {
            continue;
        }
        with_stored += 1;
        stored_is_control += (g.stored_bbox == g.control_bbox.map(control_rounded)) as usize;
        glyphs_loose += g.loose_by.iter().any(|&x| x > 0.0) as usize;
        glyphs_small += g.too_small_by.iter().any(|&x| x > 0.0) as usize;
        for (s, c) in counts.iter_mut().enumerate() {
            match classify(g, s) {
                Some("loose") => c.loose += 1,
                Some("too_small") => c.too_small += 1,
                Some("exact") => c.exact += 1,
                _ => c.undecided += 1,
            }
            c.max_loose = c.max_loose.max(g.loose_by[s]);
            c.max_small = c.max_small.max(g.too_small_by[s]);
        }
    }

    let mut summary = String::new();
    writeln!(
        summary,
        "font {} | strategy {} | {} glyphs with outline ({} curves) in {:.3} s | {} unverified | largest certified gap {:.3e} font units",
        font.display(),
        strategy.name(),
        boxes.len(),
        curves,
        secs,
        unverified,
        max_gap
    )?;
    writeln!(
        summary,
        "{with_stored} glyphs with a stored box: {glyphs_loose} have a loose side, {glyphs_small} a too-small side; {stored_is_control} stored boxes are the control-point box rounded outward"
    )?;
    for (s, c) in counts.iter().enumerate() {
        writeln!(
            summary,
            "side {:>4}: loose {:>5} (max {:>6.2}), too small {:>5} (max {:>6.2}), exact {:>5}, undecided {:>5}",
            SIDES[s], c.loose, c.max_loose, c.too_small, c.max_small, c.exact, c.undecided
        )?;
    }
    print!("{summary}");

    std::fs::create_dir_all(&out_dir)?;
    let mut csv = prov.csv_comment();
    for l in summary.lines() {
        writeln!(csv, "# {l}")?;
    }
    let f = |v: f64| format!("{v}");
    let mut header = vec!["glyph_id".to_string(), "name".into(), "curves".into()];
    for pre in ["stored", "outer", "inner", "loose_by", "too_small_by"] {
        header.extend(SIDES.iter().map(|s| format!("{pre}_{s}")));
    }
    header.extend(SIDES.iter().map(|s| format!("class_{s}")));
    writeln!(csv, "{}", header.join(","))?;
    for g in &boxes {
        let mut row = vec![
            g.glyph_id.to_string(),
            g.name.clone().unwrap_or_default().replace(',', "_"),
            g.curves.to_string(),
        ];
        let stored = g
            .stored_bbox
            .map_or(vec![String::new(); 4], |b| b.map(f).to_vec());
        row.extend(stored);
        row.extend(g.outer().map(f));
        row.extend(g.inner().map(f));
        row.extend(g.loose_by.map(f));
        row.extend(g.too_small_by.map(f));
        row.extend((0..4).map(|s| classify(g, s).unwrap_or("").to_string()));
        writeln!(csv, "{}", row.join(","))?;
    }
    let csv_path = out_dir.join("font_boxes.csv");
    std::fs::write(&csv_path, csv)?;

    // Histogram of the signed offsets (font units, outward positive), clipped to [-4, 40].
    let svg_path = out_dir.join("font_boxes.svg");
    let (lo, hi, w) = (-4.0f64, 40.0f64, 0.5f64);
    let nb = ((hi - lo) / w) as usize;
    let mut bins = vec![[0usize; 4]; nb];
    let mut zero = 0;
    for g in &boxes {
        for (s, _) in SIDES.iter().enumerate() {
            if let Some(d) = signed_offset(g, s) {
                if d == 0.0 {
                    // exact sides would dwarf the rest; counted in the caption instead
                    zero += 1;
                    continue;
                }
                let k = (((d.clamp(lo, hi - 1e-9)) - lo) / w) as usize;
                bins[k.min(nb - 1)][s] += 1;
            }
        }
    }
    let ymax = bins
        .iter()
        .map(|b| b.iter().sum::<usize>())
        .max()
        .unwrap_or(1) as f64;
    {
        let root = SVGBackend::new(&svg_path, (960, 600)).into_drawing_area();
        root.fill(&WHITE)?;
        let (main, foot) = root.split_vertically(575);
        foot.draw(&Text::new(
            prov.line(),
            (10, 4),
            ("sans-serif", 11).into_font().color(&BLACK.mix(0.7)),
        ))?;
        let mut chart = ChartBuilder::on(&main)
            .caption(
                format!(
                    "{}: stored glyph box side minus verified side ({} glyphs, {}; {} exact sides not shown)",
                    font.file_name().map_or("font".into(), |n| n.to_string_lossy()),
                    with_stored,
                    strategy.name(),
                    zero
                ),
                ("sans-serif", 18),
            )
            .margin(15)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(lo..hi, 0.0..ymax * 1.1 + 1.0)?;
        chart
            .configure_mesh()
            .x_desc("font units, outward positive (> 0 loose, < 0 too small); clipped to [-4, 40]")
            .y_desc("glyph sides")
            .draw()?;
        let colors = [
            RGBColor(31, 119, 180),
            RGBColor(255, 127, 14),
            RGBColor(44, 160, 44),
            RGBColor(214, 39, 40),
        ];
        for (s, name) in SIDES.iter().enumerate() {
            let c = colors[s];
            chart
                .draw_series(bins.iter().enumerate().map(|(k, b)| {
                    let below: usize = b[..s].iter().sum();
                    let x0 = lo + k as f64 * w;
                    Rectangle::new(
                        [(x0, below as f64), (x0 + w * 0.9, (below + b[s]) as f64)],
                        c.filled(),
                    )
                }))?
                .label(*name)
                .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 10, y + 5)], c.filled()));
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()?;
        root.present()?;
    }
    println!("wrote {} and {}", csv_path.display(), svg_path.display());
    Ok(())
}
