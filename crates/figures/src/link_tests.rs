//! Tests of the link decoder and encoder (kept beside `link.rs`, which
//! would otherwise pass the 800-line limit).

use super::*;
use crate::settings::{MeshSel, ViewOptions};
use proptest::prelude::*;

#[test]
fn defaults_round_trip() {
    let s = Settings::default();
    let q = encode(&s);
    assert!(
        q.starts_with("model=ravigneaux&omega=0.35&mesh=s1a1"),
        "{q}"
    );
    let d = decode(&q);
    assert!(d.issues.is_empty(), "{:?}", d.issues);
    assert_eq!(d.settings, s);
}

#[test]
fn changed_values_restore_exactly() {
    let mut s = Settings::default();
    keys::set_assignment(&mut s.params, "backlash_um=123.456789012345").unwrap();
    keys::set_assignment(&mut s.params, "te_um=0.1").unwrap();
    keys::set_assignment(&mut s.params, "te_cos_rb_um=-7.25").unwrap();
    keys::set_assignment(&mut s.params, "phasing=sequential").unwrap();
    keys::set_assignment(&mut s.params, "planets=5").unwrap();
    keys::set_assignment(&mut s.params, "damping_ratio=0.0333333333333333").unwrap();
    s.view.omega = 1.0 / 3.0;
    s.view.mesh = MeshSel::Worst;
    s.view.bif_dir = solver::sweep::Directions::Down;
    let q = encode(&s);
    assert!(q.contains("backlash_um=123.456789012345"), "{q}");
    assert!(
        q.contains("te_um=0.1") && !q.contains("te_sin_s1a_um"),
        "{q}"
    );
    let d = decode(&q);
    assert!(d.issues.is_empty(), "{:?}", d.issues);
    assert_eq!(d.settings, s);
    // Per-kind backlash that differ are written per kind.
    keys::set_assignment(&mut s.params, "backlash_ab_um=40").unwrap();
    let q = encode(&s);
    assert!(
        q.contains("backlash_ab_um=40") && !q.contains("backlash_um="),
        "{q}"
    );
    assert_eq!(decode(&q).settings, s);
}

#[test]
fn gear_pair_round_trips() {
    let mut s = Settings::default();
    keys::set_assignment(&mut s.params, "model=gear-pair").unwrap();
    keys::set_assignment(&mut s.params, "backlash_um=55").unwrap();
    s.view.mesh = MeshSel::Named("pg".into());
    let d = decode(&encode(&s));
    assert!(d.issues.is_empty(), "{:?}", d.issues);
    assert_eq!(d.settings, s);
    // A compound-only key on the gear pair is named, the rest applies.
    let d = decode("model=gear-pair&planets=4&backlash_um=20");
    assert_eq!(d.issues.len(), 1, "{:?}", d.issues);
    assert!(d.issues[0].contains("planets"));
    assert_eq!(
        keys::get(&d.settings.params, "backlash_um"),
        Some(Value::Num(20.0))
    );
    assert_eq!(d.settings.view.mesh, MeshSel::Named("pg".into()));
}

/// A key given twice is named in an issue (it was settled silently), its
/// last value counting; in the pinned state A too.
#[test]
fn a_key_given_twice_is_named() {
    let d = decode("model=gear-pair&backlash_um=20&backlash_um=60");
    assert_eq!(d.issues.len(), 1, "{:?}", d.issues);
    assert!(
        d.issues[0].contains("`backlash_um` is given twice")
            && d.issues[0].contains("`60` counts")
            && d.issues[0].contains("`20` was ignored"),
        "{:?}",
        d.issues
    );
    assert_eq!(
        keys::get(&d.settings.params, "backlash_um"),
        Some(Value::Num(60.0))
    );
    let d = decode("model=gear-pair&a=model%3Dgear-pair%26te_um%3D5%26te_um%3D9");
    assert!(
        d.issues
            .iter()
            .any(|i| i.starts_with("A (pinned): `te_um` is given twice")),
        "{:?}",
        d.issues
    );
}

/// The speed axes' unit rides in `axis=rpm`, and only then: a link of the
/// default Ω axes is what it was before the key existed.
#[test]
fn the_speed_axis_rides_in_the_link_only_when_rpm() {
    let s = Settings::default();
    assert!(!encode(&s).contains("axis="), "{}", encode(&s));
    let mut r = Settings::default();
    r.view.axis = crate::speed::AxisUnit::Rpm;
    let q = encode(&r);
    assert!(q.contains("&axis=rpm"), "{q}");
    let d = decode(&q);
    assert!(d.issues.is_empty(), "{:?}", d.issues);
    assert_eq!(d.settings, r);
    // A link written with the default said aloud reads the same.
    assert_eq!(decode(&format!("{}&axis=omega", encode(&s))).settings, s);
    // The unit is how the state is read: A and B do not differ by it.
    assert_eq!(ab_difference(&s, &r, 3).0, "same settings");
}

/// A malformed unit is named with what is allowed, in words, and the
/// rest of the link applies with the Ω axes kept.
#[test]
fn a_malformed_speed_axis_is_named_and_the_rest_kept() {
    let d = decode("model=ravigneaux&omega=0.9&axis=rmp");
    assert_eq!(d.issues.len(), 1, "{:?}", d.issues);
    let i = &d.issues[0];
    assert!(
        i.starts_with("From the link: Speed axes must be one of")
            && i.contains("rpm")
            && i.contains("(not rmp)"),
        "{i}"
    );
    assert_eq!(d.settings.view.axis, crate::speed::AxisUnit::Omega);
    assert_eq!(d.settings.view.omega, 0.9);
}

/// rpm and Ω map each other exactly (1e-12 relative) on both models and
/// through a link: a speed typed in rpm is stored as its Ω, written in
/// the link, and reads back as the same rpm. The factor is derived here
/// by hand from the input member's teeth and its speed relative to the
/// carrier: f_mesh = rpm / 60 z_in |n_in - n_c| / n_in, Ω = 2π f_mesh / ω_ref.
#[test]
fn rpm_and_omega_map_each_other_exactly_through_a_link() {
    use crate::speed::SpeedScale;
    for kind in [ModelKind::Ravigneaux, ModelKind::GearPair] {
        let mut s = Settings {
            params: ModelParams::defaults(kind),
            ..Settings::default()
        };
        s.view.mesh = MeshSel::Named(mesh_names(&s.params)[0].clone());
        s.view.axis = crate::speed::AxisUnit::Rpm;
        let model = Model::new(&s.params).unwrap();
        let scale = SpeedScale::of(&model);
        let sp = model.system.speed;
        let omega_per_rpm = f64::from(sp.input_teeth) * sp.relative_per_input.abs() / 60.0
            * 2.0
            * std::f64::consts::PI
            / model.system.omega_ref_rad_s;
        for rpm in [137.0, 1000.0, 2999.5, 3000.0, 4321.123456789] {
            let omega = scale.omega(rpm);
            assert!(
                (omega - rpm * omega_per_rpm).abs() <= 1e-12 * omega,
                "{kind:?} {rpm}"
            );
            assert!(
                (scale.rpm(omega) - rpm).abs() <= 1e-12 * rpm,
                "{kind:?} {rpm}"
            );
            if !(0.01..=20.0).contains(&omega) {
                continue;
            }
            s.view.omega = omega;
            let d = decode(&encode(&s));
            assert!(d.issues.is_empty(), "{:?}", d.issues);
            assert_eq!(d.settings, s);
            let back = scale.rpm(d.settings.view.omega);
            assert!((back - rpm).abs() <= 1e-12 * rpm, "{kind:?} {rpm} {back}");
        }
        for omega in [0.01, 0.35, 1.0, 1.7, 20.0] {
            let back = scale.omega(scale.rpm(omega));
            assert!((back - omega).abs() <= 1e-12 * omega, "{kind:?} {omega}");
        }
    }
}

#[test]
fn bad_values_are_named_with_their_range_and_others_kept() {
    let d = decode(
        "?backlash_um=5000&te_um=30&omega=abc&bif_points=100000000&damping_ratio=NaN&foo=1&oops",
    );
    let all = d.issues.join("\n");
    assert!(
        all.contains("Backlash must be between 0 and 1000 µm (not 5000)"),
        "{all}"
    );
    assert!(
        all.contains("Selected Ω must be between 0.01 and 20 (not abc)"),
        "{all}"
    );
    assert!(
        all.contains("Bifurcation points must be a whole number between 2 and 1000"),
        "{all}"
    );
    assert!(all.contains("Damping ratio ξ must be"), "{all}");
    assert!(!all.contains("..="), "{all}");
    assert!(all.contains("foo"), "{all}");
    assert!(all.contains("oops"), "{all}");
    assert_eq!(
        keys::get(&d.settings.params, "te_um"),
        Some(Value::Num(30.0))
    );
    assert_eq!(
        keys::get(&d.settings.params, "backlash_um"),
        Some(Value::Num(100.0))
    );
    assert_eq!(
        d.settings.view.bif_points,
        ViewOptions::default().bif_points
    );
}

#[test]
fn combinations_that_cannot_be_built_drop_the_breaking_key() {
    // An explicit s2 torque that does not balance s1: the model refuses it.
    let d = decode("torque_s2_nm=5&backlash_um=150");
    assert!(
        d.issues.iter().any(|i| i.contains("torque_s2_nm")),
        "{:?}",
        d.issues
    );
    assert_eq!(
        keys::get(&d.settings.params, "backlash_um"),
        Some(Value::Num(150.0))
    );
    assert!(Model::new(&d.settings.params).is_ok());
}

#[test]
fn a_pinned_state_rides_along_and_restores_exactly() {
    let mut a = Settings::default();
    keys::set_assignment(&mut a.params, "backlash_um=100").unwrap();
    a.view.omega = 0.5;
    let mut b = Settings::default();
    keys::set_assignment(&mut b.params, "backlash_um=150").unwrap();
    keys::set_assignment(&mut b.params, "te_um=35").unwrap();
    let q = encode_ab(&b, Some(&a));
    assert!(q.contains("&a=model%3Dravigneaux"), "{q}");
    let d = decode(&q);
    assert!(d.issues.is_empty(), "{:?}", d.issues);
    assert_eq!(d.settings, b);
    assert_eq!(d.pinned.as_ref(), Some(&a));
    // Without a pinned state there is no `a`, and none comes back.
    assert_eq!(decode(&encode_ab(&b, None)).pinned, None);
    // The difference names the keys that differ, per side.
    let (ta, tb) = ab_difference(&a, &b, 3);
    assert!(
        ta.contains("backlash 100 µm") && tb.contains("backlash 150 µm"),
        "{ta} | {tb}"
    );
    assert!(
        ta.contains("selected Ω 0.5") && tb.contains("TE amplitude 35 µm"),
        "{ta} | {tb}"
    );
    assert_eq!(ab_difference(&a, &a, 3).0, "same settings");
    // Bad values inside A are named as A's; a nested `a` is ignored.
    let d = decode("backlash_um=150&a=backlash_um%3D5000%26a%3Dx");
    assert_eq!(d.issues.len(), 2, "{:?}", d.issues);
    assert!(d.issues.iter().all(|i| i.starts_with("A (pinned): ")));
    assert!(d.pinned.is_some());
}

#[test]
fn a_pinned_state_that_names_no_setting_is_reported_and_ignored() {
    // `?a=x` turned the comparison on with default settings.
    for q in [
        "a=x",
        "a=",
        "backlash_um=150&a=%%%",
        "a=foo%3D1",
        "a=a%3Dmodel",
    ] {
        let d = decode(q);
        assert_eq!(d.pinned, None, "{q}");
        assert_eq!(d.issues.len(), 1, "{q}: {:?}", d.issues);
        assert!(
            d.issues[0].starts_with("a = ") && d.issues[0].contains("ignored"),
            "{q}: {:?}",
            d.issues
        );
    }
    assert_eq!(
        keys::get(
            &decode("backlash_um=150&a=x").settings.params,
            "backlash_um"
        ),
        Some(Value::Num(150.0))
    );
    // A pinned state with only a view option, or only the model, is one.
    assert!(decode("a=omega%3D0.5").pinned.is_some());
    assert!(decode("a=model%3Dgear-pair").pinned.is_some());
}

#[test]
fn both_inverted_ranges_are_reset_like_one() {
    let d = decode("omega_from=1.5&omega_to=1&map_from=50&map_to=10");
    let v = &d.settings.view;
    let def = ViewOptions::default();
    assert_eq!((v.omega_from, v.omega_to), (def.omega_from, def.omega_to));
    assert_eq!((v.map_from, v.map_to), (def.map_from, def.map_to));
    let all = d.issues.join("\n");
    assert!(
        all.contains("frequency range") && all.contains("map's range"),
        "{all}"
    );
    // Only the map's range inverted: the same reset.
    let d = decode("map_from=50&map_to=10");
    assert_eq!(
        (d.settings.view.map_from, d.settings.view.map_to),
        (def.map_from, def.map_to)
    );
}

#[test]
fn minus_zero_is_normalized_to_zero() {
    let d = decode("te_um=-0&map_from=-0&te_cos_rb_um=-0.0");
    assert!(d.issues.is_empty(), "{:?}", d.issues);
    let q = encode(&d.settings);
    assert!(!q.contains("-0"), "{q}");
    assert_eq!(
        keys::get(&d.settings.params, "te_um"),
        Some(Value::Num(0.0))
    );
    assert!(d.settings.view.map_from.is_sign_positive());
}

#[test]
fn a_family_rides_along_and_restores_exactly() {
    let d = decode("te_um=5&backlash_um=200&family=te_um%3A0%2C20.5%2C30");
    assert!(d.issues.is_empty(), "{:?}", d.issues);
    let f = d.family.clone().unwrap();
    assert_eq!(f.values, vec![0.0, 20.5, 30.0]);
    // The first member is the current state.
    assert_eq!(
        keys::get(&d.settings.params, "te_um"),
        Some(Value::Num(0.0))
    );
    let q = encode_all(&d.settings, None, Some(&f), None);
    assert!(q.ends_with("&family=te_um%3A0%2C20.5%2C30"), "{q}");
    let again = decode(&q);
    assert!(again.issues.is_empty(), "{:?}", again.issues);
    assert_eq!(again.family, d.family);
    assert_eq!(again.settings, d.settings);
    // Unencoded too, as a person types it.
    assert_eq!(decode("family=te_um:0,20.5,30").family, d.family);
    // A bad family is named and dropped; the rest of the link applies.
    let d = decode("backlash_um=150&family=backlash_um:50,5000");
    assert_eq!(d.family, None);
    assert_eq!(d.issues.len(), 1, "{:?}", d.issues);
    assert!(d.issues[0].contains("backlash 5000"), "{:?}", d.issues);
    assert_eq!(
        keys::get(&d.settings.params, "backlash_um"),
        Some(Value::Num(150.0))
    );
}

#[test]
fn percent_codec_round_trips_and_tolerates_garbage() {
    for s in ["a b&c=d", "µm Ω 漢字", "%%%", "100%"] {
        assert_eq!(percent_decode(&percent_encode(s)), s);
    }
    assert_eq!(percent_decode("%zz%4"), "%zz%4");
    assert_eq!(percent_decode("%C3"), "\u{FFFD}");
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn decode_never_panics_on_random_text(s in "\\PC{0,300}") {
        let d = decode(&s);
        prop_assert!(d.settings.view.bif_points <= crate::settings::MAX_BIF_POINTS);
    }

    #[test]
    fn decode_never_panics_on_hostile_pairs(
        pairs in proptest::collection::vec(
            (
                prop_oneof![
                    Just("backlash_um".to_string()),
                    Just("te_um".to_string()),
                    Just("model".to_string()),
                    Just("planets".to_string()),
                    Just("omega".to_string()),
                    Just("mesh".to_string()),
                    Just("bif_points".to_string()),
                    Just("torque_s2_nm".to_string()),
                    Just("map_key".to_string()),
                    Just("map_from".to_string()),
                    Just("map_to".to_string()),
                    Just("map_omega_points".to_string()),
                    Just("map_value_points".to_string()),
                    Just("lyap_points".to_string()),
                    Just("a".to_string()),
                    Just("family".to_string()),
                    Just("panels".to_string()),
                    Just("axis".to_string()),
                    Just("teeth_r".to_string()),
                    "[a-z_%0-9]{0,12}",
                    "\\PC{0,8}",
                ],
                prop_oneof![
                    Just("NaN".to_string()),
                    Just("inf".to_string()),
                    Just("-inf".to_string()),
                    Just("1e308".to_string()),
                    Just("1e309".to_string()),
                    Just("-0".to_string()),
                    Just("auto".to_string()),
                    Just("gear-pair".to_string()),
                    Just("%FF%FE".to_string()),
                    Just("worst".to_string()),
                    Just("rpm".to_string()),
                    Just("te_um:0,20,30".to_string()),
                    Just("s1a1,rb1".to_string()),
                    Just("backlash_um:50,1e9".to_string()),
                    any::<f64>().prop_map(|x| x.to_string()),
                    any::<i64>().prop_map(|x| x.to_string()),
                    "\\PC{0,20}",
                ],
            ),
            0..40,
        )
    ) {
        let q: Vec<String> = pairs.iter().map(|(k, v)| format!("{k}={v}")).collect();
        let d = decode(&q.join("&"));
        // Whatever the link said, the result is a buildable model with capped jobs.
        prop_assert!(Model::new(&d.settings.params).is_ok());
        let v = &d.settings.view;
        prop_assert!(v.omega_from < v.omega_to);
        prop_assert!(v.fr_points <= crate::settings::MAX_FR_POINTS);
        prop_assert!(v.transient_periods <= crate::settings::MAX_TRANSIENT);
        prop_assert!(v.record_periods <= crate::settings::MAX_RECORD);
        prop_assert!(v.map_from < v.map_to);
        prop_assert!(v.map_omega_points <= crate::settings::MAX_MAP_OMEGA_POINTS);
        prop_assert!(v.map_value_points <= crate::settings::MAX_MAP_VALUE_POINTS);
        prop_assert!(crate::settings::MAP_KEYS.contains(&v.map_key.as_str()));
        // And it round-trips, with its pinned state if it had one.
        let again = decode(&encode_all(
            &d.settings,
            d.pinned.as_ref(),
            d.family.as_ref(),
            d.panels.as_deref(),
        ));
        prop_assert!(again.issues.is_empty(), "{:?}", again.issues);
        prop_assert_eq!(again.settings, d.settings);
        prop_assert_eq!(again.pinned, d.pinned);
        prop_assert_eq!(again.family, d.family);
        prop_assert_eq!(again.panels, d.panels);
    }

    #[test]
    fn decode_survives_100_kb(c in "\\PC", v in "[0-9eE.+-]{1,30}") {
        let big = format!("backlash_um={v}&{}", c.repeat(100_000 / c.len().max(1)));
        let d = decode(&big);
        prop_assert!(d.issues.len() <= 4);
        let huge = "x=1&".repeat(30_000);
        let d = decode(&huge);
        prop_assert!(d.issues.len() <= MAX_PAIRS + 2);
    }
}
