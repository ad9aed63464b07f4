//! `gearshock frf --method shooting` as JSON: the harmonic-balance
//! response's `branch` shape (`omega`, `stable`, `bifurcation`, the mesh's
//! extremes) plus each point's `period`, and its `restarts` and `left_out`
//! as the harmonic balance writes them.

use super::{branch_point_json, mesh_names, num};
use serde_json::{json, Value};
use solver::keys;
use solver::orbits::{ShootPoint, ShootingContinuation};
use solver::params::ModelParams;
use solver::{Model, SolverError};

/// A whole shooting frequency response.
pub fn shooting_frf_json(
    model: &Model,
    params: &ModelParams,
    c: &ShootingContinuation,
    branch: &[ShootPoint],
    meshes: &[usize],
    error: Option<&SolverError>,
) -> Value {
    let names = mesh_names(model, meshes);
    let spec = c.spec();
    let s = c.stats;
    json!({
        "model": model.system.model.name(),
        "params": Value::Object(keys::to_json(params)),
        "omega_ref_rad_s": num(model.system.omega_ref_rad_s),
        "spec": {
            "method": "shooting",
            "omega_from": num(spec.omega_from),
            "omega_to": num(spec.omega_to),
            "points": spec.points,
            "direction": spec.direction.name(),
            "period": spec.period,
            "switch_branches": spec.switch_branches,
            "rtol": num(spec.shooting.rtol),
            "atol_m": num(spec.shooting.atol_m),
        },
        "meshes": names,
        // Complete only where the first branch covers the whole range.
        "complete": error.is_none() && c.is_complete(),
        "restarts": c.restarts().iter().map(|r| json!({
            "piece": r.piece,
            "reason": r.reason.name(),
            "stopped_at_omega": num(r.stopped_at),
            "start_omega": num(r.start_omega),
            "direction": r.direction.name(),
        })).collect::<Vec<_>>(),
        "left_out": c.left_out().iter().map(|l| json!({
            "omega_from": num(l.from),
            "omega_to": num(l.to),
            "reason": l.reason_name(),
        })).collect::<Vec<_>>(),
        "notes": c.notes(),
        "error": error.map_or(Value::Null, |e| Value::from(e.to_string())),
        "branch": branch.iter().map(|p| {
            let mut v = branch_point_json(model, &p.point, meshes);
            v["period"] = json!(p.period);
            v
        }).collect::<Vec<_>>(),
        "stats": {
            "points": s.points,
            "newton_iterations": s.newton_iterations,
            "rejected_steps": s.rejected_steps,
            "integrator_steps": s.integrator_steps,
            "work_steps": s.work_steps,
        },
    })
}
