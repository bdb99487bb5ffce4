//! The `serve` API over real sockets: a server on a free port in-process, requests with
//! std::net::TcpStream (HTTP/1.1 and the WebSocket), status codes, error records, limits, and
//! that the enclosure contains sampled points of the curve.
#![cfg(feature = "serve")]

use nurbs_box::serve::{Limits, Server};
use serde_json::Value;
use std::io::{Read, Write};
use std::net::{SocketAddr, TcpStream};
use std::time::Duration;

const CURVE: &str = r#"{"degree": 3, "knots": [0, 0, 0, 0, 0.5, 1, 1, 1, 1], "control_points": [[0, 0], [1, 2], [2, -1], [3, 3], [4, 0]], "weights": [1, 1, 2, 1, 1]}"#;

fn start() -> SocketAddr {
    let server = Server::bind(0, Limits::default()).expect("bind a free port");
    let (addr, _stop, _join) = server.spawn();
    addr
}

/// Send raw bytes, read the whole reply (the request asks to close), return status and body.
fn raw(addr: SocketAddr, request: &[u8]) -> (u16, String) {
    let mut s = TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    s.write_all(request).unwrap();
    let mut out = Vec::new();
    let _ = s.read_to_end(&mut out);
    let text = String::from_utf8_lossy(&out).to_string();
    let status = text
        .split(' ')
        .nth(1)
        .and_then(|c| c.parse().ok())
        .unwrap_or_else(|| panic!("no status line in {text:?}"));
    let body = text
        .split_once("\r\n\r\n")
        .map_or("", |(_, b)| b)
        .to_string();
    (status, body)
}

fn request(addr: SocketAddr, method: &str, target: &str, body: &str) -> (u16, Value) {
    let req = format!(
        "{method} {target} HTTP/1.1\r\nHost: {addr}\r\nContent-Length: {}\r\nConnection: close\r\n\r\n{body}",
        body.len()
    );
    let (status, body) = raw(addr, req.as_bytes());
    let v = serde_json::from_str(&body).unwrap_or_else(|e| panic!("not JSON ({e}): {body}"));
    (status, v)
}

/// Read a reply's status line and headers (up to the empty line), byte by byte.
fn read_head(s: &mut TcpStream) -> String {
    let mut head = Vec::new();
    let mut byte = [0u8; 1];
    while !head.ends_with(b"\r\n\r\n") {
        s.read_exact(&mut byte).unwrap();
        head.push(byte[0]);
    }
    String::from_utf8(head).unwrap()
}

fn nums(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect()
}

#[test]
fn enclose_contains_sampled_points_for_every_strategy() {
    let addr = start();
    let (status, v) = request(addr, "POST", "/api/enclose?strategy=all&samples=500", CURVE);
    assert_eq!(status, 200, "{v}");
    let samples = v["samples"].as_array().unwrap();
    assert!(samples.len() >= 500);
    let records = v["records"].as_array().unwrap();
    assert_eq!(records.len(), nurbs_box::enclose::STRATEGY_NAMES.len());
    for r in records {
        assert_eq!(r["index"], 0);
        assert!(r["time_s"].as_f64().unwrap() >= 0.0);
        let (lo, hi) = (nums(&r["lo"]), nums(&r["hi"]));
        let (ilo, ihi) = (nums(&r["inner_lo"]), nums(&r["inner_hi"]));
        for j in 0..2 {
            assert!(lo[j] <= ilo[j] && ihi[j] <= hi[j], "{r}");
            assert_eq!(nums(&r["gap"])[j], (ilo[j] - lo[j]).max(hi[j] - ihi[j]));
        }
        if r["verified"] == true {
            for p in samples {
                let p = nums(p);
                assert!(
                    (0..2).all(|j| lo[j] <= p[j] && p[j] <= hi[j]),
                    "{p:?} outside {r}"
                );
            }
        }
        // the extrema lie on the box
        let argmax = &r["argmax"][1].as_array().unwrap();
        assert!(!argmax.is_empty());
    }
    // newton: the maximum of y is a critical point, drawn at the box's top
    let newton = records.iter().find(|r| r["strategy"] == "newton").unwrap();
    let top = &newton["argmax"][1][0];
    assert_eq!(top["kind"], "critical");
    let y = nums(&top["point"])[1];
    assert!((y - nums(&newton["hi"])[1]).abs() < 1e-12, "{top}");
}

#[test]
fn enclose_matches_the_library_and_eval_gives_the_de_boor_triangle() {
    let addr = start();
    let curve = nurbs_box::parse_curve(CURVE.as_bytes()).unwrap();
    let e = nurbs_box::strategy_by_name("newton", None)
        .unwrap()
        .enclose(&curve);
    let (_, v) = request(addr, "POST", "/api/enclose", CURVE);
    assert_eq!(nums(&v["records"][0]["lo"]), e.lo());
    assert_eq!(nums(&v["records"][0]["hi"]), e.hi());
    assert_eq!(v["records"][0]["strategy"], "newton");

    let (status, v) = request(addr, "POST", "/api/eval?u=0.25", CURVE);
    assert_eq!(status, 200, "{v}");
    let tri = v["de_boor"].as_array().unwrap();
    assert_eq!(tri.len(), 4);
    assert_eq!(tri[0].as_array().unwrap().len(), 4);
    assert_eq!(nums(&tri[0][1]), vec![1.0, 2.0]);
    let p = nums(&v["point"]);
    assert_eq!(nums(&tri[3][0]), p);
    let (lo, hi) = (nums(&v["lo"]), nums(&v["hi"]));
    assert!((0..2).all(|j| lo[j] <= p[j] && p[j] <= hi[j]));
    assert_eq!(v["span"], 3);
}

#[test]
fn knots_endpoint() {
    let addr = start();
    let (status, v) = request(addr, "GET", "/api/knots?degree=2&points=5", "");
    assert_eq!(status, 200);
    assert_eq!(nums(&v["knots"]), vec![0., 0., 0., 1., 2., 3., 3., 3.]);
    let (_, v) = request(
        addr,
        "GET",
        "/api/knots?degree=2&points=3&kind=unclamped",
        "",
    );
    assert_eq!(nums(&v["knots"]), vec![0., 1., 2., 3., 4., 5.]);
    let (status, v) = request(addr, "GET", "/api/knots?degree=0&points=5", "");
    assert_eq!(
        (status, v["error"]["kind"].as_str()),
        (400, Some("invalid_degree"))
    );
    let (status, v) = request(addr, "GET", "/api/knots?degree=4&points=3", "");
    assert_eq!(
        (status, v["error"]["kind"].as_str()),
        (400, Some("too_few_control_points"))
    );
}

#[test]
fn bad_requests_get_4xx_json_errors() {
    let addr = start();
    let cases: &[(&str, &str, &str, u16, &str)] = &[
        (
            "POST",
            "/api/enclose",
            "{\"degree\": 3",
            400,
            "truncated_json",
        ),
        ("POST", "/api/enclose", "not json", 400, "invalid_json"),
        (
            "POST",
            "/api/enclose",
            r#"{"degree": 0, "knots": [0, 1], "control_points": [[0, 0]]}"#,
            400,
            "invalid_degree",
        ),
        (
            "POST",
            "/api/enclose?strategy=nope",
            CURVE,
            400,
            "bad_query",
        ),
        ("POST", "/api/enclose?tol=-1", CURVE, 400, "bad_query"),
        (
            "POST",
            "/api/enclose?samples=100000000",
            CURVE,
            400,
            "limit_exceeded",
        ),
        ("POST", "/api/enclose?colour=red", CURVE, 400, "bad_query"),
        ("POST", "/api/eval?u=2", CURVE, 400, "param_out_of_domain"),
        ("POST", "/api/eval", CURVE, 400, "bad_query"),
        ("GET", "/api/enclose", "", 405, "method_not_allowed"),
        ("GET", "/nowhere", "", 404, "not_found"),
    ];
    for &(method, target, body, status, kind) in cases {
        let (s, v) = request(addr, method, target, body);
        assert_eq!(
            (s, v["error"]["kind"].as_str()),
            (status, Some(kind)),
            "{method} {target}: {v}"
        );
        assert!(!v["error"]["message"].as_str().unwrap().is_empty());
    }
    // a curve error is the command line's record: index 0, the field and position
    let (_, v) = request(addr, "POST", "/api/enclose", "{\"degree\": 3}");
    assert_eq!(v["index"], 0);
    assert!(v["error"]["message"].as_str().unwrap().contains("knots"));
    // the server still answers after all that
    let (s, _) = request(addr, "GET", "/api/strategies", "");
    assert_eq!(s, 200);
}

#[test]
fn oversized_requests_are_refused_unread() {
    let addr = start();
    // declared far beyond the limit (and beyond memory): refused from the header alone
    let (status, body) = raw(
        addr,
        b"POST /api/enclose HTTP/1.1\r\nHost: x\r\nContent-Length: 100000000000000\r\n\r\n{",
    );
    assert_eq!(status, 413, "{body}");
    assert!(body.contains("body_too_large"));
    // really sent: two megabytes
    let big = format!("[{}]", "0,".repeat(1 << 20));
    let (status, v) = request(addr, "POST", "/api/enclose", &big);
    assert_eq!(
        (status, v["error"]["kind"].as_str()),
        (413, Some("body_too_large"))
    );
    // a head without end
    let mut head = b"GET / HTTP/1.1\r\n".to_vec();
    head.extend(std::iter::repeat_n(b'a', 20_000));
    let (status, _) = raw(addr, &head);
    assert_eq!(status, 431);
    // more control points than the limit
    let n = Limits::default().max_points + 1;
    let pts = vec!["[0,0]"; n].join(",");
    let knots = nurbs_box::build::knot_vectors::uniform_clamped(1, n).unwrap();
    let curve = format!(
        "{{\"degree\":1,\"knots\":{},\"control_points\":[{pts}]}}",
        serde_json::to_string(&knots).unwrap()
    );
    let (status, v) = request(addr, "POST", "/api/enclose", &curve);
    assert_eq!(
        (status, v["error"]["kind"].as_str()),
        (400, Some("limit_exceeded")),
        "{v}"
    );
    // malformed HTTP
    let (status, _) = raw(addr, b"\x00\x01 nonsense\r\n\r\n");
    assert_eq!(status, 400);
}

#[test]
fn keep_alive_serves_several_requests_on_one_connection() {
    let addr = start();
    let mut s = TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    for _ in 0..3 {
        write!(
            s,
            "POST /api/enclose?strategy=hull HTTP/1.1\r\nHost: x\r\nContent-Length: {}\r\n\r\n{CURVE}",
            CURVE.len()
        )
        .unwrap();
        let head = read_head(&mut s);
        assert!(head.starts_with("HTTP/1.1 200"), "{head}");
        let len: usize = head
            .lines()
            .find_map(|l| l.strip_prefix("Content-Length: "))
            .unwrap()
            .parse()
            .unwrap();
        let mut body = vec![0u8; len];
        s.read_exact(&mut body).unwrap();
        let v: Value = serde_json::from_slice(&body).unwrap();
        assert_eq!(v["records"][0]["strategy"], "hull");
    }
}

#[test]
fn websocket_answers_like_http_and_checks_the_origin() {
    let addr = start();
    let handshake = |origin: &str| {
        format!(
            "GET /api/ws HTTP/1.1\r\nHost: {addr}\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n\
             Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n{origin}\r\n"
        )
    };
    let (status, _) = raw(
        addr,
        handshake("Origin: http://evil.example\r\n").as_bytes(),
    );
    assert_eq!(status, 403);

    let mut s = TcpStream::connect(addr).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(20))).unwrap();
    let origin = format!("Origin: http://{addr}\r\n");
    s.write_all(handshake(&origin).as_bytes()).unwrap();
    let head = read_head(&mut s);
    assert!(head.starts_with("HTTP/1.1 101"), "{head}");
    assert!(
        head.contains("Sec-WebSocket-Accept: s3pPLMBiTxaQ9kYGzzhZRbK+xOo="),
        "{head}"
    );
    // one masked text frame per request
    let send = |s: &mut TcpStream, text: &str| {
        let mask = [1u8, 2, 3, 4];
        let p = text.as_bytes();
        let mut f = vec![0x81u8];
        if p.len() < 126 {
            f.push(0x80 | p.len() as u8);
        } else {
            f.push(0x80 | 126);
            f.extend_from_slice(&(p.len() as u16).to_be_bytes());
        }
        f.extend_from_slice(&mask);
        f.extend(p.iter().enumerate().map(|(i, b)| b ^ mask[i % 4]));
        s.write_all(&f).unwrap();
    };
    let recv = |s: &mut TcpStream| -> Value {
        let mut h = [0u8; 2];
        s.read_exact(&mut h).unwrap();
        assert_eq!(h[0], 0x81);
        let len = match h[1] {
            126 => {
                let mut b = [0u8; 2];
                s.read_exact(&mut b).unwrap();
                usize::from(u16::from_be_bytes(b))
            }
            127 => {
                let mut b = [0u8; 8];
                s.read_exact(&mut b).unwrap();
                u64::from_be_bytes(b) as usize
            }
            n => usize::from(n),
        };
        let mut body = vec![0u8; len];
        s.read_exact(&mut body).unwrap();
        serde_json::from_slice(&body).unwrap()
    };
    send(
        &mut s,
        &format!("POST /api/enclose?strategy=bezier\n{CURVE}"),
    );
    let v = recv(&mut s);
    assert_eq!(v["status"], 200);
    assert_eq!(v["body"]["records"][0]["strategy"], "bezier");
    send(&mut s, "POST /api/eval?u=7\n{}");
    let v = recv(&mut s);
    assert_eq!(v["status"], 400);
    assert!(v["body"]["error"]["kind"].is_string());
    send(&mut s, "GET /api/knots?degree=1&points=2\n");
    assert_eq!(nums(&recv(&mut s)["body"]["knots"]), vec![0., 0., 1., 1.]);
}

#[test]
fn the_page_is_served_with_its_script_and_style() {
    let addr = start();
    for (path, needle) in [
        ("/", "<canvas"),
        ("/page.js", "nurbsBox"),
        ("/page.css", "#canvas"),
    ] {
        let (status, body) = raw(
            addr,
            format!("GET {path} HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n").as_bytes(),
        );
        assert_eq!(status, 200);
        assert!(body.contains(needle), "{path}");
        assert!(
            !body.contains("http://") || path != "/",
            "the page fetches nothing"
        );
    }
}
