//! `gearshock simulate`: the steady-state response at one Omega, with the
//! chosen mesh's time history and spectrum, and every mesh's dynamic
//! factor beside ISO 6336-1's K_v (method B).

use crate::args::{mesh_index, Format, IsoArgs, ParamArgs, RunArgs};
use crate::csv;
use crate::failure::{usage, Failure};
use crate::output::{emit_text, note, output};
use clap::Args;
use solver::lyapunov::{largest_exponent, LyapunovOptions};
use solver::steady::{steady_state, LyapunovEvidence, Motion, SteadyOptions, LAMBDA_MIN};

/// Options of `gearshock simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    #[command(flatten)]
    p: ParamArgs,
    /// Dimensionless mesh frequency Omega = omega / omega_ref.
    #[arg(long, allow_hyphen_values = true, value_parser = crate::flags::finite)]
    omega: f64,
    #[command(flatten)]
    run: RunArgs,
    /// Mesh to report (e.g. s1a1, s2b2, a1b1, rb3; pg for the gear pair).
    #[arg(long)]
    mesh: Option<String>,
    /// Highest harmonic order in the spectrum.
    #[arg(long, default_value_t = 8.0, allow_hyphen_values = true, value_parser = crate::flags::finite)]
    max_order: f64,
    #[command(flatten)]
    iso: IsoArgs,
}

/// Runs one steady state and prints it.
pub fn run(a: &SimulateArgs) -> Result<(), Failure> {
    let (params, model) = a.p.load()?;
    let j = mesh_index(&model, a.mesh.as_deref())?;
    let iso = a.iso.inputs()?;
    let mut opts = SteadyOptions::new(a.omega);
    a.run.apply(&mut opts);
    // The reported mesh first, then the other planets' meshes of its kind:
    // the force by order sums them.
    let kind = model.system.meshes[j].kind;
    opts.history_meshes = std::iter::once(j)
        .chain(
            (0..model.system.meshes.len())
                .filter(|&i| i != j && model.system.meshes[i].kind == kind),
        )
        .collect();
    let max_order = a.max_order;
    if !(max_order.is_finite() && max_order > 0.0) {
        return Err(usage(format!(
            "--max-order {max_order}: must be a positive number"
        )));
    }
    opts.validate()?;
    let ss = steady_state(&model, &opts, None)?;
    let mut value = report::simulate_json(&model, &ss, j, max_order);
    report::add_iso6336(&mut value, &params, &model, j, ss.mesh_freq_hz, &iso);
    let mut verdict = ss.verdict();
    // Evidence for a motion that is not periodic where the run's own
    // Lyapunov probe did not find chaos: the largest exponent of the
    // Poincaré map, continued from the end state (200 periods, two
    // trajectories: a few times the steady run's own work).
    if matches!(
        ss.motion,
        Motion::NotPeriodic | Motion::StillSettling { .. }
    ) && !ss.lyapunov.is_some_and(|l| l.chaotic)
    {
        verdict = ss.motion.words(ss.stats.transient_periods_run);
        let mut lo = LyapunovOptions::new(a.omega);
        lo.transient_periods = 0;
        match largest_exponent(&model, &lo, Some(&ss.end_state)) {
            Ok(l) => {
                let evidence = LyapunovEvidence {
                    per_period: l.per_period,
                    periods: lo.periods,
                    chaotic: l.per_period >= LAMBDA_MIN,
                };
                verdict = format!("{verdict}; {}", evidence.words());
                value["lyapunov_per_period"] = serde_json::json!(l.per_period);
            }
            Err(e) => verdict = format!("{verdict}; the Lyapunov exponent failed: {e}"),
        }
        value["verdict"] = serde_json::json!(verdict);
    }
    note(&verdict);
    if let Some(n) = &ss.shooting_note {
        note(&format!("note: {n}"));
    }
    match a.p.format {
        Format::Json | Format::Jsonl => output(a.p.format, &value, |_| String::new()),
        Format::Csv => emit_text(&csv::history(&ss, j)),
    }
}
