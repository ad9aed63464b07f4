//! Field checks of merged input: every field of every point or cell of a
//! shard is one gearshock writes (its type, whole-number counters, array
//! lengths equal to the spec's `record_periods`, names it knows), or the
//! merge is refused with a message naming the field, its value (cut to a
//! few dozen characters) and what is allowed.

use serde_json::{Map, Value};
use solver::error::{Result, SolverError};
use solver::keys;
use solver::steady::Impact;

/// Largest work counter one merged point may carry: 2^53, the largest
/// integer every JSON reader holds exactly.
pub const MAX_COUNTER: u64 = 1 << 53;

/// Longest failure message a point or cell may carry (characters).
pub const MAX_MESSAGE: usize = 2000;

/// A value as shown in a message: its JSON text, cut.
pub fn shown(v: Option<&Value>) -> String {
    v.map_or_else(
        || "missing".to_string(),
        |v| keys::truncate(&v.to_string(), 40),
    )
}

/// A refusal: `where_: field = value is out of range: allowed ...`.
pub fn refuse(where_: &str, field: &str, v: Option<&Value>, allowed: &str) -> SolverError {
    SolverError::Parse(format!(
        "{where_}: {field} = {} is out of range: allowed {allowed}",
        shown(v)
    ))
}

/// A whole number in `lo ..= hi`.
pub fn whole(o: &Map<String, Value>, key: &str, (lo, hi): (u64, u64), at: &At) -> Result<u64> {
    let v = o.get(key);
    v.and_then(Value::as_u64)
        .filter(|x| (lo..=hi).contains(x))
        .ok_or_else(|| {
            refuse(
                at.0,
                &at.field(key),
                v,
                &format!("a whole number {lo} ..= {hi}"),
            )
        })
}

/// A number (finite) or `null` (what gearshock writes for a non-finite one).
fn number_or_null(o: &Map<String, Value>, key: &str, at: &At) -> Result<()> {
    match o.get(key) {
        Some(Value::Null) => Ok(()),
        Some(Value::Number(n)) if n.as_f64().is_some_and(f64::is_finite) => Ok(()),
        v => Err(refuse(at.0, &at.field(key), v, "a number or null")),
    }
}

/// An array of exactly `len` numbers (or nulls).
fn numbers(o: &Map<String, Value>, key: &str, len: u64, at: &At) -> Result<()> {
    let v = o.get(key);
    let Some(Value::Array(a)) = v else {
        return Err(refuse(at.0, &at.field(key), v, "an array of numbers"));
    };
    if a.len() as u64 != len {
        return Err(SolverError::Parse(format!(
            "{}: {} has {} entries: allowed exactly {len} (the spec's record_periods)",
            at.0,
            at.field(key),
            a.len()
        )));
    }
    for x in a {
        if !(x.is_null() || x.as_f64().is_some_and(f64::is_finite)) {
            return Err(refuse(
                at.0,
                &at.field(key),
                Some(x),
                "numbers or nulls in the array",
            ));
        }
    }
    Ok(())
}

/// An impact regime's name.
fn impact(o: &Map<String, Value>, key: &str, at: &At) -> Result<()> {
    let v = o.get(key);
    if v.and_then(Value::as_str)
        .and_then(Impact::from_name)
        .is_some()
    {
        return Ok(());
    }
    Err(refuse(
        at.0,
        &at.field(key),
        v,
        "none, single-sided, double-sided or no-contact",
    ))
}

/// A failure message: a string of at most [`MAX_MESSAGE`] characters.
fn message(o: &Map<String, Value>, key: &str, at: &At) -> Result<()> {
    let v = o.get(key);
    match v.and_then(Value::as_str) {
        Some(s) if s.chars().count() <= MAX_MESSAGE => Ok(()),
        _ => Err(refuse(
            at.0,
            &at.field(key),
            v,
            &format!("a message of at most {MAX_MESSAGE} characters"),
        )),
    }
}

/// The object's keys are exactly `keys` (in any order).
fn exact_keys(o: &Map<String, Value>, keys_: &[&str], at: &At) -> Result<()> {
    if let Some(extra) = o.keys().find(|k| !keys_.contains(&k.as_str())) {
        return Err(SolverError::Parse(format!(
            "{}: field {} is not one gearshock writes here (allowed: {})",
            at.0,
            at.field(&keys::truncate(extra, 40)),
            keys_.join(", ")
        )));
    }
    if let Some(missing) = keys_.iter().find(|k| !o.contains_key(**k)) {
        return Err(SolverError::Parse(format!(
            "{}: field {} is missing",
            at.0,
            at.field(missing)
        )));
    }
    Ok(())
}

/// Where a check is: the item's description and the path of the object
/// checked inside it (`""` at the top, `"meshes.s1a."` below).
pub struct At<'a>(pub &'a str, pub String);

impl At<'_> {
    fn field(&self, key: &str) -> String {
        format!("{}{key}", self.1)
    }

    fn object<'v>(&self, v: &'v Value, key: &str) -> Result<&'v Map<String, Value>> {
        match v {
            Value::Object(o) => Ok(o),
            _ => Err(refuse(self.0, &self.field(key), Some(v), "an object")),
        }
    }
}

/// What a sweep's points must hold, from its spec and model.
pub struct SweepShape {
    /// The spec's `record_periods`: the length of every Poincaré array.
    pub record_periods: u64,
    /// The spec's `transient_periods`: with the probes' periods (see
    /// [`sweep_point`]), the most any point ran.
    pub transient_periods: u64,
    /// The meshes the spec asks for, by name.
    pub meshes: Vec<String>,
    /// Every mesh of the model, by name (`worst_mesh` is one of them).
    pub model_meshes: Vec<String>,
}

const POINT_HEAD: [&str; 3] = ["omega", "index", "direction"];
const MESH_FIELDS: [&str; 11] = [
    "poincare_x_m",
    "poincare_x_velocity_m_s",
    "x_min_m",
    "x_max_m",
    "x_amplitude_m",
    "poincare_delta_m",
    "poincare_velocity_m_s",
    "delta_min_m",
    "delta_max_m",
    "impact",
    "dynamic_factor",
];
const STATS: [&str; 9] = [
    "transient_periods_run",
    "settled",
    "steps",
    "rejected_steps",
    "event_retakes",
    "rhs_evaluations",
    "contact_switches",
    "shooting_attempts",
    "shooting_steps",
];

/// The names a point's `motion` may take (`solver::steady::Motion::name`).
const MOTIONS: [&str; 5] = solver::steady::Motion::NAMES;

/// One mesh's fields of a sweep point.
fn point_mesh(o: &Map<String, Value>, shape: &SweepShape, at: &At) -> Result<()> {
    numbers(o, "poincare_x_m", shape.record_periods, at)?;
    numbers(o, "poincare_x_velocity_m_s", shape.record_periods, at)?;
    number_or_null(o, "x_min_m", at)?;
    number_or_null(o, "x_max_m", at)?;
    number_or_null(o, "x_amplitude_m", at)?;
    numbers(o, "poincare_delta_m", shape.record_periods, at)?;
    numbers(o, "poincare_velocity_m_s", shape.record_periods, at)?;
    number_or_null(o, "delta_min_m", at)?;
    number_or_null(o, "delta_max_m", at)?;
    impact(o, "impact", at)?;
    number_or_null(o, "dynamic_factor", at)
}

/// Checks every field of one sweep point (its place on the grid is the
/// caller's): exactly the fields gearshock writes, each of its type and
/// range.
pub fn sweep_point(p: &Value, shape: &SweepShape, where_: &str) -> Result<()> {
    let top = At(where_, String::new());
    let o = top.object(p, "point")?;
    if o.contains_key("error") {
        exact_keys(o, &[&POINT_HEAD[..], &["error"]].concat(), &top)?;
        return message(o, "error", &top);
    }
    let mut fields: Vec<&str> = POINT_HEAD.to_vec();
    if let [_] = shape.meshes[..] {
        fields.extend(MESH_FIELDS);
    } else {
        fields.push("meshes");
    }
    fields.extend([
        "impact_worst",
        "worst_mesh",
        "period",
        "exact",
        "max_multiplier_modulus",
        "motion",
        "lyapunov_per_period",
        "stats",
    ]);
    exact_keys(o, &fields, &top)?;
    if let [_] = shape.meshes[..] {
        point_mesh(o, shape, &top)?;
    } else {
        let meshes = top.object(&o["meshes"], "meshes")?;
        let names: Vec<&str> = shape.meshes.iter().map(String::as_str).collect();
        exact_keys(meshes, &names, &At(where_, "meshes.".into()))?;
        for name in &shape.meshes {
            let at = At(where_, format!("meshes.{name}."));
            point_mesh(at.object(&meshes[name], "")?, shape, &at)?;
        }
    }
    impact(o, "impact_worst", &top)?;
    let worst = o.get("worst_mesh");
    if !worst
        .and_then(Value::as_str)
        .is_some_and(|w| shape.model_meshes.iter().any(|m| m == w))
    {
        return Err(refuse(
            where_,
            "worst_mesh",
            worst,
            &format!("a mesh of the model ({})", shape.model_meshes.join(", ")),
        ));
    }
    period(o, shape.record_periods, &top)?;
    motion_fields(o, &top, where_)?;
    let at = At(where_, "stats.".into());
    let stats = at.object(&o["stats"], "")?;
    exact_keys(stats, &STATS, &at)?;
    // A Lyapunov probe that finds no chaos hands its recorded periods back
    // to the transient: each of at most `MAX_PROBES` adds up to a record.
    let probes = u64::from(solver::steady::MAX_PROBES);
    whole(
        stats,
        "transient_periods_run",
        (0, shape.transient_periods + probes * shape.record_periods),
        &at,
    )?;
    if !stats["settled"].is_boolean() {
        return Err(refuse(
            where_,
            "stats.settled",
            stats.get("settled"),
            "true or false",
        ));
    }
    for key in &STATS[2..] {
        whole(stats, key, (0, MAX_COUNTER), &at)?;
    }
    Ok(())
}

/// The classification's fields of a point or cell: `exact` (a boolean),
/// `max_multiplier_modulus` and `lyapunov_per_period` (numbers or null),
/// `motion` (one of [`MOTIONS`]), and that they agree as gearshock writes
/// them: an orbit is exact exactly when its motion is `periodic-exact`,
/// and only an exact orbit has multipliers, which are inside the unit
/// circle (an unstable orbit is never a steady state's verdict).
fn motion_fields(o: &Map<String, Value>, top: &At, where_: &str) -> Result<()> {
    if !o["exact"].is_boolean() {
        return Err(refuse(where_, "exact", o.get("exact"), "true or false"));
    }
    number_or_null(o, "max_multiplier_modulus", top)?;
    number_or_null(o, "lyapunov_per_period", top)?;
    if !o["motion"].as_str().is_some_and(|m| MOTIONS.contains(&m)) {
        return Err(refuse(
            where_,
            "motion",
            o.get("motion"),
            &format!("one of {}", MOTIONS.join(", ")),
        ));
    }
    let exact = o["motion"] == EXACT;
    if o["exact"] != exact {
        return Err(refuse(
            where_,
            "exact",
            o.get("exact"),
            &format!("{exact} with motion {}", shown(o.get("motion"))),
        ));
    }
    let modulus = o.get("max_multiplier_modulus");
    let stable_limit = 1.0 + solver::shooting::floquet::STABILITY_MARGIN;
    let agrees = match modulus.and_then(Value::as_f64) {
        Some(m) => exact && m <= stable_limit,
        None => !exact,
    };
    if !agrees {
        let allowed = if exact {
            format!("a number at most {stable_limit} (a stable orbit) with motion {EXACT}")
        } else {
            format!("null with motion {}", shown(o.get("motion")))
        };
        return Err(refuse(where_, "max_multiplier_modulus", modulus, &allowed));
    }
    Ok(())
}

/// The motion of an orbit found by shooting.
const EXACT: &str = "periodic-exact";

/// `period`: `null` (not periodic within the record) or a whole number of
/// mesh periods no longer than the record.
fn period(o: &Map<String, Value>, record_periods: u64, at: &At) -> Result<()> {
    if o.get("period").is_some_and(Value::is_null) {
        return Ok(());
    }
    whole(o, "period", (1, record_periods.max(1)), at).map(|_| ())
}

/// Checks every field of one map cell (its place on the grid is the
/// caller's).
pub fn map_cell(c: &Value, record_periods: u64, where_: &str) -> Result<()> {
    let top = At(where_, String::new());
    let o = top.object(c, "cell")?;
    exact_keys(
        o,
        &[
            "row",
            "column",
            "omega",
            "value",
            "impact",
            "period",
            "exact",
            "max_multiplier_modulus",
            "motion",
            "lyapunov_per_period",
            "error",
        ],
        &top,
    )?;
    period(o, record_periods, &top)?;
    motion_fields(o, &top, where_)?;
    // A cell's period is its motion's: a periodic one has it, no other.
    let periodic = matches!(o["motion"].as_str(), Some(EXACT | "periodic"));
    if o["period"].is_null() == periodic {
        let allowed = if periodic {
            "a whole number with a periodic motion"
        } else {
            "null with a motion that is not periodic"
        };
        return Err(refuse(where_, "period", o.get("period"), allowed));
    }
    if o["error"].is_null() {
        impact(o, "impact", &top)
    } else if o["impact"].is_null() {
        message(o, "error", &top)?;
        if o["motion"] == "not-periodic" {
            Ok(())
        } else {
            Err(refuse(
                where_,
                "motion",
                o.get("motion"),
                "not-periodic in a failed cell",
            ))
        }
    } else {
        Err(refuse(
            where_,
            "impact",
            o.get("impact"),
            "null in a failed cell",
        ))
    }
}
