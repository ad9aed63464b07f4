//! `ViewId::Bif`, the bifurcation diagram: the store of the sweep's Poincaré
//! samples from both workers, the dots the plot draws, and the CSV export.

use super::{csv_num, distinct, ViewContext};
use crate::protocol::{BifSample, Motion, Regime};
use serde::Serialize;

/// One dot of the bifurcation diagram.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BifPoint {
    /// Dimensionless frequency.
    pub omega: f64,
    /// Poincaré sample of x = delta - e (um).
    pub x_um: f64,
    /// Impact regime at this Omega.
    pub regime: Regime,
    /// Upward sweep (else downward).
    pub up: bool,
}

/// What the bifurcation diagram draws.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BifView {
    /// The plotted mesh.
    pub mesh_label: String,
    /// ±b lines (um).
    pub backlash_um: Vec<f64>,
    /// The dots.
    pub points: Vec<BifPoint>,
    /// Lower end of the axis.
    pub omega_from: f64,
    /// Upper end.
    pub omega_to: f64,
    /// The cursor.
    pub selected_omega: f64,
    /// Failed points.
    pub failed: Vec<(f64, String)>,
    /// Omega bands where the system with every tooth pair in contact is
    /// parametrically unstable (shaded).
    pub unstable_bands: Vec<(f64, f64)>,
    /// The pinned state A's dots (A/B comparison), drawn under the current ones.
    pub pinned: Vec<BifPoint>,
    /// The pinned state A's ±b.
    pub pinned_backlash_um: Vec<f64>,
    /// Legend texts of A and B when comparing.
    pub ab_labels: Option<(String, String)>,
    /// The shooting branches' lines (stable solid, unstable thin).
    #[serde(skip)]
    pub branches: Vec<super::orbits::OrbitLine>,
    /// The bifurcations located on them.
    #[serde(skip)]
    pub branch_markers: Vec<super::orbits::OrbitMarker>,
    /// Every swept point's classification, `(omega, up, motion)`, in the
    /// sweep's order: the text alternative's words about the motion.
    #[serde(skip)]
    pub motions: Vec<(f64, bool, Motion)>,
    /// Swept points received.
    pub done: usize,
    /// Swept points in all.
    pub total: usize,
    /// The axis of x shows the whole clearance ±b (else it fits the data).
    #[serde(skip)]
    pub whole_clearance: bool,
    /// What the speed axis shows.
    #[serde(skip)]
    pub speed: crate::speed::SpeedAxis,
}

/// Bifurcation points as they arrive from both workers, for one job.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BifStore {
    /// Samples in arrival order.
    pub samples: Vec<BifSample>,
    /// Swept points in all (both shards).
    pub total: usize,
}

impl BifStore {
    /// An empty store for a new job.
    pub fn new(total: usize) -> Self {
        BifStore {
            samples: Vec::new(),
            total,
        }
    }

    /// The view of mesh `mesh` (`None` = each point's worst mesh).
    pub fn view(&self, mesh: Option<usize>, backlash_um: &[f64], ctx: &ViewContext) -> BifView {
        let mut points = Vec::new();
        let mut failed = Vec::new();
        let mut motions = Vec::new();
        // In the sweep's order (up by rising Omega, then down by falling
        // Omega), whatever order the workers' samples arrived in, so that
        // the export is the same on any pool.
        let mut samples: Vec<&BifSample> = self.samples.iter().collect();
        samples.sort_by_key(|s| {
            let i = i64::from(s.index);
            if s.up {
                (0, i)
            } else {
                (1, -i)
            }
        });
        for s in samples {
            if let Some(e) = &s.error {
                failed.push((s.omega, e.clone()));
                continue;
            }
            let j = mesh.unwrap_or(s.worst_mesh);
            let Some(m) = s.meshes.get(j) else { continue };
            motions.push((s.omega, s.up, s.motion));
            points.extend(m.x_um.iter().map(|&x| BifPoint {
                omega: s.omega,
                x_um: x,
                regime: m.regime,
                up: s.up,
            }));
        }
        BifView {
            mesh_label: ctx.mesh_label.clone(),
            backlash_um: distinct(backlash_um, mesh),
            points,
            omega_from: ctx.omega_from,
            omega_to: ctx.omega_to,
            selected_omega: ctx.selected_omega,
            failed,
            unstable_bands: Vec::new(),
            pinned: Vec::new(),
            pinned_backlash_um: Vec::new(),
            ab_labels: None,
            branches: Vec::new(),
            branch_markers: Vec::new(),
            motions,
            done: self.samples.len(),
            total: self.total,
            whole_clearance: true,
            speed: ctx.speed,
        }
    }
}

/// The bifurcation diagram as CSV.
pub fn bif_csv(v: &BifView) -> String {
    let mut s = String::from("omega,direction,x_um,regime\n");
    for p in &v.points {
        s.push_str(&format!(
            "{},{},{},{}\n",
            csv_num(p.omega),
            if p.up { "up" } else { "down" },
            csv_num(p.x_um),
            p.regime.solver_name()
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::BifMesh;
    use crate::views::test_support::ctx;

    #[test]
    fn bif_store_flattens_poincare_samples() {
        let mut st = BifStore::new(4);
        st.samples.push(BifSample {
            index: 0,
            omega: 0.5,
            up: false,
            meshes: vec![BifMesh {
                x_um: vec![1.0, 2.0],
                rel_min_um: 0.5,
                rel_max_um: 2.5,
                regime: Regime::DoubleSided,
                dynamic_factor: None,
            }],
            worst_mesh: 0,
            period: Some(2),
            motion: crate::protocol::Motion::Periodic { period: 2 },
            error: None,
        });
        let v = st.view(None, &[100.0], &ctx());
        assert_eq!(v.points.len(), 2);
        assert!(!v.points[0].up);
        assert_eq!(v.done, 1);
        assert_eq!(bif_csv(&v).lines().count(), 3);
    }
}
