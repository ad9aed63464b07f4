//! Figure shards: `gearshock figure ID --shard i/n` prints the computed
//! data of members i, i + n, ... (each member's sweep as `gearshock
//! bifurcation` JSON, or its orbit at the selected Omega), and `gearshock
//! merge --out DIR` checks every shard against the figure's definition
//! (its members, options, each member's spec, parameters, grid and every
//! field of every point or orbit sample) before it draws every panel's
//! SVG, JSON and CSV itself, with the code the unsharded run draws with,
//! from the same JSON. No file text travels in a shard, so none can be
//! forged: the merged files are the unsharded run's, byte for byte.

use super::{
    bif_files, bif_spec, check_options, listing, members, orbit_files, orbits, run_options, sweeps,
    FigureArgs, Files, Member,
};
use crate::failure::{usage, Failure};
use figures::presets::{preset, Preset};
use figures::protocol::{AnimHistory, Motion, OmegaResult, Regime};
use serde_json::{json, Map, Value};
use solver::keys::truncate;
use std::path::Path;
use worker::jobs::omega::SAMPLES_PER_PERIOD;

/// The options a shard was computed with: every shard of one figure must
/// carry the same.
fn options_json(args: &FigureArgs) -> Value {
    json!({
        "points": args.points,
        "transient_periods": args.transient_periods,
        "record_periods": args.record_periods,
    })
}

/// The members shard `i/n` of a figure of `count` members computes.
fn shard_members(i: usize, n: usize, count: usize) -> Vec<usize> {
    (i..count).step_by(n.max(1)).collect()
}

/// One shard as JSON: what it is and its members' data (`sweep` for a
/// bifurcation figure, `orbit` for an orbit figure).
pub fn compute(
    p: &Preset,
    all: &[Member],
    args: &FigureArgs,
    (i, n): (usize, usize),
    bif: bool,
) -> Result<Value, Failure> {
    let only = |m: usize| m % n == i;
    let (field, data) = if bif {
        ("sweep", sweeps(all, args, &only)?)
    } else {
        ("orbit", orbits(all, args, &only)?)
    };
    Ok(json!({
        "figure_shard": {
            "id": p.id,
            "shard": i,
            "shards": n,
            "members": shard_members(i, n, all.len()),
            "options": options_json(args),
        },
        "members": data.into_iter().map(|(m, d)| json!({ "member": m, field: d })).collect::<Vec<_>>(),
    }))
}

/// An orbit as a shard carries it: what the phase portrait and the
/// Poincaré section draw and write, and nothing else.
pub fn orbit_json(r: &OmegaResult) -> Value {
    json!({
        "omega": r.omega,
        "mesh": r.mesh,
        "mesh_name": r.mesh_name,
        "backlash_um": r.backlash_um,
        "regime": r.regime,
        "period": r.period,
        "motion": r.motion,
        "settled": r.settled,
        "dynamic_factor": r.dynamic_factor,
        "samples_per_period": r.samples_per_period,
        "record_periods": r.record_periods,
        "x_um": r.x_um,
        "xdot_m_s": r.xdot_m_s,
        "poincare_x_um": r.poincare_x_um,
        "poincare_xdot_m_s": r.poincare_xdot_m_s,
    })
}

/// The orbit of member `m` read back from [`orbit_json`], every field
/// checked against the member and the options: its Omega and mesh the
/// member's, its record the options' length, every sample a number (or
/// null, JSON's non-finite number). `at` names the input in messages.
pub fn orbit_from_json(
    v: &Value,
    m: &Member,
    args: &FigureArgs,
    at: &str,
) -> Result<OmegaResult, String> {
    let bad = |field: &str, v: Option<&Value>, allowed: &str| {
        format!(
            "{at}: orbit.{field} = {} is out of range: allowed {allowed}",
            v.map_or("missing".into(), |v| truncate(&v.to_string(), 40))
        )
    };
    let o = v.as_object().ok_or_else(|| bad("", Some(v), "an object"))?;
    let fields = orbit_json_fields();
    if let Some(k) = o.keys().find(|k| !fields.contains(&k.as_str())) {
        return Err(format!(
            "{at}: field orbit.{} is not one gearshock writes",
            truncate(k, 40)
        ));
    }
    let exact = |key: &str, want: Value| -> Result<(), String> {
        match o.get(key) {
            Some(got) if *got == want => Ok(()),
            got => Err(bad(key, got, &format!("{want} (the figure's)"))),
        }
    };
    let run = run_options(m, args);
    exact("omega", json!(m.settings.view.omega))?;
    let mesh = match m.settings.mesh_index(&m.model) {
        Some(j) => j,
        None => o
            .get("mesh")
            .and_then(Value::as_u64)
            .and_then(|j| usize::try_from(j).ok())
            .filter(|&j| j < m.model.system.meshes.len())
            .ok_or_else(|| bad("mesh", o.get("mesh"), "a mesh of the model"))?,
    };
    let def = &m.model.system.meshes[mesh];
    exact("mesh", json!(mesh))?;
    exact("mesh_name", json!(def.name))?;
    exact(
        "backlash_um",
        json!((def.backlash_m * 1e6 * 1e6).round() / 1e6),
    )?;
    exact("samples_per_period", json!(SAMPLES_PER_PERIOD))?;
    exact("record_periods", json!(run.record_periods))?;
    let record = run.record_periods as usize;
    // No run keeps a deflection beyond the model's divergence bound (it
    // stops there), nor a velocity beyond that bound swept at the fastest
    // of its natural frequencies and the mesh frequency: ten and a hundred
    // times those, generous for peaks between the checks, bound what a
    // shard may hold (a forged 1e300 broke the plotting).
    let bound_m = m.model.divergence_bound_m();
    let omega_top = m
        .model
        .modes
        .modes
        .iter()
        .map(|mode| mode.omega)
        .filter(|w| w.is_finite())
        .fold(m.settings.view.omega.max(1.0), f64::max);
    let largest = |key: &str| {
        if key.contains("xdot") {
            100.0 * bound_m * omega_top * m.model.system.omega_ref_rad_s
        } else {
            10.0 * bound_m * 1e6
        }
    };
    let samples = |key: &str, len: usize| -> Result<Vec<f64>, String> {
        let limit = largest(key);
        let arr = o.get(key).and_then(Value::as_array).filter(|a| {
            a.len() == len
                && a.iter()
                    .all(|x| x.is_null() || x.as_f64().is_some_and(|x| x.abs() <= limit))
        });
        let arr = arr.ok_or_else(|| {
            let what = match o.get(key) {
                Some(Value::Array(a)) => format!("{} entries", a.len()),
                got => got.map_or("missing".into(), |v| truncate(&v.to_string(), 40)),
            };
            format!(
                "{at}: orbit.{key} ({what}) is out of range: allowed an array of exactly {len} numbers of at most {limit:.3e} ({} recorded periods)",
                run.record_periods
            )
        })?;
        Ok(arr.iter().map(|x| x.as_f64().unwrap_or(f64::NAN)).collect())
    };
    let history = record * SAMPLES_PER_PERIOD as usize;
    let regime: Regime = o
        .get("regime")
        .and_then(|r| serde_json::from_value(r.clone()).ok())
        .ok_or_else(|| {
            bad(
                "regime",
                o.get("regime"),
                "no-impact, single-sided, double-sided or no-contact",
            )
        })?;
    let period = match o.get("period") {
        Some(Value::Null) => None,
        p => Some(
            p.and_then(Value::as_u64)
                .and_then(|x| u32::try_from(x).ok())
                .filter(|&x| x >= 1 && x <= run.record_periods)
                .ok_or_else(|| {
                    bad(
                        "period",
                        p,
                        &format!("null or a whole number 1 ..= {}", run.record_periods),
                    )
                })?,
        ),
    };
    let dynamic_factor = match o.get("dynamic_factor") {
        Some(Value::Null) => None,
        d => Some(
            d.and_then(Value::as_f64)
                .ok_or_else(|| bad("dynamic_factor", d, "a number or null"))?,
        ),
    };
    let settled = o
        .get("settled")
        .and_then(Value::as_bool)
        .ok_or_else(|| bad("settled", o.get("settled"), "true or false"))?;
    // The classification as the page's own form writes it; a shard
    // without it keeps what its period says.
    let motion = match o.get("motion") {
        None => match period {
            Some(period) => Motion::Periodic { period },
            None => Motion::NotPeriodic,
        },
        Some(v) => serde_json::from_value::<Motion>(v.clone())
            .ok()
            .ok_or_else(|| {
                bad(
                    "motion",
                    Some(v),
                    "a classification (kind periodic-exact, periodic, period-above-maximum, still-settling or not-periodic)",
                )
            })?,
    };
    Ok(OmegaResult {
        omega: m.settings.view.omega,
        mesh,
        mesh_name: def.name.clone(),
        backlash_um: (def.backlash_m * 1e6 * 1e6).round() / 1e6,
        regime,
        period,
        motion,
        dynamic_factor,
        mesh_freq_hz: 0.0,
        transient_periods_run: 0,
        settled,
        samples_per_period: SAMPLES_PER_PERIOD,
        record_periods: run.record_periods,
        x_um: samples("x_um", history)?,
        xdot_m_s: samples("xdot_m_s", history)?,
        poincare_x_um: samples("poincare_x_um", record)?,
        poincare_xdot_m_s: samples("poincare_xdot_m_s", record)?,
        spectrum_order: Vec::new(),
        spectrum_um: Vec::new(),
        all_meshes: Vec::new(),
        anim: AnimHistory::default(),
        load_sharing: Vec::new(),
        force_orders: None,
        steps: 0,
        cli_json: String::new(),
        preview: false,
        end_state: Vec::new(),
    })
}

/// The fields [`orbit_json`] writes.
fn orbit_json_fields() -> [&'static str; 15] {
    [
        "motion",
        "omega",
        "mesh",
        "mesh_name",
        "backlash_um",
        "regime",
        "period",
        "settled",
        "dynamic_factor",
        "samples_per_period",
        "record_periods",
        "x_um",
        "xdot_m_s",
        "poincare_x_um",
        "poincare_xdot_m_s",
    ]
}

/// The options of a shard as the figure's arguments, checked as `figure`
/// checks its flags: each of `points`, `transient_periods` and
/// `record_periods` null or a whole number in its flag's range.
fn options_of(id: &str, options: &Value, at: &str) -> Result<FigureArgs, Failure> {
    let bad = |why: String| usage(format!("merge: {at}: {why}"));
    let o: &Map<String, Value> = options
        .as_object()
        .filter(|o| o.len() == 3)
        .ok_or_else(|| {
            bad(format!(
                "figure_shard.options = {} is out of range: allowed points, transient_periods and record_periods",
                truncate(&options.to_string(), 60)
            ))
        })?;
    let field = |key: &str| -> Result<Option<u32>, Failure> {
        match o.get(key) {
            Some(Value::Null) => Ok(None),
            Some(v) => v
                .as_u64()
                .and_then(|x| u32::try_from(x).ok())
                .map(Some)
                .ok_or_else(|| {
                    bad(format!(
                        "figure_shard.options.{key} = {} is out of range: allowed null or a whole number",
                        truncate(&v.to_string(), 40)
                    ))
                }),
            None => Err(bad(format!("figure_shard.options.{key} is missing"))),
        }
    };
    let args = FigureArgs {
        id: id.to_string(),
        out: None,
        points: field("points")?,
        transient_periods: field("transient_periods")?,
        record_periods: field("record_periods")?,
        shard: None,
        link: None,
    };
    check_options(&args).map_err(|e| bad(format!("figure_shard.options: {}", e.message)))?;
    Ok(args)
}

/// `gearshock merge --out DIR` of figure shards (named `names`, their
/// files): checks that they are all the shards of one figure computed with
/// the same options, each holding exactly the members the figure's
/// definition gives it, each member's data as gearshock computes it, then
/// draws and writes the files as the unsharded run does and returns its
/// report. Every refusal names the shard file and why (exit 2).
pub fn merge(shards: &[Value], names: &[String], out: Option<&Path>) -> Result<Value, Failure> {
    let name = |k: usize| {
        names
            .get(k)
            .map_or_else(|| format!("shard file {}", k + 1), |n| truncate(n, 80))
    };
    let bad = |k: usize, why: String| usage(format!("merge: {}: {why}", name(k)));
    let head = |k: usize, v: &Value| -> Result<(String, u64, u64, Value), Failure> {
        let o = v
            .as_object()
            .ok_or_else(|| bad(k, "not a figure shard (not a JSON object)".into()))?;
        if let Some(extra) = o.keys().find(|k| *k != "figure_shard" && *k != "members") {
            return Err(bad(
                k,
                format!(
                    "field {} is not one a figure shard holds (figure_shard, members)",
                    truncate(extra, 40)
                ),
            ));
        }
        let h = v
            .get("figure_shard")
            .ok_or_else(|| bad(k, "not a figure shard (no figure_shard)".into()))?;
        let id = h["id"]
            .as_str()
            .ok_or_else(|| bad(k, "no figure id".into()))?;
        let (Some(i), Some(n)) = (h["shard"].as_u64(), h["shards"].as_u64()) else {
            return Err(bad(k, "no shard i/n".into()));
        };
        Ok((id.to_string(), i, n, h["options"].clone()))
    };
    let (id, _, n, options) = head(0, &shards[0])?;
    let p = preset(&id)
        .filter(|p| p.family.is_some() && p.meshes.is_none())
        .ok_or_else(|| bad(0, format!("{} is not a sharded figure", truncate(&id, 30))))?;
    let Some(out) = out else {
        return Err(usage(
            "merge: figure shards need --out DIR for the figure's files",
        ));
    };
    // Before the work: a folder that cannot take the files would lose it.
    crate::output::check_dir("--out", out)?;
    let args = options_of(&id, &options, &name(0))?;
    let all = members(p)?;
    let count = all.len();
    if n == 0 || n as usize > count || shards.len() as u64 != n {
        return Err(usage(format!(
            "merge: figure {id} was split into {n} shards; {} files were given",
            shards.len()
        )));
    }
    let bif = p.settings.iter().any(|(k, _)| *k == "bif_dir");
    let mut seen = vec![false; n as usize];
    let mut files = Files::new();
    let mut panels = Vec::new();
    for (k, v) in shards.iter().enumerate() {
        let (kid, i, kn, kopt) = head(k, v)?;
        if kid != id {
            return Err(bad(
                k,
                format!("of figure {} (not {id})", truncate(&kid, 30)),
            ));
        }
        if kn != n || i >= n {
            return Err(bad(k, format!("shard {i}/{kn}, not one of {n} shards")));
        }
        if kopt != options {
            return Err(bad(
                k,
                format!(
                    "computed with other options ({}, not {options})",
                    truncate(&kopt.to_string(), 100)
                ),
            ));
        }
        if std::mem::replace(&mut seen[i as usize], true) {
            return Err(bad(k, format!("shard {i}/{n} is given twice")));
        }
        let want = shard_members(i as usize, n as usize, count);
        let listed = &v["figure_shard"]["members"];
        if *listed != json!(want) {
            return Err(bad(
                k,
                format!(
                    "figure_shard.members = {} differs from the figure's definition: shard {i}/{n} of {id} holds members {}",
                    truncate(&listed.to_string(), 40),
                    json!(want)
                ),
            ));
        }
        let data = v["members"]
            .as_array()
            .filter(|d| d.len() == want.len())
            .ok_or_else(|| {
                bad(
                    k,
                    format!("members: allowed an array of {} members' data", want.len()),
                )
            })?;
        for (&m, d) in want.iter().zip(data) {
            let at = format!("{}: member {m}", name(k));
            let member = &all[m];
            let field = if bif { "sweep" } else { "orbit" };
            let keys_ok = d.as_object().is_some_and(|o| {
                o.len() == 2 && o.get("member") == Some(&json!(m)) && o.contains_key(field)
            });
            if !keys_ok {
                return Err(usage(format!(
                    "merge: {at}: allowed {{\"member\": {m}, \"{field}\": ...}}, in the order of figure_shard.members"
                )));
            }
            if bif {
                let spec = bif_spec(member, &args);
                check_sweep(&d[field], member, &spec, &at)?;
                panels.push(bif_files(p, m, member, &spec, &d[field], &mut files)?);
            } else {
                let r = orbit_from_json(&d[field], member, &args, &at)
                    .map_err(|e| usage(format!("merge: {e}")))?;
                panels.extend(orbit_files(p, (m, count), member, &r, &mut files)?);
            }
        }
    }
    files.sort_by(|a, b| a.0.cmp(&b.0));
    super::write_all(out, &files)?;
    Ok(listing(p, out, panels))
}

/// A member's sweep as gearshock computes it: its model, params and spec
/// those of the figure's definition with the shard's options, and its
/// points each on the grid, once, every field checked
/// ([`report::check_sweep`]).
fn check_sweep(
    data: &Value,
    m: &Member,
    spec: &solver::sweep::SweepSpec,
    at: &str,
) -> Result<(), Failure> {
    let want = [
        ("model", json!(m.model.system.model.name())),
        (
            "params",
            Value::Object(solver::keys::to_json(&m.settings.params)),
        ),
        ("spec", report::sweep_spec_json(&m.model, spec)),
    ];
    for (key, value) in want {
        if data.get(key) != Some(&value) {
            return Err(usage(format!(
                "merge: {at}: sweep.{key} = {} differs from the figure's definition ({})",
                data.get(key)
                    .map_or("missing".into(), |v| truncate(&v.to_string(), 60)),
                truncate(&value.to_string(), 60)
            )));
        }
    }
    report::check_sweep(data, at).map_err(|e| usage(format!("merge: {e}")))
}
