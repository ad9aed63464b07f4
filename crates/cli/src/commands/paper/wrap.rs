//! Rewrapping the rendered document: the template's paragraphs are
//! wrapped for the template, and the values filled into them change
//! their lengths, so each paragraph and list item is wrapped again.
//! Tables, code blocks and headings stay as they are.

/// The width the document's prose is wrapped to.
pub const WIDTH: usize = 76;

/// Rewraps every paragraph and list item of a Markdown document.
pub fn rewrap(doc: &str) -> String {
    let mut out: Vec<String> = Vec::new();
    let mut block: Vec<&str> = Vec::new();
    let mut fenced = false;
    for line in doc.lines() {
        if line.starts_with("```") {
            flush(&mut block, &mut out);
            fenced = !fenced;
            out.push(line.to_string());
        } else if fenced || verbatim(line) {
            flush(&mut block, &mut out);
            out.push(line.to_string());
        } else if line.starts_with("- ") {
            flush(&mut block, &mut out);
            block.push(line);
        } else {
            block.push(line);
        }
    }
    flush(&mut block, &mut out);
    let mut text = out.join("\n");
    text.push('\n');
    text
}

/// A line kept as it is: blank, a table's row or a heading.
fn verbatim(line: &str) -> bool {
    line.trim().is_empty() || line.starts_with('|') || line.starts_with('#')
}

fn flush(block: &mut Vec<&str>, out: &mut Vec<String>) {
    if block.is_empty() {
        return;
    }
    let (first, rest) = if block[0].starts_with("- ") {
        ("- ", "  ")
    } else {
        ("", "")
    };
    let words: Vec<&str> = block
        .iter()
        .flat_map(|l| l.split_whitespace())
        .skip(usize::from(!first.is_empty()))
        .collect();
    out.extend(fill(&words, first, rest));
    block.clear();
}

/// A word that would change the Markdown at the start of a line (a list
/// item, a heading, a quote, a table): it stays on the line before.
fn risky(word: &str) -> bool {
    matches!(word, "-" | "+" | "*")
        || word.starts_with(['#', '>', '|'])
        || (word.len() > 1
            && word.ends_with(['.', ')'])
            && word[..word.len() - 1].chars().all(|c| c.is_ascii_digit()))
}

fn fill(words: &[&str], first: &str, rest: &str) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = first.to_string();
    let mut empty = true;
    for w in words {
        let fits = line.chars().count() + 1 + w.chars().count() <= WIDTH;
        if empty || fits || risky(w) {
            if !empty {
                line.push(' ');
            }
            line.push_str(w);
        } else {
            lines.push(std::mem::replace(&mut line, format!("{rest}{w}")));
        }
        empty = false;
    }
    lines.push(line);
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wraps_prose_and_keeps_tables_code_and_list_items() {
        let long = "word ".repeat(30);
        let doc =
            format!("# Head\n\n{long}\n\n| a | b |\n|---|---|\n\n```sh\n{long}\n```\n\n- {long}\n");
        let out = rewrap(&doc);
        assert!(out
            .lines()
            .all(|l| l.chars().count() <= WIDTH || l.starts_with("word word")));
        assert!(out.contains("| a | b |\n|---|---|"));
        assert!(out.contains(&format!("```sh\n{long}\n```")));
        assert!(out.contains("\n- word"));
        assert!(out.contains("\n  word"));
        // No line starts with a word that would make it a list item.
        let tricky = format!("{} - x 2. y", "a ".repeat(36));
        assert!(rewrap(&tricky)
            .lines()
            .skip(1)
            .all(|l| !l.starts_with("- ") && !l.starts_with("2. ")));
    }
}
