//! Results as JSON, in one format shared by the CLI and the browser app,
//! and the merge of sharded runs ([`merge`]). Kept outside the solver, which
//! computes and never formats.
//!
//! The tooth deflection `x = delta - e` (TE included: the dead zone's
//! argument and the quantity the seed paper plots) is given as `x_*` and
//! `poincare_x_*`; `delta_*` and `poincare_delta_*` are the rotations'
//! part alone, which swings with the TE itself.
//!
//! Field names carry SI units (`_m`, `_hz`, `_n`, `_nm`, `_s`, `_m_s`);
//! dimensionless quantities (`omega`, `dynamic_factor`) carry none. Building
//! JSON values is pure computation; writing them out is the caller's job.

mod boundaries;
mod iso;
mod orbits;
mod orders;
pub use boundaries::boundaries_json;
pub use iso::{add_branch_iso6336, add_iso6336, iso_inputs_json};
pub use orbits::shooting_frf_json;
pub use orders::force_orders_json;

use serde_json::{json, Map, Value};
use solver::error::SolverError;
use solver::keys;
use solver::modal::Mode;
use solver::params::{ModelKind, ModelParams};
use solver::steady::{spectrum, Impact, Model, SteadyState, SteadyStats};
use solver::sweep::{PointMesh, SweepPoint, SweepSpec};

pub mod check;
pub mod merge;
pub use merge::{
    check_sweep, merge_map_files, merge_maps, merge_shards, merge_sweep_files, Merge, MAX_SHARDS,
};

/// `null` for non-finite numbers (JSON has no NaN).
pub fn num(x: f64) -> Value {
    serde_json::Number::from_f64(x).map_or(Value::Null, Value::Number)
}

fn nums(xs: &[f64]) -> Value {
    Value::Array(xs.iter().map(|&x| num(x)).collect())
}

fn per_mesh(model: &Model, values: &[f64]) -> Value {
    let mut m = Map::new();
    for (mesh, &v) in model.system.meshes.iter().zip(values) {
        m.insert(mesh.name.clone(), num(v));
    }
    Value::Object(m)
}

/// A mode shape scaled so its largest entry is +1.
pub fn display_shape(mode: &Mode) -> Vec<f64> {
    let vmax = mode.shape.iter().fold(
        0.0_f64,
        |best, &v| if v.abs() > best.abs() { v } else { best },
    );
    if vmax == 0.0 {
        return mode.shape.clone();
    }
    mode.shape.iter().map(|v| v / vmax).collect()
}

/// `gearshock modes`: statics and natural modes.
pub fn modes_json(model: &Model) -> Value {
    let sys = &model.system;
    let modes: Vec<Value> = model
        .modes
        .modes
        .iter()
        .map(|m| {
            json!({
                "frequency_hz": num(m.frequency_hz),
                "omega": num(m.omega),
                "kind": m.kind.name(),
                "multiplicity": m.multiplicity,
                "damping_ratio": num(m.damping_ratio),
                "shape": nums(&display_shape(m)),
            })
        })
        .collect();
    let balancing_key = match sys.model {
        ModelKind::Ravigneaux => "balancing_torque_s2_nm",
        ModelKind::GearPair => "balancing_torque_gear_nm",
    };
    let u = &sys.rigid_mode;
    let mut ratios = Map::new();
    for (name, &ui) in sys.dof_names.iter().zip(u) {
        ratios.insert(name.clone(), num(ui));
    }
    let eq: Vec<f64> = sys.meshes.iter().map(|m| m.equivalent_mass_kg).collect();
    let damp: Vec<f64> = sys.meshes.iter().map(|m| m.damping_n_s_m).collect();
    json!({
        "model": sys.model.name(),
        "coordinates": sys.dof_names,
        "natural_frequencies_hz": nums(&model.modes.frequencies_hz()),
        "modes": modes,
        "static_mesh_force_n": per_mesh(model, &model.statics.mesh_force_n),
        "static_mesh_deflection_m": per_mesh(model, &model.statics.mesh_deflection_m),
        balancing_key: num(sys.balancing_torque_nm),
        "rigid_body_mode": Value::Object(ratios),
        "equivalent_mass_kg": per_mesh(model, &eq),
        "damping_n_s_m": per_mesh(model, &damp),
        "omega_ref_rad_s": num(sys.omega_ref_rad_s),
        "omega_ref_hz": num(sys.omega_ref_rad_s / (2.0 * std::f64::consts::PI)),
        "warnings": sys.warnings,
    })
}

fn stats_json(s: &SteadyStats) -> Value {
    json!({
        "transient_periods_run": s.transient_periods_run,
        "settled": s.settled,
        "steps": s.integrator.steps,
        "rejected_steps": s.integrator.rejected_steps,
        "event_retakes": s.integrator.event_retakes,
        "rhs_evaluations": s.integrator.rhs_evaluations,
        "contact_switches": s.integrator.events,
        "shooting_attempts": s.shooting_attempts,
        "shooting_steps": s.shooting_steps,
    })
}

/// How the planets share the load over the steady state
/// (`solver::sharing`): per mesh kind, each planet mesh's largest force
/// (N) and the largest over the mean; an empty object for the gear pair.
fn load_sharing_json(
    sys: &solver::system::MeshSystem,
    meshes: &[solver::steady::MeshSteady],
) -> Value {
    let mut out = Map::new();
    for k in solver::sharing::load_sharing(sys, meshes) {
        out.insert(
            k.kind.key().to_string(),
            json!({
                "peak_force_n": k.peak_force_n.iter().map(|f| num(*f)).collect::<Vec<Value>>(),
                "factor": k.factor.map_or(Value::Null, num),
            }),
        );
    }
    Value::Object(out)
}

/// `gearshock simulate`: one steady-state response, focused on mesh `mesh`.
pub fn simulate_json(model: &Model, ss: &SteadyState, mesh: usize, max_order: f64) -> Value {
    let sys = &model.system;
    let m = &ss.meshes[mesh];
    let spec = ss.histories.iter().find(|h| h.mesh == mesh).map(|h| {
        let spp = if ss.sample_times_s.len() > 1 {
            (ss.period_s / (ss.sample_times_s[1] - ss.sample_times_s[0])).round() as u32
        } else {
            0
        };
        let periods = (h.delta_m.len() as u32).checked_div(spp).unwrap_or(0);
        spectrum(&h.delta_m, spp, periods, max_order)
    });
    let mut all = Map::new();
    for (mesh_def, ms) in sys.meshes.iter().zip(&ss.meshes) {
        all.insert(
            mesh_def.name.clone(),
            json!({
                "x_min_m": num(ms.rel_min_m),
                "x_max_m": num(ms.rel_max_m),
                "x_amplitude_m": num(0.5 * (ms.rel_max_m - ms.rel_min_m)),
                "delta_min_m": num(ms.delta_min_m),
                "delta_max_m": num(ms.delta_max_m),
                "impact": ms.impact.name(),
                "dynamic_factor": ms.dynamic_factor.map_or(Value::Null, num),
            }),
        );
    }
    json!({
        "model": sys.model.name(),
        "omega": num(ss.omega),
        "mesh_freq_hz": num(ss.mesh_freq_hz),
        "input_speed_rpm": num(sys.speed.input_speed_rpm(ss.mesh_freq_hz)),
        "mesh": sys.meshes[mesh].name,
        "backlash_m": num(sys.meshes[mesh].backlash_m),
        "x_min_m": num(m.rel_min_m),
        "x_max_m": num(m.rel_max_m),
        "x_amplitude_m": num(0.5 * (m.rel_max_m - m.rel_min_m)),
        "delta_min_m": num(m.delta_min_m),
        "delta_max_m": num(m.delta_max_m),
        "delta_mean_m": num(m.delta_mean_m),
        "delta_rms_m": num(m.delta_rms_m),
        "force_max_n": num(m.force_max_n),
        "force_min_n": num(m.force_min_n),
        "static_force_n": num(m.static_force_n),
        "dynamic_factor": m.dynamic_factor.map_or(Value::Null, num),
        "impact": m.impact.name(),
        "period": ss.period,
        "exact": ss.motion.is_exact(),
        "max_multiplier_modulus": ss.motion.max_multiplier_modulus().map_or(Value::Null, num),
        "motion": ss.motion.name(),
        "verdict": ss.verdict(),
        "shooting_note": ss.shooting_note,
        "lyapunov_per_period": ss.lyapunov.map_or(Value::Null, |l| num(l.per_period)),
        "contact_fraction": {
            "drive": num(m.contact_fraction[0]),
            "apart": num(m.contact_fraction[1]),
            "back": num(m.contact_fraction[2]),
        },
        "poincare": {
            "x_m": nums(&m.poincare_x_m),
            "x_velocity_m_s": nums(&m.poincare_x_velocity_m_s),
            "delta_m": nums(&m.poincare_delta_m),
            "velocity_m_s": nums(&m.poincare_velocity_m_s),
        },
        "spectrum": spec.map_or(Value::Null, |s| json!({
            "order": nums(&s.order),
            "frequency_hz": nums(&s.order.iter().map(|o| o * ss.mesh_freq_hz).collect::<Vec<_>>()),
            "amplitude_m": nums(&s.amplitude),
        })),
        "all_meshes": Value::Object(all),
        "load_sharing": load_sharing_json(sys, &ss.meshes),
        "force_by_order": force_orders_json(model, ss, mesh, max_order),
        "warnings": sys.warnings,
        "stats": stats_json(&ss.stats),
    })
}

/// The sweep specification as JSON (echoed in sweep output, checked by merge).
pub fn sweep_spec_json(model: &Model, spec: &SweepSpec) -> Value {
    let mesh_names: Vec<&str> = spec
        .meshes
        .iter()
        .map(|&j| model.system.meshes[j].name.as_str())
        .collect();
    json!({
        "omega_from": num(spec.omega_from),
        "omega_to": num(spec.omega_to),
        "points": spec.points,
        "direction": spec.directions.name(),
        "transient_periods": spec.steady.transient_periods,
        "record_periods": spec.steady.record_periods,
        "early_settle": spec.steady.early_settle,
        "rtol": num(spec.steady.rtol),
        "atol_m": num(spec.steady.atol_m),
        "meshes": mesh_names,
        "chains": spec.chains,
        "shard": spec.shard.map_or(Value::Null, |s| json!(format!("{s}/{}", spec.chains))),
    })
}

fn point_mesh_json(pm: &PointMesh) -> Map<String, Value> {
    let mut m = Map::new();
    m.insert("poincare_x_m".into(), nums(&pm.poincare_x_m));
    m.insert(
        "poincare_x_velocity_m_s".into(),
        nums(&pm.poincare_x_velocity_m_s),
    );
    m.insert("x_min_m".into(), num(pm.rel_min_m));
    m.insert("x_max_m".into(), num(pm.rel_max_m));
    m.insert(
        "x_amplitude_m".into(),
        num(0.5 * (pm.rel_max_m - pm.rel_min_m)),
    );
    m.insert("poincare_delta_m".into(), nums(&pm.poincare_delta_m));
    m.insert(
        "poincare_velocity_m_s".into(),
        nums(&pm.poincare_velocity_m_s),
    );
    m.insert("delta_min_m".into(), num(pm.delta_min_m));
    m.insert("delta_max_m".into(), num(pm.delta_max_m));
    m.insert("impact".into(), Value::from(pm.impact.name()));
    m.insert(
        "dynamic_factor".into(),
        pm.dynamic_factor.map_or(Value::Null, num),
    );
    m
}

/// One swept point. With one requested mesh its fields are inlined; with
/// several they sit under `meshes` keyed by name.
pub fn sweep_point_json(model: &Model, p: &SweepPoint) -> Value {
    let mut o = Map::new();
    o.insert("omega".into(), num(p.omega));
    o.insert("index".into(), json!(p.index));
    o.insert("direction".into(), json!(p.direction.name()));
    if let Some(e) = &p.error {
        o.insert("error".into(), json!(e));
        return Value::Object(o);
    }
    if p.meshes.len() == 1 {
        o.extend(point_mesh_json(&p.meshes[0]));
    } else {
        let mut ms = Map::new();
        for pm in &p.meshes {
            ms.insert(
                model.system.meshes[pm.mesh].name.clone(),
                Value::Object(point_mesh_json(pm)),
            );
        }
        o.insert("meshes".into(), Value::Object(ms));
    }
    o.insert("impact_worst".into(), json!(p.impact_worst.name()));
    o.insert(
        "worst_mesh".into(),
        json!(model.system.meshes[p.worst_mesh].name),
    );
    o.insert("period".into(), json!(p.period));
    o.insert("exact".into(), json!(p.motion.is_exact()));
    o.insert(
        "max_multiplier_modulus".into(),
        p.motion.max_multiplier_modulus().map_or(Value::Null, num),
    );
    o.insert("motion".into(), json!(p.motion.name()));
    o.insert(
        "lyapunov_per_period".into(),
        p.lyapunov.map_or(Value::Null, |l| num(l.per_period)),
    );
    o.insert("stats".into(), stats_json(&p.stats));
    Value::Object(o)
}

/// Totals of a sweep's work, summed over points (saturating: the sweep's
/// own counters cannot come near `u64::MAX`; merged input is checked by
/// [`merge_shards`] first).
pub fn sweep_stats_json(points: &[Value]) -> Value {
    let mut t = Totals::new(true);
    points.iter().for_each(|p| t.add(p));
    t.finish().unwrap_or(Value::Null)
}

/// A sweep's work totals, summed one point at a time (so that a streamed
/// writer or merge need not hold the points): every whole-number field of
/// each point's `stats`, in the order first seen, then `points` and
/// `failed_points`.
pub struct Totals {
    sums: Vec<(String, u64)>,
    points: u64,
    failed: u64,
    saturate: bool,
    overflowed: bool,
}

impl Totals {
    /// No points yet; with `saturate` false a sum that overflows makes
    /// [`Totals::finish`] return `None`.
    pub fn new(saturate: bool) -> Self {
        Totals {
            sums: Vec::new(),
            points: 0,
            failed: 0,
            saturate,
            overflowed: false,
        }
    }

    /// Adds one point's JSON.
    pub fn add(&mut self, p: &Value) {
        self.points += 1;
        if p.get("error").is_some() {
            self.failed += 1;
        }
        let Some(Value::Object(s)) = p.get("stats") else {
            return;
        };
        for (k, v) in s {
            let Some(x) = v.as_u64() else { continue };
            let i = match self.sums.iter().position(|(name, _)| name == k) {
                Some(i) => i,
                None => {
                    self.sums.push((k.clone(), 0));
                    self.sums.len() - 1
                }
            };
            let slot = &mut self.sums[i].1;
            *slot = if self.saturate {
                slot.saturating_add(x)
            } else if let Some(sum) = slot.checked_add(x) {
                sum
            } else {
                self.overflowed = true;
                *slot
            };
        }
    }

    /// The totals as JSON; `None` if a sum overflowed (not saturating).
    pub fn finish(self) -> Option<Value> {
        if self.overflowed {
            return None;
        }
        let mut totals: Map<String, Value> =
            self.sums.into_iter().map(|(k, v)| (k, json!(v))).collect();
        totals.insert("points".into(), json!(self.points));
        totals.insert("failed_points".into(), json!(self.failed));
        // The order every sweep has written since the start (`remove`
        // moves the last field into the removed one's place).
        totals.remove("transient_periods_run");
        Some(Value::Object(totals))
    }
}

/// The fields of `gearshock bifurcation`'s document before its points
/// (`model`, `params`, `spec`, `stats`): a writer streams the points after
/// them, each made by [`sweep_point_json`] when written, so that the
/// whole document never sits in memory.
pub fn sweep_head_json(
    model: &Model,
    params: &ModelParams,
    spec: &SweepSpec,
    points: &[SweepPoint],
) -> Map<String, Value> {
    let mut totals = Totals::new(true);
    for p in points {
        totals.add(&sweep_point_json(model, p));
    }
    let mut head = Map::new();
    head.insert("model".into(), json!(model.system.model.name()));
    head.insert("params".into(), Value::Object(keys::to_json(params)));
    head.insert("spec".into(), sweep_spec_json(model, spec));
    head.insert("stats".into(), totals.finish().unwrap_or(Value::Null));
    head
}

/// `gearshock bifurcation`: the whole result.
pub fn sweep_json(
    model: &Model,
    params: &ModelParams,
    spec: &SweepSpec,
    points: &[SweepPoint],
) -> Value {
    let mut head = sweep_head_json(model, params, spec, points);
    let pts: Vec<Value> = points.iter().map(|p| sweep_point_json(model, p)).collect();
    head.insert("points".into(), Value::Array(pts));
    Value::Object(head)
}

/// Parses an impact name in JSON (for readers of sweep output).
pub fn impact_of(v: &Value) -> Option<Impact> {
    v.as_str().and_then(Impact::from_name)
}

/// The options of a harmonic-balance frequency response as JSON.
pub fn frf_spec_json(spec: &solver::hbm::FrfSpec, grid: usize) -> Value {
    json!({
        "omega_from": num(spec.omega_from),
        "omega_to": num(spec.omega_to),
        "points": spec.points,
        "direction": spec.direction.name(),
        "harmonics": spec.harmonics,
        "method": spec.method.name(),
        "grid": grid,
        "stability": spec.stability,
        "stability_stride": spec.stability_stride,
        "symmetric": spec.symmetric,
    })
}

fn branch_mesh_json(m: &solver::hbm::BranchMesh) -> Map<String, Value> {
    let mut o = Map::new();
    o.insert("x_max_m".into(), num(m.rel_max_m));
    o.insert("x_min_m".into(), num(m.rel_min_m));
    o.insert(
        "x_amplitude_m".into(),
        num(0.5 * (m.rel_max_m - m.rel_min_m)),
    );
    o.insert("delta_max_m".into(), num(m.delta_max_m));
    o.insert("delta_min_m".into(), num(m.delta_min_m));
    o.insert("delta_amplitude_m".into(), num(m.delta_amplitude_m));
    o.insert("harmonics_m".into(), nums(&m.harmonics_m));
    o.insert("impact".into(), Value::from(m.impact.name()));
    o
}

/// One branch point. With one requested mesh its fields are inlined; with
/// several they sit under `meshes` keyed by name. `x_*` is the tooth
/// deflection `x = delta - e` (TE included), `delta_*` the rotations'
/// part.
pub fn branch_point_json(model: &Model, p: &solver::hbm::BranchPoint, meshes: &[usize]) -> Value {
    let mut o = Map::new();
    o.insert("omega".into(), num(p.omega));
    if let [j] = meshes {
        if let Some(m) = p.meshes.get(*j) {
            o.extend(branch_mesh_json(m));
        }
    } else {
        let mut all = Map::new();
        for &j in meshes {
            if let (Some(mesh), Some(m)) = (model.system.meshes.get(j), p.meshes.get(j)) {
                all.insert(mesh.name.clone(), Value::Object(branch_mesh_json(m)));
            }
        }
        o.insert("meshes".into(), Value::Object(all));
    }
    o.insert("stable".into(), p.stable.map_or(Value::Null, Value::from));
    // A sampled stability route leaves some points without a monodromy:
    // their flag is their neighbours'.
    let from = match (p.stable, p.multipliers.is_empty()) {
        (None, _) => Value::Null,
        (Some(_), false) => Value::from("monodromy"),
        (Some(_), true) => Value::from("neighbours"),
    };
    o.insert("stability_from".into(), from);
    o.insert(
        "bifurcation".into(),
        p.bifurcation.map_or(Value::Null, |b| Value::from(b.name())),
    );
    let radius = p.multipliers.iter().map(|z| z.norm()).fold(0.0, f64::max);
    o.insert(
        "max_multiplier_modulus".into(),
        if p.multipliers.is_empty() {
            Value::Null
        } else {
            num(radius)
        },
    );
    o.insert("newton_iterations".into(), json!(p.newton_iterations));
    o.insert("piece".into(), json!(p.piece));
    Value::Object(o)
}

/// The names of the meshes `meshes` (indices into the model's meshes), as
/// a frequency response's JSON lists them.
pub(crate) fn mesh_names<'a>(model: &'a Model, meshes: &[usize]) -> Vec<&'a str> {
    meshes
        .iter()
        .filter_map(|&j| model.system.meshes.get(j).map(|m| m.name.as_str()))
        .collect()
}

/// A whole frequency response: spec, branch, work counters and, when the
/// continuation failed part-way, the error (the branch is then partial).
pub fn frf_json(
    model: &Model,
    params: &ModelParams,
    continuation: &solver::hbm::FrfContinuation,
    branch: &[solver::hbm::BranchPoint],
    meshes: &[usize],
    error: Option<&SolverError>,
) -> Value {
    let names = mesh_names(model, meshes);
    let s = continuation.stats;
    json!({
        "model": model.system.model.name(),
        "params": Value::Object(keys::to_json(params)),
        "omega_ref_rad_s": num(model.system.omega_ref_rad_s),
        "spec": frf_spec_json(continuation.spec(), continuation.assembly().grid.n),
        "meshes": names,
        "complete": error.is_none(),
        "left_range_at_start": continuation.left_at_start(),
        "restarts": continuation.restarts().iter().map(|r| json!({
            "piece": r.piece,
            "reason": r.reason.name(),
            "stopped_at_omega": num(r.stopped_at),
            "start_omega": num(r.start_omega),
            "direction": r.direction.name(),
        })).collect::<Vec<_>>(),
        "left_out": continuation.left_out().iter().map(|l| json!({
            "omega_from": num(l.from),
            "omega_to": num(l.to),
            "reason": l.reason_name(),
        })).collect::<Vec<_>>(),
        "notes": continuation.notes(),
        "error": error.map_or(Value::Null, |e| Value::from(e.to_string())),
        "branch": branch.iter().map(|p| branch_point_json(model, p, meshes)).collect::<Vec<_>>(),
        "stats": {
            "points": s.points,
            "newton_iterations": s.newton_iterations,
            "rejected_steps": s.rejected_steps,
            "jacobian_evaluations": s.jacobians,
        },
    })
}

/// The specification of a regime map as JSON (checked by merge).
pub fn map_spec_json(model: &Model, spec: &solver::map::MapSpec) -> Value {
    json!({
        "omega_from": num(spec.omega_from),
        "omega_to": num(spec.omega_to),
        "omega_points": spec.omega_points,
        "key": spec.key,
        "value_from": num(spec.value_from),
        "value_to": num(spec.value_to),
        "value_points": spec.value_points,
        "transient_periods": spec.steady.transient_periods,
        "record_periods": spec.steady.record_periods,
        "early_settle": spec.steady.early_settle,
        "mesh": spec.mesh.and_then(|j| model.system.meshes.get(j)).map_or(Value::from("worst"), |m| Value::from(m.name.clone())),
        "shards": spec.shard.map_or(1, |(_, n)| n),
        "shard": spec.shard.map_or(Value::Null, |(i, n)| json!(format!("{i}/{n}"))),
    })
}

/// A map cell as JSON.
pub fn map_cell_json(c: &solver::map::MapCell) -> Value {
    json!({
        "row": c.row,
        "column": c.column,
        "omega": num(c.omega),
        "value": num(c.value),
        "impact": if c.error.is_some() { Value::Null } else { Value::from(c.impact.name()) },
        "period": c.period,
        "exact": c.motion.is_exact(),
        "max_multiplier_modulus": c.motion.max_multiplier_modulus().map_or(Value::Null, num),
        "motion": c.motion.name(),
        "lyapunov_per_period": c.lyapunov.map_or(Value::Null, |l| num(l.per_period)),
        "error": c.error,
    })
}

/// A whole regime map (or one shard of it).
pub fn map_json(
    model: &Model,
    params: &ModelParams,
    spec: &solver::map::MapSpec,
    cells: &[solver::map::MapCell],
) -> Value {
    let mut head = map_head_json(model, params, spec);
    head.insert(
        "cells".into(),
        cells.iter().map(map_cell_json).collect::<Vec<_>>().into(),
    );
    Value::Object(head)
}

/// The fields of a regime map's document before its cells (`model`,
/// `params`, `spec`), for a writer that streams the cells.
pub fn map_head_json(
    model: &Model,
    params: &ModelParams,
    spec: &solver::map::MapSpec,
) -> Map<String, Value> {
    let mut head = Map::new();
    head.insert("model".into(), json!(model.system.model.name()));
    head.insert("params".into(), Value::Object(keys::to_json(params)));
    head.insert("spec".into(), map_spec_json(model, spec));
    head
}

/// A parametric-instability scan: the engaged system's Floquet spectral
/// radius per Omega, its logarithm (growth of large motion per mesh period)
/// and whether it exceeds 1; then the unstable bands
/// ([`solver::parametric::unstable_bands`] of the points, ascending Omega).
pub fn instability_json(
    model: &Model,
    params: &ModelParams,
    spec: Value,
    points: &[solver::parametric::EngagedStability],
) -> Value {
    json!({
        "model": model.system.model.name(),
        "params": Value::Object(keys::to_json(params)),
        "spec": spec,
        "points": points.iter().map(instability_point_json).collect::<Vec<_>>(),
        "unstable_bands": instability_bands(points).iter().map(|&(from, to)| json!({
            "omega_from": num(from),
            "omega_to": num(to),
        })).collect::<Vec<_>>(),
    })
}

/// The specification of a parametric-instability scan: its Omega grid.
pub fn instability_spec_json(omega_from: f64, omega_to: f64, points: u32) -> Value {
    json!({
        "omega_from": num(omega_from),
        "omega_to": num(omega_to),
        "points": points,
    })
}

/// One point of a parametric-instability scan.
pub fn instability_point_json(p: &solver::parametric::EngagedStability) -> Value {
    json!({
        "omega": num(p.omega),
        "spectral_radius": num(p.spectral_radius),
        "growth_per_period": num(p.growth_per_period()),
        "unstable": p.unstable(),
    })
}

/// The options of a Lyapunov-exponent sweep.
pub fn lyapunov_spec_json(opts: &solver::lyapunov::LyapunovOptions) -> Value {
    json!({
        "transient_periods": opts.transient_periods,
        "periods": opts.periods,
        "perturbation_m": num(opts.perturbation_um * 1e-6),
        "rtol": num(opts.rtol),
        "atol_m": num(opts.atol_m),
    })
}

/// One point of a Lyapunov-exponent sweep.
pub fn lyapunov_point_json(l: &solver::lyapunov::Lyapunov) -> Value {
    json!({
        "omega": num(l.omega),
        "exponent_per_period": num(l.per_period),
        "exponent_per_s": num(l.per_s),
    })
}

/// The unstable bands of a scan's points (ascending Omega).
pub fn instability_bands(points: &[solver::parametric::EngagedStability]) -> Vec<(f64, f64)> {
    let growth: Vec<(f64, f64)> = points
        .iter()
        .map(|p| (p.omega, p.growth_per_period()))
        .collect();
    let end = growth.last().map_or(0.0, |g| g.0);
    solver::parametric::unstable_bands(&growth, end)
}

/// A Lyapunov-exponent sweep as JSON.
pub fn lyapunov_json(
    model: &Model,
    params: &ModelParams,
    opts: &solver::lyapunov::LyapunovOptions,
    points: &[solver::lyapunov::Lyapunov],
) -> Value {
    json!({
        "model": model.system.model.name(),
        "params": Value::Object(keys::to_json(params)),
        "spec": lyapunov_spec_json(opts),
        "points": points.iter().map(lyapunov_point_json).collect::<Vec<_>>(),
    })
}
