//! `gearshock campbell`: the critical speeds against `gearshock modes`'s
//! natural frequencies, in JSON and CSV, and its refusals.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::{gearshock, json};

/// Every crossing is a natural frequency that `modes` reports, divided by
/// its order, at the speed whose mesh frequency is that quotient; Omega at
/// that speed is the mode's Omega over the order; the default range ends
/// at Omega 2 and holds every crossing below it.
#[test]
fn crossings_are_the_models_natural_frequencies_over_their_orders() {
    let c = json(&["campbell", "--orders", "3"]);
    let modes = json(&["modes"]);
    let natural: Vec<f64> = modes["natural_frequencies_hz"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_f64().unwrap())
        .filter(|f| *f > 0.0)
        .collect();
    let per_rpm = c["mesh_hz_per_rpm"].as_f64().unwrap();
    let omega_ref = modes["omega_ref_rad_s"].as_f64().unwrap();
    let rpm_to = c["rpm_to"].as_f64().unwrap();
    let two_pi = 2.0 * std::f64::consts::PI;
    assert!(
        (rpm_to * per_rpm * two_pi / omega_ref - 2.0).abs() < 1e-9,
        "{rpm_to}"
    );
    let crossings = c["crossings"].as_array().unwrap();
    let mut expected = 0;
    for f in natural.iter() {
        let distinct = natural
            .iter()
            .position(|g| (g - f).abs() <= 1e-6 * f)
            .unwrap();
        if natural[distinct] != *f {
            continue;
        }
        for order in 1..=3 {
            let omega = two_pi * f / f64::from(order) / omega_ref;
            if omega <= 2.0 {
                expected += 1;
            }
        }
    }
    assert_eq!(crossings.len(), expected, "{c}");
    for x in crossings {
        let order = x["order"].as_f64().unwrap();
        let rpm = x["rpm"].as_f64().unwrap();
        let f = rpm * per_rpm * order;
        assert!(
            natural.iter().any(|n| (n - f).abs() <= 1e-9 * n),
            "{x}: {f} Hz is not a natural frequency of {natural:?}"
        );
        let omega = x["omega"].as_f64().unwrap();
        assert!(
            (omega - two_pi * f / order / omega_ref).abs() <= 1e-9 * omega,
            "{x}"
        );
        // In-phase planets excite the rotational modes only.
        let rotational = x["mode_kind"] == "rotational";
        assert_eq!(x["excited"].as_bool(), Some(rotational), "{x}");
    }
    // The in-phase planets' planet modes are listed, never excited.
    let planet = c["modes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|m| m["kind"] == "planet")
        .expect("a planet mode");
    assert!(
        planet["participation"]
            .as_array()
            .unwrap()
            .iter()
            .all(|p| p.as_f64().unwrap() <= 1e-9),
        "{planet}"
    );
    // The first mode met by order 1 at the speed of Omega 0.2315.
    let first = crossings.iter().find(|x| x["order"] == 1).unwrap();
    assert!(
        (first["omega"].as_f64().unwrap() - 0.2315).abs() < 5e-4,
        "{first}"
    );
}

/// The CSV holds the same rows as the JSON: in-phase planets' crossings
/// with planet modes among them, marked not excited, the rotational ones
/// excited; each row says its line (a mesh order here).
#[test]
fn the_csv_holds_every_crossing() {
    let c = json(&["campbell", "--rpm-to", "6000", "--orders", "6"]);
    let out = gearshock(&[
        "campbell", "--rpm-to", "6000", "--orders", "6", "--format", "csv",
    ]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let rows: Vec<&str> = text.lines().collect();
    assert!(rows[0].starts_with("rpm,order,omega,"), "{}", rows[0]);
    assert_eq!(rows.len() - 1, c["crossings"].as_array().unwrap().len());
    assert!(
        rows.iter()
            .any(|r| r.contains(",planet,") && r.ends_with(",false,mesh order")),
        "{text}"
    );
    assert!(
        rows.iter()
            .all(|r| !(r.contains(",rotational,") && r.ends_with(",false,mesh order"))),
        "{text}"
    );
}

#[test]
fn bad_speeds_and_orders_are_refused_naming_the_option() {
    for (args, name) in [
        (
            &["campbell", "--rpm-from", "5", "--rpm-to", "2"][..],
            "--rpm-to 2",
        ),
        (&["campbell", "--rpm-to", "NaN"][..], "--rpm-to NaN"),
        (&["campbell", "--rpm-from", "-3"][..], "--rpm-from -3"),
        (&["campbell", "--orders", "13"][..], "--orders 13"),
        (&["campbell", "--orders", "0"][..], "--orders 0"),
    ] {
        let out = gearshock(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(name) && err.contains("allowed"),
            "{args:?}: {err}"
        );
        assert!(out.stdout.is_empty(), "{args:?}");
    }
}

/// A sweep's range given in rpm is the range in Omega at those speeds
/// (mesh frequency per rpm from `campbell`, omega_ref from `modes`), and
/// the sweep is the one given those Omega values.
#[test]
fn a_range_in_rpm_is_the_same_sweep_as_in_omega() {
    let per_rpm = json(&["campbell"])["mesh_hz_per_rpm"].as_f64().unwrap();
    let omega_ref = json(&["modes"])["omega_ref_rad_s"].as_f64().unwrap();
    let omega = |rpm: f64| rpm * per_rpm * 2.0 * std::f64::consts::PI / omega_ref;
    let by_rpm = json(&[
        "instability",
        "--rpm-from",
        "500",
        "--rpm-to",
        "6000",
        "--points",
        "7",
    ]);
    let spec = &by_rpm["spec"];
    for (key, rpm) in [("omega_from", 500.0), ("omega_to", 6000.0)] {
        let got = spec[key].as_f64().unwrap();
        assert!(
            (got - omega(rpm)).abs() <= 1e-12 * got,
            "{key}: {got} against {}",
            omega(rpm)
        );
    }
    let (from, to) = (spec["omega_from"].to_string(), spec["omega_to"].to_string());
    let by_omega = json(&[
        "instability",
        "--omega-from",
        &from,
        "--omega-to",
        &to,
        "--points",
        "7",
    ]);
    assert_eq!(by_rpm, by_omega);
    // Either end either way.
    let mixed = json(&[
        "instability",
        "--rpm-from",
        "500",
        "--omega-to",
        &to,
        "--points",
        "7",
    ]);
    assert_eq!(mixed, by_omega);
}

#[test]
fn a_range_given_both_ways_or_below_zero_rpm_is_refused() {
    for (args, says) in [
        (
            &[
                "instability",
                "--rpm-from",
                "500",
                "--omega-from",
                "0.1",
                "--omega-to",
                "1",
            ][..],
            "cannot be used with",
        ),
        (
            &["frf", "--rpm-from", "-5", "--rpm-to", "900"][..],
            "--rpm-from -5 is out of range",
        ),
        (
            &["bifurcation", "--rpm-from", "0", "--rpm-to", "900"][..],
            "--rpm-from 0 is out of range",
        ),
    ] {
        let out = gearshock(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert!(err.contains(says), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}");
    }
}

/// With five sequential planets the planet-pass orders join the mesh
/// orders: order m crosses mode f_n at 60 f_n / (m N |n_c / n_s1|) rpm,
/// the carrier turning z_s1 / (z_s1 - z_r) = 36 / (36 - 84) times the
/// small sun, so m N 3/4 / 60 Hz per rpm; in phase there are none.
#[test]
fn sequential_planets_add_the_planet_pass_orders() {
    let c = json(&[
        "campbell",
        "--set",
        "planets=5",
        "--set",
        "phasing=sequential",
        "--rpm-to",
        "200000",
    ]);
    let pp = &c["planet_pass"];
    let per_rpm = 5.0 * 0.75 / 60.0;
    assert!((pp["hz_per_rpm"].as_f64().unwrap() - per_rpm).abs() <= 1e-15);
    let crossings = pp["crossings"].as_array().unwrap();
    assert!(!crossings.is_empty());
    for x in crossings {
        let f_n = x["mode_frequency_hz"].as_f64().unwrap();
        let m = x["order"].as_f64().unwrap();
        let rpm = f_n / (m * per_rpm);
        assert!(
            (x["rpm"].as_f64().unwrap() - rpm).abs() <= 1e-9 * rpm,
            "{x}"
        );
        assert!((x["mesh_order"].as_f64().unwrap() - m * 5.0 / 84.0).abs() <= 1e-12);
    }
    let csv = String::from_utf8(test_support::cli::ok(&[
        "campbell",
        "--set",
        "planets=5",
        "--set",
        "phasing=sequential",
        "--rpm-to",
        "200000",
        "--format",
        "csv",
    ]))
    .unwrap();
    let passes = csv
        .lines()
        .filter(|l| l.ends_with(",planet-pass order"))
        .count();
    assert_eq!(passes, crossings.len(), "{csv}");
    let c = json(&[
        "campbell",
        "--set",
        "planets=5",
        "--set",
        "phasing=in-phase",
    ]);
    assert!(c["planet_pass"].is_null());
}
