//! Harmonic bookkeeping: the real trigonometric basis, the alternating
//! frequency–time (AFT) evaluation of a channel's force on a time grid, the
//! closed-form one-harmonic describing function of the seed paper, and the
//! multiplication operator that turns a slope `s(theta)` into a Jacobian block.
//!
//! Coefficients of a real periodic function `f(theta)` are stored as
//! `[a_0, a_1, b_1, a_2, b_2, ...]` for `f = a_0 + sum_k a_k cos k theta + b_k sin k theta`
//! (index 0 the mean, `2k - 1` the cosine and `2k` the sine of harmonic `k`).
//! Slopes are stored as complex exponential coefficients `s_l`, `l = 0..=2H`
//! (`s = sum_l s_l e^{i l theta}`, `s_-l = conj(s_l)`).
//!
//! Both methods return, per channel, the force coefficients up to `H` and the
//! slope coefficients up to `2H`; [`mult_operator`] then gives the exact
//! derivative of the force coefficients with respect to the channel
//! displacement's coefficients, `J[p][q] = proj_p(s phi_q)`. For AFT this is
//! the derivative of the discrete (quadrature) residual, because the
//! quadrature of `s phi_p phi_q` on `N > 4H` points reads the DFT of the
//! samples of `s` at indices `p +- q`.

use super::model::Law;
use nalgebra::Complex;
use std::f64::consts::PI;

mod exact;

pub(crate) use exact::{channel_exact, te_real_coefficients, ExactScratch};
pub use exact::{contact_switches, SwitchTable};

/// Number of real coefficients for `h` harmonics.
pub(crate) fn n_coef(h: usize) -> usize {
    2 * h + 1
}

/// The AFT time grid and its trigonometric tables.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Harmonics.
    pub h: usize,
    /// Time samples per period.
    pub n: usize,
    /// Sample phases `2 pi i / n`.
    pub theta: Vec<f64>,
    /// `proj[c * n + i]`: weights that project samples onto coefficient `c`.
    proj: Vec<f64>,
    /// `cos(l theta_i)`, `sin(l theta_i)` for `l = 0..=2h`: `trig[l * n + i]`.
    cos_l: Vec<f64>,
    sin_l: Vec<f64>,
}

impl Grid {
    /// A grid of `n` samples for `h` harmonics (`n > 4h` is required).
    pub fn new(h: usize, n: usize) -> Self {
        let nc = n_coef(h);
        let theta: Vec<f64> = (0..n).map(|i| 2.0 * PI * i as f64 / n as f64).collect();
        let mut proj = vec![0.0; nc * n];
        for (i, &t) in theta.iter().enumerate() {
            proj[i] = 1.0 / n as f64;
            for k in 1..=h {
                let (s, c) = crate::trig::phase_sin_cos(k as f64 * t);
                proj[(2 * k - 1) * n + i] = 2.0 * c / n as f64;
                proj[2 * k * n + i] = 2.0 * s / n as f64;
            }
        }
        let mut cos_l = vec![0.0; (2 * h + 1) * n];
        let mut sin_l = vec![0.0; (2 * h + 1) * n];
        for l in 0..=2 * h {
            for (i, &t) in theta.iter().enumerate() {
                let (s, c) = crate::trig::phase_sin_cos(l as f64 * t);
                cos_l[l * n + i] = c;
                sin_l[l * n + i] = s;
            }
        }
        Grid {
            h,
            n,
            theta,
            proj,
            cos_l,
            sin_l,
        }
    }

    /// The default grid size for `h` harmonics: a power of two of at least
    /// `64 h` and 256 points. A backlash force has kinks, so its harmonics
    /// decay only as `1/k^2`, and on a grid the residual itself has a small
    /// kink wherever a contact switch crosses a grid point; Newton and the
    /// continuation can stall on those kinks in nearly vertical stretches of
    /// the branch (measured on the default set near Omega 0.21 with a
    /// 64-point grid at H = 3 and 128 at H = 5; fine from 512). A grid far
    /// beyond the Nyquist minimum keeps both the aliasing and those kinks small.
    pub fn default_size(h: usize) -> usize {
        (64 * h).max(256).next_power_of_two()
    }

    /// Samples of the function with coefficients `coef` into `out`,
    /// coefficient by coefficient (vectorized over the samples).
    pub fn synthesize(&self, coef: &[f64], out: &mut [f64]) {
        self.synthesize_here(coef, out);
    }

    /// [`Grid::synthesize`]'s body, for callers that inline it into the
    /// vector unit's dispatch (`crate::simd`).
    #[cfg_attr(target_arch = "x86_64", inline(always))]
    pub(crate) fn synthesize_here(&self, coef: &[f64], out: &mut [f64]) {
        let n = self.n;
        out.fill(coef[0]);
        for k in 1..=self.h {
            let (a, b) = (coef[2 * k - 1], coef[2 * k]);
            let c = &self.cos_l[k * n..(k + 1) * n];
            let s = &self.sin_l[k * n..(k + 1) * n];
            for ((o, &ck), &sk) in out.iter_mut().zip(c).zip(s) {
                *o = *o + ck * a + sk * b;
            }
        }
    }

    /// Coefficients (up to `h`) of the function sampled in `samples`.
    pub fn analyze(&self, samples: &[f64], out: &mut [f64]) {
        let n = self.n;
        for (c, o) in out.iter_mut().enumerate() {
            let row = &self.proj[c * n..(c + 1) * n];
            *o = row.iter().zip(samples).map(|(p, s)| p * s).sum();
        }
    }

    /// Complex exponential coefficients `s_l = (1/n) sum_i s_i e^{-i l theta_i}`, `l = 0..=2h`.
    pub fn exp_coefficients(&self, samples: &[f64], out: &mut [Complex<f64>]) {
        let n = self.n;
        for (l, o) in out.iter_mut().enumerate() {
            let c = &self.cos_l[l * n..(l + 1) * n];
            let s = &self.sin_l[l * n..(l + 1) * n];
            let mut re = 0.0;
            let mut im = 0.0;
            for i in 0..n {
                re += samples[i] * c[i];
                im -= samples[i] * s[i];
            }
            *o = Complex::new(re / n as f64, im / n as f64);
        }
    }
}

/// Precomputed per-channel excitation on the grid: stiffness `k(theta_i)`
/// and TE `e(theta_i)` (for mesh laws).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ChannelTables {
    k: Vec<f64>,
    e: Vec<f64>,
}

impl ChannelTables {
    /// Tables of `law` on `grid`.
    pub fn new(law: &Law, grid: &Grid) -> Self {
        match *law {
            Law::Mesh { .. } => ChannelTables {
                k: grid.theta.iter().map(|&t| law.stiffness(t)).collect(),
                e: grid.theta.iter().map(|&t| law.te(t)).collect(),
            },
            Law::Cubic { .. } => ChannelTables {
                k: Vec::new(),
                e: Vec::new(),
            },
        }
    }
}

/// Scratch buffers for one channel evaluation.
#[derive(Debug, Clone, Default)]
pub(crate) struct Scratch {
    u: Vec<f64>,
    f: Vec<f64>,
    s: Vec<f64>,
}

/// AFT: force coefficients `force[0..2h+1]` and slope coefficients
/// `slope[0..=2h]` of a channel whose displacement has coefficients `u_coef`.
pub(crate) fn channel_aft(
    grid: &Grid,
    law: &Law,
    tables: &ChannelTables,
    u_coef: &[f64],
    scratch: &mut Scratch,
    force: &mut [f64],
    slope: &mut [Complex<f64>],
) {
    let n = grid.n;
    scratch.u.resize(n, 0.0);
    scratch.f.resize(n, 0.0);
    scratch.s.resize(n, 0.0);
    grid.synthesize(u_coef, &mut scratch.u);
    match *law {
        Law::Mesh { backlash_um: b, .. } => {
            for i in 0..n {
                let x = scratch.u[i] - tables.e[i];
                let kt = tables.k[i];
                let (f, s) = if x > b {
                    (kt * (x - b), kt)
                } else if x < -b {
                    (kt * (x + b), kt)
                } else {
                    (0.0, 0.0)
                };
                scratch.f[i] = f;
                scratch.s[i] = s;
            }
        }
        Law::Cubic { alpha } => {
            for i in 0..n {
                let u = scratch.u[i];
                scratch.f[i] = alpha * u * u * u;
                scratch.s[i] = 3.0 * alpha * u * u;
            }
        }
    }
    grid.analyze(&scratch.f, force);
    grid.exp_coefficients(&scratch.s, slope);
}

/// `J[p][q] = proj_p(s phi_q)` for slope coefficients `s_l` (`l = 0..=2h`),
/// row-major `nc x nc` into `out`.
pub(crate) fn mult_operator(s: &[Complex<f64>], h: usize, out: &mut [f64]) {
    let nc = n_coef(h);
    let at = |l: isize| -> Complex<f64> {
        if l >= 0 {
            s[l as usize]
        } else {
            s[(-l) as usize].conj()
        }
    };
    for p in 0..=h {
        for q in 0..=h {
            let (pi, qi) = (p as isize, q as isize);
            let minus = at(pi - qi);
            let plus = at(pi + qi);
            // Input column(s) for harmonic q: mean (q = 0) or cos, sin.
            let rows: &[(usize, bool)] = if p == 0 {
                &[(0, true)]
            } else {
                &[(2 * p - 1, true), (2 * p, false)]
            };
            for &(row, is_cos_row) in rows {
                if q == 0 {
                    // Input 1: coefficient of e^{ip} is s_p.
                    let v = if p == 0 {
                        s[0].re
                    } else if is_cos_row {
                        2.0 * s[p].re
                    } else {
                        -2.0 * s[p].im
                    };
                    out[row * nc] = v;
                } else {
                    let (cos_col, sin_col) = (2 * q - 1, 2 * q);
                    let (vc, vs) = if p == 0 {
                        // Mean of s cos q = Re s_q, mean of s sin q = -Im s_q.
                        (s[q].re, -s[q].im)
                    } else if is_cos_row {
                        ((minus + plus).re, (minus - plus).im)
                    } else {
                        (-(minus + plus).im, (minus - plus).re)
                    };
                    out[row * nc + cos_col] = vc;
                    out[row * nc + sin_col] = vs;
                }
            }
        }
    }
}

/// Fourier cosine coefficients (orders 0..=2) per unit amplitude of
/// `max(A (cos psi - mu), 0)`, and (orders 0..=3) of its slope indicator
/// `1[cos psi > mu]`.
fn upper_part(mu: f64) -> ([f64; 3], [f64; 4]) {
    if mu >= 1.0 {
        return ([0.0; 3], [0.0; 4]);
    }
    if mu <= -1.0 {
        return ([-mu, 1.0, 0.0], [1.0, 0.0, 0.0, 0.0]);
    }
    let a = mu.acos();
    let sa = a.sin();
    let g = [
        (sa - mu * a) / PI,
        (a - mu * sa) / PI,
        2.0 * sa * sa * sa / (3.0 * PI),
    ];
    let d = [
        a / PI,
        2.0 * sa / PI,
        (2.0 * a).sin() / PI,
        2.0 * (3.0 * a).sin() / (3.0 * PI),
    ];
    (g, d)
}

/// The seed's one-harmonic describing function (its Eqs. 9–13) for a mesh
/// channel, with the closed forms of the biased-sinusoid dead zone:
/// force coefficients `[mean, cos, sin]` and slope coefficients `s_0..=s_2`.
///
/// For `x = X0 + A cos psi` and `mu_+- = (+-b - X0) / A`, the dead zone
/// `g(x)` has the cosine coefficients `A (M(mu+) - M(-mu-))`,
/// `A (C1(mu+) + C1(-mu-))` and `A (C2(mu+) - C2(-mu-))` with
/// `M(mu) = (sin a - mu a) / pi`, `C1 = (a - mu sin a) / pi`,
/// `C2 = 2 sin^3 a / (3 pi)`, `a = arccos mu` (the seed's `G` and `H`
/// functions: `M = (G(mu) - mu) / 2`, `C1 = (1 - H(mu)) / 2`). The product with
/// `k(theta) = k (1 + v cos(theta + gamma))` keeps the term `v C2 / 2` that
/// carries the dead zone's second harmonic into the first; the seed drops
/// it, which makes its method differ from a one-harmonic balance whenever
/// `v != 0`. Kept here, the method *is* the one-harmonic Galerkin balance
/// and equals AFT at `H = 1` up to AFT's quadrature error.
pub(crate) fn channel_df(law: &Law, u_coef: &[f64], force: &mut [f64], slope: &mut [Complex<f64>]) {
    let Law::Mesh {
        k,
        variation: v,
        phase_rad: gamma,
        backlash_um: b,
        te_mean_um,
        te_cos_um,
        te_sin_um,
        ..
    } = *law
    else {
        // The describing function is defined for mesh laws only.
        force.iter_mut().for_each(|f| *f = 0.0);
        slope.iter_mut().for_each(|s| *s = Complex::new(0.0, 0.0));
        return;
    };
    let (sg, cg) = gamma.sin_cos();
    // Relative displacement x = u - e in the theta frame.
    let x0 = u_coef[0] - te_mean_um;
    let xc = u_coef[1] - (te_cos_um * cg + te_sin_um * sg);
    let xs = u_coef[2] - (te_sin_um * cg - te_cos_um * sg);
    let amp = xc.hypot(xs);
    // Cosine coefficients of g and of g' in the psi = theta - phi frame.
    let (g, d, phi) = if amp <= 1e-12 * (x0.abs() + b + 1.0) {
        let g0 = crate::system::dead_zone(x0, b);
        let d0 = if x0.abs() > b { 1.0 } else { 0.0 };
        ([g0, 0.0, 0.0], [d0, 0.0, 0.0, 0.0], 0.0)
    } else {
        let mu_p = (b - x0) / amp;
        let mu_m = (-b - x0) / amp;
        let (gu, du) = upper_part(mu_p);
        let (gl, dl) = upper_part(-mu_m);
        // Lower part: h(psi) = -f'(psi + pi): orders alternate in sign.
        let g = [
            amp * (gu[0] - gl[0]),
            amp * (gu[1] + gl[1]),
            amp * (gu[2] - gl[2]),
        ];
        let d = [du[0] + dl[0], du[1] - dl[1], du[2] + dl[2], du[3] - dl[3]];
        (g, d, xs.atan2(xc))
    };
    // Complex coefficients (psi frame): cosine series c_l cos l psi -> c_l / 2 at +-l.
    let cplx = |c: &[f64], l: isize| -> Complex<f64> {
        let a = l.unsigned_abs();
        if a >= c.len() {
            Complex::new(0.0, 0.0)
        } else if a == 0 {
            Complex::new(c[0], 0.0)
        } else {
            Complex::new(c[a] / 2.0, 0.0)
        }
    };
    // k(psi) = k (1 + v cos(psi + beta)), beta = phi + gamma.
    let beta = phi + gamma;
    let k1 = Complex::from_polar(k * v / 2.0, beta);
    let kc = |m: isize| -> Complex<f64> {
        match m {
            0 => Complex::new(k, 0.0),
            1 => k1,
            -1 => k1.conj(),
            _ => Complex::new(0.0, 0.0),
        }
    };
    let product =
        |c: &[f64], l: isize| -> Complex<f64> { (-1..=1).map(|m| kc(m) * cplx(c, l - m)).sum() };
    // Back to the theta frame: coefficient l picks up e^{-i l phi}.
    let rot = |l: isize| Complex::from_polar(1.0, -(l as f64) * phi);
    let f0 = product(&g, 0) * rot(0);
    let f1 = product(&g, 1) * rot(1);
    force[0] = f0.re;
    force[1] = 2.0 * f1.re;
    force[2] = -2.0 * f1.im;
    for (l, s) in slope.iter_mut().enumerate().take(3) {
        *s = product(&d, l as isize) * rot(l as isize);
    }
}

/// Evaluates a channel displacement's trigonometric polynomial at `theta`.
pub(crate) fn eval_coef(coef: &[f64], h: usize, theta: f64) -> f64 {
    // One sin_cos, then the angle-addition recurrence for the harmonics.
    let (s1, c1) = crate::trig::phase_sin_cos(theta);
    let (mut sn, mut cs) = (s1, c1);
    let mut s = coef[0];
    for k in 1..=h {
        s += coef[2 * k - 1] * cs + coef[2 * k] * sn;
        (sn, cs) = (sn * c1 + cs * s1, cs * c1 - sn * s1);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn direct_operator(grid: &Grid, s: &[f64]) -> Vec<f64> {
        let nc = n_coef(grid.h);
        let mut out = vec![0.0; nc * nc];
        let mut col = vec![0.0; nc];
        let mut samples = vec![0.0; grid.n];
        for q in 0..nc {
            col.iter_mut().for_each(|c| *c = 0.0);
            col[q] = 1.0;
            grid.synthesize(&col, &mut samples);
            for (x, si) in samples.iter_mut().zip(s) {
                *x *= si;
            }
            let mut proj = vec![0.0; nc];
            grid.analyze(&samples, &mut proj);
            for p in 0..nc {
                out[p * nc + q] = proj[p];
            }
        }
        out
    }

    /// The recurrence-based evaluator agrees with the series written out
    /// with `cos(k theta)` and `sin(k theta)` term by term.
    #[test]
    fn eval_coef_is_the_trigonometric_series() {
        let coef = [0.3, 1.0, -0.5, 0.25, 2.0, -0.125, 0.75];
        for i in 0..40 {
            let theta = -7.0 + 0.37 * f64::from(i);
            let mut want = coef[0];
            for k in 1..=3 {
                let kt = k as f64 * theta;
                want += coef[2 * k - 1] * kt.cos() + coef[2 * k] * kt.sin();
            }
            let got = eval_coef(&coef, 3, theta);
            assert!((got - want).abs() < 1e-12, "theta {theta}: {got} vs {want}");
        }
    }

    #[test]
    fn multiplication_operator_equals_the_quadrature() {
        let h = 4;
        let grid = Grid::new(h, Grid::default_size(h));
        // A rough slope: a step function plus harmonics.
        let s: Vec<f64> = grid
            .theta
            .iter()
            .map(|&t| {
                if (t - 1.0).sin() > 0.3 {
                    2.0 + t.cos()
                } else {
                    0.5 * (3.0 * t).sin()
                }
            })
            .collect();
        let mut sc = vec![Complex::new(0.0, 0.0); 2 * h + 1];
        grid.exp_coefficients(&s, &mut sc);
        let nc = n_coef(h);
        let mut op = vec![0.0; nc * nc];
        mult_operator(&sc, h, &mut op);
        let direct = direct_operator(&grid, &s);
        for (a, b) in op.iter().zip(&direct) {
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
    }

    #[test]
    fn describing_function_equals_fine_quadrature() {
        let law = test_law();
        let fine = Grid::new(1, 1 << 16);
        let tables = ChannelTables::new(&law, &fine);
        for u in &ONE_HARMONIC_CASES[..5] {
            let u = *u;
            let (mut fa, mut fd) = ([0.0; 3], [0.0; 3]);
            let (mut sa, mut sd) = ([Complex::new(0.0, 0.0); 3], [Complex::new(0.0, 0.0); 3]);
            aft_fresh(&fine, &law, &tables, &u, &mut fa, &mut sa);
            channel_df(&law, &u, &mut fd, &mut sd);
            assert_channels_close(&u, (&fa, &sa), (&fd, &sd), 1e-6, 1e-4);
        }
    }

    /// One-harmonic coefficients (mean, cosine, sine in µm) against a 100 µm
    /// backlash: both flanks, one flank, a pure oscillation, a pure offset,
    /// a grazing case and a negative mean.
    const ONE_HARMONIC_CASES: [[f64; 3]; 6] = [
        [110.0, 30.0, -20.0],
        [60.0, 80.0, 50.0],
        [0.0, 150.0, 0.0],
        [300.0, 0.0, 0.0],
        [105.0, 1e-3, 0.0],
        [-250.0, 10.0, 5.0],
    ];

    /// [`channel_aft`] with a fresh scratch.
    fn aft_fresh(
        grid: &Grid,
        law: &Law,
        tables: &ChannelTables,
        u: &[f64],
        force: &mut [f64],
        slope: &mut [Complex<f64>],
    ) {
        channel_aft(grid, law, tables, u, &mut Scratch::default(), force, slope);
    }

    /// Asserts that two evaluations of a channel's three forces and slopes
    /// agree: forces to `force_rel` of (1 + the first's size), slopes to
    /// `slope_abs`.
    fn assert_channels_close(
        u: &[f64; 3],
        (fa, sa): (&[f64; 3], &[Complex<f64>; 3]),
        (fb, sb): (&[f64; 3], &[Complex<f64>; 3]),
        force_rel: f64,
        slope_abs: f64,
    ) {
        for c in 0..3 {
            assert!(
                (fa[c] - fb[c]).abs() < force_rel * (1.0 + fa[c].abs().max(fb[c].abs())),
                "{u:?} force {c}: {} vs {}",
                fa[c],
                fb[c]
            );
            assert!(
                (sa[c] - sb[c]).norm() < slope_abs,
                "{u:?} slope {c}: {} vs {}",
                sa[c],
                sb[c]
            );
        }
    }

    fn test_law() -> Law {
        Law::Mesh {
            k: 1.3,
            variation: 0.3,
            phase_rad: 0.4,
            backlash_um: 100.0,
            te_mean_um: 2.0,
            te_cos_um: 5.0,
            te_sin_um: 20.0,
            higher: Vec::new(),
        }
    }

    #[test]
    fn exact_integration_equals_the_describing_function_at_one_harmonic() {
        // Two independent closed forms of the same one-harmonic integrals.
        let law = test_law();
        for u in ONE_HARMONIC_CASES {
            let (mut fe, mut fd) = ([0.0; 3], [0.0; 3]);
            let (mut se, mut sd) = ([Complex::new(0.0, 0.0); 3], [Complex::new(0.0, 0.0); 3]);
            assert!(channel_exact(
                1,
                &SwitchTable::new(1),
                &law,
                &u,
                &mut ExactScratch::default(),
                &mut fe,
                &mut se
            ));
            channel_df(&law, &u, &mut fd, &mut sd);
            assert_channels_close(&u, (&fe, &se), (&fd, &sd), 1e-10, 1e-10);
        }
    }

    #[test]
    fn exact_integration_equals_fine_quadrature_at_four_harmonics() {
        exact_equals_quadrature(test_law());
    }

    /// The same with an excitation of three harmonics (a stiffness with a
    /// second and third harmonic, a TE with a second): the closed-form
    /// integration against a plain quadrature of the force law on a fine grid.
    #[test]
    fn exact_integration_equals_fine_quadrature_with_a_three_harmonic_excitation() {
        let Law::Mesh {
            k,
            variation,
            phase_rad,
            backlash_um,
            te_mean_um,
            te_cos_um,
            te_sin_um,
            ..
        } = test_law()
        else {
            unreachable!()
        };
        exact_equals_quadrature(Law::Mesh {
            k,
            variation,
            phase_rad,
            backlash_um,
            te_mean_um,
            te_cos_um,
            te_sin_um,
            higher: vec![[-0.12, 8.0, -3.0], [0.07, 0.0, 0.0]],
        });
    }

    fn exact_equals_quadrature(law: Law) {
        let h = 4;
        let fine = Grid::new(h, 1 << 16);
        let tables = ChannelTables::new(&law, &fine);
        let nc = n_coef(h);
        for seed in 0..6 {
            let u: Vec<f64> = (0..nc)
                .map(|c| {
                    let base = if c == 0 { 90.0 } else { 60.0 / (c as f64) };
                    base * (1.7 * (seed * nc + c) as f64).sin()
                })
                .collect();
            let (mut fa, mut fe) = (vec![0.0; nc], vec![0.0; nc]);
            let (mut sa, mut se) = (
                vec![Complex::new(0.0, 0.0); 2 * h + 1],
                vec![Complex::new(0.0, 0.0); 2 * h + 1],
            );
            aft_fresh(&fine, &law, &tables, &u, &mut fa, &mut sa);
            assert!(channel_exact(
                h,
                &SwitchTable::new(h),
                &law,
                &u,
                &mut ExactScratch::default(),
                &mut fe,
                &mut se
            ));
            for c in 0..nc {
                // The fine grid's quadrature error of a kinked force, O(1/n^2).
                assert!(
                    (fa[c] - fe[c]).abs() < 1e-6 * (1.0 + fe[c].abs()),
                    "{seed} force {c}: {} vs {}",
                    fa[c],
                    fe[c]
                );
            }
            for l in 0..=2 * h {
                assert!(
                    (sa[l] - se[l]).norm() < 1e-4,
                    "{seed} slope {l}: {} vs {}",
                    sa[l],
                    se[l]
                );
            }
        }
    }
}
