//! Where the curves start: on the one-parameter branch at one level of
//! `p`, each located fold, and each pair of neighbouring points between
//! which a channel's extreme relative displacement crosses `+b` or `-b`
//! (interpolated linearly, the extremum's phase read from the
//! interpolated orbit).

use super::family::Family;
use super::CurveKind;
use crate::hbm::harmonic::{eval_coef, n_coef, te_real_coefficients};
use crate::hbm::{Bifurcation, BranchPoint};
use std::f64::consts::PI;

/// A guess from which a curve is corrected and traced.
#[derive(Debug, Clone)]
pub(crate) struct Start {
    /// What the curve marks.
    pub(crate) kind: CurveKind,
    /// The channel of a contact boundary.
    pub(crate) channel: Option<usize>,
    /// Its first physical mesh.
    pub(crate) mesh: Option<usize>,
    /// The guess `(X, aux, Omega, p)`.
    pub(crate) z: Vec<f64>,
}

/// Samples per period on which an extremum's phase is first read.
const PHASE_SAMPLES: usize = 512;

/// The starts on one level's branch `points` (at `p`).
pub(crate) fn find(
    fam: &mut Family,
    points: &[BranchPoint],
    p: f64,
    contact_mesh: Option<usize>,
) -> Vec<Start> {
    let mut out = Vec::new();
    for q in points {
        if q.bifurcation == Some(Bifurcation::PeriodDoubling) {
            let mut z = q.coefficients.clone();
            z.extend([q.omega, p]);
            out.push(Start {
                kind: CurveKind::PeriodDoubling,
                channel: None,
                mesh: None,
                z,
            });
        }
        if q.bifurcation == Some(Bifurcation::Fold) {
            let mut z = q.coefficients.clone();
            z.extend([q.omega, p]);
            out.push(Start {
                kind: CurveKind::Fold,
                channel: None,
                mesh: None,
                z,
            });
        }
    }
    let Ok(asm) = fam.assembly(p) else {
        return out;
    };
    let (m, h) = (asm.model.m, asm.h);
    let nc = n_coef(h);
    let channels: Vec<_> = asm.model.channels.clone();
    for (c, ch) in channels.iter().enumerate() {
        let Some(&mesh) = ch.meshes.first() else {
            continue;
        };
        if contact_mesh.is_some_and(|j| !ch.meshes.contains(&j)) {
            continue;
        }
        let b = ch.law.backlash_um();
        let te: Vec<f64> = te_real_coefficients(&ch.law).collect();
        for kind in [
            CurveKind::DriveFlanksPart,
            CurveKind::BackFlanksTouch,
            CurveKind::DriveFlanksTouch,
        ] {
            let f = |q: &BranchPoint| -> Option<f64> {
                let mm = q.meshes.get(mesh)?;
                let (lo, hi) = (mm.rel_min_m * 1e6, mm.rel_max_m * 1e6);
                Some(match kind {
                    CurveKind::DriveFlanksPart => lo - b,
                    CurveKind::BackFlanksTouch => lo + b,
                    _ => hi - b,
                })
            };
            for pair in points.windows(2) {
                let (qa, qb) = (&pair[0], &pair[1]);
                if qa.piece != qb.piece || qa.coefficients.len() != qb.coefficients.len() {
                    continue;
                }
                let (Some(fa), Some(fb)) = (f(qa), f(qb)) else {
                    continue;
                };
                if fa * fb >= 0.0 {
                    continue;
                }
                let t = fa / (fa - fb);
                let x: Vec<f64> = qa
                    .coefficients
                    .iter()
                    .zip(&qb.coefficients)
                    .map(|(a, b)| a + t * (b - a))
                    .collect();
                let mut rel: Vec<f64> = (0..nc)
                    .map(|k| (0..m).map(|i| ch.d[i] * x[k * m + i]).sum())
                    .collect();
                for (r, e) in rel.iter_mut().zip(&te) {
                    *r -= e;
                }
                let sample =
                    |i: usize| eval_coef(&rel, h, 2.0 * PI * i as f64 / PHASE_SAMPLES as f64);
                let pick = (0..PHASE_SAMPLES).max_by(|&i, &j| {
                    let (a, b) = (sample(i), sample(j));
                    if kind == CurveKind::DriveFlanksTouch {
                        a.total_cmp(&b)
                    } else {
                        b.total_cmp(&a)
                    }
                });
                let theta = 2.0 * PI * pick.unwrap_or(0) as f64 / PHASE_SAMPLES as f64;
                let mut z = x;
                z.extend([theta, qa.omega + t * (qb.omega - qa.omega), p]);
                out.push(Start {
                    kind,
                    channel: Some(c),
                    mesh: Some(mesh),
                    z,
                });
            }
        }
    }
    out
}

/// Folds first, then the contact boundaries in [`CurveKind::ALL`]'s order,
/// each by level.
pub(crate) fn order(starts: &mut [Start]) {
    starts.sort_by_key(|s| CurveKind::ALL.iter().position(|&k| k == s.kind));
}
