//! JSON text -> parse (both stream forms) -> every strategy, with a containment check.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    nurbs_box::testkit::robust::targets::json(data);
});
