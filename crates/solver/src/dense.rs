//! Dense linear algebra for the solver's square real systems: the LU
//! factorization with partial pivoting of the correctors' systems (the
//! harmonic balance's bordered Jacobians, the shooting and boundary
//! correctors), and eigenvalues with a bounded iteration.
//!
//! It performs nalgebra's `LU` arithmetic operation for operation (the same
//! pivots, the same products and sums in the same order, so the same bits),
//! but on the matrix's contiguous column-major storage. nalgebra's generic
//! kernel runs its column updates through strided views that the compiler
//! does not vectorize: on the harmonic balance's 76 x 76 Jacobian it ran at
//! about 0.5 floating-point operations per instruction, and the
//! factorization was 29 % of a branch's instructions. Here the update of a
//! column is a plain loop over two slices.

use nalgebra::{Complex, DMatrix, DVector};

/// The eigenvalues of the square matrix `a`, by nalgebra's real Schur
/// form at its default tolerance (machine epsilon), but with at most
/// [`SCHUR_ITERATIONS`] QR sweeps; `None` if they do not converge or a
/// value is not finite.
///
/// nalgebra's `complex_eigenvalues` allows unlimited sweeps: on a matrix
/// whose iteration stagnates above machine epsilon it never returns (a
/// boundary trace's period-doubling test met one and hung the page's map).
pub fn eigenvalues(a: &DMatrix<f64>) -> Option<Vec<Complex<f64>>> {
    eigenvalues_with(a, f64::EPSILON, SCHUR_ITERATIONS)
}

/// [`eigenvalues`] with the Schur form's tolerance `eps` and at most
/// `max_sweeps` QR sweeps (the Floquet multipliers' 1e-14). Every
/// eigenvalue in the solver comes from here.
pub fn eigenvalues_with(
    a: &DMatrix<f64>,
    eps: f64,
    max_sweeps: usize,
) -> Option<Vec<Complex<f64>>> {
    if a.iter().any(|v| !v.is_finite()) {
        return None;
    }
    let schur = nalgebra::linalg::Schur::try_new(a.clone(), eps, max_sweeps)?;
    let values: Vec<Complex<f64>> = schur.complex_eigenvalues().iter().copied().collect();
    values
        .iter()
        .all(|v| v.re.is_finite() && v.im.is_finite())
        .then_some(values)
}

/// Columns factored together before their steps are applied to the
/// columns right of them ([`Lu::new`]).
const PANEL: usize = 16;

/// QR sweeps [`eigenvalues`] allows before it gives up.
pub(crate) const SCHUR_ITERATIONS: usize = 100_000;

/// The factors `P A = L U` of a square matrix: unit lower `L` below the
/// diagonal and `U` on and above it, in one column-major buffer, and the
/// row transpositions applied at each step.
#[derive(Debug, Clone)]
pub struct Lu {
    n: usize,
    /// Column-major `n x n`: `lu[c * n + r]` is row `r`, column `c`.
    lu: Vec<f64>,
    /// At step `i`, row `i` was swapped with row `swaps[i]` (`i` if none).
    swaps: Vec<usize>,
}

impl Lu {
    /// Factors the square matrix `a`. A column with no nonzero entry on or
    /// below the diagonal is skipped (as nalgebra does); [`Lu::solve`] then
    /// reports the matrix singular. A non-square `a` is factored as the
    /// empty matrix, whose solves fail.
    pub fn new(a: DMatrix<f64>) -> Self {
        crate::simd::dispatch(
            #[inline(always)]
            || Self::factor(a),
        )
    }

    /// [`Lu::new`]'s body, inlined into the vector unit's dispatch.
    #[cfg_attr(target_arch = "x86_64", inline(always))]
    fn factor(a: DMatrix<f64>) -> Self {
        let (n, cols) = a.shape();
        if n != cols {
            return Lu {
                n: 0,
                lu: Vec::new(),
                swaps: Vec::new(),
            };
        }
        let mut lu: Vec<f64> = a.data.into();
        let mut swaps = Vec::with_capacity(n);
        // Whether step `i` found a pivot (a column of zeros is skipped).
        let mut pivoted = Vec::with_capacity(n);
        // Panels of `PANEL` columns: a panel is factored step by step
        // (right-looking inside it), then its steps are applied to each
        // column right of it in turn, so that a column stays in the cache
        // through all of a panel's steps instead of the whole trailing
        // matrix being streamed at every step. Every entry still receives
        // its swaps and updates in the order of the steps, each update one
        // product and one sum as before: the same bits.
        for p0 in (0..n).step_by(PANEL) {
            let p1 = (p0 + PANEL).min(n);
            for i in p0..p1 {
                // The first entry of largest modulus on or below the diagonal.
                let col = &lu[i * n..(i + 1) * n];
                let mut piv = i;
                let mut max = col[i].abs();
                for (r, v) in col.iter().enumerate().skip(i + 1) {
                    if v.abs() > max {
                        max = v.abs();
                        piv = r;
                    }
                }
                let diag = col[piv];
                if diag == 0.0 {
                    swaps.push(i);
                    pivoted.push(false);
                    continue;
                }
                swaps.push(piv);
                pivoted.push(true);
                if piv != i {
                    for c in 0..p1 {
                        lu.swap(c * n + i, c * n + piv);
                    }
                }
                let inv_diag = 1.0 / diag;
                for v in &mut lu[i * n + i + 1..(i + 1) * n] {
                    *v *= inv_diag;
                }
                let (left, right) = lu.split_at_mut((i + 1) * n);
                let coeffs = &left[i * n + i + 1..];
                for column in right[..(p1 - i - 1) * n].chunks_exact_mut(n) {
                    let p = -column[i];
                    for (y, &x) in column[i + 1..].iter_mut().zip(coeffs) {
                        *y += p * x;
                    }
                }
            }
            if p1 == n {
                break;
            }
            // The panel's steps on the columns right of it, four columns
            // at a time sharing each load of a step's multipliers: first
            // its row swaps, then its updates with the multipliers as the
            // later swaps left them (a swap at step `k` moves rows `k` and
            // below only, and moves a column's rows with the multipliers'
            // rows, so every product pairs the same two numbers).
            let (left, right) = lu.split_at_mut(p1 * n);
            let mut quads = right.chunks_exact_mut(4 * n);
            for quad in &mut quads {
                let (c0, rest) = quad.split_at_mut(n);
                let (c1, rest) = rest.split_at_mut(n);
                let (c2, c3) = rest.split_at_mut(n);
                for (i, &piv) in swaps.iter().enumerate().skip(p0) {
                    c0.swap(i, piv);
                    c1.swap(i, piv);
                    c2.swap(i, piv);
                    c3.swap(i, piv);
                }
                for i in p0..p1 {
                    if !pivoted[i] {
                        continue;
                    }
                    let coeffs = &left[i * n + i + 1..(i + 1) * n];
                    let p = [-c0[i], -c1[i], -c2[i], -c3[i]];
                    let rows = c0[i + 1..]
                        .iter_mut()
                        .zip(&mut c1[i + 1..])
                        .zip(&mut c2[i + 1..])
                        .zip(&mut c3[i + 1..])
                        .zip(coeffs);
                    for ((((y0, y1), y2), y3), &x) in rows {
                        *y0 += p[0] * x;
                        *y1 += p[1] * x;
                        *y2 += p[2] * x;
                        *y3 += p[3] * x;
                    }
                }
            }
            for column in quads.into_remainder().chunks_exact_mut(n) {
                for (i, &piv) in swaps.iter().enumerate().skip(p0) {
                    column.swap(i, piv);
                }
                for i in p0..p1 {
                    if !pivoted[i] {
                        continue;
                    }
                    let coeffs = &left[i * n + i + 1..(i + 1) * n];
                    let p = -column[i];
                    for (y, &x) in column[i + 1..].iter_mut().zip(coeffs) {
                        *y += p * x;
                    }
                }
            }
        }
        Lu { n, lu, swaps }
    }

    /// The factors' storage as an `n x n` matrix (its entries are the
    /// factors'), to be filled again for the next factorization without a
    /// new allocation.
    pub fn into_matrix(self) -> DMatrix<f64> {
        DMatrix::from_vec(self.n, self.n, self.lu)
    }

    /// The solution of `A x = b`; `None` if `U` has a zero on its diagonal
    /// or `b`'s length is not `A`'s order.
    pub fn solve(&self, b: &DVector<f64>) -> Option<DVector<f64>> {
        crate::simd::dispatch(
            #[inline(always)]
            || self.solve_here(b),
        )
    }

    /// [`Lu::solve`]'s body, inlined into the vector unit's dispatch.
    #[cfg_attr(target_arch = "x86_64", inline(always))]
    fn solve_here(&self, b: &DVector<f64>) -> Option<DVector<f64>> {
        let n = self.n;
        if b.len() != n || n == 0 {
            return None;
        }
        let mut x: Vec<f64> = b.iter().copied().collect();
        for (i, &p) in self.swaps.iter().enumerate() {
            x.swap(i, p);
        }
        // L y = P b, unit diagonal, column by column.
        for i in 0..n.saturating_sub(1) {
            let coeff = -x[i];
            let column = &self.lu[i * n + i + 1..(i + 1) * n];
            for (y, &l) in x[i + 1..].iter_mut().zip(column) {
                *y += coeff * l;
            }
        }
        // U x = y, from the last row up.
        for i in (0..n).rev() {
            let diag = self.lu[i * n + i];
            if diag == 0.0 {
                return None;
            }
            let coeff = x[i] / diag;
            x[i] = coeff;
            let column = &self.lu[i * n..i * n + i];
            for (y, &u) in x[..i].iter_mut().zip(column) {
                *y += -coeff * u;
            }
        }
        Some(DVector::from_vec(x))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn matrix(n: usize, seed: u64) -> DMatrix<f64> {
        // A deterministic, well-mixed fill (a linear congruential generator).
        let mut s = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        DMatrix::from_fn(n, n, |_, _| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
    }

    #[test]
    fn solves_to_the_same_bits_as_nalgebra() {
        for (n, seed) in [(1, 1), (2, 2), (5, 3), (10, 4), (31, 5), (76, 6)] {
            let a = matrix(n, seed);
            let b = DVector::from_fn(n, |i, _| (i as f64 * 0.37).sin());
            let ours = Lu::new(a.clone()).solve(&b).expect("regular");
            let theirs = a.clone().lu().solve(&b).expect("regular");
            assert_eq!(ours.as_slice(), theirs.as_slice(), "n = {n}");
            let residual = (&a * &ours - &b).amax();
            assert!(residual < 1e-12 * (n as f64), "n = {n}: {residual:e}");
        }
    }

    #[test]
    fn eigenvalues_are_nalgebras_and_a_bad_matrix_has_none() {
        let a = matrix(9, 21);
        let ours = eigenvalues(&a).expect("converges");
        let theirs: Vec<Complex<f64>> = a.complex_eigenvalues().iter().copied().collect();
        assert_eq!(ours, theirs);
        // A rotation by 90 degrees: the eigenvalues +-i exactly.
        let r = DMatrix::from_row_slice(2, 2, &[0.0, -1.0, 1.0, 0.0]);
        let mut z = eigenvalues(&r).expect("converges");
        z.sort_by(|u, v| u.im.total_cmp(&v.im));
        assert_eq!(z, vec![Complex::new(0.0, -1.0), Complex::new(0.0, 1.0)]);
        let mut nan = matrix(4, 2);
        nan[(1, 2)] = f64::NAN;
        assert!(eigenvalues(&nan).is_none());
    }

    #[test]
    fn a_singular_matrix_has_no_solution() {
        let mut a = matrix(6, 9);
        for r in 0..6 {
            a[(r, 3)] = 0.0;
        }
        let b = DVector::from_element(6, 1.0);
        assert!(Lu::new(a.clone()).solve(&b).is_none());
        assert!(a.lu().solve(&b).is_none());
        let rect = DMatrix::from_element(2, 3, 1.0);
        assert!(Lu::new(rect)
            .solve(&DVector::from_element(2, 1.0))
            .is_none());
        assert!(Lu::new(DMatrix::identity(3, 3))
            .solve(&DVector::from_element(2, 1.0))
            .is_none());
    }

    proptest! {
        #[test]
        fn matches_nalgebra_on_any_matrix(
            n in 1usize..24,
            seed in any::<u64>(),
            zero_col in proptest::option::of(0usize..24),
        ) {
            let mut a = matrix(n, seed);
            if let Some(c) = zero_col.filter(|&c| c < n) {
                for r in 0..n {
                    a[(r, c)] = 0.0;
                }
            }
            let b = DVector::from_fn(n, |i, _| 1.0 + i as f64);
            let ours = Lu::new(a.clone()).solve(&b);
            let theirs = a.lu().solve(&b);
            prop_assert_eq!(
                ours.map(|v| v.as_slice().to_vec()),
                theirs.map(|v| v.as_slice().to_vec())
            );
        }
    }
}
