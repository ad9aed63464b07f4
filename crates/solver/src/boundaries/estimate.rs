//! What a boundary trace will cost, in the work units of
//! [`crate::hbm::HbmCost`], before it starts: a caller checks it against
//! a budget, and [`super::BoundaryStats::work`] counts the same units as
//! the trace runs.
//!
//! The curves start where the seeding branches fold, change contact or
//! double their period, and those happen near the resonances: where Omega
//! or one of its first three multiples (the harmonics the mesh stiffness
//! and the impacts excite) meets a natural frequency. So the estimate
//! counts the resonances in the Omega range, `R` (distinct elastic
//! frequencies `omega_k / j` for `j = 1 ..= min(H, 3)`), and takes
//! `3 R + 2` curves of `(1 + R / 2) points + 40` points each (at most a
//! curve's point budget): a model with more modes in the range has more
//! curves, and longer ones, as they wind past more resonances. A point
//! costs some three corrector iterations, each an evaluation with its
//! Jacobian, a residual and two assemblies (the point and its neighbour
//! in the key), a fold's three more Jacobians (two along its null vector,
//! one in the key) and a period doubling's four monodromies (the test and
//! its three directional differences); six points in ten lie on contact
//! curves, three on folds, one on a period doubling. The seeding branches
//! add `levels` branches of `points + 60 R` points.
//!
//! Measured (`gearshock boundaries`, `stats.work_units`), the estimate was
//! within a factor of 2.5 of the work on both models, from the gear pair's
//! TE box (7 curves) to the compound set's backlash box over Omega 0.1-2
//! (81 curves); `crates/solver/tests/boundaries.rs` checks it on small
//! boxes of both.

use super::BoundarySpec;
use crate::error::Result;
use crate::hbm::{Assembly, HbmCost, HbmModel};
use crate::model::Model;
use crate::params::ModelParams;
use crate::system::MeshSystem;

/// Corrector iterations per curve point.
const ITERATIONS: f64 = 3.0;
/// Newton iterations per point of a seeding branch.
const BRANCH_ITERATIONS: f64 = 3.3;
/// Seeding branch points per resonance in the range.
const BRANCH_POINTS_PER_RESONANCE: f64 = 60.0;

impl BoundarySpec {
    /// The estimated work units of the whole trace on `base` (see the
    /// module's doc); bad options fail as [`super::BoundaryTrace::new`]
    /// fails on them.
    pub fn estimated_work(&self, base: &ModelParams) -> Result<f64> {
        self.validate(base)?;
        let model = Model::new(base)?;
        let hbm = HbmModel::from_system(&MeshSystem::build(base)?, self.symmetric)?;
        let cost = HbmCost::of(&hbm, Assembly::harmonics(self.harmonics, self.method));
        let (primary, superharmonic) =
            model.resonances(self.harmonics, self.omega_from, self.omega_to);
        let r = (primary + superharmonic) as f64;
        let points = f64::from(self.points);
        let monodromy = cost.mean_monodromy(self.omega_from, self.omega_to);
        let branch_points = points + BRANCH_POINTS_PER_RESONANCE * r;
        let levels = f64::from(self.levels)
            * branch_points
            * (BRANCH_ITERATIONS * cost.newton_iteration() + monodromy);
        let n = cost.unknowns();
        let contact =
            cost.jacobian() + cost.residual() + 2.0 * cost.assembly() + HbmCost::factor(n + 3);
        let fold = contact + 3.0 * cost.jacobian() + 2.0 * HbmCost::factor(n + 1);
        let doubling = contact + 4.0 * monodromy;
        // A map's trace of one mesh keeps that mesh's contact curves only.
        let contact_share = match self.contact_mesh {
            Some(_) => 0.6 / hbm.channels.len().max(1) as f64,
            None => 0.6,
        };
        let per_point = ITERATIONS * (contact_share * contact + 0.3 * fold + 0.1 * doubling);
        let curves = 3.0 * r + 2.0;
        let budget = 2.0 * super::trace::max_steps(1.0 / points) as f64;
        let curve_points = ((1.0 + 0.5 * r) * points + 40.0).min(budget);
        Ok(levels + curves * curve_points * per_point)
    }
}
