//! `gearshock figure`: the files of a figure's panels (shards: `figure_shards.rs`).

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use serde_json::Value;
use test_support::cli::{gearshock, json};

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
        // The panel carries the pipeline's verdict on its orbit: the
        // listing, the panel's data and its title say the same, and a
        // member's phase portrait and Poincaré section agree.
        assert_eq!(p["motion"], data["view"]["motion"], "{name}");
        assert_eq!(p["exact"], data["view"]["exact"], "{name}");
        assert_eq!(p["motion"], panels[i % 3]["motion"], "{name}");
        let verdict = p["verdict"].as_str().unwrap();
        assert!(svg.contains(&format!(": {verdict}")), "{name}: {verdict}");
        match data["view"]["period"].as_u64() {
            Some(n) => assert!(verdict.contains(&n.to_string()), "{verdict}"),
            None => assert!(verdict.starts_with("not periodic"), "{verdict}"),
        }
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
        // The dots: 6 sweep points x up to 4 Poincaré samples, one
        // rectangle per pixel, inside the one SVG document (a point on an
        // exact periodic orbit draws its 4 samples on one pixel: at least
        // one dot per point).
        assert!(svg.matches("<rect").count() > 6, "{name}");
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
            let c = figures::plots::family_color(i);
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
    assert!(String::from_utf8_lossy(&o.stderr)
        .contains("--points 1 is out of range: allowed 2 ..= 2000"));
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

/// The map's budget knows the model: where its periods' budget is over
/// the limit (stiff planet meshes take some ten times the steps a period),
/// a few pilot cells price a cell, and an undamped stiff set's cells,
/// which neither settle nor show chaos, are refused before the map starts.
#[test]
fn figure_map_over_its_budget_is_refused_before_it_starts() {
    let dir = test_support::cli::temp_dir("figure-map-budget");
    let out = dir.join("never-written");
    let link = "damping_ratio=0&stiffness_ab_n_m=1e12&stiffness_rb_n_m=1e12\
                &map_omega_points=200&map_value_points=100\
                &map_transient_periods=3000&map_record_periods=1000";
    let o = gearshock(&[
        "figure",
        "map",
        "--out",
        out.to_str().unwrap(),
        "--link",
        link,
    ]);
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    for needle in [
        "figure map --link",
        "integration steps",
        "4e9",
        "map_omega_points x map_value_points ..= ",
    ] {
        assert!(err.contains(needle), "{needle}: {err}");
    }
    assert!(!out.exists());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn figure_map_draws_a_links_map_with_the_boundaries_the_boundaries_command_traces() {
    let dir = test_support::cli::temp_dir("figure-map");
    let out = dir.to_str().expect("path");
    let link = "model=gear-pair&map_omega_points=10&map_value_points=4\
                &map_transient_periods=100&map_record_periods=20&harmonics=5";
    let v = json(&["figure", "map", "--out", out, "--link", link]);
    let panel = &v["panels"][0];
    let data: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("map.json")).unwrap()).unwrap();
    assert_eq!(data["cells"].as_array().map(Vec::len), Some(40));
    // The curves are those of `gearshock boundaries` over the same box with
    // the page's trace options (5 levels, 50 points, the link's harmonics).
    let b = json(&[
        "boundaries",
        "--model",
        "gear-pair",
        "--omega-from",
        "0.1",
        "--omega-to",
        "2",
        "--value-from",
        "0",
        "--value-to",
        "200",
        "--levels",
        "5",
        "--points",
        "50",
        "--harmonics",
        "5",
    ]);
    let kinds = |curves: &Value| -> Vec<String> {
        curves
            .as_array()
            .unwrap()
            .iter()
            .map(|c| c["kind"].as_str().unwrap().to_string())
            .collect()
    };
    let curves = &data["boundaries"]["curves"];
    assert_eq!(kinds(curves), kinds(&b["curves"]));
    assert_eq!(panel["curves"].as_u64(), Some(kinds(curves).len() as u64));
    assert!(kinds(curves).iter().any(|k| k == "fold"), "{curves}");
    let first = &curves[0]["points"][0];
    assert_eq!(first["omega"], b["curves"][0]["points"][0]["omega"]);
    // The SVG names each kind drawn in plain words in its key.
    let svg = std::fs::read_to_string(dir.join("map.svg")).unwrap();
    assert!(svg.contains("the jump") && svg.contains("Impact-regime map"));
    assert!(std::fs::read_to_string(dir.join("map.csv"))
        .unwrap()
        .starts_with("row,column,omega,backlash_um,"));
    // The disagreeing cells are counted among those judged.
    let judged = panel["judged"].as_u64().unwrap();
    assert!(
        panel["disagree"].as_u64().unwrap() <= judged && judged > 0,
        "{panel}"
    );
    // A link that says boundaries=off gets the map alone, as the page
    // shows it, and the note says so.
    let v = json(&[
        "figure",
        "map",
        "--out",
        out,
        "--link",
        &format!("{link}&boundaries=off"),
    ]);
    assert_eq!(v["panels"][0]["boundaries"], "off");
    assert_eq!(v["panels"][0]["curves"], 0);
    let data: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("map.json")).unwrap()).unwrap();
    assert_eq!(
        data["boundaries"]["curves"].as_array().map(Vec::len),
        Some(0)
    );
    assert!(
        data["boundaries"].to_string().contains("boundaries=off"),
        "{}",
        data["boundaries"]
    );
    // Options of the paper's figures are refused, naming where the map's come from.
    let o = gearshock(&["figure", "map", "--out", out, "--points", "20"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--points: the map takes its grid"));
    let o = gearshock(&["figure", "fig5", "--out", out, "--link", link]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("only `figure map` takes a link"));
    let _ = std::fs::remove_dir_all(&dir);
}
