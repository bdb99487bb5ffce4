//! Structured bytes -> surface (`robust::surface_from_bytes`) -> every surface strategy, with a
//! containment check against interval evaluations at a grid, the knot lines and decoded
//! parameters.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    nurbs_box::testkit::robust::targets::surface(data);
});
