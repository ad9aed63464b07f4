//! The flat key table: every key round-trips, JSON round-trips, and hostile
//! input never panics.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use proptest::prelude::*;
use solver::keys::{self, KeyType, Value, KEYS};
use solver::params::{ModelKind, ModelParams};

#[test]
fn every_key_round_trips_on_the_models_it_applies_to() {
    for model in [ModelKind::Ravigneaux, ModelKind::GearPair] {
        let defaults = ModelParams::defaults(model);
        for spec in KEYS.iter().filter(|k| k.applies.includes(model)) {
            let v = keys::get(&defaults, spec.name)
                .unwrap_or_else(|| panic!("{} has no value on {}", spec.name, model.name()));
            let mut p = defaults.clone();
            keys::set(&mut p, spec.name, v.clone())
                .unwrap_or_else(|e| panic!("{}: {e}", spec.name));
            assert_eq!(keys::get(&p, spec.name), Some(v), "{}", spec.name);
        }
        for spec in KEYS.iter().filter(|k| !k.applies.includes(model)) {
            let mut p = defaults.clone();
            let any = match spec.ty {
                KeyType::Choice(w) => Value::Text(w[0].into()),
                KeyType::Float { min, .. } | KeyType::FloatOrAuto { min, .. } => Value::Num(min),
                KeyType::Int { min, .. } => Value::Num(min as f64),
            };
            let err = keys::set(&mut p, spec.name, any).expect_err(spec.name);
            assert!(err.to_string().contains(spec.name), "{err}");
        }
    }
}

#[test]
fn every_key_is_written_to_json_and_read_back() {
    let mut p = ModelParams::default();
    for a in [
        "backlash_s2b_um=55",
        "te_cos_rb_um=-3",
        "phasing=sequential",
        "planets=5",
        "torque_s2_nm=auto",
    ] {
        keys::set_assignment(&mut p, a).expect(a);
    }
    let json = keys::to_json(&p);
    assert_eq!(
        json.get("model").and_then(|v| v.as_str()),
        Some("ravigneaux")
    );
    let back = keys::from_json(&json).expect("read back");
    assert_eq!(back, p);
    let text = serde_json::to_string(&serde_json::Value::Object(json)).expect("text");
    assert_eq!(keys::from_json_str(&text).expect("parse"), p);
}

#[test]
fn per_kind_keys_win_over_shortcuts_in_any_order() {
    let text = r#"{"backlash_s1a_um": 10, "backlash_um": 200}"#;
    let p = keys::from_json_str(text).expect("parse");
    assert_eq!(keys::get(&p, "backlash_s1a_um"), Some(Value::Num(10.0)));
    assert_eq!(keys::get(&p, "backlash_rb_um"), Some(Value::Num(200.0)));
}

#[test]
fn messages_name_the_key_the_value_and_the_range() {
    let mut p = ModelParams::default();
    let e = keys::set_assignment(&mut p, "backlash_um=1e9")
        .expect_err("range")
        .to_string();
    assert!(
        e.contains("backlash_um") && e.contains("1e9") && e.contains("0 ..= 1000"),
        "{e}"
    );
    let e = keys::set_assignment(&mut p, "bcklash_um=3")
        .expect_err("typo")
        .to_string();
    assert!(e.contains("did you mean `backlash_um`"), "{e}");
    let e = keys::set_assignment(&mut p, "phasing=random")
        .expect_err("choice")
        .to_string();
    assert!(e.contains("in-phase") && e.contains("sequential"), "{e}");
    let e = keys::from_json_str("[1, 2]")
        .expect_err("not an object")
        .to_string();
    assert!(e.contains("flat JSON object"), "{e}");
    // The failed assignments left the parameters untouched.
    assert_eq!(p, ModelParams::default());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn arbitrary_assignments_never_panic(key in "\\PC{0,40}", value in "\\PC{0,40}") {
        let mut p = ModelParams::default();
        let _ = keys::set_assignment(&mut p, &format!("{key}={value}"));
    }

    #[test]
    fn known_keys_with_hostile_values_keep_a_valid_set(
        idx in 0..200usize,
        value in prop_oneof![
            Just("nan".to_string()), Just("inf".to_string()), Just("-inf".to_string()),
            Just("1e308".to_string()), Just("-0".to_string()), Just("".to_string()),
            "\\PC{0,20}", any::<f64>().prop_map(|x| x.to_string()),
        ],
    ) {
        let spec = &KEYS[idx % KEYS.len()];
        let mut p = ModelParams::default();
        if keys::set_assignment(&mut p, &format!("{}={value}", spec.name)).is_ok() {
            // Whatever was accepted is in range, so the set still builds
            // unless a cross-field rule (tooth counts, torques) objects.
            if let Some(Value::Num(x)) = keys::get(&p, spec.name) {
                prop_assert!(x.is_finite());
            }
        }
    }

    #[test]
    fn json_files_of_any_shape_never_panic(text in "\\PC{0,200}") {
        let _ = keys::from_json_str(&text);
    }
}

/// `te_meshes`: the TE reading of the seed's Fig. 2 ("Ec_all"). The shortcut
/// `te_um` lands on the s1a meshes only, or on every kind, and the order of
/// the two assignments does not matter.
#[test]
fn te_meshes_moves_the_shortcut_amplitude_in_either_order() {
    let sines = |p: &ModelParams| match p {
        ModelParams::Ravigneaux(r) => r.te_um.map(|t| t.sin),
        ModelParams::GearPair(_) => panic!("compound set expected"),
    };
    let mut a = ModelParams::default();
    keys::set_assignment(&mut a, "te_um=30").unwrap();
    assert_eq!(sines(&a), [30.0, 0.0, 0.0, 0.0]);
    keys::set_assignment(&mut a, "te_meshes=all").unwrap();
    assert_eq!(sines(&a), [30.0; 4]);
    let mut b = ModelParams::default();
    keys::set_assignment(&mut b, "te_meshes=all").unwrap();
    keys::set_assignment(&mut b, "te_um=30").unwrap();
    assert_eq!(a, b);
    // Back to the s1a reading: the other kinds lose the mirrored amplitude.
    keys::set_assignment(&mut b, "te_meshes=s1a").unwrap();
    assert_eq!(sines(&b), [30.0, 0.0, 0.0, 0.0]);
    // Setting the same reading again changes nothing, so a per-kind value stays.
    keys::set_assignment(&mut b, "te_sin_rb_um=5").unwrap();
    keys::set_assignment(&mut b, "te_meshes=s1a").unwrap();
    assert_eq!(sines(&b), [30.0, 0.0, 0.0, 5.0]);
    // A JSON file round-trips the reading and the per-kind values.
    let back = keys::from_json(&keys::to_json(&a)).unwrap();
    assert_eq!(back, a);
    assert_eq!(
        keys::get(&back, "te_meshes"),
        Some(Value::Text("all".into()))
    );
    let e = keys::set_assignment(&mut b, "te_meshes=some").unwrap_err();
    assert!(e.to_string().contains("te_meshes"), "{e}");
}

/// `ring_support_radius_mm`: the ring's support torque stiffness is
/// k_rt r^2 with r the base radius m z_r cos(alpha) / 2 by default, and the
/// seed's printed 15.79 mm gives (15.79 / 157.868)^2 of it.
#[test]
fn ring_support_radius_scales_the_support_by_its_square() {
    use solver::system::MeshSystem;
    let support = |assignments: &[&str]| {
        let mut p = ModelParams::default();
        for a in assignments {
            keys::set_assignment(&mut p, a).unwrap();
        }
        let sys = MeshSystem::build(&p).unwrap();
        let r = sys.dof_names.iter().position(|n| n == "theta_r").unwrap();
        let mut e = vec![0.0; sys.dof()];
        e[r] = 1.0;
        let mut out = vec![0.0; sys.dof()];
        sys.support.mul(&e, &mut out);
        out[r]
    };
    let rho_r = 4e-3 * 84.0 / 2.0 * 20f64.to_radians().cos();
    let auto = support(&[]);
    assert!((auto - 1e9 * rho_r * rho_r).abs() < 1e-9 * auto, "{auto}");
    let printed = support(&["ring_support_radius_mm=15.79"]);
    assert!((printed - 1e9 * 0.01579f64.powi(2)).abs() < 1e-9 * printed);
    let explicit = support(&[&format!("ring_support_radius_mm={}", rho_r * 1e3)]);
    assert!((explicit - auto).abs() < 1e-12 * auto);
    let mut p = ModelParams::default();
    keys::set_assignment(&mut p, "ring_support_radius_mm=15.79").unwrap();
    keys::set_assignment(&mut p, "ring_support_radius_mm=auto").unwrap();
    assert_eq!(p, ModelParams::default());
}
