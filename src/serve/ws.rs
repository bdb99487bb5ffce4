//! The API over one WebSocket (RFC 6455), for the page's edits: a browser's `fetch` costs
//! several milliseconds of its own per request, a WebSocket message a fraction of one.
//!
//! Each text message is a request `METHOD TARGET\n` followed by the body (e.g.
//! `POST /api/enclose?strategy=newton\n{"degree": 3, ...}`); it is answered, in order, by one
//! text message `{"status": S, "body": B}` where B is the JSON the same request gets over HTTP
//! ([`super::handle`]). Frames are bounded like HTTP bodies; a larger message closes the socket
//! with status 1009.

use super::api::{handle, Limits};
use std::io::{self, Read, Write};
use std::net::TcpStream;

/// The GUID of the opening handshake (RFC 6455, sec. 1.3).
const GUID: &str = "258EAFA5-E914-47DA-95CA-C5AB0DC85B11";

/// `Sec-WebSocket-Accept` for a `Sec-WebSocket-Key`: base64(SHA-1(key + GUID)).
pub fn accept_key(key: &str) -> String {
    let digest = sha1_smol::Sha1::from(format!("{key}{GUID}"))
        .digest()
        .bytes();
    base64(&digest)
}

fn base64(bytes: &[u8]) -> String {
    const A: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut s = String::new();
    for c in bytes.chunks(3) {
        let n = (u32::from(c[0]) << 16)
            | (u32::from(*c.get(1).unwrap_or(&0)) << 8)
            | u32::from(*c.get(2).unwrap_or(&0));
        for i in 0..4 {
            if i <= c.len() {
                s.push(A[(n >> (18 - 6 * i)) as usize & 63] as char);
            } else {
                s.push('=');
            }
        }
    }
    s
}

/// Serve API requests on an upgraded connection until the client closes it. `pending` holds
/// bytes already read after the handshake.
pub fn serve(stream: &mut TcpStream, mut pending: Vec<u8>, limits: &Limits) -> io::Result<()> {
    // A message: the body limit plus room for the request line.
    let max_message = limits.max_body_bytes + 4096;
    let mut message = Vec::new();
    loop {
        let frame = match read_frame(stream, &mut pending, max_message)? {
            Some(f) => f,
            None => return Ok(()),
        };
        match frame.opcode {
            // text, binary, continuation
            0..=2 => {
                if message.len() + frame.payload.len() > max_message {
                    return close(stream, 1009);
                }
                message.extend_from_slice(&frame.payload);
                if frame.fin {
                    let reply = answer(&message, limits);
                    write_frame(stream, 1, &reply)?;
                    message.clear();
                }
            }
            8 => return close(stream, 1000),
            9 => write_frame(stream, 10, &frame.payload)?,
            10 => {}
            _ => return close(stream, 1002),
        }
    }
}

/// The reply message of one request message.
fn answer(message: &[u8], limits: &Limits) -> Vec<u8> {
    let (head, body) = match message.iter().position(|&b| b == b'\n') {
        Some(i) => (&message[..i], &message[i + 1..]),
        None => (message, &[][..]),
    };
    let head = String::from_utf8_lossy(head);
    let (method, target) = head.trim().split_once(' ').unwrap_or(("", ""));
    let reply = std::panic::catch_unwind(|| {
        if target.starts_with("/api/") {
            handle(method, target.trim(), body, limits)
        } else {
            super::ApiError::NotFound(format!(
                "{target:?} (a message is \"METHOD /api/...\\n\" and a body)"
            ))
            .reply("")
        }
    })
    .unwrap_or_else(|_| super::ApiError::Internal("the request handler failed".into()).reply(""));
    let mut out = format!("{{\"status\":{},\"body\":", reply.status).into_bytes();
    out.extend_from_slice(&reply.body);
    out.push(b'}');
    out
}

struct Frame {
    fin: bool,
    opcode: u8,
    payload: Vec<u8>,
}

/// Fill `pending` to at least `n` bytes; false at the end of the stream.
fn fill(stream: &mut TcpStream, pending: &mut Vec<u8>, n: usize) -> io::Result<bool> {
    let mut chunk = [0u8; 16384];
    while pending.len() < n {
        let k = stream.read(&mut chunk)?;
        if k == 0 {
            return Ok(false);
        }
        pending.extend_from_slice(&chunk[..k]);
    }
    Ok(true)
}

/// Read one frame (unmasked payload); `None` at the end of the stream or for a frame over
/// `max` bytes (after sending close 1009).
fn read_frame(
    stream: &mut TcpStream,
    pending: &mut Vec<u8>,
    max: usize,
) -> io::Result<Option<Frame>> {
    if !fill(stream, pending, 2)? {
        return Ok(None);
    }
    let (b0, b1) = (pending[0], pending[1]);
    let masked = b1 & 0x80 != 0;
    let (len, mut at) = match b1 & 0x7f {
        126 => {
            if !fill(stream, pending, 4)? {
                return Ok(None);
            }
            (u64::from(u16::from_be_bytes([pending[2], pending[3]])), 4)
        }
        127 => {
            if !fill(stream, pending, 10)? {
                return Ok(None);
            }
            let mut b = [0u8; 8];
            b.copy_from_slice(&pending[2..10]);
            (u64::from_be_bytes(b), 10)
        }
        n => (u64::from(n), 2),
    };
    if len > max as u64 {
        close(stream, 1009)?;
        return Ok(None);
    }
    let len = len as usize;
    let mask_len = if masked { 4 } else { 0 };
    if !fill(stream, pending, at + mask_len + len)? {
        return Ok(None);
    }
    let mask = [0, 1, 2, 3].map(|i| if masked { pending[at + i] } else { 0 });
    at += mask_len;
    let payload: Vec<u8> = pending[at..at + len]
        .iter()
        .enumerate()
        .map(|(i, b)| b ^ mask[i % 4])
        .collect();
    pending.drain(..at + len);
    Ok(Some(Frame {
        fin: b0 & 0x80 != 0,
        opcode: b0 & 0x0f,
        payload,
    }))
}

fn write_frame(stream: &mut TcpStream, opcode: u8, payload: &[u8]) -> io::Result<()> {
    let mut out = Vec::with_capacity(payload.len() + 10);
    out.push(0x80 | opcode);
    match payload.len() {
        n if n < 126 => out.push(n as u8),
        n if n <= 0xffff => {
            out.push(126);
            out.extend_from_slice(&(n as u16).to_be_bytes());
        }
        n => {
            out.push(127);
            out.extend_from_slice(&(n as u64).to_be_bytes());
        }
    }
    out.extend_from_slice(payload);
    stream.write_all(&out)?;
    stream.flush()
}

fn close(stream: &mut TcpStream, code: u16) -> io::Result<()> {
    write_frame(stream, 8, &code.to_be_bytes())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn accept_key_of_the_rfc_example() {
        // RFC 6455, sec. 1.3
        assert_eq!(
            accept_key("dGhlIHNhbXBsZSBub25jZQ=="),
            "s3pPLMBiTxaQ9kYGzzhZRbK+xOo="
        );
        assert_eq!(base64(b"ab"), "YWI=");
        assert_eq!(base64(b"a"), "YQ==");
    }
}
