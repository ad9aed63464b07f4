//! The integrator on cases with known solutions: its convergence order, its
//! tolerance proportionality and the timing of located contact switches.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::dynamics::MeshOde;
use solver::keys;
use solver::ode::{Dopri5, Ode, Tolerances};
use solver::params::ModelParams;
use solver::steady::Model;
use std::f64::consts::PI;

/// A forced, damped oscillator `x'' + 2 z x' + x = cos(1.3 t)`: smooth.
struct Forced;
impl Ode for Forced {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = (1.3 * t).cos() - 0.1 * y[1] - y[0];
    }
}

/// Its exact solution from rest at the origin.
fn forced_exact(t: f64) -> f64 {
    // Particular part A cos + B sin at w = 1.3, then the homogeneous part.
    let w: f64 = 1.3;
    let z = 0.05;
    let den = (1.0 - w * w).powi(2) + (2.0 * z * w).powi(2);
    let a = (1.0 - w * w) / den;
    let b = 2.0 * z * w / den;
    let wd = (1.0 - z * z).sqrt();
    // x(0) = 0: c1 = -a; x'(0) = 0: -z c1 + wd c2 + b w = 0.
    let c1 = -a;
    let c2 = (z * c1 - b * w) / wd;
    a * (w * t).cos()
        + b * (w * t).sin()
        + (-z * t).exp() * (c1 * (wd * t).cos() + c2 * (wd * t).sin())
}

fn fixed_step_error(h: f64) -> f64 {
    // Huge tolerances and h_max = h: every step is taken, at size h.
    let tol = Tolerances {
        rtol: 1e6,
        atol: vec![1e6; 2],
        h_min: 0.0,
        h_max: h,
    };
    let mut ode = Forced;
    let mut int = Dopri5::new(&mut ode, 0.0, &[0.0, 0.0], h, tol);
    let t_end = 8.0;
    while int.t() < t_end {
        int.step(&mut ode, t_end).expect("step");
    }
    (int.y()[0] - forced_exact(t_end)).abs()
}

#[test]
fn observed_convergence_order_is_five() {
    let hs = [0.2, 0.1, 0.05, 0.025];
    let errors: Vec<f64> = hs.iter().map(|&h| fixed_step_error(h)).collect();
    for w in errors.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!(
            (4.6..=5.4).contains(&order),
            "observed order {order} from {errors:?}"
        );
    }
}

#[test]
fn global_error_follows_the_tolerance() {
    let run = |rtol: f64| {
        let tol = Tolerances {
            rtol,
            atol: vec![rtol; 2],
            h_min: 1e-14,
            h_max: 1.0,
        };
        let mut ode = Forced;
        let mut int = Dopri5::new(&mut ode, 0.0, &[0.0, 0.0], 1e-3, tol);
        while int.t() < 20.0 {
            int.step(&mut ode, 20.0).expect("step");
        }
        (int.y()[0] - forced_exact(20.0)).abs()
    };
    let (e6, e9) = (run(1e-6), run(1e-9));
    assert!(e6 < 1e-4 && e9 < 1e-7, "{e6} {e9}");
    // Tolerance proportionality: a thousandfold tighter tolerance buys a
    // tenfold smaller error at least (here the looser run is already far
    // inside its tolerance, so the gain is less than the asymptotic 1000^0.8).
    assert!(e9 < 0.1 * e6, "{e6} {e9}");
}

/// An unloaded, undamped gear pair with constant stiffness released from a
/// deflection `b + A` rattles through the backlash: contact for a quarter
/// period, free flight across `2b` at speed `A w_n`, a half period on the
/// back flanks, free flight back. The switch times are known exactly.
#[test]
fn contact_switches_are_located_at_the_exact_crossing_times() {
    let mut p = ModelParams::default();
    for a in [
        "model=gear-pair",
        "torque_pinion_nm=0",
        "te_um=0",
        "stiffness_variation=0",
        "damping_ratio=0",
        "backlash_um=100",
    ] {
        keys::set_assignment(&mut p, a).expect(a);
    }
    let model = Model::new(&p).expect("model");
    let sys = &model.system;
    let mesh = &sys.meshes[0];
    let (b, amp) = (mesh.backlash_m, 10e-6);
    let wn = (mesh.stiffness_mean_n_m / mesh.equivalent_mass_kg).sqrt();
    let rho_p = mesh.w[0].1;
    let y0 = [(b + amp) / rho_p, 0.0, 0.0, 0.0];
    let t_quarter = PI / (2.0 * wn);
    let t_flight = 2.0 * b / (amp * wn);
    let expected = [
        t_quarter,
        t_quarter + t_flight,
        3.0 * t_quarter + t_flight,
        3.0 * t_quarter + 2.0 * t_flight,
    ];
    let mut ode = MeshOde::new(sys, wn);
    let lengths = sys.dof_length_m();
    let mut atol: Vec<f64> = lengths.iter().map(|l| 1e-14 / l).collect();
    atol.extend(lengths.iter().map(|l| 1e-14 / l * wn));
    let tol = Tolerances {
        rtol: 1e-10,
        atol,
        h_min: 1e-16,
        h_max: t_quarter / 4.0,
    };
    let mut int = Dopri5::new(&mut ode, 0.0, &y0, t_quarter / 50.0, tol);
    let mut located = Vec::new();
    let t_end = expected[3] + t_quarter;
    while int.t() < t_end {
        int.step(&mut ode, t_end).expect("step");
        located.extend(int.last_events(&mut ode).iter().map(|&(_, t)| t));
    }
    assert_eq!(
        located.len(),
        4,
        "switches at {located:?}, expected {expected:?}"
    );
    for (t, e) in located.iter().zip(expected) {
        // To the integration accuracy: the free flights turn a velocity error
        // of ~1e-8 (accumulated over ~100 steps at rtol 1e-10) into a timing
        // error of a few 1e-7 quarter periods; a grid of steps would miss by 1e-2.
        assert!((t - e).abs() < 1e-6 * t_quarter, "switch at {t}, exact {e}");
    }
    let _ = ode.dim();
}

/// The compound set's ODE with event location interpolating every position
/// (the default of [`Ode::event_components`]) instead of only the three
/// coordinates of the event's mesh.
struct AllComponents(MeshOde);
impl Ode for AllComponents {
    fn dim(&self) -> usize {
        self.0.dim()
    }
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        self.0.rhs(t, y, dy);
    }
    fn n_events(&self) -> usize {
        self.0.n_events()
    }
    fn events(&mut self, t: f64, y: &[f64], dy: &[f64], g: &mut [f64], dg: &mut [f64]) {
        self.0.events(t, y, dy, g, dg);
    }
    fn event(&mut self, i: usize, t: f64, y: &[f64]) -> f64 {
        self.0.event(i, t, y)
    }
    fn event_dim(&self) -> usize {
        self.0.event_dim()
    }
}

/// Interpolating only an event's own components is an optimization, not an
/// approximation: the same steps, states and switch times to the bit, over a
/// stretch with many double-sided impacts.
#[test]
fn event_location_on_the_mesh_coordinates_only_changes_nothing() {
    let mut p = ModelParams::default();
    keys::set_assignment(&mut p, "backlash_um=10").expect("backlash");
    let model = Model::new(&p).expect("model");
    let sys = &model.system;
    let omega_rad_s = 1.2 * sys.omega_ref_rad_s;
    let period = 2.0 * PI / omega_rad_s;
    let lengths = sys.dof_length_m();
    let mut atol: Vec<f64> = lengths.iter().map(|l| 1e-10 / l).collect();
    atol.extend(lengths.iter().map(|l| 1e-10 / l * omega_rad_s));
    let tol = Tolerances {
        rtol: 1e-7,
        atol,
        h_min: 1e-13 * period,
        h_max: period / 8.0,
    };
    let y0 = model.static_state();
    let mut fast = MeshOde::new(sys, omega_rad_s);
    assert!(fast.event_components(0).is_some());
    let mut full = AllComponents(MeshOde::new(sys, omega_rad_s));
    let mut a = Dopri5::new(&mut fast, 0.0, &y0, period / 200.0, tol.clone());
    let mut b = Dopri5::new(&mut full, 0.0, &y0, period / 200.0, tol);
    let t_end = 30.0 * period;
    let mut switches = 0;
    while a.t() < t_end {
        a.step(&mut fast, t_end).expect("step");
        b.step(&mut full, t_end).expect("step");
        assert_eq!(a.t().to_bits(), b.t().to_bits());
        assert_eq!(a.y(), b.y());
        let ea = a.last_events(&mut fast).to_vec();
        assert_eq!(ea, b.last_events(&mut full));
        switches += ea.len();
    }
    assert_eq!(a.stats, b.stats);
    assert!(
        switches > 100,
        "only {switches} switches: not a test of event location"
    );
}
