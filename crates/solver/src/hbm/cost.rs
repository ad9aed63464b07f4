//! What the harmonic balance's operations cost on a given model, in work
//! units: the residual with its Jacobian, the residual alone, a dense LU
//! factorization and a monodromy matrix. One unit is about a microsecond
//! of one core on the machine the weights were fitted on; the weights
//! follow the operations' arithmetic (the Jacobian's channel operator
//! grows with `channels x (2 H + 1)^2`, its fill with the square of the
//! unknowns, the LU with their cube, a monodromy with its RK4 steps times
//! the cube of the block size), so that a count of operations times these
//! weights measures a computation's work on any model, and an estimate in
//! the same units can be checked against it.
//!
//! The weights were fitted on the gear pair and the compound set at H = 1
//! to 21 (the best of seven timings of `Assembly::evaluate`, `Lu::new`,
//! `monodromy_matrices` and a new assembly, at Omega 0.7, on one core):
//! the exact Jacobian took 1.0 us (gear pair, H = 1) to 307 us (compound
//! set, H = 21), the LU 0.07 ns times the cube of its size, a monodromy
//! 0.13 to 2.4 us a step; each weight is within a factor of 2 of every
//! timing, most within 30 %.

use super::harmonic::{n_coef, Grid};
use super::model::HbmModel;

/// Work units (about a microsecond each) of one harmonic-balance operation
/// on one model at one number of harmonics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HbmCost {
    /// Coordinates.
    m: usize,
    /// Nonlinear channels.
    channels: usize,
    /// Fourier coefficients per coordinate, `2 H + 1`.
    nc: usize,
    /// Whether a planet block is integrated beside the main one.
    planet: bool,
    /// Highest natural frequency over omega_ref (sets the monodromy's steps).
    omega_max: f64,
}

impl HbmCost {
    /// The costs on `model` at `h` harmonics.
    pub fn of(model: &HbmModel, h: usize) -> Self {
        HbmCost {
            m: model.m,
            channels: model.channels.len(),
            nc: n_coef(h),
            planet: model.planet_block.is_some(),
            omega_max: model.omega_max,
        }
    }

    /// Unknowns of the harmonic balance, `m (2 H + 1)`.
    pub fn unknowns(&self) -> usize {
        self.m * self.nc
    }

    /// The residual alone (exact method): the channels' integration
    /// between their contact switches.
    pub fn residual(&self) -> f64 {
        let (m, ch, nc) = (self.m as f64, self.channels as f64, self.nc as f64);
        1.0 + 0.008 * ch * nc * nc + 0.03 * m * ch * nc
    }

    /// The residual and its Jacobian: the channels' multiplication
    /// operators and the fill of the `nx x nx` matrix besides.
    pub fn jacobian(&self) -> f64 {
        let (ch, nc) = (self.channels as f64, self.nc as f64);
        let nx = self.unknowns() as f64;
        self.residual() + 0.004 * ch * nc * nc + 0.005 * nx * nx
    }

    /// A new assembly: the parameter set's system, its harmonic-balance
    /// model (the modal basis) and a copy of the shared time grid, whose
    /// tables (`grid x (2 H + 1)` sines and cosines) cost some four times
    /// as much per entry from about a megabyte on (fresh pages: 1.3 to
    /// 1.6 ms at H = 21; between H = 11 and 15 the allocator reused its
    /// memory on the compound set, 40 to 50 us, and not on the gear pair,
    /// 385 to 594 us).
    pub fn assembly(&self) -> f64 {
        let m = self.m as f64;
        let entries = Grid::default_size((self.nc - 1) / 2) * self.nc;
        let per_entry = if 16 * entries > 1 << 20 { 0.015 } else { 0.004 };
        5.0 + 0.12 * m * m * m + per_entry * entries as f64
    }

    /// The LU factorization of a dense matrix of size `n`.
    pub fn factor(n: usize) -> f64 {
        let n = n as f64;
        0.1 + 7e-5 * n * n * n
    }

    /// One Newton iteration of a branch or curve: a Jacobian and the
    /// factorization of the bordered system (the unknowns plus one).
    pub fn newton_iteration(&self) -> f64 {
        self.jacobian() + Self::factor(self.unknowns() + 1)
    }

    /// A monodromy matrix at `omega`: RK4 steps at 16 per period of the
    /// fastest mode (`stability::ORBIT_STEPS_PER_FASTEST`) plus the pieces
    /// between contact switches, each step four products of the block's
    /// matrix with its `2 m` tangent vectors (and the planet block's) and
    /// the channels' slopes read on the orbit.
    pub fn monodromy(&self, omega: f64) -> f64 {
        let omega = omega.max(1e-3);
        let steps = 16.0 * self.omega_max.max(omega) / omega + 2.0 * self.channels as f64;
        let m = self.m as f64;
        let block = 16.0 * m * m * m + if self.planet { 128.0 } else { 0.0 };
        let per_step = 0.1 + 4e-4 * block + 0.01 * (self.channels * self.nc) as f64;
        steps * per_step
    }

    /// The mean of [`HbmCost::monodromy`] over Omega evenly spread from
    /// `from` to `to` (its steps go as `1 / Omega`).
    pub fn mean_monodromy(&self, from: f64, to: f64) -> f64 {
        let n = 16;
        (0..n)
            .map(|i| self.monodromy(from + (to - from) * (f64::from(i) + 0.5) / f64::from(n)))
            .sum::<f64>()
            / f64::from(n)
    }
}
