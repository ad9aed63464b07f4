//! Fig. 2: the frequency response without backlash as the TE grows, under
//! each reading of its `Ec_all` and with seven harmonics or one (claim 1),
//! and where its TE makes the teeth of some mesh part (conclusion 1).

use super::data::{branch_of, f, items, omega, spans, stable, x_amp, Spans};
use super::runs::Runs;
use super::scale::Scale;
use crate::failure::Failure;
use serde::{Deserialize, Serialize};
use serde_json::Value;

/// Fig. 2's frequency responses: `$reading` and `$te` filled in.
pub const SINE: &str = "gearshock frf --set backlash_um=0 --set te_meshes=$reading --set te_um=$te --mesh all --omega-from 0.1 --omega-to 2";
/// Fig. 2 with `Ec_all` read as a cosine on every mesh.
pub const COSINE: &str = "gearshock frf --set backlash_um=0 --set te_um=0 --set te_cos_s1a_um=$te --set te_cos_s2b_um=$te --set te_cos_ab_um=$te --set te_cos_rb_um=$te --mesh all --omega-from 0.1 --omega-to 2";
/// The paper's own method: one harmonic, the describing function.
pub const ONE_HARMONIC: &str = " --method describing-function --harmonics 1";
/// The TE amplitudes of Fig. 2 (µm).
pub const TES: [u32; 2] = [5, 30];
/// The readings of `Ec_all`: (words, template, `$reading`).
pub const READINGS: [(&str, &str, &str); 3] = [
    ("sine, every mesh", SINE, "all"),
    ("sine, small-sun meshes", SINE, "s1a"),
    ("cosine, every mesh", COSINE, ""),
];
/// The other panels' meshes (b-d).
pub const PANELS: [&str; 3] = ["s2b1", "a1b1", "rb1"];
/// The paper's resonances of Fig. 2 and 3: its first, second and a higher
/// natural frequency.
pub const PAPER_RESONANCES: [f64; 3] = [0.4, 1.2, 1.4];
/// Half the width of a window of Omega around an anchor.
pub const HALF_WINDOW: f64 = 0.025;

/// A harmonic-balance amplitude in a window, with its stability.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq)]
pub struct Hbm {
    /// The largest amplitude of x over the branch's stable points (µm).
    pub stable_um: Option<f64>,
    /// The largest over its unstable points, where larger than every
    /// stable one (µm).
    pub unstable_um: Option<f64>,
}

impl Hbm {
    /// The largest amplitudes of x on `branch` with Omega in `lo..=hi`.
    pub fn of(branch: &[Value], lo: f64, hi: f64) -> Hbm {
        let inside = || {
            branch
                .iter()
                .filter(move |p| super::data::within(omega(p), lo, hi))
        };
        let best = |want: bool| {
            inside()
                .filter(|p| stable(p) == want)
                .map(x_amp)
                .reduce(f64::max)
        };
        let stable_um = best(true);
        let unstable_um = best(false).filter(|u| stable_um.is_none_or(|s| *u > s));
        Hbm {
            stable_um,
            unstable_um,
        }
    }
}

/// The centre of a window of Omega and why it is one.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq)]
pub struct Anchor {
    /// gearshock's Omega.
    pub omega: f64,
    /// A peak of gearshock's response (x_s1a1, TE 30 µm on every mesh).
    pub peak: bool,
    /// The paper's resonance read literally here.
    pub paper: Option<f64>,
    /// The paper's resonance that the matched scale puts here.
    pub matched_from: Option<f64>,
}

/// One response of x_s1a1: a reading, a method and a TE.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Row {
    /// The reading of `Ec_all`, in words.
    pub reading: String,
    /// One harmonic (the paper's method) or seven.
    pub one_harmonic: bool,
    /// The TE (µm).
    pub te_um: u32,
    /// The largest amplitude in each anchor's window.
    pub cells: Vec<Hbm>,
    /// The peaks of the branch: (Omega, stable).
    pub peaks: Vec<(f64, bool)>,
    /// In each band of parametric instability: (unstable points, points).
    pub bands: Vec<(usize, usize)>,
}

/// Panels b-d: one mesh at one TE (sine on every mesh, 7 harmonics).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Panel {
    /// The mesh.
    pub mesh: String,
    /// The TE (µm).
    pub te_um: u32,
    /// The largest amplitude in each anchor's window.
    pub cells: Vec<Hbm>,
    /// The peaks of the branch: (Omega, stable).
    pub peaks: Vec<(f64, bool)>,
}

/// Where the TE makes the teeth of some mesh part: the branch's x falls
/// below 0 (where a mesh with backlash would leave its drive flanks), or
/// the branch is unstable (the motion grows until they do).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Contact {
    /// The reading of `Ec_all`, in words.
    pub reading: String,
    /// The TE (µm).
    pub te_um: u32,
    /// Where every mesh keeps its drive flanks in contact on a stable point.
    pub kept: Spans,
    /// The Omega range of the branch.
    pub range: (f64, f64),
}

/// Fig. 2's record.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Fig2 {
    /// The windows' centres.
    pub anchors: Vec<Anchor>,
    /// x_s1a1 under every reading, method and TE.
    pub rows: Vec<Row>,
    /// Panels b-d.
    pub panels: Vec<Panel>,
    /// Where the teeth keep contact (seven harmonics, sine readings).
    pub contact: Vec<Contact>,
}

/// A Fig. 2 command line.
pub fn line(template: &str, reading: &str, te: u32, one_harmonic: bool) -> String {
    let t = template
        .replace("$reading", reading)
        .replace("$te", &te.to_string());
    if one_harmonic {
        format!("{t}{ONE_HARMONIC}")
    } else {
        t
    }
}

/// Every command line of Fig. 2.
pub fn lines() -> Vec<String> {
    let mut out = Vec::new();
    for (_, template, reading) in READINGS {
        for one in [false, true] {
            for te in TES {
                out.push(line(template, reading, te, one));
            }
        }
    }
    out
}

/// Peaks of a branch's amplitude of x: local maxima at least 20 % above
/// the lowest amplitude within 0.05 in Omega on either side, one per 0.02.
pub fn peaks(branch: &[Value]) -> Vec<(f64, bool)> {
    let w: Vec<f64> = branch.iter().map(omega).collect();
    let a: Vec<f64> = branch.iter().map(x_amp).collect();
    let lowest = |lo: f64, hi: f64| {
        (0..a.len())
            .filter(|&j| (lo..=hi).contains(&w[j]))
            .map(|j| a[j])
            .fold(f64::INFINITY, f64::min)
    };
    let mut out: Vec<(f64, f64, bool)> = Vec::new();
    for i in 1..a.len().saturating_sub(1) {
        let prominent =
            a[i] >= 1.2 * lowest(w[i] - 0.05, w[i]) && a[i] >= 1.2 * lowest(w[i], w[i] + 0.05);
        if a[i] >= a[i - 1] && a[i] >= a[i + 1] && prominent {
            let here = (w[i], a[i], stable(&branch[i]));
            match out.last_mut() {
                Some(last) if w[i] - last.0 < 0.02 => {
                    if a[i] > last.1 {
                        *last = here;
                    }
                }
                _ => out.push(here),
            }
        }
    }
    out.iter()
        .map(|&(w, _, s)| ((w * 1000.0).round() / 1000.0, s))
        .collect()
}

/// The windows' centres: gearshock's peaks and the paper's resonances, on
/// both scales, one window for centres closer than 0.03.
fn anchors(peaks: &[(f64, bool)], scale: &Scale) -> Vec<Anchor> {
    let mut out: Vec<Anchor> = peaks
        .iter()
        .map(|&(omega, _)| Anchor {
            omega,
            peak: true,
            paper: None,
            matched_from: None,
        })
        .collect();
    for p in PAPER_RESONANCES {
        for (w, literal) in [(p, true), (scale.matched(p), false)] {
            let i = match out.iter().position(|a| (a.omega - w).abs() < 0.03) {
                Some(i) => i,
                None => {
                    out.push(Anchor {
                        omega: w,
                        peak: false,
                        paper: None,
                        matched_from: None,
                    });
                    out.len() - 1
                }
            };
            if literal {
                out[i].paper = Some(p);
            } else {
                out[i].matched_from = Some(p);
            }
        }
    }
    out.sort_by(|a, b| a.omega.total_cmp(&b.omega));
    out
}

fn cells(branch: &[Value], anchors: &[Anchor]) -> Vec<Hbm> {
    anchors
        .iter()
        .map(|a| Hbm::of(branch, a.omega - HALF_WINDOW, a.omega + HALF_WINDOW))
        .collect()
}

/// Reads Fig. 2 off the runs.
pub fn compute(runs: &Runs, scale: &Scale) -> Result<Fig2, Failure> {
    let reference = runs.get(&line(SINE, "all", 30, false))?;
    let anchors = anchors(&peaks(&branch_of(&reference, "s1a1")), scale);
    let mut rows = Vec::new();
    for (words, template, reading) in READINGS {
        for one_harmonic in [false, true] {
            for te in TES {
                let l = line(template, reading, te, one_harmonic);
                let v = runs.get(&l)?;
                if v["complete"] != true {
                    return Err(incomplete(&l));
                }
                let branch = branch_of(&v, "s1a1");
                rows.push(Row {
                    reading: words.into(),
                    one_harmonic,
                    te_um: te,
                    cells: cells(&branch, &anchors),
                    peaks: peaks(&branch),
                    bands: scale
                        .bands
                        .iter()
                        .map(|&(lo, hi)| unstable_in(&branch, lo, hi))
                        .collect(),
                });
            }
        }
    }
    let mut panels = Vec::new();
    for mesh in PANELS {
        for te in TES {
            let v = runs.get(&line(SINE, "all", te, false))?;
            let branch = branch_of(&v, mesh);
            panels.push(Panel {
                mesh: mesh.into(),
                te_um: te,
                cells: cells(&branch, &anchors),
                peaks: peaks(&branch),
            });
        }
    }
    let mut contact = Vec::new();
    for (words, template, reading) in &READINGS[..2] {
        for te in TES {
            let v = runs.get(&line(template, reading, te, false))?;
            contact.push(contact_of(&v, words, te));
        }
    }
    Ok(Fig2 {
        anchors,
        rows,
        panels,
        contact,
    })
}

/// The unstable points of a branch with Omega in `lo..=hi`, and all its
/// points there.
pub fn unstable_in(branch: &[Value], lo: f64, hi: f64) -> (usize, usize) {
    let inside: Vec<&Value> = branch
        .iter()
        .filter(|p| super::data::within(omega(p), lo, hi))
        .collect();
    (inside.iter().filter(|p| !stable(p)).count(), inside.len())
}

/// Where every mesh of a `--mesh all` branch keeps x at or above 0, on
/// stable points.
pub fn contact_of(v: &Value, reading: &str, te: u32) -> Contact {
    let branch = items(v, "branch");
    let kept = spans(branch, |p| {
        stable(p)
            && p["meshes"]
                .as_object()
                .is_some_and(|ms| ms.values().all(|m| f(&m["x_min_m"]) >= 0.0))
    });
    let range = (
        branch.first().map_or(f64::NAN, omega),
        branch.last().map_or(f64::NAN, omega),
    );
    Contact {
        reading: reading.into(),
        te_um: te,
        kept,
        range,
    }
}

/// A branch that stopped short: its verdicts would rest on part of it.
pub fn incomplete(line: &str) -> Failure {
    Failure {
        code: 1,
        message: format!("`{line}` did not complete its branch"),
    }
}
