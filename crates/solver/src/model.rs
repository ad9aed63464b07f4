//! The compiled model every computation starts from: the mesh system, its
//! natural modes and the loaded static equilibrium, built once from the
//! parameters, with the bound past which a response counts as diverged.

use crate::dynamics::MeshOde;
use crate::error::{Result, SolverError};
use crate::modal::{self, Modes, StaticSolution};
use crate::ode::Dopri5;
use crate::params::ModelParams;
use crate::system::MeshSystem;

/// A compiled model with its modes and static equilibrium, computed once.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    /// The system.
    pub system: MeshSystem,
    /// Natural modes of the mean-stiffness system.
    pub modes: Modes,
    /// The loaded static equilibrium.
    pub statics: StaticSolution,
}

impl Model {
    /// Validates the parameters and prepares the model.
    pub fn new(params: &ModelParams) -> Result<Self> {
        let system = MeshSystem::build(params)?;
        let modes = modal::modes(&system)?;
        let statics = modal::statics(&system, &modes)?;
        Ok(Model {
            system,
            modes,
            statics,
        })
    }

    /// The static equilibrium as an ODE state (at rest).
    pub fn static_state(&self) -> Vec<f64> {
        let mut y = self.statics.q.clone();
        y.extend(std::iter::repeat_n(0.0, self.system.dof()));
        y
    }

    /// Whether the model is linear: no mesh has backlash, so every mesh
    /// force is linear in the deflection (the teeth never part, there is
    /// no gap to cross) and the motion cannot be chaotic.
    pub fn is_linear(&self) -> bool {
        self.system.meshes.iter().all(|m| m.backlash_m == 0.0)
    }

    /// The resonances in `[from, to]`: the distinct elastic natural
    /// frequencies `omega_k / j` for `j = 1 ..= min(harmonics, 3)` (Omega
    /// or one of its first three multiples, which the mesh stiffness and
    /// the impacts excite, meeting a natural frequency), as the primary
    /// ones (`j = 1`) and the superharmonic ones. Where a response turns,
    /// folds, changes contact and doubles its period, so what a branch or
    /// a boundary trace over the range costs grows with them.
    pub fn resonances(&self, harmonics: usize, from: f64, to: f64) -> (usize, usize) {
        let mut found: Vec<(f64, usize)> = Vec::new();
        for mode in self.modes.elastic() {
            for j in 1..=harmonics.min(3) {
                let w = mode.omega / j as f64;
                if (from..=to).contains(&w) && !found.iter().any(|f| (f.0 - w).abs() <= 1e-6 * w) {
                    found.push((w, j));
                }
            }
        }
        let primary = found.iter().filter(|f| f.1 == 1).count();
        (primary, found.len() - primary)
    }

    /// The largest mesh deflection (m) a bounded response is taken to reach:
    /// [`DIVERGENCE_FACTOR`] times the model's own scale (the largest of any
    /// mesh's static deflection plus backlash plus TE, at least 1 um), raised
    /// in proportion under light damping (below a damping ratio of 0.05,
    /// where a resonance amplifies more).
    ///
    /// Forcing and backlash are bounded and damping is not negative, so only
    /// a parametric instability of the time-varying stiffness (the motion's
    /// growth outruns the dead zone, beyond which the force law is linear)
    /// carries a response past it, well before the integrator overflows.
    pub fn divergence_bound_m(&self) -> f64 {
        let meshes = &self.system.meshes;
        let scale = meshes
            .iter()
            .zip(&self.statics.mesh_deflection_m)
            .map(|(m, d)| {
                let higher: f64 = m.te_harmonics_m.iter().map(|[c, s]| c.hypot(*s)).sum();
                d.abs() + m.backlash_m + m.te_mean_m.abs() + m.te_cos_m.hypot(m.te_sin_m) + higher
            })
            .fold(1e-6, f64::max);
        let zeta_min = meshes
            .iter()
            .map(|m| m.damping_n_s_m / (2.0 * (m.stiffness_mean_n_m * m.equivalent_mass_kg).sqrt()))
            .fold(f64::INFINITY, f64::min)
            .max(1e-4);
        DIVERGENCE_FACTOR * scale * (0.05 / zeta_min).max(1.0)
    }

    /// [`SolverError::Diverged`] if a mesh deflection of state `y` at `t_s`
    /// exceeds `bound_m` (or is not finite).
    pub(crate) fn check_bounded(
        &self,
        ode: &MeshOde,
        t_s: f64,
        y: &[f64],
        bound_m: f64,
    ) -> Result<()> {
        let q = &y[..self.system.dof()];
        for (j, m) in self.system.meshes.iter().enumerate() {
            let delta_m = ode.deflection(j, q);
            if delta_m.abs() > bound_m || !delta_m.is_finite() {
                return Err(SolverError::Diverged {
                    mesh: m.name.clone(),
                    delta_m,
                    bound_m,
                    t_s,
                });
            }
        }
        Ok(())
    }

    /// An integrator failure, or [`SolverError::Diverged`] if the state it
    /// stopped in had already left the bounded range (the failure is then
    /// the growth's consequence, not its cause).
    pub(crate) fn explain_failure(
        &self,
        ode: &MeshOde,
        int: &Dopri5,
        e: SolverError,
    ) -> SolverError {
        match self.check_bounded(ode, int.t(), int.y(), self.divergence_bound_m()) {
            Err(diverged) => diverged,
            Ok(()) => e,
        }
    }
}

/// How many times the model's deflection scale a mesh deflection may reach
/// before the response counts as unbounded ([`Model::divergence_bound_m`]).
pub(crate) const DIVERGENCE_FACTOR: f64 = 100.0;
