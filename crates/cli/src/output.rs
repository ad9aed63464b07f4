//! Everything the program prints on stdout: a JSON document, JSON lines
//! (flushed one by one) or text such as CSV.

use crate::args::Format;
use crate::failure::Failure;
use serde_json::Value;
use std::io::Write;

/// Writes a result as JSON, or as the CSV `csv` makes of that JSON.
pub fn output(format: Format, value: &Value, csv: fn(&Value) -> String) -> Result<(), Failure> {
    match format {
        Format::Json => emit(value),
        Format::Jsonl => {
            emit_line(value);
            Ok(())
        }
        Format::Csv => {
            emit_text(&csv(value));
            Ok(())
        }
    }
}

pub fn emit(value: &Value) -> Result<(), Failure> {
    let text = serde_json::to_string_pretty(value).map_err(|e| Failure {
        code: 1,
        message: format!("cannot write JSON: {e}"),
    })?;
    let mut out = std::io::stdout().lock();
    // A closed pipe (e.g. `| head`) is not an error worth reporting.
    let _ = writeln!(out, "{text}");
    Ok(())
}

/// Writes one JSON line and flushes it, so a reader (or a killed job's
/// log) has every line written so far.
pub fn emit_line(value: &Value) {
    let mut out = std::io::stdout().lock();
    let _ = writeln!(out, "{value}");
    let _ = out.flush();
}

pub fn emit_text(text: &str) {
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(text.as_bytes());
}
