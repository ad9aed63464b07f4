//! How the planets share the load: for each mesh kind of the compound set,
//! the largest mesh force each planet's mesh reaches over a steady state,
//! and the load-sharing factor, the largest of them over their mean (the
//! dynamic counterpart of ISO 6336's K_gamma for planetary stages, which
//! is the largest planet's load over the mean planet load).
//!
//! With in-phase planets and equal meshes every planet moves alike, so the
//! factor is exactly 1; sequential phasing (Parker & Lin 2004) staggers
//! the planets' mesh cycles, which cancels some mesh orders at the central
//! members but lets the planets' forces differ within a period.

use crate::params::MeshKind;
use crate::steady::MeshSteady;
use crate::system::MeshSystem;

/// One mesh kind's sharing among the planets.
#[derive(Debug, Clone, PartialEq)]
pub struct KindSharing {
    /// The mesh kind.
    pub kind: MeshKind,
    /// Largest mesh force of each planet's mesh (N), by planet.
    pub peak_force_n: Vec<f64>,
    /// Largest peak over the mean peak; `None` where the mean is not
    /// positive (no mesh of the kind carries load).
    pub factor: Option<f64>,
}

/// The sharing of every mesh kind with more than one planet mesh, in the
/// order of [`MeshKind::COMPOUND`]; empty for the gear pair.
pub fn load_sharing(sys: &MeshSystem, meshes: &[MeshSteady]) -> Vec<KindSharing> {
    let peaks: Vec<f64> = meshes.iter().map(|m| m.force_max_n).collect();
    sharing_of_peaks(sys, &peaks)
}

/// The sharing of every mesh kind with more than one planet mesh, from
/// each mesh's largest force `peak_force_n` (N, in the system's mesh
/// order; a sweep's point gives it as its dynamic factor times the static
/// force), in the order of [`MeshKind::COMPOUND`]; empty for the gear pair
/// or when a mesh's force is missing.
pub fn sharing_of_peaks(sys: &MeshSystem, peak_force_n: &[f64]) -> Vec<KindSharing> {
    if peak_force_n.len() != sys.meshes.len() {
        return Vec::new();
    }
    MeshKind::COMPOUND
        .iter()
        .filter_map(|&kind| {
            let mut by_planet: Vec<(usize, f64)> = sys
                .meshes
                .iter()
                .zip(peak_force_n)
                .filter(|(m, _)| m.kind == kind)
                .map(|(m, f)| (m.planet, *f))
                .collect();
            if by_planet.len() < 2 {
                return None;
            }
            by_planet.sort_by_key(|p| p.0);
            let peak_force_n: Vec<f64> = by_planet.into_iter().map(|p| p.1).collect();
            let mean = peak_force_n.iter().sum::<f64>() / peak_force_n.len() as f64;
            let largest = peak_force_n
                .iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max);
            Some(KindSharing {
                kind,
                factor: (mean > 0.0 && mean.is_finite()).then(|| largest / mean),
                peak_force_n,
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
    use super::*;
    use crate::keys;
    use crate::params::ModelParams;
    use crate::steady::{steady_state, SteadyOptions};
    use crate::Model;

    fn sharing(assignments: &[&str], omega: f64) -> Vec<KindSharing> {
        let mut p = ModelParams::default();
        for a in assignments {
            keys::set_assignment(&mut p, a).unwrap();
        }
        let model = Model::new(&p).unwrap();
        let mut o = SteadyOptions::new(omega);
        o.transient_periods = 60;
        o.record_periods = 20;
        let ss = steady_state(&model, &o, None).unwrap();
        load_sharing(&model.system, &ss.meshes)
    }

    /// In-phase planets on equal meshes move alike: every kind's planets
    /// reach the same peak force, a factor of exactly 1 (to round-off).
    #[test]
    fn in_phase_planets_share_the_load_equally() {
        for omega in [0.35, 0.6] {
            let s = sharing(&["planets=4", "phasing=in-phase"], omega);
            assert_eq!(s.len(), 4);
            for k in &s {
                assert_eq!(k.peak_force_n.len(), 4);
                let f = k.factor.expect("loaded");
                assert!((f - 1.0).abs() <= 1e-9, "Omega {omega} {:?}: {f}", k.kind);
            }
        }
    }

    /// Five sequential planets (tooth counts 36/48/84: their mesh cycles
    /// staggered by fifths) do not share the dynamic load equally.
    #[test]
    fn sequential_planets_share_the_load_unequally() {
        let s = sharing(&["planets=5", "phasing=sequential"], 0.35);
        let worst = s.iter().filter_map(|k| k.factor).fold(1.0, f64::max);
        assert!(worst > 1.001, "{s:?}");
        for k in &s {
            assert!(k.factor.expect("loaded") >= 1.0);
        }
    }

    /// The gear pair has one mesh: nothing to share.
    #[test]
    fn the_gear_pair_has_no_sharing() {
        let mut p = ModelParams::default();
        keys::set_assignment(&mut p, "model=gear-pair").unwrap();
        let model = Model::new(&p).unwrap();
        let mut o = SteadyOptions::new(0.5);
        o.transient_periods = 10;
        o.record_periods = 5;
        let ss = steady_state(&model, &o, None).unwrap();
        assert!(load_sharing(&model.system, &ss.meshes).is_empty());
    }
}
