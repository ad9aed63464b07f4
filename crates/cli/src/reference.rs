//! The command line's reference in Markdown, `docs/cli.md`, rendered from
//! clap's command tree so that it cannot drift from the parser: every
//! subcommand with its usage and a table of its arguments and options.
//! Around them go the hand-written parts, kept beside the code in
//! `crates/cli/reference/`: what the commands share (`overview.md`) and
//! each subcommand's worked examples and output (`NAME.md`).
//!
//! `gearshock help-markdown > docs/cli.md` regenerates the file; the test
//! `tests/reference.rs` fails when the committed one differs.

use clap::builder::PossibleValue;
use clap::{Arg, ArgAction, Command, CommandFactory};

/// What every subcommand shares, opening the reference.
const OVERVIEW: &str = include_str!("../reference/overview.md");

/// Each subcommand's worked examples and output, by name.
const NOTES: [(&str, &str); 17] = [
    ("params", include_str!("../reference/params.md")),
    ("keys", include_str!("../reference/keys.md")),
    ("modes", include_str!("../reference/modes.md")),
    ("simulate", include_str!("../reference/simulate.md")),
    ("bifurcation", include_str!("../reference/bifurcation.md")),
    ("frf", include_str!("../reference/frf.md")),
    ("map", include_str!("../reference/map.md")),
    ("boundaries", include_str!("../reference/boundaries.md")),
    ("campbell", include_str!("../reference/campbell.md")),
    ("sharing", include_str!("../reference/sharing.md")),
    ("lyapunov", include_str!("../reference/lyapunov.md")),
    ("instability", include_str!("../reference/instability.md")),
    ("merge", include_str!("../reference/merge.md")),
    ("presets", include_str!("../reference/presets.md")),
    ("figure", include_str!("../reference/figure.md")),
    ("paper", include_str!("../reference/paper.md")),
    ("bench", include_str!("../reference/bench.md")),
];

/// The whole reference, `docs/cli.md`.
pub fn markdown() -> String {
    let mut root = crate::flags::hyphen_values(crate::Cli::command());
    root.build();
    let subcommands: Vec<&Command> = root
        .get_subcommands()
        .filter(|s| !s.is_hide_set() && s.get_name() != "help")
        .collect();
    let mut out = String::from(OVERVIEW.trim_end());
    out.push_str("\n\n## Subcommands\n\n");
    out.push_str("| command | what it does |\n|---|---|\n");
    for s in &subcommands {
        let name = s.get_name();
        out.push_str(&format!(
            "| [`{name}`](#gearshock-{name}) | {} |\n",
            cell(&about(s))
        ));
    }
    for s in subcommands {
        out.push('\n');
        out.push_str(&subcommand(s));
    }
    out
}

/// A subcommand's section: heading, what it does, usage, the table of its
/// arguments and options, then its notes.
fn subcommand(s: &Command) -> String {
    let name = s.get_name();
    let mut out = format!("## gearshock {name}\n\n");
    out.push_str(&sentences(
        &s.get_long_about()
            .or(s.get_about())
            .map(|a| a.to_string())
            .unwrap_or_default(),
    ));
    out.push_str("\n\n```text\n");
    let usage = s.clone().render_usage().to_string();
    out.push_str(usage.trim().trim_start_matches("Usage: "));
    out.push_str("\n```\n\n");
    let args: Vec<&Arg> = s
        .get_arguments()
        .filter(|a| !a.is_hide_set() && !matches!(a.get_id().as_str(), "help" | "version"))
        .collect();
    if !args.is_empty() {
        out.push_str("| argument or option | value | default | meaning |\n|---|---|---|---|\n");
        for a in args {
            out.push_str(&row(a));
        }
        out.push('\n');
    }
    match NOTES.iter().find(|(n, _)| *n == name) {
        Some((_, notes)) => out.push_str(notes.trim_end()),
        None => out.push_str("No worked example yet."),
    }
    out.push('\n');
    out
}

/// One row of an arguments table.
fn row(a: &Arg) -> String {
    let takes_value = a.get_action().takes_values();
    let value_names: Vec<String> = a
        .get_value_names()
        .map(|v| v.iter().map(|s| format!("<{s}>")).collect())
        .unwrap_or_else(|| vec![format!("<{}>", a.get_id().as_str().to_uppercase())]);
    let many = matches!(a.get_action(), ArgAction::Append)
        || a.get_num_args().is_some_and(|n| n.max_values() > 1);
    let name = match a.get_long() {
        Some(long) => match a.get_short() {
            Some(short) => format!("`-{short}`, `--{long}`"),
            None => format!("`--{long}`"),
        },
        None => format!(
            "`{}{}`",
            value_names.join(" "),
            if many { "..." } else { "" }
        ),
    };
    let value = if takes_value && a.get_long().is_some() {
        format!("`{}`", value_names.join(" "))
    } else {
        String::new()
    };
    let default = if takes_value {
        let d: Vec<String> = a
            .get_default_values()
            .iter()
            .map(|v| v.to_string_lossy().into_owned())
            .collect();
        if d.is_empty() {
            String::new()
        } else {
            format!("`{}`", d.join(" "))
        }
    } else {
        String::new()
    };
    let mut meaning = a
        .get_long_help()
        .or(a.get_help())
        .map(|h| sentences(&h.to_string()))
        .unwrap_or_default();
    let possible: Vec<PossibleValue> = a
        .get_possible_values()
        .into_iter()
        .filter(|p| !p.is_hide_set())
        .collect();
    if takes_value && !possible.is_empty() {
        let described = possible.iter().any(|p| p.get_help().is_some());
        let values: Vec<String> = possible
            .iter()
            .map(|p| match (described, p.get_help()) {
                (true, Some(h)) => {
                    let h = sentences(&h.to_string());
                    format!("`{}`: {}", p.get_name(), h.trim_end_matches('.'))
                }
                _ => format!("`{}`", p.get_name()),
            })
            .collect();
        meaning.push_str(if described { " Values: " } else { " One of " });
        meaning.push_str(&values.join(if described { "; " } else { ", " }));
        meaning.push('.');
    }
    if a.is_required_set() {
        meaning.push_str(" Required.");
    }
    if matches!(a.get_action(), ArgAction::Append) && !meaning.contains("repeatable") {
        meaning.push_str(" Repeatable.");
    }
    format!(
        "| {name} | {value} | {default} | {} |\n",
        cell(meaning.trim())
    )
}

/// A subcommand's one-line description.
fn about(s: &Command) -> String {
    s.get_about()
        .map(|a| sentences(&a.to_string()))
        .unwrap_or_default()
}

/// Help text as one line of sentences: paragraphs joined, a full stop at
/// the end.
fn sentences(text: &str) -> String {
    let joined = text.split_whitespace().collect::<Vec<_>>().join(" ");
    if joined.is_empty() || joined.ends_with('.') {
        joined
    } else {
        format!("{joined}.")
    }
}

/// Text for a table cell: `|` escaped.
fn cell(text: &str) -> String {
    text.replace('|', "\\|")
}
