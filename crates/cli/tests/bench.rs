//! `gearshock bench --quick`: medians reported.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::json;

#[test]
fn bench_quick_reports_medians() {
    let v = json(&["bench", "--quick", "--repeats", "1"]);
    assert!(v["rhs"]["evaluations_per_s"].as_f64().expect("rate") > 0.0);
    assert!(v["simulate"]["median_ms"].as_f64().expect("ms") > 0.0);
    assert!(v["bifurcation"]["points_per_s"].as_f64().expect("pts") > 0.0);
}

/// `bench --branches-only --quick`: both branch figures with their medians
/// and what the run computed (the gear pair's whole branch: its 993 points
/// end near Omega 1.5, the range's end).
#[test]
fn bench_branches_reports_both_figures() {
    let v = json(&["bench", "--branches-only", "--quick", "--repeats", "1"]);
    let b = &v["shooting_branches"];
    let page = &b["compound_page_300_points"];
    assert!(page["median_s"].as_f64().expect("s") > 0.0);
    assert_eq!(page["last_run"]["points"].as_u64(), Some(20));
    let pair = &b["gear_pair_whole_branch"]["last_run"];
    assert!(pair["points"].as_u64().expect("points") > 100, "{pair}");
    let reach = pair["omega_reached"].as_f64().expect("omega");
    assert!(reach > 1.49 && reach <= 1.5, "{pair}");
}

/// `bench --multipliers --quick`: both groups compared at three step
/// counts, every monodromy computed, and the error shrinking as the step
/// does (RK4's fourth order; the solver's floquet test checks the order).
#[test]
fn bench_multipliers_reports_the_accuracy_by_step() {
    let v = json(&["bench", "--multipliers", "--quick"]);
    let a = &v["multiplier_accuracy"];
    assert_eq!(a["monodromies_failed"].as_u64(), Some(0), "{a}");
    let mut points = 0;
    for group in ["constant_contact", "impacting"] {
        let g = &a[group];
        points += g["points"].as_u64().expect("points");
        let rows = g["against_reference"].as_array().expect("rows");
        let largest: Vec<f64> = rows
            .iter()
            .map(|r| r["largest_difference"].as_f64().expect("difference"))
            .collect();
        assert_eq!(largest.len(), 3, "{g}");
        assert!(
            largest.windows(2).all(|w| w[1] < w[0] || w[0] == 0.0),
            "{g}"
        );
    }
    assert_eq!(Some(points), a["sweep"]["branch_points"].as_u64(), "{a}");
}

/// `bench --hbm-problem` prints the harmonic-balance problem `frf` solves
/// (the peer benchmark, scripts/bench-pyharm.sh, solves it in pyHarm).
/// Checked against the physical model as `modes` reports it, computed
/// without the modal reduction: the problem's static solution with every
/// mesh on its drive flank, `(K + sum n k d d^T) x = f0 + sum n k (b + e0) d`,
/// gives each channel the static mesh deflection, and the eigenvalues of
/// that mean stiffness (the mass matrix is the identity) are, times
/// omega_ref, natural frequencies of the model (the symmetric ones).
#[test]
fn the_hbm_problem_is_the_models_statics_and_modes() {
    use nalgebra::{DMatrix, DVector};
    let p = json(&["bench", "--hbm-problem"]);
    let modes = json(&["modes"]);
    let m = p["m"].as_u64().expect("m") as usize;
    assert_eq!(m, 5, "the symmetric reduction of three in-phase planets");
    let rows = |key: &str| DMatrix::from_fn(m, m, |i, j| p[key][i][j].as_f64().expect("entry"));
    let mut k_total = rows("stiffness");
    let mut rhs = DVector::from_fn(m, |i, _| p["load"][i].as_f64().expect("load"));
    let channels = p["channels"].as_array().expect("channels");
    assert_eq!(channels.len(), 4, "one channel per mesh kind");
    for c in channels {
        let d = DVector::from_fn(m, |i, _| c["d"][i].as_f64().expect("d"));
        let law = &c["law"];
        let k = c["multiplicity"].as_f64().expect("n") * law["k"].as_f64().expect("k");
        k_total += k * &d * d.transpose();
        let shift =
            law["backlash_um"].as_f64().expect("b") + law["te_mean_um"].as_f64().expect("e0");
        rhs += k * shift * &d;
    }
    let x = k_total.clone().lu().solve(&rhs).expect("regular");
    for c in channels {
        let d = DVector::from_fn(m, |i, _| c["d"][i].as_f64().expect("d"));
        let u_um = d.dot(&x);
        for mesh in c["meshes"].as_array().expect("meshes") {
            let name = mesh.as_str().expect("name");
            let want_um = modes["static_mesh_deflection_m"][name]
                .as_f64()
                .expect("static")
                * 1e6;
            assert!(
                (u_um - want_um).abs() <= 1e-9 * want_um,
                "{name}: {u_um} um against {want_um} um"
            );
        }
    }
    let omega_ref = p["omega_ref_rad_s"].as_f64().expect("omega_ref");
    let natural: Vec<f64> = modes["natural_frequencies_hz"]
        .as_array()
        .expect("frequencies")
        .iter()
        .map(|f| f.as_f64().expect("hz"))
        .collect();
    for lambda in k_total.symmetric_eigenvalues().iter() {
        let hz = lambda.sqrt() * omega_ref / (2.0 * std::f64::consts::PI);
        assert!(
            natural.iter().any(|f| (f - hz).abs() <= 1e-6 * f),
            "{hz} Hz is not among the model's {natural:?}"
        );
    }
}
