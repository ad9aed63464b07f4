//! `gearshock merge`: joins the JSON outputs of all shards of one sweep
//! (bifurcation, map) or of one figure (`--out DIR`), each file read through
//! a size limit.

use super::figure;
use crate::failure::{usage, Failure};
use crate::input::{bytes_text, read_json, MAX_MERGE_BYTES, MAX_SHARD_BYTES};
use crate::output::emit;
use clap::Args;

/// Options of `gearshock merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// Shard outputs (JSON files).
    files: Vec<std::path::PathBuf>,
    /// Directory for a figure's files (shards of `gearshock figure ID
    /// --shard i/n` only).
    #[arg(long, value_name = "DIR")]
    out: Option<std::path::PathBuf>,
}

/// Reads the shards, checks them and prints (or, for a figure, writes) the whole.
pub fn run(a: &MergeArgs) -> Result<(), Failure> {
    let (files, out) = (&a.files, &a.out);
    if files.is_empty() {
        return Err(usage("merge: give the shard JSON files to join"));
    }
    if files.len() as u64 > report::MAX_SHARDS {
        return Err(usage(format!(
            "merge: {} files given: allowed at most {} shards",
            files.len(),
            report::MAX_SHARDS
        )));
    }
    let mut shards = Vec::new();
    let mut left = MAX_MERGE_BYTES;
    for f in files {
        let (limit, limit_text) = if left < MAX_SHARD_BYTES {
            (
                left,
                format!(
                    "what is left of the {} allowed for all files together",
                    bytes_text(MAX_MERGE_BYTES)
                ),
            )
        } else {
            (
                MAX_SHARD_BYTES,
                format!("the {} allowed per file", bytes_text(MAX_SHARD_BYTES)),
            )
        };
        let (v, read) = read_json(f, limit, "merge:", &limit_text)?;
        left -= read;
        shards.push(v);
    }
    // Messages name each shard by its file.
    let names: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
    if shards
        .first()
        .is_some_and(|v| v.get("figure_shard").is_some())
    {
        emit(&figure::shard::merge(&shards, &names, out.as_deref())?)
    } else if out.is_some() {
        Err(usage(
            "merge --out: only figure shards (gearshock figure ID --shard i/n) write files",
        ))
    } else if shards.first().is_some_and(|v| v.get("cells").is_some()) {
        emit(&report::merge_map_files(&shards, &names)?)
    } else {
        emit(&report::merge_sweep_files(&shards, &names)?)
    }
}
