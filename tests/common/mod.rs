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

/// Run the `nurbs-box` binary with `args`, feeding `stdin` (from another thread: the child may
/// fill its stdout pipe before reading all input); returns (exit code, stdout, stderr) and
/// fails if the binary panicked.
#[allow(dead_code)] // not every test crate runs the binary
pub fn run_bin(args: &[&str], stdin: &[u8]) -> (i32, String, String) {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_nurbs-box"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start nurbs-box");
    let mut sin = child.stdin.take().unwrap();
    let input = stdin.to_vec();
    let writer = std::thread::spawn(move || {
        let _ = sin.write_all(&input);
    });
    let out = child.wait_with_output().unwrap();
    writer.join().unwrap();
    let stdout = String::from_utf8(out.stdout).expect("stdout is UTF-8");
    let stderr = String::from_utf8_lossy(&out.stderr).into_owned();
    assert!(
        !stderr.contains("panicked"),
        "the binary panicked: {stderr}"
    );
    (out.status.code().expect("exit code"), stdout, stderr)
}
