//! The view options' keys: their ranges, their refusals and the ranges'
//! resets.

use super::*;

#[test]
fn every_view_key_reads_back_what_it_sets() {
    let meshes = vec!["s1a1".to_string(), "rb3".to_string()];
    let mut v = ViewOptions::default();
    for (k, t) in [
        ("omega", "1.25"),
        ("mesh", "rb3"),
        ("omega_from", "0.3"),
        ("omega_to", "1.7"),
        ("fr_points", "80"),
        ("fr_ti_points", "24"),
        ("fr_record_periods", "12"),
        ("bif_points", "150"),
        ("bif_dir", "down"),
        ("transient_periods", "500"),
        ("record_periods", "64"),
        ("harmonics", "7"),
        ("map_key", "te_um"),
        ("map_from", "5.5"),
        ("map_to", "80"),
        ("map_omega_points", "200"),
        ("map_value_points", "100"),
        ("map_transient_periods", "300"),
        ("map_record_periods", "100"),
        ("lyap_points", "0"),
        ("lyap_transient_periods", "250"),
        ("lyap_periods", "200"),
        ("clearance", "whole"),
        ("branches", "off"),
        ("boundaries", "on"),
        ("axis", "rpm"),
        ("accuracy_grade", "9"),
        ("face_width_mm", "37.5"),
    ] {
        v.set(k, t, &meshes).unwrap();
        assert_eq!(v.get(k).unwrap(), t, "{k}");
    }
    assert!(VIEW_KEYS.iter().all(|k| v.get(k.name).is_some()));
}

#[test]
fn out_of_range_values_name_key_and_range() {
    let mut v = ViewOptions::default();
    let e = v.set("bif_points", "1e9", &[]).unwrap_err().to_string();
    assert!(e.contains("bif_points") && e.contains("1000"), "{e}");
    let e = v.set("omega", "NaN", &[]).unwrap_err().to_string();
    assert!(e.contains("omega") && e.contains("0.01 ..= 20"), "{e}");
    assert!(v.set("fr_points", "2.5", &[]).is_err());
    assert!(v.set("mesh", "rb9", &["s1a1".into()]).is_err());
    assert_eq!(v, ViewOptions::default());
    v.omega_from = 1.5;
    v.omega_to = 1.0;
    assert!(v.check_range().is_some());
    assert!(v.omega_from < v.omega_to);
    // The map's caps and its own range rule.
    assert!(v.set("map_omega_points", "201", &[]).is_err());
    assert!(v.set("map_value_points", "101", &[]).is_err());
    assert!(v.set("map_key", "damping_ratio", &[]).is_err());
    v.map_from = 50.0;
    v.map_to = 10.0;
    let e = v.check_range().unwrap();
    assert!(
        e.contains("map's range") && e.contains("0 to 200 µm"),
        "{e}"
    );
    assert_eq!((v.map_from, v.map_to), (0.0, 200.0));
}

#[test]
fn both_inverted_ranges_are_named_and_reset() {
    // Once the Omega range was reset the map's was kept inverted.
    let mut v = ViewOptions {
        omega_from: 1.5,
        omega_to: 1.0,
        map_from: 50.0,
        map_to: 10.0,
        ..ViewOptions::default()
    };
    let e = v.check_range().unwrap();
    assert!(
        e.contains("frequency range") && e.contains("map's range"),
        "{e}"
    );
    let d = ViewOptions::default();
    assert_eq!((v.omega_from, v.omega_to), (d.omega_from, d.omega_to));
    assert_eq!((v.map_from, v.map_to), (d.map_from, d.map_to));
    assert_eq!(v.check_range(), None);
}

#[test]
fn minus_zero_is_kept_as_zero() {
    let mut v = ViewOptions::default();
    v.set("map_from", "-0", &[]).unwrap();
    assert_eq!(v.get("map_from").unwrap(), "0");
    assert!(v.map_from.is_sign_positive());
}
