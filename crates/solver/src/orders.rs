//! The mesh force by order: the amplitude spectrum of one mesh's force
//! `F_j(t) = k_j(t) g_j(delta_j - e_j) + c_j (delta_j' - e_j')` over a
//! steady state's recorded periods, in orders of the mesh frequency (order
//! 1 is the mesh frequency), with its peaks labelled, and the same for the
//! force summed over the planets' meshes of that mesh's kind.
//!
//! Sampling. The record is a whole number `P` of mesh periods sampled
//! uniformly (`crate::steady`), so bin `k` of its FFT
//! ([`crate::steady::spectrum`], no window) is order `k / P` exactly: a
//! periodic motion of period `p` mesh periods (`p` dividing `P`) puts its
//! energy only on the multiples of `1 / p`, with no leakage.
//!
//! Labels. A peak at bin `k` is the fraction `k / P` in lowest terms: a
//! whole number `n` reads "n×" (a mesh order), a fraction with a small
//! denominator "1/2×", "3/2×" (a subharmonic of a period-2 orbit and its
//! sidebands), anything else its decimal ("0.37×", a component of motion
//! that does not repeat within the record).
//!
//! Phasing. With sequential phasing planet `n` (position
//! `psi_n = 2 pi (n - 1) / N`) has mesh phase `gamma_n = z psi_n` on a
//! kind whose central member has `z` teeth (`crate::system`; `-z_r` for
//! the ring). If every planet's force is the first planet's shifted by its
//! phase, `F_n(t) = F_1(t + gamma_n / omega)`, harmonic `k` of the sum
//! over the planets is harmonic `k` of one planet times
//! `sum_n exp(i k gamma_n) = sum_n exp(2 pi i k z (n - 1) / N)`, a
//! geometric sum: `N` when `k z / N` is a whole number and 0 otherwise.
//! That is the classic rule (Parker & Lin 2004), here for every kind with
//! its own `z`; [`MeshSystem::phasing_factors`] gives `|sum| / N`. The
//! shift holds exactly when one relabelling of the planets moves every
//! kind's phases by the same angle (`z_s1`, `z_s2` and `-z_r` equal modulo
//! `N`) and the steady state is the symmetric one.

use crate::params::MeshKind;
use crate::steady::{spectrum, SteadyState};
use crate::system::MeshSystem;

/// Largest denominator a fractional order is written with ("3/8×"); a
/// finer fraction is written as a decimal.
pub const MAX_DENOMINATOR: u64 = 8;

/// A peak is labelled when it reaches this fraction of the spectrum's
/// largest line (the mean excluded).
pub const PEAK_FRACTION: f64 = 0.01;

/// Nor is a line labelled below this fraction of the mean force (the
/// integration's error where the phasing cancels every line).
pub const NOISE_FRACTION: f64 = 1e-6;

/// At most this many peaks are labelled (the largest ones).
pub const MAX_PEAKS: usize = 12;

/// Below this fraction of the in-phase sum an order counts as cancelled by
/// the phasing.
pub const CANCELLED: f64 = 1e-6;

/// One labelled line of an order spectrum.
#[derive(Debug, Clone, PartialEq)]
pub struct OrderPeak {
    /// The order (mesh orders).
    pub order: f64,
    /// Its amplitude (N).
    pub amplitude_n: f64,
    /// The order in words: "2×", "1/2×", "0.37×".
    pub label: String,
    /// A whole mesh order.
    pub whole: bool,
}

/// The force summed over the planets' meshes of one kind.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanetSum {
    /// The mesh kind.
    pub kind: MeshKind,
    /// The meshes summed (model indices, by planet).
    pub meshes: Vec<usize>,
    /// Amplitude of the sum at each order of [`ForceOrders::order`] (N).
    pub amplitude_n: Vec<f64>,
    /// Its labelled peaks.
    pub peaks: Vec<OrderPeak>,
    /// `|sum_n exp(i k gamma_n)| / N` at whole orders `k = 1, 2, ...` up to
    /// the spectrum's top (the fraction of the in-phase sum that survives).
    pub phasing: Vec<f64>,
    /// The whole orders the phasing cancels (`phasing` below [`CANCELLED`]).
    pub cancelled: Vec<u32>,
}

/// A mesh force's spectrum by order.
#[derive(Debug, Clone, PartialEq)]
pub struct ForceOrders {
    /// The mesh (model index).
    pub mesh: usize,
    /// Mesh periods recorded (bin `k` is order `k / record_periods`).
    pub record_periods: u32,
    /// The orders of the lines, from 0 (the mean).
    pub order: Vec<f64>,
    /// The mesh force's amplitude at each order (N; the mean at order 0).
    pub amplitude_n: Vec<f64>,
    /// Its labelled peaks, by rising order.
    pub peaks: Vec<OrderPeak>,
    /// The sum over the planets of the mesh's kind (`None` for the gear
    /// pair, or when the steady state kept no history of a planet's mesh).
    pub planets: Option<PlanetSum>,
}

/// Samples per mesh period and whole periods of `ss`'s record.
pub fn record_layout(ss: &SteadyState) -> (u32, u32) {
    let spp = match ss.sample_times_s.as_slice() {
        [a, b, ..] if b > a => (ss.period_s / (b - a)).round() as u32,
        _ => 0,
    };
    let len = ss.sample_times_s.len() as u32;
    (spp, len.checked_div(spp).unwrap_or(0))
}

/// The spectrum of mesh `mesh`'s force in `ss` up to order `max_order`;
/// `None` when `ss` kept no history of the mesh.
pub fn force_orders(
    sys: &MeshSystem,
    ss: &SteadyState,
    mesh: usize,
    max_order: f64,
) -> Option<ForceOrders> {
    let (spp, periods) = record_layout(ss);
    let history = |j: usize| ss.histories.iter().find(|h| h.mesh == j);
    let own = history(mesh)?;
    let s = spectrum(&own.force_n, spp, periods, max_order);
    let own_peaks = peaks(&s.order, &s.amplitude, periods);
    let planets = sys.meshes.get(mesh).and_then(|m| {
        let kind = m.kind;
        let meshes: Vec<usize> = (0..sys.meshes.len())
            .filter(|&j| sys.meshes[j].kind == kind)
            .collect();
        if meshes.len() < 2 {
            return None;
        }
        let mut sum = vec![0.0; own.force_n.len()];
        for &j in &meshes {
            let h = history(j)?;
            sum.iter_mut().zip(&h.force_n).for_each(|(a, f)| *a += f);
        }
        let t = spectrum(&sum, spp, periods, max_order);
        let top = max_order.max(0.0).floor() as u32;
        let phasing = sys.phasing_factors(kind, top);
        let cancelled = phasing
            .iter()
            .zip(1..)
            .filter(|(f, _)| **f < CANCELLED)
            .map(|(_, k)| k)
            .collect();
        Some(PlanetSum {
            kind,
            meshes,
            peaks: peaks(&t.order, &t.amplitude, periods),
            amplitude_n: t.amplitude,
            phasing,
            cancelled,
        })
    });
    Some(ForceOrders {
        mesh,
        record_periods: periods,
        order: s.order,
        amplitude_n: s.amplitude,
        peaks: own_peaks,
        planets,
    })
}

/// The labelled peaks of the spectrum `amplitude` at `order` (bin `k` at
/// order `k / periods`): the local maxima reaching [`PEAK_FRACTION`] of the
/// largest line after the mean and [`NOISE_FRACTION`] of the mean, the
/// [`MAX_PEAKS`] largest, by rising order.
pub fn peaks(order: &[f64], amplitude: &[f64], periods: u32) -> Vec<OrderPeak> {
    let largest = amplitude.iter().skip(1).copied().fold(0.0, f64::max);
    if !(largest > 0.0 && largest.is_finite()) {
        return Vec::new();
    }
    let floor = (PEAK_FRACTION * largest).max(NOISE_FRACTION * amplitude[0].abs());
    let at = |i: usize| amplitude.get(i).copied().unwrap_or(0.0);
    let mut found: Vec<usize> = (1..amplitude.len().min(order.len()))
        .filter(|&i| {
            let a = amplitude[i];
            a >= floor && a >= at(i - 1) && a > at(i + 1)
        })
        .collect();
    found.sort_by(|&a, &b| amplitude[b].total_cmp(&amplitude[a]));
    found.truncate(MAX_PEAKS);
    found.sort_unstable();
    found
        .into_iter()
        .map(|i| {
            let (label, whole) = order_label(i as u64, u64::from(periods.max(1)));
            OrderPeak {
                order: order[i],
                amplitude_n: amplitude[i],
                label,
                whole,
            }
        })
        .collect()
}

/// Order `bin / periods` in words, and whether it is a whole order: "2×",
/// "1/2×" (denominator at most [`MAX_DENOMINATOR`] in lowest terms), else
/// its decimal to two places ("0.37×").
pub fn order_label(bin: u64, periods: u64) -> (String, bool) {
    let periods = periods.max(1);
    let g = gcd(bin, periods).max(1);
    let (p, q) = (bin / g, periods / g);
    if q == 1 {
        (format!("{p}×"), true)
    } else if q <= MAX_DENOMINATOR {
        (format!("{p}/{q}×"), false)
    } else {
        (format!("{:.2}×", bin as f64 / periods as f64), false)
    }
}

fn gcd(a: u64, b: u64) -> u64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}

#[cfg(test)]
mod tests;
