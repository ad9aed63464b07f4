//! `gearshock keys`: every parameter key with its unit, range and meaning.

use crate::csv;
use crate::failure::Failure;
use crate::output::emit_text;
use clap::Args;

/// Options of `gearshock keys`.
#[derive(Debug, Args)]
pub struct KeysArgs {
    /// Print a Markdown table (as in docs/model.md).
    #[arg(long)]
    markdown: bool,
}

/// Prints the key table as text or Markdown.
pub fn run(a: &KeysArgs) -> Result<(), Failure> {
    emit_text(&if a.markdown {
        csv::keys_markdown()
    } else {
        csv::keys_text()
    })
}
