//! What the augmented systems share: one evaluation's result ([`Eval`])
//! and the bordered matrix `[A b; c^T 0]` whose last unknown vanishes
//! where `A` is singular (the fold's and the period doubling's test), and
//! the branch rows every system starts from: the residual, its Jacobian in
//! `(X, Omega)`, its derivative in `p`, and how `X` moves along the branch.

use super::family::Family;
use crate::error::{Result, SolverError};
use nalgebra::{DMatrix, DVector};

/// One evaluation of an augmented system.
#[derive(Debug, Clone)]
pub(crate) struct Eval {
    /// The residual, `n - 1` entries.
    pub(crate) res: DVector<f64>,
    /// Its Jacobian, `(n - 1) x n`.
    pub(crate) jac: DMatrix<f64>,
    /// A vector in `(Omega, p)` pointing to the side where the change the
    /// curve marks has not happened (the branch still exists, the contact
    /// has not begun); zero in a corrector's iterates (see
    /// [`super::systems::System::eval`]).
    pub(crate) side: (f64, f64),
    /// The cusp test (folds only; zero otherwise).
    pub(crate) cusp: f64,
    /// Scale of the orbit (largest coefficient, um).
    pub(crate) scale: f64,
    /// Period doublings only: whether every other Floquet multiplier is
    /// inside the unit circle (the doubling happens on a stable orbit);
    /// `None` in a corrector's iterates.
    pub(crate) others_stable: Option<bool>,
}

/// The bordered matrix `[J b; c^T 0]`.
pub(crate) fn bordered(jx: &DMatrix<f64>, b: &DVector<f64>, c: &DVector<f64>) -> DMatrix<f64> {
    let nx = jx.nrows();
    let mut a = DMatrix::zeros(nx + 1, nx + 1);
    a.view_mut((0, 0), (nx, nx)).copy_from(&jx.columns(0, nx));
    for i in 0..nx {
        a[(i, nx)] = b[i];
        a[(nx, i)] = c[i];
    }
    a
}

/// Solves `[A b; c^T 0] [v; g] = [0; 1]`: `(g, v)`.
pub(crate) fn bordered_solve(
    a: &DMatrix<f64>,
    b: &DVector<f64>,
    c: &DVector<f64>,
    omega: f64,
) -> Result<(f64, DVector<f64>)> {
    let n = a.nrows();
    let mut e = DVector::zeros(n + 1);
    e[n] = 1.0;
    let sol = crate::dense::Lu::new(bordered(a, b, c))
        .solve(&e)
        .ok_or_else(|| SolverError::Singular {
            what: format!("bordered matrix at Omega = {omega}"),
        })?;
    Ok((sol[n], sol.rows(0, n).into_owned()))
}

/// The largest absolute entry of `v` (0 when empty).
pub(crate) fn inf_norm(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |m, x| m.max(x.abs()))
}

/// The branch's residual at `(x, omega, p)` and its Jacobian in
/// `(X, Omega)` (`nx x (nx + 1)`).
pub(crate) fn residual_at(
    fam: &mut Family,
    x: &[f64],
    omega: f64,
    p: f64,
) -> Result<(Vec<f64>, DMatrix<f64>)> {
    let nx = x.len();
    let mut r = vec![0.0; nx];
    let mut j = DMatrix::zeros(nx, nx + 1);
    fam.evaluate(x, omega, p, &mut r, Some(&mut j))?;
    Ok((r, j))
}

/// The residual's derivative in `p` at `(x, omega)`, differenced between
/// the family's neighbours of `p` ([`Family::neighbours`]); `r` is the
/// residual at `p` itself.
pub(crate) fn residual_p(
    fam: &mut Family,
    x: &[f64],
    omega: f64,
    p: f64,
    r: &[f64],
) -> Result<Vec<f64>> {
    let nx = x.len();
    let (lo, hi) = fam.neighbours(p);
    let (other, sign) = if hi == p { (lo, -1.0) } else { (hi, 1.0) };
    let mut ro = vec![0.0; nx];
    fam.evaluate(x, omega, other, &mut ro, None)?;
    Ok((0..nx).map(|i| sign * (ro[i] - r[i]) / (hi - lo)).collect())
}

/// The residual and Jacobian of a system in `z = (X, Omega, p)` with one
/// test row below the branch rows: the branch rows are filled (`r`, the
/// `(X, Omega)` Jacobian `j`, the `p` column `r_p`), the test row is left
/// at zero for the caller.
pub(crate) fn branch_rows(
    r: &[f64],
    j: &DMatrix<f64>,
    r_p: &[f64],
) -> (DVector<f64>, DMatrix<f64>) {
    let nx = r.len();
    let mut res = DVector::zeros(nx + 1);
    let mut jac = DMatrix::zeros(nx + 1, nx + 2);
    for i in 0..nx {
        res[i] = r[i];
        for k in 0..=nx {
            jac[(i, k)] = j[(i, k)];
        }
        jac[(i, nx + 1)] = r_p[i];
    }
    (res, jac)
}

/// How `X` moves along the branch per unit `Omega` and per unit `p`:
/// `dX = -J^-1 (R_Omega dOmega + R_p dp)`, from the `(X, Omega)` Jacobian
/// `j` and the `p` derivative `r_p`; zero where `J` is singular.
pub(crate) fn branch_motion(j: &DMatrix<f64>, r_p: &[f64]) -> (DVector<f64>, DVector<f64>) {
    let nx = j.nrows();
    motion(&factor(j), j, r_p).unwrap_or_else(|| (DVector::zeros(nx), DVector::zeros(nx)))
}

/// The directions in `X` that the branch rows leave open at an iterate:
/// the Newton step's part at fixed `(Omega, p)` (`J^-1 R`) and how `X`
/// moves along the branch per unit `Omega` and per unit `p`
/// ([`branch_motion`]).
pub(crate) struct Directions {
    pub(crate) newton: DVector<f64>,
    pub(crate) omega: DVector<f64>,
    pub(crate) p: DVector<f64>,
}

/// [`Directions`] from one factorization of `dR/dX`; `None` where it is
/// singular.
pub(crate) fn branch_directions(j: &DMatrix<f64>, r: &[f64], r_p: &[f64]) -> Option<Directions> {
    let lu = factor(j);
    let (omega, p) = motion(&lu, j, r_p)?;
    Some(Directions {
        newton: lu.solve(&DVector::from_column_slice(r))?,
        omega,
        p,
    })
}

/// The factorization of `dR/dX`, the first `nx` columns of `j`.
fn factor(j: &DMatrix<f64>) -> crate::dense::Lu {
    let nx = j.nrows();
    crate::dense::Lu::new(j.columns(0, nx).into_owned())
}

/// `-J^-1 R_Omega` and `-J^-1 R_p` from the factorization `lu` of `J`.
fn motion(
    lu: &crate::dense::Lu,
    j: &DMatrix<f64>,
    r_p: &[f64],
) -> Option<(DVector<f64>, DVector<f64>)> {
    let nx = j.nrows();
    Some((
        -lu.solve(&j.column(nx).into_owned())?,
        -lu.solve(&DVector::from_column_slice(r_p))?,
    ))
}
