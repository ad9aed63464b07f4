//! The options of a steady-state run: its frequency, transient and
//! recorded periods, samples, tolerances and budgets, with their ranges.

use crate::error::{Result, SolverError};

/// Options of a steady-state run.
#[derive(Debug, Clone, PartialEq)]
pub struct SteadyOptions {
    /// Dimensionless mesh frequency Omega = omega / omega_ref.
    pub omega: f64,
    /// Maximum transient periods.
    pub transient_periods: u32,
    /// Recorded periods.
    pub record_periods: u32,
    /// End the transient once the Poincaré samples have settled.
    pub early_settle: bool,
    /// Uniform samples per period for RMS, history and spectrum (0 = none).
    pub samples_per_period: u32,
    /// Meshes whose time history (and spectrum) is kept.
    pub history_meshes: Vec<usize>,
    /// Relative tolerance of the integrator.
    pub rtol: f64,
    /// Absolute tolerance, as a mesh deflection (m).
    pub atol_m: f64,
    /// Step budget per mesh period (a blow-up guard).
    pub max_steps_per_period: u64,
    /// Find a periodic steady state by shooting during the transient
    /// (`crate::shooting::pipeline`); off, the run only integrates.
    pub shooting: bool,
}

/// Default relative tolerance of the integrator.
pub const DEFAULT_RTOL: f64 = 1e-7;

/// Default absolute tolerance, as a mesh deflection (m): 0.1 nm, a
/// millionth of the default backlash. Periodic orbits then agree with a
/// 1e-12 m run to a few 1e-11 m (a 1e-6 part of their peak-to-peak), an
/// order below the settle and period tests' tolerance, at 1.3 to 1.6 times
/// fewer steps than 1e-11 m.
pub const DEFAULT_ATOL_M: f64 = 1e-10;

impl SteadyOptions {
    /// Defaults at `omega`: 300 + 100 periods, early settle, 64 samples per period.
    pub fn new(omega: f64) -> Self {
        SteadyOptions {
            omega,
            transient_periods: 300,
            record_periods: 100,
            early_settle: true,
            samples_per_period: 64,
            history_meshes: Vec::new(),
            rtol: DEFAULT_RTOL,
            atol_m: DEFAULT_ATOL_M,
            max_steps_per_period: 200_000,
            shooting: true,
        }
    }

    /// Checks the options' ranges.
    pub fn validate(&self) -> Result<()> {
        let bad = |option: &str, value: String, allowed: &str| {
            SolverError::bad_option(option, value, allowed)
        };
        if !(self.omega.is_finite() && self.omega >= 0.01 && self.omega <= 20.0) {
            return bad("omega", format!("{}", self.omega), "0.01 ..= 20");
        }
        if self.transient_periods > 1_000_000 {
            return bad(
                "transient-periods",
                self.transient_periods.to_string(),
                "0 ..= 1000000",
            );
        }
        if self.record_periods == 0 || self.record_periods > 100_000 {
            return bad(
                "record-periods",
                self.record_periods.to_string(),
                "1 ..= 100000",
            );
        }
        if self.samples_per_period > 4096 {
            return bad(
                "samples-per-period",
                self.samples_per_period.to_string(),
                "0 ..= 4096",
            );
        }
        if !(self.rtol.is_finite() && self.rtol >= 1e-13 && self.rtol <= 1e-3) {
            return bad("rtol", format!("{}", self.rtol), "1e-13 ..= 1e-3");
        }
        if !(self.atol_m.is_finite() && self.atol_m > 0.0 && self.atol_m <= 1e-6) {
            return bad("atol", format!("{}", self.atol_m), "0 < atol <= 1e-6 m");
        }
        Ok(())
    }
}
