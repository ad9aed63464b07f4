//! `gearshock paper`: the paper's claims checked against gearshock, from
//! one computed record. It runs the commands that `docs/paper.md` quotes
//! (this binary, once per line, several at once), reads every number the
//! document and the page's claims give off their output ([`record`]), and
//! prints that record as JSON, or renders from it `docs/paper.md` and the
//! page's `crates/app/src/claims.json` ([`render`]), so that no figure in
//! either is typed by hand.
//!
//! Rooms: [`runs`] runs the command lines; [`data`] reads their JSON;
//! [`scale`], [`fig2`], [`fig3`], [`sweeps`], [`orbits`], [`advice`] and
//! [`readings`] each read one part of the record; [`words`] writes numbers
//! as the document does; [`intro`], [`frequency`], [`time`], [`speed`]
//! and [`tables`] turn the record into the named values the texts quote
//! ([`lookup`] finds them), checking the premises their fixed words rest
//! on ([`fill`]); [`render`] fills the document's
//! template (`paper/template.md`) and the claims' texts ([`claims`]), and
//! [`wrap`] wraps its paragraphs again.

mod advice;
mod claims;
mod data;
mod fig2;
mod fig3;
mod fill;
mod frequency;
mod intro;
mod lookup;
mod orbits;
mod readings;
mod record;
mod render;
mod runs;
mod scale;
mod speed;
mod sweeps;
mod tables;
mod time;
mod words;
mod wrap;

use crate::failure::{usage, Failure};
use crate::input::{read_json, MAX_MERGE_BYTES};
use crate::output::{check_dir, emit, write_files};
use clap::Args;
use std::path::{Path, PathBuf};

/// Where the rendered files go, under the repository's root.
pub const DOC: (&str, &str) = ("docs", "paper.md");
/// The page's claims, under the repository's root.
pub const CLAIMS: (&str, &str) = ("crates/app/src", "claims.json");

/// Options of `gearshock paper`.
#[derive(Debug, Args)]
pub struct PaperArgs {
    /// Write docs/paper.md and crates/app/src/claims.json under DIR (the
    /// repository's root) instead of printing the record.
    #[arg(long, value_name = "DIR")]
    root: Option<PathBuf>,
    /// Render from a record printed before (its JSON file) instead of
    /// running the commands.
    #[arg(long, value_name = "FILE")]
    record: Option<PathBuf>,
    /// Commands run at once (default: the machine's cores).
    #[arg(long)]
    jobs: Option<usize>,
    /// A line on stderr as each command finishes.
    #[arg(long)]
    progress: bool,
}

/// Computes (or reads) the record, then prints it or renders the files.
pub fn run(a: &PaperArgs) -> Result<(), Failure> {
    let record = match &a.record {
        Some(path) => {
            let (value, _) = read_json(path, MAX_MERGE_BYTES, "--record", "a record")?;
            serde_json::from_value(value)
                .map_err(|e| usage(format!("--record {}: not a record: {e}", path.display())))?
        }
        None => {
            let jobs = a.jobs.unwrap_or_else(|| {
                std::thread::available_parallelism().map_or(1, std::num::NonZeroUsize::get)
            });
            record::compute(&runs::Runs::new(jobs, a.progress)?)?
        }
    };
    match &a.root {
        None => emit(&serde_json::to_value(&record).map_err(|e| Failure {
            code: 1,
            message: format!("the record is not JSON: {e}"),
        })?),
        Some(root) => {
            let (doc, claims) = render::render(&record)?;
            write(root, DOC, doc)?;
            write(root, CLAIMS, claims)
        }
    }
}

fn write(root: &Path, (dir, name): (&str, &str), text: String) -> Result<(), Failure> {
    let dir = root.join(dir);
    check_dir("--root", &dir)?;
    write_files(&dir, &[(name.to_string(), text)])
}
