//! The module import graph of a crate's source, read as text, and a cycle
//! finder over it: the architecture tests of the solver and the app use it
//! to show that neither has an import cycle.
//!
//! Nodes are modules (`hbm::stability`, `views`, the root is `""`), one per
//! source file below `src/` (recursively; `bin/` and `tests.rs` files, and
//! everything from a `#[cfg(test)]` line on, are test or entry code and
//! left out). An edge `a -> b` is any path in `a` that names `crate::b...`
//! or `super::...` resolving to `b` (the longest module prefix of the path),
//! in `use` statements (braces expanded) and inline alike; comments are
//! skipped, and so are re-exports (`pub use`: a parent naming its child's
//! items for outsiders depends on nothing new). A module and its own
//! submodules are one unit, so edges between ancestor and descendant do not
//! count. [`cycle`] looks for a cycle with modules cut to their first
//! `depth` segments: depth 1 is the top-level modules (a cycle such as
//! `plots -> views -> worker -> plots`), a large depth every file
//! (`hbm::assembly -> hbm::harmonic -> hbm::stability -> hbm::assembly`).

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Modules and their import edges.
#[derive(Debug, Default)]
pub struct Graph {
    /// Every module.
    pub modules: BTreeSet<String>,
    /// `(from, to)`.
    pub edges: BTreeSet<(String, String)>,
}

/// The module path of a source file relative to `src/`.
fn module_of(rel: &str) -> Option<String> {
    let rel = rel.strip_suffix(".rs")?;
    if rel.starts_with("bin/") || rel == "tests" || rel.ends_with("/tests") {
        return None;
    }
    let rel = rel.strip_suffix("/mod").unwrap_or(rel);
    Some(if rel == "lib" || rel == "main" {
        String::new()
    } else {
        rel.replace('/', "::")
    })
}

/// Reads every source file below `src`.
pub fn read(src: &Path) -> Graph {
    let mut files = Vec::new();
    let mut stack = vec![src.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).expect("a source folder") {
            let path = entry.expect("an entry").path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                let rel = path.strip_prefix(src).expect("below src");
                let rel = rel.to_string_lossy().replace('\\', "/");
                files.push((rel, std::fs::read_to_string(&path).expect("readable")));
            }
        }
    }
    let refs: Vec<(&str, &str)> = files
        .iter()
        .map(|(a, b)| (a.as_str(), b.as_str()))
        .collect();
    from_files(&refs)
}

/// The graph of `(path relative to src, text)` pairs.
pub fn from_files(files: &[(&str, &str)]) -> Graph {
    let mut g = Graph::default();
    let mut code = Vec::new();
    for (rel, text) in files {
        if let Some(m) = module_of(rel) {
            g.modules.insert(m.clone());
            code.push((m, strip(text)));
        }
    }
    for (m, text) in &code {
        for path in paths(text) {
            if let Some(to) = resolve(&g.modules, m, &path) {
                if to != *m {
                    g.edges.insert((m.clone(), to));
                }
            }
        }
    }
    g
}

/// The code of a file without comments, re-exports and its test module.
fn strip(text: &str) -> String {
    let mut out = String::new();
    let mut in_reexport = false;
    for line in text.lines() {
        let t = line.trim_start();
        if t.starts_with("#[cfg(test)]") {
            break;
        }
        if t.starts_with("//") {
            continue;
        }
        if t.starts_with("pub use ") || (t.starts_with("pub(") && t.contains(") use ")) {
            in_reexport = !t.contains(';');
            continue;
        }
        if in_reexport {
            in_reexport = !t.contains(';');
            continue;
        }
        let code = line.split(" // ").next().unwrap_or("");
        out.push_str(code);
        out.push('\n');
    }
    out
}

/// Every `crate::`/`super::` path in `text`, as its segments (starting
/// with `crate` or one `super` per level), braces expanded.
fn paths(text: &str) -> Vec<Vec<String>> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let boundary = i == 0
            || !(chars[i - 1].is_alphanumeric() || chars[i - 1] == '_' || chars[i - 1] == ':');
        let rest: String = chars[i..chars.len().min(i + 7)].iter().collect();
        if boundary && (rest.starts_with("crate::") || rest.starts_with("super::")) {
            let (found, end) = parse_path(&chars, i, Vec::new());
            out.extend(found);
            i = end.max(i + 1);
        } else {
            i += 1;
        }
    }
    out
}

/// Parses a path (with `{...}` groups) from `i`; returns the paths and
/// where it ended.
fn parse_path(chars: &[char], mut i: usize, prefix: Vec<String>) -> (Vec<Vec<String>>, usize) {
    let mut segs = prefix;
    loop {
        while chars.get(i).is_some_and(|c| c.is_whitespace()) {
            i += 1;
        }
        if chars.get(i) == Some(&'{') {
            let mut out = Vec::new();
            i += 1;
            loop {
                while chars.get(i).is_some_and(|c| c.is_whitespace() || *c == ',') {
                    i += 1;
                }
                match chars.get(i) {
                    None => return (out, i),
                    Some('}') => return (out, i + 1),
                    _ => {
                        let (found, end) = parse_path(chars, i, segs.clone());
                        out.extend(found);
                        i = end.max(i + 1);
                    }
                }
            }
        }
        let start = i;
        while chars
            .get(i)
            .is_some_and(|c| c.is_alphanumeric() || *c == '_')
        {
            i += 1;
        }
        if i == start {
            return (vec![segs], i);
        }
        segs.push(chars[start..i].iter().collect());
        if chars.get(i) == Some(&':') && chars.get(i + 1) == Some(&':') {
            i += 2;
        } else {
            return (vec![segs], i);
        }
    }
}

/// The module a path in module `from` names: the longest module prefix.
fn resolve(modules: &BTreeSet<String>, from: &str, path: &[String]) -> Option<String> {
    let mut base: Vec<&str> = if from.is_empty() {
        Vec::new()
    } else {
        from.split("::").collect()
    };
    let mut segs = path.iter().map(String::as_str).peekable();
    match segs.peek() {
        Some(&"crate") => {
            segs.next();
            base.clear();
        }
        Some(&"super") => {
            while segs.peek() == Some(&"super") {
                segs.next();
                base.pop()?;
            }
        }
        _ => return None,
    }
    let mut best = base.join("::");
    let mut cur = base.clone();
    for s in segs {
        cur.push(s);
        let name = cur.join("::");
        if modules.contains(&name) {
            best = name;
        } else {
            break;
        }
    }
    Some(best)
}

fn cut(m: &str, depth: usize) -> String {
    m.split("::").take(depth).collect::<Vec<_>>().join("::")
}

fn related(a: &str, b: &str) -> bool {
    a.is_empty()
        || b.is_empty()
        || a == b
        || b.starts_with(&format!("{a}::"))
        || a.starts_with(&format!("{b}::"))
}

/// The edges with modules cut to `depth` segments, ancestor edges dropped.
pub fn edges_at(g: &Graph, depth: usize) -> BTreeSet<(String, String)> {
    g.edges
        .iter()
        .map(|(a, b)| (cut(a, depth), cut(b, depth)))
        .filter(|(a, b)| !related(a, b))
        .collect()
}

/// A cycle among the modules cut to `depth` segments, if there is one.
pub fn cycle(g: &Graph, depth: usize) -> Option<Vec<String>> {
    let mut next: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for (a, b) in edges_at(g, depth) {
        next.entry(a).or_default().push(b);
    }
    // Depth-first search; `on_path` holds the current chain.
    fn visit(
        n: &str,
        next: &BTreeMap<String, Vec<String>>,
        done: &mut BTreeSet<String>,
        on_path: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        if let Some(k) = on_path.iter().position(|m| m == n) {
            let mut c = on_path[k..].to_vec();
            c.push(n.to_string());
            return Some(c);
        }
        if done.contains(n) {
            return None;
        }
        on_path.push(n.to_string());
        for m in next.get(n).into_iter().flatten() {
            if let Some(c) = visit(m, next, done, on_path) {
                return Some(c);
            }
        }
        on_path.pop();
        done.insert(n.to_string());
        None
    }
    let mut done = BTreeSet::new();
    for n in next.keys() {
        if let Some(c) = visit(n, &next, &mut done, &mut Vec::new()) {
            return Some(c);
        }
    }
    None
}
