//! The period-doubling test function on the harmonic-balance branch: the
//! monodromy matrix `M` of the orbit (as [`crate::hbm::stability`] computes
//! its Floquet multipliers) has a multiplier at -1 where the bordered
//! `[M + I b; c^T 0] [v; g] = [0; 1]` gives `g = 0`. `g`'s gradient is
//! differenced (one monodromy per unknown): the monodromy is integrated
//! piecewise between the contact switches, so its derivatives have no
//! closed form here.
//!
//! The gradient costs `n + 2` monodromies against one for the test
//! itself, so it is differenced once and kept ([`Frozen`]) through the
//! corrector and the next ones along the curve, up to [`GRADIENT_STEPS`]
//! accepted steps: the test row's Newton is a chord method (the branch
//! rows and `g` itself stay exact, so the points are on the same curve),
//! at one monodromy an iteration. A corrector that fails or needs many
//! iterations forgets it, and the retry differences it afresh. It is kept
//! only where it costs at least [`KEEP_FROM`] monodromies: on a small
//! system (the gear pair's 15 unknowns at H = 7) the kept gradient's extra
//! iterations and shorter steps cost more than differencing it (the gear
//! pair's TE box 1.15 s with every corrector differencing, 1.23 s keeping;
//! the compound set's page box 27.6 s against 20.3 s).
//!
//! Stable side: the side where the critical multiplier is inside the unit
//! circle (`lambda > -1`), read from how `g` and `lambda + 1` move together
//! along the branch.

use super::bordered::{
    bordered_solve, branch_motion, branch_rows, inf_norm, residual_at, residual_p, Eval,
};
use super::family::Family;
use crate::dense::eigenvalues;
use crate::error::{Result, SolverError};
use crate::hbm::stability::{monodromy_block, monodromy_matrices};
use nalgebra::{DMatrix, DVector};

/// The main and planet blocks' monodromy matrices at `(x, omega, p)`.
type Monodromies = (DMatrix<f64>, Option<DMatrix<f64>>);

/// The monodromy matrices of the orbit `x` at `(omega, p)`.
fn monodromies(fam: &mut Family, x: &[f64], omega: f64, p: f64) -> Result<Monodromies> {
    fam.integrated_monodromy(omega);
    let asm = fam.assembly(p)?;
    monodromy_matrices(asm, x, omega).ok_or_else(|| no_monodromy(omega))
}

/// Whether every multiplier but the one closest to -1 (of `block`) is
/// inside the unit circle; `None` if there is no such block or the
/// eigenvalues did not converge.
fn others_stable((main, planet): &Monodromies, block: usize) -> Option<bool> {
    let mut all: Vec<(usize, nalgebra::Complex<f64>)> =
        eigenvalues(main)?.into_iter().map(|z| (0, z)).collect();
    if let Some(pl) = planet {
        all.extend(eigenvalues(pl)?.into_iter().map(|z| (1, z)));
    }
    let critical = all
        .iter()
        .enumerate()
        .filter(|(_, (b, _))| *b == block)
        .min_by(|(_, (_, u)), (_, (_, v))| (u + 1.0).norm().total_cmp(&(v + 1.0).norm()))
        .map(|(i, _)| i)?;
    Some(
        all.iter()
            .enumerate()
            .all(|(i, (_, z))| i == critical || z.norm() <= 1.0 + 1e-6),
    )
}

/// `M + I` of block `block` (0: the main block, 1: the planet block).
fn shifted_of((main, planet): &Monodromies, block: usize, omega: f64) -> Result<DMatrix<f64>> {
    let mat = if block == 0 {
        Some(main.clone())
    } else {
        planet.clone()
    };
    plus_identity(mat, omega)
}

/// `M + I`, or the failure of a monodromy that could not be had.
fn plus_identity(mat: Option<DMatrix<f64>>, omega: f64) -> Result<DMatrix<f64>> {
    let mut mat = mat.ok_or_else(|| no_monodromy(omega))?;
    for i in 0..mat.nrows() {
        mat[(i, i)] += 1.0;
    }
    Ok(mat)
}

/// A monodromy that is not finite (or a block that does not exist).
fn no_monodromy(omega: f64) -> SolverError {
    SolverError::Singular {
        what: format!("monodromy at Omega = {omega}"),
    }
}

/// The real part of the eigenvalue of `M + I` nearest zero: the real
/// multiplier closest to -1, plus one.
/// NaN if the eigenvalues do not converge (the corrector then fails).
fn critical_of(shifted: &DMatrix<f64>) -> f64 {
    eigenvalues(shifted)
        .unwrap_or_default()
        .iter()
        .min_by(|u, v| u.norm().total_cmp(&v.norm()))
        .map_or(f64::NAN, |z| z.re)
}

/// The real multiplier closest to -1 of block `block`, plus one.
fn critical(fam: &mut Family, x: &[f64], omega: f64, p: f64, block: usize) -> Result<f64> {
    Ok(critical_of(&shifted_block(fam, x, omega, p, block)?))
}

/// The block whose multiplier is closest to -1 at `(x, omega, p)`, and the
/// bordering vectors for it (the smallest singular value's vectors of `M + I`).
pub(crate) fn start(
    fam: &mut Family,
    x: &[f64],
    omega: f64,
    p: f64,
) -> Result<(usize, DVector<f64>, DVector<f64>)> {
    // One monodromy gives both blocks.
    let mono = monodromies(fam, x, omega, p)?;
    let mut best: Option<(f64, usize, DMatrix<f64>)> = None;
    for block in 0..2 {
        if let Ok(a) = shifted_of(&mono, block, omega) {
            let mu = critical_of(&a);
            if best.as_ref().is_none_or(|(b, _, _)| mu.abs() < *b) {
                best = Some((mu.abs(), block, a));
            }
        }
    }
    let (_, block, a) = best.ok_or_else(|| SolverError::Singular {
        what: format!("monodromy at Omega = {omega}"),
    })?;
    let n = a.nrows();
    let svd = a.svd(true, true);
    let (Some(u), Some(vt)) = (svd.u, svd.v_t) else {
        return Err(SolverError::Singular {
            what: format!("period-doubling start at Omega = {omega}"),
        });
    };
    let k = (0..n)
        .min_by(|&i, &j| svd.singular_values[i].total_cmp(&svd.singular_values[j]))
        .unwrap_or(0);
    Ok((block, u.column(k).into_owned(), vt.row(k).transpose()))
}

/// Accepted steps a differenced gradient is kept for (see the module's doc).
pub(crate) const GRADIENT_STEPS: u32 = 4;

/// The fewest monodromies (unknowns plus two) a gradient must cost to be
/// kept beyond its corrector (see the module's doc).
pub(crate) const KEEP_FROM: usize = 32;

/// What the correctors keep of the evaluation that differenced the test
/// function's gradient in `(X, Omega, p)`: the gradient, whether `g` grows
/// with `lambda + 1`, and the accepted steps since.
#[derive(Debug, Clone)]
pub(crate) struct Frozen {
    grad: Vec<f64>,
    orient: f64,
    /// Accepted steps since it was differenced.
    pub(crate) steps: u32,
}

impl Frozen {
    /// Whether it may outlive its corrector: it cost at least
    /// [`KEEP_FROM`] monodromies, one per entry.
    pub(crate) fn keep(&self) -> bool {
        self.grad.len() >= KEEP_FROM
    }
}

/// `M + I` of block `block` at `(x, omega, p)`, that block alone
/// integrated (the same matrix as [`shifted_of`] gives from both).
fn shifted_block(
    fam: &mut Family,
    x: &[f64],
    omega: f64,
    p: f64,
    block: usize,
) -> Result<DMatrix<f64>> {
    fam.integrated_monodromy(omega);
    let asm = fam.assembly(p)?;
    plus_identity(monodromy_block(asm, x, omega, block), omega)
}

/// `g` and the right null vector `v` at `(x, omega, p)`.
fn test(
    fam: &mut Family,
    z: &[f64],
    block: usize,
    b: &DVector<f64>,
    c: &DVector<f64>,
) -> Result<(f64, DVector<f64>)> {
    let nx = z.len() - 2;
    let a = shifted_block(fam, &z[..nx], z[nx], z[nx + 1], block)?;
    bordered_solve(&a, b, c, z[nx])
}

/// The period-doubling system at `z = (X, Omega, p)`, with bordering
/// `(b, c)`; `frozen` is the gradient kept from an earlier evaluation
/// (computed and stored when `None`). Without `full` (a corrector's
/// iterate), the side and the other multipliers' stability, which only an
/// accepted point reports, are not computed.
pub(crate) fn eval(
    fam: &mut Family,
    z: &[f64],
    block: usize,
    (b, c): (&DVector<f64>, &DVector<f64>),
    v_out: &mut DVector<f64>,
    frozen: &mut Option<Frozen>,
    full: bool,
) -> Result<Eval> {
    let nx = z.len() - 2;
    let (x, omega, p) = (&z[..nx], z[nx], z[nx + 1]);
    let (r, j) = residual_at(fam, x, omega, p)?;
    let r_p = residual_p(fam, x, omega, p)?;
    // One monodromy at `z` gives the test function, its orientation's
    // first multiplier and the other multipliers' stability.
    let mono = monodromies(fam, x, omega, p)?;
    let a = shifted_of(&mono, block, omega)?;
    let (g, v) = bordered_solve(&a, b, c, omega)?;
    let scale = 1.0 + inf_norm(x);
    let (dx_om, dx_p) = if full || frozen.is_none() {
        fam.factored(nx);
        branch_motion(&j, &r_p)
    } else {
        (DVector::zeros(nx), DVector::zeros(nx))
    };
    let kept = match frozen.take() {
        Some(f) => f,
        None => {
            let mut grad = vec![0.0; nx + 2];
            let mut zz = z.to_vec();
            // Forward in p inside the key's range, backward at its upper
            // limit (a start at backlash_um = 1000 was otherwise refused
            // as out of range).
            let (p_lo, p_hi) = fam.neighbours(p);
            let h_p = if p_hi > p { p_hi - p } else { p_lo - p };
            for (i, gi) in grad.iter_mut().enumerate() {
                let h = if i < nx {
                    1e-6 * scale
                } else if i == nx {
                    1e-7 * (1.0 + omega.abs())
                } else {
                    h_p
                };
                let keep = zz[i];
                zz[i] = keep + h;
                let (gh, _) = test(fam, &zz, block, b, c)?;
                zz[i] = keep;
                *gi = (gh - g) / h;
            }
            // Whether g grows with lambda + 1: a small step along the branch in Omega.
            let g_om = DVector::from_column_slice(&grad[..nx]).dot(&dx_om) + grad[nx];
            let step = 1e-4 * (1.0 + omega.abs());
            let moved: Vec<f64> = (0..nx).map(|i| x[i] + step * dx_om[i]).collect();
            let mu0 = critical_of(&a);
            let mu1 = critical(fam, &moved, omega + step, p, block)?;
            let orient = if (mu1 - mu0) * g_om >= 0.0 { 1.0 } else { -1.0 };
            Frozen {
                grad,
                orient,
                steps: 0,
            }
        }
    };
    let grad = &kept.grad;
    let (mut res, mut jac) = branch_rows(&r, &j, &r_p);
    res[nx] = g;
    for (k, &gk) in grad.iter().enumerate() {
        jac[(nx, k)] = gk;
    }
    // g along the branch: dX = -J^-1 (R_Omega dOmega + R_p dp).
    let side = if full {
        let g_x = DVector::from_column_slice(&grad[..nx]);
        let g_om = g_x.dot(&dx_om) + grad[nx];
        let g_p = g_x.dot(&dx_p) + grad[nx + 1];
        (kept.orient * g_om, kept.orient * g_p)
    } else {
        (0.0, 0.0)
    };
    *frozen = Some(kept);
    *v_out = v;
    Ok(Eval {
        res,
        jac,
        side,
        cusp: 0.0,
        scale,
        others_stable: if full {
            others_stable(&mono, block)
        } else {
            None
        },
    })
}
