//! Periodic orbits found by shooting: Newton's method on `P^n(z) - z = 0`,
//! where `P` is the once-per-mesh-period Poincaré map.
//!
//! Coordinates. The train turns freely along its rigid-body mode, so the
//! positions `q` never repeat and the full monodromy would carry trivial
//! multipliers at 1. Shooting works on the elastic modal coordinates
//! instead (`docs/model.md`, "How the equations are solved"):
//! `q = sum_k z_k b_k + a u`, with `b_k` the mass-normalized elastic mode
//! shapes scaled so that a unit `z_k` moves the mesh it moves most by 1 µm,
//! and the rates likewise over omega. No mesh deflection depends on the rigid part `(a, a')`, the loads
//! are balanced over it, and the elastic forces have no component along it
//! (`u^T w_j = 0`, `K_sup u = 0`), so the elastic motion does not feel it
//! and it is carried along unchanged: the reduced map has no trivial
//! multiplier and the Newton matrix `dP^n/dz - I` is regular at a
//! hyperbolic orbit.
//!
//! - [`variational`]: `P^n` and its monodromy from the variational equations.
//! - [`newton`]: damped Newton with a backtracking line search, resumable
//!   step by step ([`ShootRun`]), and the one-shot [`shoot`].
//! - [`floquet`]: Floquet multipliers and how stability is lost.
//! - [`continuation`]: pseudo-arclength continuation in Omega of period-n
//!   orbits, with folds and period doublings located and period-doubled
//!   branches followed.

// continuation: added with the frequency response below.
pub mod floquet;
pub mod newton;
#[cfg(test)]
mod tests;
pub(crate) mod variational;

pub use floquet::{classify_multiplier, Multipliers};
pub use newton::{shoot, Orbit, ShootFailure, ShootOptions, ShootOutcome};
pub(crate) use newton::{ShootRun, MAX_SHOOT_PERIOD};

use crate::modal::ModeKind;
use crate::Model;
use std::f64::consts::PI;

/// The reduced (elastic) coordinates of a model at one mesh frequency.
#[derive(Debug, Clone)]
pub struct Reduced {
    /// Generalized coordinates.
    n: usize,
    /// Scaled elastic mode shapes `b_k`, `n` entries each.
    basis: Vec<Vec<f64>>,
    /// Their duals `d_k` with `z_k = d_k . q` (`M b_k / (b_k^T M b_k)`).
    dual: Vec<Vec<f64>>,
    /// The rigid-body mode `u` and `M u / (u^T M u)`.
    rigid: Vec<f64>,
    rigid_dual: Vec<f64>,
    /// `w_j . b_k` in µm per unit `z_k`: mesh `j`, mode `k`.
    mesh_of_mode: Vec<Vec<f64>>,
    /// The meshes' names, for messages.
    mesh_names: Vec<String>,
    /// Mesh frequency (rad/s) and period (s).
    pub(crate) omega_rad_s: f64,
    pub(crate) period_s: f64,
}

impl Reduced {
    /// The reduced coordinates of `model` at dimensionless frequency `omega`.
    pub fn new(model: &Model, omega: f64) -> Self {
        let sys = &model.system;
        let n = sys.dof();
        let omega_rad_s = omega * sys.omega_ref_rad_s;
        let mass_times = |x: &[f64]| -> Vec<f64> {
            (0..n)
                .map(|i| (0..n).map(|k| sys.mass[(i, k)] * x[k]).sum())
                .collect()
        };
        let mut basis = Vec::new();
        let mut dual = Vec::new();
        let mut mesh_of_mode = vec![Vec::new(); sys.meshes.len()];
        for mode in model.modes.modes.iter() {
            if mode.kind == ModeKind::RigidBody {
                continue;
            }
            let largest = sys
                .meshes
                .iter()
                .map(|m| m.dot(&mode.shape).abs())
                .fold(0.0, f64::max);
            // A unit coordinate moves its most deformed mesh by 1 um.
            let scale = if largest > 0.0 { 1e-6 / largest } else { 1.0 };
            let b: Vec<f64> = mode.shape.iter().map(|v| v * scale).collect();
            let mb = mass_times(&b);
            let norm: f64 = b.iter().zip(&mb).map(|(x, y)| x * y).sum();
            for (j, m) in sys.meshes.iter().enumerate() {
                mesh_of_mode[j].push(m.dot(&b) * 1e6);
            }
            dual.push(mb.iter().map(|v| v / norm).collect());
            basis.push(b);
        }
        let rigid = sys.rigid_mode.clone();
        let mu = mass_times(&rigid);
        let unorm: f64 = rigid.iter().zip(&mu).map(|(x, y)| x * y).sum();
        Reduced {
            n,
            basis,
            dual,
            rigid_dual: mu.iter().map(|v| v / unorm).collect(),
            rigid,
            mesh_of_mode,
            mesh_names: sys.meshes.iter().map(|m| m.name.clone()).collect(),
            omega_rad_s,
            period_s: 2.0 * PI / omega_rad_s,
        }
    }

    /// Dimension of the reduced state: twice the elastic modes.
    pub fn dim(&self) -> usize {
        2 * self.basis.len()
    }

    /// The name of mesh `j`.
    pub(crate) fn mesh_name(&self, j: usize) -> &str {
        self.mesh_names.get(j).map_or("?", String::as_str)
    }

    /// Dimension of the full state `(q, q')`.
    pub(crate) fn n2(&self) -> usize {
        2 * self.n
    }

    /// The full state of reduced state `z` with rigid-body position and
    /// rate `rigid`.
    pub fn to_state(&self, z: &[f64], rigid: (f64, f64)) -> Vec<f64> {
        let (m, n) = (self.basis.len(), self.n);
        let mut y = vec![0.0; 2 * n];
        for (k, b) in self.basis.iter().enumerate() {
            let (zq, zv) = (z[k], z[m + k] * self.omega_rad_s);
            for i in 0..n {
                y[i] += zq * b[i];
                y[n + i] += zv * b[i];
            }
        }
        for i in 0..n {
            y[i] += rigid.0 * self.rigid[i];
            y[n + i] += rigid.1 * self.rigid[i];
        }
        y
    }

    /// The reduced state of full state `y` and its rigid-body position and rate.
    pub fn from_state(&self, y: &[f64]) -> (Vec<f64>, (f64, f64)) {
        let n = self.n;
        let (q, v) = y.split_at(n);
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let mut z: Vec<f64> = self.dual.iter().map(|d| dot(d, q)).collect();
        z.extend(self.dual.iter().map(|d| dot(d, v) / self.omega_rad_s));
        (z, (dot(&self.rigid_dual, q), dot(&self.rigid_dual, v)))
    }

    /// The tangent vector (in the full state) of reduced coordinate `k`.
    pub(crate) fn tangent_start(&self, k: usize) -> Vec<f64> {
        let mut e = vec![0.0; self.dim()];
        e[k] = 1.0;
        self.to_state(&e, (0.0, 0.0))
    }

    /// A reduced vector's size in mesh space (µm): the largest mesh
    /// deflection and rate over omega it stands for, the Poincaré points'
    /// metric.
    pub fn mesh_norm_um(&self, z: &[f64]) -> f64 {
        let m = self.basis.len();
        self.mesh_of_mode
            .iter()
            .map(|row| {
                let d: f64 = row.iter().zip(&z[..m]).map(|(a, b)| a * b).sum();
                let r: f64 = row.iter().zip(&z[m..]).map(|(a, b)| a * b).sum();
                d.abs().max(r.abs())
            })
            .fold(0.0, f64::max)
    }
}
