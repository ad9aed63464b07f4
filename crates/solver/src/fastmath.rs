//! Portable arithmetic for the integrator's hot loops: `max`, `min` and a
//! power function made of plain instructions, so that native and wasm32
//! builds run them at full speed and compute the same bits.
//!
//! In wasm32, `f64::max` and `f64::min` are calls to `fmax`/`fmin` (wasm's
//! own `f64.max` propagates NaN, Rust's does not) and `f64::powf` is Rust's
//! software `libm`: together some 14 % of a regime map's time in node. The
//! step-size controller needs `err^0.17` and `err^0.04` to a few digits;
//! [`log2_pos`] and [`exp2`] give them to about 1e-12 from `+ - * /` and
//! bit operations (one division).

use std::f64::consts::{LN_2, LOG2_E, SQRT_2};

/// The larger of `a` and `b` (for finite or infinite values; with a NaN,
/// `b`), by one comparison.
#[inline(always)]
pub fn max(a: f64, b: f64) -> f64 {
    if a > b {
        a
    } else {
        b
    }
}

/// The smaller of `a` and `b` (for finite or infinite values; with a NaN,
/// `b`), by one comparison.
#[inline(always)]
pub fn min(a: f64, b: f64) -> f64 {
    if a < b {
        a
    } else {
        b
    }
}

/// `log2 x` for a positive, finite `x` (normal or subnormal), to about
/// 1e-13 absolute; NaN for anything else.
///
/// `log2 x = e + log2 m` with `m` in `[sqrt(1/2), sqrt(2))`, `ln m` by the
/// series of `2 atanh(s)`, `s = (m - 1) / (m + 1)`, `|s| <= 0.172` (seven
/// terms: error below 1e-13).
pub(crate) fn log2_pos(x: f64) -> f64 {
    if !(x > 0.0 && x < f64::INFINITY) {
        return f64::NAN;
    }
    // Subnormals: scale into the normal range first.
    let (x, e_bias) = if x < f64::MIN_POSITIVE {
        (x * TWO_64, -64.0)
    } else {
        (x, 0.0)
    };
    let bits = x.to_bits();
    let mut e = ((bits >> 52) & 0x7ff) as f64 - 1023.0 + e_bias;
    let mut m = f64::from_bits((bits & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000);
    if m > SQRT_2 {
        m *= 0.5;
        e += 1.0;
    }
    let s = (m - 1.0) / (m + 1.0);
    let s2 = s * s;
    let series = 1.0
        + s2 * (1.0 / 3.0
            + s2 * (1.0 / 5.0
                + s2 * (1.0 / 7.0 + s2 * (1.0 / 9.0 + s2 * (1.0 / 11.0 + s2 * (1.0 / 13.0))))));
    e + 2.0 * s * series * LOG2_E
}

/// `2^y`, to about 1e-13 relative for `|y| < 1022`; infinity above 1024,
/// zero below -1022 (no subnormal results), NaN for NaN.
///
/// `2^y = 2^k e^t`, `k` the nearest integer, `t = (y - k) ln 2` in
/// `[-0.347, 0.347]`, `e^t` by its Taylor polynomial of degree 11.
pub(crate) fn exp2(y: f64) -> f64 {
    if y.is_nan() {
        return f64::NAN;
    }
    if y >= 1024.0 {
        return f64::INFINITY;
    }
    if y <= -1022.0 {
        return 0.0;
    }
    // The nearest integer without a rounding call (truncation, then one
    // correction for negative values).
    let mut k = (y + 0.5) as i64;
    if k as f64 > y + 0.5 {
        k -= 1;
    }
    let t = (y - k as f64) * LN_2;
    let mut p = EXP_TAYLOR[11];
    for c in EXP_TAYLOR[..11].iter().rev() {
        p = c + t * p;
    }
    // k is in [-1021, 1024]: 2^k as a bit pattern (2^1024 as 2 * 2^1023).
    if k == 1024 {
        return 2.0 * p * f64::from_bits(2046 << 52);
    }
    p * f64::from_bits(((k + 1023) as u64) << 52)
}

/// 2^64.
const TWO_64: f64 = 18_446_744_073_709_551_616.0;

/// 1 / k! for k = 0 ..= 11.
const EXP_TAYLOR: [f64; 12] = [
    1.0,
    1.0,
    1.0 / 2.0,
    1.0 / 6.0,
    1.0 / 24.0,
    1.0 / 120.0,
    1.0 / 720.0,
    1.0 / 5040.0,
    1.0 / 40320.0,
    1.0 / 362_880.0,
    1.0 / 3_628_800.0,
    1.0 / 39_916_800.0,
];

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn powers_from_log2_and_exp2_match_the_standard_library() {
        let pow_pos = |x: f64, a: f64| exp2(a * log2_pos(x));
        let mut worst: f64 = 0.0;
        for a in [0.17f64, 0.04, -0.2, 0.5, 2.0, 1.0 / 3.0] {
            let mut x: f64 = 1e-300;
            while x < 1e300 {
                if (a * x.log2()).abs() < 1000.0 {
                    let (got, want) = (pow_pos(x, a), x.powf(a));
                    worst = worst.max(((got - want) / want).abs());
                }
                x *= 1.37;
            }
        }
        assert!(worst < 2e-12, "worst relative error {worst:e}");
        assert_eq!(pow_pos(1.0, 0.17), 1.0);
        assert!(log2_pos(-1.0).is_nan() && log2_pos(f64::NAN).is_nan());
        assert_eq!(exp2(2000.0), f64::INFINITY);
        assert_eq!(exp2(-2000.0), 0.0);
        let tiny = 5e-324;
        assert!(((pow_pos(tiny, 0.5) - tiny.powf(0.5)) / tiny.powf(0.5)).abs() < 2e-12);
        for y in [-1021.5, -300.25, -0.5, 0.0, 0.49999, 0.5, 7.0, 1023.4] {
            let want = 2f64.powf(y);
            assert!(((exp2(y) - want) / want).abs() < 1e-13, "2^{y}");
        }
        assert!(log2_pos(0.0).is_nan() && log2_pos(f64::INFINITY).is_nan());
    }

    #[test]
    fn max_and_min_take_the_larger_and_the_smaller() {
        assert_eq!(max(1.0, -2.0), 1.0);
        assert_eq!(max(-2.0, 1.0), 1.0);
        assert_eq!(min(1.0, -2.0), -2.0);
        assert_eq!(min(f64::INFINITY, 3.0), 3.0);
    }
}
