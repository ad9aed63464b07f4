//! The first branch's pieces: where each ended and why, and the restarts
//! that cover the rest of the range, as the harmonic balance's branch has
//! them ([`crate::hbm::FrfContinuation::restarts`]).
//!
//! A piece leaving the range lands its last point on the edge it crossed
//! (Omega held there): it reached the range's far end, or it turned back
//! at a fold and left through the end it started from. A piece of the
//! first branch (the spec's period) that ends before the range is covered
//! (it turned back, stalled, lost its tangent or ran out of points) is
//! followed by a restart while part of the range is not covered: first
//! from the other end in the other direction, then inside the first gap
//! (at its middle, then a quarter and three quarters where no first orbit
//! is found), upward. A restart's first orbit is found at its Omega by
//! Newton from the static equilibrium, else after [`SETTLE_PERIODS`]
//! periods of the map from it (the transient), every integration through
//! the replayed map, so a restart pauses and resumes like any step. A
//! restarted piece ends where the range is covered. A gap where three
//! starts found no orbit (`not-followed`), or that remains after
//! [`MAX_RESTARTS`] (`restarts-used`), is left out and reported. Doubled branches end where they end (they rejoin,
//! double again or leave the range): they cover nothing.

use super::replay::{Halt, Step};
use super::{ns_count, pd_count, Cursor, Jacobian, ShootPoint, ShootingContinuation, Solved};
use crate::hbm::{LeftOut, LeftOutReason, PieceEnd, Restart};
use crate::shooting::floquet::Multipliers;
use crate::shooting::Reduced;
use crate::sweep::Direction;

/// Restarts of the first branch at most.
const MAX_RESTARTS: usize = 4;
/// Where in a gap (as a fraction of it) restarts try to start, in turn,
/// while no first orbit is found.
const GAP_STARTS: [f64; 3] = [0.5, 0.25, 0.75];
/// Periods of the map a restart integrates from rest before its Newton.
const SETTLE_PERIODS: u32 = 30;

/// What a step changes of the first branch's coverage: its spans,
/// restarts, parts left out and failed starts (restored when it pauses).
pub(super) type Coverage = (Vec<(u32, f64, f64)>, Vec<Restart>, Vec<LeftOut>, Vec<f64>);

impl ShootingContinuation {
    /// The first branch's automatic restarts, as the harmonic balance's
    /// ([`crate::hbm::FrfContinuation::restarts`]).
    pub fn restarts(&self) -> &[Restart] {
        &self.restarts
    }

    /// Parts of the range the first branch does not cover, and why.
    pub fn left_out(&self) -> &[LeftOut] {
        &self.left_out
    }

    /// Whether every branch has ended and the first one covers the whole
    /// range (its pieces, restarts included, reached the range's ends, and
    /// nothing is left out).
    pub fn is_complete(&self) -> bool {
        self.is_finished() && self.left_out.is_empty() && self.coverage_gaps().is_empty()
    }

    /// The coverage, to restore if the step pauses.
    pub(super) fn coverage(&self) -> Coverage {
        (
            self.spans.clone(),
            self.restarts.clone(),
            self.left_out.clone(),
            self.failed_starts.clone(),
        )
    }

    /// Restores the coverage saved before a step that paused.
    pub(super) fn restore(&mut self, (spans, restarts, left_out, failed): Coverage) {
        self.spans = spans;
        self.restarts = restarts;
        self.left_out = left_out;
        self.failed_starts = failed;
    }

    /// Records a point of piece `piece` at `omega` in its span, if the
    /// piece is one of the first branch's.
    pub(super) fn cover(&mut self, piece: u32, omega: f64) {
        let main = piece == 0 || self.restarts.iter().any(|r| r.piece == piece);
        if !main {
            return;
        }
        let w = omega.clamp(self.spec.omega_from, self.spec.omega_to);
        match self.spans.iter_mut().find(|s| s.0 == piece) {
            Some(s) => {
                s.1 = s.1.min(w);
                s.2 = s.2.max(w);
            }
            None => self.spans.push((piece, w, w)),
        }
    }

    /// The parts of the range no piece of the first branch covers (nor a
    /// part left out), in order.
    pub(super) fn coverage_gaps(&self) -> Vec<(f64, f64)> {
        let (from, to) = (self.spec.omega_from, self.spec.omega_to);
        let tol = 1e-9 * (to - from);
        let mut covered: Vec<(f64, f64)> = self.spans.iter().map(|s| (s.1, s.2)).collect();
        covered.extend(self.left_out.iter().map(|l| (l.from, l.to)));
        covered.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut gaps = Vec::new();
        let mut at = from;
        for (lo, hi) in covered {
            if lo > at + tol {
                gaps.push((at, lo));
            }
            at = at.max(hi);
        }
        if to > at + tol {
            gaps.push((at, to));
        }
        gaps
    }

    /// The branch left the range between the cursor and `solved`: its last
    /// point lands on the edge it crossed, and the piece ends there.
    pub(super) fn leave_range(
        &mut self,
        c: &Cursor,
        solved: &Solved,
        out: &mut Vec<ShootPoint>,
    ) -> Step<()> {
        let n = c.y.len() - 1;
        let (w0, w1) = (self.omega_of(&c.y), self.omega_of(&solved.y));
        let edge = if w1 > self.spec.omega_to {
            self.spec.omega_to
        } else {
            self.spec.omega_from
        };
        let s = ((edge - w0) / (w1 - w0)).clamp(0.0, 1.0);
        let mut pred: Vec<f64> =
            c.y.iter()
                .zip(&solved.y)
                .map(|(a, b)| a + s * (b - a))
                .collect();
        pred[n] = edge * self.weight;
        // The hyperplane Omega = edge.
        let mut row = vec![0.0; n + 1];
        row[n] = 1.0;
        let landed = match self.correct(&pred, &row, c.period, c.jac.as_ref())? {
            Some(at) => {
                out.push(self.emit(&at, c.period, c.piece, None)?);
                String::new()
            }
            None => " (no orbit was corrected on it)".to_string(),
        };
        let far = match c.dir {
            Direction::Up => edge == self.spec.omega_to,
            Direction::Down => edge == self.spec.omega_from,
        };
        let how = if c.main && !far {
            self.notes.push(format!(
                "the period-{} branch turned back at a fold and left the range at its start, Omega {edge}{landed}",
                c.period
            ));
            PieceEnd::TurnedBack
        } else {
            self.notes.push(format!(
                "the period-{} branch reached the range's end at Omega {edge}{landed}",
                c.period
            ));
            PieceEnd::Reached
        };
        self.end_piece(c, how, edge, out)
    }

    /// Ends piece `c` (`how`, at `stopped_at`); a piece of the first branch
    /// is followed by a restart while part of the range is not covered,
    /// and gaps no restart can cover are left out.
    pub(super) fn end_piece(
        &mut self,
        c: &Cursor,
        how: PieceEnd,
        stopped_at: f64,
        out: &mut Vec<ShootPoint>,
    ) -> Step<()> {
        if !c.main {
            return Ok(());
        }
        let tol = 1e-9 * (self.spec.omega_to - self.spec.omega_from);
        loop {
            let gaps = self.coverage_gaps();
            let Some(&(a, b)) = gaps.first() else {
                return Ok(());
            };
            let inside = |w: f64| a - tol <= w && w <= b + tol;
            let failed = self.failed_starts.iter().filter(|&&w| inside(w)).count();
            if self.restarts.len() >= MAX_RESTARTS || failed >= GAP_STARTS.len() {
                let reason = if failed >= GAP_STARTS.len() {
                    LeftOutReason::NotFollowed
                } else {
                    LeftOutReason::RestartsUsed
                };
                self.notes.push(
                    LeftOut {
                        from: a,
                        to: b,
                        reason,
                    }
                    .note(),
                );
                self.left_out.push(LeftOut {
                    from: a,
                    to: b,
                    reason,
                });
                continue;
            }
            let (omega, dir) = if self.restarts.is_empty() && failed == 0 {
                match self.spec.direction {
                    Direction::Up => (self.spec.omega_to, Direction::Down),
                    Direction::Down => (self.spec.omega_from, Direction::Up),
                }
            } else {
                (a + GAP_STARTS[failed] * (b - a), Direction::Up)
            };
            match self.restart_at(omega, dir, c.period)? {
                Some((cursor, first)) => {
                    let restart = Restart {
                        piece: cursor.piece,
                        reason: how,
                        stopped_at,
                        start_omega: omega,
                        direction: dir,
                    };
                    self.restarts.push(restart);
                    self.notes.push(restart.note());
                    out.push(self.emit(&first, cursor.period, cursor.piece, None)?);
                    self.cur = Some(cursor);
                    return Ok(());
                }
                None => self.failed_starts.push(omega),
            }
        }
    }

    /// A new piece of the first branch from its orbit at `omega`, heading
    /// `dir`, and that orbit; `None` if Newton does not find it.
    fn restart_at(
        &mut self,
        omega: f64,
        dir: Direction,
        period: u32,
    ) -> Step<Option<(Cursor, Solved)>> {
        let red = Reduced::new(&self.model, omega);
        let (rest, _) = red.from_state(&self.model.static_state());
        let n = rest.len();
        let mut row = vec![0.0; n + 1];
        row[n] = 1.0;
        // Newton from rest (it reaches an unstable orbit the motion does not
        // settle on), else from where the motion has settled.
        let mut z = rest;
        let mut solved = None;
        for settle in [0, SETTLE_PERIODS] {
            for _ in 0..settle {
                match self.map(&z, omega, period, false) {
                    Ok((g, _)) => z.iter_mut().zip(&g).for_each(|(zi, gi)| *zi += gi),
                    Err(Halt::Pause) => return Err(Halt::Pause),
                    Err(Halt::Fail(_)) => return Ok(None),
                }
            }
            let mut pred = z.clone();
            pred.push(omega * self.weight);
            solved = self.correct(&pred, &row, period, None)?;
            if solved.is_some() {
                break;
            }
        }
        let Some(solved) = solved else {
            return Ok(None);
        };
        let mut t0 = vec![0.0; n + 1];
        t0[n] = if dir == Direction::Up { 1.0 } else { -1.0 };
        let Some(tangent) = self.tangent(&solved, &t0) else {
            return Ok(None);
        };
        let m = Multipliers::of(&solved.monodromy);
        self.pieces += 1;
        let cursor = Cursor {
            period,
            piece: self.pieces,
            y: solved.y.clone(),
            tangent,
            ds: 0.25 * self.ds_max,
            pd_count: m.as_ref().map_or(0, pd_count),
            ns_count: m.as_ref().map_or(0, ns_count),
            stable: m.as_ref().is_some_and(Multipliers::is_stable),
            count: 0,
            doubles_again: false,
            jac: Some(Jacobian::of(&solved)),
            main: true,
            dir,
        };
        Ok(Some((cursor, solved)))
    }
}
