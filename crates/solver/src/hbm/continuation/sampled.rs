//! Floquet stability on a sample of the branch's points.
//!
//! The monodromy matrix costs about as much as the point itself (30 % of a
//! branch's time over Omega 0.1..0.5 at H = 7), and stability changes
//! rarely along a branch. So a point's stability waits
//! ([`FrfContinuation::unresolved`]) until `stability_stride` points have
//! gathered, or the piece ends: then the monodromy of the last one is
//! computed. If it has the stability of the last point decided before, the
//! points between take it; otherwise the change is located by bisection on
//! the points between (each a monodromy), so that it is labelled between
//! the same two neighbouring points as with a monodromy at every point.
//! The first point of a piece and every fold are always computed, and so
//! is every point between two samples whose largest multiplier lies within
//! 1 % of the unit circle (where a window of another stability can open
//! and close between them), and between two unstable samples whose
//! multipliers leave the circle differently (a complex pair outside at one
//! end, a real one beyond -1 at the other). Points whose stability was
//! inferred carry no multipliers. A window shorter than the stride
//! between two samples both clear of the circle and unstable the same way
//! (or both stable) is not seen; a stride of 1 computes every point.

use super::point::classify_crossing;
use super::*;

/// Stability and multipliers of one point.
type Verdict = (Option<bool>, Vec<Complex<f64>>);

/// How far from the unit circle (relative) a point's largest multiplier
/// must lie for the points between it and a sample of the same stability
/// to take that stability unseen.
const CLEAR_OF_CIRCLE: f64 = 0.01;

/// Whether `multipliers` (none: unknown) keep clear of the unit circle.
fn clear_of(multipliers: &[Complex<f64>]) -> bool {
    let radius = multipliers.iter().map(|m| m.norm()).fold(0.0, f64::max);
    !multipliers.is_empty() && (radius - 1.0).abs() > CLEAR_OF_CIRCLE
}

/// How the multipliers leave the unit circle: how many real ones lie
/// beyond +1, how many beyond -1, how many complex ones outside. Two
/// unstable points with different counts are unstable for different
/// reasons, so multipliers crossed between them, and a stable window may
/// lie there (next to the compound set's Neimark-Sacker point at Omega
/// 0.2405 a pair goes in one point before a real one goes out at -1).
fn outside_counts(multipliers: &[Complex<f64>]) -> [usize; 3] {
    let mut counts = [0; 3];
    for z in multipliers.iter().filter(|z| z.norm() > 1.0) {
        let slot = if z.im.abs() > 1e-6 * z.norm() {
            2
        } else if z.re < 0.0 {
            1
        } else {
            0
        };
        counts[slot] += 1;
    }
    counts
}

impl FrfContinuation {
    /// The monodromy of the queued point `i`.
    fn floquet_at(&mut self, i: usize) -> Verdict {
        self.stats.monodromies += 1;
        let p = &self.queue[i];
        match floquet(&self.asm, &p.coefficients, p.omega) {
            Some(f) => {
                let stable = f.spectral_radius() <= 1.0 + 1e-6;
                let mut all = f.multipliers;
                all.extend(f.planet_multipliers);
                (Some(stable), all)
            }
            None => (None, Vec::new()),
        }
    }

    /// Whether enough points wait for their stability to sample the next.
    pub(super) fn stability_due(&self) -> bool {
        self.stability.unresolved.len() >= self.spec.stability_stride.max(1) as usize
    }

    /// Decides the stability of every waiting point and labels the changes.
    pub(super) fn resolve_stability(&mut self) {
        let n = self.stability.unresolved.len();
        if n == 0 {
            return;
        }
        let since = std::mem::take(&mut self.stability.unresolved);
        let first = self.queue.len() - n;
        let every = self.spec.stability_stride <= 1;
        let mut known: Vec<Option<Verdict>> = vec![None; n];
        known[n - 1] = Some(self.floquet_at(first + n - 1));
        // The reference before the waiting points: the last decided point
        // of the piece, or the piece's first point itself.
        let mut left: isize = -1;
        if (self.stability.prev_stable.is_none() || every) && n > 1 {
            known[0] = Some(self.floquet_at(first));
            left = 0;
        }
        let prev_stable = self.stability.prev_stable;
        let stable_at = |known: &[Option<Verdict>], i: isize| -> Option<bool> {
            if i < 0 {
                prev_stable
            } else {
                known[i as usize].as_ref().and_then(|v| v.0)
            }
        };
        // Whether a computed point's multipliers lie clearly off the unit
        // circle: near it a second multiplier may cross out and back
        // between two samples (a window one point wide, as next to the
        // compound set's period doublings at Omega 0.214), so such an
        // interval is split, not filled.
        let prev_clear = clear_of(&self.stability.prev_multipliers);
        let clear_at = |known: &[Option<Verdict>], i: isize| -> bool {
            if i < 0 {
                prev_clear
            } else {
                known[i as usize].as_ref().is_some_and(|v| clear_of(&v.1))
            }
        };
        let prev_counts = outside_counts(&self.stability.prev_multipliers);
        let counts_at = |known: &[Option<Verdict>], i: isize| -> Option<[usize; 3]> {
            if i < 0 {
                Some(prev_counts)
            } else {
                known[i as usize].as_ref().map(|v| outside_counts(&v.1))
            }
        };
        // A fold (where the tangent's Omega component changes sign) is
        // where stability usually changes: always computed.
        let mut anchors = vec![left];
        let folds: Vec<usize> = ((left + 1).max(0) as usize..n - 1)
            .filter(|&j| self.queue[first + j].bifurcation.is_some())
            .collect();
        for j in folds {
            known[j] = Some(self.floquet_at(first + j));
            anchors.push(j as isize);
        }
        anchors.push(n as isize - 1);
        // Bisection: an interval whose ends agree (and are known) is filled,
        // any other is split at a computed middle point.
        let mut stack: Vec<(isize, isize)> = anchors.windows(2).map(|w| (w[0], w[1])).collect();
        while let Some((a, b)) = stack.pop() {
            if b - a <= 1 {
                continue;
            }
            let (sa, sb) = (stable_at(&known, a), stable_at(&known, b));
            if !every
                && sa.is_some()
                && sa == sb
                && clear_at(&known, a)
                && clear_at(&known, b)
                && counts_at(&known, a) == counts_at(&known, b)
            {
                for v in &mut known[(a + 1) as usize..b as usize] {
                    *v = Some((sa, Vec::new()));
                }
                continue;
            }
            let mid = a + (b - a) / 2;
            known[mid as usize] = Some(self.floquet_at(first + mid as usize));
            stack.push((mid, b));
            stack.push((a, mid));
        }
        for (j, (verdict, since_fold)) in known.into_iter().zip(since).enumerate() {
            let (stable, multipliers) = verdict.unwrap_or((None, Vec::new()));
            let p = &mut self.queue[first + j];
            if p.bifurcation.is_none() {
                if let (Some(a), Some(b)) = (self.stability.prev_stable, stable) {
                    if a != b {
                        let kind =
                            classify_crossing(&self.stability.prev_multipliers, &multipliers);
                        // A real multiplier through +1 next to a turn is the
                        // fold itself (the monodromy of the truncated orbit
                        // and the truncated balance place it a point apart).
                        if !(kind == Bifurcation::BranchPoint && since_fold <= 5) {
                            p.bifurcation = Some(kind);
                        }
                    }
                }
            }
            self.stability.prev_stable = stable;
            if !multipliers.is_empty() || stable.is_none() {
                self.stability.prev_multipliers.clone_from(&multipliers);
            }
            p.stable = stable;
            p.multipliers = multipliers;
        }
    }
}
