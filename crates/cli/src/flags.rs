//! Clap's refusals in this program's words: one line naming the flag, its
//! value (cut, control characters escaped) and the range the command
//! really allows (not the range of the integer type that holds it), at
//! most [`MAX_LINE`] characters.

use clap::error::{ContextKind, ContextValue, ErrorKind};

/// Longest line a refusal of the command line takes (characters).
pub const MAX_LINE: usize = 200;

/// The ranges the commands allow for their whole-number flags and for
/// Omega, as their checks word them (a test checks each against the
/// command's own refusal): (subcommand, or `*` for any; flag; range).
pub const RANGES: &[(&str, &str, &str)] = &[
    ("bench", "--repeats", "1 ..= 100"),
    ("bifurcation", "--points", "1 ..= 100000"),
    ("bifurcation", "--chains", "1 ..= points"),
    ("boundaries", "--levels", "2 ..= 50"),
    ("boundaries", "--points", "10 ..= 2000"),
    ("figure", "--points", "2 ..= 2000"),
    ("figure", "--transient-periods", "1 ..= 100000"),
    ("figure", "--record-periods", "1 ..= 10000"),
    ("frf", "--points", "2 ..= 100000"),
    ("frf", "--grid", "4 H + 1 ..= 65536"),
    ("frf", "--period", "1 ..= 32"),
    ("instability", "--points", "2 ..= 100000"),
    ("lyapunov", "--points", "2 ..= 10000"),
    ("lyapunov", "--periods", "1 ..= 100000"),
    ("map", "--omega-points", "2 ..= 2000"),
    ("map", "--value-points", "1 ..= 2000"),
    ("*", "--harmonics", "1 ..= 40"),
    ("*", "--transient-periods", "0 ..= 1000000"),
    ("*", "--record-periods", "1 ..= 100000"),
    ("*", "--omega", "0.01 ..= 20"),
    ("*", "--omega-from", "0.01 ..= 20"),
    ("*", "--omega-to", "0.01 ..= 20"),
];

/// The range `flag` takes in `subcommand`, if it is a whole number's or
/// Omega's.
pub fn range(subcommand: &str, flag: &str) -> Option<&'static str> {
    RANGES
        .iter()
        .find(|(s, f, _)| *s == subcommand && *f == flag)
        .or_else(|| RANGES.iter().find(|(s, f, _)| *s == "*" && *f == flag))
        .map(|(_, _, r)| *r)
}

/// Lets every option's value start with a hyphen (`--shard -1/2`,
/// `--points -inf`, `--points -0`), so that such a value reaches the
/// option's own check and is refused naming the option, instead of being
/// taken for an unknown flag.
pub fn hyphen_values(cmd: clap::Command) -> clap::Command {
    cmd.mut_subcommands(|sub| {
        sub.mut_args(|a| {
            if a.get_long().is_some() && a.get_action().takes_values() {
                a.allow_hyphen_values(true)
            } else {
                a
            }
        })
    })
}

/// Text typed by the user as shown in a message: control characters
/// escaped (`\u{0}`, `\n`), cut to `max` characters.
pub fn shown(text: &str, max: usize) -> String {
    solver::keys::truncate(&escaped(text), max)
}

/// `text` with its control characters escaped.
pub fn escaped(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// The line for a clap refusal of `argv` (the program's arguments).
pub fn message(e: &clap::Error, argv: &[String]) -> String {
    let context = |k: ContextKind| match e.get(k) {
        Some(ContextValue::String(s)) => Some(s.clone()),
        _ => None,
    };
    let subcommand = argv
        .iter()
        .skip(1)
        .find(|a| !a.starts_with('-'))
        .map_or("", String::as_str);
    let worded = match (
        e.kind(),
        context(ContextKind::InvalidArg),
        context(ContextKind::InvalidValue),
    ) {
        (ErrorKind::ValueValidation, Some(arg), Some(value)) => {
            let flag = arg.split_whitespace().next().unwrap_or(&arg).to_string();
            let v = shown(&value, 40);
            let number = value.trim().parse::<f64>().ok();
            let whole = value.trim().parse::<i128>().is_ok();
            let omega = flag.starts_with("--omega") && !flag.ends_with("-points");
            let finite = number.is_some_and(f64::is_finite);
            Some(match range(subcommand, &flag) {
                Some(r) if omega && finite => format!("{flag} {v} is out of range: allowed {r}"),
                Some(r) if omega && number.is_some() => {
                    format!("{flag} {v} is not a finite number: allowed {r}")
                }
                Some(r) if omega => format!("{flag} {v} is not a number: allowed {r}"),
                Some(r) if whole => format!("{flag} {v} is out of range: allowed {r}"),
                Some(r) => format!("{flag} {v} is not a whole number: allowed {r}"),
                None if number.is_some() => format!("{flag} {v} is not a finite number"),
                None => format!("{flag} {v} is not a number"),
            })
        }
        _ => None,
    };
    let line = worded.unwrap_or_else(|| {
        // Clap's own words up to its usage block, joined into one line.
        let text = e.render().to_string();
        let lines: Vec<&str> = text
            .lines()
            .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
            .map(str::trim)
            .filter(|l| !l.is_empty() && !l.starts_with("tip:"))
            .collect();
        lines.join(" ").trim_start_matches("error: ").to_string()
    });
    // Room for the "gearshock: " the note starts with.
    shown(&line, MAX_LINE - "gearshock: ".len() - 1)
}

/// Clap's parser of a number flag: finite numbers only (`NaN` and `inf`
/// are refused naming the flag).
pub fn finite(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err("not a finite number".into()),
        Err(_) => Err("not a number".into()),
    }
}
