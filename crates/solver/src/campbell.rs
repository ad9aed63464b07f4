//! The Campbell diagram: the natural frequencies of the linear model (every
//! mesh in contact, mean stiffness) against the input member's speed, the
//! lines of the mesh-frequency orders, and their crossings, the critical
//! speeds.
//!
//! The model is lumped and torsional with no gyroscopic or centrifugal
//! terms, so its natural frequencies do not change with speed: each is a
//! horizontal line, and order `k` crosses it where `k f_mesh(rpm) = f_n`,
//! with `f_mesh = rpm / 60 z_in |n_in - n_c| / n_in` (the input member's
//! teeth and its speed relative to the carrier,
//! [`crate::rpm::SpeedInfo::mesh_hz_per_rpm`]). At that
//! speed `Omega = omega_n / (k omega_ref)`.
//!
//! Which crossings the meshes can excite follows from the planets' mesh
//! phases (Parker & Lin 2004; docs/model.md, "Mesh phasing"): the order-`k`
//! pattern of the mesh excitation is `F_k = sum_j w_j F_j e^(i k gamma_j)`,
//! every mesh `j` weighted by its static force `F_j` (the load its
//! stiffness fluctuation modulates). A mode's participation at order `k`
//! is the size of that pattern's projection on the mode's eigenspace,
//! `sqrt(sum |phi^T F_k|^2)` over the modes sharing its frequency (so that
//! the basis chosen within a repeated frequency does not matter), divided
//! by the largest over every mode and order. With in-phase planets a
//! planet mode's participation is zero at every order; with sequential
//! phasing a rotational mode is excited only at orders `k` for which
//! `k z / N` is a whole number on every mesh kind. A participation is the
//! phase pattern's, not a predicted amplitude: the seed's stiffness and TE
//! are single harmonics, so orders above 1 are reached only through the
//! backlash and the stiffness's products (superharmonic resonances).
//!
//! Planet-pass orders ([`Campbell::with_planet_pass`]): the planets pass a
//! point of the held ring `N |n_c|` times a second, `N |n_c / n_in|` per
//! unit input speed (the carrier's speed per input speed,
//! [`crate::rpm::SpeedInfo::carrier_per_input`]); planet-pass order `m`
//! crosses a natural frequency at `rpm = 60 f_n / (m N |n_c / n_in|)`, mesh
//! order `m N / z_r`. The model has no carrier or planet position errors,
//! and every excitation repeats with the mesh period, so nothing in it
//! excites these lines below the mesh orders: they mark where a real
//! gearbox's planet-pass excitation would meet a mode.

use crate::error::{Result, SolverError};
use crate::modal::ModeKind;
use crate::Model;
use nalgebra::Complex;

/// Largest order a diagram draws.
pub const MAX_ORDER: u32 = 12;

/// Below this participation a crossing is called cancelled by the phasing.
pub const CANCELLED: f64 = 1e-9;

/// One natural frequency of the diagram (a horizontal line).
#[derive(Debug, Clone, PartialEq)]
pub struct ModeLine {
    /// Natural frequency (Hz).
    pub frequency_hz: f64,
    /// omega_n / omega_ref.
    pub omega: f64,
    /// Rotational or planet mode.
    pub kind: ModeKind,
    /// How many modes share the frequency.
    pub multiplicity: usize,
    /// Participation at orders 1 ..= `orders` (see the module's doc).
    pub participation: Vec<f64>,
}

/// One critical speed: order `order` crossing mode line `mode`.
#[derive(Debug, Clone, PartialEq)]
pub struct Crossing {
    /// Index into [`Campbell::modes`].
    pub mode: usize,
    /// The mesh-frequency order.
    pub order: u32,
    /// Input member speed (rpm).
    pub rpm: f64,
    /// Omega at that speed.
    pub omega: f64,
    /// Mesh frequency at that speed (Hz).
    pub mesh_frequency_hz: f64,
    /// The mode's participation at this order.
    pub participation: f64,
}

/// A Campbell diagram over an input speed range.
#[derive(Debug, Clone, PartialEq)]
pub struct Campbell {
    /// Mesh frequency per input rpm (Hz / rpm).
    pub mesh_hz_per_rpm: f64,
    /// The speed range (rpm).
    pub rpm_range: (f64, f64),
    /// Orders drawn, 1 ..= this.
    pub orders: u32,
    /// The elastic natural frequencies, ascending, one per distinct value.
    pub modes: Vec<ModeLine>,
    /// The crossings inside the range, ascending in speed.
    pub crossings: Vec<Crossing>,
    /// The planet-pass orders, where asked for ([`Campbell::with_planet_pass`]).
    pub planet_pass: Option<PlanetPass>,
}

/// The planet-pass orders of a diagram (see the module's doc).
#[derive(Debug, Clone, PartialEq)]
pub struct PlanetPass {
    /// Planets N.
    pub planets: u32,
    /// Planet-pass frequency (order 1) per input rpm (Hz / rpm).
    pub hz_per_rpm: f64,
    /// Orders drawn, 1 ..= this.
    pub orders: u32,
    /// The crossings inside the diagram's range, ascending in speed.
    pub crossings: Vec<PassCrossing>,
}

/// Planet-pass order `order` crossing mode line `mode`.
#[derive(Debug, Clone, PartialEq)]
pub struct PassCrossing {
    /// Index into [`Campbell::modes`].
    pub mode: usize,
    /// The planet-pass order.
    pub order: u32,
    /// Input member speed (rpm).
    pub rpm: f64,
    /// Omega at that speed.
    pub omega: f64,
    /// The same frequency in mesh orders.
    pub mesh_order: f64,
}

impl Campbell {
    /// Builds the diagram of `model` over input speeds `rpm_from ..= rpm_to`
    /// with orders `1 ..= orders`.
    pub fn new(model: &Model, rpm_from: f64, rpm_to: f64, orders: u32) -> Result<Self> {
        check_range(rpm_from, rpm_to)?;
        if !(1..=MAX_ORDER).contains(&orders) {
            return Err(SolverError::OutOfRange {
                key: "orders".into(),
                value: orders.to_string(),
                allowed: format!("1 ..= {MAX_ORDER}"),
            });
        }
        let mesh_hz_per_rpm = model.system.speed.mesh_hz_per_rpm();
        let modes = mode_lines(model, orders);
        let mut crossings = Vec::new();
        for (i, line) in modes.iter().enumerate() {
            for order in 1..=orders {
                let mesh_frequency_hz = line.frequency_hz / f64::from(order);
                let rpm = mesh_frequency_hz / mesh_hz_per_rpm;
                if rpm >= rpm_from && rpm <= rpm_to {
                    crossings.push(Crossing {
                        mode: i,
                        order,
                        rpm,
                        omega: line.omega / f64::from(order),
                        mesh_frequency_hz,
                        participation: line.participation[order as usize - 1],
                    });
                }
            }
        }
        crossings.sort_by(|a, b| a.rpm.total_cmp(&b.rpm));
        Ok(Campbell {
            mesh_hz_per_rpm,
            rpm_range: (rpm_from, rpm_to),
            orders,
            modes,
            crossings,
            planet_pass: None,
        })
    }

    /// The diagram with the planet-pass orders `1 ..= orders` of `planets`
    /// planets on a carrier turning `carrier_per_input` times the input
    /// member ([`crate::rpm::SpeedInfo::carrier_per_input`]), and their
    /// crossings in the diagram's range. Refused for a carrier that does not
    /// turn (the gear pair) or an order count outside `1 ..= MAX_ORDER`.
    pub fn with_planet_pass(
        mut self,
        planets: u32,
        carrier_per_input: f64,
        orders: u32,
    ) -> Result<Self> {
        let hz_per_rpm = f64::from(planets) * carrier_per_input.abs() / 60.0;
        if !(hz_per_rpm > 0.0 && hz_per_rpm.is_finite()) {
            return Err(SolverError::OutOfRange {
                key: "planets".into(),
                value: format!(
                    "{planets} on a carrier at {carrier_per_input} times the input speed"
                ),
                allowed: "at least one planet on a turning carrier".into(),
            });
        }
        if !(1..=MAX_ORDER).contains(&orders) {
            return Err(SolverError::OutOfRange {
                key: "planet_pass_orders".into(),
                value: orders.to_string(),
                allowed: format!("1 ..= {MAX_ORDER}"),
            });
        }
        let (from, to) = self.rpm_range;
        let mut crossings = Vec::new();
        for (i, line) in self.modes.iter().enumerate() {
            for order in 1..=orders {
                let rpm = line.frequency_hz / (f64::from(order) * hz_per_rpm);
                if rpm >= from && rpm <= to {
                    let mesh_order = f64::from(order) * hz_per_rpm / self.mesh_hz_per_rpm;
                    crossings.push(PassCrossing {
                        mode: i,
                        order,
                        rpm,
                        omega: line.omega / mesh_order,
                        mesh_order,
                    });
                }
            }
        }
        crossings.sort_by(|a, b| a.rpm.total_cmp(&b.rpm));
        self.planet_pass = Some(PlanetPass {
            planets,
            hz_per_rpm,
            orders,
            crossings,
        });
        Ok(self)
    }
}

/// Input speed (rpm) at `omega` on `model`: `omega omega_ref / (2 pi)` is
/// the mesh frequency.
pub fn rpm_at(model: &Model, omega: f64) -> f64 {
    model.system.rpm_scale().rpm(omega)
}

/// Omega at input speed `rpm` on `model` (the inverse of [`rpm_at`]).
pub fn omega_at(model: &Model, rpm: f64) -> f64 {
    model.system.rpm_scale().omega(rpm)
}

fn check_range(rpm_from: f64, rpm_to: f64) -> Result<()> {
    let bad = |key: &str, v: f64| SolverError::OutOfRange {
        key: key.into(),
        value: format!("{v}"),
        allowed: "0 ..= 1 000 000 rpm, rpm_from below rpm_to".into(),
    };
    if !rpm_from.is_finite() || !(0.0..=1e6).contains(&rpm_from) {
        return Err(bad("rpm_from", rpm_from));
    }
    if !rpm_to.is_finite() || !(0.0..=1e6).contains(&rpm_to) || rpm_to <= rpm_from {
        return Err(bad("rpm_to", rpm_to));
    }
    Ok(())
}

/// The elastic natural frequencies, one line per distinct value, with
/// their participations.
fn mode_lines(model: &Model, orders: u32) -> Vec<ModeLine> {
    let sys = &model.system;
    let elastic: Vec<&crate::modal::Mode> = model.modes.elastic().collect();
    // |phi^T F_k|^2 of every elastic mode at every order.
    let power: Vec<Vec<f64>> = elastic
        .iter()
        .map(|mode| {
            (1..=orders)
                .map(|k| {
                    let mut sum = Complex::new(0.0, 0.0);
                    for (j, mesh) in sys.meshes.iter().enumerate() {
                        let proj = mesh.dot(&mode.shape);
                        let force = model.statics.mesh_force_n[j];
                        sum += Complex::from_polar(proj * force, f64::from(k) * mesh.phase_rad);
                    }
                    sum.norm_sqr()
                })
                .collect()
        })
        .collect();
    // Group modes of one frequency (relative gap 1e-6, as the modes'
    // multiplicities).
    let mut lines: Vec<(usize, Vec<f64>)> = Vec::new();
    for (i, mode) in elastic.iter().enumerate() {
        match lines.iter_mut().find(|(first, _)| {
            let f = elastic[*first].frequency_hz;
            (f - mode.frequency_hz).abs() <= 1e-6 * f.max(mode.frequency_hz)
        }) {
            Some((_, p)) => p.iter_mut().zip(&power[i]).for_each(|(a, b)| *a += b),
            None => lines.push((i, power[i].clone())),
        }
    }
    let largest = lines
        .iter()
        .flat_map(|(_, p)| p.iter().map(|x| x.sqrt()))
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    lines
        .into_iter()
        .map(|(first, p)| {
            let mode = elastic[first];
            ModeLine {
                frequency_hz: mode.frequency_hz,
                omega: mode.omega,
                kind: mode.kind,
                multiplicity: mode.multiplicity,
                participation: p.iter().map(|x| x.sqrt() / largest).collect(),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]
    use super::*;
    use crate::keys;
    use crate::params::ModelParams;

    fn model(assignments: &[&str]) -> Model {
        let mut p = ModelParams::default();
        for a in assignments {
            keys::set_assignment(&mut p, a).unwrap();
        }
        Model::new(&p).unwrap()
    }

    /// Every crossing is a natural frequency over its order, in Hz and in
    /// Omega, and rpm and Omega map each other exactly.
    #[test]
    fn crossings_are_natural_frequencies_over_their_orders() {
        let m = model(&[]);
        let c = Campbell::new(&m, 0.0, 1e6, 4).unwrap();
        assert_eq!(
            c.crossings.len(),
            c.modes.len() * 4,
            "every line crosses every order below 1e6 rpm"
        );
        for x in &c.crossings {
            let line = &c.modes[x.mode];
            let f = x.rpm * c.mesh_hz_per_rpm * f64::from(x.order);
            assert!(
                (f - line.frequency_hz).abs() <= 1e-9 * line.frequency_hz,
                "{x:?}"
            );
            assert!(
                (x.omega - line.omega / f64::from(x.order)).abs() <= 1e-12,
                "{x:?}"
            );
            assert!(
                (omega_at(&m, x.rpm) - x.omega).abs() <= 1e-9 * x.omega,
                "{x:?}"
            );
            assert!((rpm_at(&m, x.omega) - x.rpm).abs() <= 1e-9 * x.rpm, "{x:?}");
        }
        for w in c.crossings.windows(2) {
            assert!(w[0].rpm <= w[1].rpm);
        }
    }

    /// In-phase planets: the planet modes (repeated N - 1 times) are never
    /// excited, the rotational ones are.
    #[test]
    fn in_phase_planets_never_excite_planet_modes() {
        let m = model(&["planets=4", "phasing=in-phase"]);
        let c = Campbell::new(&m, 0.0, 1e6, 6).unwrap();
        assert!(c
            .modes
            .iter()
            .any(|l| l.kind == ModeKind::Planet && l.multiplicity == 3));
        for l in &c.modes {
            for (k, p) in l.participation.iter().enumerate() {
                match l.kind {
                    ModeKind::Planet => assert!(*p <= CANCELLED, "order {}: {l:?}", k + 1),
                    _ => assert!(*p > 1e-6, "order {}: {l:?}", k + 1),
                }
            }
        }
    }

    /// Sequential phasing with five planets (tooth counts 36, 48, 84: no
    /// `k z / 5` is whole for k = 1 ..= 4): the rotational modes are
    /// cancelled at orders 1 to 4 and excited at order 5, and the planet
    /// modes take the excitation at orders 1 to 4.
    #[test]
    fn five_sequential_planets_cancel_rotational_modes_below_order_five() {
        let m = model(&["planets=5", "phasing=sequential"]);
        let c = Campbell::new(&m, 0.0, 1e6, 5).unwrap();
        for l in &c.modes {
            match l.kind {
                ModeKind::Rotational => {
                    for k in 0..4 {
                        assert!(l.participation[k] <= CANCELLED, "order {}: {l:?}", k + 1);
                    }
                    assert!(l.participation[4] > 1e-6, "order 5: {l:?}");
                }
                ModeKind::Planet => assert_eq!(l.multiplicity, 4),
                ModeKind::RigidBody => panic!("the rigid mode is not a line"),
            }
        }
        let planet_excited = c
            .modes
            .iter()
            .filter(|l| l.kind == ModeKind::Planet)
            .any(|l| l.participation[..4].iter().any(|p| *p > 1e-6));
        assert!(planet_excited, "{:?}", c.modes);
    }

    /// Planet-pass order m of N planets crosses a mode where m N n_c / 60
    /// equals f_n, the carrier turning z_s1 / (z_s1 - z_r) times the small
    /// sun (36 / (36 - 84) = -3/4 on the defaults, with the ring held); in
    /// mesh orders that is m N / z_r.
    #[test]
    fn planet_pass_crossings_are_natural_frequencies_over_their_orders() {
        let m = model(&["planets=5", "phasing=sequential"]);
        let carrier = 36.0 / (36.0 - 84.0);
        assert!((m.system.speed.carrier_per_input() - carrier).abs() <= 1e-15);
        let c = Campbell::new(&m, 0.0, 1e6, 4)
            .unwrap()
            .with_planet_pass(5, carrier, 6)
            .unwrap();
        let pass = c.planet_pass.as_ref().unwrap();
        assert!(!pass.crossings.is_empty());
        for x in &pass.crossings {
            let f_n = c.modes[x.mode].frequency_hz;
            let rpm = 60.0 * f_n / (f64::from(x.order) * 5.0 * carrier.abs());
            assert!((x.rpm - rpm).abs() <= 1e-9 * rpm, "{x:?}");
            let mesh_order = f64::from(x.order) * 5.0 / 84.0;
            assert!((x.mesh_order - mesh_order).abs() <= 1e-12, "{x:?}");
            assert!(
                (omega_at(&m, x.rpm) - x.omega).abs() <= 1e-9 * x.omega,
                "{x:?}"
            );
        }
        // Every line below 1e6 rpm: the first mode crosses order 1 at
        // 60 f_1 / (5 * 3/4) rpm.
        let first = 60.0 * c.modes[0].frequency_hz / (5.0 * 0.75);
        assert_eq!(
            first < 1e6,
            pass.crossings.iter().any(|x| x.mode == 0 && x.order == 1)
        );
        assert!(Campbell::new(&m, 0.0, 1e6, 4)
            .unwrap()
            .with_planet_pass(5, 0.0, 4)
            .is_err());
        assert!(Campbell::new(&m, 0.0, 1e6, 4)
            .unwrap()
            .with_planet_pass(5, carrier, 0)
            .is_err());
    }

    #[test]
    fn bad_ranges_and_orders_are_refused() {
        let m = model(&[]);
        assert!(Campbell::new(&m, 100.0, 50.0, 4).is_err());
        assert!(Campbell::new(&m, f64::NAN, 50.0, 4).is_err());
        assert!(Campbell::new(&m, 0.0, 50.0, 0).is_err());
        assert!(Campbell::new(&m, 0.0, 50.0, MAX_ORDER + 1).is_err());
    }
}
