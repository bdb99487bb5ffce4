//! Structured bytes -> curve (`robust::curve_from_bytes`) -> every strategy, with a
//! containment check against interval evaluations at sampled parameters.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    nurbs_box::testkit::robust::targets::structured(data);
});
