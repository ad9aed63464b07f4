//! The command line's reference cannot drift from the code: `docs/cli.md`
//! is exactly what `gearshock help-markdown` renders from the clap
//! definitions and `crates/cli/reference/`, every subcommand has its
//! section with worked examples, and the key table of `docs/model.md` is
//! `gearshock keys --markdown`.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::ok;

fn read(path: &str) -> String {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    std::fs::read_to_string(format!("{root}/{path}")).expect(path)
}

/// The first line where two texts differ (1-based), with both versions.
fn first_difference(committed: &str, generated: &str) -> String {
    let (a, b): (Vec<&str>, Vec<&str>) = (committed.lines().collect(), generated.lines().collect());
    let n = a.len().max(b.len());
    (0..n).find(|&i| a.get(i) != b.get(i)).map_or_else(
        || "only in the line endings".to_string(),
        |i| {
            format!(
                "line {}:\n  committed: {}\n  generated: {}",
                i + 1,
                a.get(i).unwrap_or(&"(end of file)"),
                b.get(i).unwrap_or(&"(end of file)")
            )
        },
    )
}

#[test]
fn docs_cli_md_is_what_the_code_generates() {
    let generated = String::from_utf8(ok(&["help-markdown"])).expect("UTF-8");
    let committed = read("docs/cli.md");
    assert!(
        committed == generated,
        "docs/cli.md differs from what the command line generates, first at {}\n\
         Regenerate it with:\n    cargo run -q -p cli -- help-markdown > docs/cli.md",
        first_difference(&committed, &generated)
    );
}

#[test]
fn every_subcommand_has_its_section_with_examples() {
    let help = String::from_utf8(ok(&["--help"])).expect("UTF-8");
    let reference = String::from_utf8(ok(&["help-markdown"])).expect("UTF-8");
    let listed: Vec<&str> = help
        .lines()
        .skip_while(|l| !l.starts_with("Commands:"))
        .skip(1)
        .take_while(|l| l.starts_with("  "))
        .filter_map(|l| l.split_whitespace().next())
        .filter(|name| *name != "help")
        .collect();
    assert!(listed.len() >= 12, "{help}");
    for name in listed {
        let heading = format!("\n## gearshock {name}\n");
        let start = reference
            .find(&heading)
            .unwrap_or_else(|| panic!("no section for {name}"));
        let section = &reference[start + heading.len()..];
        let section = &section[..section.find("\n## ").unwrap_or(section.len())];
        assert!(
            section.contains("```sh\ngearshock "),
            "{name} has no worked example"
        );
    }
    assert!(!reference.contains("No worked example yet."));
}

#[test]
fn the_key_table_of_docs_model_md_is_the_command_lines() {
    let table = String::from_utf8(ok(&["keys", "--markdown"])).expect("UTF-8");
    assert!(
        read("docs/model.md").contains(&table),
        "docs/model.md's key table differs from `gearshock keys --markdown`: \
         replace it with that command's output"
    );
}
