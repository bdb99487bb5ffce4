//! `nurbs-box enclose`: box enclosures of whole curves, one record per curve and strategy.

use crate::{default_strategy, run_stream, Fatal, InputArgs, Outcome};
use clap::Args;
use nurbs_box::enclose::{strategy_by_name, BoxEncloser, STRATEGY_NAMES};
use nurbs_box::io::batch::{enclose_shape_records, group_for, SurfaceStrategies};
use nurbs_box::surface::{surface_strategy_by_name, SURFACE_STRATEGY_NAMES};

#[derive(Args, Debug)]
pub(crate) struct EncloseArgs {
    /// Strategy name, or `all` for one record per strategy (default: newton if built in,
    /// otherwise the first registered strategy).
    #[arg(long)]
    strategy: Option<String>,
    /// Tolerance of the iterative strategies (finite, > 0; default: each strategy's own).
    #[arg(long, allow_negative_numbers = true)]
    tol: Option<f64>,
    /// Add time_total_s / time_derivatives_s to the stats (makes output non-reproducible).
    #[arg(long)]
    timings: bool,
    #[command(flatten)]
    input: InputArgs,
}

pub(crate) fn run(a: EncloseArgs) -> Result<Outcome, Fatal> {
    if let Some(t) = a.tol {
        if !(t.is_finite() && t > 0.0) {
            return Err(Fatal(format!(
                "--tol: expected a finite number > 0, got {t}"
            )));
        }
    }
    let name = a.strategy.as_deref().unwrap_or_else(|| default_strategy());
    let names: Vec<&str> = if name == "all" {
        STRATEGY_NAMES.to_vec()
    } else {
        vec![name]
    };
    let strategies: Vec<Box<dyn BoxEncloser>> = names
        .iter()
        .map(|n| {
            strategy_by_name(n, a.tol).ok_or_else(|| {
                Fatal(format!(
                    "unknown strategy {n:?}; known strategies: {}, all",
                    STRATEGY_NAMES.join(", ")
                ))
            })
        })
        .collect::<Result<_, _>>()?;
    // surfaces: the surface strategies of the same names (`all`: every surface strategy); a
    // curve-only name gives surfaces an `unsupported_strategy` record
    let surface_names: Vec<&str> = if name == "all" {
        SURFACE_STRATEGY_NAMES.to_vec()
    } else {
        names.clone()
    };
    let surfaces: SurfaceStrategies = surface_names
        .iter()
        .map(|n| {
            surface_strategy_by_name(n, a.tol).ok_or_else(|| {
                strategies
                    .iter()
                    .find(|s| s.name() == *n)
                    .map_or("unknown", |s| s.name())
            })
        })
        .collect();
    let timings = a.timings;
    // the strategies read the clock only when asked (it costs more than a cubic's box)
    nurbs_box::enclose::set_timing(timings);
    // each chunk grouped by kind of curve unless `hull` is the only strategy (`group_for`)
    run_stream(&a.input, group_for(&strategies), |index, shape, buf| {
        enclose_shape_records(index, shape, &strategies, &surfaces, timings, buf)
    })
}
