//! `gearshock boundaries`: the curves as JSON and CSV, each traced once
//! at a coarse step, and bad input refused naming the flag and its range.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::{json, ok, refused, words};

const TRACE: &str = "boundaries --model gear-pair --key te_um --value-from 0.2 --value-to 40 \
     --omega-from 0.4 --omega-to 1.3 --points 40";

#[test]
fn the_curves_are_json_with_kinds_points_and_cusps_and_csv_alike() {
    let v = json(&words(TRACE));
    let curves = v["curves"].as_array().unwrap();
    assert!(curves.iter().any(|c| c["kind"] == "fold"), "{v}");
    assert!(
        curves.iter().any(|c| c["kind"] == "drive-flanks-part"),
        "{v}"
    );
    for c in curves {
        for p in c["points"].as_array().unwrap() {
            let (w, x) = (p["omega"].as_f64().unwrap(), p["value"].as_f64().unwrap());
            assert!((0.4..=1.3).contains(&w) && (0.2..=40.0).contains(&x), "{p}");
            assert!(p["stable_side"].is_string(), "{p}");
        }
    }
    // The secondary jump near Omega 0.46 disappears at a cusp.
    let cusps = v["cusps"].as_array().unwrap();
    assert!(!cusps.is_empty(), "{v}");
    assert_eq!(v["complete"], true);
    // CSV: a header, one row per point, one per cusp.
    let mut args = words(TRACE);
    args.extend(["--format", "csv"]);
    let text = String::from_utf8(ok(&args)).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("curve,kind,omega,te_um,stable_side"));
    let points: usize = curves
        .iter()
        .map(|c| c["points"].as_array().unwrap().len())
        .sum();
    assert_eq!(lines.count(), points + cusps.len());
}

/// The fold curve through the cusp near Omega 0.46, as (Omega, value)
/// ends, and the cusps, of the two-level trace at `points`.
fn cusp_fold(points: u32) -> (Vec<[f64; 4]>, usize) {
    let line = format!(
        "boundaries --model gear-pair --key te_um --value-from 0.2 --value-to 40 \
         --omega-from 0.4 --omega-to 1.3 --levels 2 --points {points}"
    );
    let v = json(&words(&line));
    let ends = v["curves"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|c| c["kind"] == "fold")
        .map(|c| {
            let pts = c["points"].as_array().unwrap();
            let at = |p: &serde_json::Value| {
                (p["omega"].as_f64().unwrap(), p["value"].as_f64().unwrap())
            };
            let ((w0, v0), (w1, v1)) = (at(&pts[0]), at(&pts[pts.len() - 1]));
            [w0, v0, w1, v1]
        })
        .filter(|e| e[0] < 0.45 && e[2] < 0.45)
        .collect();
    (ends, v["cusps"].as_array().unwrap().len())
}

/// At 10 and 20 points a step the two fold branches beside the cusp are
/// closer than a step: the curve through them is traced once, from the
/// box's top edge back to it, with one cusp, as at 30 and 60 points.
#[test]
fn a_coarse_trace_gives_the_cusps_fold_once() {
    for points in [10, 20, 30] {
        let (ends, cusps) = cusp_fold(points);
        assert_eq!(ends.len(), 1, "{points} points: {ends:?}");
        assert_eq!(cusps, 1, "{points} points");
        let e = ends[0];
        assert!(
            e[1] == 40.0 && e[3] == 40.0 && (e[0] - e[2]).abs() > 0.005,
            "{points} points: {e:?}"
        );
    }
}

#[test]
fn the_aft_method_is_refused_saying_why() {
    refused(
        &words(&format!("{TRACE} --method aft")),
        &["--method aft", "exact", "Jacobian"],
    );
}

/// The budget knows the model: the compound set's trace at H = 40 is
/// estimated at some 6e9 work units (41 times the gear pair's at the same
/// options) and refused before any work, naming the points that fit.
#[test]
fn a_trace_over_its_budget_on_this_model_is_refused_naming_what_fits() {
    let line = "boundaries --key backlash_um --value-from 0 --value-to 200 \
         --omega-from 0.1 --omega-to 2 --harmonics 40";
    let err = refused(
        &words(line),
        &[
            "work units",
            "3.6e9",
            "allowed --points 10 ..= ",
            "--harmonics 40",
        ],
    );
    assert!(err.trim_end().chars().count() <= 200, "{err}");
}

#[test]
fn bad_input_names_the_flag_and_its_range() {
    let base = "boundaries --model gear-pair --omega-from 0.4 --omega-to 1.3";
    let cases: [(&str, &[&str]); 3] = [
        (
            "--key te_um --value-from 10 --value-to 10",
            &["value-to", "10"],
        ),
        (
            "--key stiffness_n_m --value-from 1e8 --value-to 1e9",
            &["key", "stiffness_n_m", "backlash_um"],
        ),
        (
            "--key te_um --value-from 1 --value-to 40 --levels 1",
            &["levels", "2 ..= 50"],
        ),
    ];
    for (extra, needles) in cases {
        let line = format!("{base} {extra}");
        refused(&words(&line), needles);
    }
    refused(
        &words(
            "boundaries --key te_um --value-from 1 --value-to 10 --omega-from 1.3 --omega-to 0.4",
        ),
        &["omega-to"],
    );
}
