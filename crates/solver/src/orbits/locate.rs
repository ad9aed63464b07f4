//! Locating a fold or a period doubling between two points of a shooting
//! branch: the Illinois method on a test function over the arclength (the
//! tangent's Omega component for a fold, the real multiplier nearest -1
//! plus one for a period doubling), each trial point corrected onto the
//! branch on the hyperplane normal to the previous tangent.

use super::replay::Step;
use super::{Cursor, ShootPoint, ShootingContinuation, Solved};
use crate::bifurcation::Bifurcation;
use crate::shooting::floquet::Multipliers;

impl ShootingContinuation {
    /// The point at arclength `s` from the cursor along its tangent, solved.
    pub(super) fn at(&mut self, c: &Cursor, s: f64) -> Step<Option<Solved>> {
        let pred: Vec<f64> = c.y.iter().zip(&c.tangent).map(|(y, t)| y + s * t).collect();
        self.correct(&pred, &c.tangent, c.period, c.jac.as_ref())
    }

    /// Locates a fold between the cursor and `end` (Illinois on the
    /// tangent's Omega component over the arclength): the solution there,
    /// which the caller labels.
    pub(super) fn locate(&mut self, c: &Cursor, end: &Solved) -> Step<Option<Solved>> {
        let n = c.y.len() - 1;
        let ds = c.ds;
        let f = |me: &Self, s: &Solved| me.tangent(s, &c.tangent).map(|t| t[n]);
        let (mut a, mut fa) = (0.0, c.tangent[n]);
        let Some(fb0) = f(self, end) else {
            return Ok(None);
        };
        let (mut b, mut fb) = (ds, fb0);
        let (mut best, mut side) = (end.clone(), 0);
        for _ in 0..30 {
            let s = (a * fb - b * fa) / (fb - fa);
            let Some(sol) = self.at(c, s)? else { break };
            let Some(fs) = f(self, &sol) else { break };
            best = sol;
            if fs.abs() <= 1e-7 {
                break;
            }
            if fs.signum() == fb.signum() {
                b = s;
                fb = fs;
                if side == -1 {
                    fa *= 0.5;
                }
                side = -1;
            } else {
                a = s;
                fa = fs;
                if side == 1 {
                    fb *= 0.5;
                }
                side = 1;
            }
            if (b - a).abs() <= 1e-9 * ds.max(1e-300) {
                break;
            }
        }
        Ok(Some(best))
    }

    /// Locates a period doubling between the cursor and `end` (Illinois on
    /// the real multiplier nearest -1, plus one, until the bracket spans
    /// less than 1e-7 in Omega); the point and its solution.
    pub(super) fn locate_pd(
        &mut self,
        c: &Cursor,
        end: &Solved,
    ) -> Step<Option<(ShootPoint, Solved)>> {
        let ds = c.ds;
        let f = |s: &Solved| {
            Multipliers::of(&s.monodromy).and_then(|m| {
                m.values
                    .iter()
                    .filter(|v| v.im.abs() <= 1e-9 * v.norm() && v.re < 0.0)
                    .map(|v| v.re + 1.0)
                    .min_by(|x, y| x.abs().total_cmp(&y.abs()))
            })
        };
        let (_, start) = self.evaluate(&c.y, c.period)?;
        let (Some(fa0), Some(fb0)) = (f(&start), f(end)) else {
            return Ok(None);
        };
        let (mut a, mut fa, mut oa) = (0.0, fa0, self.omega_of(&c.y));
        let (mut b, mut fb, mut ob) = (ds, fb0, self.omega_of(&end.y));
        let mut best = end.clone();
        let mut side = 0;
        if fa.signum() == fb.signum() {
            // The count changed, but not through the nearest real multiplier:
            // label the end point.
            let p = self.emit(end, c.period, c.piece, Some(Bifurcation::PeriodDoubling))?;
            return Ok(Some((p, end.clone())));
        }
        for _ in 0..40 {
            if (ob - oa).abs() <= 1e-7 {
                break;
            }
            let s = (a * fb - b * fa) / (fb - fa);
            let Some(sol) = self.at(c, s)? else { break };
            let Some(fs) = f(&sol) else { break };
            let os = self.omega_of(&sol.y);
            best = sol;
            if fs.abs() <= 1e-10 {
                break;
            }
            if fs.signum() == fb.signum() {
                (b, fb, ob) = (s, fs, os);
                if side == -1 {
                    fa *= 0.5;
                }
                side = -1;
            } else {
                (a, fa, oa) = (s, fs, os);
                if side == 1 {
                    fb *= 0.5;
                }
                side = 1;
            }
        }
        let p = self.emit(&best, c.period, c.piece, Some(Bifurcation::PeriodDoubling))?;
        Ok(Some((p, best)))
    }
}
