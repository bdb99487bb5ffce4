//! `nurbs-box eval`: verified enclosures of points C(u) and derivatives C^(k)(u) of curves,
//! and of S(u, v) and partial derivatives of surfaces, one record per object and parameter.

use crate::{run_stream, Fatal, InputArgs, Outcome};
use clap::Args;
use nurbs_box::io::batch::input_error_line;
use nurbs_box::io::{
    eval_fields, surface_eval_fields, write_error_record, write_eval_record,
    write_surface_eval_record, Shape,
};
use nurbs_box::num::iv;
use nurbs_box::{NurbsCurve, NurbsSurface, TightEval};

#[derive(Args, Debug)]
pub(crate) struct EvalArgs {
    /// Parameter U, or U,V for surfaces (repeatable); finite numbers. A curve uses U.
    #[arg(long = "param", required = true, allow_hyphen_values = true)]
    params: Vec<String>,
    /// Derivative order K, or K,L for surfaces (d^(K+L) S / du^K dv^L; K alone means K,0);
    /// each at most 50 (the rational-derivative formula needs binomials exact in f64). A curve
    /// uses K.
    #[arg(long, default_value = "0")]
    derivative: String,
    #[command(flatten)]
    input: InputArgs,
}

/// "A" or "A,B" as one or two values.
fn pair<T: std::str::FromStr>(s: &str) -> Option<(T, Option<T>)> {
    let mut it = s.split(',').map(str::trim);
    let a = it.next()?.parse().ok()?;
    let b = match it.next() {
        Some(b) => Some(b.parse().ok()?),
        None => None,
    };
    it.next().is_none().then_some((a, b))
}

pub(crate) fn run(a: EvalArgs) -> Result<Outcome, Fatal> {
    let mut params = Vec::with_capacity(a.params.len());
    for p in &a.params {
        match pair::<f64>(p) {
            Some((u, v)) if u.is_finite() && v.is_none_or(f64::is_finite) => params.push((u, v)),
            _ => {
                return Err(Fatal(format!(
                    "--param: expected a finite number U or U,V, got {p}"
                )))
            }
        }
    }
    let (k, l) = match pair::<u8>(&a.derivative) {
        Some((k, l)) if k <= 50 && l.unwrap_or(0) <= 50 => {
            (usize::from(k), usize::from(l.unwrap_or(0)))
        }
        _ => {
            return Err(Fatal(format!(
                "--derivative: expected K or K,L with 0 <= K, L <= 50, got {}",
                a.derivative
            )))
        }
    };
    run_stream(&a.input, false, |index, shape, buf| match shape {
        Ok(Shape::Curve(c)) => eval_curve(index, &c, &params, k, buf),
        Ok(Shape::Surface(s)) => eval_surface(index, &s, &params, (k, l), buf),
        Err(e) => {
            input_error_line(index, &e, buf);
            false
        }
    })
}

fn eval_curve(
    index: usize,
    c: &NurbsCurve,
    params: &[(f64, Option<f64>)],
    k: usize,
    buf: &mut Vec<u8>,
) -> bool {
    // K = 0: the double-double evaluator gives ~1-ulp boxes (src/tight.rs); built once
    // per curve, only when needed.
    let tight = (k == 0).then(|| TightEval::new(c));
    let mut ok = true;
    for &(u, _) in params {
        // Verified: interval de Boor on the exact f64 parameter (eval.rs); it also checks
        // the domain. For K = 0 it is intersected with the TightEval enclosure: both contain
        // the exact value, so their intersection does too.
        match c.enclose_derivative(iv::point(u), k) {
            Ok(mut v) => {
                if let Some(t) = &tight {
                    for (x, y) in v.iter_mut().zip(t.point(u)) {
                        *x = x.intersection(y);
                    }
                }
                write_eval_record(buf, index, u, k, &v)
            }
            Err(e) => {
                ok = false;
                write_error_record(buf, index, &eval_fields(u, k), e.kind(), &e.to_string());
            }
        }
        buf.push(b'\n');
    }
    ok
}

fn eval_surface(
    index: usize,
    s: &NurbsSurface,
    params: &[(f64, Option<f64>)],
    kl: (usize, usize),
    buf: &mut Vec<u8>,
) -> bool {
    let mut ok = true;
    for &(u, v) in params {
        let Some(v) = v else {
            ok = false;
            let msg = format!("param: a surface needs two parameters U,V, got {u}");
            write_error_record(buf, index, &eval_fields(u, kl.0), "missing_param", &msg);
            buf.push(b'\n');
            continue;
        };
        // Verified: interval tensor de Boor at the exact parameters, intersected with the
        // double-double enclosure (NurbsSurface::enclose_derivative).
        match s.enclose_derivative(u, v, kl.0, kl.1) {
            Ok(x) => write_surface_eval_record(buf, index, (u, v), kl, &x),
            Err(e) => {
                ok = false;
                let msg = e.to_string().replace(
                    "the curve's domain",
                    "the surface's domain in this direction",
                );
                write_error_record(buf, index, &surface_eval_fields((u, v), kl), e.kind(), &msg);
            }
        }
        buf.push(b'\n');
    }
    ok
}
