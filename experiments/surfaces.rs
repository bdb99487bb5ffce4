//! The surface harness binary: runs [`surface_sweep::run`] (see there), writes
//! `results/surfaces.md` and `results/surface_figure.svg` (built with `--features mpfr` also
//! `results/surface_tightness.md`, every strategy against the 256-bit reference), exits
//! non-zero on a containment miss (or, with `mpfr`, a reference miss or a false certificate).
//!
//! `cargo run --release --bin surfaces` (`-- --quick` for a smaller sweep; `-- --bicubic` for
//! the bicubic timing table alone, printed, no file written).

#[allow(dead_code)] // the curve plots are used by reproduce
mod plots;
mod surface_sweep;

fn main() {
    let quick = std::env::args().any(|a| a == "--quick");
    if std::env::args().any(|a| a == "--bicubic") {
        let mut md = String::new();
        surface_sweep::bicubic_table(quick, &mut md);
        print!("{md}");
        return;
    }
    let misses = surface_sweep::run(quick, std::path::Path::new("results"));
    if misses > 0 {
        eprintln!("containment misses: {misses}");
        std::process::exit(1);
    }
}
