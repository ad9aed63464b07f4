//! The merge of sharded runs: the JSON outputs of `--shard i/n` joined
//! into the output of the unsharded run (a sweep with `--chains n`, a regime
//! map). Every shard is checked against the spec it carries before anything
//! is copied: a shard set that is not one run's is refused with a message
//! naming the input, the field, its value and the allowed range.

use crate::{check, stats_totals};
use serde_json::{json, Map, Value};
use solver::error::{Result, SolverError};
use solver::keys;
use solver::steady::Model;
use solver::sweep::{Direction, SweepSpec};

/// The shards joined: the first input, its spec with `shard` cleared, its
/// model, and every item with its input's number and its shard's.
struct Joined<'a> {
    first: &'a Value,
    spec: Map<String, Value>,
    model: Model,
    items: Vec<Tagged>,
}

/// One point or cell of a shard: (input number, shard number, item).
type Tagged = (usize, u64, Value);

/// Most shards one run may be split into (as `--shard i/n` allows).
pub const MAX_SHARDS: u64 = 10_000;

/// Most recorded periods of a run (as `SteadyOptions::validate` allows).
const MAX_RECORD: u64 = 100_000;
/// Most transient periods of a run (likewise).
const MAX_TRANSIENT: u64 = 1_000_000;

/// What is joined: a sweep's points or a map's cells.
struct Kind {
    /// The spec's field holding the shard count.
    count_key: &'static str,
    /// The array of items.
    items: &'static str,
    /// The command's output, for messages.
    what: &'static str,
}

const SWEEP: Kind = Kind {
    count_key: "chains",
    items: "points",
    what: "bifurcation",
};
const MAP: Kind = Kind {
    count_key: "shards",
    items: "cells",
    what: "map",
};

/// The default names of unnamed inputs: "input 1", "input 2", ...
fn input_names(n: usize) -> Vec<String> {
    (1..=n).map(|k| format!("input {k}")).collect()
}

/// Checks that `shards` (named `names`, e.g. their files) are the `n`
/// shards `i/n` of one run (`n` read from `spec[count_key]`, at most
/// [`MAX_SHARDS`], which must equal the number of inputs): every input has
/// the first one's model, spec (but for `shard`) and params, the params
/// and model as gearshock writes them, each `spec.shard` one of `0/n ..
/// n-1/n`, and each shard exactly once. Nothing is sized from the inputs
/// before `n` is bounded.
fn join_shards<'a>(shards: &'a [Value], names: &[String], kind: &Kind) -> Result<Joined<'a>> {
    let bad = |m: String| SolverError::Parse(m);
    let name = |k: usize| {
        names
            .get(k)
            .map_or_else(|| format!("input {}", k + 1), |n| keys::truncate(n, 80))
    };
    let first = shards
        .first()
        .ok_or_else(|| bad("merge needs at least one shard".into()))?;
    let what = kind.what;
    let spec_of = |k: usize, v: &Value| -> Result<Map<String, Value>> {
        match v.get("spec") {
            Some(Value::Object(m)) => {
                let mut m = m.clone();
                m.insert("shard".into(), Value::Null);
                Ok(m)
            }
            _ => Err(bad(format!(
                "{}: no `spec` object: is it gearshock {what} output?",
                name(k)
            ))),
        }
    };
    let base = spec_of(0, first)?;
    // The parameter set is copied to the output: it must be one gearshock
    // reads, written as gearshock writes it, and the model its own.
    let model = match first.get("params") {
        Some(Value::Object(p)) => {
            let params = keys::from_json(p)
                .map_err(|e| bad(format!("{}: the shard's params: {e}", name(0))))?;
            if keys::to_json(&params) != *p {
                return Err(bad(format!(
                    "{}: params are not as gearshock writes them (a key repeated, reordered or with a default left out)",
                    name(0)
                )));
            }
            let kind_name = params.kind().name();
            if first.get("model").and_then(Value::as_str) != Some(kind_name) {
                return Err(bad(format!(
                    "{}: model = {} is out of range: allowed {kind_name} (the model of its params)",
                    name(0),
                    check::shown(first.get("model"))
                )));
            }
            Model::new(&params).map_err(|e| bad(format!("{}: the shard's params: {e}", name(0))))?
        }
        _ => return Err(bad(format!("{}: no `params` object", name(0)))),
    };
    let count_key = kind.count_key;
    let n = base
        .get(count_key)
        .and_then(Value::as_u64)
        .filter(|n| (1..=MAX_SHARDS).contains(n))
        .ok_or_else(|| {
            check::refuse(
                &name(0),
                &format!("spec.{count_key}"),
                base.get(count_key),
                &format!("a whole number 1 ..= {MAX_SHARDS}"),
            )
        })?;
    if shards.len() as u64 > n {
        return Err(bad(format!(
            "{} shards given for spec.{count_key} = {n}: allowed exactly {n}",
            shards.len()
        )));
    }
    // Bounded by MAX_SHARDS just above.
    let mut seen = vec![false; n as usize];
    let mut all = Vec::new();
    for (k, sh) in shards.iter().enumerate() {
        let field = sh.get("spec").and_then(|s| s.get("shard"));
        let shard = field
            .and_then(Value::as_str)
            .and_then(|s| s.split_once('/'))
            .and_then(|(i, m)| Some((i.parse::<u64>().ok()?, m.parse::<u64>().ok()?)))
            .filter(|&(i, m)| {
                m == n && i < n && field.and_then(Value::as_str) == Some(&format!("{i}/{m}"))
            })
            .map(|(i, _)| i)
            .ok_or_else(|| {
                check::refuse(
                    &name(k),
                    "spec.shard",
                    field,
                    &format!(
                        "\"i/{n}\" with i in 0 ..= {} (spec.{count_key} = {n})",
                        n - 1
                    ),
                )
            })?;
        if sh.get("model") != first.get("model") {
            return Err(bad(format!(
                "{}: model = {} differs from {}'s {}: the shards are of one run",
                name(k),
                check::shown(sh.get("model")),
                name(0),
                check::shown(first.get("model"))
            )));
        }
        if spec_of(k, sh)? != base || sh.get("params") != first.get("params") {
            return Err(bad(format!(
                "{} belongs to a different {what} (its spec or params differ from {}'s)",
                name(k),
                name(0)
            )));
        }
        // Bounded: shard < n checked above.
        if std::mem::replace(&mut seen[shard as usize], true) {
            return Err(bad(format!(
                "{}: shard {shard}/{n} is given twice",
                name(k)
            )));
        }
        let items = kind.items;
        match sh.get(items) {
            Some(Value::Array(p)) => all.extend(p.iter().map(|v| (k, shard, v.clone()))),
            _ => {
                return Err(bad(format!(
                    "{} (shard {shard}/{n}) has no `{items}` array",
                    name(k)
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
    Ok(Joined {
        first,
        spec: base,
        model,
        items: all,
    })
}

/// A number field of a spec, or a message naming it.
fn spec_f64(spec: &Map<String, Value>, key: &str, at: &str) -> Result<f64> {
    spec.get(key)
        .and_then(Value::as_f64)
        .filter(|x| x.is_finite())
        .ok_or_else(|| check::refuse(at, &format!("spec.{key}"), spec.get(key), "a finite number"))
}

/// A whole-number field of a spec in `1 ..= max`, or a message naming it.
fn spec_count(spec: &Map<String, Value>, key: &str, max: u64, at: &str) -> Result<u64> {
    check::whole(spec, key, (1, max), &check::At(at, "spec.".into()))
}

/// Whether a value read back from JSON is the grid value `expected` (JSON
/// round-trips a number to within an ulp or so).
fn on_grid(got: f64, expected: f64) -> bool {
    (got - expected).abs() <= 1e-9 * expected.abs().max(1.0)
}

/// Merges the JSON outputs of the shards `0/n .. n-1/n` of one sweep into the
/// JSON of the unsharded run with `chains = n`. Every point must lie on the
/// spec's grid (its index below `points`, its Omega that index's, its
/// direction one the spec sweeps, its index in its shard's chain) and appear
/// once, every grid point must be present, and every field of every point
/// must be one gearshock writes ([`check::sweep_point`]). Numbers are
/// copied as read (serde_json reads them back exactly, `float_roundtrip`),
/// so the result is the unsharded run's output byte for byte.
pub fn merge_shards(shards: &[Value]) -> Result<Value> {
    merge_sweep_files(shards, &input_names(shards.len()))
}

/// [`merge_shards`], messages naming each input by `names` (its file).
pub fn merge_sweep_files(shards: &[Value], names: &[String]) -> Result<Value> {
    let joined = join_shards(shards, names, &SWEEP)?;
    let name = |k: usize| {
        names
            .get(k)
            .map_or_else(|| format!("input {}", k + 1), |n| keys::truncate(n, 80))
    };
    let bad = |m: String| SolverError::Parse(m);
    let base_spec = &joined.spec;
    let at0 = name(0);
    let points_n = spec_count(
        base_spec,
        "points",
        u64::from(solver::sweep::MAX_POINTS),
        &at0,
    )?;
    let chains = spec_count(base_spec, "chains", points_n, &at0)?;
    let grid = SweepSpec::new(
        spec_f64(base_spec, "omega_from", &at0)?,
        spec_f64(base_spec, "omega_to", &at0)?,
        points_n as u32,
    );
    let directions = base_spec
        .get("direction")
        .and_then(Value::as_str)
        .and_then(solver::sweep::Directions::from_name)
        .ok_or_else(|| {
            check::refuse(
                &at0,
                "spec.direction",
                base_spec.get("direction"),
                "up, down or both",
            )
        })?;
    let shape = sweep_shape(base_spec, &joined.model, &at0)?;
    let dirs = directions.list();
    // One flag per (direction, index): at most 2 * MAX_POINTS, checked above.
    let mut seen = vec![false; dirs.len() * points_n as usize];
    let mut points = Vec::with_capacity(joined.items.len().min(seen.len()));
    for (k, shard, p) in joined.items {
        let index = p.get("index").and_then(Value::as_u64);
        let direction = p
            .get("direction")
            .and_then(Value::as_str)
            .and_then(Direction::from_name);
        let omega = p.get("omega").and_then(Value::as_f64);
        let where_ = format!(
            "{}: a point of shard {shard}/{chains} (index {}, direction {}, omega {})",
            name(k),
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
        check::sweep_point(&p, &shape, &where_)?;
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
        "model": joined.first.get("model").cloned().unwrap_or(Value::Null),
        "params": joined.first.get("params").cloned().unwrap_or(Value::Null),
        "spec": Value::Object(joined.spec),
        "stats": stats,
        "points": points,
    }))
}

/// Checks a whole sweep (the output of an unsharded run with one chain,
/// such as a figure's panel) as a merge checks shards: every point on the
/// grid once, every field of every point one gearshock writes, and its
/// totals its points'. `name` names it in messages.
pub fn check_sweep(v: &Value, name: &str) -> Result<()> {
    let mut one = v.clone();
    match one.get_mut("spec") {
        Some(Value::Object(spec)) if spec.get("shard").is_some_and(Value::is_null) => {
            spec.insert("shard".into(), json!("0/1"));
        }
        got => {
            return Err(check::refuse(
                name,
                "spec.shard",
                got.and_then(|s| s.get("shard")),
                "null in an unsharded run",
            ))
        }
    }
    let whole = merge_sweep_files(std::slice::from_ref(&one), &[name.to_string()])?;
    if whole != *v {
        return Err(SolverError::Parse(format!(
            "{name}: its stats are not the totals of its points, or its fields are not in gearshock's order"
        )));
    }
    Ok(())
}

/// What every point of a sweep must hold, from its spec and model.
fn sweep_shape(spec: &Map<String, Value>, model: &Model, at: &str) -> Result<check::SweepShape> {
    let model_meshes: Vec<String> = model.system.meshes.iter().map(|m| m.name.clone()).collect();
    let listed = spec.get("meshes");
    let meshes: Option<Vec<String>> = match listed {
        Some(Value::Array(a)) if !a.is_empty() && a.len() <= model_meshes.len() => a
            .iter()
            .map(|m| {
                m.as_str()
                    .filter(|m| model_meshes.iter().any(|x| x == m))
                    .map(String::from)
            })
            .collect(),
        _ => None,
    };
    let meshes = meshes.ok_or_else(|| {
        check::refuse(
            at,
            "spec.meshes",
            listed,
            &format!("a list of the model's meshes ({})", model_meshes.join(", ")),
        )
    })?;
    let a = check::At(at, "spec.".into());
    Ok(check::SweepShape {
        record_periods: check::whole(spec, "record_periods", (1, MAX_RECORD), &a)?,
        transient_periods: check::whole(spec, "transient_periods", (0, MAX_TRANSIENT), &a)?,
        meshes,
        model_meshes,
    })
}

/// Merges the shards `0/n .. n-1/n` of one regime map into the unsharded
/// map. Every cell must lie on the spec's grid (row and column in range,
/// its Omega and value those of its column and row, its row in its shard)
/// and appear once, every cell of the grid must be present, and every
/// field of every cell must be one gearshock writes ([`check::map_cell`]).
pub fn merge_maps(shards: &[Value]) -> Result<Value> {
    merge_map_files(shards, &input_names(shards.len()))
}

/// [`merge_maps`], messages naming each input by `names` (its file).
pub fn merge_map_files(shards: &[Value], names: &[String]) -> Result<Value> {
    let joined = join_shards(shards, names, &MAP)?;
    let name = |k: usize| {
        names
            .get(k)
            .map_or_else(|| format!("input {}", k + 1), |n| keys::truncate(n, 80))
    };
    let bad = |m: String| SolverError::Parse(m);
    let mut base = joined.spec;
    let at0 = name(0);
    let n = spec_count(&base, "shards", MAX_SHARDS, &at0)?;
    let columns = spec_count(&base, "omega_points", 2000, &at0)?;
    let rows = spec_count(&base, "value_points", 2000, &at0)?;
    if columns < 2 {
        return Err(check::refuse(
            &at0,
            "spec.omega_points",
            base.get("omega_points"),
            "a whole number 2 ..= 2000",
        ));
    }
    let record_periods = check::whole(
        &base,
        "record_periods",
        (1, MAX_RECORD),
        &check::At(&at0, "spec.".into()),
    )?;
    let grid = solver::map::MapSpec::new(
        (
            spec_f64(&base, "omega_from", &at0)?,
            spec_f64(&base, "omega_to", &at0)?,
            columns as u32,
        ),
        "",
        (
            spec_f64(&base, "value_from", &at0)?,
            spec_f64(&base, "value_to", &at0)?,
            rows as u32,
        ),
    );
    // At most 2000 x 2000 flags, checked above.
    let mut seen = vec![false; (rows * columns) as usize];
    let mut cells = Vec::with_capacity(joined.items.len().min(seen.len()));
    for (k, shard, c) in joined.items {
        let row = c.get("row").and_then(Value::as_u64);
        let column = c.get("column").and_then(Value::as_u64);
        let omega = c.get("omega").and_then(Value::as_f64);
        let value = c.get("value").and_then(Value::as_f64);
        let where_ = format!(
            "{}: a cell of shard {shard}/{n} (row {}, column {})",
            name(k),
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
        check::map_cell(&c, record_periods, &where_)?;
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
        "model": joined.first.get("model").cloned().unwrap_or(Value::Null),
        "params": joined.first.get("params").cloned().unwrap_or(Value::Null),
        "spec": Value::Object(base),
        "cells": cells,
    }))
}
