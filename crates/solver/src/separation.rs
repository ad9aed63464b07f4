//! Separations in mesh space, shared by the Lyapunov exponent
//! ([`crate::lyapunov`]) and the steady run's probe (`steady::probe`): a
//! state's mesh-space point (every mesh's delta and delta'/omega in µm),
//! the distance between two, the free rigid-body rotation projected out,
//! and a neighbour at a given distance.

use crate::dynamics::MeshOde;
use crate::error::{Result, SolverError};
use crate::Model;

/// Mesh-space coordinates (um) of a state: every mesh's delta and delta'/omega.
pub(crate) fn mesh_point(ode: &MeshOde, t: f64, y: &[f64], omega_rad_s: f64, out: &mut Vec<f64>) {
    out.clear();
    for j in 0..ode.n_meshes() {
        let mi = ode.mesh_instant(j, t, y);
        out.push(mi.delta * 1e6);
        out.push(mi.delta_dot / omega_rad_s * 1e6);
    }
}

pub(crate) fn dist2(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// The rigid-body mode `phi`, `M phi` and `phi' M phi`, to remove a
/// separation along the free rotation (M-orthogonally).
#[derive(Debug, Clone)]
pub(crate) struct Rigid {
    phi: Vec<f64>,
    m_phi: Vec<f64>,
    norm: f64,
}

impl Rigid {
    pub(crate) fn of(model: &Model) -> Option<Self> {
        let sys = &model.system;
        let dof = sys.dof();
        let phi = model
            .modes
            .modes
            .iter()
            .find(|m| m.kind == crate::modal::ModeKind::RigidBody)
            .map(|m| m.shape.clone())?;
        let m_phi: Vec<f64> = (0..dof)
            .map(|i| (0..dof).map(|k| sys.mass[(i, k)] * phi[k]).sum())
            .collect();
        let norm: f64 = (0..dof).map(|i| phi[i] * m_phi[i]).sum();
        Some(Rigid { phi, m_phi, norm })
    }

    /// Removes the rigid-body component of positions and rates of `dy`.
    pub(crate) fn project_out(rigid: Option<&Self>, dy: &mut [f64]) {
        let Some(r) = rigid else { return };
        let dof = r.phi.len();
        if r.norm > 0.0 {
            for half in [0, dof] {
                let c: f64 = (0..dof).map(|i| r.m_phi[i] * dy[half + i]).sum::<f64>() / r.norm;
                for i in 0..dof {
                    dy[half + i] -= c * r.phi[i];
                }
            }
        }
    }
}

/// The neighbour of state `y0` (at time `t`) at distance `d0` (µm) in mesh
/// space: displaced along a fixed mixed direction (every coordinate,
/// positions and rates), scaled to the separation, without a rigid-body
/// component (M-orthogonally removed: a separation along the free rotation
/// is invisible in mesh space and never decays).
pub(crate) fn neighbour(
    model: &Model,
    ode: &MeshOde,
    t: f64,
    y0: &[f64],
    d0: f64,
    rigid: Option<&Rigid>,
) -> Result<Vec<f64>> {
    let sys = &model.system;
    let omega_rad_s = ode.omega_rad_s();
    let lengths = sys.dof_length_m();
    let n = y0.len();
    let dof = sys.dof();
    let mut y1 = y0.to_vec();
    for (i, v) in y1.iter_mut().enumerate() {
        let scale = if i < dof {
            lengths[i]
        } else {
            lengths[i - dof] * omega_rad_s
        };
        *v += scale * 1e-6 * (1.0 + 0.37 * i as f64).sin();
    }
    let (mut pa, mut pb) = (Vec::new(), Vec::new());
    mesh_point(ode, t, y0, omega_rad_s, &mut pa);
    mesh_point(ode, t, &y1, omega_rad_s, &mut pb);
    let d_init = dist2(&pa, &pb);
    if !(d_init > 0.0 && d_init.is_finite()) {
        return Err(SolverError::Singular {
            what: "Lyapunov: the initial perturbation has no mesh-space component".into(),
        });
    }
    for i in 0..n {
        y1[i] = y0[i] + (y1[i] - y0[i]) * d0 / d_init;
    }
    let mut dy: Vec<f64> = (0..n).map(|i| y1[i] - y0[i]).collect();
    Rigid::project_out(rigid, &mut dy);
    for i in 0..n {
        y1[i] = y0[i] + dy[i];
    }
    Ok(y1)
}
