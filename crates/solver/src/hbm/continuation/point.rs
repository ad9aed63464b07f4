//! A converged solution turned into a branch point: each mesh's orbit
//! reconstructed with its extremes, Floquet stability and bifurcation labels.

use super::*;

impl FrfContinuation {
    /// Builds the output for the current solution.
    pub(super) fn point(
        &mut self,
        newton_iterations: usize,
        fold: Option<Bifurcation>,
    ) -> BranchPoint {
        let nx = self.n_x();
        let omega = self.cursor.y[nx];
        let x = self.cursor.y[..nx].to_vec();
        let meshes = self.meshes_of(&x);
        let bifurcation = fold;
        if fold.is_some() {
            self.stability.since_fold = 0;
        } else {
            self.stability.since_fold = self.stability.since_fold.saturating_add(1);
        }
        // Stability is decided once the next sampled point is known
        // ([`FrfContinuation::resolve_stability`]).
        if self.spec.stability {
            self.stability.unresolved.push(self.stability.since_fold);
        }
        BranchPoint {
            omega,
            meshes,
            stable: None,
            multipliers: Vec::new(),
            bifurcation,
            newton_iterations,
            coefficients: x,
            piece: self.piece.index,
        }
    }

    /// Reconstructs every physical mesh's orbit from the coefficients.
    pub fn meshes_of(&self, x: &[f64]) -> Vec<BranchMesh> {
        let h = self.asm.h;
        let nc = harmonic::n_coef(h);
        let m = self.asm.model.m;
        let per_channel: Vec<BranchMesh> = self
            .asm
            .model
            .channels
            .iter()
            .map(|ch| {
                let coef: Vec<f64> = (0..nc)
                    .map(|c| (0..m).map(|i| ch.d[i] * x[c * m + i]).sum())
                    .collect();
                // delta - e has the same series with the TE's mean and first
                // harmonic subtracted.
                let mut rel_coef = coef.clone();
                let te = harmonic::te_real_coefficients(&ch.law);
                let mut te_free = true;
                for (r, t) in rel_coef.iter_mut().zip(te) {
                    *r -= t;
                    te_free &= t == 0.0;
                }
                let (dmin, dmax) = extremes(&self.recon.grid, &coef, h);
                // Without TE on this mesh the two series are one.
                let (xmin, xmax) = if te_free {
                    (dmin, dmax)
                } else {
                    extremes(&self.recon.grid, &rel_coef, h)
                };
                let mut harmonics_m = vec![coef[0] * 1e-6];
                for k in 1..=h {
                    harmonics_m.push(coef[2 * k - 1].hypot(coef[2 * k]) * 1e-6);
                }
                let b = ch.law.backlash_um();
                BranchMesh {
                    delta_max_m: dmax * 1e-6,
                    delta_min_m: dmin * 1e-6,
                    delta_amplitude_m: 0.5 * (dmax - dmin) * 1e-6,
                    harmonics_m,
                    rel_min_m: xmin * 1e-6,
                    rel_max_m: xmax * 1e-6,
                    impact: Impact::classify(xmin, xmax, b),
                }
            })
            .collect();
        self.recon
            .mesh_to_channel
            .iter()
            .map(|&c| per_channel[c].clone())
            .collect()
    }
}

/// Labels a stability change from the multipliers on either side.
pub(super) fn classify_crossing(before: &[Complex<f64>], after: &[Complex<f64>]) -> Bifurcation {
    // The multiplier outside the unit circle on the unstable side.
    let outside = |set: &[Complex<f64>]| -> Option<Complex<f64>> {
        set.iter()
            .copied()
            .filter(|z| z.norm() > 1.0)
            .max_by(|a, b| a.norm().total_cmp(&b.norm()))
    };
    let z = outside(after).or_else(|| outside(before));
    match z {
        Some(z) if z.im.abs() > 1e-6 * z.norm() => Bifurcation::NeimarkSacker,
        Some(z) if z.re < 0.0 => Bifurcation::PeriodDoubling,
        _ => Bifurcation::BranchPoint,
    }
}

/// Min and max of a Fourier series: samples on `grid`, then a parabola
/// through the best sample and its neighbours.
pub(super) fn extremes(grid: &harmonic::Grid, coef: &[f64], h: usize) -> (f64, f64) {
    let n = grid.n;
    let dt = 2.0 * PI / n as f64;
    let mut vals = vec![0.0; n];
    // With the widest vector instructions (the same bits, `crate::simd`).
    crate::simd::dispatch(
        #[inline(always)]
        || grid.synthesize_here(coef, &mut vals),
    );
    let refine = |i: usize| -> f64 {
        let (a, b, c) = (vals[(i + n - 1) % n], vals[i], vals[(i + 1) % n]);
        let den = a - 2.0 * b + c;
        if den == 0.0 {
            return b;
        }
        let off = (0.5 * (a - c) / den).clamp(-1.0, 1.0);
        eval_coef(coef, h, (i as f64 + off) * dt)
    };
    // One pass, in the total order, with `max_by`'s and `min_by`'s ties:
    // the last of equal largest samples, the first of equal smallest.
    let (mut imin, mut imax) = (0, 0);
    for (i, v) in vals.iter().enumerate().skip(1) {
        if v.total_cmp(&vals[imax]).is_ge() {
            imax = i;
        }
        if v.total_cmp(&vals[imin]).is_lt() {
            imin = i;
        }
    }
    (refine(imin).min(vals[imin]), refine(imax).max(vals[imax]))
}
