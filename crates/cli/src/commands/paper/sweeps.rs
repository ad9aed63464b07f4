//! The bifurcation sweeps of Figs. 4 and 8 (claims 3-5, 8 and 9), on the
//! paper's 0.05 grid and on the finer grids that claim 10 reads, and the
//! Lyapunov exponents of Fig. 8.

use super::data::{
    any_back, any_part, at, f, first, items, largest, merged, mesh_parts, omega, smallest, spans,
    spans_not, um, x_amp, Spans,
};
use super::runs::Runs;
use super::scale::Scale;
use crate::failure::Failure;
use serde::{Deserialize, Serialize};
use serde_json::Value;

/// The sweep of Figs. 4 and 8: `$b` and `$te` filled in.
pub const SWEEP: &str = "gearshock bifurcation --set backlash_um=$b --set te_um=$te --mesh s1a1 --omega-from 0.15 --omega-to 2 --points 38 --direction up";
/// The finer sweeps: `$from`, `$to` and `$n` too.
pub const FINE: &str = "gearshock bifurcation --set backlash_um=$b --set te_um=$te --mesh s1a1 --omega-from $from --omega-to $to --points $n --direction up";
/// The finer grids: (from, to, points). Steps of 0.01 over the whole
/// range and below the paper's; of 0.002 over the first two modes'
/// resonances and their neighbours; of 0.0001 over the superharmonic
/// resonance at half the first natural frequency.
pub const FINE_GRIDS: [(f64, f64, u32); 3] =
    [(0.02, 2.0, 199), (0.1, 0.5, 201), (0.114, 0.117, 31)];
/// Fig. 8's Lyapunov grid: (from, to, points).
pub const LYAPUNOV_GRID: (f64, f64, u32) = (0.3, 1.0, 15);
/// An exponent per period above this is chaos.
pub const CHAOS: f64 = 0.01;
/// The Omegas where Fig. 4's amplitudes are read on the 0.05 grid.
pub const AMPLITUDE_AT: [f64; 3] = [0.15, 0.25, 0.4];
/// Where the first mode's resonance is looked for on the finer grids.
pub const FIRST_MODE_RANGE: (f64, f64) = (0.15, 0.35);
/// The paper's high-frequency range, where claim 4 reads its largest amplitude.
pub const HIGH: (f64, f64) = (1.2, 2.0);

/// A sweep's settings: the backlash, the TE and a reading's `--set`s.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Case {
    /// Backlash (µm).
    pub backlash_um: u32,
    /// TE (µm).
    pub te_um: u32,
    /// A reading's extra settings (" --set te_meshes=all"), or empty.
    pub extra: String,
}

impl Case {
    /// A case of the default readings.
    pub fn new(backlash_um: u32, te_um: u32) -> Case {
        Case {
            backlash_um,
            te_um,
            extra: String::new(),
        }
    }

    fn fill(&self, template: &str) -> String {
        template
            .replace("$b", &self.backlash_um.to_string())
            .replace("$te", &self.te_um.to_string())
            .replace(" --mesh", &format!("{} --mesh", self.extra))
    }

    /// The 0.05-grid sweep.
    pub fn sweep(&self) -> String {
        self.fill(SWEEP)
    }

    /// The finer sweeps.
    pub fn fine(&self) -> Vec<String> {
        FINE_GRIDS
            .iter()
            .map(|(from, to, n)| {
                self.fill(FINE)
                    .replace("$from", &super::words::omega_arg(*from))
                    .replace("$to", &super::words::omega_arg(*to))
                    .replace("$n", &n.to_string())
            })
            .collect()
    }

    /// Every line of the case, the finer sweeps' if `fine`.
    pub fn lines(&self, fine: bool) -> Vec<String> {
        let mut out = vec![self.sweep()];
        if fine {
            out.extend(self.fine());
        }
        out
    }
}

/// What the sweeps of one case show.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Sweep {
    /// The settings.
    pub case: Case,
    /// The amplitude of x_s1a1 at each of [`AMPLITUDE_AT`] (µm).
    pub amplitude_at: Vec<f64>,
    /// The amplitude of delta, the rotations' part, at Omega 0.25 (µm).
    pub delta_at_025_um: f64,
    /// The largest amplitude over [`HIGH`] (µm).
    pub largest_high_um: f64,
    /// The largest amplitude over the paper's high range matched (µm).
    pub largest_high_matched_um: f64,
    /// The paper's high range matched, on the 0.05 grid.
    pub high_matched: (f64, f64),
    /// The first Omega without period 1.
    pub first_not_period_1: Option<f64>,
    /// Where the motion is not periodic (0.05 grid).
    pub not_periodic: Spans,
    /// The lowest x_s1a1 over the whole sweep and over the paper's range
    /// matched (µm).
    pub lowest_x_um: (f64, f64),
    /// The largest penetration velocity of s1a1 in the Poincaré sections,
    /// over the whole sweep and over the paper's range matched (m/s).
    pub largest_velocity_m_s: (f64, f64),
    /// Where the drive flanks of s1a1 part.
    pub s1a1_parts: Spans,
    /// Where the drive flanks of some mesh part.
    pub any_parts: Spans,
    /// Where x_s1a1 is negative.
    pub x_negative: Spans,
    /// Where the back flanks of s1a1 touch.
    pub s1a1_back: Spans,
    /// Where the back flanks of some mesh touch.
    pub any_back: Spans,
    /// The finer sweeps, where they are run.
    pub fine: Option<Fine>,
}

/// What the finer sweeps of one case show.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Fine {
    /// The first mode's resonance: (Omega, amplitude of x_s1a1 µm).
    pub first_mode_peak: (f64, f64),
    /// The first Omega without period 1.
    pub first_not_period_1: Option<f64>,
    /// Where the drive flanks of some mesh part (or the motion is not
    /// periodic), and where none do on a periodic orbit.
    pub any: (Spans, Spans),
    /// The same for s1a1 alone.
    pub s1a1: (Spans, Spans),
    /// The first Omega where the back flanks of some mesh touch, and that mesh.
    pub first_back: Option<(f64, String)>,
}

/// Reads one case's sweeps off the runs, the finer ones if `fine`.
pub fn compute(runs: &Runs, scale: &Scale, case: &Case, fine: bool) -> Result<Sweep, Failure> {
    let coarse = runs.get(&case.sweep())?;
    let pts = items(&coarse, "points");
    let amp = |w: f64| at(pts, w).map_or(f64::NAN, x_amp);
    let p25 = at(pts, 0.25);
    let delta_at_025_um = p25.map_or(f64::NAN, |p| {
        0.5 * (um(&p["delta_max_m"]) - um(&p["delta_min_m"]))
    });
    // The paper's Omega 1.2-2 matched, on the 0.05 grid.
    let grid = |w: f64, up: bool| {
        let k = w / 0.05;
        0.05 * if up { k.ceil() } else { k.floor() }
    };
    let high_matched = (
        grid(scale.matched(HIGH.0), true),
        grid(scale.matched(HIGH.1), false),
    );
    let matched_top = scale.matched(2.0);
    let x_min = |p: &Value| um(&p["x_min_m"]);
    let velocity = |p: &Value| {
        p["poincare_x_velocity_m_s"]
            .as_array()
            .map_or(f64::NAN, |xs| {
                xs.iter().map(|s| f(s).abs()).fold(0.0, f64::max)
            })
    };
    let not_p1 = |p: &Value| p["period"] != 1;
    Ok(Sweep {
        case: case.clone(),
        amplitude_at: AMPLITUDE_AT.iter().map(|&w| amp(w)).collect(),
        delta_at_025_um,
        largest_high_um: largest(pts, HIGH.0, HIGH.1, x_amp),
        largest_high_matched_um: largest(pts, high_matched.0, high_matched.1, x_amp),
        high_matched,
        first_not_period_1: first(pts, not_p1),
        not_periodic: spans(pts, |p| p["period"].is_null()),
        lowest_x_um: (
            smallest(pts, 0.0, 2.0, x_min),
            smallest(pts, 0.0, matched_top, x_min),
        ),
        largest_velocity_m_s: (
            largest(pts, 0.0, 2.0, velocity),
            largest(pts, 0.0, matched_top, velocity),
        ),
        s1a1_parts: spans(pts, mesh_parts),
        any_parts: spans(pts, any_part),
        x_negative: spans(pts, |p| f(&p["x_min_m"]) < 0.0),
        s1a1_back: spans(pts, |p| p["impact"] == "double-sided"),
        any_back: spans(pts, any_back),
        fine: if fine { Some(finer(runs, case)?) } else { None },
    })
}

/// A point free of impacts: no flanks part (as `parts` reads them) and
/// the motion settles on a periodic orbit. A motion that does not, inside
/// a band of parametric instability, may still be growing towards contact
/// loss however long the record.
fn free(p: &Value, parts: impl Fn(&Value) -> bool) -> bool {
    !parts(p) && p["period"].is_u64()
}

/// Reads one case's finer sweeps off the runs.
fn finer(runs: &Runs, case: &Case) -> Result<Fine, Failure> {
    let fine_runs = case
        .fine()
        .iter()
        .map(|l| runs.get(l))
        .collect::<Result<Vec<_>, _>>()?;
    let fine = merged(&fine_runs.iter().map(|v| &**v).collect::<Vec<_>>());
    let first_mode_peak = fine
        .iter()
        .filter(|p| super::data::within(omega(p), FIRST_MODE_RANGE.0, FIRST_MODE_RANGE.1))
        .map(|p| (omega(p), x_amp(p)))
        .fold((f64::NAN, f64::NEG_INFINITY), |best, here| {
            if here.1 > best.1 {
                here
            } else {
                best
            }
        });
    Ok(Fine {
        first_mode_peak,
        first_not_period_1: first(&fine, |p| p["period"] != 1),
        any: (
            spans(&fine, |p| !free(p, any_part)),
            spans_not(&fine, |p| !free(p, any_part)),
        ),
        s1a1: (
            spans(&fine, |p| !free(p, mesh_parts)),
            spans_not(&fine, |p| !free(p, mesh_parts)),
        ),
        first_back: fine.iter().find(|p| any_back(p)).map(|p| {
            (
                omega(p),
                p["worst_mesh"].as_str().unwrap_or_default().to_string(),
            )
        }),
    })
}

/// Fig. 8's Lyapunov exponents for one backlash.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Chaos {
    /// The backlash (µm).
    pub backlash_um: u32,
    /// Where the exponent is above [`CHAOS`].
    pub chaotic: Spans,
    /// The largest exponent per period.
    pub largest: f64,
}

/// Fig. 8's Lyapunov exponents: `$b` to fill in.
pub fn lyapunov_template() -> String {
    let (from, to, n) = LYAPUNOV_GRID;
    format!(
        "gearshock lyapunov --set backlash_um=$b --set te_um={} --omega-from {} --omega-to {} --points {n}",
        super::record::FIG8_TE,
        super::words::omega_arg(from),
        super::words::omega_arg(to)
    )
}

/// The Lyapunov line of one backlash.
pub fn lyapunov_line(b: u32) -> String {
    lyapunov_template().replace("$b", &b.to_string())
}

/// Reads one backlash's exponents off the runs.
pub fn chaos(runs: &Runs, b: u32) -> Result<Chaos, Failure> {
    let v = runs.get(&lyapunov_line(b))?;
    let pts = items(&v, "points");
    let exponent = |p: &Value| f(&p["exponent_per_period"]);
    Ok(Chaos {
        backlash_um: b,
        chaotic: spans(pts, |p| exponent(p) > CHAOS),
        largest: pts.iter().map(exponent).fold(f64::NAN, f64::max),
    })
}
