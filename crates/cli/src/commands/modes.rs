//! `gearshock modes`: static equilibrium, mesh forces and natural modes.

use crate::args::{Format, ParamArgs};
use crate::csv;
use crate::failure::Failure;
use crate::output::{emit_text, output};

/// Prints the model's statics and modes.
pub fn run(p: &ParamArgs) -> Result<(), Failure> {
    let (_, model) = p.load()?;
    match p.format {
        Format::Json | Format::Jsonl => {
            output(p.format, &report::modes_json(&model), |_| String::new())
        }
        Format::Csv => emit_text(&csv::modes(&model)),
    }
}
