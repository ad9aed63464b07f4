//! `gearshock params` and `gearshock keys`: the parameter set from the defaults,
//! a file and `--set` (the model settled first, nothing dropped), and the key table.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use serde_json::json;
use test_support::cli::{gearshock, json, refused, temp_dir, words, write_json};

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
    for k in
        words("backlash_um te_um stiffness_variation damping_ratio torque_s1_nm planets phasing")
    {
        assert!(text.contains(&format!("`{k}`")), "{k}");
    }
}

#[test]
fn no_setting_is_silently_dropped_by_the_model_choice() {
    // `model` reset every parameter, so the backlash given before it was lost.
    let v = json(&words("params --set backlash_um=50 --set model=gear-pair"));
    assert_eq!(v["model"], "gear-pair");
    assert_eq!(v["backlash_um"], 50);
    refused(
        &words("params --model ravigneaux --set model=gear-pair"),
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
