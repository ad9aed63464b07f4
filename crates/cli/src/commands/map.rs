//! `gearshock map`: the impact-regime map over Omega (columns) and any
//! numeric key (rows), optionally one shard of its rows.

use crate::args::{
    mesh_index, parse_shard, stream_header, Format, KeyRange, OmegaRange, ParamArgs, RunArgs,
};
use crate::budget::{check_work, StepCost};
use crate::csv;
use crate::failure::Failure;
use crate::output::{output, Document};
use crate::sweep::{self, Lines};
use clap::Args;
use solver::map::{MapSpec, RegimeMap};

/// Options of `gearshock map`.
#[derive(Debug, Args)]
pub struct MapArgs {
    #[command(flatten)]
    p: ParamArgs,
    #[command(flatten)]
    range: OmegaRange,
    /// Number of Omega columns.
    #[arg(long, default_value_t = 100)]
    omega_points: u32,
    #[command(flatten)]
    rows: KeyRange,
    /// Number of rows.
    #[arg(long, default_value_t = 40)]
    value_points: u32,
    #[command(flatten)]
    run: RunArgs,
    /// Mesh whose regime is mapped (default: the worst over all meshes).
    #[arg(long)]
    mesh: Option<String>,
    /// Compute only shard i of n (rows i, i + n, ...).
    #[arg(long, value_name = "i/n")]
    shard: Option<String>,
}

/// Checks the options and the budget, computes the map and prints it.
pub fn run(a: &MapArgs) -> Result<(), Failure> {
    let (params, model) = a.p.load()?;
    let (omega_from, omega_to) = a.range.omegas(&model)?;
    // `+ 0.0` turns a typed -0 into 0, so the echoed spec reads 0.
    let mut spec = MapSpec::new(
        (omega_from, omega_to, a.omega_points),
        &a.rows.key,
        (
            a.rows.value_from + 0.0,
            a.rows.value_to + 0.0,
            a.value_points,
        ),
    );
    a.run.apply(&mut spec.steady);
    spec.mesh = match a.mesh.as_deref() {
        None | Some("worst") => None,
        other => Some(mesh_index(&model, other)?),
    };
    if let Some(s) = &a.shard {
        spec.shard = Some(parse_shard(s)?);
    }
    let mut map = RegimeMap::new(&params, spec.clone())?;
    let total = map.total() as u64;
    let (transient, record) = (a.run.transient_periods, a.run.record_periods);
    // The row key may change the modes (a stiffness, an inertia): the
    // dearer end of its range prices every row.
    let mut cost = StepCost::of(&model);
    for v in [spec.value_from, spec.value_to] {
        let mut row = params.clone();
        if solver::keys::set(&mut row, &spec.key, solver::keys::Value::Num(v)).is_ok() {
            if let Ok(m) = solver::steady::Model::new(&row) {
                cost = cost.max(StepCost::of(&m));
            }
        }
    }
    check_work(
        total * (u64::from(transient) + u64::from(record)),
        cost.mean_per_period(spec.omega_from, spec.omega_to, spec.omega_points),
        &format!("{total} cells x (--transient-periods {transient} + --record-periods {record})"),
        "fewer --omega-points, --value-points or periods, or --shard i/n",
    )?;
    let lines = Lines {
        header: stream_header(&model, &params, Some(report::map_spec_json(&model, &spec))),
        line: &report::map_cell_json,
        count: "cells",
    };
    let Some(cells) = sweep::run(&mut map, &a.p, "cells", Some(lines))? else {
        return Ok(());
    };
    if a.p.format == Format::Json {
        // Streamed, as bifurcation's points are: one cell's JSON at a time.
        let mut doc = Document::begin(&report::map_head_json(&model, &params, &spec), "cells")?;
        for c in &cells {
            doc.item(&report::map_cell_json(c))?;
        }
        return doc.finish();
    }
    let value = report::map_json(&model, &params, &spec, &cells);
    output(a.p.format, &value, csv::map)
}
