//! Shared by the integration tests (`mod common;`).

use proptest::test_runner::Config as ProptestConfig;

/// Proptest configuration with `default_cases` cases unless the `PROPTEST_CASES` environment
/// variable says otherwise (CI sets it; see `.ci/run`).
pub fn config(default_cases: u32) -> ProptestConfig {
    let cases = std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default_cases);
    ProptestConfig {
        cases,
        ..ProptestConfig::default()
    }
}
