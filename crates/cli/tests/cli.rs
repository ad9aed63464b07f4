//! The `gearshock` binary end to end: each subcommand on the defaults, a
//! sharded sweep merged equals the unsharded one, bad input exits 2 with one
//! line.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use serde_json::{json, Value};
use std::process::{Command, Output};

fn gearshock(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gearshock"))
        .args(args)
        .output()
        .expect("run gearshock")
}

fn json(args: &[&str]) -> Value {
    let out = gearshock(args);
    assert!(
        out.status.success(),
        "{args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).expect("JSON on stdout")
}

#[test]
fn params_prints_the_defaults_as_flat_keys() {
    let v = json(&["params"]);
    assert_eq!(v["model"], "ravigneaux");
    assert_eq!(v["backlash_s1a_um"], 100);
    assert_eq!(v["te_sin_s1a_um"], 20);
    assert_eq!(v["torque_s2_nm"], "auto");
    // The printed set is a valid parameter file.
    let dir = std::env::temp_dir().join(format!("gearshock-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let file = dir.join("p.json");
    std::fs::write(&file, v.to_string()).expect("write");
    let again = json(&[
        "params",
        "--params",
        file.to_str().expect("path"),
        "--set",
        "backlash_um=50",
    ]);
    assert_eq!(again["backlash_rb_um"], 50);
    let pair = json(&["params", "--model", "gear-pair"]);
    assert_eq!(pair["model"], "gear-pair");
    assert!(pair.get("planets").is_none());
}

#[test]
fn keys_lists_the_table() {
    let out = gearshock(&["keys", "--markdown"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.starts_with("| key |"));
    for k in [
        "backlash_um",
        "te_um",
        "stiffness_variation",
        "damping_ratio",
        "torque_s1_nm",
        "planets",
        "phasing",
    ] {
        assert!(text.contains(&format!("`{k}`")), "{k}");
    }
}

#[test]
fn modes_reports_frequencies_forces_and_the_balancing_torque() {
    let v = json(&["modes"]);
    let f = v["natural_frequencies_hz"].as_array().expect("array");
    assert_eq!(f.len(), 10);
    assert_eq!(f[0], 0.0);
    assert!(f.windows(2).all(|w| w[0].as_f64() <= w[1].as_f64()));
    assert!((v["balancing_torque_s2_nm"].as_f64().expect("number") - 969.697).abs() < 1e-3);
    assert!((v["static_mesh_force_n"]["s1a1"].as_f64().expect("force") - 9853.5).abs() < 0.1);
    assert_eq!(v["modes"][0]["kind"], "rigid-body");
    assert!((v["omega_ref_rad_s"].as_f64().expect("omega_ref") - 34068.0).abs() < 1.0);
    let csv = gearshock(&["modes", "--format", "csv"]);
    assert!(String::from_utf8_lossy(&csv.stdout).starts_with("frequency_hz,omega,kind"));
}

#[test]
fn simulate_reports_one_mesh_with_si_units() {
    let v = json(&[
        "simulate",
        "--omega",
        "0.5",
        "--transient-periods",
        "20",
        "--record-periods",
        "10",
        "--mesh",
        "rb2",
    ]);
    assert_eq!(v["mesh"], "rb2");
    for k in [
        "omega",
        "mesh_freq_hz",
        "delta_min_m",
        "delta_max_m",
        "delta_rms_m",
        "dynamic_factor",
    ] {
        assert!(v[k].is_number(), "{k}");
    }
    assert_eq!(
        v["poincare"]["delta_m"].as_array().expect("samples").len(),
        10
    );
    assert!(["none", "single-sided", "double-sided", "no-contact"]
        .contains(&v["impact"].as_str().expect("impact")));
    assert!(v["period"].is_null() || v["period"].is_u64());
    assert!((v["mesh_freq_hz"].as_f64().expect("f") - 0.5 * 5422.1).abs() < 1.0);
    assert!(
        v["spectrum"]["amplitude_m"]
            .as_array()
            .expect("spectrum")
            .len()
            > 10
    );
    let csv = gearshock(&[
        "simulate",
        "--omega",
        "0.5",
        "--transient-periods",
        "2",
        "--record-periods",
        "2",
        "--format",
        "csv",
    ]);
    let text = String::from_utf8_lossy(&csv.stdout);
    assert!(text.starts_with("t_s,delta_m,velocity_m_s"));
    assert_eq!(text.lines().count(), 1 + 2 * 64);
}

#[test]
fn sharded_sweep_merged_equals_the_unsharded_run() {
    let base = [
        "bifurcation",
        "--omega-from",
        "0.4",
        "--omega-to",
        "1.4",
        "--points",
        "7",
        "--direction",
        "both",
        "--transient-periods",
        "30",
        "--record-periods",
        "6",
    ];
    let mut whole_args = base.to_vec();
    whole_args.extend(["--chains", "2"]);
    let whole = json(&whole_args);
    assert_eq!(whole["points"].as_array().expect("points").len(), 14);
    let dir = std::env::temp_dir().join(format!("gearshock-shards-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    let mut files = Vec::new();
    for i in 0..2 {
        let mut args = base.to_vec();
        let shard = format!("{i}/2");
        args.extend(["--shard", &shard]);
        let v = json(&args);
        let file = dir.join(format!("shard{i}.json"));
        std::fs::write(&file, v.to_string()).expect("write");
        files.push(file.to_str().expect("path").to_string());
    }
    let mut merge_args = vec!["merge"];
    merge_args.extend(files.iter().map(String::as_str));
    let merged = json(&merge_args);
    assert_eq!(merged, whole);
    // A missing shard is refused.
    let out = gearshock(&["merge", &files[0]]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("shard 1/2 is missing"));
}

#[test]
fn bad_input_exits_2_with_one_line_naming_it() {
    let cases: &[(&[&str], &str)] = &[
        (
            &["simulate", "--omega", "0.5", "--set", "backlash_um=-5"],
            "backlash_um",
        ),
        (&["simulate", "--omega", "nan"], "omega"),
        (
            &["simulate", "--omega", "0.5", "--set", "nonsense=1"],
            "nonsense",
        ),
        (&["simulate", "--omega", "0.5", "--mesh", "s9a9"], "s9a9"),
        (
            &["simulate", "--omega", "0.5", "--set", "torque_s2_nm=10"],
            "969.697",
        ),
        (
            &["simulate", "--omega", "0.5", "--set", "teeth_r=85"],
            "teeth_r",
        ),
        (&["simulate", "--omega", "0.5", "--bogus"], "--bogus"),
        (&["simulate"], "--omega"),
        (
            &["bifurcation", "--omega-from", "1", "--omega-to", "0.5"],
            "omega-to",
        ),
        (
            &[
                "bifurcation",
                "--omega-from",
                "0.1",
                "--omega-to",
                "1",
                "--points",
                "99999999",
            ],
            "points",
        ),
        (
            &[
                "bifurcation",
                "--omega-from",
                "0.1",
                "--omega-to",
                "1",
                "--shard",
                "3/2",
            ],
            "shard",
        ),
        (
            &[
                "bifurcation",
                "--omega-from",
                "0.1",
                "--omega-to",
                "1",
                "--direction",
                "sideways",
            ],
            "direction",
        ),
        (
            &["params", "--params", "/nonexistent/p.json"],
            "/nonexistent/p.json",
        ),
        (&["frobnicate"], "frobnicate"),
    ];
    for (args, needle) in cases {
        let out = gearshock(args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(
            err.trim_end().lines().count(),
            1,
            "{args:?}: one line, got {err}"
        );
        assert!(err.contains(needle), "{args:?}: {err}");
        assert!(!err.contains("panicked"), "{args:?}: {err}");
        assert!(out.stdout.is_empty(), "{args:?}: no partial output");
    }
}

#[test]
fn bench_quick_reports_medians() {
    let v = json(&["bench", "--quick", "--repeats", "1"]);
    assert!(v["rhs"]["evaluations_per_s"].as_f64().expect("rate") > 0.0);
    assert!(v["simulate"]["median_ms"].as_f64().expect("ms") > 0.0);
    assert!(v["bifurcation"]["points_per_s"].as_f64().expect("pts") > 0.0);
}

#[test]
fn frf_reports_the_branch_with_stability_and_bifurcations() {
    // The gear pair's hysteresis band (folds near Omega 0.49 and 0.60).
    let v = json(&[
        "frf",
        "--model",
        "gear-pair",
        "--omega-from",
        "0.4",
        "--omega-to",
        "0.7",
        "--points",
        "100",
        "--harmonics",
        "5",
    ]);
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
    let out = gearshock(&[
        "frf",
        "--model",
        "gear-pair",
        "--omega-from",
        "1.2",
        "--omega-to",
        "1.5",
        "--points",
        "20",
        "--harmonics",
        "1",
        "--method",
        "describing-function",
        "--format",
        "csv",
    ]);
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
            vec![
                "frf",
                "--omega-from",
                "0.1",
                "--omega-to",
                "1",
                "--harmonics",
                "99",
            ],
            "harmonics",
        ),
        (
            vec![
                "frf",
                "--omega-from",
                "0.1",
                "--omega-to",
                "1",
                "--method",
                "magic",
            ],
            "--method",
        ),
        (
            vec![
                "frf",
                "--omega-from",
                "0.1",
                "--omega-to",
                "1",
                "--direction",
                "sideways",
            ],
            "--direction",
        ),
        (
            vec!["frf", "--omega-from", "NaN", "--omega-to", "1"],
            "omega-from",
        ),
    ] {
        let out = gearshock(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

#[test]
fn map_shards_merge_into_the_unsharded_map() {
    let args = |extra: &[&'static str]| -> Vec<&'static str> {
        let mut a = vec![
            "map",
            "--model",
            "gear-pair",
            "--omega-from",
            "0.4",
            "--omega-to",
            "1.6",
            "--omega-points",
            "4",
            "--key",
            "te_um",
            "--value-from",
            "1",
            "--value-to",
            "40",
            "--value-points",
            "3",
            "--transient-periods",
            "100",
            "--record-periods",
            "20",
        ];
        a.extend_from_slice(extra);
        a
    };
    let whole = json(&args(&[]));
    let cells = whole["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 12);
    assert!(cells.iter().all(|c| c["impact"].is_string()));
    let dir = std::env::temp_dir().join(format!("gearshock-map-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut files = Vec::new();
    for s in ["0/2", "1/2"] {
        let v = json(&args(&["--shard", s]));
        let f = dir.join(format!("{}.json", s.replace('/', "-")));
        std::fs::write(&f, v.to_string()).unwrap();
        files.push(f.to_string_lossy().into_owned());
    }
    let merged = json(&["merge", &files[0], &files[1]]);
    assert_eq!(merged, whole);
    let out = gearshock(&args(&["--shard", "2/2"]));
    assert_eq!(out.status.code(), Some(2));
}

#[test]
fn lyapunov_is_negative_on_a_stable_orbit() {
    let v = json(&[
        "lyapunov",
        "--model",
        "gear-pair",
        "--set",
        "backlash_um=0",
        "--omega-from",
        "0.8",
        "--omega-to",
        "1.2",
        "--points",
        "2",
        "--periods",
        "100",
    ]);
    let pts = v["points"].as_array().unwrap();
    assert_eq!(pts.len(), 2);
    for p in pts {
        assert!(p["exponent_per_period"].as_f64().unwrap() < 0.0);
        assert!(p["exponent_per_s"].as_f64().unwrap() < 0.0);
    }
}

/// The gear pair at its principal parametric resonance (Omega = 2,
/// stiffness variation 0.3, damping ratio 0.05 < 0.3 / 4) is unstable when
/// engaged, and stable far from it; the CSV carries the same rows.
#[test]
fn instability_finds_the_principal_parametric_resonance() {
    let args = [
        "instability",
        "--model",
        "gear-pair",
        "--set",
        "stiffness_variation=0.3",
        "--set",
        "damping_ratio=0.05",
        "--omega-from",
        "1.0",
        "--omega-to",
        "2.0",
        "--points",
        "2",
    ];
    let v = json(&args);
    let pts = v["points"].as_array().unwrap();
    assert_eq!(pts.len(), 2);
    assert_eq!(pts[0]["unstable"], false);
    assert_eq!(pts[1]["unstable"], true);
    let rho = pts[1]["spectral_radius"].as_f64().unwrap();
    let growth = pts[1]["growth_per_period"].as_f64().unwrap();
    assert!((rho.ln() - growth).abs() < 1e-12 && rho > 1.0);
    // Stable at 1.0, unstable at 2.0: one band, from the interpolated edge
    // to the end of the scan.
    let bands = v["unstable_bands"].as_array().unwrap();
    assert_eq!(bands.len(), 1);
    assert_eq!(bands[0]["omega_to"], 2.0);
    let from = bands[0]["omega_from"].as_f64().unwrap();
    assert!(from > 1.0 && from < 2.0, "{from}");
    let bad = gearshock(&["instability", "--omega-from", "2", "--omega-to", "1"]);
    assert_eq!(bad.status.code(), Some(2));
}

/// Runs and expects exit 2 with one line on stderr containing every needle,
/// no panic and nothing on stdout; returns the line.
fn refused(args: &[&str], needles: &[&str]) -> String {
    let out = gearshock(args);
    let err = String::from_utf8_lossy(&out.stderr).to_string();
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    for n in needles {
        assert!(err.contains(n), "{args:?}: `{n}` not in {err}");
    }
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    assert!(out.stdout.is_empty(), "{args:?}: no partial output");
    err
}

fn temp_dir(name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("gearshock-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("dir");
    dir
}

fn write_json(dir: &std::path::Path, name: &str, v: &Value) -> String {
    let file = dir.join(name);
    std::fs::write(&file, v.to_string()).expect("write");
    file.to_str().expect("path").to_string()
}

/// Two real shards of a tiny sweep (3 points, up and down).
fn tiny_sweep_shards() -> Vec<Value> {
    (0..2)
        .map(|i| {
            let shard = format!("{i}/2");
            json(&[
                "bifurcation",
                "--model",
                "gear-pair",
                "--omega-from",
                "0.5",
                "--omega-to",
                "0.7",
                "--points",
                "3",
                "--direction",
                "both",
                "--transient-periods",
                "5",
                "--record-periods",
                "2",
                "--shard",
                &shard,
            ])
        })
        .collect()
}

#[test]
fn merge_refuses_forged_shards_before_sizing_anything() {
    let dir = temp_dir("forged");
    let good = tiny_sweep_shards();
    let merge = |shards: &[Value], needles: &[&str]| {
        let files: Vec<String> = shards
            .iter()
            .enumerate()
            .map(|(i, v)| write_json(&dir, &format!("s{i}.json"), v))
            .collect();
        let mut args = vec!["merge"];
        args.extend(files.iter().map(String::as_str));
        refused(&args, needles)
    };
    // The genuine shards merge.
    let files: Vec<String> = good
        .iter()
        .enumerate()
        .map(|(i, v)| write_json(&dir, &format!("g{i}.json"), v))
        .collect();
    let merged = json(&["merge", &files[0], &files[1]]);
    assert_eq!(merged["points"].as_array().expect("points").len(), 6);

    // A forged shard count sized memory: capacity overflow (exit 101) or abort (134).
    for (chains, needle) in [
        (json!(u64::MAX), "out of range"),
        (json!(1_000_000_000_000u64), "out of range"),
        // The shards still say i/2: not shards of 3.
        (json!(3), "spec.shard = \"0/2\" is out of range"),
    ] {
        let mut forged = good.clone();
        for v in &mut forged {
            v["spec"]["chains"] = chains.clone();
        }
        merge(&forged, &["chains", needle]);
    }
    let mut forged = good.clone();
    for v in &mut forged {
        v["spec"]["points"] = json!(u64::MAX);
    }
    merge(&forged, &["points", "out of range"]);
    // A foreign point (omega 999) was copied into the output.
    let mut forged = good.clone();
    forged[0]["points"][0]["omega"] = json!(999.0);
    merge(&forged, &["omega 999", "not on the sweep's grid"]);
    let mut forged = good.clone();
    forged[0]["points"][0]["index"] = json!(1);
    merge(&forged, &["index 1", "not on the sweep's grid"]);
    let mut forged = good.clone();
    let extra = forged[0]["points"][0].clone();
    forged[0]["points"]
        .as_array_mut()
        .expect("points")
        .push(extra);
    merge(&forged, &["given twice"]);
    let mut forged = good.clone();
    forged[1]["points"].as_array_mut().expect("points").pop();
    merge(&forged, &["missing"]);
    // A forged parameter set would be copied into the output.
    let mut forged = good.clone();
    for v in &mut forged {
        v["params"]["backlash_um"] = json!(-5);
    }
    merge(&forged, &["params", "backlash_um"]);
    // Step counts that wrapped when summed.
    let mut forged = good.clone();
    forged[0]["points"][0]["stats"]["steps"] = json!(u64::MAX);
    merge(&forged, &["stats.steps", "out of range"]);

    // Maps: forged shard count and a cell off the grid.
    let map_shard = |i: u32| {
        let shard = format!("{i}/2");
        json(&[
            "map",
            "--model",
            "gear-pair",
            "--omega-from",
            "0.5",
            "--omega-to",
            "0.6",
            "--omega-points",
            "2",
            "--value-from",
            "50",
            "--value-to",
            "60",
            "--value-points",
            "2",
            "--transient-periods",
            "5",
            "--record-periods",
            "2",
            "--shard",
            &shard,
        ])
    };
    let maps = vec![map_shard(0), map_shard(1)];
    let mut forged = maps.clone();
    for v in &mut forged {
        v["spec"]["shards"] = json!(4_000_000_000u64);
    }
    merge(&forged, &["shards", "out of range"]);
    let mut forged = maps.clone();
    forged[1]["cells"][0]["row"] = json!(999);
    merge(&forged, &["row 999", "not on the map's grid"]);
    let mut forged = maps.clone();
    forged[1]["cells"][0]["value"] = json!(1e300);
    merge(&forged, &["not on the map's grid"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn input_files_are_read_through_a_size_limit() {
    // `--params /dev/zero` read until memory ran out.
    refused(&["params", "--params", "/dev/zero"], &["/dev/zero"]);
    let dir = temp_dir("big");
    let big = dir.join("big.json");
    let mut text = " ".repeat(2 << 20);
    text.push_str("{}");
    std::fs::write(&big, &text).expect("write");
    let big = big.to_str().expect("path");
    refused(
        &["params", "--params", big],
        &["--params", "larger than", "1 MiB"],
    );
    // A pipe (no size to look at first) is cut at the limit too.
    let mut child = Command::new(env!("CARGO_BIN_EXE_gearshock"))
        .args(["params", "--params", "/dev/stdin"])
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("spawn");
    let mut stdin = child.stdin.take().expect("stdin");
    let writer = std::thread::spawn(move || {
        use std::io::Write;
        // The reader stops early: a broken pipe here is expected.
        let _ = stdin.write_all(text.as_bytes());
    });
    let out = child.wait_with_output().expect("wait");
    let _ = writer.join();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(err.contains("larger than"), "{err}");
    refused(&["merge", "/dev/zero"], &["merge", "/dev/zero"]);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn total_work_and_memory_are_capped_naming_the_options() {
    // Each option within its range, the product not: these grew memory
    // until they died, or ran for days.
    refused(
        &[
            "bifurcation",
            "--omega-from",
            "0.1",
            "--omega-to",
            "2",
            "--points",
            "100000",
            "--record-periods",
            "100000",
            "--mesh",
            "all",
        ],
        &["--points", "--record-periods", "100000000", "--shard"],
    );
    refused(
        &[
            "bifurcation",
            "--omega-from",
            "0.1",
            "--omega-to",
            "2",
            "--points",
            "1000",
            "--record-periods",
            "10000",
            "--transient-periods",
            "0",
            "--mesh",
            "all",
        ],
        &["--mesh", "--record-periods", "Poincaré samples", "2000000"],
    );
    refused(
        &[
            "lyapunov",
            "--omega-from",
            "0.1",
            "--omega-to",
            "2",
            "--points",
            "10000",
            "--transient-periods",
            "1000000",
            "--periods",
            "100000",
        ],
        &["--points 10000", "--periods 100000", "100000000"],
    );
    refused(
        &[
            "map",
            "--omega-from",
            "0.1",
            "--omega-to",
            "2",
            "--omega-points",
            "2000",
            "--value-from",
            "10",
            "--value-to",
            "200",
            "--value-points",
            "500",
        ],
        &["--omega-points", "--value-points", "100000000"],
    );
    refused(
        &[
            "frf",
            "--omega-from",
            "0.1",
            "--omega-to",
            "2",
            "--points",
            "100000",
            "--harmonics",
            "40",
        ],
        &["--points 100000", "--harmonics 40", "2000000000"],
    );
    // The largest number the flag parses overflowed the budget's arithmetic.
    refused(
        &[
            "frf",
            "--omega-from",
            "0.1",
            "--omega-to",
            "2",
            "--harmonics",
            "18446744073709551615",
        ],
        &["--harmonics 18446744073709551615", "1 ..= 40"],
    );
    for flag in ["--transient-periods", "--record-periods"] {
        refused(
            &[
                "bifurcation",
                "--omega-from",
                "0.1",
                "--omega-to",
                "2",
                flag,
                "4294967295",
            ],
            &[flag, "4294967295"],
        );
    }
}

#[test]
fn progress_lines_go_to_stderr_on_request_even_when_it_is_not_a_terminal() {
    let args = [
        "bifurcation",
        "--model",
        "gear-pair",
        "--omega-from",
        "0.5",
        "--omega-to",
        "0.7",
        "--points",
        "3",
        "--transient-periods",
        "5",
        "--record-periods",
        "2",
    ];
    let quiet = gearshock(&args);
    assert!(quiet.status.success());
    assert!(
        quiet.stderr.is_empty(),
        "no bar when stderr is not a terminal"
    );
    let mut with = args.to_vec();
    with.push("--progress");
    let out = gearshock(&with);
    assert!(out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 3, "one line per point here: {err}");
    assert_eq!(lines[2], "gearshock: progress 3/3 points (100 %)");
    // The result is unchanged.
    let a: Value = serde_json::from_slice(&quiet.stdout).expect("json");
    let b: Value = serde_json::from_slice(&out.stdout).expect("json");
    assert_eq!(a, b);
}

#[test]
fn negative_values_are_accepted_and_options_checked_before_any_work() {
    // "unexpected argument '-1' found" before.
    refused(
        &["simulate", "--omega", "-1"],
        &["--omega -1", "0.01 ..= 20"],
    );
    refused(
        &["simulate", "--omega", "0.5", "--rtol", "-1e-6"],
        &["--rtol -0.000001", "1e-13"],
    );
    let v = json(&[
        "map",
        "--model",
        "gear-pair",
        "--key",
        "te_um",
        "--value-from",
        "-100",
        "--value-to",
        "-0",
        "--value-points",
        "2",
        "--omega-from",
        "0.5",
        "--omega-to",
        "0.6",
        "--omega-points",
        "2",
        "--transient-periods",
        "5",
        "--record-periods",
        "2",
    ]);
    assert_eq!(v["spec"]["value_from"], -100.0);
    // A typed -0 is echoed as 0.
    assert_eq!(v["spec"]["value_to"].to_string(), "0.0");
    assert_eq!(v["cells"][0]["value"], -100.0);
    // These computed every point and then named an internal grid value; a
    // large --points shows they now stop before the first point.
    refused(
        &[
            "lyapunov",
            "--omega-from",
            "0.1",
            "--omega-to",
            "20.001",
            "--points",
            "10000",
            "--periods",
            "10",
            "--transient-periods",
            "10",
        ],
        &["--omega-to 20.001", "0.01 ..= 20"],
    );
    refused(
        &["instability", "--omega-from", "1", "--omega-to", "25"],
        &["--omega-to 25", "0.01 ..= 20"],
    );
    refused(
        &[
            "lyapunov",
            "--omega-from",
            "0.5",
            "--omega-to",
            "1",
            "--periods",
            "0",
        ],
        &["--periods 0"],
    );
    refused(
        &["bifurcation", "--omega-from", "-1", "--omega-to", "1"],
        &["--omega-from -1"],
    );
}

#[test]
fn no_setting_is_silently_dropped_by_the_model_choice() {
    // `model` reset every parameter, so the backlash given before it was lost.
    let v = json(&[
        "params",
        "--set",
        "backlash_um=50",
        "--set",
        "model=gear-pair",
    ]);
    assert_eq!(v["model"], "gear-pair");
    assert_eq!(v["backlash_um"], 50);
    refused(
        &[
            "params",
            "--model",
            "ravigneaux",
            "--set",
            "model=gear-pair",
        ],
        &["--set model=gear-pair", "--model ravigneaux"],
    );
    // A parameter file of the other model would be replaced by defaults.
    let dir = temp_dir("model");
    let file = write_json(
        &dir,
        "p.json",
        &json!({"model": "ravigneaux", "planets": 4}),
    );
    refused(
        &["params", "--params", &file, "--model", "gear-pair"],
        &["--params", "ravigneaux", "--model gear-pair"],
    );
    let v = json(&["params", "--params", &file, "--set", "backlash_um=70"]);
    assert_eq!(v["planets"], 4);
    assert_eq!(v["backlash_rb_um"], 70);
    let v = json(&["params", "--set", "te_um=-0"]);
    assert_eq!(v["te_sin_s1a_um"].to_string(), "0");
    let _ = std::fs::remove_dir_all(&dir);
}

/// The JSON lines of a run: every line parses.
fn json_lines(args: &[&str]) -> Vec<Value> {
    let out = gearshock(args);
    assert!(
        out.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).expect("one JSON value per line"))
        .collect()
}

#[test]
fn jsonl_streams_each_point_as_computed_with_the_same_results() {
    let sweep = [
        "bifurcation",
        "--model",
        "gear-pair",
        "--omega-from",
        "0.5",
        "--omega-to",
        "0.7",
        "--points",
        "3",
        "--direction",
        "both",
        "--transient-periods",
        "5",
        "--record-periods",
        "2",
    ];
    let whole = json(&sweep);
    let mut args = sweep.to_vec();
    args.extend(["--format", "jsonl"]);
    let lines = json_lines(&args);
    assert_eq!(lines.len(), 1 + 6 + 1);
    assert_eq!(lines[0]["spec"], whole["spec"]);
    assert_eq!(lines[0]["params"], whole["params"]);
    assert_eq!(lines[7], json!({"complete": true, "points": 6}));
    let key = |p: &Value| (p["direction"].to_string(), p["index"].as_u64());
    let mut streamed: Vec<Value> = lines[1..7].to_vec();
    let mut written: Vec<Value> = whole["points"].as_array().expect("points").clone();
    streamed.sort_by_key(key);
    written.sort_by_key(key);
    assert_eq!(streamed, written);

    let lyap = [
        "lyapunov",
        "--model",
        "gear-pair",
        "--omega-from",
        "0.5",
        "--omega-to",
        "0.6",
        "--points",
        "2",
        "--transient-periods",
        "10",
        "--periods",
        "10",
    ];
    let whole = json(&lyap);
    let mut args = lyap.to_vec();
    args.extend(["--format", "jsonl"]);
    let lines = json_lines(&args);
    assert_eq!(lines[0]["spec"], whole["spec"]);
    assert_eq!(lines[1..3], whole["points"].as_array().expect("points")[..]);
    assert_eq!(lines[3], json!({"complete": true, "points": 2}));

    let inst = [
        "instability",
        "--model",
        "gear-pair",
        "--omega-from",
        "0.5",
        "--omega-to",
        "2",
        "--points",
        "3",
    ];
    let whole = json(&inst);
    let mut args = inst.to_vec();
    args.extend(["--format", "jsonl"]);
    let lines = json_lines(&args);
    assert_eq!(lines[1..4], whole["points"].as_array().expect("points")[..]);
    assert_eq!(lines[4], json!({"complete": true, "points": 3}));

    let map = [
        "map",
        "--model",
        "gear-pair",
        "--omega-from",
        "0.5",
        "--omega-to",
        "0.6",
        "--omega-points",
        "2",
        "--value-from",
        "50",
        "--value-to",
        "60",
        "--value-points",
        "2",
        "--transient-periods",
        "5",
        "--record-periods",
        "2",
    ];
    let whole = json(&map);
    let mut args = map.to_vec();
    args.extend(["--format", "jsonl"]);
    let lines = json_lines(&args);
    assert_eq!(lines[0]["spec"], whole["spec"]);
    assert_eq!(lines[1..5], whole["cells"].as_array().expect("cells")[..]);
    assert_eq!(lines[5], json!({"complete": true, "cells": 4}));

    // Other commands write their one document on one line.
    let lines = json_lines(&["params", "--format", "jsonl"]);
    assert_eq!(lines, vec![json(&["params"])]);
}

#[test]
fn presets_prints_every_figure_with_its_family_and_panels() {
    let v = json(&["presets"]);
    let list = v["presets"].as_array().expect("presets array");
    let by_id = |id: &str| {
        list.iter()
            .find(|p| p["id"] == id)
            .unwrap_or_else(|| panic!("no preset {id}"))
    };
    for p in list {
        for field in ["id", "title", "settings", "family", "meshes"] {
            assert!(p.get(field).is_some(), "{}: no {field}", p["id"]);
        }
        assert!(p["settings"]["model"].is_string(), "{}", p["id"]);
    }
    // Fig. 5: one Omega, TE 0 / 20 / 30 um across the panels, b = 200 um.
    let f5 = by_id("fig5");
    assert_eq!(f5["settings"]["omega"], 0.5);
    assert_eq!(f5["settings"]["backlash_um"], 200);
    assert_eq!(f5["settings"]["mesh"], "s1a1");
    assert_eq!(f5["family"]["key"], "te_um");
    assert_eq!(f5["family"]["values"], serde_json::json!([0, 20, 30]));
    assert!(f5["meshes"].is_null());
    // Fig. 2: four mesh kinds as panels, a TE family, no backlash.
    let f2 = by_id("fig2");
    assert_eq!(
        f2["meshes"],
        serde_json::json!(["s1a1", "s2b1", "a1b1", "rb1"])
    );
    assert_eq!(f2["settings"]["backlash_um"], 0);
    assert_eq!(f2["settings"]["te_meshes"], "all");
    assert_eq!(f2["family"]["values"][0], 5);
    // Fig. 8: a backlash family at TE 20 um; the table defaults are no family.
    assert_eq!(by_id("fig8")["family"]["key"], "backlash_um");
    assert!(by_id("table1")["family"].is_null());
    // Every member's settings are accepted by the other commands.
    let s = &by_id("fig3")["settings"];
    let out = gearshock(&[
        "params",
        "--set",
        &format!("te_um={}", s["te_um"]),
        "--set",
        "backlash_um=150",
    ]);
    assert!(out.status.success());
}

#[test]
fn figure_fig5_writes_three_phase_portraits_and_three_poincare_sections() {
    let dir = std::env::temp_dir().join(format!("gearshock-fig5-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = dir.to_str().expect("path");
    let v = json(&[
        "figure",
        "fig5",
        "--out",
        out,
        "--transient-periods",
        "40",
        "--record-periods",
        "8",
    ]);
    let panels = v["panels"].as_array().expect("panels");
    let names: Vec<&str> = panels
        .iter()
        .map(|p| p["panel"].as_str().unwrap())
        .collect();
    assert_eq!(
        names,
        ["fig5a", "fig5b", "fig5c", "fig5d", "fig5e", "fig5f"]
    );
    for (i, p) in panels.iter().enumerate() {
        let view = if i < 3 { "phase" } else { "poincare" };
        assert_eq!(p["view"], view);
        // Panels a and d are TE 0 um, b and e 20 um, c and f 30 um (Fig. 5).
        let te = ["te_um=0", "te_um=20", "te_um=30"][i % 3];
        assert!(p["query"].as_str().unwrap().ends_with(te), "{p}");
        assert!(p["query"].as_str().unwrap().contains("omega=0.5"));
        let name = names[i];
        let svg = std::fs::read_to_string(dir.join(format!("{name}.svg"))).expect("svg");
        assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
        let title = if i < 3 {
            "Phase portrait"
        } else {
            "Poincaré section"
        };
        assert!(svg.contains(title), "{name}");
        assert!(
            svg.contains(&format!("TE {} µm", [0, 20, 30][i % 3])),
            "{name}"
        );
        let data: Value = serde_json::from_str(
            &std::fs::read_to_string(dir.join(format!("{name}.json"))).unwrap(),
        )
        .unwrap();
        assert_eq!(data["view"]["omega"], 0.5);
        assert_eq!(data["view"]["backlash_um"], 200.0);
        let csv = std::fs::read_to_string(dir.join(format!("{name}.csv"))).expect("csv");
        // 8 recorded periods: 8 Poincaré samples, or 8 x 64 orbit samples.
        let rows = csv.lines().count() - 1;
        assert_eq!(rows, if i < 3 { 8 * 64 } else { 8 }, "{name}");
    }
    // A bifurcation figure: three panels, one sweep each, on a small grid.
    let v = json(&[
        "figure",
        "fig8",
        "--out",
        out,
        "--points",
        "3",
        "--transient-periods",
        "20",
        "--record-periods",
        "4",
    ]);
    let panels = v["panels"].as_array().expect("panels");
    assert_eq!(panels.len(), 3);
    for (p, b) in panels.iter().zip([50, 100, 200]) {
        assert_eq!(p["points"], 6, "3 points up and down");
        assert!(p["query"]
            .as_str()
            .unwrap()
            .ends_with(&format!("backlash_um={b}")));
        let name = p["panel"].as_str().unwrap();
        let svg = std::fs::read_to_string(dir.join(format!("{name}.svg"))).expect("svg");
        assert!(svg.contains("Bifurcation diagram") && svg.contains(&format!("backlash {b} µm")));
        // The dots: 6 sweep points x 4 Poincaré samples, one rectangle each,
        // inside the one SVG document.
        assert!(svg.matches("<rect").count() > 24, "{name}");
        assert_eq!(svg.matches("</svg>").count(), 1, "{name}");
    }
    // A frequency-response figure: four mesh panels, every member's branch
    // in each, overlaid in the SVG one colour per value, named in words.
    let v = json(&["figure", "fig3", "--out", out, "--points", "10"]);
    let panels = v["panels"].as_array().expect("panels");
    let meshes: Vec<&str> = panels.iter().map(|p| p["mesh"].as_str().unwrap()).collect();
    assert_eq!(meshes, ["s1a1", "s2b1", "a1b1", "rb1"]);
    for p in panels {
        let name = p["panel"].as_str().unwrap();
        assert!(
            p["svg"] == format!("{name}.svg") && p["complete"] == true,
            "{p}"
        );
        let svg = std::fs::read_to_string(dir.join(format!("{name}.svg"))).expect("svg");
        assert!(
            svg.contains(&format!("mesh {}", p["mesh"].as_str().unwrap())),
            "{name}"
        );
        for (i, b) in [50, 100, 150, 200].iter().enumerate() {
            assert!(svg.contains(&format!("backlash {b} µm")), "{name}: {b}");
            let c = app::plots::family_color(i);
            let hex = format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2);
            assert!(svg.contains(&hex), "{name}: the colour of backlash {b} µm");
        }
        // Every member's ±b: the key names all four.
        assert!(svg.contains("b = 50, 100, 150, 200 µm"), "{name}");
        let data: Value = serde_json::from_str(
            &std::fs::read_to_string(dir.join(format!("{name}.json"))).unwrap(),
        )
        .unwrap();
        let members = data["members"].as_array().unwrap();
        let b: Vec<f64> = members
            .iter()
            .map(|m| m["member"].as_f64().unwrap())
            .collect();
        assert_eq!(b, [50.0, 100.0, 150.0, 200.0]);
        for m in members {
            assert_eq!(m["params"]["te_sin_s1a_um"], 60);
            assert_eq!(m["params"]["backlash_rb_um"].as_f64(), m["member"].as_f64());
            assert!(m["branch"].as_array().unwrap().len() > 5);
        }
    }
    // A bad option: exit 2 naming it and its range, before any work.
    let o = gearshock(&["figure", "fig8", "--out", out, "--points", "1"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--points 1: allowed 2 ..= 2000"));
    // Not a figure: exit 2 naming it.
    for (id, words) in [
        ("fig99", "no such figure"),
        ("table1", "not one of the paper's figures"),
    ] {
        let o = gearshock(&["figure", id, "--out", out]);
        assert_eq!(o.status.code(), Some(2), "{id}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(id) && err.contains(words), "{err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
