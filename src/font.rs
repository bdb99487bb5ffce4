//! Glyph outlines of TrueType / OpenType fonts as NURBS curves, their verified boxes, and a
//! comparison with the glyph boxes the font stores.
//!
//! Outlines come from `ttf-parser`'s [`OutlineBuilder`]: TrueType (`glyf`) contours arrive as
//! line and quadratic segments (implied on-curve points already inserted as midpoints), CFF
//! contours as line and cubic segments. The coordinates are f32, hence exact in f64, and the
//! curves built here are *exactly* the outline ttf-parser reports:
//!
//! * each contour becomes one B-spline of the contour's highest segment degree p (2 for
//!   TrueType, 3 for CFF), knots at the integers, segment joins of multiplicity p, so every
//!   segment is one Bézier piece of the spline;
//! * for p = 2, a join whose on-curve point is exactly the midpoint of the neighbouring
//!   off-curve points (TrueType's implied points) becomes a simple knot and the point is
//!   dropped: the quadratic B-spline with the off-curve points as control points (knot
//!   spacing 1 on both sides, so the join value is the midpoint) — fewer control points, same
//!   curve;
//! * lower-degree segments are degree-elevated when the elevated control points are exactly
//!   representable (checked with interval arithmetic: the elevation in `Interval` must give
//!   singletons — always true for a line in a quadratic contour, whose midpoint of f32 values
//!   is exact); otherwise the segment is kept as a separate curve of its own degree and the
//!   contour's spline is cut there.
//!
//! ## Placement of TrueType outlines
//!
//! A `glyf` outline is placed as rasterizers place it: shifted horizontally by
//! `lsb - xMin`, the `hmtx` left side bearing minus the `xMin` stored in the glyph's `glyf`
//! header, so that the stored `xMin` lands on the left side bearing. For almost every glyph the
//! two agree and the shift is 0; where a font's `hmtx` and `glyf` disagree, the shifted outline
//! is the one a user of the font sees. FreeType does this in its TrueType loader
//! (`ttgload.c`): the phantom point `pp1.x = bbox.xMin - left_bearing` (the stored header
//! `xMin`), and `TT_Load_Glyph` translates the loaded outline by `-pp1.x` "so that (0,0) is the
//! glyph's origin", independent of bit 1 of the `head` flags; fontTools' glyph set draws
//! `glyf` glyphs with the offset `lsb - xMin` likewise. ttf-parser reports the coordinates as
//! stored, so the shift is applied here ([`glyph_outline`]), and the stored box is shifted
//! with it ([`GlyphBox::stored_bbox`]) so that the comparison with the verified box is the
//! one in the font's own frame. The shift is an integer, so the coordinates stay exact. CFF
//! outlines are used as they are (their `hmtx` side bearing is informational).

use crate::enclose::BoxEncloser;
use crate::error::CurveError;
use crate::num::iv;
use crate::spline::bspline::BezierSeg;
use crate::spline::curve::NurbsCurve;
use inari::Interval;
use thiserror::Error;
use ttf_parser::{Face, GlyphId, OutlineBuilder};

/// Why a font could not be processed.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum FontError {
    /// The bytes are not a font ttf-parser can read.
    #[error("font: cannot parse the font file: {0}")]
    Parse(String),
    /// A glyph outline did not give a valid curve (should not happen for finite outlines).
    #[error("glyph {glyph_id}: {source}")]
    Curve {
        /// the glyph
        glyph_id: u16,
        /// why
        source: CurveError,
    },
}

impl FontError {
    /// A short machine-readable kind.
    pub fn kind(&self) -> &'static str {
        match self {
            FontError::Parse(_) => "font_parse",
            FontError::Curve { .. } => "glyph_curve",
        }
    }
}

/// One outline segment: a Bézier piece of degree `pts.len() - 1` (1, 2 or 3).
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    /// control points (first and last on the curve)
    pub pts: Vec<[f64; 2]>,
}

/// A glyph outline as ttf-parser reports it: closed contours of segments.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Outline {
    /// the contours; each contour's segments join end to start and the last ends at the first
    /// segment's start
    pub contours: Vec<Vec<Segment>>,
}

impl Outline {
    /// All on-curve points (segment ends).
    pub fn on_curve_points(&self) -> Vec<[f64; 2]> {
        self.contours
            .iter()
            .flatten()
            .flat_map(|s| [s.pts[0], s.pts[s.pts.len() - 1]])
            .collect()
    }

    /// The box of all control points (on- and off-curve): [x_min, y_min, x_max, y_max], or
    /// `None` for an empty outline. The curve lies inside it (convex hull property).
    pub fn control_box(&self) -> Option<[f64; 4]> {
        let mut it = self.contours.iter().flatten().flat_map(|s| s.pts.iter());
        let first = it.next()?;
        Some(it.fold([first[0], first[1], first[0], first[1]], |b, p| {
            [
                b[0].min(p[0]),
                b[1].min(p[1]),
                b[2].max(p[0]),
                b[3].max(p[1]),
            ]
        }))
    }

    /// The outline as NURBS curves (see the module documentation for the construction).
    pub fn curves(&self) -> Result<Vec<NurbsCurve>, CurveError> {
        let mut out = Vec::new();
        for contour in &self.contours {
            contour_curves(contour, &mut out)?;
        }
        Ok(out)
    }
}

/// Collects ttf-parser's outline callbacks into an [`Outline`].
#[derive(Default)]
struct Collector {
    outline: Outline,
    current: Vec<Segment>,
    start: [f64; 2],
    last: [f64; 2],
}

impl Collector {
    fn push(&mut self, mut pts: Vec<[f64; 2]>) {
        pts.insert(0, self.last);
        self.last = pts[pts.len() - 1];
        self.current.push(Segment { pts });
    }
    fn finish(&mut self) {
        if self.current.is_empty() {
            return;
        }
        // A closed contour ends where it started; ttf-parser emits the closing segment for
        // glyf, CFF's closepath may leave it implicit.
        if self.last != self.start {
            self.push(vec![self.start]);
        }
        let c = std::mem::take(&mut self.current);
        self.outline.contours.push(c);
    }
}

fn pt(x: f32, y: f32) -> [f64; 2] {
    // f32 -> f64 is exact
    [x as f64, y as f64]
}

impl OutlineBuilder for Collector {
    fn move_to(&mut self, x: f32, y: f32) {
        self.finish();
        self.start = pt(x, y);
        self.last = self.start;
    }
    fn line_to(&mut self, x: f32, y: f32) {
        self.push(vec![pt(x, y)]);
    }
    fn quad_to(&mut self, x1: f32, y1: f32, x: f32, y: f32) {
        self.push(vec![pt(x1, y1), pt(x, y)]);
    }
    fn curve_to(&mut self, x1: f32, y1: f32, x2: f32, y2: f32, x: f32, y: f32) {
        self.push(vec![pt(x1, y1), pt(x2, y2), pt(x, y)]);
    }
    fn close(&mut self) {
        self.finish();
    }
}

/// The outline of one glyph (empty for glyphs without one, e.g. the space), placed as
/// rasterizers place it: a TrueType outline shifted by [`placement_shift`] (see the module
/// documentation).
pub fn glyph_outline(face: &Face<'_>, id: GlyphId) -> Outline {
    let mut c = Collector::default();
    face.outline_glyph(id, &mut c);
    c.finish();
    let dx = placement_shift(face, id);
    if dx != 0.0 {
        for p in c
            .outline
            .contours
            .iter_mut()
            .flatten()
            .flat_map(|s| s.pts.iter_mut())
        {
            // integers of at most 17 bits: the sum is exact
            p[0] += dx;
        }
    }
    c.outline
}

/// The horizontal shift rasterizers apply to a TrueType (`glyf`) outline: the `hmtx` left
/// side bearing minus the `xMin` of the glyph's `glyf` header (FreeType's `-pp1.x`, fontTools'
/// `lsb - xMin`); 0 for CFF outlines and for glyphs without a `glyf` box or side bearing.
pub fn placement_shift(face: &Face<'_>, id: GlyphId) -> f64 {
    let Some(glyf) = face.tables().glyf else {
        return 0.0;
    };
    match (face.glyph_hor_side_bearing(id), glyf.bbox(id)) {
        (Some(lsb), Some(b)) => f64::from(lsb) - f64::from(b.x_min),
        _ => 0.0,
    }
}

/// The segment's control points elevated to degree `p`, if the elevated points are exactly
/// representable in f64 (the elevation run in interval arithmetic gives singletons, and an
/// interval result contains the exact value; see [`BezierSeg::elevate`]).
fn exact_elevation(s: &Segment, p: usize) -> Option<Vec<[f64; 2]>> {
    let deg = s.pts.len() - 1;
    if deg == p {
        return Some(s.pts.clone());
    }
    let flat: Vec<Interval> = s.pts.iter().flatten().map(|&x| iv::point(x)).collect();
    let e = BezierSeg::from_points(0.0, 1.0, 2, flat).elevate_by(p - deg);
    let single = |v: &Interval| v.inf() == v.sup();
    if !e.pts.iter().all(single) {
        return None;
    }
    Some(e.pts.chunks(2).map(|c| [c[0].inf(), c[1].inf()]).collect())
}

/// Whether m is exactly the midpoint of a and b: (a + b) / 2 evaluated in interval arithmetic
/// is the singleton m (an interval result contains the exact midpoint).
fn is_exact_midpoint(a: [f64; 2], b: [f64; 2], m: [f64; 2]) -> bool {
    (0..2).all(|j| {
        let mid = (iv::point(a[j]) + iv::point(b[j])) * iv::point(0.5);
        mid.inf() == m[j] && mid.sup() == m[j]
    })
}

/// One B-spline of degree p through a run of segments all of degree p (after exact
/// elevation): clamped, knots 0..n at the joins with multiplicity p, or 1 for a quadratic join
/// at an exact midpoint (the join point is then not a control point).
fn run_curve(p: usize, run: &[Vec<[f64; 2]>]) -> Result<NurbsCurve, CurveError> {
    let mut knots = vec![0.0; p + 1];
    let mut pts: Vec<Vec<f64>> = vec![run[0][0].to_vec()];
    for (i, seg) in run.iter().enumerate() {
        pts.extend(seg[1..p].iter().map(|q| q.to_vec()));
        let end = seg[p];
        if i + 1 == run.len() {
            pts.push(end.to_vec());
            knots.extend(std::iter::repeat_n((i + 1) as f64, p + 1));
        } else if p == 2 && is_exact_midpoint(seg[1], run[i + 1][1], end) {
            // simple knot: C(i+1) = (P_prev + P_next) / 2 = end, exactly
            knots.push((i + 1) as f64);
        } else {
            pts.push(end.to_vec());
            knots.extend(std::iter::repeat_n((i + 1) as f64, p));
        }
    }
    NurbsCurve::new(p, knots, pts, None)
}

fn contour_curves(contour: &[Segment], out: &mut Vec<NurbsCurve>) -> Result<(), CurveError> {
    let p = contour.iter().map(|s| s.pts.len() - 1).max().unwrap_or(1);
    let mut run: Vec<Vec<[f64; 2]>> = Vec::new();
    for s in contour {
        match exact_elevation(s, p) {
            Some(e) => run.push(e),
            None => {
                if !run.is_empty() {
                    out.push(run_curve(p, &run)?);
                    run.clear();
                }
                out.push(run_curve(s.pts.len() - 1, std::slice::from_ref(&s.pts))?);
            }
        }
    }
    if !run.is_empty() {
        out.push(run_curve(p, &run)?);
    }
    Ok(())
}

/// The verified box of one glyph and how the font's stored box compares with it.
///
/// Sides are ordered [x_min, y_min, x_max, y_max]. For a minimum side the exact extreme value
/// lies in [outer, inner]; for a maximum side in [inner, outer] (when `verified`).
#[derive(Debug, Clone, PartialEq)]
pub struct GlyphBox {
    /// glyph index
    pub glyph_id: u16,
    /// glyph name from the `post` or CFF table, if any
    pub name: Option<String>,
    /// the box stored in the `glyf` table (integer font units), if the font has one, shifted
    /// horizontally like the outline (by [`placement_shift`]; its x_min is then the `hmtx`
    /// left side bearing)
    pub stored_bbox: Option<[f64; 4]>,
    /// box of all control points (ttf-parser's computed "bbox" is this box)
    pub control_bbox: Option<[f64; 4]>,
    /// outer (verified) box: lo corner
    pub tight_lo: [f64; 2],
    /// outer (verified) box: hi corner
    pub tight_hi: [f64; 2],
    /// the outline provably reaches x <= inner_lo[0] and y <= inner_lo[1]
    pub inner_lo: [f64; 2],
    /// the outline provably reaches x >= inner_hi[0] and y >= inner_hi[1]
    pub inner_hi: [f64; 2],
    /// whether every curve's enclosure was verified
    pub verified: bool,
    /// number of curves the outline became
    pub curves: usize,
    /// certified lower bound on how far each stored side lies *outside* the exact box
    /// (stored x_min < outer lo, ...), 0 when not certified
    pub loose_by: [f64; 4],
    /// certified lower bound on how far each stored side lies *inside* the exact box, i.e.
    /// cuts off part of the outline (stored x_min > inner lo, ...), 0 when not certified
    pub too_small_by: [f64; 4],
}

impl GlyphBox {
    /// The outer box as [x_min, y_min, x_max, y_max].
    pub fn outer(&self) -> [f64; 4] {
        [
            self.tight_lo[0],
            self.tight_lo[1],
            self.tight_hi[0],
            self.tight_hi[1],
        ]
    }
    /// The inner box as [x_min, y_min, x_max, y_max].
    pub fn inner(&self) -> [f64; 4] {
        [
            self.inner_lo[0],
            self.inner_lo[1],
            self.inner_hi[0],
            self.inner_hi[1],
        ]
    }
}

/// Compare a stored box side by side with the verified bracket of the exact box:
/// returns (loose_by, too_small_by). Minimum sides: loose if stored < outer (the exact min is
/// at least outer), too small if stored > inner (the outline reaches inner or below). Maximum
/// sides mirrored. Differences are rounded down (toward zero) so they stay lower bounds.
fn compare(stored: [f64; 4], outer: [f64; 4], inner: [f64; 4]) -> ([f64; 4], [f64; 4]) {
    let mut loose = [0.0; 4];
    let mut small = [0.0; 4];
    let down = |a: f64, b: f64| (iv::point(a) - iv::point(b)).inf().max(0.0);
    for s in 0..4 {
        if s < 2 {
            loose[s] = down(outer[s], stored[s]);
            small[s] = down(stored[s], inner[s]);
        } else {
            loose[s] = down(stored[s], outer[s]);
            small[s] = down(inner[s], stored[s]);
        }
    }
    (loose, small)
}

/// Enclose every curve of every glyph of the font with `strategy`, hull the boxes per glyph,
/// and compare with the stored `glyf` boxes. Glyphs without outline are skipped.
pub fn glyph_boxes(
    font_bytes: &[u8],
    strategy: &dyn BoxEncloser,
) -> Result<Vec<GlyphBox>, FontError> {
    let face = Face::parse(font_bytes, 0).map_err(|e| FontError::Parse(e.to_string()))?;
    let glyf = face.tables().glyf;
    let mut out = Vec::new();
    for id in 0..face.number_of_glyphs() {
        let gid = GlyphId(id);
        let outline = glyph_outline(&face, gid);
        let curves = outline.curves().map_err(|source| FontError::Curve {
            glyph_id: id,
            source,
        })?;
        if curves.is_empty() {
            continue;
        }
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        let mut ilo = [f64::INFINITY; 2];
        let mut ihi = [f64::NEG_INFINITY; 2];
        let mut verified = true;
        for c in &curves {
            let e = strategy.enclose(c);
            verified &= e.verified;
            for j in 0..2 {
                let b = &e.coords[j];
                lo[j] = lo[j].min(b.lo);
                hi[j] = hi[j].max(b.hi);
                // the union reaches the smallest inner_lo of any of its curves
                ilo[j] = ilo[j].min(b.inner_lo);
                ihi[j] = ihi[j].max(b.inner_hi);
            }
        }
        let dx = placement_shift(&face, gid);
        let stored_bbox = glyf.and_then(|g| g.bbox(gid)).map(|r| {
            [
                f64::from(r.x_min) + dx,
                f64::from(r.y_min),
                f64::from(r.x_max) + dx,
                f64::from(r.y_max),
            ]
        });
        let outer = [lo[0], lo[1], hi[0], hi[1]];
        let inner = [ilo[0], ilo[1], ihi[0], ihi[1]];
        let (loose_by, too_small_by) = match stored_bbox {
            Some(s) if verified => compare(s, outer, inner),
            _ => ([0.0; 4], [0.0; 4]),
        };
        out.push(GlyphBox {
            glyph_id: id,
            name: face.glyph_name(gid).map(str::to_string),
            stored_bbox,
            control_bbox: outline.control_box(),
            tight_lo: lo,
            tight_hi: hi,
            inner_lo: ilo,
            inner_hi: ihi,
            verified,
            curves: curves.len(),
            loose_by,
            too_small_by,
        });
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seg(p: &[[f64; 2]]) -> Segment {
        Segment { pts: p.to_vec() }
    }

    /// The contour's curves pass through exactly the same points as its segments.
    fn same_curve(contour: &[Segment]) {
        let mut curves = Vec::new();
        contour_curves(contour, &mut curves).unwrap();
        // sample each segment and check some curve contains the point (f64 tolerance)
        for s in contour {
            let b = BezierSeg::<f64>::from_points(
                0.0,
                1.0,
                2,
                s.pts.iter().flatten().cloned().collect(),
            );
            for i in 0..=16 {
                let t = i as f64 / 16.0;
                let q = b.eval_local(&t);
                let hit = curves.iter().any(|c| {
                    let (a, e) = c.domain();
                    (0..=(64 * (e - a) as usize)).any(|k| {
                        let u = (a + k as f64 / 64.0).min(e);
                        let r: Vec<f64> = c.point(u).unwrap();
                        (r[0] - q[0]).abs() < 1e-9 && (r[1] - q[1]).abs() < 1e-9
                    })
                });
                assert!(hit, "point {q:?} of segment {:?} missing", s.pts);
            }
        }
    }

    #[test]
    fn truetype_contour_with_implied_points_is_one_quadratic_spline() {
        // square-ish contour: line, two quads joined at an implied midpoint, line back
        let contour = vec![
            seg(&[[0., 0.], [10., 0.]]),
            seg(&[[10., 0.], [20., 0.], [20., 5.]]),
            seg(&[[20., 5.], [20., 10.], [10., 10.]]),
            seg(&[[10., 10.], [0., 0.]]),
        ];
        let mut curves = Vec::new();
        contour_curves(&contour, &mut curves).unwrap();
        assert_eq!(curves.len(), 1);
        let c = &curves[0];
        assert_eq!(c.degree(), 2);
        // joins at 1 and 3 double (on-curve corners), at 2 simple ((20,0)+(20,10))/2 = (20,5)
        assert_eq!(c.knots(), &[0., 0., 0., 1., 1., 2., 3., 3., 4., 4., 4.]);
        let at2: Vec<f64> = c.point(2.0).unwrap();
        assert_eq!(at2, vec![20., 5.]);
        same_curve(&contour);
    }

    #[test]
    fn cubic_contour_keeps_inexact_lines_separate() {
        let contour = vec![
            seg(&[[0., 0.], [1., 2.], [3., 2.], [4., 0.]]),
            seg(&[[4., 0.], [0., 0.]]),
        ];
        let mut curves = Vec::new();
        contour_curves(&contour, &mut curves).unwrap();
        // (4,0)->(0,0) elevated to degree 3 needs 4/3, 8/3: not representable
        assert_eq!(curves.len(), 2);
        assert_eq!(curves[0].degree(), 3);
        assert_eq!(curves[1].degree(), 1);
        // a line whose thirds are exact is elevated and stays in the spline
        let contour = vec![
            seg(&[[0., 0.], [1., 2.], [2., 2.], [3., 0.]]),
            seg(&[[3., 0.], [0., 0.]]),
        ];
        let mut curves = Vec::new();
        contour_curves(&contour, &mut curves).unwrap();
        assert_eq!(curves.len(), 1);
        assert_eq!(curves[0].num_points(), 7);
        same_curve(&contour);
    }

    #[test]
    fn comparison_of_sides() {
        let (l, s) = compare(
            [-2.0, 0.0, 10.0, 7.0],
            [-1.0, 0.5, 10.5, 6.0],
            [-1.0, 0.6, 10.4, 6.0],
        );
        assert_eq!(l, [1.0, 0.5, 0.0, 1.0]);
        assert_eq!(s[0], 0.0);
        assert_eq!(s[1], 0.0);
        assert_eq!(s[3], 0.0);
        // 10.4 - 10 rounded down: a lower bound on the exact difference of the f64 values
        assert!(s[2] <= 10.4 - 10.0 && s[2] > 0.399_999);
    }
}
