//! The steady-state pipeline's pieces that belong to shooting: when to try
//! it, which period to try, its options, and the verdict a run ends with.
//!
//! A steady run ([`super::SteadyRun`]) integrates a short
//! transient; at the checkpoints [`CHECKPOINTS`] (and whenever the
//! early-settle test fires) it reads a candidate period from its recent
//! Poincaré points with a loose tolerance ([`candidate_period`]) and shoots
//! for that period from the current state. A converged, stable orbit is the
//! steady state: the run records its periods from the orbit's exact start
//! and calls it [`Motion::PeriodicExact`]. A converged orbit that lost
//! stability by a period doubling leads to a second attempt at twice the
//! period. Anything else (no candidate, Newton failing, an unstable orbit)
//! lets the integration go on, up to the transient budget; the recorded
//! window then decides ([`classify_recorded`]), and a failed attempt is
//! said in the verdict's note, never shown as an orbit. A window that
//! repeats or still approaches a period (or, without chaotic evidence,
//! shows a candidate at the loose tolerance) is shot from once more, from
//! its end state (`SteadyRun::confirm_window`): a stable orbit found there
//! is the steady state; otherwise the window is reported as recorded.

use super::probe::Probe;
use super::record::Recorder;
use super::{
    detect_period, poincare_point, settle_tol_um, Model, Phase, SteadyRun, MAX_PERIOD,
    SETTLE_DISTANCES,
};
use crate::error::{Result, SolverError};
use crate::ode::Dopri5;
use crate::shooting::{ShootOptions, ShootOutcome, ShootRun};
use serde::{Deserialize, Serialize};

/// The transient periods after which a candidate period is looked for.
pub(crate) const CHECKPOINTS: &[u32] = &[6, 12, 24, 48, 96, 192, 384, 768, 1536, 3072, 6144];

/// Lyapunov probes a steady run makes at most.
pub const MAX_PROBES: u32 = 2;

/// Transient periods before a run from the static equilibrium may start
/// the probe: the motion from rest can look chaotic for dozens of periods
/// before it settles (the gear pair with TE 21.4 µm at Omega 0.747: an
/// exponent of 0.14 per period over periods 6 to 22, then a stable
/// period-2 orbit). Runs continued from another state (sweeps, maps)
/// probe from the first checkpoint.
pub(crate) const PROBE_FROM_REST: u32 = 96;

/// Newton iterations a steady run gives one shooting attempt.
pub(crate) const PIPELINE_ITERATIONS: u32 = 8;

/// How a steady state was classified. It travels as JSON (the page's
/// worker replies, the CLI's figure shards) tagged by its [`Motion::name`]
/// in `kind`.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Motion {
    /// A periodic orbit found by shooting and stable: exact to the
    /// integrator's accuracy.
    PeriodicExact {
        /// Period in mesh periods.
        period: u32,
        /// The largest Floquet multiplier's modulus (below 1).
        max_multiplier_modulus: f64,
        /// Newton iterations (0 where the form read did not say).
        #[serde(default)]
        newton_iterations: u32,
    },
    /// The recorded Poincaré points repeat after `period` mesh periods
    /// within the period tolerance, but no orbit was confirmed by shooting.
    Periodic {
        /// Period in mesh periods.
        period: u32,
    },
    /// The recorded points repeat, but only after more than
    /// [`MAX_PERIOD`] mesh periods: beyond what is classified.
    PeriodAboveMaximum {
        /// The shortest repeat found in the recorded window.
        period: u32,
    },
    /// The points still approach a repeat of `period` mesh periods
    /// geometrically: the transient budget ran out first.
    StillSettling {
        /// The period they approach.
        period: u32,
    },
    /// No repeat within the recorded window and nothing approaching one.
    #[default]
    NotPeriodic,
}

impl Motion {
    /// The period, where the motion has one within the maximum.
    pub fn period(&self) -> Option<u32> {
        match self {
            Motion::PeriodicExact { period, .. } | Motion::Periodic { period } => Some(*period),
            _ => None,
        }
    }

    /// Whether the orbit was found by shooting.
    pub fn is_exact(&self) -> bool {
        matches!(self, Motion::PeriodicExact { .. })
    }

    /// The largest multiplier's modulus, for an exact orbit.
    pub fn max_multiplier_modulus(&self) -> Option<f64> {
        match self {
            Motion::PeriodicExact {
                max_multiplier_modulus,
                ..
            } => Some(*max_multiplier_modulus),
            _ => None,
        }
    }

    /// Every [`Motion::name`], in the order of the variants: what a file's
    /// `motion` field may say.
    pub const NAMES: [&'static str; 5] = [
        "periodic-exact",
        "periodic",
        "period-above-maximum",
        "still-settling",
        "not-periodic",
    ];

    /// A short name for output: `periodic-exact`, `periodic`,
    /// `period-above-maximum`, `still-settling`, `not-periodic`.
    pub fn name(&self) -> &'static str {
        match self {
            Motion::PeriodicExact { .. } => "periodic-exact",
            Motion::Periodic { .. } => "periodic",
            Motion::PeriodAboveMaximum { .. } => "period-above-maximum",
            Motion::StillSettling { .. } => "still-settling",
            Motion::NotPeriodic => "not-periodic",
        }
    }

    /// The verdict in words, e.g. "period 2 (exact)" or "not periodic after
    /// 300 periods".
    pub fn words(&self, periods_run: u32) -> String {
        match self {
            Motion::PeriodicExact {
                period,
                max_multiplier_modulus,
                ..
            } => format!(
                "period {period} (exact; largest Floquet multiplier {max_multiplier_modulus:.4})"
            ),
            Motion::Periodic { period } => {
                format!("period {period} (by integration, not confirmed by shooting)")
            }
            Motion::PeriodAboveMaximum { period } => format!(
                "repeats after {period} periods, above the largest period classified ({MAX_PERIOD})"
            ),
            Motion::StillSettling { period } => format!(
                "still settling towards period {period} after {periods_run} transient periods"
            ),
            Motion::NotPeriodic => format!("not periodic after {periods_run} transient periods"),
        }
    }
}

/// The shooting options of a steady run whose integrator uses `rtol` and
/// `atol_m`: a hundred times tighter (at most 1e-9 and 1e-12 m), so that
/// the orbit is exact at the run's own accuracy, and a residual tolerance
/// a hundredth of the period test's (a tenth of the settle test's). The
/// monodromy that only steers Newton is integrated at the run's own
/// tolerances (about half the steps); the converged orbit's, which gives
/// the Floquet multipliers, at the tight ones, its tangents to the orbit's
/// relative accuracy (`tangent_atol_scale`): a largest multiplier far
/// inside the unit circle (the gear pair's 0.081 at Omega 0.15) is then
/// right to 1e-8 instead of 6e-6.
pub(crate) fn pipeline_options(period: u32, rtol: f64, atol_m: f64, span_um: f64) -> ShootOptions {
    let mut o = ShootOptions::new(period);
    o.max_iterations = PIPELINE_ITERATIONS;
    o.rtol = (rtol * 1e-2).clamp(1e-13, 1e-9);
    o.atol_m = (atol_m * 1e-2).clamp(1e-16, 1e-12);
    o.tol_abs_um = 0.1 * settle_tol_um(span_um);
    o.tol_rel = 0.0;
    o.jacobian_tol = Some((rtol.clamp(1e-13, 1e-3), atol_m.clamp(1e-16, 1e-6)));
    o.tangent_atol_scale = 1e-2;
    o
}

/// The loose tolerance (µm) of [`candidate_period`] for an orbit whose
/// deflections span `span_um`: 2 % of the span, plus the settle tolerance.
pub(crate) fn loose_tol_um(span_um: f64) -> f64 {
    0.02 * span_um + settle_tol_um(span_um)
}

fn dist_inf(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// The smallest `p <= MAX_PERIOD` such that the last `p` Poincaré points
/// (newest last) each lie within `tol` of the point `p` before it, if the
/// history holds `2 p` points.
pub(crate) fn candidate_period(points: &[Vec<f64>], tol: f64) -> Option<u32> {
    let n = points.len();
    (1..=MAX_PERIOD.min(n / 2)).find_map(|p| {
        (0..p)
            .all(|k| dist_inf(&points[n - 1 - k], &points[n - 1 - k - p]) <= tol)
            .then_some(p as u32)
    })
}

/// The verdict of a recorded window without an exact orbit: its Poincaré
/// points (newest last), the period detected in them (if any) and the
/// period tolerance (µm).
pub fn classify_recorded(points: &[Vec<f64>], detected: Option<u32>, tol: f64) -> Motion {
    if let Some(period) = detected {
        return Motion::Periodic { period };
    }
    let n = points.len();
    // A repeat beyond the maximum, seen at least twice.
    if let Some(p) = (MAX_PERIOD + 1..=n / 3)
        .find(|&p| (0..n - p).all(|i| dist_inf(&points[i], &points[i + p]) <= tol))
    {
        return Motion::PeriodAboveMaximum { period: p as u32 };
    }
    // Still settling: for some period, the distance between cycles shrinks
    // steadily over the window (each quarter's largest at most 0.8 of the
    // previous one's) without reaching the tolerance.
    let settling = (1..=MAX_PERIOD.min(n / 8)).find(|&p| {
        let d: Vec<f64> = (p..n)
            .map(|i| dist_inf(&points[i], &points[i - p]))
            .collect();
        let q = d.len() / 4;
        if q == 0 {
            return false;
        }
        let quarter_max: Vec<f64> = d
            .chunks(q)
            .take(4)
            .map(|c| c.iter().copied().fold(0.0, f64::max))
            .collect();
        quarter_max.windows(2).all(|w| w[1] <= 0.8 * w[0])
    });
    match settling {
        Some(p) => Motion::StillSettling { period: p as u32 },
        None => Motion::NotPeriodic,
    }
}

/// A recorded window's own verdict, without shooting: the period detected
/// in its Poincaré points (within ten times the settle tolerance of its
/// deflections' range) and the classification that follows.
pub(super) fn window_verdict(rec: &Recorder) -> (Option<u32>, Motion) {
    let points = rec.points();
    let tol = 10.0 * settle_tol_um(rec.span_um());
    let detected = detect_period(points, tol);
    (detected, classify_recorded(points, detected, tol))
}

impl SteadyRun {
    /// The period worth confirming by shooting at the end of a recorded
    /// window without an exact orbit: the one its points repeat with or
    /// still approach (only with shooting on). Once per run: after the
    /// attempt the run either has its exact orbit or reports this window.
    pub(super) fn period_to_confirm(&self, rec: &Recorder) -> Option<u32> {
        if !self.opts.shooting {
            return None;
        }
        if self.facts.linear {
            return Some(1);
        }
        match window_verdict(rec).1 {
            Motion::StillSettling { period } | Motion::Periodic { period } => Some(period),
            // Without chaotic evidence, a candidate read with the loose
            // tolerance from the window's last points, as at a checkpoint
            // (a budget below the first checkpoint has none).
            Motion::NotPeriodic if !self.probing.lyapunov.is_some_and(|ev| ev.chaotic) => {
                candidate_period(rec.points(), loose_tol_um(rec.span_um()))
            }
            _ => None,
        }
    }

    /// Keeps the recorded window (started at `t_rec`, `periods` long) and
    /// shoots for a period-`n` orbit from its end state. A stable orbit
    /// found there is the steady state, recorded afresh from its exact
    /// start (the window's periods then count as transient); anything else
    /// reports the window as it was, with the attempt in the note.
    pub(super) fn confirm_window(
        &mut self,
        model: &Model,
        t_rec: f64,
        rec: Recorder,
        n: u32,
        periods: u32,
    ) {
        self.periods_run += periods;
        let span_um = rec.span_um();
        self.window = Some((t_rec, Box::new(rec), periods));
        if let Err(e) = self.start_shooting(model, n, span_um, false) {
            self.report_kept_window();
            self.note_attempt(format!(
                "shooting from the recorded window for a period-{n} orbit could not start ({e})"
            ));
        }
    }

    /// Hands the window kept by [`SteadyRun::confirm_window`], if any, to
    /// the `Finish` phase as it was recorded (its periods no longer
    /// counted as transient): `false` if no window was kept.
    fn report_kept_window(&mut self) -> bool {
        let Some((t_rec, rec, periods)) = self.window.take() else {
            return false;
        };
        self.periods_run -= periods;
        self.phase = Phase::Finish { t_rec, rec };
        true
    }

    /// Starts a shooting attempt for a period-`n` orbit from the current
    /// state (the end of transient period `periods_run`).
    pub(super) fn start_shooting(
        &mut self,
        model: &Model,
        n: u32,
        span_um: f64,
        settled: bool,
    ) -> Result<()> {
        let opts = pipeline_options(n, self.opts.rtol, self.opts.atol_m, span_um);
        let run = ShootRun::new(model, self.opts.omega, self.int.y(), &opts)?;
        self.shooting.attempts += 1;
        self.phase = Phase::Shoot {
            run: Box::new(run),
            period: n,
            settled,
        };
        Ok(())
    }

    /// What follows a shooting attempt: a stable orbit is recorded from its
    /// exact start; an orbit unstable by a period doubling is followed by
    /// an attempt at twice the period; anything else goes back to the
    /// integration (or records what it has, if the transient had settled).
    pub(super) fn after_shooting(
        &mut self,
        model: &Model,
        out: ShootOutcome,
        n: u32,
        settled: bool,
    ) -> Result<()> {
        match out {
            ShootOutcome::Converged(orbit) if orbit.is_stable() => {
                let t = f64::from(self.periods_run) * self.facts.period;
                let stats = self.int.stats;
                self.int = Dopri5::new(
                    &mut self.ode,
                    t,
                    &orbit.start_state,
                    self.facts.period / 200.0,
                    self.tol.clone(),
                );
                self.int.stats = stats;
                self.shooting.exact = Some(Motion::PeriodicExact {
                    period: orbit.period,
                    max_multiplier_modulus: orbit.max_multiplier_modulus(),
                    newton_iterations: orbit.iterations,
                });
                self.settling.settled = true;
                self.window = None;
                self.start_recording(model);
                return Ok(());
            }
            ShootOutcome::Converged(orbit) if self.facts.linear => {
                // A linear model's periodic response is unique; unstable,
                // every other motion grows from it without bound.
                return Err(SolverError::ParametricallyUnstable {
                    omega: self.opts.omega,
                    modulus: orbit.max_multiplier_modulus(),
                });
            }
            ShootOutcome::Converged(orbit) => {
                let doubled = orbit
                    .multipliers
                    .as_ref()
                    .and_then(|m| m.most_negative_real())
                    .is_some_and(|mu| mu < -1.0);
                // The orbit may repeat sooner than the period shot for
                // (`orbit.period` divides `n`); twice its period is then at
                // most `n`. Only ever doubling upwards ends the chain: a
                // shot for 4 that lands on a period-1 orbit must not go
                // back to 2, whose doubling leads to 4 again.
                let twice = 2 * orbit.period;
                if doubled && twice > n && twice as usize <= MAX_PERIOD {
                    let span_um = self.settling.span.span_um();
                    return self.start_shooting(model, twice, span_um, settled);
                }
                let how = match orbit.multipliers.as_ref().and_then(|m| m.critical()) {
                    Some(mu) if mu.im.abs() > 1e-9 * mu.norm() => "a complex pair outside the unit circle, as past a Neimark-Sacker point (a torus nearby)",
                    Some(mu) if mu.re < 0.0 => "a multiplier below -1, as past a period doubling",
                    _ => "a multiplier above +1",
                };
                self.note_attempt(format!(
                    "shooting after {} periods found a period-{} orbit, but it is unstable ({how}; largest Floquet multiplier modulus {:.4})",
                    self.periods_run,
                    orbit.period,
                    orbit.max_multiplier_modulus()
                ));
            }
            ShootOutcome::Failed(f) => {
                self.note_attempt(format!(
                    "shooting after {} periods for a period-{n} orbit did not converge ({})",
                    self.periods_run, f.reason
                ));
            }
        }
        if self.report_kept_window() {
            // The window's own verdict stands.
            return Ok(());
        }
        if settled {
            self.start_recording(model);
        } else if self.may_probe() {
            self.start_probe(model)?;
        } else {
            self.phase = Phase::Transient {
                p: self.periods_run + 1,
            };
        }
        Ok(())
    }

    /// The period to shoot for at a transient checkpoint: the one the last
    /// Poincaré points repeat with at the loose tolerance; for a linear
    /// model period 1, once (its orbit is unique, and where it is unstable
    /// the motion grows without bound: another attempt finds the same).
    pub(super) fn checkpoint_candidate(&self, span_um: f64) -> Option<u32> {
        if self.facts.linear {
            return (self.shooting.attempts == 0).then_some(1);
        }
        candidate_period(&self.settling.pipe_hist, loose_tol_um(span_um))
    }

    /// Whether the run may start a Lyapunov probe now: not for a linear
    /// model (it cannot be chaotic), at most [`MAX_PROBES`] times, and not
    /// before `probe_from` transient periods.
    pub(super) fn may_probe(&self) -> bool {
        !self.facts.linear
            && self.probing.count < MAX_PROBES
            && self.periods_run >= self.probing.from
    }

    /// Starts recording from the current state (the end of transient
    /// period `periods_run`) with the Lyapunov probe beside it.
    pub(super) fn start_probe(&mut self, model: &Model) -> Result<()> {
        self.probing.count += 1;
        let probe = Probe::new(model, &self.ode, self.int.t(), self.int.y(), &self.tol)?;
        self.probing.probe = Some(Box::new(probe));
        self.start_recording(model);
        Ok(())
    }

    /// How many periods the window records: all of them, but for an exact
    /// orbit (without time histories) two of its periods, the rest of the
    /// Poincaré samples following from its periodicity.
    pub(super) fn record_target(&self) -> u32 {
        match self.shooting.exact.as_ref().and_then(Motion::period) {
            Some(n) if self.opts.history_meshes.is_empty() => {
                (2 * n).clamp(1, self.opts.record_periods)
            }
            _ => self.opts.record_periods,
        }
    }

    /// The probe's measurement at the end of recorded period `r` of
    /// `target`: `true` if the run went back to its transient (the probe
    /// found no chaos, or the window ended before it decided; a candidate
    /// period in the latest points is then shot for at once), `false` if
    /// the recording goes on (chaos, with the probe done, or undecided).
    pub(super) fn probe_period(&mut self, model: &Model, r: u32, target: u32) -> Result<bool> {
        let Some(pr) = self.probing.probe.as_mut() else {
            return Ok(false);
        };
        let (t, y) = (self.int.t(), self.int.y());
        let ev = pr.measure(&self.ode, t, y)?;
        // The recorded points feed the transient's tests too, should the
        // run go back to it.
        let point = poincare_point(&self.ode, t, y, self.facts.omega_rad_s);
        if self.opts.early_settle {
            self.settling.poincare_hist.push(point.clone());
            if self.settling.poincare_hist.len() > SETTLE_DISTANCES * 8 + 1 {
                self.settling.poincare_hist.remove(0);
            }
        }
        self.settling.pipe_hist.push(point);
        if self.settling.pipe_hist.len() > 2 * MAX_PERIOD + 1 {
            self.settling.pipe_hist.remove(0);
        }
        if ev.is_none() && r < target {
            return Ok(false);
        }
        self.probing.steps += pr.steps();
        self.probing.probe = None;
        if let Some(ev) = ev {
            self.probing.lyapunov = Some(ev);
            if ev.chaotic {
                return Ok(false);
            }
        }
        let span_um = match &self.phase {
            Phase::Record { rec, .. } => rec.span_um(),
            _ => 0.0,
        };
        self.periods_run += r;
        self.phase = Phase::Transient {
            p: self.periods_run + 1,
        };
        self.settling.span.reset_keep_last();
        // Without chaos the motion settles (or winds on a torus): shoot for
        // the period the points suggest, or else for period 1, the usual
        // steady state, whose transient may decay too slowly for the loose
        // test (a largest multiplier of 0.998 needs some 2 000 periods to
        // come within 2 % of the span).
        let n = candidate_period(&self.settling.pipe_hist, loose_tol_um(span_um)).unwrap_or(1);
        self.start_shooting(model, n, span_um, false)?;
        Ok(true)
    }

    /// Adds a shooting attempt that did not give the steady state to the note.
    fn note_attempt(&mut self, what: String) {
        match &mut self.shooting.note {
            Some(note) => {
                note.push_str("; ");
                note.push_str(&what);
            }
            None => self.shooting.note = Some(what),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every verdict reads from its JSON form (tagged by its name in
    /// `kind`) with its period and exactness, and writes back to the same
    /// value; a form without the Newton count (an older shard) still reads.
    #[test]
    fn every_verdict_survives_json() {
        let forms = [
            (
                r#"{"kind":"periodic-exact","period":2,"max_multiplier_modulus":0.5,"newton_iterations":3}"#,
                Some(2),
                true,
            ),
            (
                r#"{"kind":"periodic-exact","period":1,"max_multiplier_modulus":0.9}"#,
                Some(1),
                true,
            ),
            (r#"{"kind":"periodic","period":3}"#, Some(3), false),
            (
                r#"{"kind":"period-above-maximum","period":40}"#,
                None,
                false,
            ),
            (r#"{"kind":"still-settling","period":11}"#, None, false),
            (r#"{"kind":"not-periodic"}"#, None, false),
        ];
        for (json, period, exact) in forms {
            let m: Motion = serde_json::from_str(json).unwrap();
            let v: serde_json::Value = serde_json::from_str(json).unwrap();
            assert_eq!(v["kind"], m.name(), "{json}");
            assert!(Motion::NAMES.contains(&m.name()), "{json}");
            assert_eq!((m.period(), m.is_exact()), (period, exact), "{json}");
            let back: Motion = serde_json::from_value(serde_json::to_value(m).unwrap()).unwrap();
            assert_eq!(back, m, "{json}");
        }
    }
}
