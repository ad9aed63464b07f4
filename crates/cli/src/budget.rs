//! Caps on the work and memory of one command (one shard of a sharded
//! run), as `map` caps its cells: each option has its own range, and these
//! bound their product, so no combination runs for days or fills memory
//! before writing anything.

use crate::failure::{usage, Failure};

/// Most mesh periods one command integrates (some hours on one core at
/// the 20-70 us a period takes; split larger runs with `--shard`).
pub const MAX_PERIODS: u64 = 100_000_000;
/// Most Poincaré samples (points x directions x meshes x recorded
/// periods) one bifurcation command keeps for its output (some hundred
/// MB once written as JSON).
pub const MAX_SAMPLES: u64 = 2_000_000;
/// Most `--points x (2 --harmonics + 1)^3` of one frequency response: a
/// Newton step solves a dense system of (2 H + 1) unknowns per
/// coordinate, so its work grows like the cube; this allows every point
/// count up to H = 27 and some hours at H = 40.
pub const MAX_FRF_WORK: u64 = 2_000_000_000;
/// Most `--levels x --points x (2 --harmonics + 1)^3` of one boundary
/// trace: each level is a frequency response of `--points`, and each curve
/// point a corrector whose iterations assemble some seven Jacobians, so a
/// tenth of a frequency response's budget per level.
pub const MAX_BOUNDARY_WORK: u64 = 200_000_000;

/// Checks `periods` (the product `formula` of the options) against
/// [`MAX_PERIODS`]; `split` says how to split a larger run.
pub fn check_work(periods: u64, formula: &str, split: &str) -> Result<(), Failure> {
    if periods > MAX_PERIODS {
        return Err(usage(format!(
            "{formula} = {periods} mesh periods is more than the {} one command may integrate: \
             use fewer points or periods, or {split}",
            MAX_PERIODS
        )));
    }
    Ok(())
}
