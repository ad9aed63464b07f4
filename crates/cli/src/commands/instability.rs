//! `gearshock instability`: the Floquet spectral radius of the fully
//! engaged linear system over Omega, and its unstable bands.

use crate::args::{omega_grid, stream_header, OmegaPoints, ParamArgs};
use crate::csv;
use crate::failure::Failure;
use crate::output::{note, output};
use crate::sweep::{self, Lines, Points};
use clap::Args;
use solver::parametric::Parametric;

/// Options of `gearshock instability`.
#[derive(Debug, Args)]
pub struct InstabilityArgs {
    #[command(flatten)]
    p: ParamArgs,
    #[command(flatten)]
    grid: OmegaPoints,
}

/// Scans Omega, says the unstable bands on stderr and prints the points.
pub fn run(a: &InstabilityArgs) -> Result<(), Failure> {
    let (params, model) = a.p.load()?;
    let (omega_from, omega_to) = a.grid.range.omegas(&model)?;
    let omegas = omega_grid(omega_from, omega_to, a.grid.points, 100_000)?;
    let engaged = Parametric::new(&model)?;
    let spec = report::instability_spec_json(omega_from, omega_to, a.grid.points);
    let lines = Lines {
        header: stream_header(&model, &params, Some(spec.clone())),
        line: &report::instability_point_json,
        count: "points",
    };
    // Every point is kept for the bands (a few numbers each), streamed or
    // not: the bands said at the end are those of the points written.
    let mut all = Vec::new();
    let kept = {
        let mut scan = Points::new(omegas, |omega| {
            let p = engaged.at(omega)?;
            all.push(p);
            Ok(p)
        });
        sweep::run(&mut scan, &a.p, "points", Some(lines))?
    };
    let bands = report::instability_bands(&all);
    let text: Vec<String> = bands
        .iter()
        .map(|(a, b)| format!("Omega {a:.4} to {b:.4}"))
        .collect();
    note(&format!(
        "unstable bands of the engaged system: {}",
        if text.is_empty() {
            "none in the scanned range".to_string()
        } else {
            text.join(", ")
        }
    ));
    if kept.is_none() {
        return Ok(());
    }
    let value = report::instability_json(&model, &params, spec, &all);
    output(a.p.format, &value, csv::instability)
}
