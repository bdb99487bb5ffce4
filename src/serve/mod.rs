//! `nurbs-box serve`: an interactive page (edit a curve, watch its verified box live) and a
//! small JSON API over the library, on 127.0.0.1.
//!
//! The routes and their JSON are in [`api`] ([`handle`] is a pure function of the request);
//! this module is the HTTP/1.1 transport: requests are parsed with `httparse`, one thread per
//! connection (at most [`MAX_CONNECTIONS`]), keep-alive, `TCP_NODELAY` (an edit's round trip
//! is a few milliseconds; Nagle's algorithm would add tens), read and write timeouts, and every
//! size bounded *before* anything is allocated for it: the request head
//! ([`MAX_HEAD_BYTES`]), the body ([`Limits::max_body_bytes`], refused with 413 from its
//! declared length, unread), and the work of one request (the limits of [`Limits`]).
//! Only `Content-Length` bodies are taken (the page and common clients send those); a chunked
//! body gets 411.

mod api;
mod ws;

pub use api::{handle, ApiError, Limits, Reply};

use std::io::{self, Read, Write};
use std::net::{Ipv4Addr, Shutdown, SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;
use std::thread;
use std::time::Duration;

/// Longest request line plus headers.
pub const MAX_HEAD_BYTES: usize = 16 << 10;
/// Most connections served at once; more get 503.
pub const MAX_CONNECTIONS: usize = 32;
/// Most headers in one request.
const MAX_HEADERS: usize = 64;
/// An idle or stalled connection is closed after this.
const IO_TIMEOUT: Duration = Duration::from_secs(30);
/// An idle WebSocket is closed after this (the page opens a new one when it needs it).
const WS_IDLE_TIMEOUT: Duration = Duration::from_secs(600);

/// A bound listener, ready to [`Server::run`].
#[derive(Debug)]
pub struct Server {
    listener: TcpListener,
    addr: SocketAddr,
    limits: Limits,
    stop: Arc<AtomicBool>,
}

/// Stops a running [`Server`] (from another thread).
#[derive(Debug, Clone)]
pub struct StopHandle {
    addr: SocketAddr,
    stop: Arc<AtomicBool>,
}

impl StopHandle {
    /// Make [`Server::run`] return after the connection it is accepting (wakes it up).
    pub fn stop(&self) {
        self.stop.store(true, Ordering::SeqCst);
        let _ = TcpStream::connect_timeout(&self.addr, Duration::from_secs(1));
    }
}

impl Server {
    /// Bind 127.0.0.1:`port` (0: a free port, see [`Server::addr`]).
    pub fn bind(port: u16, limits: Limits) -> io::Result<Server> {
        let listener = TcpListener::bind((Ipv4Addr::LOCALHOST, port))?;
        let addr = listener.local_addr()?;
        // the page shows the strategies' times (`time_total_s`): ask them to read the clock
        crate::enclose::set_timing(true);
        Ok(Server {
            listener,
            addr,
            limits,
            stop: Arc::new(AtomicBool::new(false)),
        })
    }

    /// The address it listens on.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// The page's address, `http://127.0.0.1:PORT/`.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    /// A handle that stops [`Server::run`].
    pub fn stop_handle(&self) -> StopHandle {
        StopHandle {
            addr: self.addr,
            stop: Arc::clone(&self.stop),
        }
    }

    /// Accept and serve connections until stopped (or forever).
    pub fn run(self) {
        let open = Arc::new(AtomicUsize::new(0));
        for stream in self.listener.incoming() {
            if self.stop.load(Ordering::SeqCst) {
                break;
            }
            let Ok(stream) = stream else { continue };
            if open.fetch_add(1, Ordering::SeqCst) >= MAX_CONNECTIONS {
                open.fetch_sub(1, Ordering::SeqCst);
                let mut s = stream;
                let _ = s.set_write_timeout(Some(Duration::from_secs(1)));
                let busy = status_reply(
                    503,
                    "busy",
                    &format!("more than {MAX_CONNECTIONS} connections are open; try again"),
                );
                let _ = write_reply(&mut s, &busy, false, false);
                continue;
            }
            let (count, limits) = (Arc::clone(&open), self.limits);
            let spawned = thread::Builder::new()
                .name("serve-connection".into())
                .spawn(move || {
                    let _ = connection(stream, &limits);
                    count.fetch_sub(1, Ordering::SeqCst);
                });
            if spawned.is_err() {
                open.fetch_sub(1, Ordering::SeqCst);
            }
        }
    }

    /// Run on a background thread; returns the address and a [`StopHandle`] (for tests and
    /// embedding).
    pub fn spawn(self) -> (SocketAddr, StopHandle, thread::JoinHandle<()>) {
        let (addr, stop) = (self.addr, self.stop_handle());
        (addr, stop, thread::spawn(move || self.run()))
    }
}

/// A JSON error reply for a transport-level refusal (`{"error": {"kind", "message"}}`).
fn status_reply(status: u16, kind: &str, message: &str) -> Reply {
    let mut body = b"{\"error\":{\"kind\":".to_vec();
    crate::io::write_str(&mut body, kind);
    body.extend_from_slice(b",\"message\":");
    crate::io::write_str(&mut body, message);
    body.extend_from_slice(b"}}");
    Reply {
        status,
        content_type: "application/json",
        body,
    }
}

/// One parsed request.
struct Request {
    method: String,
    target: String,
    body: Vec<u8>,
    keep_alive: bool,
    /// `Upgrade: websocket`: the `Sec-WebSocket-Key` and the `Origin` (if any)
    websocket: Option<(String, Option<String>)>,
}

/// The path of the WebSocket endpoint (see [`ws`]).
const WS_PATH: &str = "/api/ws";

/// Whether a WebSocket handshake may proceed: no `Origin` (not a browser) or this server's
/// own page; a page of another site must not drive the API through the user's browser.
fn origin_allowed(origin: Option<&str>, port: u16) -> bool {
    origin.is_none_or(|o| {
        o == format!("http://127.0.0.1:{port}") || o == format!("http://localhost:{port}")
    })
}

/// What reading a request gave.
enum Read1 {
    Request(Request),
    /// refuse with this reply and close the connection
    Refuse(Reply),
    /// the client closed the connection between requests
    Closed,
}

/// Serve one connection: requests in order until the client closes, asks to close, or a
/// request is refused.
fn connection(mut stream: TcpStream, limits: &Limits) -> io::Result<()> {
    stream.set_nodelay(true)?;
    stream.set_read_timeout(Some(IO_TIMEOUT))?;
    stream.set_write_timeout(Some(IO_TIMEOUT))?;
    let mut buf = Vec::with_capacity(4096);
    loop {
        match read_request(&mut stream, &mut buf, limits)? {
            Read1::Closed => return Ok(()),
            Read1::Refuse(reply) => {
                write_reply(&mut stream, &reply, false, false)?;
                linger(&mut stream);
                return Ok(());
            }
            Read1::Request(r) if r.websocket.is_some() && r.target == WS_PATH => {
                let (key, origin) = r.websocket.unwrap_or_default();
                let port = stream.local_addr()?.port();
                if r.method != "GET" || !origin_allowed(origin.as_deref(), port) {
                    let reply = status_reply(
                        403,
                        "forbidden",
                        "a WebSocket to the API is open to this server's own page only",
                    );
                    write_reply(&mut stream, &reply, false, false)?;
                    return Ok(());
                }
                stream.write_all(
                    format!(
                        "HTTP/1.1 101 Switching Protocols\r\nUpgrade: websocket\r\n\
                         Connection: Upgrade\r\nSec-WebSocket-Accept: {}\r\n\r\n",
                        ws::accept_key(&key)
                    )
                    .as_bytes(),
                )?;
                stream.set_read_timeout(Some(WS_IDLE_TIMEOUT))?;
                return ws::serve(&mut stream, std::mem::take(&mut buf), limits);
            }
            Read1::Request(r) => {
                let reply =
                    std::panic::catch_unwind(|| api::handle(&r.method, &r.target, &r.body, limits))
                        .unwrap_or_else(|_| {
                            ApiError::Internal("the request handler failed".into()).reply("")
                        });
                write_reply(&mut stream, &reply, r.keep_alive, r.method == "HEAD")?;
                if !r.keep_alive {
                    return Ok(());
                }
            }
        }
    }
}

/// Read one request from `stream`; `buf` holds bytes already read (pipelining) and keeps what
/// follows this request.
fn read_request(stream: &mut TcpStream, buf: &mut Vec<u8>, limits: &Limits) -> io::Result<Read1> {
    let mut chunk = [0u8; 8192];
    // The head.
    let (head_len, method, target, keep_alive, length, expect_continue, websocket) = loop {
        let mut headers = [httparse::EMPTY_HEADER; MAX_HEADERS];
        let mut req = httparse::Request::new(&mut headers);
        match req.parse(buf) {
            Ok(httparse::Status::Complete(n)) => {
                let header = |name: &str| {
                    req.headers
                        .iter()
                        .find(|h| h.name.eq_ignore_ascii_case(name))
                        .map(|h| String::from_utf8_lossy(h.value).trim().to_string())
                };
                if header("transfer-encoding").is_some() {
                    return Ok(Read1::Refuse(status_reply(
                        411,
                        "length_required",
                        "send the body with a Content-Length header (chunked bodies are not taken)",
                    )));
                }
                let length = match header("content-length").map(|v| v.parse::<u64>()) {
                    None => 0,
                    Some(Ok(l)) => l,
                    Some(Err(_)) => {
                        return Ok(Read1::Refuse(status_reply(
                            400,
                            "bad_request",
                            "the Content-Length header is not a number",
                        )))
                    }
                };
                let conn = header("connection")
                    .unwrap_or_default()
                    .to_ascii_lowercase();
                let keep_alive = req.version == Some(1) && !conn.contains("close");
                let expect =
                    header("expect").is_some_and(|v| v.eq_ignore_ascii_case("100-continue"));
                let websocket = header("upgrade")
                    .filter(|u| u.eq_ignore_ascii_case("websocket"))
                    .and_then(|_| header("sec-websocket-key"))
                    .map(|key| (key, header("origin")));
                break (
                    n,
                    req.method.unwrap_or("").to_string(),
                    req.path.unwrap_or("").to_string(),
                    keep_alive,
                    length,
                    expect,
                    websocket,
                );
            }
            Ok(httparse::Status::Partial) if buf.len() <= MAX_HEAD_BYTES => {}
            Ok(httparse::Status::Partial) => {
                return Ok(Read1::Refuse(status_reply(
                    431,
                    "head_too_large",
                    &format!("the request line and headers exceed {MAX_HEAD_BYTES} bytes"),
                )))
            }
            Err(e) => {
                return Ok(Read1::Refuse(status_reply(
                    400,
                    "bad_request",
                    &format!("malformed HTTP request: {e}"),
                )))
            }
        }
        let n = match stream.read(&mut chunk) {
            Ok(n) => n,
            Err(e) if buf.is_empty() && is_timeout(&e) => return Ok(Read1::Closed),
            Err(e) => return Err(e),
        };
        if n == 0 {
            return Ok(Read1::Closed);
        }
        buf.extend_from_slice(&chunk[..n]);
    };
    // The body: refused from its declared length, before reading or allocating anything.
    if length > limits.max_body_bytes as u64 {
        let e = ApiError::BodyTooLarge {
            got: usize::try_from(length).unwrap_or(usize::MAX),
            limit: limits.max_body_bytes,
        };
        return Ok(Read1::Refuse(e.reply("")));
    }
    let length = length as usize;
    if expect_continue && buf.len() < head_len + length {
        stream.write_all(b"HTTP/1.1 100 Continue\r\n\r\n")?;
    }
    while buf.len() < head_len + length {
        let n = stream.read(&mut chunk)?;
        if n == 0 {
            return Ok(Read1::Closed);
        }
        buf.extend_from_slice(&chunk[..n]);
    }
    let body = buf[head_len..head_len + length].to_vec();
    buf.drain(..head_len + length);
    Ok(Read1::Request(Request {
        method,
        target,
        body,
        keep_alive,
        websocket,
    }))
}

/// Close after a refusal without resetting the connection under the client's feet (which could
/// lose the reply): stop writing, then discard what the client still sends, bounded in bytes
/// and time.
fn linger(stream: &mut TcpStream) {
    let _ = stream.shutdown(Shutdown::Write);
    let _ = stream.set_read_timeout(Some(Duration::from_millis(500)));
    let mut chunk = [0u8; 8192];
    let mut left: usize = 8 << 20;
    while left > 0 {
        match stream.read(&mut chunk) {
            Ok(0) | Err(_) => break,
            Ok(n) => left = left.saturating_sub(n),
        }
    }
}

fn is_timeout(e: &io::Error) -> bool {
    matches!(
        e.kind(),
        io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut
    )
}

fn reason(status: u16) -> &'static str {
    match status {
        200 => "OK",
        204 => "No Content",
        400 => "Bad Request",
        404 => "Not Found",
        405 => "Method Not Allowed",
        403 => "Forbidden",
        411 => "Length Required",
        413 => "Content Too Large",
        431 => "Request Header Fields Too Large",
        503 => "Service Unavailable",
        _ => "Internal Server Error",
    }
}

/// Write a reply in one `write_all` (head and body together: one segment for small replies).
fn write_reply(s: &mut TcpStream, r: &Reply, keep_alive: bool, head_only: bool) -> io::Result<()> {
    let mut out = format!(
        "HTTP/1.1 {} {}\r\nContent-Type: {}\r\nContent-Length: {}\r\nCache-Control: no-store\r\n\
         X-Content-Type-Options: nosniff\r\nConnection: {}\r\n\r\n",
        r.status,
        reason(r.status),
        r.content_type,
        r.body.len(),
        if keep_alive { "keep-alive" } else { "close" }
    )
    .into_bytes();
    if !head_only {
        out.extend_from_slice(&r.body);
    }
    s.write_all(&out)?;
    s.flush()
}
