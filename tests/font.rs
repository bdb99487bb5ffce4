//! Verified glyph boxes on a real TrueType font (DejaVu Sans Mono, tests/data, Bitstream Vera
//! license): the box contains every on-curve point and sampled outline points, and lies in the
//! control-point box.

use inari::Interval;
use nurbs_box::enclose::{all_strategies, strategy_by_name};
use nurbs_box::font::{glyph_boxes, glyph_outline, GlyphBox};
use nurbs_box::num::iv;
use nurbs_box::{BezierSeg, Guarantee};
use ttf_parser::Face;

const FONT: &[u8] = include_bytes!("data/DejaVuSansMono.ttf");
/// CFF (cubic) outlines: Inconsolata, SIL Open Font License.
const CFF_FONT: &[u8] = include_bytes!("data/Inconsolata.otf");
const CHARS: &str = "AaBgOo08@&SQéß§%{~";

fn check(face: &Face<'_>, boxes: &[GlyphBox], stored: bool) {
    for ch in CHARS.chars() {
        let gid = face.glyph_index(ch).unwrap();
        let g = boxes.iter().find(|g| g.glyph_id == gid.0).unwrap();
        assert!(g.verified);
        let outline = glyph_outline(face, gid);
        // every on-curve point (exact f64 data) lies in the closed outer box
        for p in outline.on_curve_points() {
            for j in 0..2 {
                assert!(
                    g.tight_lo[j] <= p[j] && p[j] <= g.tight_hi[j],
                    "{ch}: {p:?}"
                );
            }
        }
        // sampled outline points, enclosed in interval arithmetic from the segments as
        // ttf-parser reports them: the enclosure of each exact point meets the box
        for s in outline.contours.iter().flatten() {
            let seg = BezierSeg::<Interval>::from_points(
                0.0,
                1.0,
                2,
                s.pts.iter().flatten().map(|&x| iv::point(x)).collect(),
            );
            for i in 0..=32 {
                let q = seg.eval_local(&iv::point(i as f64 / 32.0));
                #[allow(clippy::needless_range_loop)]
                for j in 0..2 {
                    assert!(
                        q[j].sup() >= g.tight_lo[j] && q[j].inf() <= g.tight_hi[j],
                        "{ch}"
                    );
                }
            }
        }
        // inside the control-point box, and inner inside outer
        let cb = g.control_bbox.unwrap();
        assert!(g.tight_lo[0] >= cb[0] && g.tight_lo[1] >= cb[1], "{ch}");
        assert!(g.tight_hi[0] <= cb[2] && g.tight_hi[1] <= cb[3], "{ch}");
        for j in 0..2 {
            assert!(g.tight_lo[j] <= g.inner_lo[j] && g.inner_hi[j] <= g.tight_hi[j]);
        }
        assert_eq!(g.stored_bbox.is_some(), stored);
    }
}

#[test]
fn verified_glyph_boxes_for_every_verified_strategy() {
    let face = Face::parse(FONT, 0).unwrap();
    for s in all_strategies(None) {
        if s.guarantee() != Guarantee::Verified {
            continue;
        }
        let boxes = glyph_boxes(FONT, s.as_ref()).unwrap();
        assert!(boxes.len() > 2000, "{}", boxes.len());
        check(&face, &boxes, true);
        let cff = Face::parse(CFF_FONT, 0).unwrap();
        let boxes = glyph_boxes(CFF_FONT, s.as_ref()).unwrap();
        assert!(boxes.len() > 100, "{}", boxes.len());
        check(&cff, &boxes, false);
    }
}

#[test]
fn cff_outlines_are_cubic() {
    let face = Face::parse(CFF_FONT, 0).unwrap();
    let o = glyph_outline(&face, face.glyph_index('O').unwrap());
    assert!(o.contours.iter().flatten().any(|s| s.pts.len() == 4));
    let curves = o.curves().unwrap();
    assert!(curves.iter().any(|c| c.degree() == 3));
}

#[test]
fn letter_o_has_curved_extremes_and_the_stored_box_is_close() {
    // "O" has its extremes on curve segments; the stored integer box must be within one unit
    // of the exact box on each side (fonts round outward or to nearest).
    let face = Face::parse(FONT, 0).unwrap();
    let s = strategy_by_name("bezier", None)
        .or_else(|| strategy_by_name("hull", None))
        .unwrap();
    let boxes = glyph_boxes(FONT, s.as_ref()).unwrap();
    let gid = face.glyph_index('O').unwrap();
    let g = boxes.iter().find(|g| g.glyph_id == gid.0).unwrap();
    let st = g.stored_bbox.unwrap();
    let outer = g.outer();
    for k in 0..4 {
        assert!(
            (st[k] - outer[k]).abs() <= 1.0,
            "side {k}: stored {} vs {}",
            st[k],
            outer[k]
        );
    }
    assert!(g.name.as_deref() == Some("O"));
    assert_eq!(
        glyph_boxes(b"not a font", s.as_ref()).unwrap_err().kind(),
        "font_parse"
    );
}

#[test]
fn truetype_outlines_are_placed_as_freetype_places_them() {
    // DejaVu Sans Mono has 58 glyphs whose hmtx left side bearing is one unit more than the
    // glyf xMin; FreeType (FT_LOAD_NO_SCALE | FT_LOAD_NO_HINTING) shifts their outlines, simple
    // and composite, by lsb - xMin. The smallest control-point x FreeType reports:
    let freetype_min_x = [
        ("ij", -4.0),
        ("uni0361", -235.0),
        ("uni0EB1", -1142.0),
        ("uni0EB3", -826.0), // composite
        ("uni1F0A", -403.0), // composite
    ];
    let face = Face::parse(FONT, 0).unwrap();
    let s = strategy_by_name("hull", None).unwrap();
    let boxes = glyph_boxes(FONT, s.as_ref()).unwrap();
    for (name, x) in freetype_min_x {
        let g = boxes
            .iter()
            .find(|g| g.name.as_deref() == Some(name))
            .unwrap();
        assert_eq!(g.control_bbox.unwrap()[0], x, "{name}");
        let gid = ttf_parser::GlyphId(g.glyph_id);
        assert_eq!(nurbs_box::font::placement_shift(&face, gid), 1.0, "{name}");
    }
    // the stored box moves with the outline: its x_min is the left side bearing
    let mut shifted = 0;
    for g in &boxes {
        let gid = ttf_parser::GlyphId(g.glyph_id);
        let lsb = face.glyph_hor_side_bearing(gid).unwrap();
        assert_eq!(g.stored_bbox.unwrap()[0], f64::from(lsb), "{:?}", g.name);
        shifted += usize::from(nurbs_box::font::placement_shift(&face, gid) != 0.0);
    }
    assert_eq!(shifted, 58);
    // CFF outlines are not moved
    let cff = Face::parse(CFF_FONT, 0).unwrap();
    let o = cff.glyph_index('O').unwrap();
    assert_eq!(nurbs_box::font::placement_shift(&cff, o), 0.0);
}
