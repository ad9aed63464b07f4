//! `gearshock params`: the full parameter set (defaults plus `--params` and
//! `--set`) as JSON, JSON lines or CSV.

use crate::args::{Format, ParamArgs};
use crate::csv;
use crate::failure::Failure;
use crate::output::{emit, emit_line, emit_text};
use serde_json::Value;
use solver::keys;

/// Prints the parameter set once the model it builds is valid.
pub fn run(p: &ParamArgs) -> Result<(), Failure> {
    // Building checks cross-field rules (tooth counts, torque balance).
    let (params, _) = p.load()?;
    match p.format {
        Format::Json => emit(&Value::Object(keys::to_json(&params))),
        Format::Jsonl => emit_line(&Value::Object(keys::to_json(&params))),
        Format::Csv => emit_text(&csv::params(&params)),
    }
}
