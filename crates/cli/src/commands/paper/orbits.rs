//! Figs. 5-7 and 9-11: the orbit of mesh s1a1 at one Omega for each TE or
//! backlash of a figure (claims 6, 7a and 7b), at the paper's Omega and
//! at the matched one.

use super::data::{f, motion, um};
use super::runs::Runs;
use super::scale::Scale;
use crate::failure::Failure;
use serde::{Deserialize, Serialize};
use serde_json::Value;

/// Figs. 5-7: the TE `$x` grows at 200 µm backlash.
pub const TE: &str =
    "gearshock simulate --set backlash_um=200 --set te_um=$x --mesh s1a1 --omega $w";
/// Figs. 9-11: the backlash `$x` grows at 20 µm TE.
pub const BACKLASH: &str =
    "gearshock simulate --set te_um=20 --set backlash_um=$x --mesh s1a1 --omega $w";
/// The TEs of Figs. 5-7 (µm).
pub const TES: [u32; 3] = [0, 20, 30];
/// The backlashes of Figs. 8-11 (µm).
pub const BACKLASHES: [u32; 3] = [50, 100, 200];
/// The figures: (number, the paper's Omega, whether the backlash varies).
pub const FIGURES: [(u32, f64, bool); 6] = [
    (5, 0.5, false),
    (6, 0.84, false),
    (7, 1.97, false),
    (9, 0.5, true),
    (10, 0.84, true),
    (11, 1.97, true),
];

/// A steady state of `gearshock simulate`, as the document quotes it.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Orbit {
    /// Omega.
    pub omega: f64,
    /// The motion in words ("period 2", "chaotic", ...).
    pub motion: String,
    /// The impact regime of s1a1.
    pub impact: String,
    /// Half the peak-to-peak of x_s1a1 (µm).
    pub amplitude_um: f64,
    /// The largest penetration velocity (rate of x) in the Poincaré section (m/s).
    pub velocity_m_s: f64,
    /// The meshes whose back flanks touch.
    pub back_flanks: Vec<String>,
    /// Half the peak-to-peak of x_rb1 (µm).
    pub rb1_amplitude_um: f64,
    /// The lowest x_s1a1 (µm).
    pub x_min_um: f64,
}

impl Orbit {
    /// Reads a `simulate` output.
    pub fn of(v: &Value) -> Orbit {
        let velocity_m_s = v["poincare"]["x_velocity_m_s"]
            .as_array()
            .map_or(f64::NAN, |xs| {
                xs.iter().map(|s| f(s).abs()).fold(0.0, f64::max)
            });
        let back_flanks = v["all_meshes"]
            .as_object()
            .map(|ms| {
                ms.iter()
                    .filter(|(_, m)| m["impact"] == "double-sided")
                    .map(|(name, _)| name.clone())
                    .collect()
            })
            .unwrap_or_default();
        Orbit {
            omega: f(&v["omega"]),
            motion: motion(v),
            impact: v["impact"].as_str().unwrap_or_default().to_string(),
            amplitude_um: um(&v["x_amplitude_m"]),
            velocity_m_s,
            back_flanks,
            rb1_amplitude_um: um(&v["all_meshes"]["rb1"]["x_amplitude_m"]),
            x_min_um: um(&v["x_min_m"]),
        }
    }
}

/// One figure at one Omega.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Row {
    /// The figure's number.
    pub figure: u32,
    /// The paper's Omega.
    pub paper_omega: f64,
    /// Whether Omega is the matched one.
    pub matched: bool,
    /// The TE or backlash of each panel (µm).
    pub values: Vec<u32>,
    /// The orbit of each.
    pub orbits: Vec<Orbit>,
}

/// A figure's command with its value and Omega filled in; `extra` (a
/// reading's `--set`s) before `--mesh`.
pub fn line(template: &str, x: u32, w: f64, extra: &str) -> String {
    template
        .replace("$x", &x.to_string())
        .replace("$w", &super::words::omega_arg(w))
        .replace(" --mesh", &format!("{extra} --mesh"))
}

/// The line the input speed per unit of Omega is read from (Fig. 5's first).
pub fn rpm_line() -> String {
    line(TE, TES[0], FIGURES[0].1, "")
}

/// The rows: each figure literally, then matched; `te_values` and
/// `backlashes` are the panels' values.
fn plan(te_values: &[u32], backlashes: &[u32]) -> Vec<(Row, &'static str)> {
    let mut out = Vec::new();
    for (figure, w, varies_backlash) in FIGURES {
        for matched in [false, true] {
            let (template, values) = if varies_backlash {
                (BACKLASH, backlashes)
            } else {
                (TE, te_values)
            };
            out.push((
                Row {
                    figure,
                    paper_omega: w,
                    matched,
                    values: values.to_vec(),
                    orbits: Vec::new(),
                },
                template,
            ));
        }
    }
    out
}

fn omega_of(scale: &Scale, row: &Row) -> f64 {
    if row.matched {
        scale.matched(row.paper_omega)
    } else {
        row.paper_omega
    }
}

/// The command lines of every row under a reading (`extra`: its `--set`s;
/// `full_gap`: the backlash halved).
pub fn lines(scale: &Scale, extra: &str, backlashes: &[u32], te_backlash: u32) -> Vec<String> {
    let mut out = Vec::new();
    for (row, template) in plan(&TES, backlashes) {
        for &x in &row.values {
            out.push(line_for(
                template,
                x,
                omega_of(scale, &row),
                extra,
                te_backlash,
            ));
        }
    }
    out
}

/// The line of one panel: Figs. 5-7 at `te_backlash` (200 µm unless a
/// reading halves it).
fn line_for(template: &str, x: u32, w: f64, extra: &str, te_backlash: u32) -> String {
    let l = line(template, x, w, extra);
    if template == TE {
        l.replace("backlash_um=200", &format!("backlash_um={te_backlash}"))
    } else {
        l
    }
}

/// Reads every figure's orbits off the runs, under a reading.
pub fn compute(
    runs: &Runs,
    scale: &Scale,
    extra: &str,
    backlashes: &[u32],
    te_backlash: u32,
) -> Result<Vec<Row>, Failure> {
    let mut out = Vec::new();
    for (mut row, template) in plan(&TES, backlashes) {
        let w = omega_of(scale, &row);
        for &x in &row.values {
            let v = runs.get(&line_for(template, x, w, extra, te_backlash))?;
            row.orbits.push(Orbit::of(&v));
        }
        out.push(row);
    }
    Ok(out)
}
