//! `gearshock sharing`: how the planets share the load over a sweep of
//! speed, in-phase against sequential phasing. Each phasing runs one
//! upward sweep of steady states (`solver::sweep`, every mesh kept); at
//! each speed every planet mesh's largest force and, per mesh kind, the
//! load-sharing factor, the largest over the mean (`solver::sharing`).

use crate::args::{stream_header, OmegaPoints, ParamArgs, RunArgs};
use crate::budget::{check_work, StepCost};
use crate::failure::{usage, Failure};
use crate::output::output;
use crate::sweep;
use clap::Args;
use serde_json::{json, Map, Value};
use solver::keys;
use solver::params::ModelParams;
use solver::sweep::{canonical_order, BifurcationSweep, SweepPoint, SweepSpec};
use solver::Model;

/// Options of `gearshock sharing`.
#[derive(Debug, Args)]
pub struct SharingArgs {
    #[command(flatten)]
    p: ParamArgs,
    #[command(flatten)]
    grid: OmegaPoints,
    #[command(flatten)]
    run: RunArgs,
}

/// The two phasings compared, in the keys' words.
const PHASINGS: [&str; 2] = ["in-phase", "sequential"];

/// Checks the options and the budget, runs both sweeps and prints them.
pub fn run(a: &SharingArgs) -> Result<(), Failure> {
    let (params, model) = a.p.load()?;
    if !matches!(params, ModelParams::Ravigneaux(_)) {
        return Err(usage(
            "sharing: the gear pair has one mesh, no load to share: use the ravigneaux model"
                .to_string(),
        ));
    }
    let (omega_from, omega_to) = a.grid.range.omegas(&model)?;
    let mut spec = SweepSpec::new(omega_from, omega_to, a.grid.points);
    a.run.apply(&mut spec.steady);
    spec.meshes = (0..model.system.meshes.len()).collect();
    let total = u64::from(spec.points) * PHASINGS.len() as u64;
    let periods = u64::from(a.run.transient_periods) + u64::from(a.run.record_periods);
    check_work(
        total * periods,
        StepCost::of(&model).mean_per_period(omega_from, omega_to, spec.points),
        &format!(
            "2 phasings x {} points (--points) x (--transient-periods {} + --record-periods {})",
            spec.points, a.run.transient_periods, a.run.record_periods
        ),
        "fewer points or periods",
    )?;
    let scale = model.system.rpm_scale();
    let mut value = stream_header(
        &model,
        &params,
        Some(report::sweep_spec_json(&model, &spec)),
    );
    if let ModelParams::Ravigneaux(p) = &params {
        value["planets"] = json!(p.planets);
    }
    let mut by_phasing = Map::new();
    for phasing in PHASINGS {
        let mut p = params.clone();
        keys::set_assignment(&mut p, &format!("phasing={phasing}"))?;
        let m = Model::new(&p)?;
        let mut s = BifurcationSweep::new(m.clone(), spec.clone())?;
        let Some(mut pts) = sweep::run(&mut s, &a.p, "points", None)? else {
            return Ok(());
        };
        canonical_order(&mut pts);
        let points: Vec<Value> = pts
            .iter()
            .map(|pt| point_json(&m, pt, scale.rpm(pt.omega)))
            .collect();
        by_phasing.insert(phasing.to_string(), json!({ "points": points }));
    }
    value["phasings"] = Value::Object(by_phasing);
    output(a.p.format, &value, csv)
}

/// One speed's sharing: per mesh kind, each planet's largest mesh force
/// (N) and the factor; the point's error instead where it failed.
fn point_json(model: &Model, pt: &SweepPoint, rpm: f64) -> Value {
    let mut kinds = Map::new();
    if pt.error.is_none() && pt.meshes.len() == model.system.meshes.len() {
        let mut peaks = vec![0.0; model.system.meshes.len()];
        for m in &pt.meshes {
            if let Some(slot) = peaks.get_mut(m.mesh) {
                *slot = m.force_max_n;
            }
        }
        for k in solver::sharing::sharing_of_peaks(&model.system, &peaks) {
            kinds.insert(
                k.kind.key().to_string(),
                json!({ "peak_force_n": k.peak_force_n, "factor": k.factor }),
            );
        }
    }
    json!({
        "omega": pt.omega,
        "input_speed_rpm": rpm,
        "kinds": Value::Object(kinds),
        "error": pt.error,
    })
}

/// One CSV row per phasing, speed and mesh kind.
fn csv(v: &Value) -> String {
    let planets = v["planets"].as_u64().unwrap_or(0);
    let mut out = String::from("phasing,omega,input_speed_rpm,kind,factor");
    for n in 1..=planets {
        out.push_str(&format!(",peak_force_n_planet_{n}"));
    }
    out.push('\n');
    for phasing in PHASINGS {
        for pt in v["phasings"][phasing]["points"]
            .as_array()
            .into_iter()
            .flatten()
        {
            for (kind, k) in pt["kinds"].as_object().into_iter().flatten() {
                out.push_str(&format!(
                    "{phasing},{},{},{kind},{}",
                    pt["omega"], pt["input_speed_rpm"], k["factor"]
                ));
                for f in k["peak_force_n"].as_array().into_iter().flatten() {
                    out.push_str(&format!(",{f}"));
                }
                out.push('\n');
            }
        }
    }
    out
}
