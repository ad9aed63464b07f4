//! Amplitude spectra of uniformly sampled signals (rustfft).

/// Amplitude spectrum of a signal sampled uniformly over whole periods.
#[derive(Debug, Clone, PartialEq)]
pub struct Spectrum {
    /// Frequency of each line in mesh orders (multiples of the mesh frequency).
    pub order: Vec<f64>,
    /// One-sided amplitude (a sinusoid of amplitude A gives A; the mean gives its value).
    pub amplitude: Vec<f64>,
}

/// One-sided amplitude spectrum (rustfft) of `samples`, taken at
/// `samples_per_period` per mesh period over `periods` periods, up to `max_order`.
pub fn spectrum(
    samples: &[f64],
    samples_per_period: u32,
    periods: u32,
    max_order: f64,
) -> Spectrum {
    use rustfft::{num_complex::Complex, FftPlanner};
    let n = samples.len();
    if n < 2 {
        return Spectrum {
            order: Vec::new(),
            amplitude: Vec::new(),
        };
    }
    let mut buf: Vec<Complex<f64>> = samples.iter().map(|&x| Complex::new(x, 0.0)).collect();
    FftPlanner::new().plan_fft_forward(n).process(&mut buf);
    let per = f64::from(periods.max(1));
    let nyquist = f64::from(samples_per_period) / 2.0;
    let mut order = Vec::new();
    let mut amplitude = Vec::new();
    for (k, c) in buf.iter().enumerate().take(n / 2 + 1) {
        let o = k as f64 / per;
        if o > max_order.min(nyquist) {
            break;
        }
        let scale = if k == 0 || 2 * k == n { 1.0 } else { 2.0 };
        order.push(o);
        amplitude.push(scale * c.norm() / n as f64);
    }
    Spectrum { order, amplitude }
}
