//! `gearshock bench --hbm-problem`: the harmonic-balance problem that
//! `gearshock frf` solves, printed as JSON so that another code (pyHarm, in
//! scripts/bench-pyharm.sh) can solve the same equations.
use serde_json::{json, Value};
use solver::hbm::model::Law;
use solver::hbm::HbmModel;
use solver::params::ModelParams;
use solver::steady::Model;

/// The harmonic-balance problem of `model` as JSON (see `docs/model.md`
/// and `solver::hbm::model`): in scaled modal coordinates `x` (channel
/// displacements in micrometres, time `tau = omega_ref t`, phase
/// `theta = Omega tau`),
/// `x'' + C x' + K x + sum_j n_j d_j k_j(theta) g_j(d_j . x - e_j(theta))
///  = f0 + Omega sum_j n_j c_j d_j e_j'(theta)`,
/// with `k_j = k (1 + v cos(theta + phase))` and
/// `e_j = mean + cos cos(theta + phase) + sin sin(theta + phase)`.
pub(super) fn hbm_problem(model: &Model, hbm: &HbmModel) -> Value {
    let rows = |m: &nalgebra::DMatrix<f64>| -> Vec<Vec<f64>> {
        (0..m.nrows())
            .map(|i| m.row(i).iter().copied().collect())
            .collect()
    };
    let channels: Vec<Value> = hbm
        .channels
        .iter()
        .map(|ch| {
            let names: Vec<&str> = ch
                .meshes
                .iter()
                .map(|&i| model.system.meshes[i].name.as_str())
                .collect();
            let law = match ch.law {
                Law::Mesh {
                    k,
                    variation,
                    phase_rad,
                    backlash_um,
                    te_mean_um,
                    te_cos_um,
                    te_sin_um,
                    // The default model's excitation has one harmonic.
                    ..
                } => json!({
                    "k": k, "variation": variation, "phase_rad": phase_rad,
                    "backlash_um": backlash_um, "te_mean_um": te_mean_um,
                    "te_cos_um": te_cos_um, "te_sin_um": te_sin_um,
                }),
                Law::Cubic { alpha } => json!({ "cubic_alpha": alpha }),
            };
            json!({
                "meshes": names,
                "d": ch.d,
                "multiplicity": ch.multiplicity,
                "damping": ch.damping,
                "law": law,
            })
        })
        .collect();
    json!({
        "model": "ravigneaux",
        "params": Value::Object(solver::keys::to_json(&ModelParams::default())),
        "omega_ref_rad_s": model.system.omega_ref_rad_s,
        "reduction": format!("{:?}", hbm.reduction),
        "m": hbm.m,
        "stiffness": rows(&hbm.stiffness),
        "damping": rows(&hbm.damping),
        "load": hbm.load,
        "channels": channels,
    })
}
