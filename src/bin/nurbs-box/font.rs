//! `nurbs-box font FILE`: verified glyph boxes of a font against the boxes it stores, one
//! record per glyph with an outline.

use crate::{default_strategy, Fatal, Outcome};
use clap::Args;
use nurbs_box::enclose::{strategy_by_name, BoxEncloser, STRATEGY_NAMES};
use nurbs_box::font::{glyph_boxes, GlyphBox};
use nurbs_box::io::{write_nums, write_str};
use std::io;
use std::path::PathBuf;

#[derive(Args, Debug)]
pub(crate) struct FontArgs {
    /// The font file (.ttf / .otf).
    file: PathBuf,
    /// Strategy name (default as for `enclose`).
    #[arg(long)]
    strategy: Option<String>,
    /// Tolerance of the iterative strategies.
    #[arg(long, allow_negative_numbers = true)]
    tol: Option<f64>,
}

pub(crate) fn run(a: FontArgs) -> Result<Outcome, Fatal> {
    let name = a.strategy.as_deref().unwrap_or_else(|| default_strategy());
    let strategy = strategy_by_name(name, a.tol).ok_or_else(|| {
        Fatal(format!(
            "unknown strategy {name:?}; known strategies: {}",
            STRATEGY_NAMES.join(", ")
        ))
    })?;
    let bytes = std::fs::read(&a.file)
        .map_err(|e| Fatal(format!("cannot read {}: {e}", a.file.display())))?;
    write_glyph_records(&bytes, strategy.as_ref(), &mut io::stdout().lock())
        .map(|()| Outcome::AllOk)
        .map_err(|e| match e.downcast_ref::<io::Error>() {
            // the reader of our output went away (`| head`): stop quietly
            Some(io) if io.kind() == io::ErrorKind::BrokenPipe => Fatal(String::new()),
            _ => Fatal(e.to_string()),
        })
}

/// One record per glyph with an outline (see [`write_glyph_record`]) on `out`. Errors: the font
/// cannot be parsed, or writing fails.
fn write_glyph_records<W: io::Write>(
    font_bytes: &[u8],
    strategy: &dyn BoxEncloser,
    out: &mut W,
) -> Result<(), Box<dyn std::error::Error>> {
    for g in glyph_boxes(font_bytes, strategy)? {
        let mut line = Vec::new();
        write_glyph_record(&mut line, &g);
        line.push(b'\n');
        out.write_all(&line)?;
    }
    Ok(())
}

/// Append one glyph record (one line of `nurbs-box font` output, no newline):
/// `{"glyph_id","name","verified","curves","lo","hi","inner_lo","inner_hi","stored_bbox",
/// "control_bbox","loose_by","too_small_by"}`; boxes as [x_min, y_min, x_max, y_max] arrays
/// (corners as [x, y]), `null` where absent; numbers as in `docs/formats.md`.
fn write_glyph_record(out: &mut Vec<u8>, g: &GlyphBox) {
    let opt = |out: &mut Vec<u8>, b: Option<[f64; 4]>| match b {
        Some(b) => write_nums(out, b),
        None => out.extend_from_slice(b"null"),
    };
    out.extend_from_slice(format!("{{\"glyph_id\":{},\"name\":", g.glyph_id).as_bytes());
    match &g.name {
        Some(n) => write_str(out, n),
        None => out.extend_from_slice(b"null"),
    }
    out.extend_from_slice(
        format!(",\"verified\":{},\"curves\":{}", g.verified, g.curves).as_bytes(),
    );
    for (key, v) in [
        ("lo", g.tight_lo),
        ("hi", g.tight_hi),
        ("inner_lo", g.inner_lo),
        ("inner_hi", g.inner_hi),
    ] {
        out.extend_from_slice(format!(",\"{key}\":").as_bytes());
        write_nums(out, v);
    }
    out.extend_from_slice(b",\"stored_bbox\":");
    opt(out, g.stored_bbox);
    out.extend_from_slice(b",\"control_bbox\":");
    opt(out, g.control_bbox);
    out.extend_from_slice(b",\"loose_by\":");
    write_nums(out, g.loose_by);
    out.extend_from_slice(b",\"too_small_by\":");
    write_nums(out, g.too_small_by);
    out.push(b'}');
}
