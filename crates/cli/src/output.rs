//! Every byte the program writes goes through here: stdout (a JSON
//! document, JSON lines flushed one by one, text such as CSV), files
//! (written under a temporary name and renamed once complete) and notes on
//! stderr.
//!
//! Each write to stdout or a file is flushed and checked. A failure (a full
//! disk, `> /dev/full`) is an error naming stdout or the file, with its own
//! exit code [`EXIT_IO`]; a reader that went away (a closed pipe, `| head`)
//! ends the program at the next write with the same code and no message,
//! so a streamed sweep stops computing at once. Notes and progress on
//! stderr are best effort: a failure to show them is no reason to stop.

use crate::args::Format;
use crate::failure::Failure;
use serde_json::Value;
use std::io::{self, Write};
use std::path::Path;

/// The exit code of a failed write (1 is a solver failure, 2 bad input).
pub const EXIT_IO: u8 = 3;

/// The failure of a write to `what` (stdout or a file's path): quiet for a
/// closed pipe, whose reader has gone and wants nothing more.
fn failed(what: &str, e: &io::Error) -> Failure {
    let message = if e.kind() == io::ErrorKind::BrokenPipe {
        String::new()
    } else {
        // "No space left on device", without the "(os error 28)" suffix.
        let text = e.to_string();
        let reason = text.split(" (os error ").next().unwrap_or(&text);
        format!("cannot write {what}: {reason}")
    };
    Failure {
        code: EXIT_IO,
        message,
    }
}

/// Writes `bytes` to stdout and flushes them.
pub fn stdout(bytes: &[u8]) -> Result<(), Failure> {
    let mut out = io::stdout().lock();
    out.write_all(bytes)
        .and_then(|()| out.flush())
        .map_err(|e| failed("stdout", &e))
}

/// Writes a result as JSON, or as the CSV `csv` makes of that JSON.
pub fn output(format: Format, value: &Value, csv: fn(&Value) -> String) -> Result<(), Failure> {
    match format {
        Format::Json => emit(value),
        Format::Jsonl => emit_line(value),
        Format::Csv => emit_text(&csv(value)),
    }
}

/// Writes one pretty-printed JSON document.
pub fn emit(value: &Value) -> Result<(), Failure> {
    let mut text = serde_json::to_string_pretty(value).map_err(|e| Failure {
        code: 1,
        message: format!("cannot write JSON: {e}"),
    })?;
    text.push('\n');
    stdout(text.as_bytes())
}

/// Writes one JSON line and flushes it, so a reader (or a killed job's
/// log) has every line written so far.
pub fn emit_line(value: &Value) -> Result<(), Failure> {
    stdout(format!("{value}\n").as_bytes())
}

/// Writes text (CSV, a table) as it is.
pub fn emit_text(text: &str) -> Result<(), Failure> {
    stdout(text.as_bytes())
}

/// One line on stderr, `gearshock: ` first.
pub fn note(text: &str) {
    let _ = writeln!(io::stderr().lock(), "gearshock: {text}");
}

/// Checks before any work that `dir` (`flag`'s value) can take files:
/// creates it if missing and writes and removes a probe file there.
pub fn check_dir(flag: &str, dir: &Path) -> Result<(), Failure> {
    let refused = |e: io::Error| {
        let text = e.to_string();
        let reason = text
            .split(" (os error ")
            .next()
            .unwrap_or(&text)
            .to_string();
        crate::failure::usage(format!("{flag} {}: {reason}", dir.display()))
    };
    std::fs::create_dir_all(dir).map_err(refused)?;
    let probe = dir.join(format!(".gearshock-probe-{}", std::process::id()));
    std::fs::write(&probe, b"probe").map_err(refused)?;
    std::fs::remove_file(&probe).map_err(refused)
}

/// Writes `files` (name, contents) into `dir`: each under a temporary name,
/// flushed to the disk, then all renamed, so that a failed run leaves no
/// empty or cut file behind (the temporary files are removed).
pub fn write_files(dir: &Path, files: &[(String, String)]) -> Result<(), Failure> {
    let mut temps = Vec::with_capacity(files.len());
    let result = write_then_rename(dir, files, &mut temps);
    if result.is_err() {
        for t in &temps {
            let _ = std::fs::remove_file(t);
        }
    }
    result
}

fn write_then_rename(
    dir: &Path,
    files: &[(String, String)],
    temps: &mut Vec<std::path::PathBuf>,
) -> Result<(), Failure> {
    let shown = |name: &str| dir.join(name).display().to_string();
    for (name, text) in files {
        let temp = dir.join(format!(".{name}.part-{}", std::process::id()));
        temps.push(temp.clone());
        std::fs::File::create(&temp)
            .and_then(|mut f| {
                f.write_all(text.as_bytes())?;
                f.sync_data()
            })
            .map_err(|e| failed(&shown(name), &e))?;
    }
    for ((name, _), temp) in files.iter().zip(temps.iter()) {
        std::fs::rename(temp, dir.join(name)).map_err(|e| failed(&shown(name), &e))?;
    }
    temps.clear();
    Ok(())
}
