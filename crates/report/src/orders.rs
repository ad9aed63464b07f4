//! The mesh force by order as JSON (`solver::orders`): the spectrum of
//! one mesh's force in orders of the mesh frequency with its labelled
//! peaks, and of the force summed over the planets' meshes of its kind
//! with the whole orders the phasing cancels. Part of `gearshock
//! simulate`'s output and of the page's export of a run.

use serde_json::{json, Value};
use solver::orders::{force_orders, OrderPeak};
use solver::steady::{Model, SteadyState};

use crate::num;

fn peaks_json(peaks: &[OrderPeak]) -> Value {
    Value::Array(
        peaks
            .iter()
            .map(|p| {
                json!({
                    "order": num(p.order),
                    "label": p.label,
                    "whole": p.whole,
                    "amplitude_n": num(p.amplitude_n),
                })
            })
            .collect(),
    )
}

/// Mesh `mesh`'s force by order in `ss` up to `max_order`; `null` when the
/// run kept no history of the mesh.
pub fn force_orders_json(model: &Model, ss: &SteadyState, mesh: usize, max_order: f64) -> Value {
    let sys = &model.system;
    let Some(f) = force_orders(sys, ss, mesh, max_order) else {
        return Value::Null;
    };
    let nums = |xs: &[f64]| Value::Array(xs.iter().map(|&x| num(x)).collect());
    let planets = f.planets.as_ref().map_or(Value::Null, |s| {
        json!({
            "kind": s.kind.key(),
            "meshes": s.meshes.iter().map(|&j| sys.meshes[j].name.clone()).collect::<Vec<_>>(),
            "amplitude_n": nums(&s.amplitude_n),
            "peaks": peaks_json(&s.peaks),
            "phasing_fraction": nums(&s.phasing),
            "cancelled_orders": s.cancelled,
        })
    });
    json!({
        "mesh": sys.meshes.get(mesh).map(|m| m.name.clone()),
        "record_periods": f.record_periods,
        "order": nums(&f.order),
        "amplitude_n": nums(&f.amplitude_n),
        "peaks": peaks_json(&f.peaks),
        "planet_sum": planets,
    })
}
