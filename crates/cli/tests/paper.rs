//! `docs/paper.md` cannot drift from the code: every number it quotes is
//! recomputed here by running the very commands it gives (the debug
//! `gearshock`, with the solver optimized), formatted as the document writes
//! it, and looked up in the document's tables. A failure prints the rows the
//! document should hold.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use serde_json::Value;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

fn doc() -> String {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/paper.md");
    std::fs::read_to_string(path).expect("docs/paper.md")
}

/// Runs `gearshock` with a command line written as in the document, once
/// per line for the whole test binary (Figs. 4 and 8 share a sweep).
fn gearshock(line: &str) -> Value {
    static RUNS: OnceLock<Mutex<HashMap<String, Arc<OnceLock<Value>>>>> = OnceLock::new();
    let cell = RUNS
        .get_or_init(Mutex::default)
        .lock()
        .unwrap()
        .entry(line.to_string())
        .or_default()
        .clone();
    cell.get_or_init(|| run(line)).clone()
}

fn run(line: &str) -> Value {
    let args: Vec<&str> = line.split_whitespace().skip(1).collect();
    test_support::cli::json(&args)
}

/// Every command line quoted in a row must appear in the document too.
fn assert_rows(rows: &[String], commands: &[String]) {
    let doc = doc();
    let missing: Vec<&String> = rows
        .iter()
        .chain(commands)
        .filter(|r| !doc.contains(r.as_str()))
        .collect();
    assert!(
        missing.is_empty(),
        "docs/paper.md lacks (recomputed now):\n{}",
        missing
            .iter()
            .map(|s| s.as_str())
            .collect::<Vec<_>>()
            .join("\n")
    );
}

/// A command line of the document with its `$name` placeholders filled in.
fn fill(template: &str, values: &[(&str, &str)]) -> String {
    values
        .iter()
        .fold(template.to_string(), |t, (k, v)| t.replace(k, v))
}

/// Adds a template to the commands the document must show, once.
fn show(commands: &mut Vec<String>, template: &str) {
    if !commands.iter().any(|c| c == template) {
        commands.push(template.to_string());
    }
}

fn um(x_m: f64) -> String {
    format!("{:.1}", x_m * 1e6)
}

fn f(x: &Value) -> f64 {
    x.as_f64().unwrap_or(f64::NAN)
}

/// Contiguous runs of grid points where `pred` holds, as "a–b" (or "a").
fn ranges(points: &[Value], pred: impl Fn(&Value) -> bool) -> String {
    ranges_to(points, 2, pred)
}

/// As [`ranges`], with `digits` decimals.
fn ranges_to(points: &[Value], digits: usize, pred: impl Fn(&Value) -> bool) -> String {
    let mut out: Vec<String> = Vec::new();
    let mut run: Option<(f64, f64)> = None;
    for p in points {
        let w = f(&p["omega"]);
        if pred(p) {
            run = Some(run.map_or((w, w), |(a, _)| (a, w)));
        } else if let Some(r) = run.take() {
            out.push(span(r, digits));
        }
    }
    if let Some(r) = run {
        out.push(span(r, digits));
    }
    if out.is_empty() {
        "none".into()
    } else {
        out.join(", ")
    }
}

fn span((a, b): (f64, f64), digits: usize) -> String {
    if (a - b).abs() < 1e-9 {
        format!("{a:.digits$}")
    } else {
        format!("{a:.digits$}–{b:.digits$}")
    }
}

/// Fig. 2's frequency responses: `$reading` and `$te` filled in.
const FIG2: &str = "gearshock frf --set backlash_um=0 --set te_meshes=$reading --set te_um=$te --mesh s1a1 --omega-from 0.1 --omega-to 2";

/// Peaks of a branch's amplitude: local maxima at least 20 % above the
/// lowest amplitude within 0.05 in Omega on either side, one per 0.02.
fn peaks(branch: &[Value]) -> Vec<String> {
    let w: Vec<f64> = branch.iter().map(|p| f(&p["omega"])).collect();
    let a: Vec<f64> = branch.iter().map(|p| f(&p["delta_amplitude_m"])).collect();
    let lowest = |lo: f64, hi: f64| {
        (0..a.len())
            .filter(|&j| (lo..=hi).contains(&w[j]))
            .map(|j| a[j])
            .fold(f64::INFINITY, f64::min)
    };
    let mut out: Vec<(f64, f64)> = Vec::new();
    for i in 1..a.len().saturating_sub(1) {
        let prominent =
            a[i] >= 1.2 * lowest(w[i] - 0.05, w[i]) && a[i] >= 1.2 * lowest(w[i], w[i] + 0.05);
        if a[i] >= a[i - 1] && a[i] >= a[i + 1] && prominent {
            match out.last_mut() {
                Some(last) if w[i] - last.0 < 0.02 => {
                    if a[i] > last.1 {
                        *last = (w[i], a[i]);
                    }
                }
                _ => out.push((w[i], a[i])),
            }
        }
    }
    out.iter().map(|(w, _)| format!("{w:.3}")).collect()
}

#[test]
fn the_frequency_scale() {
    let modes_line = |set: &str| format!("gearshock modes{set}");
    let natural = |v: &Value, kind: &str| -> Vec<String> {
        let mut out: Vec<String> = Vec::new();
        for m in v["modes"].as_array().unwrap() {
            let s = format!("{:.3}", f(&m["omega"]));
            if m["kind"] == kind && !out.contains(&s) {
                out.push(s);
            }
        }
        out
    };
    let base = gearshock(&modes_line(""));
    let printed = gearshock(&modes_line(" --set ring_support_radius_mm=15.79"));
    let bands_line = "gearshock instability --omega-from 0.1 --omega-to 2 --points 381";
    let bands = gearshock(bands_line);
    let response = gearshock(&fill(FIG2, &[("$reading", "all"), ("$te", "30")]));
    let rows = vec![
        format!(
            "| peaks of the response with no backlash, TE 30 µm on every mesh | {} |",
            peaks(response["branch"].as_array().unwrap()).join(", ")
        ),
        format!(
            "| parametric instability, every tooth pair engaged | {} |",
            ranges_to(bands["points"].as_array().unwrap(), 3, |p| p["unstable"]
                == true)
        ),
        format!(
            "| rotational modes (every planet alike) | {} |",
            natural(&base, "rotational").join(", ")
        ),
        format!(
            "| planet modes (suns, carrier and ring still; double) | {} |",
            natural(&base, "planet").join(", ")
        ),
        format!(
            "| rotational modes, ring support at 15.79 mm | {} |",
            natural(&printed, "rotational").join(", ")
        ),
    ];
    assert_rows(
        &rows,
        &[
            modes_line(""),
            modes_line(" --set ring_support_radius_mm=15.79"),
            bands_line.to_string(),
        ],
    );
}

/// Fig. 2: the largest half peak-to-peak of delta_s1a1 on the branch in
/// each window of Omega, with no backlash, for TE 5 and 30 um.
#[test]
fn te_and_the_resonances_fig2() {
    const WINDOWS: [(f64, f64); 6] = [
        (0.1, 0.14),
        (0.2, 0.26),
        (0.54, 0.61),
        (0.98, 1.02),
        (1.15, 1.3),
        (1.5, 1.6),
    ];
    let mut rows = Vec::new();
    let mut commands = Vec::new();
    for reading in ["all", "s1a"] {
        for te in [5, 30] {
            let line = fill(FIG2, &[("$reading", reading), ("$te", &te.to_string())]);
            show(&mut commands, FIG2);
            let v = gearshock(&line);
            assert_eq!(v["complete"], true, "{line}");
            let branch = v["branch"].as_array().unwrap();
            let cells: Vec<String> = WINDOWS
                .iter()
                .map(|&(lo, hi)| {
                    let best = branch
                        .iter()
                        .filter(|p| (lo..=hi).contains(&f(&p["omega"])))
                        .map(|p| f(&p["delta_amplitude_m"]))
                        .fold(f64::NAN, f64::max);
                    um(best)
                })
                .collect();
            rows.push(format!(
                "| TE {te} µm, {} | {} |",
                if reading == "all" {
                    "every mesh"
                } else {
                    "small-sun meshes"
                },
                cells.join(" | ")
            ));
        }
    }
    assert_rows(&rows, &commands);
}

/// Fig. 3: time integration at the paper's three resonances, TE 60 um,
/// backlash 50..200 um; and where the harmonic-balance branch is unstable.
#[test]
fn backlash_and_the_higher_peaks_fig3() {
    let mut rows = Vec::new();
    let mut commands = Vec::new();
    for b in [50, 100, 150, 200] {
        let mut cells = Vec::new();
        for omega in ["0.4", "1.2", "1.4"] {
            const T: &str = "gearshock simulate --set backlash_um=$b --set te_um=60 --mesh s1a1 --omega $w --transient-periods 3000";
            let v = gearshock(&fill(T, &[("$b", &b.to_string()), ("$w", omega)]));
            show(&mut commands, T);
            let amp = 0.5 * (f(&v["delta_max_m"]) - f(&v["delta_min_m"]));
            let period = match v["period"].as_u64() {
                Some(n) => format!("period {n}"),
                None => "not periodic".into(),
            };
            cells.push(format!(
                "{} ({}, {period})",
                um(amp),
                v["impact"].as_str().unwrap()
            ));
        }
        rows.push(format!("| {b} µm | {} |", cells.join(" | ")));
    }
    let line = "gearshock frf --set backlash_um=50 --set te_um=60 --mesh s1a1 --omega-from 0.1 --omega-to 2".to_string();
    let v = gearshock(&line);
    let branch = v["branch"].as_array().unwrap();
    let middle: Vec<&Value> = branch
        .iter()
        .filter(|p| (0.5..=1.7).contains(&f(&p["omega"])))
        .collect();
    let unstable = middle.iter().filter(|p| p["stable"] == false).count();
    rows.push(format!(
        "{unstable} of its {} points between Ω 0.5 and 1.7 are unstable",
        middle.len()
    ));
    commands.push(line);
    assert_rows(&rows, &commands);
}

/// Fig. 4's and Fig. 8's sweeps: `$b` and `$te` filled in.
const BIFURCATION: &str = "gearshock bifurcation --set backlash_um=$b --set te_um=$te --mesh s1a1 --omega-from 0.15 --omega-to 2 --points 38 --direction up --transient-periods 3000";

fn bifurcation(backlash: u32, te: u32) -> Vec<Value> {
    let line = fill(
        BIFURCATION,
        &[("$b", &backlash.to_string()), ("$te", &te.to_string())],
    );
    gearshock(&line)["points"].as_array().unwrap().clone()
}

fn half_pp(p: &Value) -> f64 {
    0.5 * (f(&p["delta_max_m"]) - f(&p["delta_min_m"]))
}

fn at(points: &[Value], omega: f64) -> &Value {
    points
        .iter()
        .find(|p| (f(&p["omega"]) - omega).abs() < 1e-6)
        .unwrap_or_else(|| panic!("no point at {omega}"))
}

/// Fig. 4: TE 0 / 20 / 30 um at 200 um backlash: amplitudes, the first
/// Omega without a period-1 response, the lowest deflection and where the
/// two impact criteria hold.
#[test]
fn te_and_the_bifurcation_diagram_fig4() {
    let mut rows = Vec::new();
    let mut commands = Vec::new();
    let (mut low, mut highs) = (Vec::new(), Vec::new());
    for te in [0, 20, 30] {
        let pts = bifurcation(200, te);
        low.push(um(half_pp(at(&pts, 0.25))));
        let high = pts
            .iter()
            .filter(|p| f(&p["omega"]) >= 1.2 - 1e-9)
            .map(half_pp)
            .fold(f64::NAN, f64::max);
        highs.push(um(high));
        let first_not_p1 = pts
            .iter()
            .find(|p| p["period"] != 1)
            .map_or("none".into(), |p| format!("{:.2}", f(&p["omega"])));
        let lowest = pts
            .iter()
            .map(|p| f(&p["delta_min_m"]))
            .fold(f64::NAN, f64::min);
        rows.push(format!(
            "| {te} µm | {} | {} | {} | {} | {first_not_p1} | {} | {} | {} | {} |",
            um(half_pp(at(&pts, 0.15))),
            um(half_pp(at(&pts, 0.25))),
            um(half_pp(at(&pts, 0.4))),
            um(high),
            um(lowest),
            ranges(&pts, |p| p["impact"] != "none"),
            ranges(&pts, |p| f(&p["delta_min_m"]) < 0.0),
            ranges(&pts, |p| p["impact"] == "double-sided"),
        ));
    }
    // The verdicts at a glance quote the same numbers.
    rows.push(format!("reproduced in size ({} to {})", low[0], low[2]));
    rows.push(format!(
        "the amplitude there grows {} → {} µm",
        highs[0], highs[2]
    ));
    show(&mut commands, BIFURCATION);
    assert_rows(&rows, &commands);
}

/// Fig. 8: backlash 50 / 100 / 200 um at TE 20 um: where the two impact
/// criteria hold, the first Omega without a period-1 response, and the
/// first Omega with a positive Lyapunov exponent (chaos).
#[test]
fn backlash_and_the_onset_of_chaos_fig8() {
    let mut onsets: Vec<f64> = Vec::new();
    let mut rows = Vec::new();
    let mut commands = Vec::new();
    for b in [50, 100, 200] {
        let pts = bifurcation(b, 20);
        show(&mut commands, BIFURCATION);
        let first_not_p1 = pts
            .iter()
            .find(|p| p["period"] != 1)
            .map_or("none".into(), |p| format!("{:.2}", f(&p["omega"])));
        const T: &str = "gearshock lyapunov --set backlash_um=$b --set te_um=20 --omega-from 0.3 --omega-to 1 --points 15";
        let l = gearshock(&fill(T, &[("$b", &b.to_string())]));
        show(&mut commands, T);
        let lp = l["points"].as_array().unwrap();
        let chaos = ranges(lp, |p| f(&p["exponent_per_period"]) > 0.01);
        if let Some(p) = lp.iter().find(|p| f(&p["exponent_per_period"]) > 0.01) {
            onsets.push(f(&p["omega"]));
        }
        let largest = lp
            .iter()
            .map(|p| f(&p["exponent_per_period"]))
            .fold(f64::NAN, f64::max);
        rows.push(format!(
            "| {b} µm | {} | {} | {first_not_p1} | {chaos} | {largest:.2} |",
            ranges(&pts, |p| f(&p["delta_min_m"]) < 0.0),
            ranges(&pts, |p| p["impact"] == "double-sided"),
        ));
    }
    // Quoted in the verdicts at a glance and in claim 10.
    let first = onsets.iter().copied().fold(f64::INFINITY, f64::min);
    let last = onsets.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    // One value when every backlash gives the same onset, else the range.
    let onset = if format!("{first:.2}") == format!("{last:.2}") {
        format!("{first:.2}")
    } else {
        format!("{first:.2}–{last:.2}")
    };
    rows.push(format!("chaos starts at Ω {onset} for every backlash"));
    rows.push(format!("the motion is chaotic from Ω {onset}"));
    assert_rows(&rows, &commands);
}

/// Figs. 5-7 and 9-11: the orbit at one Omega for each family member.
#[test]
fn the_orbits_figs5_to_11() {
    let mut rows = Vec::new();
    let mut commands = Vec::new();
    const TE: &str = "gearshock simulate --set backlash_um=200 --set te_um=$x --mesh s1a1 --omega $w --transient-periods 3000";
    const B: &str = "gearshock simulate --set te_um=20 --set backlash_um=$x --mesh s1a1 --omega $w --transient-periods 3000";
    let figs = [
        ("5", "0.5", [0, 20, 30], TE),
        ("6", "0.84", [0, 20, 30], TE),
        ("7", "1.97", [0, 20, 30], TE),
        ("9", "0.5", [50, 100, 200], B),
        ("10", "0.84", [50, 100, 200], B),
        ("11", "1.97", [50, 100, 200], B),
    ];
    for (fig, omega, values, template) in figs {
        let mut cells = Vec::new();
        for x in values {
            let v = gearshock(&fill(template, &[("$x", &x.to_string()), ("$w", omega)]));
            show(&mut commands, template);
            let period = match v["period"].as_u64() {
                Some(n) => format!("period {n}"),
                None => "not periodic".into(),
            };
            let amp = 0.5 * (f(&v["delta_max_m"]) - f(&v["delta_min_m"]));
            let vel = v["poincare"]["velocity_m_s"]
                .as_array()
                .unwrap()
                .iter()
                .map(|s| f(s).abs())
                .fold(0.0, f64::max);
            // Other meshes whose back flanks touch (the backlash matters there).
            let back: Vec<&str> = v["all_meshes"]
                .as_object()
                .unwrap()
                .iter()
                .filter(|(name, m)| *name != "s1a1" && m["impact"] == "double-sided")
                .map(|(name, _)| name.as_str())
                .collect();
            let elsewhere = if back.is_empty() {
                String::new()
            } else {
                format!("; back flanks touch on {}", back.join(", "))
            };
            cells.push(format!(
                "{period}, {}, {} µm, {:.2} m/s{elsewhere}",
                v["impact"].as_str().unwrap(),
                um(amp),
                vel
            ));
        }
        rows.push(format!("| Fig. {fig}, Ω {omega} | {} |", cells.join(" | ")));
    }
    assert_rows(&rows, &commands);
}

/// The paper's authors, and no wrong attribution anywhere a reader looks.
#[test]
fn the_paper_is_attributed_to_its_authors() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let doc = doc();
    assert!(doc.contains("Shen, Liu, Yang and Zhang"));
    for file in ["README.md", "ARCHITECTURE.md", "docs/paper.md"] {
        let text = std::fs::read_to_string(format!("{root}/{file}")).expect(file);
        assert!(!text.contains("Hou et al"), "{file}");
    }
    let readme = std::fs::read_to_string(format!("{root}/README.md")).expect("README");
    assert!(readme.contains("Shen, Liu, Yang and"));
}
