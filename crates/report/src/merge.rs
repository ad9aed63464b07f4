//! The merge of sharded runs: the JSON outputs of `--shard i/n` joined
//! into the output of the unsharded run (a sweep with `--chains n`, a regime
//! map). Every shard is checked against the spec it carries before anything
//! is copied, one shard and one item at a time ([`Merge`]): a shard set
//! that is not one run's is refused with a message
//! naming the input, the field, its value and the allowed range.

use crate::{check, Totals};
use serde_json::{json, Map, Value};
use solver::error::{Result, SolverError};
use solver::keys;
use solver::steady::Model;
use solver::sweep::{Direction, Directions, SweepSpec};

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

/// The grid the items of a merge must cover, each place once.
enum Grid {
    Sweep {
        points_n: u64,
        chains: u64,
        grid: SweepSpec,
        directions: Directions,
        shape: check::SweepShape,
        totals: Totals,
    },
    Map {
        rows: u64,
        columns: u64,
        record_periods: u64,
        grid: solver::map::MapSpec,
    },
}

/// A merge of the shards `0/n .. n-1/n` of one run, fed one shard and one
/// item at a time so that a caller may stream them from files and never
/// hold more than one item ([`Merge::new`], then per input
/// [`Merge::shard`] and [`Merge::item`] for each of its items, then
/// [`Merge::finish`]). Each item is checked when given and gets its place
/// in the merged output; the caller keeps it (in memory or on disk) and
/// writes the items in the order of their places after the fields
/// `finish` returns.
///
/// Every input must have the first one's model, spec (but for `shard`) and
/// params, the params and model as gearshock writes them, each
/// `spec.shard` one of `0/n .. n-1/n` (`n` from `spec.chains` or
/// `spec.shards`, at most [`MAX_SHARDS`], and at least the number of
/// inputs), and each shard exactly once. Every item must lie on the spec's
/// grid (index and Omega, row and column, in its shard), appear once, and
/// hold exactly the fields gearshock writes ([`check`]); every place of
/// the grid must be filled. Nothing is sized from the inputs before its
/// size is bounded.
pub struct Merge {
    kind: &'static Kind,
    names: Vec<String>,
    model_json: Value,
    params_json: Value,
    spec: Map<String, Value>,
    n: u64,
    seen_shards: Vec<bool>,
    grid: Grid,
    seen: Vec<bool>,
}

fn bad(m: String) -> SolverError {
    SolverError::Parse(m)
}

/// A spec with its `shard` cleared (what every shard shares).
fn spec_of(head: &Map<String, Value>, name: &str, what: &str) -> Result<Map<String, Value>> {
    match head.get("spec") {
        Some(Value::Object(m)) => {
            let mut m = m.clone();
            m.insert("shard".into(), Value::Null);
            Ok(m)
        }
        _ => Err(bad(format!(
            "{name}: no `spec` object: is it gearshock {what} output?"
        ))),
    }
}

impl Merge {
    /// Starts a merge of `names.len()` inputs (named in messages by
    /// `names`, e.g. their files) from the first input's fields other
    /// than its items (`head`); `items` names the items' field, `points`
    /// (a sweep) or `cells` (a map).
    pub fn new(head: &Map<String, Value>, items: &str, names: Vec<String>) -> Result<Self> {
        let kind = match items {
            "points" => &SWEEP,
            "cells" => &MAP,
            other => {
                return Err(bad(format!(
                "merge joins the points of bifurcation shards or the cells of map shards, not `{}`",
                keys::truncate(other, 40)
            )))
            }
        };
        let name0 = names
            .first()
            .map_or_else(|| "input 1".to_string(), |n| keys::truncate(n, 80));
        let what = kind.what;
        let spec = spec_of(head, &name0, what)?;
        // The parameter set is copied to the output: it must be one
        // gearshock reads, written as gearshock writes it, and the model
        // its own.
        let model = match head.get("params") {
            Some(Value::Object(p)) => {
                let params = keys::from_json(p)
                    .map_err(|e| bad(format!("{name0}: the shard's params: {e}")))?;
                if keys::to_json(&params) != *p {
                    return Err(bad(format!(
                        "{name0}: params are not as gearshock writes them (a key repeated, reordered or with a default left out)"
                    )));
                }
                let kind_name = params.kind().name();
                if head.get("model").and_then(Value::as_str) != Some(kind_name) {
                    return Err(bad(format!(
                        "{name0}: model = {} is out of range: allowed {kind_name} (the model of its params)",
                        check::shown(head.get("model"))
                    )));
                }
                Model::new(&params).map_err(|e| bad(format!("{name0}: the shard's params: {e}")))?
            }
            _ => return Err(bad(format!("{name0}: no `params` object"))),
        };
        let count_key = kind.count_key;
        let n = spec
            .get(count_key)
            .and_then(Value::as_u64)
            .filter(|n| (1..=MAX_SHARDS).contains(n))
            .ok_or_else(|| {
                check::refuse(
                    &name0,
                    &format!("spec.{count_key}"),
                    spec.get(count_key),
                    &format!("a whole number 1 ..= {MAX_SHARDS}"),
                )
            })?;
        if names.len() as u64 > n {
            return Err(bad(format!(
                "{} shards given for spec.{count_key} = {n}: allowed exactly {n}",
                names.len()
            )));
        }
        let grid = if kind.items == "points" {
            sweep_grid(&spec, &model, &name0)?
        } else {
            map_grid(&spec, &name0)?
        };
        let places = match &grid {
            // At most 2 * MAX_POINTS, checked by `sweep_grid`.
            Grid::Sweep {
                points_n,
                directions,
                ..
            } => directions.list().len() * *points_n as usize,
            // At most 2000 x 2000, checked by `map_grid`.
            Grid::Map { rows, columns, .. } => (rows * columns) as usize,
        };
        Ok(Merge {
            kind,
            names,
            model_json: head.get("model").cloned().unwrap_or(Value::Null),
            params_json: head.get("params").cloned().unwrap_or(Value::Null),
            spec,
            // Bounded by MAX_SHARDS just above.
            seen_shards: vec![false; n as usize],
            n,
            grid,
            seen: vec![false; places],
        })
    }

    fn name(&self, k: usize) -> String {
        self.names
            .get(k)
            .map_or_else(|| format!("input {}", k + 1), |n| keys::truncate(n, 80))
    }

    /// How many items the merged output holds (places of the grid).
    pub fn len(&self) -> usize {
        self.seen.len()
    }

    /// Whether the merged output holds no items (never: a grid has a place).
    pub fn is_empty(&self) -> bool {
        self.seen.is_empty()
    }

    /// The items' field: `points` or `cells`.
    pub fn items_key(&self) -> &'static str {
        self.kind.items
    }

    /// Checks input `k`'s fields other than its items (`head`) and returns
    /// its shard number.
    pub fn shard(&mut self, k: usize, head: &Map<String, Value>) -> Result<u64> {
        let (n, count_key) = (self.n, self.kind.count_key);
        let field = head.get("spec").and_then(|s| s.get("shard"));
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
                    &self.name(k),
                    "spec.shard",
                    field,
                    &format!(
                        "\"i/{n}\" with i in 0 ..= {} (spec.{count_key} = {n})",
                        n - 1
                    ),
                )
            })?;
        if head.get("model") != Some(&self.model_json) {
            return Err(bad(format!(
                "{}: model = {} differs from {}'s {}: the shards are of one run",
                self.name(k),
                check::shown(head.get("model")),
                self.name(0),
                check::shown(Some(&self.model_json))
            )));
        }
        if spec_of(head, &self.name(k), self.kind.what)? != self.spec
            || head.get("params") != Some(&self.params_json)
        {
            return Err(bad(format!(
                "{} belongs to a different {} (its spec or params differ from {}'s)",
                self.name(k),
                self.kind.what,
                self.name(0)
            )));
        }
        // Bounded: shard < n checked above.
        if std::mem::replace(&mut self.seen_shards[shard as usize], true) {
            return Err(bad(format!(
                "{}: shard {shard}/{n} is given twice",
                self.name(k)
            )));
        }
        Ok(shard)
    }

    /// The refusal of input `k` (shard `shard`), which has no items array.
    pub fn no_items(&self, k: usize, shard: u64) -> SolverError {
        bad(format!(
            "{} (shard {shard}/{}) has no `{}` array",
            self.name(k),
            self.n,
            self.kind.items
        ))
    }

    /// Checks one item of input `k` (shard `shard`) and returns its place
    /// in the merged output (`0 .. len()`).
    pub fn item(&mut self, k: usize, shard: u64, v: &Value) -> Result<usize> {
        let name = self.name(k);
        let n = self.n;
        let place = match &mut self.grid {
            Grid::Sweep {
                points_n,
                chains,
                grid,
                directions,
                shape,
                totals,
            } => {
                let place = sweep_place(v, &name, shard, (*points_n, *chains), grid, *directions)?;
                let (slot, where_) = place;
                if self.seen[slot] {
                    return Err(bad(format!("{where_} is given twice")));
                }
                check::sweep_point(v, shape, &where_)?;
                totals.add(v);
                slot
            }
            Grid::Map {
                rows,
                columns,
                record_periods,
                grid,
            } => {
                let (slot, where_) = map_place(v, &name, (shard, n), (*rows, *columns), grid)?;
                if self.seen[slot] {
                    return Err(bad(format!("{where_} is given twice")));
                }
                check::map_cell(v, *record_periods, &where_)?;
                slot
            }
        };
        self.seen[place] = true;
        Ok(place)
    }

    /// Checks that every shard and every place of the grid was given and
    /// returns the merged output's fields before its items: `model`,
    /// `params`, `spec` (that of the unsharded run) and, for a sweep,
    /// `stats` (the totals of its points).
    pub fn finish(self) -> Result<Map<String, Value>> {
        let (n, count_key) = (self.n, self.kind.count_key);
        if let Some(missing) = self.seen_shards.iter().position(|s| !s) {
            return Err(bad(format!(
                "shard {missing}/{n} is missing ({count_key} = {n}, {} given)",
                self.names.len()
            )));
        }
        let mut head = Map::new();
        head.insert("model".into(), self.model_json);
        head.insert("params".into(), self.params_json);
        let mut spec = self.spec;
        match self.grid {
            Grid::Sweep {
                points_n,
                directions,
                totals,
                ..
            } => {
                if let Some(slot) = self.seen.iter().position(|s| !s) {
                    let (d, index) = (slot / points_n as usize, slot % points_n as usize);
                    let direction = directions.list()[d];
                    let index = match direction {
                        Direction::Down => points_n as usize - 1 - index,
                        _ => index,
                    };
                    return Err(bad(format!(
                        "point {index} ({}) is missing from the shards",
                        direction.name()
                    )));
                }
                head.insert("spec".into(), Value::Object(spec));
                let stats = totals
                    .finish()
                    .ok_or_else(|| bad("the shards' work counters overflow when summed".into()))?;
                head.insert("stats".into(), stats);
            }
            Grid::Map { columns, .. } => {
                if let Some(slot) = self.seen.iter().position(|s| !s) {
                    return Err(bad(format!(
                        "cell (row {}, column {}) is missing from the shards",
                        slot as u64 / columns,
                        slot as u64 % columns
                    )));
                }
                // The merged map is the unsharded one.
                spec.insert("shards".into(), json!(1));
                head.insert("spec".into(), Value::Object(spec));
            }
        }
        Ok(head)
    }
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

/// A sweep's grid from its spec.
fn sweep_grid(spec: &Map<String, Value>, model: &Model, at0: &str) -> Result<Grid> {
    let points_n = spec_count(spec, "points", u64::from(solver::sweep::MAX_POINTS), at0)?;
    let chains = spec_count(spec, "chains", points_n, at0)?;
    let grid = SweepSpec::new(
        spec_f64(spec, "omega_from", at0)?,
        spec_f64(spec, "omega_to", at0)?,
        points_n as u32,
    );
    let directions = spec
        .get("direction")
        .and_then(Value::as_str)
        .and_then(solver::sweep::Directions::from_name)
        .ok_or_else(|| {
            check::refuse(
                at0,
                "spec.direction",
                spec.get("direction"),
                "up, down or both",
            )
        })?;
    Ok(Grid::Sweep {
        points_n,
        chains,
        grid,
        directions,
        shape: sweep_shape(spec, model, at0)?,
        totals: Totals::new(false),
    })
}

/// Where a sweep point goes: its place in the merged output (the
/// directions in the order swept, up by rising index, down by falling
/// index) and its description for messages.
fn sweep_place(
    p: &Value,
    name: &str,
    shard: u64,
    (points_n, chains): (u64, u64),
    grid: &SweepSpec,
    directions: Directions,
) -> Result<(usize, String)> {
    let index = p.get("index").and_then(Value::as_u64);
    let direction = p
        .get("direction")
        .and_then(Value::as_str)
        .and_then(Direction::from_name);
    let omega = p.get("omega").and_then(Value::as_f64);
    let where_ = format!(
        "{name}: a point of shard {shard}/{chains} (index {}, direction {}, omega {})",
        index.map_or("missing".into(), |i| i.to_string()),
        direction.map_or("missing", Direction::name),
        omega.map_or("missing".into(), |o| o.to_string()),
    );
    let (Some(index), Some(direction), Some(omega)) = (index, direction, omega) else {
        return Err(bad(format!("{where_} lacks its index, direction or omega")));
    };
    let d = directions
        .list()
        .iter()
        .position(|&x| x == direction)
        .ok_or_else(|| {
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
    let rank = match direction {
        Direction::Down => points_n - 1 - index,
        _ => index,
    };
    Ok((d * points_n as usize + rank as usize, where_))
}

/// A map's grid from its spec.
fn map_grid(spec: &Map<String, Value>, at0: &str) -> Result<Grid> {
    spec_count(spec, "shards", MAX_SHARDS, at0)?;
    let columns = spec_count(spec, "omega_points", 2000, at0)?;
    let rows = spec_count(spec, "value_points", 2000, at0)?;
    if columns < 2 {
        return Err(check::refuse(
            at0,
            "spec.omega_points",
            spec.get("omega_points"),
            "a whole number 2 ..= 2000",
        ));
    }
    let record_periods = check::whole(
        spec,
        "record_periods",
        (1, MAX_RECORD),
        &check::At(at0, "spec.".into()),
    )?;
    let grid = solver::map::MapSpec::new(
        (
            spec_f64(spec, "omega_from", at0)?,
            spec_f64(spec, "omega_to", at0)?,
            columns as u32,
        ),
        "",
        (
            spec_f64(spec, "value_from", at0)?,
            spec_f64(spec, "value_to", at0)?,
            rows as u32,
        ),
    );
    Ok(Grid::Map {
        rows,
        columns,
        record_periods,
        grid,
    })
}

/// Where a map cell goes (row by row) and its description for messages.
fn map_place(
    c: &Value,
    name: &str,
    (shard, n): (u64, u64),
    (rows, columns): (u64, u64),
    grid: &solver::map::MapSpec,
) -> Result<(usize, String)> {
    let row = c.get("row").and_then(Value::as_u64);
    let column = c.get("column").and_then(Value::as_u64);
    let omega = c.get("omega").and_then(Value::as_f64);
    let value = c.get("value").and_then(Value::as_f64);
    let where_ = format!(
        "{name}: a cell of shard {shard}/{n} (row {}, column {})",
        row.map_or("missing".into(), |i| i.to_string()),
        column.map_or("missing".into(), |i| i.to_string()),
    );
    let (Some(row), Some(column), Some(omega), Some(value)) = (row, column, omega, value) else {
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
    Ok(((row * columns + column) as usize, where_))
}

/// The default names of unnamed inputs: "input 1", "input 2", ...
fn input_names(n: usize) -> Vec<String> {
    (1..=n).map(|k| format!("input {k}")).collect()
}

/// Merges whole shards held in memory (the page's two halves, tests) with
/// [`Merge`]: the merged output, its items in their places.
fn merge_values(shards: &[Value], names: &[String], items: &str) -> Result<Value> {
    let mut names = names.to_vec();
    names.extend(input_names(shards.len()).into_iter().skip(names.len()));
    names.truncate(shards.len().max(1));
    let head = |k: usize, v: &Value| -> Result<Map<String, Value>> {
        match v {
            Value::Object(o) => Ok(o
                .iter()
                .filter(|(key, _)| *key != items)
                .map(|(key, v)| (key.clone(), v.clone()))
                .collect()),
            _ => Err(bad(format!(
                "{}: not a JSON object: is it gearshock output?",
                keys::truncate(&names[k], 80)
            ))),
        }
    };
    let first = shards
        .first()
        .ok_or_else(|| bad("merge needs at least one shard".into()))?;
    let mut merge = Merge::new(&head(0, first)?, items, names.clone())?;
    let mut placed: Vec<(usize, &Value)> = Vec::new();
    for (k, sh) in shards.iter().enumerate() {
        let shard = merge.shard(k, &head(k, sh)?)?;
        let Some(Value::Array(list)) = sh.get(items) else {
            return Err(merge.no_items(k, shard));
        };
        for v in list {
            placed.push((merge.item(k, shard, v)?, v));
        }
    }
    let mut out = merge.finish()?;
    placed.sort_by_key(|&(place, _)| place);
    out.insert(
        items.into(),
        Value::Array(placed.into_iter().map(|(_, v)| v.clone()).collect()),
    );
    Ok(Value::Object(out))
}

/// Merges the JSON outputs of the shards `0/n .. n-1/n` of one sweep into the
/// JSON of the unsharded run with `chains = n` ([`Merge`] says what is
/// checked). Numbers are copied as read (serde_json reads them back
/// exactly, `float_roundtrip`), so the result is the unsharded run's output
/// byte for byte.
pub fn merge_shards(shards: &[Value]) -> Result<Value> {
    merge_sweep_files(shards, &input_names(shards.len()))
}

/// [`merge_shards`], messages naming each input by `names` (its file).
pub fn merge_sweep_files(shards: &[Value], names: &[String]) -> Result<Value> {
    merge_values(shards, names, "points")
}

/// Merges the shards `0/n .. n-1/n` of one regime map into the unsharded
/// map ([`Merge`] says what is checked).
pub fn merge_maps(shards: &[Value]) -> Result<Value> {
    merge_map_files(shards, &input_names(shards.len()))
}

/// [`merge_maps`], messages naming each input by `names` (its file).
pub fn merge_map_files(shards: &[Value], names: &[String]) -> Result<Value> {
    merge_values(shards, names, "cells")
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
