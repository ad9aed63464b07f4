//! The period-doubling test function on the harmonic-balance branch: the
//! monodromy matrix `M` of the orbit (as [`crate::hbm::stability`] computes
//! its Floquet multipliers) has a multiplier at -1 where the bordered
//! `[M + I b; c^T 0] [v; g] = [0; 1]` gives `g = 0`. The monodromy is
//! integrated piecewise between the contact switches, so `g`'s derivatives
//! are differenced, and only along the three directions the Newton steps
//! and tangents can take ([`reduced_gradient`]): the branch rows pin every
//! other. That is three monodromies an evaluation against `n + 2` for the
//! whole gradient, and the Newton is exact (the gradient kept through a
//! chord corrector before it needed more iterations and shorter steps).
//!
//! Stable side: the side where the critical multiplier is inside the unit
//! circle (`lambda > -1`), read from how `g` and `lambda + 1` move together
//! along the branch.

use super::bordered::{
    bordered_solve, branch_directions, branch_rows, inf_norm, residual_at, residual_p, Directions,
    Eval,
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
/// `(b, c)`. Without `full` (a corrector's iterate), the side and the
/// other multipliers' stability, which only an accepted point reports, are
/// not computed.
pub(crate) fn eval(
    fam: &mut Family,
    z: &[f64],
    block: usize,
    (b, c): (&DVector<f64>, &DVector<f64>),
    v_out: &mut DVector<f64>,
    full: bool,
) -> Result<Eval> {
    let nx = z.len() - 2;
    let (x, omega, p) = (&z[..nx], z[nx], z[nx + 1]);
    let (r, j) = residual_at(fam, x, omega, p)?;
    let r_p = residual_p(fam, x, omega, p, &r)?;
    // One monodromy at `z` gives the test function, its orientation's
    // first multiplier and the other multipliers' stability.
    let mono = monodromies(fam, x, omega, p)?;
    let a = shifted_of(&mono, block, omega)?;
    let (g, v) = bordered_solve(&a, b, c, omega)?;
    let scale = 1.0 + inf_norm(x);
    fam.factored(nx);
    let Some(dirs) = branch_directions(&j, &r, &r_p) else {
        return Err(SolverError::Singular {
            what: format!("harmonic-balance Jacobian at Omega = {omega}"),
        });
    };
    let grad = reduced_gradient(fam, z, block, (b, c), g, &dirs, scale)?;
    let (mut res, mut jac) = branch_rows(&r, &j, &r_p);
    res[nx] = g;
    for (k, &gk) in grad.iter().enumerate() {
        jac[(nx, k)] = gk;
    }
    // g along the branch: the reduced gradient holds it exactly.
    let side = if full {
        let g_x = DVector::from_column_slice(&grad[..nx]);
        let g_om = g_x.dot(&dirs.omega) + grad[nx];
        let g_p = g_x.dot(&dirs.p) + grad[nx + 1];
        // Whether g grows with lambda + 1: a small step along the branch in Omega.
        let step = 1e-4 * (1.0 + omega.abs());
        let moved: Vec<f64> = (0..nx).map(|i| x[i] + step * dirs.omega[i]).collect();
        let mu0 = critical_of(&a);
        let mu1 = critical(fam, &moved, omega + step, p, block)?;
        let orient = if (mu1 - mu0) * g_om >= 0.0 { 1.0 } else { -1.0 };
        (orient * g_om, orient * g_p)
    } else {
        (0.0, 0.0)
    };
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

/// A gradient of `g` in `(X, Omega, p)` that is exact where the system's
/// Newton steps and tangents use it. Every such vector `dz` solves the
/// branch rows' `J_R dz = R` (or `= 0`), so it lies in the span of
/// `(J^-1 R, 0, 0)`, `(dX/dOmega, 1, 0)` and `(dX/dp, 0, 1)`: `g`'s three
/// directional derivatives along them (one monodromy each, differenced)
/// fix the row, in place of `n + 2` monodromies for the whole gradient.
fn reduced_gradient(
    fam: &mut Family,
    z: &[f64],
    block: usize,
    (b, c): (&DVector<f64>, &DVector<f64>),
    g: f64,
    dirs: &Directions,
    scale: f64,
) -> Result<Vec<f64>> {
    let nx = z.len() - 2;
    let (omega, p) = (z[nx], z[nx + 1]);
    let along = |fam: &mut Family, dx: &DVector<f64>, d_om: f64, d_p: f64, h: f64| {
        let mut zz = z.to_vec();
        for i in 0..nx {
            zz[i] += h * dx[i];
        }
        zz[nx] += h * d_om;
        zz[nx + 1] += h * d_p;
        test(fam, &zz, block, b, c).map(|(gh, _)| (gh - g) / h)
    };
    // Forward in p inside the key's range, backward at its upper limit (a
    // start at backlash_um = 1000 was otherwise refused as out of range).
    let (p_lo, p_hi) = fam.neighbours(p);
    let h_p = if p_hi > p { p_hi - p } else { p_lo - p };
    let d_om = along(fam, &dirs.omega, 1.0, 0.0, 1e-7 * (1.0 + omega.abs()))?;
    let d_p = along(fam, &dirs.p, 0.0, 1.0, h_p)?;
    let norm = dirs.newton.norm();
    let d_newton = if norm > 0.0 && norm.is_finite() {
        let u = &dirs.newton / norm;
        let d_u = along(fam, &u, 0.0, 0.0, 1e-6 * scale)?;
        Some((u, d_u))
    } else {
        None
    };
    Ok(reduced_row(dirs, d_newton, d_om, d_p))
}

/// The row `G` with `G . (u, 0, 0) = d_u` (for the Newton direction's unit
/// vector `u`, when there is one), `G . (dX/dOmega, 1, 0) = d_om` and
/// `G . (dX/dp, 0, 1) = d_p`: `G = (d_u u, beta, gamma)`.
fn reduced_row(
    dirs: &Directions,
    newton: Option<(DVector<f64>, f64)>,
    d_om: f64,
    d_p: f64,
) -> Vec<f64> {
    let nx = dirs.omega.len();
    let mut grad = vec![0.0; nx + 2];
    grad[nx] = d_om;
    grad[nx + 1] = d_p;
    if let Some((u, d_u)) = newton {
        for i in 0..nx {
            grad[i] = d_u * u[i];
        }
        grad[nx] -= d_u * u.dot(&dirs.omega);
        grad[nx + 1] -= d_u * u.dot(&dirs.p);
    }
    grad
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Entries in [-1, 1) from a fixed linear congruential sequence.
    fn filled(rows: usize, cols: usize, seed: &mut u64) -> DMatrix<f64> {
        DMatrix::from_fn(rows, cols, |_, _| {
            *seed = seed
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (*seed >> 11) as f64 / (1u64 << 52) as f64 - 1.0
        })
    }

    /// The Newton step of `[J_R; G; row] dz = [R; g; s]`.
    fn newton_step(
        jr: &DMatrix<f64>,
        g_row: &[f64],
        row: &[f64],
        rhs: &DVector<f64>,
    ) -> DVector<f64> {
        let (nx, n) = (jr.nrows(), jr.ncols());
        let mut a = DMatrix::zeros(n, n);
        a.view_mut((0, 0), (nx, n)).copy_from(jr);
        for k in 0..n {
            a[(nx, k)] = g_row[k];
            a[(nx + 1, k)] = row[k];
        }
        a.lu().solve(rhs).unwrap()
    }

    #[test]
    fn the_reduced_row_gives_the_full_gradients_newton_steps_and_tangents() {
        let mut seed = 7;
        for nx in [3, 8, 15] {
            // The branch rows `[dR/dX dR/dOmega dR/dp]`, a residual, the
            // full gradient of g and an arclength row, all arbitrary.
            let jr = filled(nx, nx + 2, &mut seed) + DMatrix::identity(nx, nx + 2) * 3.0;
            let r: Vec<f64> = filled(nx, 1, &mut seed).iter().copied().collect();
            let full: Vec<f64> = filled(1, nx + 2, &mut seed).iter().copied().collect();
            let row: Vec<f64> = filled(1, nx + 2, &mut seed).iter().copied().collect();
            let r_p: Vec<f64> = jr.column(nx + 1).iter().copied().collect();
            let dirs = branch_directions(&jr.columns(0, nx + 1).into_owned(), &r, &r_p).unwrap();
            // The three directional derivatives the trace differences.
            let along = |dx: &DVector<f64>, d_om: f64, d_p: f64| {
                (0..nx).map(|i| full[i] * dx[i]).sum::<f64>() + full[nx] * d_om + full[nx + 1] * d_p
            };
            let u = &dirs.newton / dirs.newton.norm();
            let d_u = along(&u, 0.0, 0.0);
            let reduced = reduced_row(
                &dirs,
                Some((u, d_u)),
                along(&dirs.omega, 1.0, 0.0),
                along(&dirs.p, 0.0, 1.0),
            );
            let mut rhs = DVector::zeros(nx + 2);
            rhs.rows_mut(0, nx).copy_from_slice(&r);
            rhs[nx] = 0.3;
            rhs[nx + 1] = -0.2;
            let exact = newton_step(&jr, &full, &row, &rhs);
            let ours = newton_step(&jr, &reduced, &row, &rhs);
            assert!(
                (&exact - &ours).amax() <= 1e-10 * exact.amax(),
                "Newton step, nx = {nx}"
            );
            // The tangent: the same right-hand side without the residuals.
            rhs.rows_mut(0, nx + 1).fill(0.0);
            rhs[nx + 1] = 1.0;
            let exact = newton_step(&jr, &full, &row, &rhs);
            let ours = newton_step(&jr, &reduced, &row, &rhs);
            assert!(
                (&exact - &ours).amax() <= 1e-10 * exact.amax(),
                "tangent, nx = {nx}"
            );
        }
    }
}
