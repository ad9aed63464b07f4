//! `gearshock merge`: joins the JSON outputs of all shards of one sweep
//! (bifurcation, map) or of one figure (`--out DIR`), each file read through
//! a size limit.
//!
//! A sweep's or a map's shards are streamed: each file is read one item at
//! a time ([`crate::shards`]), each item checked ([`report::Merge`]) and
//! put in a temporary file (in `TMPDIR`, [`crate::output::Spill`]), and the merged document is
//! written from there in the unsharded run's order, one item at a time.
//! Memory holds one item and an index of the items' places (16 bytes
//! each), never a shard: merging a gigabyte of shards takes a few
//! megabytes. A figure's shards (small: a figure's data) are read whole.

use super::figure;
use crate::failure::{usage, Failure};
use crate::input::{bytes_text, read_json, LimitedFile, MAX_MERGE_BYTES, MAX_SHARD_BYTES};
use crate::output::{emit, Document, Spill};
use crate::shards::{self, Sink};
use clap::Args;
use serde_json::{Map, Value};
use std::path::{Path, PathBuf};

/// Options of `gearshock merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// Shard outputs (JSON files).
    files: Vec<PathBuf>,
    /// Directory for a figure's files (shards of `gearshock figure ID
    /// --shard i/n` only).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
}

/// The size limit for the next file: the per-file limit, or what is left
/// of the total, with its words.
fn limit_for(left: u64) -> (u64, String) {
    if left < MAX_SHARD_BYTES {
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
    }
}

/// Reads the shards, checks them and prints (or, for a figure, writes) the whole.
pub fn run(a: &MergeArgs) -> Result<(), Failure> {
    let files = &a.files;
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
    // Messages name each shard by its file.
    let names: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
    let mut sink = MergeSink {
        names: names.clone(),
        out_given: a.out.is_some(),
        merge: None,
        spill: None,
        k: 0,
        shard: 0,
    };
    let mut left = MAX_MERGE_BYTES;
    for (k, f) in files.iter().enumerate() {
        let (limit, limit_text) = limit_for(left);
        let mut file = LimitedFile::open(f, limit, "merge:", &limit_text)?;
        sink.k = k;
        let read = match shards::read(file.reader(), &["points", "cells"], &mut sink) {
            Ok(r) => r,
            Err(Ok(stopped)) => return Err(stopped),
            Err(Err(e)) => return Err(file.failure(&e)),
        };
        left -= file.read_bytes();
        if read.listed {
            continue;
        }
        if k == 0 && read.head.contains_key("figure_shard") {
            return merge_figure(files, &names, a.out.as_deref());
        }
        return Err(match &mut sink.merge {
            Some(m) => {
                let shard = m.shard(k, &read.head)?;
                m.no_items(k, shard).into()
            }
            None => usage(format!(
                "merge: {}: no `points` or `cells` array: is it gearshock bifurcation, map or figure --shard output?",
                solver::keys::truncate(&names[k], 80)
            )),
        });
    }
    let (Some(merge), Some(spill)) = (sink.merge, sink.spill) else {
        return Err(usage("merge: give the shard JSON files to join"));
    };
    let key = merge.items_key();
    let head = merge.finish()?;
    let mut doc = Document::begin(&head, key)?;
    spill.replay(|v| doc.item(&v))?;
    doc.finish()
}

/// A figure's shards, read whole and merged.
fn merge_figure(files: &[PathBuf], names: &[String], out: Option<&Path>) -> Result<(), Failure> {
    let mut shards = Vec::with_capacity(files.len());
    let mut left = MAX_MERGE_BYTES;
    for f in files {
        let (limit, limit_text) = limit_for(left);
        let (v, read) = read_json(f, limit, "merge:", &limit_text)?;
        left -= read;
        shards.push(v);
    }
    emit(&figure::shard::merge(&shards, names, out)?)
}

/// Takes a streamed shard's items: checks each and puts it aside.
struct MergeSink {
    names: Vec<String>,
    out_given: bool,
    merge: Option<report::Merge>,
    spill: Option<Spill>,
    /// The input being read.
    k: usize,
    /// Its shard number.
    shard: u64,
}

impl Sink for MergeSink {
    fn head(&mut self, key: &str, head: &Map<String, Value>) -> Result<(), Failure> {
        if self.out_given {
            return Err(usage(
                "merge --out: only figure shards (gearshock figure ID --shard i/n) write files",
            ));
        }
        let merge = match &mut self.merge {
            Some(m) => m,
            None => {
                let m = report::Merge::new(head, key, self.names.clone())?;
                self.spill = Some(Spill::new(m.len())?);
                self.merge.insert(m)
            }
        };
        if key != merge.items_key() {
            return Err(usage(format!(
                "merge: {}: has `{key}` where the first file has `{}`: the shards are of one run",
                solver::keys::truncate(&self.names[self.k], 80),
                merge.items_key()
            )));
        }
        self.shard = merge.shard(self.k, head)?;
        Ok(())
    }

    fn item(&mut self, v: Value) -> Result<(), Failure> {
        let (Some(merge), Some(spill)) = (&mut self.merge, &mut self.spill) else {
            return Ok(());
        };
        let place = merge.item(self.k, self.shard, &v)?;
        spill.put(place, &v)
    }
}
