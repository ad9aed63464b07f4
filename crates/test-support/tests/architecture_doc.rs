//! The documents name only what exists. ARCHITECTURE.md: every path,
//! module, type, function and test it quotes is found in the tree, the
//! rooms of its code maps are files or folders, and every row of its table
//! of invariants names a test that exists. Every relative link of the
//! README, ARCHITECTURE.md, CONTRIBUTING.md, CHANGELOG.md and `docs/`
//! leads to a file, and every path the README quotes exists. Data-driven:
//! the names come from the documents themselves.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use std::path::{Path, PathBuf};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn doc() -> String {
    std::fs::read_to_string(root().join("ARCHITECTURE.md")).expect("ARCHITECTURE.md")
}

/// The crates whose source a name may refer to, as (crate, src folder).
const CRATES: [(&str, &str); 7] = [
    ("solver", "crates/solver/src"),
    ("figures", "crates/figures/src"),
    ("worker", "crates/worker/src"),
    ("app", "crates/app/src"),
    ("cli", "crates/cli/src"),
    ("wasm_bench", "crates/wasm-bench/src"),
    ("fuzz", "crates/fuzz/src"),
];

/// Every `.rs` file below `dir`: (path, text).
fn rust_files(dir: &Path, out: &mut Vec<(PathBuf, String)>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            let text = std::fs::read_to_string(&path).unwrap();
            out.push((path, text));
        }
    }
}

/// The Rust source of the workspace: every crate's `src` and `tests`.
struct Tree {
    /// Every file with its text.
    files: Vec<(PathBuf, String)>,
}

impl Tree {
    fn read() -> Tree {
        let mut files = Vec::new();
        rust_files(&root().join("crates"), &mut files);
        assert!(files.len() > 50, "the walk finds the sources");
        Tree { files }
    }

    /// Whether some file names `name::...` (a crate or module in use).
    fn uses_path(&self, name: &str) -> bool {
        let needle = format!("{name}::");
        self.files.iter().any(|(_, text)| {
            text.match_indices(&needle)
                .any(|(i, _)| !text[..i].ends_with(is_ident_char))
        })
    }

    /// Whether `name` is defined (an item, a variant, a field, a method, a
    /// module file, a re-export) in a file below `under`.
    fn defines(&self, under: &Path, name: &str) -> bool {
        let under = normal(under);
        self.files
            .iter()
            .filter(|(p, _)| normal(p).starts_with(&under))
            .any(|(p, text)| p.file_stem().is_some_and(|s| s == name) || defines_in(text, name))
    }
}

/// A path without `..` or `.` parts (for prefix tests).
fn normal(p: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in p.components() {
        match c {
            std::path::Component::ParentDir => {
                out.pop();
            }
            std::path::Component::CurDir => {}
            c => out.push(c),
        }
    }
    out
}

fn is_ident_char(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// Whether `text` defines `name`: after a keyword (`fn`, `struct`, ...),
/// as an enum variant or field at the start of a line, or in a `use`.
fn defines_in(text: &str, name: &str) -> bool {
    let keywords = [
        "fn ",
        "struct ",
        "enum ",
        "trait ",
        "type ",
        "const ",
        "static ",
        "mod ",
        "macro_rules! ",
    ];
    text.match_indices(name).any(|(i, _)| {
        let before = &text[..i];
        let after = &text[i + name.len()..];
        if before.ends_with(is_ident_char) || after.starts_with(is_ident_char) {
            return false;
        }
        let line_start = before.rfind('\n').map_or(0, |k| k + 1);
        let head = before[line_start..].trim_start();
        let head = head
            .strip_prefix("pub(crate) ")
            .or_else(|| head.strip_prefix("pub(super) "))
            .or_else(|| head.strip_prefix("pub "))
            .unwrap_or(head);
        let rest = after.trim_start();
        keywords.iter().any(|k| head.ends_with(k))
            // A variant or field: the name starts its line.
            || (head.is_empty()
                && (rest.starts_with(':') && !rest.starts_with("::")
                    || rest.starts_with(',')
                    || rest.starts_with('{')
                    || rest.starts_with('(')
                    || rest.is_empty()
                    || rest.starts_with('\n')))
            || head.starts_with("use ")
            || head.starts_with("pub use ")
    })
}

/// The `backticked` spans outside code blocks, joined where a line break
/// cut them (`crates/test-support/` + `src/modgraph.rs`).
fn spans(doc: &str) -> Vec<String> {
    let mut prose = String::new();
    let mut in_code = false;
    for line in doc.lines() {
        if line.starts_with("```") {
            in_code = !in_code;
        } else if !in_code {
            prose.push_str(line);
            prose.push('\n');
        }
    }
    prose
        .split('`')
        .skip(1)
        .step_by(2)
        .map(|s| {
            let mut joined = String::new();
            for part in s.split('\n') {
                let part = part.trim();
                if !(joined.is_empty() || joined.ends_with('/') || joined.ends_with("::")) {
                    joined.push(' ');
                }
                joined.push_str(part);
            }
            joined
        })
        .collect()
}

/// What a span names, if it names something in the tree.
#[derive(Debug, PartialEq)]
enum Name {
    /// A file or folder, from the repository's root or a crate's `src`.
    Path(String),
    /// A Rust path (`views::ViewId`, `Model::divergence_bound_m`) or name.
    Rust(Vec<String>),
}

fn classify(span: &str) -> Option<Name> {
    // Commands, flags, keys with values, link keys, literals: not names.
    if span.contains(' ')
        || span.starts_with('-')
        || span.contains('=')
        || span.starts_with("std::")
        || span.starts_with("//")
        || span.starts_with('#')
        || span.contains('*')
        || span.contains("KEY")
        || span.contains("NAME")
        || span.contains('<')
    {
        return None;
    }
    let looks_like_file = span.contains('/')
        || [
            ".rs", ".md", ".sh", ".mjs", ".toml", ".html", ".txt", ".json", ".py",
        ]
        .iter()
        .any(|e| span.ends_with(e));
    if looks_like_file {
        return Some(Name::Path(span.trim_end_matches('/').to_string()));
    }
    // Cut call arguments and a macro's `!`: `advance(k)`, `println!`.
    let path = span.split('(').next().unwrap().trim_end_matches('!');
    let segments: Vec<String> = path.split("::").map(str::to_string).collect();
    let rusty = segments.iter().all(|s| {
        !s.is_empty()
            && s.chars().all(is_ident_char)
            && !s.starts_with(|c: char| c.is_ascii_digit())
    });
    // One lower-case word with no `_` or `::` is prose (`mod`, `step`) as
    // often as a name: only compound names are checked.
    let plain_word =
        segments.len() == 1 && !path.contains('_') && !path.starts_with(|c: char| c.is_uppercase());
    (rusty && !plain_word).then_some(Name::Rust(segments))
}

/// Where a path in the document can live: from the repository's root, a
/// crate's folder or its `src`, or the end of a source file's path
/// (`harmonic/exact.rs` inside `hbm/`, `harness.mjs` in `tests/browser/`).
fn path_exists(p: &str) -> bool {
    let root = root();
    let bases = std::iter::once(root.clone())
        .chain(CRATES.iter().map(|(_, s)| root.join(s)))
        .chain(CRATES.iter().map(|(_, s)| root.join(s).join("..")));
    if bases
        .flat_map(|b| [b.join(p), b.join(format!("{p}.rs"))])
        .any(|c| c.exists())
    {
        return true;
    }
    let mut all = Vec::new();
    for dir in ["crates", "tests", "scripts", "tools", "web"] {
        walk(&root.join(dir), &mut all);
    }
    all.iter().any(|f| {
        let f = f.to_string_lossy().replace('\\', "/");
        f.ends_with(&format!("/{p}"))
            || f.ends_with(&format!("/{p}.rs"))
            || f.contains(&format!("/{p}/"))
    })
}

/// Every file below `dir` (no `target` or `node_modules`).
fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries {
        let path = entry.unwrap().path();
        let name = path
            .file_name()
            .unwrap_or_default()
            .to_string_lossy()
            .to_string();
        if path.is_dir() && name != "target" && name != "node_modules" {
            walk(&path, out);
        } else if path.is_file() {
            out.push(path);
        }
    }
}

/// Resolves a Rust path: a crate or module prefix to a folder, then each
/// further segment defined below it (methods and variants anywhere in the
/// crate); a name without a module prefix anywhere in the tree.
fn rust_exists(tree: &Tree, segments: &[String]) -> bool {
    let root = root();
    let crates: Vec<(&str, PathBuf)> = CRATES.iter().map(|(c, s)| (*c, root.join(s))).collect();
    let (candidates, rest): (Vec<PathBuf>, &[String]) =
        match crates.iter().find(|(c, _)| *c == segments[0]) {
            Some((_, src)) => (vec![src.clone()], &segments[1..]),
            None => (crates.iter().map(|(_, s)| s.clone()).collect(), segments),
        };
    if rest.is_empty() {
        return true;
    }
    candidates.iter().any(|src| {
        // The longest module prefix that is a file or folder.
        let mut dir = src.clone();
        let mut k = 0;
        while k < rest.len() {
            let next = dir.join(&rest[k]);
            if next.is_dir() || next.with_extension("rs").is_file() {
                dir = next;
                k += 1;
            } else {
                break;
            }
        }
        if k == rest.len() {
            return true;
        }
        // A name without a module: anywhere in the tree (tests too), or a
        // crate or module used as `name::`.
        if k == 0 {
            let crates_dir = root.join("crates");
            return (tree.defines(&crates_dir, &rest[0]) || tree.uses_path(&rest[0]))
                && rest[1..].iter().all(|m| tree.defines(&crates_dir, m));
        }
        // The module's own file and its folder.
        let scope = dir.clone();
        let file = scope.with_extension("rs");
        let first_ok = tree.defines(&scope, &rest[k])
            || (file.is_file() && defines_in(&std::fs::read_to_string(&file).unwrap(), &rest[k]));
        first_ok && rest[k + 1..].iter().all(|m| tree.defines(src, m))
    })
}

#[test]
fn every_name_in_architecture_md_exists() {
    let doc = doc();
    let tree = Tree::read();
    let mut checked = 0;
    let mut missing = Vec::new();
    for span in spans(&doc) {
        let ok = match classify(&span) {
            None => continue,
            Some(Name::Path(p)) => path_exists(&p),
            Some(Name::Rust(s)) => rust_exists(&tree, &s),
        };
        checked += 1;
        if !ok {
            missing.push(span);
        }
    }
    assert!(checked > 100, "only {checked} names checked");
    assert!(
        missing.is_empty(),
        "ARCHITECTURE.md names what does not exist: {missing:?}"
    );
}

/// The rooms of the code maps (the first column of each code block):
/// `crates/solver`, `jobs/`, `web.rs, web/`, `csv.rs, progress.rs`.
#[test]
fn every_room_of_the_code_maps_exists() {
    let doc = doc();
    let mut in_code = false;
    let mut missing = Vec::new();
    let mut checked = 0;
    for line in doc.lines() {
        if line.starts_with("```") {
            in_code = !in_code;
            continue;
        }
        if !in_code || line.starts_with(' ') || line.trim().is_empty() {
            continue;
        }
        // The first column ends at two spaces.
        let column = line.split("  ").next().unwrap().trim();
        for room in column.split(", ") {
            checked += 1;
            if !path_exists(room.trim_end_matches('/')) {
                missing.push(room.to_string());
            }
        }
    }
    assert!(checked > 20, "only {checked} rooms checked");
    assert!(missing.is_empty(), "rooms that do not exist: {missing:?}");
}

/// Every row of the table of invariants names a test that exists: a test
/// file (`crates/*/tests/*.rs`, `tests/browser/*.mjs`) or a test function.
#[test]
fn every_invariant_names_its_test() {
    let doc = doc();
    let tree = Tree::read();
    let test_fns = |name: &str| {
        tree.files.iter().any(|(_, text)| {
            text.match_indices(&format!("fn {name}(")).any(|(i, _)| {
                let before = text[..i].trim_end();
                before.ends_with("#[test]") || before.ends_with(')')
            })
        })
    };
    let start = doc
        .find("\n## Invariants\n")
        .expect("a section of invariants");
    let section = &doc[start + 1..];
    let section = &section[..section[3..].find("\n## ").map_or(section.len(), |i| i + 3)];
    let rows: Vec<&str> = section
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| Architecture invariant |"))
        .collect();
    assert!(rows.len() >= 15, "{} invariants", rows.len());
    for row in rows {
        let cells: Vec<&str> = row.split(" | ").collect();
        assert_eq!(cells.len(), 2, "a row is an invariant and its tests: {row}");
        let tests = spans(cells[1]);
        assert!(!tests.is_empty(), "this invariant names no test:\n{row}");
        for s in tests {
            let is_test_path = s.contains("tests/") && path_exists(s.trim_end_matches('/'));
            assert!(is_test_path || test_fns(&s), "no test {s} for:\n{row}");
        }
    }
}

/// The documents whose links are checked: the root's and `docs/`'s.
fn documents() -> Vec<PathBuf> {
    let root = root();
    let mut out: Vec<PathBuf> = [
        "README.md",
        "ARCHITECTURE.md",
        "CONTRIBUTING.md",
        "CHANGELOG.md",
    ]
    .iter()
    .map(|f| root.join(f))
    .collect();
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .expect("docs/")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    out.extend(docs);
    out
}

/// The targets of a Markdown text's inline links and images, `](target)`,
/// outside code blocks.
fn link_targets(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut in_code = false;
    for line in text.lines() {
        if line.starts_with("```") {
            in_code = !in_code;
            continue;
        }
        if in_code {
            continue;
        }
        for (i, _) in line.match_indices("](") {
            let rest = &line[i + 2..];
            if let Some(end) = rest.find(')') {
                out.push(rest[..end].to_string());
            }
        }
    }
    out
}

#[test]
fn every_docs_link_exists() {
    let mut checked = 0;
    let mut missing = Vec::new();
    for doc in documents() {
        let text = std::fs::read_to_string(&doc).unwrap();
        let dir = doc.parent().unwrap();
        for target in link_targets(&text) {
            if target.contains("://") || target.starts_with('#') || target.starts_with("mailto:") {
                continue;
            }
            let file = target.split('#').next().unwrap();
            checked += 1;
            if !dir.join(file).exists() {
                missing.push(format!("{}: {target}", doc.display()));
            }
        }
    }
    assert!(checked > 20, "only {checked} links checked");
    assert!(missing.is_empty(), "links to nothing: {missing:?}");
}

#[test]
fn every_path_the_readme_names_exists() {
    let root = root();
    let readme = std::fs::read_to_string(root.join("README.md")).expect("README.md");
    let mut checked = 0;
    let mut missing = Vec::new();
    let mut paths: Vec<String> = spans(&readme)
        .into_iter()
        .filter_map(|s| match classify(&s) {
            Some(Name::Path(p)) => Some(p),
            _ => None,
        })
        .collect();
    paths.extend(
        link_targets(&readme)
            .into_iter()
            .filter(|t| !t.contains("://")),
    );
    // Commands in code blocks name scripts and files too.
    let mut in_code = false;
    for line in readme.lines() {
        if line.starts_with("```") {
            in_code = !in_code;
        } else if in_code {
            let words = line.split('#').next().unwrap().split_whitespace();
            paths.extend(
                words
                    .filter(|w| w.starts_with("scripts/") || w.starts_with("docs/"))
                    .map(str::to_string),
            );
        }
    }
    for p in paths {
        checked += 1;
        if !root.join(p.split('#').next().unwrap()).exists() {
            missing.push(p);
        }
    }
    assert!(checked > 20, "only {checked} paths checked");
    assert!(
        missing.is_empty(),
        "the README names what does not exist: {missing:?}"
    );
}
