//! The dynamic-factor view: the standard's curve where its ranges put it,
//! the model's curve from the steady states, and the words.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use super::*;
use crate::protocol::{FrSample, KindSharing, MeshExtremes, MeshSummary};
use solver::keys;

fn model(assignments: &[&str]) -> (ModelParams, Model) {
    let mut p = ModelParams::default();
    for a in assignments {
        keys::set_assignment(&mut p, a).unwrap();
    }
    let m = Model::new(&p).unwrap();
    (p, m)
}

fn ctx(from: f64, to: f64, selected: f64) -> ViewContext {
    ViewContext {
        omega_from: from,
        omega_to: to,
        selected_omega: selected,
        mesh_label: String::new(),
        natural: Vec::new(),
        speed: crate::speed::SpeedAxis::default(),
    }
}

/// Steady states at Omega 0.2, 0.4, ... with factor 1 + Omega on mesh 0
/// (one failed point, one without a factor).
fn states(meshes: usize) -> FrStore {
    let mut s = FrStore::new(6, 10, 10);
    let extremes = |f: Option<f64>| MeshExtremes {
        rel_min_um: 0.0,
        rel_max_um: 1.0,
        regime: Regime::NoImpact,
        dynamic_factor: f,
    };
    s.add(
        (0..6u32)
            .map(|i| {
                let omega = 0.2 * f64::from(i + 1);
                let f = (i != 3).then_some(1.0 + omega);
                FrSample {
                    index: i,
                    omega,
                    meshes: if i == 5 {
                        Vec::new()
                    } else {
                        vec![extremes(f); meshes]
                    },
                    period: Some(1),
                    error: (i == 5).then(|| "failed".into()),
                }
            })
            .rev()
            .collect(),
    );
    s
}

/// On the gear pair N is Omega, so the standard's range edges sit at
/// Omega N_S, 1.15 and 1.5, and K_v's polylines are the rating's values
/// at their ends: rising in proportion to N up to N_S, a jump, the
/// plateau, the interpolation, the supercritical constant.
#[test]
fn the_standards_curve_follows_its_ranges_on_the_gear_pair() {
    let (p, m) = model(&["model=gear-pair"]);
    let v = DynamicView::new(
        &p,
        &m,
        &ctx(0.1, 2.0, 0.5),
        0,
        None,
        None,
        &IsoInputs::default(),
    )
    .unwrap();
    assert!((v.omega_per_n - 1.0).abs() < 1e-12, "{}", v.omega_per_n);
    let r = &v.rating;
    assert_eq!(r.n_s, 0.85);
    assert_eq!(v.kv.len(), 2, "one break, at N_S: {:?}", v.kv);
    let first = &v.kv[0];
    assert_eq!(first.len(), 2);
    assert!((first[0].0 - 0.1).abs() < 1e-12 && (first[1].0 - 0.85).abs() < 1e-12);
    assert!((first[1].1 - r.kv(0.85)).abs() < 1e-9);
    let second = &v.kv[1];
    let xs: Vec<f64> = second.iter().map(|p| p.0).collect();
    for (x, want) in xs.iter().zip([0.85, 1.15, 1.5, 2.0]) {
        assert!((x - want).abs() < 1e-12, "{xs:?}");
    }
    // The plateau is flat, the supercritical end flat at a lower value.
    assert!((second[0].1 - second[1].1).abs() < 1e-12);
    assert!((second[2].1 - second[3].1).abs() < 1e-12);
    assert!(second[2].1 < second[1].1);
    // The jump at N_S: the main resonance is above the subcritical end.
    assert!(second[0].1 > first[1].1);
    let (start, centre, end) = v.main_band();
    assert!(
        (start - 0.85).abs() < 1e-12 && (centre - 1.0).abs() < 1e-12 && (end - 1.15).abs() < 1e-12
    );
}

/// The model's curve is every computed steady state's factor for the
/// mesh, by rising Omega, skipping failed points and points without one.
#[test]
fn the_models_curve_comes_from_the_steady_states() {
    let (p, m) = model(&["model=gear-pair"]);
    let s = states(1);
    let v = DynamicView::new(
        &p,
        &m,
        &ctx(0.1, 2.0, 0.5),
        0,
        Some(&s),
        None,
        &IsoInputs::default(),
    )
    .unwrap();
    let omegas: Vec<f64> = v.nonlinear.iter().map(|p| p.0).collect();
    assert_eq!(omegas.len(), 4, "{omegas:?}");
    assert!(omegas.windows(2).all(|w| w[0] < w[1]));
    for (o, f) in &v.nonlinear {
        assert!((f - (1.0 + o)).abs() < 1e-12);
    }
    assert_eq!(v.states, 6);
    let csv = dynamic_csv(&v);
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("omega,input_speed_rpm,dynamic_factor,kv_iso6336,iso_range,resonance_ratio")
    );
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    // The four states plus K_v's break points 0.1, 0.85, 1.15, 1.5, 2.0.
    assert_eq!(rows.len(), 4 + 5, "{csv}");
    for r in &rows {
        let o: f64 = r[0].parse().unwrap();
        let kv: f64 = r[3].parse().unwrap();
        assert!((kv - v.kv_at(o)).abs() < 1e-12);
        assert_eq!(r[4], v.range_at(o).name());
    }
    assert!(dynamic_json(&v)["dynamic_factor"].as_array().unwrap().len() == 4);
}

/// The selected state: its factor, its regime's reason, and the planets'
/// sharing labelled with the set's phasing.
#[test]
fn the_note_gives_both_factors_and_the_sharing_with_its_phasing() {
    let (p, m) = model(&["planets=5", "phasing=sequential"]);
    let mut r = crate::views::test_support::omega_result();
    r.omega = 0.35;
    r.all_meshes = m
        .system
        .meshes
        .iter()
        .map(|x| MeshSummary {
            name: x.name.clone(),
            regime: Regime::SingleSided,
            dynamic_factor: Some(2.5),
        })
        .collect();
    r.load_sharing = vec![KindSharing {
        kind: "s2b".into(),
        peak_force_n: vec![1.0, 1.2, 1.0, 1.0, 0.8],
        factor: Some(1.2),
    }];
    let v = DynamicView::new(
        &p,
        &m,
        &ctx(0.1, 2.0, 0.35),
        0,
        None,
        Some(&r),
        &IsoInputs::default(),
    )
    .unwrap();
    let note = v.note();
    for words in [
        "At Ω 0.350",
        "the model's dynamic factor 2.50",
        "dynamic factor Kv (ISO 6336-1, method B)",
        "subcritical",
        "the teeth part and strike again",
        "5 planets, sequential phasing: large sun – long planet 1.200",
    ] {
        assert!(note.contains(words), "`{words}` not in {note}");
    }
    assert_eq!(dynamic_json(&v)["load_sharing"]["phasing"], "sequential");
    // A state at another Omega is not the selected one's.
    r.omega = 0.5;
    let v = DynamicView::new(
        &p,
        &m,
        &ctx(0.1, 2.0, 0.35),
        0,
        None,
        Some(&r),
        &IsoInputs::default(),
    )
    .unwrap();
    assert!(v.selected.is_none() && v.sharing.is_empty());
    assert!(v.note().contains("computing"), "{}", v.note());
}

/// A mesh the standard cannot rate (no load) gives the reason.
#[test]
fn an_unloaded_mesh_gives_the_reason() {
    let (p, m) = model(&["model=gear-pair", "torque_pinion_nm=0"]);
    let e = DynamicView::new(
        &p,
        &m,
        &ctx(0.1, 2.0, 0.5),
        0,
        None,
        None,
        &IsoInputs::default(),
    )
    .unwrap_err()
    .to_string();
    assert!(
        e.contains("mesh pg") && e.contains("tangential load"),
        "{e}"
    );
}

/// Over speed, each planet mesh's largest force is its dynamic factor
/// times its static force. With every mesh at the same factor (equal
/// planets) every kind shares exactly (1, to round-off); raising one
/// planet's s1a factor by 30 % (statics equal across the planets) makes
/// that kind's factor 1.3 / (1 + 0.3 / 3) = 1.3 / 1.1, its peak force 1.3
/// times the static force.
#[test]
fn the_load_sharing_over_speed_is_the_planets_largest_over_mean() {
    let (p, m) = model(&["planets=3", "phasing=in-phase"]);
    let n = m.system.meshes.len();
    let mut s = states(n);
    let v = DynamicView::new(
        &p,
        &m,
        &ctx(0.1, 2.0, 0.5),
        0,
        Some(&s),
        None,
        &IsoInputs::default(),
    )
    .unwrap();
    // Omega 0.8 has no factor, 1.2 failed: four states remain.
    let omegas: Vec<f64> = v.sharing_over_speed.iter().map(|x| x.omega).collect();
    assert_eq!(omegas.len(), 4, "{omegas:?}");
    for at in &v.sharing_over_speed {
        assert_eq!(at.kinds.len(), 4);
        assert!((at.worst().unwrap() - 1.0).abs() <= 1e-12, "{at:?}");
    }
    let s1a2 = m
        .system
        .meshes
        .iter()
        .position(|x| x.name == "s1a2")
        .unwrap();
    let fs = m.statics.mesh_force_n[s1a2];
    let mut pts: Vec<FrSample> = s.points.iter().flatten().cloned().collect();
    for pt in &mut pts {
        if let Some(e) = pt.meshes.get_mut(s1a2) {
            e.dynamic_factor = e.dynamic_factor.map(|f| f * 1.3);
        }
    }
    s = FrStore::new(6, 10, 10);
    s.add(pts);
    let v = DynamicView::new(
        &p,
        &m,
        &ctx(0.1, 2.0, 0.5),
        0,
        Some(&s),
        None,
        &IsoInputs::default(),
    )
    .unwrap();
    let first = &v.sharing_over_speed[0];
    let s1a = first.kinds.iter().find(|k| k.kind == "s1a").unwrap();
    assert!((s1a.factor.unwrap() - 1.3 / 1.1).abs() <= 1e-12, "{s1a:?}");
    assert!((s1a.peak_force_n[1] - 1.3 * (1.0 + first.omega) * fs).abs() <= 1e-9 * fs);
    assert!((first.worst().unwrap() - 1.3 / 1.1).abs() <= 1e-12);
    let (lo, hi) = v.sharing_range().unwrap();
    assert!((lo - 1.3 / 1.1).abs() <= 1e-12 && (hi - lo).abs() <= 1e-12);
    assert!(
        v.note().contains("runs from 1.182 to 1.182"),
        "{}",
        v.note()
    );
    let j = dynamic_json(&v);
    assert_eq!(j["load_sharing"]["over_speed"].as_array().unwrap().len(), 4);
}
