//! The augmented systems whose solution curves are the boundaries: the
//! harmonic-balance residual `R(X, Omega, p) = 0` plus the condition that
//! vanishes on the boundary.
//!
//! Unknowns `z = (X, aux, Omega, p)`; the systems have one equation fewer
//! than unknowns, so their solutions are curves (the tracer adds the
//! arclength equation).
//!
//! Fold: the minimally extended system. With bordering vectors `b`, `c`
//! (the last point's left and right null vectors) the bordered matrix
//! `[J b; c^T 0]` is regular at the fold, and the `g` of
//! `[J b; c^T 0] [v; g] = [0; 1]` vanishes exactly where `J = dR/dX` is
//! singular. Its gradient is `g_z = -w^T J_z v` with `w` from the
//! transposed system; `w^T J_X v` is the gradient of `w^T J v`, the
//! directional derivative of the Jacobian along `v` (central differences
//! of two Jacobians), and `J_p` a one-sided difference in `p`. The cusp test
//! `kappa = w^T R_XX[v, v]`, the fold's quadratic coefficient, changes sign
//! where two folds meet; the branch exists on the side of the fold where
//! `kappa (w^T R_Omega dOmega + w^T R_p dp) < 0` (the fold's normal form).
//!
//! Contact: one extremum of a channel's relative displacement
//! `x(theta) = u(theta) - e(theta)` touches `+b` or `-b`:
//! `x(theta*) = s b` and `x'(theta*) = 0`, with `theta*` the one auxiliary
//! unknown, all derivatives in closed form but the one in `p` (differenced).

use super::bordered::{
    bordered, branch_motion, branch_rows, inf_norm, residual_at, residual_p, Eval,
};
use super::family::Family;
use super::CurveKind;
use crate::error::{Result, SolverError};
use crate::hbm::harmonic::{n_coef, te_real_coefficients};
use crate::hbm::HbmCost;
use nalgebra::{DMatrix, DVector};

/// The condition a curve follows.
#[derive(Debug, Clone)]
pub(crate) enum System {
    /// A fold of the periodic branch.
    Fold {
        /// Bordering vectors: approximate left and right null vectors.
        b: DVector<f64>,
        c: DVector<f64>,
        /// The null vectors of the last evaluation.
        w: DVector<f64>,
        v: DVector<f64>,
    },
    /// A Floquet multiplier at -1.
    Doubling {
        /// The block (0 main, 1 the planet block under the symmetric reduction).
        block: usize,
        /// Bordering vectors and the last right null vector.
        b: DVector<f64>,
        c: DVector<f64>,
        v: DVector<f64>,
    },
    /// A channel's extremum at `+-b`.
    Contact {
        /// The channel (mesh, or mesh kind under the symmetric reduction).
        channel: usize,
        /// Which extremum and which flank.
        kind: CurveKind,
    },
}

impl System {
    /// The period-doubling system at `(x, omega, p)`.
    pub(crate) fn doubling(fam: &mut Family, x: &[f64], omega: f64, p: f64) -> Result<Self> {
        let (block, b, c) = super::doubling::start(fam, x, omega, p)?;
        Ok(System::Doubling {
            block,
            v: c.clone(),
            b,
            c,
        })
    }

    /// The fold system at `(x, omega, p)`, its bordering vectors from the
    /// smallest singular value's vectors of `dR/dX` there.
    pub(crate) fn fold(fam: &mut Family, x: &[f64], omega: f64, p: f64) -> Result<Self> {
        let nx = x.len();
        let mut r = vec![0.0; nx];
        let mut j = DMatrix::zeros(nx, nx + 1);
        fam.evaluate(x, omega, p, &mut r, Some(&mut j))?;
        let jx = j.columns(0, nx).into_owned();
        fam.spend(5.0 * HbmCost::factor(nx));
        let svd = jx.svd(true, true);
        let (u, vt) = match (svd.u, svd.v_t) {
            (Some(u), Some(vt)) => (u, vt),
            _ => {
                return Err(SolverError::Singular {
                    what: format!("fold start at Omega = {omega}"),
                })
            }
        };
        let k = (0..nx)
            .min_by(|&a, &b| svd.singular_values[a].total_cmp(&svd.singular_values[b]))
            .unwrap_or(0);
        let b = u.column(k).into_owned();
        let c = vt.row(k).transpose();
        Ok(System::Fold {
            w: b.clone(),
            v: c.clone(),
            b,
            c,
        })
    }

    /// Auxiliary unknowns between `X` and `(Omega, p)`.
    pub(crate) fn n_aux(&self) -> usize {
        match self {
            System::Fold { .. } | System::Doubling { .. } => 0,
            System::Contact { .. } => 1,
        }
    }

    /// Takes the last evaluation's null vectors as the next bordering.
    pub(crate) fn accept(&mut self) {
        match self {
            System::Fold { b, c, w, v } => {
                *b = w.normalize();
                *c = v.normalize();
            }
            System::Doubling { c, v, .. } => *c = v.normalize(),
            System::Contact { .. } => {}
        }
    }

    /// Evaluates the system at `z`; with `full`, also what only an
    /// accepted point reports ([`Eval::side`], [`Eval::others_stable`]),
    /// which costs a factorization of the branch's Jacobian.
    pub(crate) fn eval(&mut self, fam: &mut Family, z: &[f64], full: bool) -> Result<Eval> {
        match self {
            System::Fold { b, c, w, v } => fold_eval(fam, z, b, c, w, v),
            System::Doubling { block, b, c, v } => {
                super::doubling::eval(fam, z, *block, (b, c), v, full)
            }
            System::Contact { channel, kind } => contact_eval(fam, z, *channel, *kind, full),
        }
    }
}

fn fold_eval(
    fam: &mut Family,
    z: &[f64],
    b: &DVector<f64>,
    c: &DVector<f64>,
    w_out: &mut DVector<f64>,
    v_out: &mut DVector<f64>,
) -> Result<Eval> {
    let nx = z.len() - 2;
    let (x, omega, p) = (&z[..nx], z[nx], z[nx + 1]);
    let (r, j) = residual_at(fam, x, omega, p)?;
    let a = bordered(&j, b, c);
    let singular = || SolverError::Singular {
        what: format!("bordered fold matrix at Omega = {omega}"),
    };
    let mut e = DVector::zeros(nx + 1);
    e[nx] = 1.0;
    fam.factored(nx + 1);
    fam.factored(nx + 1);
    let sol = crate::dense::Lu::new(a.clone())
        .solve(&e)
        .ok_or_else(singular)?;
    let solt = crate::dense::Lu::new(a.transpose())
        .solve(&e)
        .ok_or_else(singular)?;
    let v = sol.rows(0, nx).into_owned();
    let w = solt.rows(0, nx).into_owned();
    let g = sol[nx];
    // The Jacobian's directional derivative along v (both X and Omega
    // columns), by central differences.
    let scale = 1.0 + inf_norm(x);
    let vn = v.amax().max(1e-300);
    let eps = 1e-5 * scale / vn;
    let (mut jp, mut jm) = (j.clone(), j.clone());
    let mut rr = vec![0.0; nx];
    let xp: Vec<f64> = (0..nx).map(|i| x[i] + eps * v[i]).collect();
    let xm: Vec<f64> = (0..nx).map(|i| x[i] - eps * v[i]).collect();
    fam.evaluate(&xp, omega, p, &mut rr, Some(&mut jp))?;
    fam.evaluate(&xm, omega, p, &mut rr, Some(&mut jm))?;
    let dv = (jp - jm) / (2.0 * eps);
    // w^T (d/dv J): the gradient of w^T J v in X, and its Omega derivative.
    let wdv = w.transpose() * &dv;
    // Derivatives in p.
    // One side is `p` itself (`Family::neighbours`): its residual and
    // Jacobian are `r` and `j`.
    let (lo, hi) = fam.neighbours(p);
    let (mut rp, mut rm) = (r.clone(), r.clone());
    let (mut jhi, mut jlo) = (j.clone(), j.clone());
    if hi != p {
        fam.evaluate(x, omega, hi, &mut rp, Some(&mut jhi))?;
    }
    if lo != p {
        fam.evaluate(x, omega, lo, &mut rm, Some(&mut jlo))?;
    }
    let h = hi - lo;
    let r_p: Vec<f64> = (0..nx).map(|i| (rp[i] - rm[i]) / h).collect();
    let jv_p = (jhi.columns(0, nx) - jlo.columns(0, nx)) * &v / h;
    let g_p = -w.dot(&jv_p);
    let (mut res, mut jac) = branch_rows(&r, &j, &r_p);
    res[nx] = g;
    for k in 0..=nx {
        jac[(nx, k)] = -wdv[k];
    }
    jac[(nx, nx + 1)] = g_p;
    let kappa: f64 = (0..nx).map(|k| wdv[k] * v[k]).sum();
    let w_omega: f64 = (0..nx).map(|i| w[i] * j[(i, nx)]).sum();
    let w_p: f64 = (0..nx).map(|i| w[i] * r_p[i]).sum();
    let s = -kappa.signum();
    *w_out = w;
    *v_out = v;
    Ok(Eval {
        res,
        jac,
        side: (s * w_omega, s * w_p),
        cusp: kappa,
        scale,
        others_stable: None,
    })
}

/// `(phi_c, phi_c', phi_c'')` of the Fourier basis (mean, cos 1, sin 1, ...)
/// at `theta`.
fn basis(nc: usize, theta: f64) -> [Vec<f64>; 3] {
    let mut f = vec![0.0; nc];
    let mut d1 = vec![0.0; nc];
    let mut d2 = vec![0.0; nc];
    f[0] = 1.0;
    for c in 1..nc {
        let k = c.div_ceil(2) as f64;
        let (s, co) = (k * theta).sin_cos();
        if c % 2 == 1 {
            f[c] = co;
            d1[c] = -k * s;
            d2[c] = -k * k * co;
        } else {
            f[c] = s;
            d1[c] = k * co;
            d2[c] = -k * k * s;
        }
    }
    [f, d1, d2]
}

/// The channel's relative-displacement coefficients and its backlash at `p`.
fn rel_coef(fam: &mut Family, x: &[f64], p: f64, channel: usize) -> Result<(Vec<f64>, f64)> {
    let asm = fam.assembly(p)?;
    let m = asm.model.m;
    let nc = n_coef(asm.h);
    let ch = asm
        .model
        .channels
        .get(channel)
        .ok_or_else(|| SolverError::Singular {
            what: format!("no channel {channel}"),
        })?;
    let mut coef: Vec<f64> = (0..nc)
        .map(|c| (0..m).map(|i| ch.d[i] * x[c * m + i]).sum())
        .collect();
    for (r, t) in coef.iter_mut().zip(te_real_coefficients(&ch.law)) {
        *r -= t;
    }
    Ok((coef, ch.law.backlash_um()))
}

/// The flank `s` (+1 drive, -1 back) a contact curve's extremum touches.
pub(crate) fn flank(kind: CurveKind) -> f64 {
    match kind {
        CurveKind::BackFlanksTouch => -1.0,
        _ => 1.0,
    }
}

fn contact_eval(
    fam: &mut Family,
    z: &[f64],
    channel: usize,
    kind: CurveKind,
    full: bool,
) -> Result<Eval> {
    let nx = z.len() - 3;
    let (x, theta, omega, p) = (&z[..nx], z[nx], z[nx + 1], z[nx + 2]);
    let s = flank(kind);
    let (r, j) = residual_at(fam, x, omega, p)?;
    let (coef, backlash) = rel_coef(fam, x, p, channel)?;
    let nc = coef.len();
    let [f, d1, d2] = basis(nc, theta);
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(u, v)| u * v).sum::<f64>();
    let c1 = dot(&coef, &f) - s * backlash;
    let c2 = dot(&coef, &d1);
    let x2 = dot(&coef, &d2);
    // Derivatives in p: the TE and the backlash move with it.
    let (lo, hi) = fam.neighbours(p);
    let (chi, bhi) = rel_coef(fam, x, hi, channel)?;
    let (clo, blo) = rel_coef(fam, x, lo, channel)?;
    let h = hi - lo;
    let c1_p = (dot(&chi, &f) - s * bhi - dot(&clo, &f) + s * blo) / h;
    let c2_p = (dot(&chi, &d1) - dot(&clo, &d1)) / h;
    let r_p = residual_p(fam, x, omega, p, &r)?;
    let asm = fam.assembly(p)?;
    let m = asm.model.m;
    let d = asm.model.channels[channel].d.clone();
    let n = nx + 3;
    let mut res = DVector::zeros(n - 1);
    let mut jac = DMatrix::zeros(n - 1, n);
    for i in 0..nx {
        res[i] = r[i];
        for k in 0..nx {
            jac[(i, k)] = j[(i, k)];
        }
        jac[(i, nx + 1)] = j[(i, nx)];
        jac[(i, nx + 2)] = r_p[i];
    }
    res[nx] = c1;
    res[nx + 1] = c2;
    // d c / d X[c m + i] = d_i phi_c(theta*).
    let mut c1_x = DVector::zeros(nx);
    for cc in 0..nc {
        for i in 0..m {
            c1_x[cc * m + i] = d[i] * f[cc];
            jac[(nx, cc * m + i)] = d[i] * f[cc];
            jac[(nx + 1, cc * m + i)] = d[i] * d1[cc];
        }
    }
    jac[(nx, nx)] = c2;
    jac[(nx + 1, nx)] = x2;
    jac[(nx, nx + 2)] = c1_p;
    jac[(nx + 1, nx + 2)] = c2_p;
    // The extremum's rate of change along the branch (theta* drops out:
    // x' = 0 there): dX = -J^-1 (R_Omega dOmega + R_p dp).
    let (g_om, g_p) = if full {
        fam.factored(nx);
        let (dx_om, dx_p) = branch_motion(&j, &r_p);
        (c1_x.dot(&dx_om), c1_x.dot(&dx_p) + c1_p)
    } else {
        (0.0, 0.0)
    };
    // The change has not happened where the extremum is inside the dead
    // zone's side it leaves: a minimum above +b (drive flanks still in
    // contact), a minimum above -b (back flanks apart), a maximum below +b.
    let toward = if kind == CurveKind::DriveFlanksTouch {
        -1.0
    } else {
        1.0
    };
    Ok(Eval {
        res,
        jac,
        side: (toward * g_om, toward * g_p),
        cusp: 0.0,
        scale: 1.0 + inf_norm(x),
        others_stable: None,
    })
}
