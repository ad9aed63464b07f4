//! `gearshock instability`: the principal parametric resonance of the gear pair.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::{gearshock, json, words};

/// The gear pair at its principal parametric resonance (Omega = 2,
/// stiffness variation 0.3, damping ratio 0.05 < 0.3 / 4) is unstable when
/// engaged, and stable far from it; the CSV carries the same rows.
#[test]
fn instability_finds_the_principal_parametric_resonance() {
    let args = words("instability --model gear-pair --set stiffness_variation=0.3 --set damping_ratio=0.05 --omega-from 1.0 --omega-to 2.0 --points 2");
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

/// Streamed (`--format jsonl`), the scan says the same bands as the
/// document (not "none" while its lines say unstable), and its header
/// carries the spec, as every streamed command's does.
#[test]
fn streamed_scan_says_its_bands_and_carries_its_spec() {
    let scan = "instability --model gear-pair --set stiffness_variation=0.3 --set damping_ratio=0.05 --omega-from 1.0 --omega-to 2.0 --points 2";
    let whole = json(&words(scan));
    let mut args = words(scan);
    args.extend(["--format", "jsonl"]);
    let out = gearshock(&args);
    assert_eq!(out.status.code(), Some(0));
    let text = String::from_utf8_lossy(&out.stdout);
    let header: serde_json::Value = serde_json::from_str(text.lines().next().unwrap()).unwrap();
    assert_eq!(header["spec"], whole["spec"]);
    assert_eq!(header["spec"]["points"], 2);
    assert_eq!(header["spec"]["omega_to"], 2.0);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("to 2.0000") && !err.contains("none"), "{err}");
    // Far from the resonance: plainly none.
    let calm = words("instability --model gear-pair --set stiffness_variation=0.3 --set damping_ratio=0.05 --omega-from 1.0 --omega-to 1.2 --points 2 --format jsonl");
    let out = gearshock(&calm);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("none in the scanned range"), "{err}");
}
