//! `gearshock frf`: the harmonic-balance branch with stability and
//! bifurcations, and its options refused with exit 2 naming them.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::{gearshock, json, words};

#[test]
fn frf_reports_the_branch_with_stability_and_bifurcations() {
    // The gear pair's hysteresis band (folds near Omega 0.49 and 0.60).
    let v = json(&words(
        "frf --model gear-pair --omega-from 0.4 --omega-to 0.7 --points 100 --harmonics 5",
    ));
    assert_eq!(v["complete"], true);
    assert_eq!(v["spec"]["harmonics"], 5);
    assert_eq!(v["spec"]["method"], "exact");
    let branch = v["branch"].as_array().expect("branch");
    assert!(branch.len() >= 100);
    assert_eq!(v["stats"]["points"].as_u64(), Some(branch.len() as u64));
    for p in branch {
        let (max, min, amp) = (
            p["delta_max_m"].as_f64().unwrap(),
            p["delta_min_m"].as_f64().unwrap(),
            p["delta_amplitude_m"].as_f64().unwrap(),
        );
        assert!((amp - 0.5 * (max - min)).abs() <= 1e-12 * max.abs());
        assert_eq!(p["harmonics_m"].as_array().unwrap().len(), 6);
        assert!(p["stable"].is_boolean());
    }
    let folds = branch.iter().filter(|p| p["bifurcation"] == "fold").count();
    assert!(folds >= 2, "{folds} folds");
    assert!(branch.iter().any(|p| p["stable"] == false));
    // The seed's describing function at H = 1, and CSV.
    let out = gearshock(&words("frf --model gear-pair --omega-from 1.2 --omega-to 1.5 --points 20 --harmonics 1 --method describing-function --format csv"));
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    assert!(text.starts_with("index,omega,mesh,delta_max_m"));
    assert!(text.lines().count() > 20);
}

#[test]
fn frf_bad_options_exit_2_naming_them() {
    for (args, needle) in [
        (
            vec!["frf", "--omega-from", "0.5", "--omega-to", "0.4"],
            "omega-to",
        ),
        (
            words("frf --omega-from 0.1 --omega-to 1 --harmonics 99"),
            "harmonics",
        ),
        (
            words("frf --omega-from 0.1 --omega-to 1 --method magic"),
            "--method",
        ),
        (
            words("frf --omega-from 0.1 --omega-to 1 --direction sideways"),
            "--direction",
        ),
        (
            vec!["frf", "--omega-from", "NaN", "--omega-to", "1"],
            "omega-from",
        ),
        (
            words("frf --omega-from 0.1 --omega-to 1 --stability-stride 0"),
            "stability-stride",
        ),
        (
            words("frf --omega-from 0.1 --omega-to 1 --no-stability --stability-stride 2"),
            "--stability-stride",
        ),
        (
            words("frf --omega-from 0.4 --omega-to 1 --method shooting --stability-stride 2"),
            "--stability-stride",
        ),
    ] {
        let out = gearshock(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

/// A shooting branch's budget knows the model: its pilot prices a period
/// (the compound set's 18 tangents make a branch point some 12 000
/// integration steps), and a branch over it is refused before any work,
/// naming the points that fit.
#[test]
fn a_shooting_branch_over_its_budget_is_refused_naming_the_points_that_fit() {
    let out = gearshock(&words(
        "frf --method shooting --omega-from 0.4 --omega-to 20 --points 100000",
    ));
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    for needle in [
        "--points 100000",
        "integration steps",
        "4e9",
        "allowed --points 2 ..= ",
    ] {
        assert!(err.contains(needle), "{needle}: {err}");
    }
    assert!(out.stdout.is_empty());
}

/// The points of piece `piece` of a shooting branch, as (Omega, period,
/// bifurcation).
fn piece_of(branch: &[serde_json::Value], piece: u64) -> Vec<(f64, u64, String)> {
    branch
        .iter()
        .filter(|p| p["piece"] == piece)
        .map(|p| {
            (
                p["omega"].as_f64().unwrap(),
                p["period"].as_u64().unwrap(),
                p["bifurcation"].as_str().unwrap_or("").to_string(),
            )
        })
        .collect()
}

/// A shooting branch says where and why each piece ended: the gear
/// pair's first branch lands on the range's end (it was "left the range
/// at Omega 1.249227", inside the range), the period-2 piece from the
/// doubling at 0.5568 ends at the doubling where it rejoins (labelled one,
/// not a fold) without jumping to the other bubble at 0.75, and every
/// step within a piece is bounded.
#[test]
fn a_shooting_branch_ends_on_the_range_or_says_why_with_bounded_steps() {
    let v = json(&words(
        "frf --model gear-pair --method shooting --omega-from 0.4 --omega-to 1.3 --points 50",
    ));
    assert_eq!(v["complete"], true, "{}", v["notes"]);
    assert_eq!(v["restarts"], serde_json::json!([]));
    assert_eq!(v["left_out"], serde_json::json!([]));
    let notes = v["notes"].to_string();
    assert!(
        notes.contains("the period-1 branch reached the range's end at Omega 1.3"),
        "{notes}"
    );
    let branch = v["branch"].as_array().unwrap();
    let first = piece_of(branch, 0);
    assert!((first.last().unwrap().0 - 1.3).abs() < 1e-9, "{first:?}");
    let pieces: std::collections::BTreeSet<u64> = branch
        .iter()
        .map(|p| p["piece"].as_u64().unwrap())
        .collect();
    for piece in pieces {
        let pts = piece_of(branch, piece);
        for w in pts.windows(2) {
            // A step moves Omega by at most 1.5 nominal steps (0.027),
            // and a corrected point lies within two steps of the last.
            assert!(
                (w[1].0 - w[0].0).abs() <= 3.0 * 0.9 / 50.0,
                "piece {piece}: {w:?}"
            );
        }
    }
    let doubled: Vec<(f64, u64, String)> = branch
        .iter()
        .filter(|p| p["period"] == 2)
        .map(|p| {
            (
                p["omega"].as_f64().unwrap(),
                2,
                p["bifurcation"].as_str().unwrap_or("").to_string(),
            )
        })
        .collect();
    assert!(
        doubled
            .iter()
            .any(|(w, _, b)| b == "period-doubling" && (w - 0.5904).abs() < 1e-3),
        "{doubled:?}"
    );
    assert!(
        !doubled
            .iter()
            .any(|(w, _, b)| b == "fold" && (w - 0.5904).abs() < 1e-3),
        "{doubled:?}"
    );
}

/// Undamped, the gear pair's first branch folds back from 0.47 and leaves
/// the range at its start: it is restarted from the other end, downward,
/// until it meets the part followed, and the restart is reported as the
/// harmonic balance reports its own. Where no orbit can be found (the
/// compound set is chaotic over Omega 0.53 to 0.7), the gap is left out
/// and the branch is not complete.
#[test]
fn a_shooting_branch_that_turns_back_is_restarted_or_leaves_out_what_it_cannot_cover() {
    let v = json(&words(
        "frf --model gear-pair --method shooting --omega-from 0.4 --omega-to 1.3 --points 50 \
         --set damping_ratio=0",
    ));
    assert_eq!(v["complete"], true, "{}", v["notes"]);
    let r = &v["restarts"][0];
    assert_eq!(r["reason"], "turned-back", "{r}");
    assert_eq!(r["start_omega"], 1.3);
    assert_eq!(r["direction"], "down");
    assert!(v["notes"]
        .to_string()
        .contains("turned back at a fold and left the range at its start"));
    let v = json(&words(
        "frf --method shooting --omega-from 0.5 --omega-to 0.7 --points 10",
    ));
    assert_eq!(v["complete"], false, "{}", v["notes"]);
    let gap = &v["left_out"][0];
    assert_eq!(gap["reason"], "not-followed", "{gap}");
    assert_eq!(gap["omega_to"], 0.7);
}

/// The flags a method ignores are refused, naming them.
#[test]
fn flags_the_method_ignores_are_refused() {
    let base = "frf --model gear-pair --omega-from 0.4 --omega-to 1.3 --points 20";
    for (extra, needle) in [
        (
            "--method shooting --no-stability",
            "--no-stability: --method shooting does not take it",
        ),
        (
            "--method shooting --harmonics 5",
            "--harmonics: --method shooting does not take it",
        ),
        (
            "--method shooting --grid 512",
            "--grid: --method shooting does not take it",
        ),
        ("--period 2", "--period: only --method shooting takes it"),
        (
            "--method aft --no-switch",
            "--no-switch: only --method shooting takes it",
        ),
    ] {
        let out = gearshock(&words(&format!("{base} {extra}")));
        assert_eq!(out.status.code(), Some(2), "{extra}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{extra}: {err}");
        assert!(out.stdout.is_empty());
    }
}

/// `frf --method shooting`: the same JSON branch (omega, stable,
/// bifurcation) plus each point's period; the gear pair's two folds bound
/// its hysteresis band, a period doubling starts a period-2 branch, and
/// stability changes only at a located bifurcation or a piece's end.
#[test]
fn frf_by_shooting_reports_periodic_branches_with_their_period() {
    let v = json(&words(
        "frf --model gear-pair --omega-from 0.3 --omega-to 1.5 --points 200 --method shooting",
    ));
    assert_eq!(v["complete"], true);
    let branch = v["branch"].as_array().expect("branch");
    assert!(branch.len() >= 200, "{} points", branch.len());
    for p in branch {
        let w = p["omega"].as_f64().unwrap();
        assert!((0.3 - 1e-9..=1.5 + 1e-9).contains(&w), "omega {w}");
        assert!(p["stable"].is_boolean());
        assert!(p["period"].as_u64().is_some_and(|n| (1..=32).contains(&n)));
        assert!(p["bifurcation"].is_null() || p["bifurcation"].is_string());
        // A stable orbit's multipliers lie inside the unit circle (on it,
        // to the location's accuracy, at a located bifurcation).
        if p["stable"] == true {
            let slack = if p["bifurcation"].is_null() {
                1e-9
            } else {
                1e-6
            };
            let modulus = p["max_multiplier_modulus"].as_f64().unwrap();
            assert!(modulus <= 1.0 + slack, "{p}");
        }
    }
    let of = |kind: &str, period: u64| -> Vec<f64> {
        branch
            .iter()
            .filter(|p| p["bifurcation"] == kind && p["period"] == period)
            .map(|p| p["omega"].as_f64().unwrap())
            .collect()
    };
    let folds = of("fold", 1);
    assert_eq!(folds.len(), 2, "{folds:?}");
    // The hysteresis band of the harmonic-balance test above (0.49 to 0.60).
    assert!(folds.iter().any(|f| (0.47..0.50).contains(f)), "{folds:?}");
    assert!(folds.iter().any(|f| (0.59..0.62).contains(f)), "{folds:?}");
    assert!(!of("period-doubling", 1).is_empty());
    assert!(branch.iter().any(|p| p["period"] == 2));
}

/// Sampled stability (a monodromy on every fourth point) gives each point
/// of the compound set's first resonance, with its folds, its period
/// doublings and its Neimark-Sacker pair, the flag and the label of a
/// monodromy at every point (the default); the points it inferred say so
/// and carry no multipliers. At Omega 0.2405 a stable point lies between
/// two unstable samples, one with a complex pair outside the circle, the
/// other with a real multiplier beyond -1: the interval is split because
/// they are unstable in different ways.
#[test]
fn sampled_stability_keeps_every_flag_and_label_of_every_point() {
    let base = "frf --omega-from 0.19 --omega-to 0.25 --points 60 --harmonics 7 --mesh s2b1";
    let sampled = json(&words(&format!("{base} --stability-stride 4")));
    let every = json(&words(base));
    assert_eq!(sampled["spec"]["stability_stride"], 4);
    assert_eq!(every["spec"]["stability_stride"], 1);
    let (a, b) = (
        sampled["branch"].as_array().unwrap(),
        every["branch"].as_array().unwrap(),
    );
    assert_eq!(a.len(), b.len());
    let labels = b.iter().filter(|p| !p["bifurcation"].is_null()).count();
    assert!(labels >= 4, "{labels} labels: a fold pair and more");
    let mut inferred = 0;
    for (p, q) in a.iter().zip(b) {
        assert_eq!(p["omega"], q["omega"], "the same points");
        assert_eq!(p["stable"], q["stable"], "at Omega {}", p["omega"]);
        assert_eq!(
            p["bifurcation"], q["bifurcation"],
            "at Omega {}",
            p["omega"]
        );
        assert_eq!(q["stability_from"], "monodromy");
        match p["stability_from"].as_str() {
            Some("monodromy") => {
                assert_eq!(p["max_multiplier_modulus"], q["max_multiplier_modulus"])
            }
            Some("neighbours") => {
                assert!(p["max_multiplier_modulus"].is_null());
                inferred += 1;
            }
            other => panic!("stability_from {other:?}"),
        }
    }
    assert!(
        inferred * 3 >= a.len(),
        "{inferred} of {} inferred",
        a.len()
    );
}

/// `kv_iso6336` beside each branch point's extremes: ISO 6336-1's K_v
/// (method B) at the point's mesh frequency, the flags of `simulate`
/// setting its inputs. On the gear pair N is Omega (its reduced mass is
/// the model's equivalent mass), and `solver::iso6336`'s hand calculation
/// of the defaults gives K_v 1.3284 at N 0.5, so 1 + 0.6568 N below N_S
/// (0.85 at this line load), and 2.2214 in the main resonance range.
/// Every point's K_v is the solver's rating called here directly.
#[test]
fn frf_reports_iso_kv_at_each_point_with_simulates_flags() {
    let v = json(&words(
        "frf --model gear-pair --omega-from 0.3 --omega-to 1.1 --points 40 --harmonics 3",
    ));
    assert_eq!(v["iso6336"]["inputs"]["accuracy_grade"], 6.0);
    assert_eq!(v["iso6336"]["meshes"]["pg"]["n_s"], 0.85);
    let branch = v["branch"].as_array().expect("branch");
    let (mut below, mut main) = (0, 0);
    for p in branch {
        let n = p["omega"].as_f64().unwrap();
        let kv = p["kv_iso6336"].as_f64().expect("kv");
        if n <= 0.8 {
            assert!((kv - (1.0 + 0.6568 * n)).abs() < 1e-4, "N {n}: {kv}");
            below += 1;
        } else if (0.9..=1.1).contains(&n) {
            assert!((kv - 2.2214).abs() < 1e-4, "N {n}: {kv}");
            main += 1;
        }
    }
    assert!(below > 5 && main > 3, "{below} {main}");

    // The compound set, every mesh, grade 8 over 30 mm: the solver's own
    // rating at each point, and the CSV's last column is the JSON's.
    let args = "frf --omega-from 0.2 --omega-to 0.6 --points 12 --harmonics 2 --mesh all --accuracy-grade 8 --face-width-mm 30";
    let v = json(&words(args));
    let params = solver::params::ModelParams::defaults(solver::params::ModelKind::Ravigneaux);
    let model = solver::model::Model::new(&params).unwrap();
    let inputs = solver::iso6336::IsoInputs {
        accuracy_grade: 8.0,
        face_width_mm: 30.0,
        ..Default::default()
    };
    let rated = solver::iso6336::rate_model(&params, &model, &inputs).unwrap();
    let names = v["meshes"].as_array().unwrap();
    assert_eq!(names.len(), 12);
    let branch = v["branch"].as_array().unwrap();
    for p in branch {
        let hz = model.system.mesh_freq_hz(p["omega"].as_f64().unwrap());
        for (j, m) in model.system.meshes.iter().enumerate() {
            let r = &rated[j].rating;
            let want = r.kv(r.resonance_ratio(hz));
            assert_eq!(p["meshes"][&m.name]["kv_iso6336"].as_f64(), Some(want));
        }
    }
    assert_eq!(v["iso6336"]["meshes"].as_object().unwrap().len(), 12);
    let csv = gearshock(&words(&format!("{args} --format csv")));
    assert!(csv.status.success());
    let text = String::from_utf8(csv.stdout).unwrap();
    let mut lines = text.lines();
    assert!(lines.next().unwrap().ends_with(",bifurcation,kv_iso6336"));
    let first: Vec<&str> = lines.next().unwrap().split(',').collect();
    let kv: f64 = first.last().unwrap().parse().unwrap();
    assert_eq!(
        Some(kv),
        branch[0]["meshes"][first[2]]["kv_iso6336"].as_f64()
    );
    // Refused as simulate refuses them.
    let out = gearshock(&words(
        "frf --model gear-pair --omega-from 0.4 --omega-to 0.5 --accuracy-grade 0",
    ));
    assert_eq!(out.status.code(), Some(2));
    let err = String::from_utf8(out.stderr).unwrap();
    assert!(
        err.contains("accuracy grade = 0") && err.contains("1 ..= 11"),
        "{err}"
    );
}

/// The page's Kv inputs default to the command line's: the page's
/// defaults are what `gearshock frf` and `simulate` echo without flags.
#[test]
fn the_pages_kv_defaults_are_the_command_lines() {
    let v = json(&words(
        "frf --model gear-pair --omega-from 0.4 --omega-to 0.5 --points 4 --harmonics 1",
    ));
    let page = figures::settings::ViewOptions::default().iso_inputs();
    assert_eq!(v["iso6336"]["inputs"], report::iso_inputs_json(&page));
}
