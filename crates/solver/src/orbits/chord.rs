//! The branch corrector's chord iterations: Newton on the bordered system
//! `G(Y) = 0`, `t . (Y - pred) = 0` with the last solved point's Jacobian
//! `[Phi - I, dG/dOmega / W]` (its monodromy and derivative, already
//! integrated there), updated by Broyden's rank-one formula after each
//! step, so that an iterate costs one plain integration of the map instead
//! of one with the 2m tangent vectors and two more for `dG/dOmega`. Once
//! the residual meets the tolerance the monodromy and `dG/dOmega` are
//! integrated at the converged point itself: its multipliers (stability,
//! the bifurcation tests) and its tangent are the point's own. A chord that
//! does not halve the residual in a step gives up, and the caller corrects
//! from the same prediction by full Newton (the monodromy at every
//! iterate). The chord converges linearly where Newton does
//! quadratically, so the step-size rule counts two of its iterations as
//! one of Newton's (`CHORD_EASY`): otherwise the steps stop growing and the
//! page's 300 points end at Omega 0.22 instead of 0.53 on the default set.

use super::replay::{Halt, Step};
use super::{newton_rhs, ShootingContinuation, Solved};
use crate::shooting::Reduced;
use nalgebra::DMatrix;

/// Chord iterations before giving up.
const CHORD_ITERATIONS: usize = 8;

/// Chord iterations after which the step still grows (full Newton: 3).
pub(super) const CHORD_EASY: usize = 6;

/// The residual's ratio over a step above which the chord gives up.
const SLOW: f64 = 0.5;

/// A solved point's monodromy and `dG/dOmega`: the chord's first matrix.
#[derive(Debug, Clone)]
pub(super) struct Jacobian {
    pub(super) monodromy: DMatrix<f64>,
    pub(super) g_omega: Vec<f64>,
}

impl Jacobian {
    pub(super) fn of(s: &Solved) -> Self {
        Jacobian {
            monodromy: s.monodromy.clone(),
            g_omega: s.g_omega.clone(),
        }
    }
}

fn norm2(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

impl ShootingContinuation {
    /// The chord corrector from `pred` on the hyperplane normal to `t` with
    /// `jac` as the first matrix; `None` if it gives up.
    pub(super) fn correct_chord(
        &mut self,
        pred: &[f64],
        t: &[f64],
        period: u32,
        jac: &Jacobian,
    ) -> Step<Option<Solved>> {
        let n = pred.len() - 1;
        if jac.monodromy.shape() != (n, n) || jac.g_omega.len() != n {
            return Ok(None);
        }
        let mut a = self.bordered(&jac.monodromy, &jac.g_omega, t);
        let mut y = pred.to_vec();
        // The last residual and the step taken from it.
        let mut last: Option<(Vec<f64>, Vec<f64>)> = None;
        for it in 0..CHORD_ITERATIONS {
            let omega = self.omega_of(&y);
            if !(0.01..=20.0).contains(&omega) {
                return Ok(None);
            }
            let g = match self.map(&y[..n], omega, period, false) {
                Ok((g, _)) => g,
                Err(Halt::Pause) => return Err(Halt::Pause),
                Err(Halt::Fail(_)) => return Ok(None),
            };
            self.stats.newton_iterations += 1;
            let red = Reduced::new(&self.model, omega);
            if red.mesh_norm_um(&g) <= self.residual_tol(&y[..n], omega) {
                return match self.evaluate(&y, period) {
                    Ok((_, mut solved)) => {
                        solved.iterations = it;
                        solved.chord = true;
                        Ok(Some(solved))
                    }
                    Err(Halt::Pause) => Err(Halt::Pause),
                    Err(Halt::Fail(_)) => Ok(None),
                };
            }
            if let Some((g_prev, s)) = last.take() {
                if norm2(&g) > SLOW * norm2(&g_prev) {
                    return Ok(None);
                }
                // Broyden's update of the residual's rows; the hyperplane's
                // row is exact.
                let ss: f64 = s.iter().map(|v| v * v).sum();
                if ss > 0.0 {
                    for r in 0..n {
                        let js: f64 = (0..=n).map(|col| a[(r, col)] * s[col]).sum();
                        let coef = (g[r] - g_prev[r] - js) / ss;
                        for (col, sc) in s.iter().enumerate() {
                            a[(r, col)] += coef * sc;
                        }
                    }
                }
            }
            let Some(dy) = crate::dense::Lu::new(a.clone()).solve(&newton_rhs(&g, t, &y, pred))
            else {
                return Ok(None);
            };
            if dy.iter().any(|v| !v.is_finite()) {
                return Ok(None);
            }
            let s: Vec<f64> = dy.iter().copied().collect();
            for (yi, d) in y.iter_mut().zip(&s) {
                *yi += d;
            }
            last = Some((g, s));
        }
        Ok(None)
    }
}
