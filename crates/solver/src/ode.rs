//! Adaptive Dormand–Prince 5(4) integration with dense output and event location.
//!
//! The method is DOPRI5 as in Hairer, Nørsett & Wanner, *Solving Ordinary
//! Differential Equations I*, §II.5 and §II.6: fifth-order propagation, an
//! embedded fourth-order error estimate, first-same-as-last, the PI step-size
//! controller of their code `DOPRI5`, and its fourth-order continuous
//! extension for dense output.
//!
//! Events. A system may declare scalar event functions `g_i(t, y)` (for the
//! gear models: the contact switches `delta - e = +-b`). After a step passes
//! the error test, every event is checked for a sign change between the
//! step's ends, and, where the ends agree in sign, for a pair of crossings
//! inside the step (a cubic Hermite model of `g` from its values and rates
//! at both ends, confirmed on the dense output). The earliest crossing is
//! located on the dense output by the Illinois method and the step is
//! *retaken* to end there, so the force law's kink always falls on a step
//! boundary: the error estimate stays valid across contact switches and the
//! method keeps its order. A crossing closer to a step's start than the
//! landing tolerance counts as having happened at the start.

use crate::error::{Result, SolverError};
use crate::fastmath::{exp2, log2_pos, max, min};

/// A first-order system `y' = f(t, y)` with optional event functions.
pub trait Ode {
    /// Dimension of `y`.
    fn dim(&self) -> usize;
    /// Evaluates `dy = f(t, y)`.
    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]);
    /// Number of event functions.
    fn n_events(&self) -> usize {
        0
    }
    /// Values `g` and time rates `dg` of all event functions at `(t, y)`, with
    /// `dy = f(t, y)` given.
    fn events(&mut self, _t: f64, _y: &[f64], _dy: &[f64], _g: &mut [f64], _dg: &mut [f64]) {}
    /// Value of event function `i` at `(t, y)`; `y` holds at least the
    /// first [`Ode::event_dim`] components.
    fn event(&mut self, _i: usize, _t: f64, _y: &[f64]) -> f64 {
        0.0
    }
    /// How many leading components of `y` the event functions read: event
    /// location interpolates only those (a mechanical system's crossings
    /// depend on the positions, not the rates).
    fn event_dim(&self) -> usize {
        self.dim()
    }
    /// The components of `y` that event function `i` reads, if fewer than
    /// [`Ode::event_dim`]: event location then interpolates only those (a
    /// mesh's contact switch depends on its three coordinates).
    fn event_components(&self, _i: usize) -> Option<&[usize]> {
        None
    }
    /// How many leading components the dense output covers (at least
    /// [`Ode::event_dim`]): an extended system whose extra components are
    /// never interpolated (the variational equations' tangents) skips them.
    fn dense_dim(&self) -> usize {
        self.dim()
    }
}

/// Work counters of an integration.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct IntegratorStats {
    /// Accepted steps.
    pub steps: u64,
    /// Steps rejected by the error test.
    pub rejected_steps: u64,
    /// Steps retaken to land on an event.
    pub event_retakes: u64,
    /// Right-hand side evaluations.
    pub rhs_evaluations: u64,
    /// Events located (contact switches).
    pub events: u64,
}

impl std::ops::AddAssign for IntegratorStats {
    fn add_assign(&mut self, o: Self) {
        self.steps += o.steps;
        self.rejected_steps += o.rejected_steps;
        self.event_retakes += o.event_retakes;
        self.rhs_evaluations += o.rhs_evaluations;
        self.events += o.events;
    }
}

/// Tolerances and limits.
#[derive(Debug, Clone, PartialEq)]
pub struct Tolerances {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance per component.
    pub atol: Vec<f64>,
    /// Smallest step allowed before giving up (s).
    pub h_min: f64,
    /// Largest step allowed (s).
    pub h_max: f64,
}

// Dormand–Prince coefficients.
const C2: f64 = 1.0 / 5.0;
const C3: f64 = 3.0 / 10.0;
const C4: f64 = 4.0 / 5.0;
const C5: f64 = 8.0 / 9.0;
const A21: f64 = 1.0 / 5.0;
const A31: f64 = 3.0 / 40.0;
const A32: f64 = 9.0 / 40.0;
const A41: f64 = 44.0 / 45.0;
const A42: f64 = -56.0 / 15.0;
const A43: f64 = 32.0 / 9.0;
const A51: f64 = 19372.0 / 6561.0;
const A52: f64 = -25360.0 / 2187.0;
const A53: f64 = 64448.0 / 6561.0;
const A54: f64 = -212.0 / 729.0;
const A61: f64 = 9017.0 / 3168.0;
const A62: f64 = -355.0 / 33.0;
const A63: f64 = 46732.0 / 5247.0;
const A64: f64 = 49.0 / 176.0;
const A65: f64 = -5103.0 / 18656.0;
const A71: f64 = 35.0 / 384.0;
const A73: f64 = 500.0 / 1113.0;
const A74: f64 = 125.0 / 192.0;
const A75: f64 = -2187.0 / 6784.0;
const A76: f64 = 11.0 / 84.0;
const E1: f64 = 71.0 / 57600.0;
const E3: f64 = -71.0 / 16695.0;
const E4: f64 = 71.0 / 1920.0;
const E5: f64 = -17253.0 / 339200.0;
const E6: f64 = 22.0 / 525.0;
const E7: f64 = -1.0 / 40.0;
const D1: f64 = -12715105075.0 / 11282082432.0;
const D3: f64 = 87487479700.0 / 32700410799.0;
const D4: f64 = -10690763975.0 / 1880347072.0;
const D5: f64 = 701980252875.0 / 199316789632.0;
const D6: f64 = -1453857185.0 / 822651844.0;
const D7: f64 = 69997945.0 / 29380423.0;

// Step-size controller of Hairer's DOPRI5.
const SAFE: f64 = 0.9;
const FAC_MIN_INV: f64 = 5.0; // step may shrink at most 5x
const FAC_MAX_INV: f64 = 0.1; // and grow at most 10x
const BETA: f64 = 0.04;
const EXPO1: f64 = 0.2 - BETA * 0.75;
/// log2 of the floor 1e-4 of the PI controller's remembered error.
const LOG2_FAC_OLD_MIN: f64 = -13.287_712_379_549_449;

/// Relative position inside a step below which an event counts as at the step's start
/// (or, after a retake, as landed at its end).
///
/// The force law is continuous and only its slope jumps at a switch, so a
/// step that straddles a switch by `eps h` makes a local error of order
/// `(eps h)^3` times the jump in the third derivative. Measured against an
/// independent DOP853 reference at rtol 1e-12 (the `reference` test), 1e-4
/// keeps the Poincaré samples as accurate as exact landing does (1e-6 gives
/// no better agreement) while 1e-3 loses a factor 20 at double-sided impacts;
/// it saves a second retake per switch.
const EVENT_LANDING: f64 = 1e-4;

/// What an accepted step did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepInfo {
    /// Start of the step.
    pub t0: f64,
    /// End of the step.
    pub t1: f64,
    /// Number of event crossings inside the step; [`Dopri5::last_events`]
    /// locates them.
    pub events: usize,
}

/// The DOPRI5 integrator's state.
#[derive(Debug, Clone)]
pub struct Dopri5 {
    n: usize,
    /// The dense output's components ([`Ode::dense_dim`]).
    dense_n: usize,
    t: f64,
    y: Vec<f64>,
    h: f64,
    tol: Tolerances,
    /// log2 of the previous accepted step's error norm (at least 1e-4).
    log_fac_old: f64,
    k: [Vec<f64>; 7],
    y1: Vec<f64>,
    ytmp: Vec<f64>,
    err: Vec<f64>,
    // Dense output of the last accepted step: y(t0 + theta h) =
    // r0 + theta (r1 + (1 - theta) (r2 + theta (r3 + (1 - theta) r4))).
    r: [Vec<f64>; 5],
    dense_t0: f64,
    dense_h: f64,
    n_events: usize,
    g0: Vec<f64>,
    dg0: Vec<f64>,
    /// Event rates at the start of the previous step and its length, for a
    /// finite-difference second derivative used to predict crossings.
    dg_prev: Vec<f64>,
    h_prev: f64,
    g1: Vec<f64>,
    dg1: Vec<f64>,
    /// Crossings inside the last accepted step: (event, value at the step's
    /// start). Their times are located only on request ([`Dopri5::last_events`]):
    /// a long run needs the count, rarely the instants.
    crossings: Vec<(usize, f64)>,
    /// The located crossings of the last accepted step: (event, time).
    located: Vec<(usize, f64)>,
    /// Counters.
    pub stats: IntegratorStats,
}

impl Dopri5 {
    /// Starts an integration at `(t0, y0)` with initial step `h0`.
    pub fn new<O: Ode>(ode: &mut O, t0: f64, y0: &[f64], h0: f64, tol: Tolerances) -> Self {
        let n = ode.dim();
        let dense_n = ode.dense_dim().max(ode.event_dim()).min(n);
        let ne = ode.n_events();
        let zeros = || vec![0.0; n];
        let mut s = Dopri5 {
            n,
            dense_n,
            t: t0,
            y: y0.to_vec(),
            h: h0.min(tol.h_max),
            tol,
            log_fac_old: LOG2_FAC_OLD_MIN,
            k: std::array::from_fn(|_| zeros()),
            y1: zeros(),
            ytmp: zeros(),
            err: zeros(),
            r: std::array::from_fn(|_| zeros()),
            dense_t0: t0,
            dense_h: 0.0,
            n_events: ne,
            g0: vec![0.0; ne],
            dg0: vec![0.0; ne],
            dg_prev: vec![0.0; ne],
            h_prev: 0.0,
            crossings: Vec::new(),
            located: Vec::new(),
            g1: vec![0.0; ne],
            dg1: vec![0.0; ne],
            stats: IntegratorStats::default(),
        };
        ode.rhs(t0, &s.y, &mut s.k[0]);
        s.stats.rhs_evaluations += 1;
        if ne > 0 {
            ode.events(t0, &s.y, &s.k[0], &mut s.g0, &mut s.dg0);
        }
        s
    }

    /// The event crossings inside the last accepted step, as (event, time), in
    /// time order, each located on the step's dense output to 1e-12 of the
    /// step (Illinois iterations; computed here, on request).
    pub fn last_events<O: Ode>(&mut self, ode: &mut O) -> &[(usize, f64)] {
        self.located.clear();
        let mut ybuf = std::mem::take(&mut self.ytmp);
        for k in 0..self.crossings.len() {
            let (i, g0) = self.crossings[k];
            let theta = self.illinois(ode, i, (0.0, g0), 1.0, 1e-12, &mut ybuf);
            self.located.push((i, self.dense_t0 + theta * self.dense_h));
        }
        self.ytmp = ybuf;
        self.located.sort_by(|a, b| a.1.total_cmp(&b.1));
        &self.located
    }

    /// Current time.
    pub fn t(&self) -> f64 {
        self.t
    }

    /// Current state.
    pub fn y(&self) -> &[f64] {
        &self.y
    }

    /// Derivative at the current state (first-same-as-last stage).
    pub fn dy(&self) -> &[f64] {
        &self.k[0]
    }

    /// The step size the controller proposes next.
    pub fn h(&self) -> f64 {
        self.h
    }

    /// Evaluates the dense output of the last accepted step at time `t`
    /// (which should lie inside that step) into `out`: its first
    /// [`Ode::dense_dim`] components at most.
    pub fn dense(&self, t: f64, out: &mut [f64]) {
        let m = out.len().min(self.dense_n);
        dense_eval(&self.r, self.dense_theta(t), &mut out[..m]);
    }

    /// Time `t` as a fraction of the last accepted step.
    fn dense_theta(&self, t: f64) -> f64 {
        if self.dense_h > 0.0 {
            (t - self.dense_t0) / self.dense_h
        } else {
            0.0
        }
    }

    /// The dense output of the last accepted step at time `t` for the
    /// components `cols` only, each into its own place in `out` (the same
    /// bits there as [`Dopri5::dense`]; the other places are left as they
    /// are).
    pub fn dense_components(&self, t: f64, cols: &[usize], out: &mut [f64]) {
        dense_eval_at(&self.r, self.dense_theta(t), cols, out);
    }

    /// One trial step of size `h` from the current state: fills `y1`, `k[1..7]`
    /// and returns the scaled error norm.
    fn trial<O: Ode>(&mut self, ode: &mut O, h: f64) -> f64 {
        let n = self.n;
        let t = self.t;
        let y = &self.y[..n];
        let yt = &mut self.ytmp[..n];
        let [k1, k2, k3, k4, k5, k6, k7] = &mut self.k;
        // Slices of exactly n entries let the compiler drop bounds checks.
        let k1 = &k1[..n];
        for i in 0..n {
            yt[i] = y[i] + h * A21 * k1[i];
        }
        ode.rhs(t + C2 * h, yt, k2);
        let k2 = &k2[..n];
        for i in 0..n {
            yt[i] = y[i] + h * (A31 * k1[i] + A32 * k2[i]);
        }
        ode.rhs(t + C3 * h, yt, k3);
        let k3 = &k3[..n];
        for i in 0..n {
            yt[i] = y[i] + h * (A41 * k1[i] + A42 * k2[i] + A43 * k3[i]);
        }
        ode.rhs(t + C4 * h, yt, k4);
        let k4 = &k4[..n];
        for i in 0..n {
            yt[i] = y[i] + h * (A51 * k1[i] + A52 * k2[i] + A53 * k3[i] + A54 * k4[i]);
        }
        ode.rhs(t + C5 * h, yt, k5);
        let k5 = &k5[..n];
        for i in 0..n {
            yt[i] =
                y[i] + h * (A61 * k1[i] + A62 * k2[i] + A63 * k3[i] + A64 * k4[i] + A65 * k5[i]);
        }
        ode.rhs(t + h, yt, k6);
        let k6 = &k6[..n];
        let y1 = &mut self.y1[..n];
        for i in 0..n {
            y1[i] =
                y[i] + h * (A71 * k1[i] + A73 * k3[i] + A74 * k4[i] + A75 * k5[i] + A76 * k6[i]);
        }
        ode.rhs(t + h, y1, k7);
        let k7 = &k7[..n];
        self.stats.rhs_evaluations += 6;
        let atol = &self.tol.atol[..n];
        let err = &mut self.err[..n];
        let mut sum = 0.0;
        for i in 0..n {
            let e =
                h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i]);
            err[i] = e;
            let sk = atol[i] + self.tol.rtol * max(y[i].abs(), y1[i].abs());
            sum += (e / sk) * (e / sk);
        }
        (sum / n as f64).sqrt()
    }

    /// Fills the dense-output coefficients for the trial step of size `h`.
    fn build_dense(&mut self, h: f64) {
        let n = self.dense_n;
        let [k1, _k2, k3, k4, k5, k6, k7] = &self.k;
        let (k1, k3, k4, k5, k6, k7) = (&k1[..n], &k3[..n], &k4[..n], &k5[..n], &k6[..n], &k7[..n]);
        let (y, y1) = (&self.y[..n], &self.y1[..n]);
        let [r0, r1, r2, r3, r4] = &mut self.r;
        let (r0, r1, r2, r3, r4) = (
            &mut r0[..n],
            &mut r1[..n],
            &mut r2[..n],
            &mut r3[..n],
            &mut r4[..n],
        );
        for i in 0..n {
            let ydiff = y1[i] - y[i];
            let bspl = h * k1[i] - ydiff;
            r0[i] = y[i];
            r1[i] = ydiff;
            r2[i] = bspl;
            r3[i] = ydiff - h * k7[i] - bspl;
            r4[i] =
                h * (D1 * k1[i] + D3 * k3[i] + D4 * k4[i] + D5 * k5[i] + D6 * k6[i] + D7 * k7[i]);
        }
        self.dense_t0 = self.t;
        self.dense_h = h;
    }

    /// Takes one accepted step that ends no later than `t_limit`.
    pub fn step<O: Ode>(&mut self, ode: &mut O, t_limit: f64) -> Result<StepInfo> {
        let mut h = min(min(self.h, t_limit - self.t), self.tol.h_max);
        // The step the controller wanted before any retake aimed at an event.
        let mut h_proposal: Option<f64> = None;
        let mut aimed: Option<usize> = None;
        // A crossing predicted inside the step: end the first trial just past
        // it, so that it neither fails the error test across the kink nor needs
        // a second retake (the located crossing is then checked as usual).
        if let Some((i, tau)) = self.predict_event(h) {
            h_proposal = Some(h);
            aimed = Some(i);
            h = min(tau * (1.0 + 0.5 * EVENT_LANDING), h);
        }
        loop {
            if h < self.tol.h_min && self.t + h < t_limit {
                return Err(SolverError::StepSizeTooSmall {
                    t_s: self.t,
                    h_s: h,
                });
            }
            let err = self.trial(ode, h);
            if !err.is_finite() || self.y1.iter().any(|v| !v.is_finite()) {
                if h > self.tol.h_min * 16.0 {
                    // A blow-up inside one over-long trial step: retry smaller
                    // before declaring the solution non-finite.
                    self.stats.rejected_steps += 1;
                    h *= 0.1;
                    continue;
                }
                return Err(SolverError::NonFinite { t_s: self.t });
            }
            // err^EXPO1 (and below the PI term) from one logarithm per trial.
            let log_err = log2_pos(max(err, 1e-300));
            if err > 1.0 {
                self.stats.rejected_steps += 1;
                let fac11 = exp2(EXPO1 * log_err);
                let h_err = h / min(FAC_MIN_INV, fac11 / SAFE);
                // A trial that failed because it straddles a contact switch:
                // aim the retry at the switch (located roughly on the trial's
                // own dense output) instead of only shrinking blindly.
                let h_event = if self.n_events > 0 && aimed.is_none() {
                    self.build_dense(h);
                    ode.events(
                        self.t + h,
                        &self.y1,
                        &self.k[6],
                        &mut self.g1,
                        &mut self.dg1,
                    );
                    self.first_event(ode, h)
                        .filter(|&(_, theta)| theta < 1.0 - EVENT_LANDING)
                        .map(|(i, theta)| (i, theta * h))
                } else {
                    None
                };
                match h_event {
                    Some((i, he)) if he > 0.5 * h_err => {
                        h_proposal.get_or_insert(max(h_err, he));
                        aimed = Some(i);
                        h = he;
                    }
                    _ => {
                        h = h_err;
                        aimed = None;
                    }
                }
                continue;
            }
            // Passed the error test: look for events inside (t, t + h].
            self.build_dense(h);
            if self.n_events > 0 {
                let t1 = self.t + h;
                ode.events(t1, &self.y1, &self.k[6], &mut self.g1, &mut self.dg1);
                if let Some((i, theta)) = self.first_event(ode, h) {
                    if theta < 1.0 - EVENT_LANDING {
                        // Retake the step to end just past the event, so the
                        // retaken step holds the crossing within its last
                        // EVENT_LANDING / 2.
                        self.stats.event_retakes += 1;
                        h_proposal.get_or_insert(h);
                        aimed = Some(i);
                        h *= min(theta / (1.0 - 0.5 * EVENT_LANDING), 1.0);
                        continue;
                    }
                }
            }
            // Every crossing inside the accepted step (the one it was aimed
            // at, and any that the landing tolerance let it straddle at its
            // start); `last_events` locates them.
            self.crossings.clear();
            for i in 0..self.n_events {
                let (g0, g1) = (self.g0[i], self.g1[i]);
                if g0 != 0.0 && (g0.signum() != g1.signum() || g1 == 0.0) {
                    self.crossings.push((i, g0));
                }
            }
            // Accept.
            let t0 = self.t;
            self.t += h;
            if (t_limit - self.t).abs() <= 4.0 * f64::EPSILON * max(t_limit.abs(), 1.0) {
                self.t = t_limit;
            }
            std::mem::swap(&mut self.y, &mut self.y1);
            self.k.swap(0, 6);
            std::mem::swap(&mut self.g0, &mut self.g1);
            std::mem::swap(&mut self.dg_prev, &mut self.dg1);
            std::mem::swap(&mut self.dg0, &mut self.dg_prev);
            self.h_prev = h;
            self.stats.steps += 1;
            self.stats.events += self.crossings.len() as u64;
            // Step-size proposal (PI control).
            let fac = (exp2(EXPO1 * log_err - BETA * self.log_fac_old) / SAFE)
                .clamp(FAC_MAX_INV, FAC_MIN_INV);
            self.log_fac_old = max(log_err, LOG2_FAC_OLD_MIN);
            let h_next = h / fac;
            self.h = min(
                match h_proposal {
                    Some(hp) => max(hp, h_next),
                    None => h_next,
                },
                self.tol.h_max,
            );
            return Ok(StepInfo {
                t0,
                t1: self.t,
                events: self.crossings.len(),
            });
        }
    }

    /// The earliest crossing within `h` predicted by a quadratic Taylor model of
    /// each event function (`g''` by a finite difference over the last step).
    fn predict_event(&self, h: f64) -> Option<(usize, f64)> {
        if self.n_events == 0 || self.h_prev <= 0.0 {
            return None;
        }
        let mut best: Option<(usize, f64)> = None;
        for i in 0..self.n_events {
            let (g, d) = (self.g0[i], self.dg0[i]);
            // Only surfaces being approached, and close enough to matter.
            if g == 0.0 || g.signum() == d.signum() || g.abs() > 2.0 * h * d.abs() {
                continue;
            }
            let dd = (d - self.dg_prev[i]) / self.h_prev;
            // Smallest positive root of g + d tau + dd tau^2 / 2.
            let (a, b, c) = (0.5 * dd, d, g);
            let tau = if a.abs() * h <= 1e-3 * b.abs() {
                -c / b
            } else {
                let disc = b * b - 4.0 * a * c;
                if disc < 0.0 {
                    continue;
                }
                let q = -0.5 * (b + b.signum() * disc.sqrt());
                let r1 = q / a;
                let r2 = c / q;
                match (r1 > 0.0, r2 > 0.0) {
                    (true, true) => min(r1, r2),
                    (true, false) => r1,
                    (false, true) => r2,
                    (false, false) => continue,
                }
            };
            if tau > EVENT_LANDING * h && tau < h && best.is_none_or(|b| tau < b.1) {
                best = Some((i, tau));
            }
        }
        best
    }

    /// The earliest event crossing in the trial step, as `(event, theta)`.
    fn first_event<O: Ode>(&mut self, ode: &mut O, h: f64) -> Option<(usize, f64)> {
        let mut best: Option<(usize, f64)> = None;
        let mut ybuf = std::mem::take(&mut self.ytmp);
        for i in 0..self.n_events {
            let (g0, g1, d0, d1) = (self.g0[i], self.g1[i], self.dg0[i] * h, self.dg1[i] * h);
            let limit = best.map_or(1.0, |b| b.1);
            // Where to look: a sign change between the ends, or a pair of
            // crossings inside the step (same signs at the ends).
            let bracket = if g0 == 0.0 {
                None // on the surface at the start: that crossing was handled
            } else if g0.signum() != g1.signum() || g1 == 0.0 {
                Some(min(limit, 1.0))
            } else if min(g0.abs(), g1.abs()) <= 0.15 * (d0.abs() + d1.abs()) {
                hermite_dip(g0, g1, d0, d1).and_then(|theta_dip| {
                    if theta_dip >= limit {
                        return None;
                    }
                    let g = self.event_on_dense(ode, i, theta_dip, &mut ybuf);
                    (g.signum() != g0.signum()).then_some(theta_dip)
                })
            } else {
                None
            };
            let Some(hi) = bracket else { continue };
            let theta = self.illinois(ode, i, (0.0, g0), hi, 0.05 * EVENT_LANDING, &mut ybuf);
            if theta <= EVENT_LANDING {
                // A crossing at the very start of the step: it is the switch we
                // just landed on (or one that happened there), not a new one.
                continue;
            }
            if best.is_none_or(|b| theta < b.1) {
                best = Some((i, theta));
            }
        }
        self.ytmp = ybuf;
        best
    }

    /// Event `i` on the dense output at `theta`: only the components the event
    /// reads are interpolated into `ybuf`.
    #[inline]
    fn event_on_dense<O: Ode>(&self, ode: &mut O, i: usize, theta: f64, ybuf: &mut [f64]) -> f64 {
        match ode.event_components(i) {
            Some(cols) => dense_eval_at(&self.r, theta, cols, ybuf),
            None => {
                let m = ode.event_dim().min(ybuf.len());
                dense_eval(&self.r, theta, &mut ybuf[..m]);
            }
        }
        ode.event(i, self.dense_t0 + theta * self.dense_h, ybuf)
    }

    /// Illinois (modified regula falsi) on `[a, hi]` for event `i` on the
    /// dense output, to a bracket of width `tol` (in units of the step);
    /// returns the end of the final bracket that lies past the crossing.
    fn illinois<O: Ode>(
        &self,
        ode: &mut O,
        i: usize,
        (a0, ga): (f64, f64),
        hi: f64,
        tol: f64,
        ybuf: &mut [f64],
    ) -> f64 {
        let eval =
            |theta: f64, ode: &mut O, buf: &mut [f64]| self.event_on_dense(ode, i, theta, buf);
        let (mut a, mut fa) = (a0, ga);
        let (mut b, mut fb) = (hi, eval(hi, ode, ybuf));
        if fb == 0.0 || fa.signum() == fb.signum() {
            // On the surface, or the dense output disagrees with the end
            // values (round-off at a graze): take the bracket's end.
            return b;
        }
        let mut side = 0;
        for _ in 0..100 {
            let c = (a * fb - b * fa) / (fb - fa);
            let fc = eval(c, ode, ybuf);
            if fc == 0.0 {
                return c;
            }
            if fc.signum() == fb.signum() {
                b = c;
                fb = fc;
                if side == -1 {
                    fa *= 0.5;
                }
                side = -1;
            } else {
                a = c;
                fa = fc;
                if side == 1 {
                    fb *= 0.5;
                }
                side = 1;
            }
            if b - a <= tol {
                break;
            }
        }
        b
    }
}

/// Evaluates the DOPRI5 dense output at `theta` in `[0, 1]`.
#[inline]
fn dense_eval(r: &[Vec<f64>; 5], theta: f64, out: &mut [f64]) {
    let n = out.len();
    let s1 = 1.0 - theta;
    let (r0, r1, r2, r3, r4) = (&r[0][..n], &r[1][..n], &r[2][..n], &r[3][..n], &r[4][..n]);
    for i in 0..n {
        out[i] = r0[i] + theta * (r1[i] + s1 * (r2[i] + theta * (r3[i] + s1 * r4[i])));
    }
}

/// Evaluates the dense output at `theta` for the components `cols` only,
/// each into its own place in `out` (the same arithmetic as [`dense_eval`]).
#[inline]
fn dense_eval_at(r: &[Vec<f64>; 5], theta: f64, cols: &[usize], out: &mut [f64]) {
    let s1 = 1.0 - theta;
    for &i in cols {
        out[i] = r[0][i] + theta * (r[1][i] + s1 * (r[2][i] + theta * (r[3][i] + s1 * r[4][i])));
    }
}

/// For a cubic Hermite model of `g` on `[0, 1]` with end values `g0`, `g1`
/// (same sign) and end slopes `d0`, `d1` (already times `h`), the position of
/// its extremum that lies across zero, if any.
fn hermite_dip(g0: f64, g1: f64, d0: f64, d1: f64) -> Option<f64> {
    let a = 6.0 * (g0 - g1) + 3.0 * (d0 + d1);
    let b = -6.0 * (g0 - g1) - 4.0 * d0 - 2.0 * d1;
    let c = d0;
    let p = |t: f64| {
        let t2 = t * t;
        let t3 = t2 * t;
        (2.0 * t3 - 3.0 * t2 + 1.0) * g0
            + (t3 - 2.0 * t2 + t) * d0
            + (-2.0 * t3 + 3.0 * t2) * g1
            + (t3 - t2) * d1
    };
    let mut roots = [f64::NAN; 2];
    if a.abs() < 1e-300 {
        if b.abs() > 1e-300 {
            roots[0] = -c / b;
        }
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc >= 0.0 {
            let sq = disc.sqrt();
            let q = -0.5 * (b + b.signum() * sq);
            roots[0] = q / a;
            if q != 0.0 {
                roots[1] = c / q;
            }
        }
    }
    roots
        .iter()
        .copied()
        .filter(|t| t.is_finite() && *t > 0.0 && *t < 1.0)
        .filter(|&t| p(t).signum() != g0.signum())
        .min_by(f64::total_cmp)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Harmonic oscillator y'' = -y, exact solution (cos t, -sin t).
    struct Harmonic;
    impl Ode for Harmonic {
        fn dim(&self) -> usize {
            2
        }
        fn rhs(&mut self, _t: f64, y: &[f64], dy: &mut [f64]) {
            dy[0] = y[1];
            dy[1] = -y[0];
        }
    }

    fn tol(rtol: f64) -> Tolerances {
        Tolerances {
            rtol,
            atol: vec![rtol; 2],
            h_min: 1e-14,
            h_max: 1.0,
        }
    }

    #[test]
    fn dense_output_is_accurate_inside_steps() {
        let mut ode = Harmonic;
        let mut int = Dopri5::new(&mut ode, 0.0, &[1.0, 0.0], 0.1, tol(1e-10));
        let mut y = [0.0; 2];
        let mut worst: f64 = 0.0;
        while int.t() < 10.0 {
            let info = int.step(&mut ode, 10.0).expect("step");
            for k in 1..10 {
                let t = info.t0 + (info.t1 - info.t0) * f64::from(k) / 10.0;
                int.dense(t, &mut y);
                worst = worst
                    .max((y[0] - t.cos()).abs())
                    .max((y[1] + t.sin()).abs());
            }
        }
        assert!(worst < 1e-8, "dense output error {worst}");
    }

    #[test]
    fn hermite_dip_finds_a_dip_below_zero() {
        // g = (t - 0.5)^2 - 0.01 on [0, 1]: g0 = g1 = 0.24, slopes -1 and +1.
        let theta = hermite_dip(0.24, 0.24, -1.0, 1.0).expect("dip");
        assert!((theta - 0.5).abs() < 1e-12);
        assert!(hermite_dip(0.24, 0.24, -0.1, 0.1).is_none());
    }
}
