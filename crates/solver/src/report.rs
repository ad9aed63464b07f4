//! Results as JSON, in one format shared by the CLI and the browser app.
//!
//! Field names carry SI units (`_m`, `_hz`, `_n`, `_nm`, `_s`, `_m_s`);
//! dimensionless quantities (`omega`, `dynamic_factor`) carry none. Building
//! JSON values is pure computation; writing them out is the caller's job.

mod orbits;
pub use orbits::shooting_frf_json;

use crate::error::{Result, SolverError};
use crate::keys;
use crate::modal::Mode;
use crate::params::{ModelKind, ModelParams};
use crate::steady::{spectrum, Impact, Model, SteadyState, SteadyStats};
use crate::sweep::{Direction, PointMesh, SweepPoint, SweepSpec};
use serde_json::{json, Map, Value};

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
        "delta_min_m": num(m.delta_min_m),
        "delta_max_m": num(m.delta_max_m),
        "delta_mean_m": num(m.delta_mean_m),
        "delta_rms_m": num(m.delta_rms_m),
        "relative_min_m": num(m.rel_min_m),
        "relative_max_m": num(m.rel_max_m),
        "force_max_n": num(m.force_max_n),
        "force_min_n": num(m.force_min_n),
        "static_force_n": num(m.static_force_n),
        "dynamic_factor": m.dynamic_factor.map_or(Value::Null, num),
        "impact": m.impact.name(),
        "period": ss.period,
        "exact": ss.motion.is_exact(),
        "max_multiplier_modulus": ss.motion.max_multiplier_modulus().map_or(Value::Null, num),
        "motion": ss.motion.name(),
        "verdict": ss.motion.words(ss.stats.transient_periods_run),
        "shooting_note": ss.shooting_note,
        "contact_fraction": {
            "drive": num(m.contact_fraction[0]),
            "apart": num(m.contact_fraction[1]),
            "back": num(m.contact_fraction[2]),
        },
        "poincare": {
            "delta_m": nums(&m.poincare_delta_m),
            "velocity_m_s": nums(&m.poincare_velocity_m_s),
        },
        "spectrum": spec.map_or(Value::Null, |s| json!({
            "order": nums(&s.order),
            "frequency_hz": nums(&s.order.iter().map(|o| o * ss.mesh_freq_hz).collect::<Vec<_>>()),
            "amplitude_m": nums(&s.amplitude),
        })),
        "all_meshes": Value::Object(all),
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
    o.insert("stats".into(), stats_json(&p.stats));
    Value::Object(o)
}

/// Totals of a sweep's work, summed over points (saturating: the sweep's
/// own counters cannot come near `u64::MAX`; merged input is checked by
/// [`merge_shards`] first).
pub fn sweep_stats_json(points: &[Value]) -> Value {
    stats_totals(points, true).unwrap_or(Value::Null)
}

/// The totals; with `saturate` false, `None` if a sum overflows.
fn stats_totals(points: &[Value], saturate: bool) -> Option<Value> {
    let mut totals: Map<String, Value> = Map::new();
    let mut failed = 0u64;
    for p in points {
        if p.get("error").is_some() {
            failed += 1;
        }
        if let Some(Value::Object(s)) = p.get("stats") {
            for (k, v) in s {
                if let Some(x) = v.as_u64() {
                    let cur = totals.get(k).and_then(Value::as_u64).unwrap_or(0);
                    let sum = if saturate {
                        cur.saturating_add(x)
                    } else {
                        cur.checked_add(x)?
                    };
                    totals.insert(k.clone(), json!(sum));
                }
            }
        }
    }
    totals.insert("points".into(), json!(points.len()));
    totals.insert("failed_points".into(), json!(failed));
    totals.remove("transient_periods_run");
    Some(Value::Object(totals))
}

/// `gearshock bifurcation`: the whole result.
pub fn sweep_json(
    model: &Model,
    params: &ModelParams,
    spec: &SweepSpec,
    points: &[SweepPoint],
) -> Value {
    let pts: Vec<Value> = points.iter().map(|p| sweep_point_json(model, p)).collect();
    json!({
        "model": model.system.model.name(),
        "params": Value::Object(keys::to_json(params)),
        "spec": sweep_spec_json(model, spec),
        "stats": sweep_stats_json(&pts),
        "points": pts,
    })
}

/// The first input, its spec without `shard`, and every item with its shard.
type Joined<'a> = (&'a Value, Map<String, Value>, Vec<(u64, Value)>);

/// Most shards one run may be split into (as `--shard i/n` allows).
pub const MAX_SHARDS: u64 = 10_000;

/// Largest work counter one merged point may carry: 2^53, the largest
/// integer every JSON reader holds exactly.
const MAX_COUNTER: u64 = 1 << 53;

/// Checks that `shards` are the `n` shards `i/n` of one run (`n` read from
/// `spec[count_key]`, at most [`MAX_SHARDS`], which must equal the number
/// of inputs): every input has the first one's spec (but for `shard`) and
/// params, and each shard appears exactly once. Nothing is sized from the
/// inputs before `n` is bounded. Returns the first input, its spec
/// with `shard` cleared, and every shard's `items` with the shard's number,
/// in input order.
fn join_shards<'a>(
    shards: &'a [Value],
    count_key: &str,
    items: &str,
    what: &str,
) -> Result<Joined<'a>> {
    let bad = |m: String| SolverError::Parse(m);
    let first = shards
        .first()
        .ok_or_else(|| bad("merge needs at least one shard".into()))?;
    let spec_of = |v: &Value| -> Result<Map<String, Value>> {
        match v.get("spec") {
            Some(Value::Object(m)) => {
                let mut m = m.clone();
                m.insert("shard".into(), Value::Null);
                Ok(m)
            }
            _ => Err(bad(format!(
                "a shard has no `spec` object: is it gearshock {what} output?"
            ))),
        }
    };
    let base = spec_of(first)?;
    // The parameter set is copied to the output: it must be one gearshock reads.
    match first.get("params") {
        Some(Value::Object(p)) => {
            keys::from_json(p).map_err(|e| bad(format!("the shards' params: {e}")))?;
        }
        _ => return Err(bad("a shard has no `params` object".into())),
    }
    let n = base
        .get(count_key)
        .and_then(Value::as_u64)
        .ok_or_else(|| bad(format!("shard spec has no whole number `{count_key}`")))?;
    if n == 0 || n > MAX_SHARDS {
        return Err(bad(format!(
            "spec.{count_key} = {n} is out of range: allowed 1 ..= {MAX_SHARDS}"
        )));
    }
    // Bounded by MAX_SHARDS just above.
    let mut seen = vec![false; n as usize];
    let mut all = Vec::new();
    for (k, sh) in shards.iter().enumerate() {
        let shard = sh
            .get("spec")
            .and_then(|s| s.get("shard"))
            .and_then(Value::as_str)
            .and_then(|s| s.split_once('/'))
            .and_then(|(i, _)| i.parse::<u64>().ok())
            .ok_or_else(|| {
                bad(format!(
                    "input {} is not a shard (spec.shard is missing)",
                    k + 1
                ))
            })?;
        if spec_of(sh)? != base || sh.get("params") != first.get("params") {
            return Err(bad(format!(
                "input {} belongs to a different {what} (its spec or params differ from the first input's)",
                k + 1
            )));
        }
        let slot = usize::try_from(shard).ok().filter(|&s| s < seen.len());
        match slot {
            Some(s) if !seen[s] => seen[s] = true,
            _ => {
                return Err(bad(format!(
                    "shard {shard}/{n} is given twice or out of range"
                )))
            }
        }
        match sh.get(items) {
            Some(Value::Array(p)) => all.extend(p.iter().map(|v| (shard, v.clone()))),
            _ => {
                return Err(bad(format!(
                    "input {} (shard {shard}/{n}) has no `{items}` array",
                    k + 1
                )))
            }
        }
    }
    if let Some(missing) = seen.iter().position(|s| !s) {
        return Err(bad(format!(
            "shard {missing}/{n} is missing ({count_key} = {n}, {} given)",
            shards.len()
        )));
    }
    Ok((first, base, all))
}

/// A number field of a spec, or a message naming it.
fn spec_f64(spec: &Map<String, Value>, key: &str) -> Result<f64> {
    spec.get(key)
        .and_then(Value::as_f64)
        .filter(|x| x.is_finite())
        .ok_or_else(|| SolverError::Parse(format!("shard spec has no finite number `{key}`")))
}

/// A whole-number field of a spec in `1 ..= max`, or a message naming it.
fn spec_count(spec: &Map<String, Value>, key: &str, max: u64) -> Result<u64> {
    let n = spec
        .get(key)
        .and_then(Value::as_u64)
        .ok_or_else(|| SolverError::Parse(format!("shard spec has no whole number `{key}`")))?;
    if n == 0 || n > max {
        return Err(SolverError::Parse(format!(
            "spec.{key} = {n} is out of range: allowed 1 ..= {max}"
        )));
    }
    Ok(n)
}

/// Whether a value read back from JSON is the grid value `expected` (JSON
/// round-trips a number to within an ulp or so).
fn on_grid(got: f64, expected: f64) -> bool {
    (got - expected).abs() <= 1e-9 * expected.abs().max(1.0)
}

/// Checks one merged point's or cell's work counters: whole numbers no
/// larger than [`MAX_COUNTER`].
fn check_counters(item: &Value, what: &str) -> Result<()> {
    if let Some(Value::Object(s)) = item.get("stats") {
        for (k, v) in s {
            if v.as_u64().is_some_and(|x| x > MAX_COUNTER) || v.as_i64().is_some_and(|x| x < 0) {
                return Err(SolverError::Parse(format!(
                    "{what}: stats.{} = {} is out of range: allowed 0 ..= {MAX_COUNTER}",
                    keys::truncate(k, 40),
                    keys::truncate(&v.to_string(), 40)
                )));
            }
        }
    }
    Ok(())
}

/// Merges the JSON outputs of the shards `0/n .. n-1/n` of one sweep into the
/// JSON of the unsharded run with `chains = n`. Every point must lie on the
/// spec's grid (its index below `points`, its Omega that index's, its
/// direction one the spec sweeps, its index in its shard's chain) and appear
/// once, and every grid point must be present.
pub fn merge_shards(shards: &[Value]) -> Result<Value> {
    let (first, base_spec, tagged) = join_shards(shards, "chains", "points", "sweep")?;
    let bad = |m: String| SolverError::Parse(m);
    let points_n = spec_count(&base_spec, "points", u64::from(crate::sweep::MAX_POINTS))?;
    let chains = spec_count(&base_spec, "chains", points_n)?;
    let grid = SweepSpec::new(
        spec_f64(&base_spec, "omega_from")?,
        spec_f64(&base_spec, "omega_to")?,
        points_n as u32,
    );
    let directions = base_spec
        .get("direction")
        .and_then(Value::as_str)
        .and_then(crate::sweep::Directions::from_name)
        .ok_or_else(|| bad("shard spec has no `direction` (up, down or both)".into()))?;
    let dirs = directions.list();
    // One flag per (direction, index): at most 2 * MAX_POINTS, checked above.
    let mut seen = vec![false; dirs.len() * points_n as usize];
    let mut points = Vec::with_capacity(tagged.len().min(seen.len()));
    for (shard, p) in tagged {
        let index = p.get("index").and_then(Value::as_u64);
        let direction = p
            .get("direction")
            .and_then(Value::as_str)
            .and_then(Direction::from_name);
        let omega = p.get("omega").and_then(Value::as_f64);
        let where_ = format!(
            "a point of shard {shard}/{chains} (index {}, direction {}, omega {})",
            index.map_or("missing".into(), |i| i.to_string()),
            direction.map_or("missing", Direction::name),
            omega.map_or("missing".into(), |o| o.to_string()),
        );
        let (Some(index), Some(direction), Some(omega)) = (index, direction, omega) else {
            return Err(bad(format!("{where_} lacks its index, direction or omega")));
        };
        let d = dirs.iter().position(|&x| x == direction).ok_or_else(|| {
            bad(format!(
                "{where_}: the sweep runs {} only",
                directions.name()
            ))
        })?;
        if index >= points_n || index % chains != shard {
            return Err(bad(format!(
                "{where_} is not on the sweep's grid: shard {shard}/{chains} holds indices {shard}, {}, ... below {points_n}",
                shard + chains
            )));
        }
        if !on_grid(omega, grid.omega(index as u32)) {
            return Err(bad(format!(
                "{where_} is not on the sweep's grid: point {index} is at omega {}",
                grid.omega(index as u32)
            )));
        }
        let slot = d * points_n as usize + index as usize;
        if seen[slot] {
            return Err(bad(format!("{where_} is given twice")));
        }
        seen[slot] = true;
        check_counters(&p, &where_)?;
        points.push(p);
    }
    if let Some(slot) = seen.iter().position(|s| !s) {
        return Err(bad(format!(
            "point {} ({}) is missing from the shards",
            slot % points_n as usize,
            dirs[slot / points_n as usize].name()
        )));
    }
    points.sort_by_key(|p| {
        let idx = p.get("index").and_then(Value::as_i64).unwrap_or(0);
        match p
            .get("direction")
            .and_then(Value::as_str)
            .and_then(Direction::from_name)
        {
            Some(Direction::Down) => (1, -idx),
            _ => (0, idx),
        }
    });
    let stats = stats_totals(&points, false)
        .ok_or_else(|| bad("the shards' work counters overflow when summed".into()))?;
    Ok(json!({
        "model": first.get("model").cloned().unwrap_or(Value::Null),
        "params": first.get("params").cloned().unwrap_or(Value::Null),
        "spec": Value::Object(base_spec),
        "stats": stats,
        "points": points,
    }))
}

/// Parses an impact name in JSON (for readers of sweep output).
pub fn impact_of(v: &Value) -> Option<Impact> {
    v.as_str().and_then(Impact::from_name)
}

/// The options of a harmonic-balance frequency response as JSON.
pub fn frf_spec_json(spec: &crate::hbm::FrfSpec, grid: usize) -> Value {
    json!({
        "omega_from": num(spec.omega_from),
        "omega_to": num(spec.omega_to),
        "points": spec.points,
        "direction": spec.direction.name(),
        "harmonics": spec.harmonics,
        "method": spec.method.name(),
        "grid": grid,
        "stability": spec.stability,
        "symmetric": spec.symmetric,
    })
}

fn branch_mesh_json(m: &crate::hbm::BranchMesh) -> Map<String, Value> {
    let mut o = Map::new();
    o.insert("delta_max_m".into(), num(m.delta_max_m));
    o.insert("delta_min_m".into(), num(m.delta_min_m));
    o.insert("delta_amplitude_m".into(), num(m.delta_amplitude_m));
    o.insert("rel_max_m".into(), num(m.rel_max_m));
    o.insert("rel_min_m".into(), num(m.rel_min_m));
    o.insert("harmonics_m".into(), nums(&m.harmonics_m));
    o.insert("impact".into(), Value::from(m.impact.name()));
    o
}

/// One branch point. With one requested mesh its fields are inlined; with
/// several they sit under `meshes` keyed by name. `rel_*` is `x = delta - e`.
pub fn branch_point_json(model: &Model, p: &crate::hbm::BranchPoint, meshes: &[usize]) -> Value {
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

/// A whole frequency response: spec, branch, work counters and, when the
/// continuation failed part-way, the error (the branch is then partial).
pub fn frf_json(
    model: &Model,
    params: &ModelParams,
    continuation: &crate::hbm::FrfContinuation,
    branch: &[crate::hbm::BranchPoint],
    meshes: &[usize],
    error: Option<&SolverError>,
) -> Value {
    let names: Vec<&str> = meshes
        .iter()
        .filter_map(|&j| model.system.meshes.get(j).map(|m| m.name.as_str()))
        .collect();
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
pub fn map_spec_json(model: &Model, spec: &crate::map::MapSpec) -> Value {
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
pub fn map_cell_json(c: &crate::map::MapCell) -> Value {
    json!({
        "row": c.row,
        "column": c.column,
        "omega": num(c.omega),
        "value": num(c.value),
        "impact": if c.error.is_some() { Value::Null } else { Value::from(c.impact.name()) },
        "period": c.period,
        "error": c.error,
    })
}

/// A whole regime map (or one shard of it).
pub fn map_json(
    model: &Model,
    params: &ModelParams,
    spec: &crate::map::MapSpec,
    cells: &[crate::map::MapCell],
) -> Value {
    json!({
        "model": model.system.model.name(),
        "params": Value::Object(keys::to_json(params)),
        "spec": map_spec_json(model, spec),
        "cells": cells.iter().map(map_cell_json).collect::<Vec<_>>(),
    })
}

/// Merges the shards `0/n .. n-1/n` of one regime map into the unsharded
/// map. Every cell must lie on the spec's grid (row and column in range,
/// its Omega and value those of its column and row, its row in its shard)
/// and appear once, and every cell of the grid must be present.
pub fn merge_maps(shards: &[Value]) -> Result<Value> {
    let (first, mut base, tagged) = join_shards(shards, "shards", "cells", "map")?;
    let bad = |m: String| SolverError::Parse(m);
    let n = spec_count(&base, "shards", MAX_SHARDS)?;
    let columns = spec_count(&base, "omega_points", 2000)?;
    let rows = spec_count(&base, "value_points", 2000)?;
    if columns < 2 {
        return Err(bad(
            "spec.omega_points = 1 is out of range: allowed 2 ..= 2000".into(),
        ));
    }
    let grid = crate::map::MapSpec::new(
        (
            spec_f64(&base, "omega_from")?,
            spec_f64(&base, "omega_to")?,
            columns as u32,
        ),
        "",
        (
            spec_f64(&base, "value_from")?,
            spec_f64(&base, "value_to")?,
            rows as u32,
        ),
    );
    // At most 2000 x 2000 flags, checked above.
    let mut seen = vec![false; (rows * columns) as usize];
    let mut cells = Vec::with_capacity(tagged.len().min(seen.len()));
    for (shard, c) in tagged {
        let row = c.get("row").and_then(Value::as_u64);
        let column = c.get("column").and_then(Value::as_u64);
        let omega = c.get("omega").and_then(Value::as_f64);
        let value = c.get("value").and_then(Value::as_f64);
        let where_ = format!(
            "a cell of shard {shard}/{n} (row {}, column {})",
            row.map_or("missing".into(), |i| i.to_string()),
            column.map_or("missing".into(), |i| i.to_string()),
        );
        let (Some(row), Some(column), Some(omega), Some(value)) = (row, column, omega, value)
        else {
            return Err(bad(format!(
                "{where_} lacks its row, column, omega or value"
            )));
        };
        if row >= rows || column >= columns || row % n != shard {
            return Err(bad(format!(
                "{where_} is not on the map's grid of {rows} rows x {columns} columns (shard {shard}/{n} holds rows {shard}, {}, ...)",
                shard + n
            )));
        }
        let (r, col) = (row as u32, column as u32);
        if !on_grid(omega, grid.omega(col)) || !on_grid(value, grid.value(r)) {
            return Err(bad(format!(
                "{where_} is not on the map's grid: its omega {omega} and value {value} should be {} and {}",
                grid.omega(col),
                grid.value(r)
            )));
        }
        let slot = (row * columns + column) as usize;
        if seen[slot] {
            return Err(bad(format!("{where_} is given twice")));
        }
        seen[slot] = true;
        cells.push(c);
    }
    if let Some(slot) = seen.iter().position(|s| !s) {
        return Err(bad(format!(
            "cell (row {}, column {}) is missing from the shards",
            slot as u64 / columns,
            slot as u64 % columns
        )));
    }
    // The merged map is the unsharded one.
    base.insert("shards".into(), json!(1));
    let key = |v: &Value, f: &str| v.get(f).and_then(Value::as_u64).unwrap_or(0);
    cells.sort_by_key(|c| (key(c, "row"), key(c, "column")));
    Ok(json!({
        "model": first.get("model").cloned().unwrap_or(Value::Null),
        "params": first.get("params").cloned().unwrap_or(Value::Null),
        "spec": Value::Object(base),
        "cells": cells,
    }))
}

/// A parametric-instability scan: the engaged system's Floquet spectral
/// radius per Omega, its logarithm (growth of large motion per mesh period)
/// and whether it exceeds 1; then the unstable bands
/// ([`crate::parametric::unstable_bands`] of the points, ascending Omega).
pub fn instability_json(
    model: &Model,
    params: &ModelParams,
    points: &[crate::parametric::EngagedStability],
) -> Value {
    json!({
        "model": model.system.model.name(),
        "params": Value::Object(keys::to_json(params)),
        "points": points.iter().map(instability_point_json).collect::<Vec<_>>(),
        "unstable_bands": instability_bands(points).iter().map(|&(from, to)| json!({
            "omega_from": num(from),
            "omega_to": num(to),
        })).collect::<Vec<_>>(),
    })
}

/// One point of a parametric-instability scan.
pub fn instability_point_json(p: &crate::parametric::EngagedStability) -> Value {
    json!({
        "omega": num(p.omega),
        "spectral_radius": num(p.spectral_radius),
        "growth_per_period": num(p.growth_per_period()),
        "unstable": p.unstable(),
    })
}

/// The options of a Lyapunov-exponent sweep.
pub fn lyapunov_spec_json(opts: &crate::lyapunov::LyapunovOptions) -> Value {
    json!({
        "transient_periods": opts.transient_periods,
        "periods": opts.periods,
        "perturbation_m": num(opts.perturbation_um * 1e-6),
        "rtol": num(opts.rtol),
        "atol_m": num(opts.atol_m),
    })
}

/// One point of a Lyapunov-exponent sweep.
pub fn lyapunov_point_json(l: &crate::lyapunov::Lyapunov) -> Value {
    json!({
        "omega": num(l.omega),
        "exponent_per_period": num(l.per_period),
        "exponent_per_s": num(l.per_s),
    })
}

/// The unstable bands of a scan's points (ascending Omega).
pub fn instability_bands(points: &[crate::parametric::EngagedStability]) -> Vec<(f64, f64)> {
    let growth: Vec<(f64, f64)> = points
        .iter()
        .map(|p| (p.omega, p.growth_per_period()))
        .collect();
    let end = growth.last().map_or(0.0, |g| g.0);
    crate::parametric::unstable_bands(&growth, end)
}

/// A Lyapunov-exponent sweep as JSON.
pub fn lyapunov_json(
    model: &Model,
    params: &ModelParams,
    opts: &crate::lyapunov::LyapunovOptions,
    points: &[crate::lyapunov::Lyapunov],
) -> Value {
    json!({
        "model": model.system.model.name(),
        "params": Value::Object(keys::to_json(params)),
        "spec": lyapunov_spec_json(opts),
        "points": points.iter().map(lyapunov_point_json).collect::<Vec<_>>(),
    })
}
