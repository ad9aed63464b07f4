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

/// The tooth deflection x = delta - e (TE included): half its peak-to-peak.
fn x_amp(p: &Value) -> f64 {
    f(&p["x_amplitude_m"])
}

/// The largest of `value` over the points with Omega in `lo..=hi`.
fn largest(points: &[Value], lo: f64, hi: f64, value: impl Fn(&Value) -> f64) -> f64 {
    points
        .iter()
        .filter(|p| (lo - 1e-9..=hi + 1e-9).contains(&f(&p["omega"])))
        .map(value)
        .fold(f64::NAN, f64::max)
}

/// The motion of a run in the document's words: "period n" or, for a
/// motion that is not periodic, what its Lyapunov exponent says.
fn motion(v: &Value) -> String {
    if let Some(n) = v["period"].as_u64() {
        return format!("period {n}");
    }
    let verdict = v["verdict"].as_str().unwrap_or_default();
    if verdict.contains("Lyapunov") {
        verdict.rsplit(": ").next().unwrap_or(verdict).to_string()
    } else {
        "not periodic".into()
    }
}

/// The meshes of a run whose flanks meet `impact`, "none" if none.
fn meshes_with(v: &Value, impact: &str) -> Vec<String> {
    v["all_meshes"]
        .as_object()
        .unwrap()
        .iter()
        .filter(|(_, m)| m["impact"] == impact)
        .map(|(name, _)| name.clone())
        .collect()
}

/// The first mode's Omega (the lowest rotational mode).
fn first_mode() -> f64 {
    gearshock("gearshock modes")["modes"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|m| m["kind"] == "rotational")
        .map(|m| f(&m["omega"]))
        .fold(f64::INFINITY, f64::min)
}

/// The paper's Omega matched on the first mode: its 0.4 is gearshock's
/// first natural frequency.
fn matched(paper: f64) -> String {
    format!("{:.3}", paper * first_mode() / 0.4)
}

/// Fig. 2's frequency responses: `$reading` and `$te` filled in.
const FIG2: &str = "gearshock frf --set backlash_um=0 --set te_meshes=$reading --set te_um=$te --mesh all --omega-from 0.1 --omega-to 2";
/// Fig. 2 with `Ec_all` read as a cosine on every mesh.
const FIG2_COS: &str = "gearshock frf --set backlash_um=0 --set te_um=0 --set te_cos_s1a_um=$te --set te_cos_s2b_um=$te --set te_cos_ab_um=$te --set te_cos_rb_um=$te --mesh all --omega-from 0.1 --omega-to 2";
/// The paper's own method: one harmonic, the describing function.
const ONE_HARMONIC: &str = " --method describing-function --harmonics 1";

/// One mesh's branch out of a `--mesh all` frequency response.
fn branch_of(v: &Value, mesh: &str) -> Vec<Value> {
    v["branch"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            let mut m = p["meshes"][mesh].clone();
            m["omega"] = p["omega"].clone();
            m
        })
        .collect()
}

/// Peaks of a branch's amplitude of x: local maxima at least 20 % above
/// the lowest amplitude within 0.05 in Omega on either side, one per 0.02.
fn peaks(branch: &[Value]) -> Vec<String> {
    let w: Vec<f64> = branch.iter().map(|p| f(&p["omega"])).collect();
    let a: Vec<f64> = branch.iter().map(x_amp).collect();
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
    let paper = ["0.4", "0.5", "0.8", "0.84", "1.2", "1.4", "1.97"];
    let rows = vec![
        format!(
            "| peaks of x with no backlash, TE 30 µm on every mesh | {} |",
            peaks(&branch_of(&response, "s1a1")).join(", ")
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
        format!("factor {:.2}", first_mode() / 0.4),
        format!(
            "| the paper's Ω | {} |\n| matched on the first mode | {} |",
            paper.join(" | "),
            paper
                .iter()
                .map(|w| matched(w.parse().unwrap()))
                .collect::<Vec<_>>()
                .join(" | ")
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

/// Fig. 2: the largest half peak-to-peak of x on the branch in each window
/// of Omega, with no backlash, for TE 5 and 30 um, under each reading of
/// `Ec_all` and with one or several harmonics; and panels b-d.
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
    let readings = [
        ("sine, every mesh", FIG2, "all"),
        ("sine, small-sun meshes", FIG2, "s1a"),
        ("cosine, every mesh", FIG2_COS, ""),
    ];
    for (label, template, reading) in readings {
        for harmonics in ["", ONE_HARMONIC] {
            for te in [5, 30] {
                let template = format!("{template}{harmonics}");
                let line = fill(
                    &template,
                    &[("$reading", reading), ("$te", &te.to_string())],
                );
                show(&mut commands, &template);
                let v = gearshock(&line);
                assert_eq!(v["complete"], true, "{line}");
                let branch = branch_of(&v, "s1a1");
                let cells: Vec<String> = WINDOWS
                    .iter()
                    .map(|&(lo, hi)| um(largest(&branch, lo, hi, x_amp)))
                    .collect();
                let method = if harmonics.is_empty() {
                    "7 harmonics"
                } else {
                    "one harmonic"
                };
                rows.push(format!(
                    "| TE {te} µm, {label}, {method} | {} |",
                    cells.join(" | ")
                ));
            }
        }
    }
    // Panels b-d: the other kinds of mesh, sine on every mesh.
    for mesh in ["s1a1", "s2b1", "a1b1", "rb1"] {
        let mut cells = Vec::new();
        for (lo, hi) in [(0.2, 0.26), (0.54, 0.61), (0.98, 1.02)] {
            for te in ["5", "30"] {
                let v = gearshock(&fill(FIG2, &[("$reading", "all"), ("$te", te)]));
                cells.push(um(largest(&branch_of(&v, mesh), lo, hi, x_amp)));
            }
        }
        rows.push(format!("| x_{mesh} | {} |", cells.join(" | ")));
    }
    assert_rows(&rows, &commands);
}

/// Fig. 3's time integrations: `$b`, `$w` filled in; and the mean reading.
const FIG3: &str = "gearshock simulate --set backlash_um=$b --set te_um=60 --mesh s1a1 --omega $w";
const FIG3_MEAN: &str =
    "gearshock simulate --set backlash_um=$b --set te_um=0 --set te_mean_s1a_um=60 --mesh s1a1 --omega $w";
const FIG3_FRF: &str =
    "gearshock frf --set backlash_um=$b --set te_um=60 --mesh s1a1 --omega-from 0.1 --omega-to 2";

/// Fig. 3: time integration at the paper's three resonances, read
/// literally and matched on the first mode, TE 60 um, backlash 50..200
/// um, on s1a1 and rb1; the mean-TE reading; the one-harmonic branch; and
/// where the multi-harmonic branch is unstable.
#[test]
fn backlash_and_the_higher_peaks_fig3() {
    let mut rows = Vec::new();
    let mut commands = Vec::new();
    let mut omegas: Vec<String> = ["0.4", "1.2", "1.4"].map(String::from).to_vec();
    omegas.extend([0.4, 1.2, 1.4].map(matched));
    rows.push(format!("| backlash | Ω {} |", omegas.join(" | Ω ")));
    let mut rb = Vec::new();
    for b in [50, 100, 150, 200] {
        let mut cells = Vec::new();
        let mut rb_cells = Vec::new();
        for w in &omegas {
            let v = gearshock(&fill(FIG3, &[("$b", &b.to_string()), ("$w", w)]));
            show(&mut commands, FIG3);
            cells.push(format!(
                "{} ({}, {})",
                um(x_amp(&v)),
                v["impact"].as_str().unwrap(),
                motion(&v)
            ));
            rb_cells.push(um(x_amp(&v["all_meshes"]["rb1"])));
        }
        rows.push(format!("| {b} µm | {} |", cells.join(" | ")));
        rb.push(format!("| {b} µm | {} |", rb_cells.join(" | ")));
    }
    rows.extend(rb);
    // The mean reading: a constant TE, whatever the backlash.
    for b in [50, 200] {
        let cells: Vec<String> = omegas
            .iter()
            .map(|w| {
                let v = gearshock(&fill(FIG3_MEAN, &[("$b", &b.to_string()), ("$w", w)]));
                um(x_amp(&v))
            })
            .collect();
        show(&mut commands, FIG3_MEAN);
        rows.push(format!("| {b} µm, mean TE | {} |", cells.join(" | ")));
    }
    // The paper's own method, one harmonic.
    let windows: Vec<(f64, f64)> = omegas
        .iter()
        .map(|w| {
            let w: f64 = w.parse().unwrap();
            (w - 0.05, w + 0.05)
        })
        .collect();
    for b in [50, 100, 150, 200] {
        let template = format!("{FIG3_FRF}{ONE_HARMONIC}");
        let v = gearshock(&fill(&template, &[("$b", &b.to_string())]));
        show(&mut commands, &template);
        assert_eq!(v["complete"], true, "{template} {b}");
        let branch = v["branch"].as_array().unwrap();
        let cells: Vec<String> = windows
            .iter()
            .map(|&(lo, hi)| um(largest(branch, lo, hi, x_amp)))
            .collect();
        rows.push(format!("| {b} µm, one harmonic | {} |", cells.join(" | ")));
    }
    let line = fill(FIG3_FRF, &[("$b", "50")]);
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
    show(&mut commands, FIG3_FRF);
    assert_rows(&rows, &commands);
}

/// Fig. 4's and Fig. 8's sweeps: `$b` and `$te` filled in.
const BIFURCATION: &str = "gearshock bifurcation --set backlash_um=$b --set te_um=$te --mesh s1a1 --omega-from 0.15 --omega-to 2 --points 38 --direction up";
/// The finer sweeps, refined near the first three natural frequencies and
/// the first mode's superharmonic.
const FINE: &str = "gearshock bifurcation --set backlash_um=$b --set te_um=$te --mesh s1a1 --omega-from $from --omega-to $to --points $n --direction up";
const FINE_GRIDS: [(&str, &str, &str); 4] = [
    ("0.1", "0.8", "71"),
    ("0.105", "0.125", "21"),
    ("0.22", "0.245", "26"),
    ("0.565", "0.585", "21"),
];

fn bifurcation(backlash: u32, te: u32) -> Vec<Value> {
    let line = fill(
        BIFURCATION,
        &[("$b", &backlash.to_string()), ("$te", &te.to_string())],
    );
    gearshock(&line)["points"].as_array().unwrap().clone()
}

/// Every point of the finer sweeps, in order of Omega.
fn fine(backlash: u32, te: u32) -> Vec<Value> {
    let mut pts: Vec<Value> = FINE_GRIDS
        .iter()
        .flat_map(|(from, to, n)| {
            let line = fill(
                FINE,
                &[
                    ("$b", &backlash.to_string()),
                    ("$te", &te.to_string()),
                    ("$from", from),
                    ("$to", to),
                    ("$n", n),
                ],
            );
            gearshock(&line)["points"].as_array().unwrap().clone()
        })
        .collect();
    pts.sort_by(|a, b| f(&a["omega"]).total_cmp(&f(&b["omega"])));
    pts
}

fn at(points: &[Value], omega: f64) -> &Value {
    points
        .iter()
        .find(|p| (f(&p["omega"]) - omega).abs() < 1e-6)
        .unwrap_or_else(|| panic!("no point at {omega}"))
}

fn first(points: &[Value], pred: impl Fn(&Value) -> bool) -> String {
    points
        .iter()
        .find(|p| pred(p))
        .map_or("none".into(), |p| format!("{:.2}", f(&p["omega"])))
}

/// Fig. 4: TE 0 / 20 / 30 um at 200 um backlash: amplitudes of x, the
/// motion and where each impact criterion holds.
#[test]
fn te_and_the_bifurcation_diagram_fig4() {
    let mut rows = Vec::new();
    let mut commands = Vec::new();
    let mut low = Vec::new();
    let mut literal = Vec::new();
    let mut high = Vec::new();
    for te in [0, 20, 30] {
        let pts = bifurcation(200, te);
        let fine_pts = fine(200, te);
        let p25 = at(&pts, 0.25);
        low.push(um(x_amp(p25)));
        literal.push(um(x_amp(at(&pts, 0.4))));
        high.push(um(largest(&pts, 1.2, 2.0, x_amp)));
        rows.push(format!(
            "| {te} µm | {} | {} | {} | {} | {} | {} | {} |",
            um(x_amp(at(&pts, 0.15))),
            um(x_amp(p25)),
            um(x_amp(at(&pts, 0.4))),
            um(largest(&fine_pts, 0.22, 0.245, x_amp)),
            um(largest(&pts, 1.2, 2.0, x_amp)),
            um(largest(&pts, 0.7, 1.15, x_amp)),
            um(0.5 * (f(&p25["delta_max_m"]) - f(&p25["delta_min_m"]))),
        ));
        let lowest = pts
            .iter()
            .map(|p| f(&p["x_min_m"]))
            .fold(f64::NAN, f64::min);
        rows.push(format!(
            "| {te} µm | {} | {} | {} | {} | {} | {} | {} |",
            first(&pts, |p| p["period"] != 1),
            ranges(&pts, |p| p["period"].is_null()),
            um(lowest),
            ranges(&pts, |p| p["impact"] != "none"),
            ranges(&pts, |p| p["impact_worst"] != "none"),
            ranges(&pts, |p| f(&p["x_min_m"]) < 0.0),
            ranges(&pts, |p| p["impact_worst"] == "double-sided"),
        ));
    }
    // The verdicts at a glance quote the same numbers.
    rows.push(format!(
        "x grows {} → {} → {} µm at Ω 0.25",
        low[0], low[1], low[2]
    ));
    rows.push(format!(
        "{} → {} → {} µm at the literal 0.4",
        literal[0], literal[1], literal[2]
    ));
    rows.push(format!(
        "the amplitude there grows {} → {} µm",
        high[0], high[2]
    ));
    show(&mut commands, BIFURCATION);
    show(&mut commands, FINE);
    assert_rows(&rows, &commands);
}

/// Fig. 8: backlash 50 / 100 / 200 um at TE 20 um: where the impact
/// criteria hold, the first Omega without a period-1 response, and the
/// Omega with a positive Lyapunov exponent (chaos).
#[test]
fn backlash_and_the_onset_of_chaos_fig8() {
    let mut onsets: Vec<f64> = Vec::new();
    let mut negative = Vec::new();
    let mut rows = Vec::new();
    let mut commands = Vec::new();
    for b in [50, 100, 200] {
        let pts = bifurcation(b, 20);
        show(&mut commands, BIFURCATION);
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
        negative.push(first(&pts, |p| f(&p["x_min_m"]) < 0.0));
        let fine_pts = fine(b, 20);
        show(&mut commands, FINE);
        rows.push(format!(
            "| {b} µm | {} | {} | {} | {} | {} | {chaos} | {largest:.2} |",
            ranges(&pts, |p| f(&p["x_min_m"]) < 0.0),
            ranges(&pts, |p| p["impact"] == "double-sided"),
            ranges(&pts, |p| p["impact_worst"] == "double-sided"),
            first(&pts, |p| p["period"] != 1),
            fine_pts
                .iter()
                .find(|p| p["period"] != 1)
                .map_or("none".into(), |p| format!("{:.3}", f(&p["omega"]))),
        ));
    }
    // Quoted in the verdicts at a glance and in claims 8 and 10.
    let first = onsets.iter().copied().fold(f64::INFINITY, f64::min);
    let last = onsets.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    // One value when every backlash gives the same onset, else the range.
    let onset = if format!("{first:.2}") == format!("{last:.2}") {
        format!("{first:.2}")
    } else {
        format!("{first:.2}–{last:.2}")
    };
    rows.push(format!("chaos starts at Ω {onset} for every backlash"));
    rows.push(format!(
        "a negative tooth deflection x, TE included, first appears at Ω {}, {} and {}",
        negative[0], negative[1], negative[2]
    ));
    assert_rows(&rows, &commands);
}

/// Claim 10: where the drive flanks of any of the twelve meshes first
/// part, on grids refined near the natural frequencies.
#[test]
fn no_safe_speed_on_any_mesh_claim10() {
    let mut rows = Vec::new();
    let mut firsts: Vec<f64> = Vec::new();
    for (b, te) in [(200, 0), (200, 20), (200, 30), (50, 20), (100, 20)] {
        let pts = fine(b, te);
        let hit = pts.iter().find(|p| p["impact_worst"] != "none");
        if let Some(p) = hit {
            firsts.push(f(&p["omega"]));
        }
        rows.push(format!(
            "| {b} µm | {te} µm | {} | {} | {} | {} |",
            hit.map_or("none".into(), |p| format!(
                "{:.3} ({})",
                f(&p["omega"]),
                p["worst_mesh"].as_str().unwrap()
            )),
            pts.iter()
                .find(|p| p["impact"] != "none")
                .map_or("none".into(), |p| format!("{:.3}", f(&p["omega"]))),
            pts.iter()
                .find(|p| p["impact_worst"] == "double-sided")
                .map_or("none".into(), |p| format!(
                    "{:.3} ({})",
                    f(&p["omega"]),
                    p["worst_mesh"].as_str().unwrap()
                )),
            pts.len()
        ));
    }
    let lo = firsts.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = firsts.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let from = if format!("{lo:.3}") == format!("{hi:.3}") {
        format!("{lo:.3}")
    } else {
        format!("{lo:.3}–{hi:.3}")
    };
    rows.push(format!("some mesh's drive flanks part from Ω {from} up"));
    let mut commands = Vec::new();
    show(&mut commands, FINE);
    assert_rows(&rows, &commands);
}

/// Figs. 5-7 and 9-11: the orbit at one Omega for each family member.
#[test]
fn the_orbits_figs5_to_11() {
    let mut rows = Vec::new();
    let mut commands = Vec::new();
    const TE: &str =
        "gearshock simulate --set backlash_um=200 --set te_um=$x --mesh s1a1 --omega $w";
    const B: &str = "gearshock simulate --set te_um=20 --set backlash_um=$x --mesh s1a1 --omega $w";
    let figs = [
        ("5", "0.5", [0, 20, 30], TE),
        ("6", "0.84", [0, 20, 30], TE),
        ("7", "1.97", [0, 20, 30], TE),
        ("9", "0.5", [50, 100, 200], B),
        ("10", "0.84", [50, 100, 200], B),
        ("11", "1.97", [50, 100, 200], B),
    ];
    // Each figure at the paper's Omega read literally, then matched on the
    // first mode.
    let figs = figs.into_iter().flat_map(|(fig, omega, values, template)| {
        let m = matched(omega.parse().unwrap());
        [
            (fig, omega.to_string(), values, template),
            (fig, m, values, template),
        ]
    });
    for (fig, omega, values, template) in figs {
        let omega = omega.as_str();
        let mut cells = Vec::new();
        for x in values {
            let v = gearshock(&fill(template, &[("$x", &x.to_string()), ("$w", omega)]));
            show(&mut commands, template);
            let vel = v["poincare"]["x_velocity_m_s"]
                .as_array()
                .unwrap()
                .iter()
                .map(|s| f(s).abs())
                .fold(0.0, f64::max);
            let back = meshes_with(&v, "double-sided");
            let elsewhere = if back.is_empty() {
                String::new()
            } else {
                format!("; back flanks touch on {}", back.join(", "))
            };
            cells.push(format!(
                "{}, {}, {} µm, {:.2} m/s{elsewhere}",
                motion(&v),
                v["impact"].as_str().unwrap(),
                um(x_amp(&v)),
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
