//! Tests of the DOPRI5 integrator: dense output, event location and the
//! tail that rides outside the error control.

use super::*;

/// Harmonic oscillator y'' = -y, exact solution (cos t, -sin t).
struct Harmonic;
impl Ode for Harmonic {
    fn dim(&self) -> usize {
        2
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = -y[0];
    }
}

fn tol(rtol: f64) -> Tolerances {
    Tolerances {
        rtol,
        atol: vec![rtol; 2],
        h_min: 1e-14,
        h_max: 1.0,
    }
}

#[test]
fn dense_output_is_accurate_inside_steps() {
    let mut ode = Harmonic;
    let mut int = Dopri5::new(&mut ode, 0.0, &[1.0, 0.0], 0.1, tol(1e-10));
    let mut y = [0.0; 2];
    let mut worst: f64 = 0.0;
    while int.t() < 10.0 {
        let info = int.step(&mut ode, 10.0).expect("step");
        for k in 1..10 {
            let t = info.t0 + (info.t1 - info.t0) * f64::from(k) / 10.0;
            int.dense(t, &mut y);
            worst = worst
                .max((y[0] - t.cos()).abs())
                .max((y[1] + t.sin()).abs());
        }
    }
    assert!(worst < 1e-8, "dense output error {worst}");
}

#[test]
fn hermite_dip_finds_a_dip_below_zero() {
    // g = (t - 0.5)^2 - 0.01 on [0, 1]: g0 = g1 = 0.24, slopes -1 and +1.
    let theta = hermite_dip(0.24, 0.24, -1.0, 1.0).expect("dip");
    assert!((theta - 0.5).abs() < 1e-12);
    assert!(hermite_dip(0.24, 0.24, -0.1, 0.1).is_none());
}

/// The oscillator with a tangent vector after its state (the system is
/// linear, so the tangent obeys the same equation).
struct HarmonicWithTangent;
impl Ode for HarmonicWithTangent {
    fn dim(&self) -> usize {
        4
    }
    fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
        dy[0] = y[1];
        dy[1] = -y[0];
        dy[2] = y[3];
        dy[3] = -y[2];
    }
}

/// A tail rides on the state's steps without changing them: the state's
/// trajectory is the same, bit for bit, as a run without it, before,
/// during and after; and the tail, started at (0, 1) halfway, is the exact
/// tangent (sin, cos) of the elapsed time to the state's own accuracy.
#[test]
fn a_tail_rides_on_the_same_steps_and_integrates_its_own_equation() {
    let mut plain = Dopri5::new(&mut Harmonic, 0.0, &[1.0, 0.0], 0.01, tol(1e-9));
    let mut with = plain.clone();
    let (t_on, t_off, t_end) = (3.0, 9.0, 12.0);
    while plain.t() < t_on {
        plain.step(&mut Harmonic, t_on).unwrap();
        with.step(&mut Harmonic, t_on).unwrap();
    }
    with.attach_tail(&mut HarmonicWithTangent, &[0.0, 1.0]);
    assert_eq!(with.tail(), &[0.0, 1.0]);
    while plain.t() < t_off {
        let a = plain.step(&mut Harmonic, t_off).unwrap();
        let b = with.step(&mut HarmonicWithTangent, t_off).unwrap();
        assert_eq!(a, b);
        assert_eq!(plain.y(), with.y());
        assert_eq!(plain.dy(), with.dy());
    }
    let s = t_off - t_on;
    let z = with.tail();
    assert!((z[0] - s.sin()).abs() < 1e-7, "{z:?}");
    assert!((z[1] - s.cos()).abs() < 1e-7, "{z:?}");
    with.detach_tail();
    assert!(with.tail().is_empty());
    while plain.t() < t_end {
        let a = plain.step(&mut Harmonic, t_end).unwrap();
        let b = with.step(&mut Harmonic, t_end).unwrap();
        assert_eq!(a, b);
        assert_eq!(plain.y(), with.y());
    }
}
