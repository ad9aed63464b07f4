//! The mesh force by order against facts derived beside each test: a
//! hand-built signal's known lines, a linear periodic response's whole
//! orders, and the geometric sum of the planets' phases.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use super::*;
use crate::keys;
use crate::params::ModelParams;
use crate::steady::{steady_state, SteadyOptions};
use crate::Model;
use std::f64::consts::PI;

fn solved(assignments: &[&str], omega: f64) -> (Model, SteadyState) {
    let mut p = ModelParams::default();
    for a in assignments {
        keys::set_assignment(&mut p, a).unwrap();
    }
    let model = Model::new(&p).unwrap();
    let mut o = SteadyOptions::new(omega);
    // Tight tolerances and a full transient (the slowest mode, near Omega
    // 0.4 at 6 % damping, decays by 0.77 a period at Omega 0.6: 1e-22
    // after 200 periods), so what is left between the orders is the
    // integration's error alone.
    o.transient_periods = 200;
    o.early_settle = false;
    o.rtol = 1e-10;
    o.atol_m = 1e-13;
    o.record_periods = 16;
    o.samples_per_period = 64;
    o.history_meshes = (0..model.system.meshes.len()).collect();
    let ss = steady_state(&model, &o, None).unwrap();
    (model, ss)
}

/// The amplitude at order `k / periods` (bin k).
fn at(f: &[f64], order: &[f64], o: f64) -> f64 {
    order
        .iter()
        .zip(f)
        .find(|(x, _)| (**x - o).abs() < 1e-9)
        .map(|(_, a)| *a)
        .unwrap()
}

/// A signal of known lines: 3 N at the mesh frequency, 1 N at twice it,
/// 0.5 N at half of it (a period-2 subharmonic) and 0.2 N at 3/2 of it
/// (its sideband), plus a 7 N mean, sampled 64 times a period over 20
/// periods: the peaks are exactly those four, labelled "1/2×", "1×",
/// "3/2×", "2×", with their amplitudes.
#[test]
fn a_signal_of_known_lines_gets_exactly_their_labels() {
    let (spp, periods) = (64u32, 20u32);
    let n = (spp * periods) as usize;
    let x: Vec<f64> = (0..n)
        .map(|i| {
            let t = i as f64 / f64::from(spp); // in mesh periods
            7.0 + 3.0 * (2.0 * PI * t).cos()
                + 1.0 * (4.0 * PI * t + 0.3).cos()
                + 0.5 * (PI * t - 1.0).cos()
                + 0.2 * (3.0 * PI * t + 2.0).sin()
        })
        .collect();
    let s = spectrum(&x, spp, periods, 8.0);
    let p = peaks(&s.order, &s.amplitude, periods);
    let labels: Vec<&str> = p.iter().map(|p| p.label.as_str()).collect();
    assert_eq!(labels, ["1/2×", "1×", "3/2×", "2×"]);
    let whole: Vec<bool> = p.iter().map(|p| p.whole).collect();
    assert_eq!(whole, [false, true, false, true]);
    for (peak, (o, a)) in p
        .iter()
        .zip([(0.5, 0.5), (1.0, 3.0), (1.5, 0.2), (2.0, 1.0)])
    {
        assert!((peak.order - o).abs() <= 1e-12, "{peak:?}");
        assert!((peak.amplitude_n - a).abs() <= 1e-12, "{peak:?}");
    }
    assert!((s.amplitude[0] - 7.0).abs() <= 1e-12);
}

/// Orders in lowest terms; fine fractions as decimals.
#[test]
fn orders_are_named_in_lowest_terms() {
    assert_eq!(order_label(20, 20), ("1×".to_string(), true));
    assert_eq!(order_label(60, 20), ("3×".to_string(), true));
    assert_eq!(order_label(10, 20), ("1/2×".to_string(), false));
    assert_eq!(order_label(5, 20), ("1/4×".to_string(), false));
    assert_eq!(order_label(7, 20), ("0.35×".to_string(), false));
    assert_eq!(order_label(0, 20), ("0×".to_string(), true));
}

/// A linear mesh (no backlash) with in-phase planets and the seed's
/// one-harmonic stiffness, away from its parametric resonances, settles
/// on a motion of the mesh period: every line of the force between the
/// whole orders is nothing (below 1e-7 of the largest), and the labelled
/// peaks are whole orders.
#[test]
fn a_linear_mesh_has_force_only_at_whole_orders() {
    let (model, ss) = solved(&["backlash_um=0", "phasing=in-phase"], 0.6);
    let f = force_orders(&model.system, &ss, 0, 8.0).unwrap();
    assert_eq!(f.record_periods, 16);
    let largest = f.amplitude_n.iter().skip(1).copied().fold(0.0, f64::max);
    assert!(largest > 1.0, "{largest}");
    let mut whole_seen = 0;
    for (o, a) in f.order.iter().zip(&f.amplitude_n) {
        let whole = (o - o.round()).abs() < 1e-9;
        if whole {
            whole_seen += 1;
        } else {
            assert!(*a <= 1e-7 * largest, "order {o}: {a} N of {largest} N");
        }
    }
    assert_eq!(whole_seen, 9, "orders 0 to 8");
    assert!(!f.peaks.is_empty());
    assert!(f.peaks.iter().all(|p| p.whole), "{:?}", f.peaks);
    assert_eq!(f.peaks[0].label, "1×");
    // In phase, the sum over the planets is N times one planet's force.
    let sum = f.planets.as_ref().unwrap();
    assert_eq!(sum.meshes.len(), 3);
    assert!(sum.cancelled.is_empty());
    for (s, a) in sum.amplitude_n.iter().zip(&f.amplitude_n) {
        assert!((s - 3.0 * a).abs() <= 1e-6 * largest, "{s} against 3 x {a}");
    }
}

/// Five sequential planets with z_s1 = 36, z_s2 = 46 and z_r = 84 (all
/// 1 modulo 5, so one relabelling of the planets shifts every kind's phase
/// by the same angle and planet n's force is planet 1's shifted in time):
/// harmonic k of the sum over the planets is one planet's harmonic k
/// times |sum_n exp(2 pi i k z (n - 1) / 5)|, which the geometric sum
/// makes 5 when 5 divides k z and 0 otherwise. Checked on the solved
/// model's forces, kind by kind, at whole orders 1 to 6.
#[test]
fn sequential_phasing_cancels_the_orders_its_geometric_sum_says() {
    let (model, ss) = solved(
        &[
            "planets=5",
            "phasing=sequential",
            "teeth_s2=46",
            "backlash_um=0",
        ],
        0.6,
    );
    for (mesh, z) in [
        ("s1a1", 36.0),
        ("s2b1", 46.0),
        ("a1b1", 36.0),
        ("rb1", -84.0),
    ] {
        let j = model
            .system
            .meshes
            .iter()
            .position(|m| m.name == mesh)
            .unwrap();
        let f = force_orders(&model.system, &ss, j, 8.0).unwrap();
        let sum = f.planets.as_ref().unwrap();
        let largest = f.amplitude_n.iter().skip(1).copied().fold(0.0, f64::max);
        let mut cancelled = Vec::new();
        for k in 1..=6u32 {
            let (c, s) = (0..5).fold((0.0, 0.0), |(c, s), n| {
                let a = 2.0 * PI * f64::from(k) * z * f64::from(n) / 5.0;
                (c + a.cos(), s + a.sin())
            });
            let closed = (c * c + s * s).sqrt();
            if closed < 1e-9 {
                cancelled.push(k);
            }
            let one = at(&f.amplitude_n, &f.order, f64::from(k));
            let total = at(&sum.amplitude_n, &f.order, f64::from(k));
            assert!(
                (total - closed * one).abs() <= 1e-6 * largest,
                "{mesh} order {k}: sum {total} N against {closed} x {one} N"
            );
        }
        assert_eq!(cancelled, [1, 2, 3, 4, 6], "{mesh}");
        let up_to_6: Vec<u32> = sum.cancelled.iter().copied().filter(|k| *k <= 6).collect();
        assert_eq!(up_to_6, cancelled, "{mesh}");
        // A single planet carries the cancelled orders.
        assert!(at(&f.amplitude_n, &f.order, 1.0) > 1e-2 * largest);
        assert!(
            !sum.peaks.iter().any(|p| p.label == "1×"),
            "{:?}",
            sum.peaks
        );
    }
}

/// In-phase planets on equal meshes carry equal forces: the load-sharing
/// factor is 1 to 1e-12, with and without backlash.
#[test]
fn in_phase_planets_share_exactly() {
    for b in ["backlash_um=0", "backlash_um=100"] {
        let (model, ss) = solved(&["planets=4", "phasing=in-phase", b], 0.45);
        let s = crate::sharing::load_sharing(&model.system, &ss.meshes);
        assert_eq!(s.len(), 4);
        for k in &s {
            let f = k.factor.unwrap();
            assert!((f - 1.0).abs() <= 1e-12, "{b} {:?}: {f}", k.kind);
        }
    }
}
