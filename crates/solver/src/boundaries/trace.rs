//! Pseudo-arclength continuation of an augmented system's solution curve
//! in `(X, aux, Omega, p)`: tangent predictor, Newton corrector on the
//! system bordered by the arclength equation, step control from the
//! curve's geometry (the corrector's distance and the tangent's turn, as
//! the harmonic balance's branch does), and the curve's ends (it
//! leaves the box of the two ranges, closes on itself, or the corrector
//! fails at the smallest step).
//!
//! The metric measures Omega and `p` in units of their ranges, the orbit's
//! coefficients in units of three times their RMS at the start (at least
//! 1 um; the mean's in ten times that) and the auxiliary phase in units of
//! a period, so that a step of `ds` moves the curve by at most `ds` of the
//! box in the plane.

use super::bordered::Eval;
use super::family::Family;
use super::systems::System;
use crate::error::{Result, SolverError};
use crate::hbm::continuation::overshoot;
use crate::hbm::HbmCost;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

const NEWTON_MAX: usize = 12;
/// Converged when the scaled Newton step is below this.
const STEP_TOL: f64 = 1e-10;
/// The weight of the mean's coefficients in the metric, relative to the
/// vibration's (see [`Tracer::start`]).
const MEAN_WEIGHT: f64 = 1e-2;
/// Steps in a row below a thousandth of the largest after which a curve
/// ends as failed: it has moved by less than a twentieth of its largest
/// step, where its corrector converges only at the smallest steps (near
/// Ω 0.939 on the page's compound box, a period-doubling curve took 8 to
/// 11 iterations at 1e-5 and failed at twice that, 500 times over).
pub(crate) const CRAWL_STEPS: u32 = 50;

/// The box the curve is traced in: `(omega_lo, omega_hi, p_lo, p_hi)`.
pub(crate) type Bounds = (f64, f64, f64, f64);

/// One traced point.
#[derive(Debug, Clone)]
pub(crate) struct Traced {
    /// The unknowns.
    pub(crate) z: Vec<f64>,
    /// See [`Eval::side`].
    pub(crate) side: (f64, f64),
    /// See [`Eval::cusp`].
    pub(crate) cusp: f64,
    /// See [`Eval::others_stable`].
    pub(crate) others_stable: Option<bool>,
}

/// How one direction of a curve ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TraceEnd {
    /// It left the box of the two ranges.
    LeftRange,
    /// It came back to its start.
    Closed,
    /// The corrector failed at the smallest step, or could only crawl:
    /// [`CRAWL_STEPS`] steps in a row below a thousandth of the largest.
    Failed,
    /// It used its point budget.
    Budget,
}

/// One step's outcome.
#[derive(Debug, Clone)]
pub(crate) enum Stepped {
    /// A new point inside the box.
    Point(Traced),
    /// The end of this direction, with the last point (clipped to the box)
    /// if there is one.
    End(TraceEnd, Option<Traced>),
}

/// A curve being traced in one direction.
#[derive(Debug, Clone)]
pub(crate) struct Tracer {
    pub(crate) system: System,
    metric: Vec<f64>,
    bounds: Bounds,
    z: Vec<f64>,
    t: Vec<f64>,
    /// The tangent at the start (the other direction starts along its opposite).
    t0: Vec<f64>,
    start: Vec<f64>,
    /// The direction this tracer set out in from `start`: a curve that
    /// closes comes back to `start` heading this way.
    heading: Vec<f64>,
    ds: f64,
    ds_max: f64,
    steps: usize,
    max_steps: usize,
    /// Accepted steps in a row below a thousandth of `ds_max`.
    crawl: u32,
    last: Option<Traced>,
    /// Newton iterations so far.
    pub(crate) newton_iterations: u64,
}

/// A curve's point budget in each direction at the largest step
/// `ds_max`: twelve times across the box at that step; more is a curve
/// wound up where its conditions degenerate.
pub(crate) fn max_steps(ds_max: f64) -> usize {
    (12.0 / ds_max) as usize + 100
}

fn rms(v: &[f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt()
}

impl Tracer {
    /// A tracer for `system` from the guess `z0`, first corrected at fixed
    /// `p`; `m` is the number of coordinates (the mean's coefficients are
    /// left out of the scale), `ds_max` the largest step in the box.
    pub(crate) fn start(
        fam: &mut Family,
        mut system: System,
        z0: Vec<f64>,
        m: usize,
        bounds: Bounds,
        ds_max: f64,
    ) -> Result<(Self, Traced)> {
        let n = z0.len();
        let n_aux = system.n_aux();
        let nx = n - 2 - n_aux;
        let scale = (3.0 * rms(&z0[m.min(nx)..nx])).max(1.0);
        let mut metric = vec![1.0 / (scale * scale * nx as f64); n];
        // The mean's coefficients follow the static deflection, which moves
        // one for one with the backlash (and with the torque): measured
        // like the vibration, a curve at constant Omega in backlash was
        // some 60 times longer than its span in the box and ran out of
        // points at a tenth of a micrometre a step. They are measured in
        // ten times the vibration's unit. Not left out: where a curve
        // turns a corner (a period doubling at constant Omega meeting one
        // with contact, on the gear pair near Omega 1.831, backlash 7
        // um), the mean moving along both sides is what lets the
        // corrector cross to the other side.
        for w in metric.iter_mut().take(m.min(nx)) {
            *w *= MEAN_WEIGHT;
        }
        for w in metric.iter_mut().skip(nx).take(n_aux) {
            *w = 1.0 / (4.0 * PI * PI);
        }
        let (om, pr) = (bounds.1 - bounds.0, bounds.3 - bounds.2);
        metric[n - 2] = 1.0 / (om * om);
        metric[n - 1] = 1.0 / (pr * pr);
        let mut tracer = Tracer {
            system: system.clone(),
            metric,
            bounds,
            z: z0.clone(),
            t: vec![0.0; n],
            t0: vec![0.0; n],
            start: z0.clone(),
            heading: vec![0.0; n],
            ds: 0.25 * ds_max,
            ds_max,
            steps: 0,
            max_steps: max_steps(ds_max),
            crawl: 0,
            last: None,
            newton_iterations: 0,
        };
        // At fixed p: the arclength row is the unit vector of p.
        let mut row = vec![0.0; n];
        row[n - 1] = 1.0;
        let (z, ev) = tracer.correct(fam, &z0, &row)?;
        tracer.system.accept();
        system = tracer.system.clone();
        // The tangent: the null vector of the system's Jacobian.
        let mut sq = DMatrix::zeros(n, n);
        sq.view_mut((0, 0), (n - 1, n)).copy_from(&ev.jac);
        // A singular value decomposition: some five factorizations' work.
        fam.spend(5.0 * HbmCost::factor(n));
        let svd = sq.svd(false, true);
        let vt = svd.v_t.ok_or_else(|| SolverError::Singular {
            what: "tangent of a boundary curve".into(),
        })?;
        let k = (0..n)
            .min_by(|&a, &b| svd.singular_values[a].total_cmp(&svd.singular_values[b]))
            .unwrap_or(0);
        let mut t: Vec<f64> = vt.row(k).iter().copied().collect();
        tracer.normalize(&mut t);
        tracer.system = system;
        tracer.z = z.clone();
        tracer.start = z;
        tracer.t0 = t.clone();
        tracer.heading = t.clone();
        tracer.t = t;
        let first = tracer.traced(&ev);
        tracer.last = Some(first.clone());
        Ok((tracer, first))
    }

    /// The same curve from the same start, in the other direction.
    pub(crate) fn reversed(&self, first: &Traced) -> Self {
        let mut r = self.clone();
        r.z = first.z.clone();
        r.start = first.z.clone();
        r.t = self.t0_reversed();
        r.heading = r.t.clone();
        r.ds = 0.25 * self.ds_max;
        r.steps = 0;
        r.crawl = 0;
        r.last = Some(first.clone());
        r.newton_iterations = 0;
        r
    }

    fn t0_reversed(&self) -> Vec<f64> {
        self.t0.iter().map(|v| -v).collect()
    }

    fn normalize(&self, t: &mut [f64]) {
        let norm = (0..t.len())
            .map(|i| self.metric[i] * t[i] * t[i])
            .sum::<f64>()
            .sqrt();
        for v in t.iter_mut() {
            *v /= norm;
        }
    }

    fn traced(&self, ev: &Eval) -> Traced {
        Traced {
            z: self.z.clone(),
            side: ev.side,
            cusp: ev.cusp,
            others_stable: ev.others_stable,
        }
    }

    fn inside(&self, z: &[f64]) -> bool {
        let n = z.len();
        let (om, p) = (z[n - 2], z[n - 1]);
        let (a, b, c, d) = self.bounds;
        let tol = 1e-12;
        om >= a - tol * (b - a)
            && om <= b + tol * (b - a)
            && p >= c - tol * (d - c)
            && p <= d + tol * (d - c)
    }

    /// Where a step of `ds` along the tangent crosses an edge of `p`:
    /// the arclength to it and the edge's value (a length of 0 or less: the
    /// point is on the edge and the curve heads out).
    fn edge_step(&self, ds: f64) -> Option<(f64, f64)> {
        let n = self.z.len();
        let (_, _, lo, hi) = self.bounds;
        let (p, tp) = (self.z[n - 1], self.t[n - 1]);
        let ahead = p + ds * tp;
        let edge = if ahead < lo && tp < 0.0 {
            lo
        } else if ahead > hi && tp > 0.0 {
            hi
        } else {
            return None;
        };
        Some(((edge - p) / tp, edge))
    }

    /// Newton on the system bordered by `row . (z - pred) = 0`.
    fn correct(&mut self, fam: &mut Family, pred: &[f64], row: &[f64]) -> Result<(Vec<f64>, Eval)> {
        let n = pred.len();
        let mut z = pred.to_vec();
        let mut last_res = f64::NAN;
        for _ in 1..=NEWTON_MAX {
            let ev = self.system.eval(fam, &z, false)?;
            self.newton_iterations += 1;
            let mut a = DMatrix::zeros(n, n);
            a.view_mut((0, 0), (n - 1, n)).copy_from(&ev.jac);
            let mut g = DVector::zeros(n);
            g.rows_mut(0, n - 1).copy_from(&ev.res);
            for i in 0..n {
                a[(n - 1, i)] = row[i];
                g[n - 1] += row[i] * (z[i] - pred[i]);
            }
            last_res = ev.res.amax();
            fam.factored(n);
            let dz = crate::dense::Lu::new(a)
                .solve(&g)
                .ok_or_else(|| SolverError::Singular {
                    what: format!("boundary corrector at Omega = {}", z[n - 2]),
                })?;
            let step = (0..n)
                .map(|i| dz[i].abs() * self.metric[i].sqrt())
                .fold(0.0, f64::max);
            for i in 0..n {
                z[i] -= dz[i];
            }
            if !step.is_finite() {
                break;
            }
            if step <= STEP_TOL {
                let ev = self.system.eval(fam, &z, true)?;
                if ev.res.amax() <= 1e-6 * ev.scale {
                    return Ok((z, ev));
                }
                last_res = ev.res.amax();
                break;
            }
        }
        Err(SolverError::NotConverged {
            omega: z[n - 2],
            residual: last_res,
            iterations: NEWTON_MAX,
        })
    }

    /// The tangent at a converged point: `[J; row] t = [0; 1]`, in the
    /// metric's unit length, oriented like the last one.
    fn tangent(&self, ev: &Eval, row: &[f64]) -> Option<Vec<f64>> {
        let n = row.len();
        let mut a = DMatrix::zeros(n, n);
        a.view_mut((0, 0), (n - 1, n)).copy_from(&ev.jac);
        for i in 0..n {
            a[(n - 1, i)] = row[i];
        }
        let mut e = DVector::zeros(n);
        e[n - 1] = 1.0;
        let t = crate::dense::Lu::new(a).solve(&e)?;
        let mut t: Vec<f64> = t.iter().copied().collect();
        self.normalize(&mut t);
        let dot: f64 = (0..n).map(|i| self.metric[i] * t[i] * self.t[i]).sum();
        if dot < 0.0 {
            t.iter_mut().for_each(|v| *v = -*v);
        }
        Some(t)
    }

    /// One predictor-corrector step.
    ///
    /// The step length follows the curve's geometry: the distance from the
    /// predictor to the corrected point (`d`, in the metric) and the turn
    /// of the tangent (`alpha`) give the factor `f` by which the step
    /// overshot its nominal size, as on the harmonic balance's branch
    /// ([`overshoot`]);
    /// `f > 2` retries with `ds / f`, otherwise the next step is `ds / f`,
    /// growing by at most 2, up to `ds_max`. A failed corrector halves the
    /// step. The corrector's iterations do not steer it: near the test
    /// functions' noise floor they stay at 5 or 6 at any step, which held
    /// some curves at the smallest step until they ran out of points.
    pub(crate) fn step(&mut self, fam: &mut Family) -> Stepped {
        let n = self.z.len();
        let ds_min = 1e-4 * self.ds_max;
        if self.steps >= self.max_steps {
            return Stepped::End(TraceEnd::Budget, None);
        }
        loop {
            let ds = self.ds;
            let mut pred: Vec<f64> = (0..n).map(|i| self.z[i] + ds * self.t[i]).collect();
            let mut row: Vec<f64> = (0..n).map(|i| self.metric[i] * self.t[i]).collect();
            // A step that would leave the box across an edge of `p` lands
            // on the edge, `p` held there: where the edge is the key's own
            // limit (backlash 0) a point beyond it cannot be evaluated, so
            // the step would fail at every size and the curve end as a
            // corrector failure a hair inside the box.
            let edge = self.edge_step(ds);
            match edge {
                Some((s, _)) if s <= 0.0 => return Stepped::End(TraceEnd::LeftRange, None),
                Some((s, e)) => {
                    pred = (0..n).map(|i| self.z[i] + s * self.t[i]).collect();
                    pred[n - 1] = e;
                    row = vec![0.0; n];
                    row[n - 1] = 1.0;
                }
                None => {}
            }
            let outcome = self.correct(fam, &pred, &row).and_then(|(z, ev)| {
                fam.factored(n);
                let t = self
                    .tangent(&ev, &row)
                    .ok_or_else(|| SolverError::Singular {
                        what: "boundary tangent".into(),
                    })?;
                Ok((z, ev, t))
            });
            match outcome {
                Ok((z, ev, t)) => {
                    let cos: f64 = (0..n).map(|i| self.metric[i] * t[i] * self.t[i]).sum();
                    let alpha = cos.clamp(-1.0, 1.0).acos();
                    let dist = (0..n)
                        .map(|i| self.metric[i] * (z[i] - pred[i]).powi(2))
                        .sum::<f64>()
                        .sqrt();
                    let f = overshoot(dist, alpha);
                    if f > 2.0 && ds > ds_min {
                        self.ds = (ds / f.min(4.0)).max(ds_min);
                        continue;
                    }
                    self.ds = (ds / f).clamp(ds_min, self.ds_max);
                    if ds < 1e-3 * self.ds_max {
                        self.crawl += 1;
                        if self.crawl >= CRAWL_STEPS {
                            return Stepped::End(TraceEnd::Failed, None);
                        }
                    } else {
                        self.crawl = 0;
                    }
                    self.steps += 1;
                    self.system.accept();
                    self.z = z;
                    self.t = t;
                    let point = self.traced(&ev);
                    if edge.is_some() {
                        return Stepped::End(TraceEnd::LeftRange, Some(point));
                    }
                    if !self.inside(&self.z) {
                        let clipped = self.clip(point);
                        return Stepped::End(TraceEnd::LeftRange, Some(clipped));
                    }
                    let closes = self.steps > 8 && self.passes_start(&point.z, ds);
                    self.last = Some(point.clone());
                    if closes {
                        let mut closing = point;
                        closing.z = self.start.clone();
                        return Stepped::End(TraceEnd::Closed, Some(closing));
                    }
                    return Stepped::Point(point);
                }
                Err(_) if ds > ds_min => {
                    self.ds = (ds * 0.5).max(ds_min);
                }
                Err(_) => return Stepped::End(TraceEnd::Failed, None),
            }
        }
    }

    /// Whether the step just taken, from the last point to `z` (of length
    /// `ds`), passes the start heading the way this tracer set out: the
    /// start lies within a quarter step of the segment and the tangent
    /// points along the start's heading. Nearness alone is not enough:
    /// near a cusp the two fold branches run side by side, less than a
    /// step apart and in opposite directions, and a nearness test closed
    /// the curve from one branch to the other, tracing it twice (the gear
    /// pair's te_um trace at 20 points a step).
    fn passes_start(&self, z: &[f64], ds: f64) -> bool {
        let Some(last) = &self.last else { return false };
        let n = z.len();
        let dot = |a: &dyn Fn(usize) -> f64, b: &dyn Fn(usize) -> f64| {
            (0..n).map(|i| self.metric[i] * a(i) * b(i)).sum::<f64>()
        };
        let heading = dot(&|i| self.t[i], &|i| self.heading[i]);
        if heading <= 0.0 {
            return false;
        }
        let seg = |i: usize| z[i] - last.z[i];
        let rel = |i: usize| self.start[i] - last.z[i];
        let len2 = dot(&seg, &seg);
        let s = if len2 > 0.0 {
            (dot(&rel, &seg) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let off = |i: usize| rel(i) - s * seg(i);
        dot(&off, &off).sqrt() < 0.25 * ds
    }

    /// The point where the segment from the last point to `p` leaves the
    /// box (linear in Omega and p).
    fn clip(&self, p: Traced) -> Traced {
        let Some(last) = &self.last else { return p };
        let n = p.z.len();
        let (a0, b0) = (last.z[n - 2], last.z[n - 1]);
        let (a1, b1) = (p.z[n - 2], p.z[n - 1]);
        let (lo, hi, plo, phi) = self.bounds;
        let mut s: f64 = 1.0;
        let frac = |from: f64, to: f64, edge: f64| (edge - from) / (to - from);
        if a1 > hi {
            s = s.min(frac(a0, a1, hi));
        }
        if a1 < lo {
            s = s.min(frac(a0, a1, lo));
        }
        if b1 > phi {
            s = s.min(frac(b0, b1, phi));
        }
        if b1 < plo {
            s = s.min(frac(b0, b1, plo));
        }
        let s = s.clamp(0.0, 1.0);
        let mut out = p;
        out.z = (0..n)
            .map(|i| last.z[i] + s * (out.z[i] - last.z[i]))
            .collect();
        out
    }
}
