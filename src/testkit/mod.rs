//! Test and experiment tooling (feature `testkit`, enabled for the crate's own tests): seeded
//! generators of nasty curves, curve families, the fuzz decoder and checkers, containment
//! checks, result provenance and (feature `mpfr`) the high-precision reference box.

pub mod families;
pub mod gen;
#[cfg(feature = "mpfr")]
pub mod reference;
pub mod report;
pub mod robust;
pub mod ties;
pub mod validate;
