//! Refusals of the command line in plain words: every bad flag is named
//! with the range the command really allows (not its integer type's), in
//! one line of at most 200 characters, with a long value cut and control
//! characters escaped; a key given twice in a file is refused, named.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::{refused, words};

const OMEGA: &str = "--omega-from 0.5 --omega-to 1";

fn with(base: &str, extra: &[&str]) -> Vec<String> {
    let mut a: Vec<String> = base.split_whitespace().map(String::from).collect();
    a.extend(extra.iter().map(|s| s.to_string()));
    a
}

fn refused_line(args: &[String], needles: &[&str]) -> String {
    let a: Vec<&str> = args.iter().map(String::as_str).collect();
    let line = refused(&a, needles);
    assert!(
        line.trim_end().chars().count() <= 200,
        "{args:?}: {} characters: {line}",
        line.trim_end().chars().count()
    );
    line
}

#[test]
fn values_clap_used_to_word_name_the_flag_and_its_range() {
    let b = format!("bifurcation {OMEGA}");
    let cases: &[(Vec<String>, &[&str])] = &[
        (with(&b, &["--shard", "-1/2"]), &["--shard -1/2", "i/n"]),
        (
            with(&b, &["--points", "-inf"]),
            &["--points -inf", "not a whole number", "1 ..= 100000"],
        ),
        (
            with("figure fig8", &["--points", "-0"]),
            &["--points", "out of range", "2 ..= 2000"],
        ),
        (
            with(
                &format!("map {OMEGA} --value-to 3"),
                &["--value-from", "NaN"],
            ),
            &["--value-from NaN", "not a finite number"],
        ),
        (
            with(&b, &["--points", "99999999999"]),
            &["--points 99999999999", "out of range", "1 ..= 100000"],
        ),
        (
            with("simulate --omega 0.5", &["--record-periods", "-3"]),
            &["--record-periods -3", "1 ..= 100000"],
        ),
        (
            with("simulate", &["--omega", "1e999"]),
            &["--omega 1e999", "not a finite number", "0.01 ..= 20"],
        ),
        (
            with("simulate", &["--omega", "abc"]),
            &["--omega abc", "not a number"],
        ),
    ];
    for (args, needles) in cases {
        let line = refused_line(args, needles);
        // The integer type's range is never shown.
        assert!(!line.contains("4294967295"), "{args:?}: {line}");
        assert!(!line.contains("invalid value"), "{args:?}: {line}");
    }
}

#[test]
fn a_huge_value_is_cut_and_the_line_stays_short() {
    let digits = "9".repeat(100_000);
    let line = refused_line(
        &with(&format!("bifurcation {OMEGA}"), &["--points", &digits]),
        &["--points 999", "1 ..= 100000"],
    );
    assert!(line.contains('…'), "{line}");
}

/// Each whole-number flag's range, as the command's own check words it
/// for a value of its type (0 or 4294967295), is the range the refusal of
/// a value beyond its type (99999999999) names: one range per flag, the
/// command's.
#[test]
fn a_flag_beyond_its_type_names_the_range_the_command_checks() {
    let frf = format!("frf --model gear-pair {OMEGA}");
    let boundaries = format!("boundaries --key te_um --value-from 1 --value-to 2 {OMEGA}");
    let map = format!("map {OMEGA} --value-from 1 --value-to 2");
    let cases: &[(String, &str, &str, &str)] = &[
        ("bench".into(), "--repeats", "0", "1 ..= 100"),
        (
            format!("bifurcation {OMEGA}"),
            "--points",
            "0",
            "1 ..= 100000",
        ),
        (
            format!("bifurcation {OMEGA}"),
            "--chains",
            "0",
            "1 ..= points",
        ),
        (
            format!("bifurcation {OMEGA}"),
            "--record-periods",
            "0",
            "1 ..= 100000",
        ),
        (
            format!("bifurcation {OMEGA}"),
            "--transient-periods",
            "4294967295",
            "0 ..= 1000000",
        ),
        (boundaries.clone(), "--levels", "0", "2 ..= 50"),
        (boundaries.clone(), "--points", "0", "10 ..= 2000"),
        (boundaries, "--harmonics", "0", "1 ..= 40"),
        ("figure fig8".into(), "--points", "0", "2 ..= 2000"),
        (
            "figure fig8".into(),
            "--transient-periods",
            "0",
            "1 ..= 100000",
        ),
        ("figure fig8".into(), "--record-periods", "0", "1 ..= 10000"),
        (frf.clone(), "--points", "0", "2 ..= 100000"),
        (frf.clone(), "--harmonics", "0", "1 ..= 40"),
        (frf.clone(), "--grid", "0", "4 H + 1 ..= 65536"),
        (
            format!("{frf} --method shooting"),
            "--period",
            "0",
            "1 ..= 32",
        ),
        (
            format!("instability {OMEGA}"),
            "--points",
            "0",
            "2 ..= 100000",
        ),
        (format!("lyapunov {OMEGA}"), "--points", "0", "2 ..= 10000"),
        (
            format!("lyapunov {OMEGA}"),
            "--periods",
            "0",
            "1 ..= 100000",
        ),
        (map.clone(), "--omega-points", "0", "2 ..= 2000"),
        (map, "--value-points", "0", "1 ..= 2000"),
        (
            "simulate --omega 0.5".into(),
            "--record-periods",
            "0",
            "1 ..= 100000",
        ),
    ];
    for (base, flag, in_type, range) in cases {
        let own = refused_line(&with(base, &[flag, in_type]), &[flag, range]);
        let beyond = refused_line(
            &with(base, &[flag, "99999999999"]),
            &[&format!("{flag} 99999999999"), range],
        );
        for line in [own, beyond] {
            assert!(line.contains("out of range"), "{base} {flag}: {line}");
        }
    }
}

#[test]
fn control_characters_in_echoed_input_are_escaped() {
    let d = std::env::temp_dir().join(format!("gearshock-messages-{}", std::process::id()));
    std::fs::create_dir_all(&d).expect("dir");
    let f = d.join("nul.json");
    std::fs::write(
        &f,
        "{\"model\": \"gear-pair\", \"a\\u0000b\\u001b[31m\": 1}",
    )
    .expect("write");
    let line = refused(
        &["params", "--params", f.to_str().expect("path")],
        &["a\\u{0}b\\u{1b}[31m"],
    );
    assert!(
        !line.chars().any(|c| c.is_control() && c != '\n'),
        "{line:?}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn a_key_given_twice_in_a_parameter_file_is_refused_naming_it() {
    let d = std::env::temp_dir().join(format!("gearshock-dup-{}", std::process::id()));
    std::fs::create_dir_all(&d).expect("dir");
    for (text, key) in [
        (
            r#"{"model": "gear-pair", "backlash_um": 50, "backlash_um": 60}"#,
            "backlash_um",
        ),
        (r#"{"model": "gear-pair", "model": "ravigneaux"}"#, "model"),
    ] {
        let f = d.join("dup.json");
        std::fs::write(&f, text).expect("write");
        refused(
            &words(&format!("params --params {}", f.display())),
            &[&format!("key \"{key}\" is given twice"), "dup.json"],
        );
    }
    let _ = std::fs::remove_dir_all(&d);
}
