//! The repository documents itself:
//!
//! * `src/guarantees.md` has a table row for every strategy of
//!   [`nurbs_box::enclose::STRATEGY_NAMES`], and `docs/formats.md` names every strategy;
//! * the README points to `docs/formats.md` and `docs/sources.md`;
//! * no text file of the repository refers to material outside it: no paths into the
//!   workspace's shared folder, no issue numbers, no source-document file names or line numbers
//!   of those text files. Sources are cited by name instead (`docs/sources.md`).
//!
//! The forbidden patterns are assembled from pieces below, so this file does not contain them.

use nurbs_box::enclose::STRATEGY_NAMES;
use std::path::{Path, PathBuf};

const ROOT: &str = env!("CARGO_MANIFEST_DIR");

fn read(rel: &str) -> String {
    std::fs::read_to_string(Path::new(ROOT).join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

#[test]
fn guarantees_table_has_a_row_for_every_strategy() {
    let text = read("src/guarantees.md");
    let rows: Vec<&str> = text
        .lines()
        .map(str::trim_start)
        .filter(|l| l.starts_with('|'))
        .collect();
    let missing: Vec<&str> = STRATEGY_NAMES
        .iter()
        .copied()
        .filter(|n| {
            let cell = format!("| `{n}` |");
            !rows.iter().any(|r| r.starts_with(&cell))
        })
        .collect();
    assert!(
        missing.is_empty(),
        "src/guarantees.md: no table row `| `name` | ...` for {missing:?}"
    );
}

#[test]
fn formats_names_every_strategy() {
    let text = read("docs/formats.md");
    let missing: Vec<&str> = STRATEGY_NAMES
        .iter()
        .copied()
        .filter(|n| !text.contains(&format!("`{n}`")))
        .collect();
    assert!(
        missing.is_empty(),
        "docs/formats.md does not name the strategies {missing:?}"
    );
}

#[test]
fn readme_points_to_the_docs() {
    let text = read("README.md");
    for doc in ["docs/formats.md", "docs/sources.md"] {
        assert!(
            text.contains(&format!("]({doc}")),
            "README.md: no link to {doc}"
        );
        assert!(Path::new(ROOT).join(doc).is_file(), "{doc} is missing");
    }
}

/// A check on the repository's text files: (description, predicate on one line).
type LineCheck = (String, Box<dyn Fn(&str) -> bool>);

/// What the repository's text files are checked for.
fn forbidden() -> Vec<LineCheck> {
    let shared = ["sha", "red"].concat();
    let literal = |s: String| -> LineCheck {
        let d = format!("{s:?}");
        (d, Box::new(move |l: &str| l.contains(&s)))
    };
    vec![
        literal(format!("../{shared}")),
        literal(format!("{shared}/formats")),
        literal([".t", "xt lines"].concat()),
        (
            format!("{:?} (any case)", ["se", "ed 00"].concat()),
            Box::new(|l: &str| l.to_ascii_lowercase().contains(&["se", "ed 00"].concat())),
        ),
        (
            format!(
                "{:?} followed by a digit (any case)",
                ["iss", "ue "].concat()
            ),
            Box::new(|l: &str| issue_number(l)),
        ),
        (
            "a source-document file name (3 digits, '_', 16 hex digits)".to_string(),
            Box::new(seed_file_name),
        ),
    ]
}

/// The word "issue", a space, maybe `#`, then a digit, in any case.
fn issue_number(line: &str) -> bool {
    let l = line.to_ascii_lowercase();
    let word = ["iss", "ue "].concat();
    l.match_indices(&word).any(|(i, _)| {
        let rest = l[i + word.len()..].trim_start_matches('#');
        rest.starts_with(|c: char| c.is_ascii_digit())
    })
}

/// A token of three digits, `_` and sixteen lowercase hex digits (the source documents' file
/// names).
fn seed_file_name(line: &str) -> bool {
    let b = line.as_bytes();
    (0..(b.len() + 1).saturating_sub(20)).any(|i| {
        (i == 0 || !b[i - 1].is_ascii_alphanumeric())
            && b[i..i + 3].iter().all(u8::is_ascii_digit)
            && b[i + 3] == b'_'
            && b[i + 4..i + 20]
                .iter()
                .all(|c| c.is_ascii_digit() || (b'a'..=b'f').contains(c))
            && b.get(i + 20).is_none_or(|c| !c.is_ascii_alphanumeric())
    })
}

/// Directories and files whose text is checked, relative to the repository root.
const CHECKED: &[&str] = &[
    "src",
    "tests",
    "examples",
    "experiments",
    "benches",
    "fuzz",
    "docs",
    ".ci",
    "README.md",
    "Cargo.toml",
];

/// Never descended into: test data (fonts, licences, fuzz findings), the fuzz corpus, build
/// output and installed packages.
fn skipped(rel: &Path) -> bool {
    let s = rel.to_string_lossy().replace('\\', "/");
    s == "tests/data"
        || s == "fuzz/corpus"
        || rel
            .file_name()
            .is_some_and(|n| n == "node_modules" || n == "target" || n == ".git")
}

fn walk(rel: &Path, out: &mut Vec<PathBuf>) {
    if skipped(rel) {
        return;
    }
    let abs = Path::new(ROOT).join(rel);
    if abs.is_dir() {
        let mut entries: Vec<PathBuf> = std::fs::read_dir(&abs)
            .unwrap_or_else(|e| panic!("{}: {e}", rel.display()))
            .map(|e| rel.join(e.expect("directory entry").file_name()))
            .collect();
        entries.sort();
        for e in entries {
            walk(&e, out);
        }
    } else if abs.is_file() {
        out.push(rel.to_path_buf());
    }
}

/// Every checked text file: (relative path, text). Binary files (a NUL byte, or not UTF-8) are
/// left out.
fn text_files() -> Vec<(PathBuf, String)> {
    let mut files = Vec::new();
    for c in CHECKED {
        walk(Path::new(c), &mut files);
    }
    files
        .into_iter()
        .filter_map(|rel| {
            let bytes = std::fs::read(Path::new(ROOT).join(&rel)).ok()?;
            if bytes.contains(&0) {
                return None;
            }
            String::from_utf8(bytes).ok().map(|t| (rel, t))
        })
        .collect()
}

#[test]
fn no_references_outside_the_repository() {
    let files = text_files();
    assert!(
        files.iter().any(|(p, _)| p.ends_with("src/lib.rs")),
        "the walk found no src/lib.rs; is CARGO_MANIFEST_DIR the repository root?"
    );
    let checks = forbidden();
    let mut hits = Vec::new();
    for (rel, text) in &files {
        for (no, line) in text.lines().enumerate() {
            for (what, hit) in &checks {
                if hit(line) {
                    hits.push(format!(
                        "{}:{}: {what}: {}",
                        rel.display(),
                        no + 1,
                        line.trim()
                    ));
                }
            }
        }
    }
    assert!(
        hits.is_empty(),
        "{} line(s) refer to material outside the repository (cite the source by name, see \
         docs/sources.md, or the format in docs/formats.md):\n{}",
        hits.len(),
        hits.join("\n")
    );
}

#[test]
fn the_checks_recognise_what_they_look_for() {
    let checks = forbidden();
    let caught = |line: &str| checks.iter().any(|(_, hit)| hit(line));
    let shared = ["sha", "red"].concat();
    for bad in [
        format!("see ../{shared}/x"),
        format!("the contract of `{shared}/formats.md`"),
        ["(Iss", "ue 6)"].concat(),
        ["iss", "ue #11"].concat(),
        ["Se", "ed 002, sec. 2.3"].concat(),
        ["000_x.t", "xt lines 1-2"].concat(),
        ["see 004_", "13a322ef30dc9658"].concat(),
    ] {
        assert!(caught(&bad), "not caught: {bad}");
    }
    for good in [
        "thesis sec. 7.1.2, listing `inewtonKNRH`",
        "lab course \"B-Spline-Kurven\", sec. 2.3",
        "the issue is that 3 curves fail",
        "seeds 0..3000",
        "(line 1, column 40)",
        "docs/formats.md",
        "a shared kernel",
    ] {
        assert!(!caught(good), "false positive: {good}");
    }
}
