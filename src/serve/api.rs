//! The JSON API of `nurbs-box serve`, as a pure function [`handle`] of (method, target, body):
//! no sockets here, so every route is testable directly.
//!
//! Request bodies are curves in the command line's JSON format (parsed by
//! [`crate::io::parse_curve`], with its messages); options travel in the query string. Replies
//! reuse the command line's records ([`write_enclosure_record`], [`write_eval_record`],
//! [`write_error_record`]) and add fields, never rename them.

use crate::build::knot_vectors::{uniform_clamped, uniform_unclamped};
use crate::enclose::{
    strategy_with_work, BoxEncloser, CandidateKind, Enclosure, Extremum, Guarantee, STRATEGY_NAMES,
};
use crate::error::{CurveError, EvalError};
use crate::io::{
    eval_fields, parse_curve, write_enclosure_record, write_error_record, write_eval_record,
    write_num, write_nums, write_str, InputError,
};
use crate::num::iv;
use crate::spline::bspline::HSpline;
use crate::spline::eval::project;
use crate::NurbsCurve;
use std::time::Instant;
use thiserror::Error;

/// The page and its script and style, shipped inside the binary.
const PAGE_HTML: &str = include_str!("page.html");
const PAGE_JS: &str = include_str!("page.js");
const PAGE_CSS: &str = include_str!("page.css");

/// Bounds on one request: its size and the work it may cause.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// Longest request body, in bytes (longer: 413).
    pub max_body_bytes: usize,
    /// Most control points of a curve.
    pub max_points: usize,
    /// Highest degree.
    pub max_degree: usize,
    /// Highest dimension (the page draws 2-D curves and 3-D ones in projection).
    pub max_dim: usize,
    /// Most curve samples returned by `/api/enclose?samples=N`.
    pub max_samples: usize,
    /// Work budget of each searching strategy per coordinate (see
    /// [`crate::enclose::Newton::max_work`]); a tenth of the command line's default.
    pub max_work: u64,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_body_bytes: 1 << 20,
            max_points: 2000,
            max_degree: 40,
            max_dim: 3,
            max_samples: 20_000,
            max_work: crate::enclose::DEFAULT_MAX_WORK / 10,
        }
    }
}

/// A reply: status, content type and body.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Reply {
    /// HTTP status code
    pub status: u16,
    /// value of the Content-Type header
    pub content_type: &'static str,
    /// the body
    pub body: Vec<u8>,
}

impl Reply {
    fn json(body: Vec<u8>) -> Reply {
        Reply {
            status: 200,
            content_type: JSON,
            body,
        }
    }
}

const JSON: &str = "application/json";

/// Why a request was refused. Each variant has a status (4xx, or 500 for a bug) and a
/// machine-readable kind; the reply body is a JSON error record.
#[derive(Debug, Error)]
#[non_exhaustive]
pub enum ApiError {
    /// No such page or endpoint.
    #[error("no such page or endpoint: {0}; the API is /api/strategies, /api/knots, /api/enclose and /api/eval")]
    NotFound(String),
    /// Wrong method for the path.
    #[error("{path} takes {allowed} requests, not {method}")]
    MethodNotAllowed {
        /// the path
        path: String,
        /// the method that was used
        method: String,
        /// the method it takes
        allowed: &'static str,
    },
    /// The body is longer than [`Limits::max_body_bytes`].
    #[error("the request body has {got} bytes, more than the limit of {limit}")]
    BodyTooLarge {
        /// declared or received length
        got: usize,
        /// the limit
        limit: usize,
    },
    /// A bad query parameter.
    #[error("{0}")]
    BadQuery(String),
    /// The body is not a valid curve (the command line's message).
    #[error(transparent)]
    Curve(#[from] InputError),
    /// A valid curve beyond what one request may ask for.
    #[error("{what} is {got}, more than this server's limit of {max}")]
    Limit {
        /// what is too large
        what: &'static str,
        /// its value
        got: usize,
        /// the limit
        max: usize,
    },
    /// A parameter outside the curve's domain.
    #[error(transparent)]
    Eval(#[from] EvalError),
    /// No knot vector for that degree and point count.
    #[error(transparent)]
    Knots(#[from] CurveError),
    /// A bug (a strategy panicked); reported, never hidden.
    #[error("internal error: {0}; please report it with the curve")]
    Internal(String),
}

impl ApiError {
    /// The HTTP status.
    pub fn status(&self) -> u16 {
        match self {
            ApiError::NotFound(_) => 404,
            ApiError::MethodNotAllowed { .. } => 405,
            ApiError::BodyTooLarge { .. } => 413,
            ApiError::Internal(_) => 500,
            _ => 400,
        }
    }

    /// The `kind` of the error record (the command line's kinds for curve errors).
    pub fn kind(&self) -> &'static str {
        match self {
            ApiError::NotFound(_) => "not_found",
            ApiError::MethodNotAllowed { .. } => "method_not_allowed",
            ApiError::BodyTooLarge { .. } => "body_too_large",
            ApiError::BadQuery(_) => "bad_query",
            ApiError::Curve(e) => e.kind(),
            ApiError::Limit { .. } => "limit_exceeded",
            ApiError::Eval(e) => e.kind(),
            ApiError::Knots(e) => e.kind(),
            ApiError::Internal(_) => "internal_error",
        }
    }

    /// The reply: `{"error": {"kind", "message"}}`; for errors about the request's curve the
    /// command line's record, `{"index": 0, ..., "error": {...}}` (the curve is curve 0).
    pub fn reply(&self, extra: &str) -> Reply {
        let mut body = Vec::new();
        let msg = self.to_string();
        match self {
            ApiError::Curve(_) | ApiError::Limit { .. } | ApiError::Eval(_) => {
                write_error_record(&mut body, 0, extra, self.kind(), &msg)
            }
            _ => {
                body.extend_from_slice(b"{\"error\":{\"kind\":");
                write_str(&mut body, self.kind());
                body.extend_from_slice(b",\"message\":");
                write_str(&mut body, &msg);
                body.extend_from_slice(b"}}");
            }
        }
        Reply {
            status: self.status(),
            content_type: JSON,
            body,
        }
    }
}

/// Answer one request. `target` is the request target (path and query); `body` has already
/// been bounded by the caller (it is checked again here). Never panics on any input.
pub fn handle(method: &str, target: &str, body: &[u8], limits: &Limits) -> Reply {
    let (path, query) = target.split_once('?').unwrap_or((target, ""));
    let text = |content_type, s: &str| Reply {
        status: 200,
        content_type,
        body: s.as_bytes().to_vec(),
    };
    let want = |allowed: &'static str| -> Result<(), ApiError> {
        if method == allowed || (allowed == "GET" && method == "HEAD") {
            Ok(())
        } else {
            Err(ApiError::MethodNotAllowed {
                path: path.to_string(),
                method: method.to_string(),
                allowed,
            })
        }
    };
    if body.len() > limits.max_body_bytes {
        return ApiError::BodyTooLarge {
            got: body.len(),
            limit: limits.max_body_bytes,
        }
        .reply("");
    }
    let result = match path {
        "/" | "/index.html" => want("GET").map(|()| text("text/html; charset=utf-8", PAGE_HTML)),
        "/page.js" => want("GET").map(|()| text("text/javascript; charset=utf-8", PAGE_JS)),
        "/page.css" => want("GET").map(|()| text("text/css; charset=utf-8", PAGE_CSS)),
        "/favicon.ico" => want("GET").map(|()| Reply {
            status: 204,
            content_type: "image/x-icon",
            body: Vec::new(),
        }),
        "/api/strategies" => want("GET").and_then(|()| strategies(query, limits)),
        "/api/knots" => want("GET").and_then(|()| knots(query, limits)),
        "/api/enclose" => want("POST").and_then(|()| enclose(query, body, limits)),
        "/api/eval" => want("POST").and_then(|()| eval(query, body, limits)),
        _ => Err(ApiError::NotFound(path.to_string())),
    };
    result.unwrap_or_else(|e| {
        let extra = match (&e, Query::parse(query, &["u"]).and_then(|q| q.f64("u"))) {
            (ApiError::Eval(_), Ok(Some(u))) => eval_fields(u, 0),
            _ => String::new(),
        };
        e.reply(&extra)
    })
}

/// The query string as (name, value) pairs, percent-decoded, names checked against a list.
struct Query(Vec<(String, String)>);

impl Query {
    fn parse(q: &str, allowed: &[&str]) -> Result<Query, ApiError> {
        let mut pairs: Vec<(String, String)> = Vec::new();
        for part in q.split('&').filter(|p| !p.is_empty()) {
            let (k, v) = part.split_once('=').unwrap_or((part, ""));
            let (k, v) = (decode(k)?, decode(v)?);
            if !allowed.contains(&k.as_str()) {
                return Err(ApiError::BadQuery(format!(
                    "unknown query parameter {k:?}; this endpoint takes {}",
                    if allowed.is_empty() {
                        "none".to_string()
                    } else {
                        allowed.join(", ")
                    }
                )));
            }
            if pairs.iter().any(|(n, _)| *n == k) {
                return Err(ApiError::BadQuery(format!(
                    "query parameter {k:?} given twice"
                )));
            }
            pairs.push((k, v));
        }
        Ok(Query(pairs))
    }

    fn get(&self, name: &str) -> Option<&str> {
        self.0
            .iter()
            .find(|(k, _)| k == name)
            .map(|(_, v)| v.as_str())
    }

    fn f64(&self, name: &str) -> Result<Option<f64>, ApiError> {
        self.get(name)
            .map(|v| {
                v.parse::<f64>()
                    .ok()
                    .filter(|x| x.is_finite())
                    .ok_or_else(|| {
                        ApiError::BadQuery(format!("{name}: expected a finite number, got {v:?}"))
                    })
            })
            .transpose()
    }

    fn usize(&self, name: &str, max: usize) -> Result<Option<usize>, ApiError> {
        self.get(name)
            .map(|v| {
                let n = v.parse::<usize>().map_err(|_| {
                    ApiError::BadQuery(format!(
                        "{name}: expected a non-negative integer, got {v:?}"
                    ))
                })?;
                if n > max {
                    return Err(ApiError::Limit {
                        what: name_of(name),
                        got: n,
                        max,
                    });
                }
                Ok(n)
            })
            .transpose()
    }
}

fn name_of(q: &str) -> &'static str {
    match q {
        "degree" => "the degree",
        "points" => "the number of control points",
        "samples" => "the number of samples",
        _ => "a parameter",
    }
}

/// Percent-decoding of a query component (`+` is a space).
fn decode(s: &str) -> Result<String, ApiError> {
    let b = s.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'%' => {
                let hex = b
                    .get(i + 1..i + 3)
                    .and_then(|h| std::str::from_utf8(h).ok())
                    .and_then(|h| u8::from_str_radix(h, 16).ok())
                    .ok_or_else(|| {
                        ApiError::BadQuery(format!("bad percent escape in the query: {s:?}"))
                    })?;
                out.push(hex);
                i += 3;
            }
            b'+' => {
                out.push(b' ');
                i += 1;
            }
            c => {
                out.push(c);
                i += 1;
            }
        }
    }
    String::from_utf8(out)
        .map_err(|_| ApiError::BadQuery(format!("the query is not UTF-8 after decoding: {s:?}")))
}

/// Parse the body as a curve and check it against the limits.
fn curve_from_body(body: &[u8], limits: &Limits) -> Result<NurbsCurve, ApiError> {
    let c = parse_curve(body)?;
    let checks = [
        (
            "the number of control points",
            c.num_points(),
            limits.max_points,
        ),
        ("the degree", c.degree(), limits.max_degree),
        ("the dimension", c.dim(), limits.max_dim),
    ];
    for (what, got, max) in checks {
        if got > max {
            return Err(ApiError::Limit { what, got, max });
        }
    }
    Ok(c)
}

/// `GET /api/strategies`: the strategy names, the default, and the limits.
fn strategies(query: &str, limits: &Limits) -> Result<Reply, ApiError> {
    Query::parse(query, &[])?;
    let mut out = b"{\"strategies\":[".to_vec();
    for (i, n) in STRATEGY_NAMES.iter().enumerate() {
        let verified = strategy_with_work(n, None, limits.max_work)
            .is_some_and(|s| s.guarantee() == Guarantee::Verified);
        if i > 0 {
            out.push(b',');
        }
        out.extend_from_slice(b"{\"name\":");
        write_str(&mut out, n);
        out.extend_from_slice(format!(",\"verified\":{verified}}}").as_bytes());
    }
    let l = limits;
    out.extend_from_slice(
        format!(
            "],\"default\":\"newton\",\"limits\":{{\"max_body_bytes\":{},\"max_points\":{},\
             \"max_degree\":{},\"max_dim\":{},\"max_samples\":{},\"max_work\":{}}}}}",
            l.max_body_bytes, l.max_points, l.max_degree, l.max_dim, l.max_samples, l.max_work
        )
        .as_bytes(),
    );
    Ok(Reply::json(out))
}

/// `GET /api/knots?degree=P&points=N[&kind=clamped|unclamped]`: the uniform knot vector.
fn knots(query: &str, limits: &Limits) -> Result<Reply, ApiError> {
    let q = Query::parse(query, &["degree", "points", "kind"])?;
    let missing = |n: &str| ApiError::BadQuery(format!("{n}: missing (e.g. ?degree=3&points=5)"));
    let p = q
        .usize("degree", limits.max_degree)?
        .ok_or_else(|| missing("degree"))?;
    let n = q
        .usize("points", limits.max_points)?
        .ok_or_else(|| missing("points"))?;
    let kind = q.get("kind").unwrap_or("clamped");
    let k = match kind {
        "clamped" => uniform_clamped(p, n)?,
        "unclamped" => uniform_unclamped(p, n)?,
        _ => {
            return Err(ApiError::BadQuery(format!(
                "kind: expected clamped or unclamped, got {kind:?}"
            )))
        }
    };
    let mut out = format!("{{\"degree\":{p},\"points\":{n},\"kind\":").into_bytes();
    write_str(&mut out, kind);
    out.extend_from_slice(b",\"knots\":");
    write_nums(&mut out, k.iter().copied());
    out.extend_from_slice(b",\"domain\":");
    write_nums(&mut out, [k[p], k[n]]);
    out.push(b'}');
    Ok(Reply::json(out))
}

/// `POST /api/enclose?strategy=S|all[&tol=T][&samples=N]`, body a curve: `{"domain", "dim",
/// "records": [one per strategy], "samples": [points]}`. Each record is the command line's
/// `enclose` record with timings, plus `time_s` (wall time of the strategy), `gap` (certified
/// overestimation per coordinate), `argmin` / `argmax` (per coordinate, the candidate parameter
/// intervals with the curve point at their midpoint).
fn enclose(query: &str, body: &[u8], limits: &Limits) -> Result<Reply, ApiError> {
    let q = Query::parse(query, &["strategy", "tol", "samples"])?;
    let tol = q.f64("tol")?;
    if let Some(t) = tol.filter(|t| *t <= 0.0) {
        return Err(ApiError::BadQuery(format!(
            "tol: expected a finite number > 0, got {t}"
        )));
    }
    let samples = q.usize("samples", limits.max_samples)?.unwrap_or(0);
    let names: Vec<&str> = match q.get("strategy").unwrap_or("newton") {
        "all" => STRATEGY_NAMES.to_vec(),
        n => vec![n],
    };
    let strategies = names
        .iter()
        .map(|n| {
            strategy_with_work(n, tol, limits.max_work).ok_or_else(|| {
                ApiError::BadQuery(format!(
                    "strategy: unknown strategy {n:?}; known strategies: {}, all",
                    STRATEGY_NAMES.join(", ")
                ))
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    let c = curve_from_body(body, limits)?;
    let h = HSpline::<f64>::from_curve(&c);
    let mut out = b"{\"domain\":".to_vec();
    let (a, b) = c.domain();
    write_nums(&mut out, [a, b]);
    out.extend_from_slice(format!(",\"dim\":{},\"records\":[", c.dim()).as_bytes());
    for (i, s) in strategies.iter().enumerate() {
        if i > 0 {
            out.push(b',');
        }
        let (e, secs) = run_strategy(s.as_ref(), &c)?;
        write_record(&mut out, &e, secs, &c, &h);
    }
    out.extend_from_slice(b"],\"samples\":[");
    for (i, pt) in sample(&c, &h, samples).into_iter().enumerate() {
        if i > 0 {
            out.push(b',');
        }
        write_nums(&mut out, pt);
    }
    out.extend_from_slice(b"]}");
    Ok(Reply::json(out))
}

/// Run one strategy; a panic (a bug: strategies must not panic) becomes a 500 reply.
fn run_strategy(s: &dyn BoxEncloser, c: &NurbsCurve) -> Result<(Enclosure, f64), ApiError> {
    let t = Instant::now();
    std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| s.enclose(c)))
        .map(|e| (e, t.elapsed().as_secs_f64()))
        .map_err(|_| ApiError::Internal(format!("strategy {} failed", s.name())))
}

/// The command line's record for `e`, with the extra fields of [`enclose`].
fn write_record(out: &mut Vec<u8>, e: &Enclosure, secs: f64, c: &NurbsCurve, h: &HSpline<f64>) {
    write_enclosure_record(out, 0, e, true);
    out.pop(); // the record's closing brace: the extra fields go inside
    out.extend_from_slice(b",\"time_s\":");
    write_num(out, secs);
    out.extend_from_slice(b",\"gap\":");
    write_nums(out, e.coords.iter().map(|cb| cb.gap()));
    for (name, side) in [("argmin", 0), ("argmax", 1)] {
        out.extend_from_slice(format!(",\"{name}\":[").as_bytes());
        for (j, cb) in e.coords.iter().enumerate() {
            if j > 0 {
                out.push(b',');
            }
            let list = if side == 0 { &cb.argmin } else { &cb.argmax };
            out.push(b'[');
            for (i, x) in list.iter().enumerate() {
                if i > 0 {
                    out.push(b',');
                }
                write_extremum(out, x, c, h);
            }
            out.push(b']');
        }
        out.push(b']');
    }
    out.push(b'}');
}

fn write_extremum(out: &mut Vec<u8>, x: &Extremum, c: &NurbsCurve, h: &HSpline<f64>) {
    let kind = match x.kind {
        CandidateKind::EndPoint => "end_point",
        CandidateKind::Knot => "knot",
        CandidateKind::Critical => "critical",
        CandidateKind::Unresolved => "unresolved",
        CandidateKind::ControlPoint => "control_point",
    };
    out.extend_from_slice(b"{\"u_lo\":");
    write_num(out, x.u_lo);
    out.extend_from_slice(b",\"u_hi\":");
    write_num(out, x.u_hi);
    out.extend_from_slice(
        format!(",\"unique\":{},\"kind\":\"{kind}\",\"point\":", x.unique).as_bytes(),
    );
    let (a, b) = c.domain();
    let u = (0.5 * x.u_lo + 0.5 * x.u_hi).clamp(a, b);
    if u.is_finite() {
        write_nums(out, point_f64(c, h, u));
    } else {
        out.extend_from_slice(b"null");
    }
    out.push(b'}');
}

/// C(u) in f64 (for drawing), u in the domain.
fn point_f64(c: &NurbsCurve, h: &HSpline<f64>, u: f64) -> Vec<f64> {
    project(h.eval(u), c.dim(), c.is_rational())
}

/// About `n` points of the curve (f64, for drawing): the same number on each non-empty knot
/// span, both ends of each span included; none for `n == 0`.
fn sample(c: &NurbsCurve, h: &HSpline<f64>, n: usize) -> Vec<Vec<f64>> {
    if n == 0 {
        return Vec::new();
    }
    let (p, k) = (c.degree(), c.knots());
    let spans: Vec<usize> = (p..c.num_points()).filter(|&i| k[i] < k[i + 1]).collect();
    let per = (n / spans.len()).max(1);
    let mut pts = Vec::with_capacity(per * spans.len() + 1);
    let mut buf = Vec::new();
    for &s in &spans {
        let (u0, u1) = (k[s], k[s + 1]);
        for i in 0..per {
            let u = u0 + (u1 - u0) * (i as f64 / per as f64);
            h.eval_span(s, &u, &mut buf);
            pts.push(project(buf.clone(), c.dim(), c.is_rational()));
        }
    }
    let last = *spans.last().expect("a valid curve has a non-empty span");
    h.eval_span(last, &k[last + 1], &mut buf);
    pts.push(project(buf, c.dim(), c.is_rational()));
    pts
}

/// `POST /api/eval?u=U`, body a curve: the command line's `eval` record of C(U) (a verified
/// enclosure, `lo` / `hi`), plus `point` (C(U) in f64), `span` (the knot span k with
/// u_k <= U < u_{k+1}), `domain`, and `de_boor`: the de Boor triangle, one list of points per
/// level r = 0..p (level 0 the p + 1 control points of the span, level p the point itself).
fn eval(query: &str, body: &[u8], limits: &Limits) -> Result<Reply, ApiError> {
    let q = Query::parse(query, &["u"])?;
    let u = q
        .f64("u")?
        .ok_or_else(|| ApiError::BadQuery("u: missing (e.g. ?u=0.5)".to_string()))?;
    let c = curve_from_body(body, limits)?;
    let v = c.enclose_point(iv::point(u))?;
    let h = HSpline::<f64>::from_curve(&c);
    let mut out = Vec::new();
    write_eval_record(&mut out, 0, u, 0, &v);
    out.pop();
    out.extend_from_slice(b",\"point\":");
    write_nums(&mut out, point_f64(&c, &h, u));
    let k = h.span(u);
    let (a, b) = c.domain();
    out.extend_from_slice(format!(",\"span\":{k},\"domain\":").as_bytes());
    write_nums(&mut out, [a, b]);
    out.extend_from_slice(b",\"de_boor\":[");
    let p = c.degree();
    let hd = h.hdim();
    for r in 0..=p {
        if r > 0 {
            out.push(b',');
        }
        let col = h.de_boor_column(k, &u, p + 1 - r);
        out.push(b'[');
        for (i, pt) in col.chunks(hd).enumerate() {
            if i > 0 {
                out.push(b',');
            }
            write_nums(&mut out, project(pt.to_vec(), c.dim(), c.is_rational()));
        }
        out.push(b']');
    }
    out.extend_from_slice(b"]}");
    Ok(Reply::json(out))
}
