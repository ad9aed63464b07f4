//! `gearshock lyapunov`: the largest Lyapunov exponent of the Poincaré map
//! over a sweep of Omega, each point continued from the last one's end state.

use crate::args::{omega_grid, stream_header, OmegaRange, ParamArgs};
use crate::budget::{check_work, StepCost};
use crate::csv;
use crate::failure::Failure;
use crate::output::output;
use crate::sweep::{self, Lines, Points};
use clap::Args;
use solver::lyapunov::{largest_exponent, LyapunovOptions};

/// Options of `gearshock lyapunov`.
#[derive(Debug, Args)]
pub struct LyapunovArgs {
    #[command(flatten)]
    p: ParamArgs,
    #[command(flatten)]
    range: OmegaRange,
    /// Number of Omega points.
    #[arg(long, default_value_t = 50)]
    points: u32,
    /// Transient mesh periods before measuring.
    #[arg(long, default_value_t = 300)]
    transient_periods: u32,
    /// Mesh periods averaged.
    #[arg(long, default_value_t = 200)]
    periods: u32,
}

/// Checks the options and the budget, computes the exponents and prints them.
pub fn run(a: &LyapunovArgs) -> Result<(), Failure> {
    let (params, model) = a.p.load()?;
    let (points, transient_periods, periods) = (a.points, a.transient_periods, a.periods);
    let (omega_from, omega_to) = a.range.omegas(&model)?;
    let omegas = omega_grid(omega_from, omega_to, points, 10_000)?;
    let mut opts = LyapunovOptions::new(omega_from);
    opts.transient_periods = transient_periods;
    opts.periods = periods;
    // Every option checked before the first point is computed.
    opts.validate()?;
    // The transient once, then two trajectories over the periods.
    check_work(
        u64::from(points) * (u64::from(transient_periods) + 2 * u64::from(periods)),
        StepCost::of(&model).mean_per_period(omega_from, omega_to, points),
        &format!(
            "--points {points} x (--transient-periods {transient_periods} + 2 x --periods {periods})"
        ),
        "fewer points or periods, or split the Omega range",
    )?;
    let lines = Lines {
        header: stream_header(&model, &params, Some(report::lyapunov_spec_json(&opts))),
        line: &report::lyapunov_point_json,
        count: "points",
    };
    let mut state: Option<Vec<f64>> = None;
    let mut last = opts.clone();
    let mut chain = Points::new(omegas, |omega| {
        last.omega = omega;
        let l = largest_exponent(&model, &last, state.as_deref())?;
        state = Some(l.end_state.clone());
        Ok(l)
    });
    let Some(out) = sweep::run(&mut chain, &a.p, "points", Some(lines))? else {
        return Ok(());
    };
    // The spec as the loop left it (at the last Omega), as always written.
    let value = report::lyapunov_json(&model, &params, &last, &out);
    output(a.p.format, &value, csv::lyapunov)
}
