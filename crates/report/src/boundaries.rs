//! `gearshock boundaries` as JSON: the spec, each traced curve (its `kind`,
//! plain-words `meaning`, mesh, how its ends came about, and `points` of
//! `{omega, value, stable_side}`), the cusps, the notes and the work done.

use super::num;
use serde_json::{json, Value};
use solver::boundaries::{BoundaryTrace, Curve, TraceEnd};
use solver::keys;
use solver::params::ModelParams;
use solver::{Model, SolverError};

fn end_name(e: TraceEnd) -> &'static str {
    match e {
        TraceEnd::LeftRange => "left-range",
        TraceEnd::Closed => "closed",
        TraceEnd::Failed => "corrector-failed",
        TraceEnd::Budget => "point-budget",
    }
}

fn curve_json(model: &Model, c: &Curve) -> Value {
    json!({
        "kind": c.kind.name(),
        "meaning": c.kind.meaning(),
        "mesh": c.mesh.and_then(|j| model.system.meshes.get(j)).map(|m| m.name.clone()),
        "ends": c.ends.iter().map(|&e| end_name(e)).collect::<Vec<_>>(),
        "points": c.points.iter().map(|p| json!({
            "omega": num(p.omega),
            "value": num(p.value),
            "stable_side": p.stable_side.name(),
            "others_stable": p.others_stable,
        })).collect::<Vec<_>>(),
    })
}

/// A whole boundary trace; `error` (a solver failure that ended it) is
/// written with `complete: false`.
pub fn boundaries_json(
    model: &Model,
    params: &ModelParams,
    t: &BoundaryTrace,
    error: Option<&SolverError>,
) -> Value {
    let s = t.spec();
    json!({
        "model": model.system.model.name(),
        "params": Value::Object(keys::to_json(params)),
        "spec": {
            "key": s.key,
            "value_from": num(s.value_from),
            "value_to": num(s.value_to),
            "omega_from": num(s.omega_from),
            "omega_to": num(s.omega_to),
            "levels": s.levels,
            "points": s.points,
            "harmonics": s.harmonics,
            "method": s.method.name(),
            "contact_mesh": s.contact_mesh.and_then(|j| model.system.meshes.get(j)).map(|m| m.name.clone()),
        },
        "complete": error.is_none(),
        "error": error.map(|e| e.to_string()),
        "curves": t.curves().iter().map(|c| curve_json(model, c)).collect::<Vec<_>>(),
        "cusps": t.cusps().iter().map(|c| json!({
            "omega": num(c.omega),
            "value": num(c.value),
            "curve": c.curve,
        })).collect::<Vec<_>>(),
        "notes": t.notes(),
        "stats": {
            "level_points": t.stats.level_points,
            "curve_points": t.stats.curve_points,
            "newton_iterations": t.stats.newton_iterations,
            "work_units": t.stats.work(),
            "work_units_estimated": t.estimated_work().round() as u64,
        },
    })
}
