//! `gearshock bifurcation`: Poincaré samples over a sweep of Omega, in
//! interleaved chains, optionally one shard of them.

use crate::args::{meshes, parse_shard, stream_header, Format, OmegaPoints, ParamArgs, RunArgs};
use crate::budget::{check_work, StepCost, MAX_SAMPLES};
use crate::csv;
use crate::failure::{usage, Failure};
use crate::output::{output, Document};
use crate::sweep::{self, Lines};
use clap::Args;
use solver::keys;
use solver::sweep::{canonical_order, BifurcationSweep, Directions, SweepSpec};

/// Options of `gearshock bifurcation`.
#[derive(Debug, Args)]
pub struct BifurcationArgs {
    #[command(flatten)]
    p: ParamArgs,
    #[command(flatten)]
    grid: OmegaPoints,
    /// Sweep direction: up, down or both (up then down).
    #[arg(long, default_value = "up")]
    direction: String,
    #[command(flatten)]
    run: RunArgs,
    /// Mesh to report, or `all`.
    #[arg(long)]
    mesh: Option<String>,
    /// Number of interleaved continuation chains: point i continues from
    /// point i - chains (default 1; the points split across chains run
    /// independently, and merged shards equal the run with as many chains).
    #[arg(long)]
    chains: Option<u32>,
    /// Compute only shard i of n (every n-th point from i; implies --chains n).
    #[arg(long, value_name = "i/n")]
    shard: Option<String>,
}

/// Checks the options and the budget, runs the sweep and prints it.
pub fn run(a: &BifurcationArgs) -> Result<(), Failure> {
    let (params, model) = a.p.load()?;
    let (omega_from, omega_to) = a.grid.range.omegas(&model)?;
    let mut spec = SweepSpec::new(omega_from, omega_to, a.grid.points);
    a.run.apply(&mut spec.steady);
    spec.directions = Directions::from_name(&a.direction).ok_or_else(|| {
        usage(format!(
            "--direction {}: allowed up, down, both",
            keys::truncate(&a.direction, 20)
        ))
    })?;
    spec.meshes = meshes(&model, a.mesh.as_deref())?;
    if let Some(s) = &a.shard {
        let (i, n) = parse_shard(s)?;
        if let Some(c) = a.chains {
            if c != n {
                return Err(usage(format!(
                    "--shard {s} needs --chains {n} (got --chains {c})"
                )));
            }
        }
        spec.chains = n;
        spec.shard = Some(i);
    } else if let Some(c) = a.chains {
        spec.chains = c;
    }
    let mut bifurcation = BifurcationSweep::new(model.clone(), spec.clone())?;
    let total = bifurcation.total() as u64;
    let (transient, record) = (
        u64::from(a.run.transient_periods),
        u64::from(a.run.record_periods),
    );
    check_work(
        total * (transient + record),
        StepCost::of(&model).mean_per_period(spec.omega_from, spec.omega_to, spec.points),
        &format!(
            "{total} runs (--points) x (--transient-periods {transient} + --record-periods {record})"
        ),
        "fewer points or periods, or --shard i/n",
    )?;
    let samples = total * spec.meshes.len() as u64 * record;
    // Streamed points are not kept, so only the work is capped then.
    if samples > MAX_SAMPLES && a.p.format != Format::Jsonl {
        return Err(usage(format!(
            "{total} points x {} meshes (--mesh) x --record-periods {record} = {samples} Poincaré samples, \
             over the {} kept at most: fewer of them, --format jsonl, or --shard i/n",
            spec.meshes.len(),
            MAX_SAMPLES
        )));
    }
    let lines = Lines {
        header: stream_header(
            &model,
            &params,
            Some(report::sweep_spec_json(&model, &spec)),
        ),
        line: &|pt| report::sweep_point_json(&model, pt),
        count: "points",
    };
    let Some(mut pts) = sweep::run(&mut bifurcation, &a.p, "points", Some(lines))? else {
        return Ok(());
    };
    canonical_order(&mut pts);
    if a.p.format == Format::Json {
        // Streamed: each point's JSON is made as it is written, so memory
        // holds the solver's points (a quarter of their text) and one
        // point's JSON, never the document.
        let head = report::sweep_head_json(&model, &params, &spec, &pts);
        let mut doc = Document::begin(&head, "points")?;
        for p in &pts {
            doc.item(&report::sweep_point_json(&model, p))?;
        }
        return doc.finish();
    }
    let value = report::sweep_json(&model, &params, &spec, &pts);
    output(a.p.format, &value, csv::sweep)
}
