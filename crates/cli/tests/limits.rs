//! Limits every subcommand shares: bad input exits 2 with one line naming
//! it, work and memory capped naming the options, negative values accepted
//! and every option checked before any work.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::{gearshock, json, refused, words};

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
            &words("bifurcation --omega-from 0.1 --omega-to 1 --points 99999999"),
            "points",
        ),
        (
            &words("bifurcation --omega-from 0.1 --omega-to 1 --shard 3/2"),
            "shard",
        ),
        (
            &words("bifurcation --omega-from 0.1 --omega-to 1 --direction sideways"),
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
fn total_work_and_memory_are_capped_naming_the_options() {
    // Each option within its range, the product not: these grew memory
    // until they died, or ran for days. Each refusal is one line of at most
    // 200 characters.
    let refused = |args: &[&str], needles: &[&str]| {
        let err = refused(args, needles);
        assert!(err.trim_end().chars().count() <= 200, "{args:?}: {err}");
    };
    refused(
        &words("bifurcation --omega-from 0.1 --omega-to 2 --points 100000 --record-periods 100000 --mesh all"),
        &["--points", "--record-periods", "integration steps", "4e9", "--shard"],
    );
    refused(
        &words("bifurcation --omega-from 0.1 --omega-to 2 --points 1000 --record-periods 10000 --transient-periods 0 --mesh all"),
        &["--mesh", "--record-periods", "Poincaré samples", "2000000"],
    );
    refused(
        &words("lyapunov --omega-from 0.1 --omega-to 2 --points 10000 --transient-periods 1000000 --periods 100000"),
        &["--points 10000", "--periods 100000", "4e9"],
    );
    refused(
        &words("map --omega-from 0.1 --omega-to 2 --omega-points 2000 --value-from 10 --value-to 200 --value-points 500"),
        &["--omega-points", "--value-points", "4e9"],
    );
    refused(
        &words("frf --omega-from 0.1 --omega-to 2 --points 100000 --harmonics 40"),
        &["--points 100000", "--harmonics 40", "2000000000"],
    );
    // The largest number the flag parses overflowed the budget's arithmetic.
    refused(
        &words("frf --omega-from 0.1 --omega-to 2 --harmonics 18446744073709551615"),
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
fn work_is_priced_in_integration_steps_by_the_stiffest_mode_before_any_work() {
    // The same options: accepted on the default model (its header line
    // is streamed, which only happens after the budget's check; the run is
    // then stopped), refused when 1e12 N/m planet-planet and ring-planet
    // stiffnesses raise the stiffest mode about 20 times, and with it the
    // steps a period takes.
    let opts = "--omega-from 0.05 --omega-to 0.2 --points 60 --transient-periods 100000 --record-periods 1 --direction up --format jsonl";
    let mut child = test_support::cli::command(&words(&format!("bifurcation {opts}")))
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let mut header = String::new();
    std::io::BufRead::read_line(
        &mut std::io::BufReader::new(child.stdout.take().unwrap()),
        &mut header,
    )
    .unwrap();
    child.kill().unwrap();
    child.wait().unwrap();
    assert!(header.contains("\"spec\""), "accepted: {header}");
    let err = refused(
        &words(&format!(
            "bifurcation {opts} --set stiffness_ab_n_m=1e12 --set stiffness_rb_n_m=1e12"
        )),
        &["integration steps", "4e9"],
    );
    assert!(err.trim_end().chars().count() <= 200, "{err}");
    // A figure has a budget too, checked before its first panel.
    refused(
        &words("figure fig8 --points 2000 --transient-periods 100000 --record-periods 100 --out /tmp/never-written"),
        &["figure fig8", "integration steps", "--shard"],
    );
    assert!(!std::path::Path::new("/tmp/never-written").exists());
    refused(
        &words("figure fig8 --points 2000 --transient-periods 100 --record-periods 10000 --out /tmp/never-written"),
        &["figure fig8", "Poincaré samples"],
    );
    // Integer keys take whole values in every row; shards are rows.
    refused(
        &words("map --omega-from 0.1 --omega-to 2 --key planets --value-from 3 --value-to 6 --value-points 7"),
        &["--value-points 7", "planets", "3.5"],
    );
    refused(
        &words("map --omega-from 0.1 --omega-to 2 --value-from 0 --value-to 100 --value-points 2 --shard 0/100"),
        &["--shard 0/100", "--value-points 2"],
    );
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
    let v = json(&words("map --model gear-pair --key te_um --value-from -100 --value-to -0 --value-points 2 --omega-from 0.5 --omega-to 0.6 --omega-points 2 --transient-periods 5 --record-periods 2"));
    assert_eq!(v["spec"]["value_from"], -100.0);
    // A typed -0 is echoed as 0.
    assert_eq!(v["spec"]["value_to"].to_string(), "0.0");
    assert_eq!(v["cells"][0]["value"], -100.0);
    // These computed every point and then named an internal grid value; a
    // large --points shows they now stop before the first point.
    refused(
        &words("lyapunov --omega-from 0.1 --omega-to 20.001 --points 10000 --periods 10 --transient-periods 10"),
        &["--omega-to 20.001", "0.01 ..= 20"],
    );
    refused(
        &["instability", "--omega-from", "1", "--omega-to", "25"],
        &["--omega-to 25", "0.01 ..= 20"],
    );
    refused(
        &words("lyapunov --omega-from 0.5 --omega-to 1 --periods 0"),
        &["--periods 0"],
    );
    refused(
        &["bifurcation", "--omega-from", "-1", "--omega-to", "1"],
        &["--omega-from -1"],
    );
}
