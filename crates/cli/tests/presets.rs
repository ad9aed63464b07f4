//! `gearshock presets`: every figure with its family and panels.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::{gearshock, json};

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
