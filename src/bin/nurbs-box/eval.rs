//! `nurbs-box eval`: verified enclosures of points C(u) and derivatives C^(k)(u), one
//! record per curve and parameter.

use crate::{run_stream, Fatal, InputArgs, Outcome};
use clap::Args;
use nurbs_box::io::batch::input_error_line;
use nurbs_box::io::{eval_fields, write_error_record, write_eval_record};
use nurbs_box::num::iv;
use nurbs_box::TightEval;

#[derive(Args, Debug)]
pub(crate) struct EvalArgs {
    /// Parameter value U (repeatable); must be finite.
    #[arg(long = "param", required = true, allow_negative_numbers = true)]
    params: Vec<f64>,
    /// Derivative order K (0 = the point itself). At most 50: the rational-derivative formula
    /// uses binomial coefficients that must be exact in f64.
    #[arg(long, default_value_t = 0, value_parser = clap::value_parser!(u8).range(0..=50))]
    derivative: u8,
    #[command(flatten)]
    input: InputArgs,
}

pub(crate) fn run(a: EvalArgs) -> Result<Outcome, Fatal> {
    if let Some(u) = a.params.iter().find(|u| !u.is_finite()) {
        return Err(Fatal(format!("--param: expected a finite number, got {u}")));
    }
    let k = usize::from(a.derivative);
    run_stream(&a.input, |index, curve, buf| {
        let c = match curve {
            Ok(c) => c,
            Err(e) => {
                input_error_line(index, &e, buf);
                return false;
            }
        };
        // K = 0: the double-double evaluator gives ~1-ulp boxes (src/tight.rs); built once
        // per curve, only when needed.
        let tight = (k == 0).then(|| TightEval::new(&c));
        let mut ok = true;
        for &u in &a.params {
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
    })
}
