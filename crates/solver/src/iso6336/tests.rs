//! Method B against a hand calculation kept here: every intermediate
//! number is recomputed below by plain arithmetic from the standard's
//! formulas (written out, not by calling the code under test), and the
//! code's numbers are compared with them.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use super::*;
use crate::keys;

/// The worked input: the gear pair model's defaults (30/45 teeth, module
/// 4 mm, 20 degrees, J 0.0048 and 0.0243 kg m^2, 1e9 N/m, 500 N m on
/// the pinion), face width 50 mm, grade 6, K_A 1, no tip relief.
fn worked() -> IsoMesh {
    IsoMesh {
        teeth_1: 30,
        teeth_2: 45,
        internal: false,
        module_mm: 4.0,
        pressure_angle_deg: 20.0,
        reduced_mass_kg: 1.045_360_921_321_656,
        stiffness_n_m: 1e9,
        // 500 N m on the 60 mm pitch radius.
        tangential_load_n: 500.0 / 0.060,
    }
}

fn close(what: &str, got: f64, want: f64, tol: f64) {
    assert!(
        (got - want).abs() <= tol * want.abs().max(1.0),
        "{what}: got {got}, hand calculation {want}"
    );
}

/// The hand calculation, step by step (values to 4 figures in comments).
struct Hand {
    eps: f64,
    c_single: f64,
    w: f64,
    b_p: f64,
    b_f: f64,
    b_k: f64,
    f_e_hz: f64,
    c7: f64,
}

fn hand() -> Hand {
    let cos20 = 20f64.to_radians().cos();
    let sin20 = 20f64.to_radians().sin();
    // Radii (mm): r1 = 60, r2 = 90, tips 64 and 94, base 56.38 and 84.57.
    let (rb1, rb2) = (60.0 * cos20, 90.0 * cos20);
    // Path of contact over the base pitch: eps_alpha = 1.695.
    let g =
        (64.0f64 * 64.0 - rb1 * rb1).sqrt() + (94.0f64 * 94.0 - rb2 * rb2).sqrt() - 150.0 * sin20;
    let eps = g / (PI * 4.0 * cos20);
    // Masses on the line of action J / r_b^2: 1.510 and 3.397 kg; reduced 1.0454 kg.
    let m1 = 0.0048 / (rb1 * 1e-3 * rb1 * 1e-3);
    let m2 = 0.0243 / (rb2 * 1e-3 * rb2 * 1e-3);
    let m_red = m1 * m2 / (m1 + m2);
    assert!((m_red - 1.045_36).abs() < 1e-4);
    // N = 1 at the mesh frequency sqrt(k / m_red) / 2 pi = 4 922.5 Hz.
    let f_e_hz = (1e9 / m_red).sqrt() / (2.0 * PI);
    // c_gamma_alpha = 1e9 N/m / 50 mm = 20 N/(mm um); c' = 20 / (0.75 eps + 0.25) = 13.15.
    let c_single = 20.0 / (0.75 * eps + 0.25);
    // F_t = 500 N m / 60 mm = 8 333 N; w = F_t / 50 mm = 166.7 N/mm.
    let w = 500.0 / 0.060 / 50.0;
    // Grade 6 at the wheel (d = 180 mm): f_pT = (0.18 + 1.6 + 5) sqrt 2 = 9.589,
    // f_pb = f_pT cos 20 = 9.010; f_f_alpha = (2.2 + 5) sqrt 2 = 10.18.
    let f_pb = (0.18 + 1.6 + 5.0) * 2f64.sqrt() * cos20;
    let f_fa = (2.2 + 5.0) * 2f64.sqrt();
    // Case-hardened running-in: 7.5 % (under 3 um): 0.6758 and 0.7637 um.
    let (y_p, y_f) = (0.075 * f_pb, 0.075 * f_fa);
    // C_ay = (1500 / 97 - 18.45)^2 / 18 + 1.5 = 1.995 um.
    let c_ay = (1500.0 / 97.0 - 18.45) * (1500.0 / 97.0 - 18.45) / 18.0 + 1.5;
    // B_p = 0.6575, B_f = 0.7431, B_k = 0.8426.
    let b_p = c_single * (f_pb - y_p) / w;
    let b_f = c_single * (f_fa - y_f) / w;
    let b_k = (1.0 - c_single * c_ay / w).abs();
    // 1.5 < eps <= 2.5: C_v7 = 0.125 sin(pi (eps - 2)) + 0.875 = 0.7727.
    let c7 = 0.125 * (PI * (eps - 2.0)).sin() + 0.875;
    Hand {
        eps,
        c_single,
        w,
        b_p,
        b_f,
        b_k,
        f_e_hz,
        c7,
    }
}

#[test]
fn method_b_matches_the_hand_calculation_in_every_range() {
    let h = hand();
    close("eps_alpha", h.eps, 1.6947, 1e-4);
    let r = MeshRating::new(&worked(), &IsoInputs::default()).unwrap();
    close("eps_alpha", r.contact_ratio, h.eps, 1e-12);
    close("c'", r.single_stiffness_n_mm_um, h.c_single, 1e-12);
    close("c_gamma_alpha", r.mesh_stiffness_n_mm_um, 20.0, 1e-12);
    close("w", r.line_load_n_mm, h.w, 1e-12);
    close("B_p", r.b_p, h.b_p, 1e-12);
    close("B_f", r.b_f, h.b_f, 1e-12);
    close("B_k", r.b_k, h.b_k, 1e-12);
    close("f_E", r.resonance_mesh_freq_hz, h.f_e_hz, 1e-9);
    // Above 100 N/mm the main resonance starts at N_S = 0.85.
    assert_eq!(r.n_s, 0.85);
    // Spur, 1 < eps <= 2: C_v1..C_v6 = 0.32, 0.34, 0.23, 0.90, 0.47, 0.47.
    let k_sub = 0.32 * h.b_p + 0.34 * h.b_f + 0.23 * h.b_k;
    let main = 0.32 * h.b_p + 0.34 * h.b_f + 0.90 * h.b_k + 1.0;
    let sup = 0.47 * h.b_p + 0.47 * h.b_f + h.c7;
    // Subcritical, N = 0.5: 0.5 K + 1 = 1.328.
    assert_eq!(r.range(0.5), SpeedRange::Subcritical);
    close("K_v(0.5)", r.kv(0.5), 0.5 * k_sub + 1.0, 1e-12);
    close("K_v(0.5) to 4 figures", r.kv(0.5), 1.3284, 1e-4);
    // Main resonance, N = 1: 2.221.
    assert_eq!(r.range(1.0), SpeedRange::MainResonance);
    close("K_v(1)", r.kv(1.0), main, 1e-12);
    close("K_v(1) to 4 figures", r.kv(1.0), 2.2214, 1e-4);
    // Intermediate, N = 1.3: between 1.15's and 1.5's values, 1.883.
    assert_eq!(r.range(1.3), SpeedRange::Intermediate);
    close(
        "K_v(1.3)",
        r.kv(1.3),
        sup + (main - sup) * (1.5 - 1.3) / 0.35,
        1e-12,
    );
    close("K_v(1.3) to 4 figures", r.kv(1.3), 1.8826, 1e-4);
    // Supercritical, N = 2: 1.431.
    assert_eq!(r.range(2.0), SpeedRange::Supercritical);
    close("K_v(2)", r.kv(2.0), sup, 1e-12);
    close("K_v(2) to 4 figures", r.kv(2.0), 1.4310, 1e-4);
    // The interpolation joins its neighbours.
    close("K_v(1.15+)", r.kv(1.15 + 1e-12), main, 1e-9);
    close("K_v(1.5-)", r.kv(1.5 - 1e-12), sup, 1e-9);
}

/// Below 100 N/mm the main resonance range starts lower:
/// N_S = 0.5 + 0.35 sqrt(w / 100); a tenth of the load gives w = 16.67
/// N/mm and N_S = 0.6429.
#[test]
fn a_light_load_widens_the_main_resonance_range() {
    let mut m = worked();
    m.tangential_load_n /= 10.0;
    let r = MeshRating::new(&m, &IsoInputs::default()).unwrap();
    let n_s = 0.5 + 0.35 * (500.0f64 / 0.060 / 50.0 / 10.0 / 100.0).sqrt();
    close("N_S", r.n_s, n_s, 1e-12);
    close("N_S to 4 figures", r.n_s, 0.6429, 1e-4);
    assert_eq!(r.range(0.7), SpeedRange::MainResonance);
    assert_eq!(r.range(0.6), SpeedRange::Subcritical);
}

/// The C_v table above eps_gamma = 2 and C_v7's three pieces.
#[test]
fn the_c_v_table_follows_the_contact_ratio() {
    let c = c_v(2.2);
    close("C_v2", c[1], 0.57 / 1.9, 1e-12);
    close("C_v3", c[2], 0.096 / 0.64, 1e-12);
    close("C_v4", c[3], (0.57 - 0.11) / 0.76, 1e-12);
    close("C_v6", c[5], 0.12 / 0.46, 1e-12);
    close("C_v7", c[6], 0.125 * (0.2 * PI).sin() + 0.875, 1e-12);
    assert_eq!(c_v(1.4)[6], 0.75);
    assert_eq!(c_v(2.7)[6], 1.0);
    // Continuous at eps = 2 for C_v7: 0.875.
    close("C_v7(2)", c_v(2.0)[6], 0.875, 1e-12);
}

/// An internal pair: the ring's tip circle is inside its pitch circle and
/// the centre distance is r2 - r1. Long planet 18 teeth, ring 84, m 4:
/// r 36 and 168, tips 40 and 164.
#[test]
fn the_contact_ratio_of_an_internal_pair_is_the_hand_calculation() {
    let a = 20f64.to_radians();
    let (rb1, rb2) = (36.0 * a.cos(), 168.0 * a.cos());
    let g = (40.0f64 * 40.0 - rb1 * rb1).sqrt() - (164.0f64 * 164.0 - rb2 * rb2).sqrt()
        + 132.0 * a.sin();
    close(
        "eps internal",
        crate::waveform::contact_ratio(18, 84, true, 4.0, 20.0),
        g / (PI * 4.0 * a.cos()),
        1e-12,
    );
}

/// Refusals name the value and the allowed range.
#[test]
fn bad_inputs_are_refused_naming_the_value() {
    let refused = |m: IsoMesh, i: IsoInputs| match MeshRating::new(&m, &i) {
        Err(SolverError::OutOfRange {
            key,
            value,
            allowed,
        }) => format!("{key} = {value}: {allowed}"),
        other => panic!("not refused: {other:?}"),
    };
    let grade = IsoInputs {
        accuracy_grade: -1.0,
        ..IsoInputs::default()
    };
    let e = refused(worked(), grade);
    assert!(
        e.contains("accuracy grade = -1") && e.contains("1 ..= 11"),
        "{e}"
    );
    let half = IsoInputs {
        accuracy_grade: 6.5,
        ..IsoInputs::default()
    };
    assert!(refused(worked(), half).contains("accuracy grade = 6.5"));
    let mut m = worked();
    m.reduced_mass_kg = 0.0;
    let e = refused(m, IsoInputs::default());
    assert!(
        e.contains("reduced mass (kg) = 0") && e.contains("positive"),
        "{e}"
    );
    let mut m = worked();
    m.tangential_load_n = f64::NAN;
    assert!(refused(m, IsoInputs::default()).contains("tangential load (N) = NaN"));
    let wide = IsoInputs {
        face_width_mm: 0.0,
        ..IsoInputs::default()
    };
    assert!(refused(worked(), wide).contains("face width (mm) = 0"));
}

fn model(assignments: &[&str]) -> (ModelParams, Model) {
    let mut p = ModelParams::default();
    for a in assignments {
        keys::set_assignment(&mut p, a).unwrap();
    }
    let m = Model::new(&p).unwrap();
    (p, m)
}

/// The gear pair's reduced mass is the model's equivalent mass (the same
/// two inertias on one line of action), so N is Omega exactly.
#[test]
fn on_the_gear_pair_the_resonance_ratio_is_omega() {
    let (p, m) = model(&["model=gear-pair"]);
    let r = rate_model(&p, &m, &IsoInputs::default()).unwrap();
    assert_eq!(r.len(), 1);
    for omega in [0.3, 1.0, 1.7] {
        let n = r[0].rating.resonance_ratio(m.system.mesh_freq_hz(omega));
        close("N", n, omega, 1e-12);
    }
    close("F_t", r[0].mesh.tangential_load_n, 8333.333, 1e-3);
}

/// The planetary rules: sun meshes m_P m_S / (m_S + p m_P), ring meshes
/// the planet's m_P, the planet-planet mesh a plain pair; the defaults'
/// masses J / r_b^2 by hand.
#[test]
fn planetary_meshes_follow_the_standards_reduced_mass() {
    let (p, m) = model(&[]);
    let r = rate_model(&p, &m, &IsoInputs::default()).unwrap();
    assert_eq!(r.len(), 12);
    let c = 20f64.to_radians().cos();
    let rb = |z: f64| 0.004 * z / 2.0 * c;
    let (m_s1, m_s2) = (0.015 / rb(36.0).powi(2), 0.059 / rb(48.0).powi(2));
    let (m_a, m_b) = (0.0019 / rb(21.0).powi(2), 0.0022 / rb(18.0).powi(2));
    let want = |name: &str| match &name[..2] {
        "s1" => m_a * m_s1 / (m_s1 + 3.0 * m_a),
        "s2" => m_b * m_s2 / (m_s2 + 3.0 * m_b),
        "rb" => m_b,
        _ => m_a * m_b / (m_a + m_b),
    };
    for (mesh, rating) in m.system.meshes.iter().zip(&r) {
        close(
            &mesh.name,
            rating.mesh.reduced_mass_kg,
            want(&mesh.name),
            1e-12,
        );
        assert!(rating.rating.kv(1.0) > 1.0, "{}", mesh.name);
        assert_eq!(rating.mesh.internal, mesh.name.starts_with("rb"));
    }
}

/// A model whose meshes carry no load cannot be rated: the refusal names
/// the mesh.
#[test]
fn an_unloaded_mesh_is_refused_by_name() {
    let (p, m) = model(&["model=gear-pair", "torque_pinion_nm=0"]);
    match rate_model(&p, &m, &IsoInputs::default()) {
        Err(SolverError::OutOfRange { key, .. }) => {
            assert_eq!(key, "tangential load (N) of mesh pg")
        }
        other => panic!("{other:?}"),
    }
}
