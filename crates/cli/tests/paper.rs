//! `docs/paper.md` and the page's claims (`crates/app/src/claims.json`)
//! cannot drift from the code: `gearshock paper` runs every command the
//! document quotes (the debug `gearshock`, with the solver optimized; about
//! two minutes on two cores) and prints the record it reads off them;
//! `gearshock paper --record` renders both files from that record, and
//! this test finds them identical to what is committed. A
//! failure names the first line that differs; `gearshock paper --root .`
//! writes both anew.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::Path;
use test_support::cli::{ok, temp_dir};

/// The first line where `rendered` and `committed` differ, with both.
fn first_difference(rendered: &str, committed: &str) -> Option<String> {
    let (a, b): (Vec<&str>, Vec<&str>) = (rendered.lines().collect(), committed.lines().collect());
    (0..a.len().max(b.len()))
        .find(|&i| a.get(i) != b.get(i))
        .map(|i| {
            format!(
                "line {}:\n  rendered:  {}\n  committed: {}",
                i + 1,
                a.get(i).unwrap_or(&"(end)"),
                b.get(i).unwrap_or(&"(end)")
            )
        })
        .or_else(|| (rendered != committed).then(|| "line endings".to_string()))
}

#[test]
fn the_paper_and_the_page_claims_are_rendered_from_the_code() {
    let out = temp_dir("paper");
    // The record, printed; then the files rendered from it.
    let record = out.join("record.json");
    std::fs::write(&record, ok(&["paper"])).unwrap();
    ok(&[
        "paper",
        "--record",
        record.to_str().unwrap(),
        "--root",
        out.to_str().unwrap(),
    ]);
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut stale = Vec::new();
    for file in ["docs/paper.md", "crates/app/src/claims.json"] {
        let rendered = std::fs::read_to_string(out.join(file)).unwrap();
        let committed = std::fs::read_to_string(repo.join(file)).unwrap_or_default();
        if let Some(d) = first_difference(&rendered, &committed) {
            stale.push(format!("{file} differs from the code's, {d}"));
        }
    }
    assert!(
        stale.is_empty(),
        "{}\n(`gearshock paper --root .` renders both anew)",
        stale.join("\n")
    );
}

/// A record that is not one is refused, and nothing is written.
#[test]
fn a_broken_record_is_refused() {
    let out = temp_dir("paper-record");
    let bad = out.join("bad.json");
    std::fs::write(&bad, "{\"transient_periods\": \"many\"}").unwrap();
    let line = test_support::cli::refused(
        &[
            "paper",
            "--record",
            bad.to_str().unwrap(),
            "--root",
            out.to_str().unwrap(),
        ],
        &["--record", "not a record"],
    );
    assert!(!out.join("docs").exists(), "{line}");
}
