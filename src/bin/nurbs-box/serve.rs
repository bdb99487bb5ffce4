//! `nurbs-box serve`: the interactive page and its JSON API on 127.0.0.1.

use crate::{Fatal, Outcome};
use clap::Args;
use std::io;

#[derive(Args, Debug)]
pub(crate) struct ServeArgs {
    /// TCP port (default: a free one; the address is printed on start).
    #[arg(long, default_value_t = 0)]
    port: u16,
}

pub(crate) fn run(a: ServeArgs) -> Result<Outcome, Fatal> {
    use nurbs_box::serve::{Limits, Server};
    use std::io::Write;
    let server = Server::bind(a.port, Limits::default())
        .map_err(|e| Fatal(format!("cannot listen on 127.0.0.1:{}: {e}", a.port)))?;
    let mut out = io::stdout().lock();
    writeln!(out, "nurbs-box serve: {} (Ctrl-C stops it)", server.url())
        .and_then(|()| out.flush())
        .map_err(|e| Fatal(e.to_string()))?;
    drop(out);
    server.run();
    Ok(Outcome::AllOk)
}
