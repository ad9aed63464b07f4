//! The mesh phase's sine and cosine, one portable routine for native and
//! WebAssembly builds.
//!
//! The equations of motion need `sin(omega t)` and `cos(omega t)` at every
//! right-hand side evaluation. Natively `f64::sin_cos` calls the C library;
//! in wasm32 it is Rust's software `libm`, which made `simulate` about 1.7x
//! slower there than natively. [`phase_sin_cos`] uses only `+ - * floor`,
//! which wasm executes as native instructions, so both builds compute the
//! same bits: a run in the browser reproduces the CLI's run exactly.
//!
//! Method (fdlibm's): reduce `x` by multiples of `pi/2` with a three-part
//! Cody–Waite constant (exact products for `|x| < 2^20`), then the fdlibm
//! kernel polynomials on `[-pi/4, pi/4]`. The error is below 2 ulp of 1 for
//! `|x| <= 1e5` rad (tested against the standard library); larger arguments
//! fall back to `f64::sin_cos`.

// The constants are fdlibm's decimal spellings, kept digit for digit so they
// can be checked against the source; they round to the intended doubles.
#![allow(clippy::excessive_precision)]

use std::f64::consts::FRAC_2_PI;

/// `pi/2` in three parts: 33 + 33 + 53 bits.
const PIO2_1: f64 = 1.570_796_326_734_125_614_17e+00;
const PIO2_2: f64 = 6.077_100_506_303_965_976_6e-11;
const PIO2_3: f64 = 2.022_266_248_711_166_455_8e-21;

/// fdlibm `__kernel_sin` coefficients.
const S1: f64 = -1.666_666_666_666_663_243_48e-01;
const S2: f64 = 8.333_333_333_322_489_461_24e-03;
const S3: f64 = -1.984_126_982_985_794_931_34e-04;
const S4: f64 = 2.755_731_370_707_006_767_89e-06;
const S5: f64 = -2.505_076_025_340_686_341_95e-08;
const S6: f64 = 1.589_690_995_211_550_102_21e-10;

/// fdlibm `__kernel_cos` coefficients.
const C1: f64 = 4.166_666_666_666_660_190_37e-02;
const C2: f64 = -1.388_888_888_887_410_957_49e-03;
const C3: f64 = 2.480_158_728_947_672_941_78e-05;
const C4: f64 = -2.755_731_435_139_066_330_35e-07;
const C5: f64 = 2.087_572_321_298_174_827_90e-09;
const C6: f64 = -1.135_964_755_778_819_482_65e-11;

/// Largest argument reduced here; beyond it the standard library serves.
const REDUCE_MAX: f64 = 1e5;

/// `(sin x, cos x)`.
#[inline]
pub(crate) fn phase_sin_cos(x: f64) -> (f64, f64) {
    if x.abs() > REDUCE_MAX || !x.is_finite() {
        return x.sin_cos();
    }
    let q = (x * FRAC_2_PI + 0.5).floor();
    let r = ((x - q * PIO2_1) - q * PIO2_2) - q * PIO2_3;
    let z = r * r;
    let s = r + r * z * (S1 + z * (S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    let c =
        w + (((1.0 - w) - hz) + z * z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6))))));
    // q is an integer below 2^17 in magnitude here.
    match (q as i64).rem_euclid(4) {
        0 => (s, c),
        1 => (c, -s),
        2 => (-s, -c),
        _ => (-c, s),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_standard_library_to_two_ulp() {
        let mut worst: f64 = 0.0;
        let mut x = -1e5;
        // An irrational step visits every quadrant and phase.
        while x < 1e5 {
            let (s, c) = phase_sin_cos(x);
            let (s0, c0) = x.sin_cos();
            worst = worst.max((s - s0).abs()).max((c - c0).abs());
            x += 0.618_033_988_749_894_8 * 3.7;
        }
        assert!(worst <= 2.0 * f64::EPSILON, "worst error {worst:e}");
        // Small arguments keep full relative accuracy.
        for x in [1e-300, 1e-20, -1e-12] {
            let (s, c) = phase_sin_cos(x);
            assert_eq!(s, x);
            assert_eq!(c, 1.0);
        }
    }

    #[test]
    fn quadrant_points_and_fallbacks() {
        use std::f64::consts::{FRAC_PI_2, PI};
        for (k, x) in [0.0, FRAC_PI_2, PI, 3.0 * FRAC_PI_2, -FRAC_PI_2]
            .into_iter()
            .enumerate()
        {
            let (s, c) = phase_sin_cos(x);
            let (s0, c0) = x.sin_cos();
            assert!((s - s0).abs() < 1e-15 && (c - c0).abs() < 1e-15, "{k}");
        }
        assert_eq!(phase_sin_cos(1e7), 1e7_f64.sin_cos());
        assert!(phase_sin_cos(f64::NAN).0.is_nan());
    }
}
