//! The `shards` target: real shards of a tiny sweep and map, forged
//! (whole shards, spec counts, text, and per-point or per-cell fields),
//! and the invariants an accepted merge keeps. Also the forgeries the
//! figure-shard merge is fuzzed with (`figure_shards_input`), run by
//! `crates/cli/tests/figure_shards_fuzz.rs` on the `gearshock` binary.

use super::{mutate_text, random_json, value_text, Rng};
use serde_json::{json, Value};

/// Real shards of a tiny sweep (gear pair, 3 points up and down, 2
/// chains) and of a tiny map (2 x 2 cells, 2 shards): the material the
/// shard target mutates.
pub fn base_shards() -> (Vec<Value>, Vec<Value>) {
    use solver::map::{MapSpec, RegimeMap};
    use solver::params::{ModelKind, ModelParams};
    use solver::steady::Model;
    use solver::sweep::{canonical_order, BifurcationSweep, Directions, SweepSpec};
    let params = ModelParams::defaults(ModelKind::GearPair);
    let Ok(model) = Model::new(&params) else {
        return (Vec::new(), Vec::new());
    };
    let mut sweeps = Vec::new();
    let mut maps = Vec::new();
    for i in 0..2 {
        let mut spec = SweepSpec::new(0.5, 0.7, 3);
        spec.directions = Directions::Both;
        spec.steady.transient_periods = 5;
        spec.steady.record_periods = 2;
        spec.chains = 2;
        spec.shard = Some(i);
        if let Ok(mut sweep) = BifurcationSweep::new(model.clone(), spec.clone()) {
            let mut pts = Vec::new();
            while !sweep.is_finished() {
                pts.extend(sweep.advance(8));
            }
            canonical_order(&mut pts);
            sweeps.push(report::sweep_json(&model, &params, &spec, &pts));
        }
        let mut mspec = MapSpec::new((0.5, 0.6, 2), "backlash_um", (50.0, 60.0, 2));
        mspec.steady.transient_periods = 5;
        mspec.steady.record_periods = 2;
        mspec.shard = Some((i, 2));
        if let Ok(mut map) = RegimeMap::new(&params, mspec.clone()) {
            let mut cells = Vec::new();
            while !map.is_finished() {
                cells.extend(map.advance(8));
            }
            maps.push(report::map_json(&model, &params, &mspec, &cells));
        }
    }
    (sweeps, maps)
}

/// Numbers that forged counts, indices and counters are known to try
/// (1e300, 1e20, 1.5, "7" and null as step counts among them).
fn forged_number(r: &mut Rng) -> Value {
    match r.below(13) {
        0 => json!(u64::MAX),
        1 => json!(i64::MIN),
        2 => json!(0),
        3 => json!(1u64 << 53),
        4 => json!(999.0),
        5 => json!(-1),
        6 => json!(r.below(8)),
        7 => json!(1e300),
        8 => json!(1e20),
        9 => json!(1.5),
        10 => json!("7"),
        11 => Value::Null,
        _ => json!(r.bits() >> r.below(64)),
    }
}

/// Replaces, removes or forges one node of `v`, found by a random walk.
fn mutate_value(r: &mut Rng, v: &mut Value) {
    let descend = r.chance(75);
    match v {
        Value::Object(m) if descend && !m.is_empty() => {
            let k = r.below(m.len());
            let Some(key) = m.keys().nth(k).cloned() else {
                return;
            };
            if r.chance(10) {
                m.remove(&key);
            } else if let Some(next) = m.get_mut(&key) {
                mutate_value(r, next);
            }
        }
        Value::Array(a) if descend && !a.is_empty() => {
            let k = r.below(a.len());
            match r.below(10) {
                0 => {
                    a.remove(k);
                }
                1 => {
                    let dup = a[k].clone();
                    a.push(dup);
                }
                _ => mutate_value(r, &mut a[k]),
            }
        }
        _ => {
            *v = match r.below(3) {
                0 => forged_number(r),
                1 => random_json(r, 2),
                _ => Value::String(value_text(r)),
            };
        }
    }
}

/// A forged set of shards.
pub fn shards_input(r: &mut Rng, sweeps: &[Value], maps: &[Value]) -> Vec<Value> {
    let mut shards: Vec<Value> = if r.chance(50) {
        sweeps.to_vec()
    } else {
        maps.to_vec()
    };
    if r.chance(10) {
        return shards;
    }
    for _ in 0..1 + r.below(3) {
        match r.below(10) {
            0 if !shards.is_empty() => {
                let k = r.below(shards.len());
                shards.remove(k);
            }
            1 if !shards.is_empty() => {
                let k = r.below(shards.len());
                let dup = shards[k].clone();
                shards.push(dup);
            }
            2 => shards.reverse(),
            3 if !shards.is_empty() => {
                // The same forged count in every shard, so they still agree.
                let key = *r.pick(
                    &["chains", "shards", "points", "omega_points", "value_points"],
                    &"chains",
                );
                let n = forged_number(r);
                for s in &mut shards {
                    if let Some(spec) = s.get_mut("spec").and_then(Value::as_object_mut) {
                        spec.insert(key.into(), n.clone());
                    }
                }
            }
            4 if !shards.is_empty() => {
                let k = r.below(shards.len());
                let text = mutate_text(r, &shards[k].to_string());
                match serde_json::from_str(&text) {
                    Ok(v) => shards[k] = v,
                    Err(_) => shards[k] = Value::String(text),
                }
            }
            5 | 6 if !shards.is_empty() => {
                let k = r.below(shards.len());
                forge_item(r, &mut shards[k]);
            }
            _ if !shards.is_empty() => {
                let k = r.below(shards.len());
                mutate_value(r, &mut shards[k]);
            }
            _ => {}
        }
    }
    shards
}

/// The fields of a sweep point a forgery aims at (paths below the point).
const POINT_FIELDS: &[&str] = &[
    "/stats/steps",
    "/stats/rejected_steps",
    "/stats/rhs_evaluations",
    "/stats/settled",
    "/stats/transient_periods_run",
    "/poincare_delta_m",
    "/poincare_x_m",
    "/poincare_velocity_m_s",
    "/poincare_x_velocity_m_s",
    "/poincare_delta_m/0",
    "/impact",
    "/impact_worst",
    "/worst_mesh",
    "/period",
    "/exact",
    "/motion",
    "/max_multiplier_modulus",
    "/lyapunov_per_period",
    "/x_min_m",
    "/dynamic_factor",
    "/omega",
    "/index",
    "/direction",
    "/error",
    "/extra",
];

/// The fields of a map cell a forgery aims at.
const CELL_FIELDS: &[&str] = &[
    "/row",
    "/column",
    "/omega",
    "/value",
    "/impact",
    "/period",
    "/exact",
    "/motion",
    "/max_multiplier_modulus",
    "/lyapunov_per_period",
    "/error",
    "/extra",
];

/// A forged value for one field: a number that has broken readers, an
/// array of the wrong length or kind, hostile text or random JSON.
fn forged_field(r: &mut Rng) -> Value {
    match r.below(6) {
        0 | 1 => forged_number(r),
        2 => {
            let len = *r.pick(&[0usize, 1, 2, 3, 5, 3000], &1);
            Value::Array((0..len).map(|i| json!(i as f64 * 1e-6)).collect())
        }
        3 => Value::Array(vec![forged_number(r), Value::String(value_text(r))]),
        4 => Value::String(value_text(r)),
        _ => random_json(r, 2),
    }
}

/// Forges one field of one point or cell of `shard`: the per-item
/// contents a merge copies into its output.
fn forge_item(r: &mut Rng, shard: &mut Value) {
    let (items, fields) = if shard.get("points").is_some() {
        ("points", POINT_FIELDS)
    } else {
        ("cells", CELL_FIELDS)
    };
    let Some(list) = shard.get_mut(items).and_then(Value::as_array_mut) else {
        return;
    };
    if list.is_empty() {
        return;
    }
    let k = r.below(list.len());
    let field = *r.pick(fields, &"/extra");
    let value = forged_field(r);
    let item = &mut list[k];
    match item.pointer_mut(field) {
        Some(slot) => *slot = value,
        None => {
            let (parent, key) = field.rsplit_once('/').unwrap_or(("", field));
            if let Some(o) = item.pointer_mut(parent).and_then(Value::as_object_mut) {
                o.insert(key.to_string(), value);
            }
        }
    }
}

/// Every item of a merged output is one of its inputs' items, verbatim:
/// a merge copies, it never makes up or alters a point or cell.
fn items_from_inputs(merged: &Value, key: &str, shards: &[Value]) -> Result<(), String> {
    let given: std::collections::HashSet<String> = shards
        .iter()
        .filter_map(|s| s.get(key).and_then(Value::as_array))
        .flatten()
        .map(Value::to_string)
        .collect();
    for item in merged[key].as_array().map_or(&[][..], Vec::as_slice) {
        if !given.contains(&item.to_string()) {
            return Err(format!(
                "merged {key} holds an item no input has: {}",
                solver::keys::truncate(&item.to_string(), 200)
            ));
        }
    }
    Ok(())
}

/// Every cell of an accepted map is one gearshock writes: `period` null or
/// 1 ..= `record_periods`, a motion it names, and a regime exactly when
/// the cell did not fail; its fields agree (exact exactly when its motion
/// is `periodic-exact`, with the multipliers of a stable orbit).
fn map_cells_well_formed(v: &Value) -> Result<(), String> {
    let record = v["spec"]["record_periods"].as_u64().unwrap_or(0);
    for c in v["cells"].as_array().map_or(&[][..], Vec::as_slice) {
        let period_fine = c["period"].is_null()
            || c["period"]
                .as_u64()
                .is_some_and(|p| (1..=record).contains(&p));
        let motion_fine = c["motion"]
            .as_str()
            .is_some_and(|m| solver::steady::Motion::NAMES.contains(&m));
        let regime_fine = c["error"].is_null() != c["impact"].is_null();
        let exact = c["motion"] == "periodic-exact";
        let agree = c["exact"] == exact
            && match c["max_multiplier_modulus"].as_f64() {
                Some(m) => exact && m <= 1.0 + solver::shooting::floquet::STABILITY_MARGIN,
                None => !exact,
            };
        if !(period_fine && motion_fine && regime_fine && agree) {
            return Err(format!(
                "accepted a cell gearshock does not write: {}",
                solver::keys::truncate(&c.to_string(), 200)
            ));
        }
    }
    Ok(())
}

/// Checks the shard merger on one input.
pub fn check_shards(shards: &[Value]) -> Result<(), String> {
    if let Ok(v) = report::merge_shards(shards) {
        items_from_inputs(&v, "points", shards)?;
        let spec = &v["spec"];
        let dirs = if spec["direction"] == "both" { 2 } else { 1 };
        let expected = spec["points"].as_u64().unwrap_or(0) * dirs;
        let got = v["points"].as_array().map_or(0, Vec::len) as u64;
        if got != expected {
            return Err(format!(
                "merged sweep has {got} points, its grid {expected}"
            ));
        }
        sweep_points_well_formed(&v)?;
    }
    if let Ok(v) = report::merge_maps(shards) {
        let spec = &v["spec"];
        let expected =
            spec["omega_points"].as_u64().unwrap_or(0) * spec["value_points"].as_u64().unwrap_or(0);
        let got = v["cells"].as_array().map_or(0, Vec::len) as u64;
        if got != expected {
            return Err(format!("merged map has {got} cells, its grid {expected}"));
        }
        items_from_inputs(&v, "cells", shards)?;
        map_cells_well_formed(&v)?;
    }
    Ok(())
}

/// Every point of an accepted sweep is one gearshock writes: its work
/// counters whole numbers up to 2^53, `settled` true or false, and each
/// Poincaré array `record_periods` long (a forged point would otherwise be
/// copied into the merged output).
fn sweep_points_well_formed(v: &Value) -> Result<(), String> {
    let record = v["spec"]["record_periods"].as_u64().unwrap_or(0) as usize;
    for p in v["points"].as_array().map_or(&[][..], Vec::as_slice) {
        if p.get("error").is_some() {
            continue;
        }
        let stats = p["stats"].as_object().ok_or("a point without stats")?;
        for (k, x) in stats {
            let fine = if k == "settled" {
                x.is_boolean()
            } else {
                x.as_u64().is_some_and(|n| n <= 1 << 53)
            };
            if !fine {
                return Err(format!("accepted a point with stats.{k} = {x}"));
            }
        }
        let meshes: Vec<&Value> = match p.get("meshes").and_then(Value::as_object) {
            Some(m) => m.values().collect(),
            None => vec![p],
        };
        for m in meshes {
            for key in [
                "poincare_x_m",
                "poincare_x_velocity_m_s",
                "poincare_delta_m",
                "poincare_velocity_m_s",
            ] {
                let n = m[key].as_array().map(Vec::len);
                if n != Some(record) {
                    return Err(format!(
                        "accepted a point whose {key} has {n:?} entries, not {record}"
                    ));
                }
            }
        }
    }
    Ok(())
}

/// A forged set of figure shards, from the real shards `base` of one
/// figure: shards dropped, doubled or swapped; the members a shard claims;
/// file text smuggled in (an SVG with a script, 200 000 characters); a
/// member's data or the options forged; mutated text.
pub fn figure_shards_input(r: &mut Rng, base: &[Value]) -> Vec<Value> {
    let mut shards = base.to_vec();
    if r.chance(10) || shards.is_empty() {
        return shards;
    }
    for _ in 0..1 + r.below(3) {
        if shards.is_empty() {
            break;
        }
        let k = r.below(shards.len());
        match r.below(9) {
            0 => {
                shards.remove(k);
            }
            1 => {
                let dup = shards[k].clone();
                shards.push(dup);
            }
            2 => shards.reverse(),
            3 => {
                let members = match r.below(3) {
                    0 => json!([]),
                    1 => json!([r.below(4), r.below(4)]),
                    _ => forged_field(r),
                };
                if let Some(h) = shards[k]
                    .get_mut("figure_shard")
                    .and_then(Value::as_object_mut)
                {
                    h.insert("members".into(), members);
                }
            }
            4 => {
                let text = if r.chance(50) {
                    "<svg><script>alert(1)</script></svg>".to_string()
                } else {
                    "x".repeat(200_000)
                };
                let file = json!([{ "name": "../escape.svg", "text": text }]);
                let at = *r.pick(&["/files", "/members/0/svg", "/members/0/text"], &"/files");
                set_pointer(&mut shards[k], at, file);
            }
            5 => {
                // A member's data: its orbit or sweep, field by field.
                let data = shards[k]
                    .pointer_mut("/members/0")
                    .and_then(Value::as_object_mut)
                    .and_then(|m| m.values_mut().find(|v| v.is_object()));
                if let Some(d) = data {
                    mutate_value(r, d);
                }
            }
            6 => {
                let key = *r.pick(
                    &["points", "transient_periods", "record_periods", "shards"],
                    &"points",
                );
                let n = forged_number(r);
                set_pointer(&mut shards[k], &format!("/figure_shard/options/{key}"), n);
            }
            7 => {
                let text = mutate_text(r, &shards[k].to_string());
                shards[k] = serde_json::from_str(&text).unwrap_or(Value::String(text));
            }
            _ => mutate_value(r, &mut shards[k]),
        }
    }
    shards
}

/// Sets the value at `pointer`, adding the last key if its parent is an
/// object without it.
fn set_pointer(v: &mut Value, pointer: &str, value: Value) {
    if let Some(slot) = v.pointer_mut(pointer) {
        *slot = value;
        return;
    }
    let (parent, key) = pointer.rsplit_once('/').unwrap_or(("", pointer));
    if let Some(o) = v.pointer_mut(parent).and_then(Value::as_object_mut) {
        o.insert(key.to_string(), value);
    }
}

/// Checks one `gearshock merge --out DIR` of figure shards: it exits 0 or
/// 2 (never a panic, an abort or a solver failure); refused, it says why
/// in one line and writes nothing; accepted, it writes exactly the files
/// of the genuine merge (`expected`, by name), none with a script in it.
/// `written` is what the folder holds afterwards (name, text).
pub fn check_figure_merge(
    code: Option<i32>,
    stderr: &str,
    written: &[(String, String)],
    expected: &[String],
) -> Result<(), String> {
    match code {
        Some(2) => {
            if stderr.trim_end().lines().count() != 1 || stderr.contains("panicked") {
                return Err(format!("refused without one line: {stderr}"));
            }
            if !written.is_empty() {
                return Err(format!("refused but wrote {} files", written.len()));
            }
        }
        Some(0) => {
            let mut names: Vec<&str> = written.iter().map(|(n, _)| n.as_str()).collect();
            names.sort_unstable();
            let mut want: Vec<&str> = expected.iter().map(String::as_str).collect();
            want.sort_unstable();
            if names != want {
                return Err(format!("accepted, wrote {names:?}, not {want:?}"));
            }
            if let Some((n, _)) = written.iter().find(|(_, t)| t.contains("<script")) {
                return Err(format!("accepted and wrote a script into {n}"));
            }
        }
        other => return Err(format!("exit {other:?}: {stderr}")),
    }
    Ok(())
}
