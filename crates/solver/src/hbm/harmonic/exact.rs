//! Exact (piecewise) evaluation of a backlash mesh channel: the contact
//! switches located as roots of trigonometric polynomials, and the force and
//! slope coefficients integrated in closed form between them.

use super::*;

/// Exact (piecewise) evaluation of a backlash mesh channel: the force's
/// Fourier coefficients up to `h` and the slope's exponential coefficients up
/// to `2h`, integrated in closed form between the contact switches instead
/// of by quadrature.
///
/// On each interval between consecutive roots of `x(theta) = +-b` (with
/// `x = u - e` a trigonometric polynomial) the contact state is fixed and
/// the force `k(theta) (x -+ b)` is itself a trigonometric polynomial of
/// degree `h + 1`, so `int w(theta) e^{-i p theta}` over the interval is a
/// finite sum of `(e^{i m beta} - e^{i m alpha}) / (i m)`. The roots are
/// found by [`contact_switches`]. Because the dead zone is continuous, the result is a smooth
/// (C1) function of the coefficients: no grid kinks, and the Jacobian from
/// [`mult_operator`] is its exact derivative. At `h = 1` it equals the
/// describing function's closed forms. Non-mesh laws fall back to AFT.
pub(crate) fn channel_exact(
    h: usize,
    table: &SwitchTable,
    law: &Law,
    u_coef: &[f64],
    scratch: &mut ExactScratch,
    force: &mut [f64],
    slope: &mut [Complex<f64>],
) -> bool {
    let Law::Mesh {
        k,
        variation,
        phase_rad,
        backlash_um: b,
        ..
    } = *law
    else {
        return false;
    };
    let nc = n_coef(h);
    // x = u - e as real coefficients.
    scratch.x.clear();
    scratch.x.extend_from_slice(&u_coef[..nc]);
    for (xi, t) in scratch.x.iter_mut().zip(te_first_coefficients(law)) {
        *xi -= t;
    }
    for (i, [c, s]) in law.te_higher_theta().enumerate() {
        if let Some(x) = scratch.x.get_mut(2 * i + 3..2 * i + 5) {
            x[0] -= c;
            x[1] -= s;
        }
    }
    // Complex exponential coefficients of x (index j + h for j = -h..=h) and of k.
    let cx = |coef: &[f64], j: isize| -> Complex<f64> {
        let ja = j.unsigned_abs();
        if ja == 0 {
            Complex::new(coef[0], 0.0)
        } else if j > 0 {
            Complex::new(0.5 * coef[2 * ja - 1], -0.5 * coef[2 * ja])
        } else {
            Complex::new(0.5 * coef[2 * ja - 1], 0.5 * coef[2 * ja])
        }
    };
    // The stiffness's exponential coefficients kap_d, d = -kk..=kk: on
    // the stack for the seed's one harmonic.
    let kk = 1 + law.higher().len() as isize;
    let hk = h as isize + kk;
    let one = [
        Complex::from_polar(0.5 * k * variation, -phase_rad),
        Complex::new(k, 0.0),
        Complex::from_polar(0.5 * k * variation, phase_rad),
    ];
    let kap: &[Complex<f64>] = if kk == 1 {
        &one
    } else {
        scratch.kap.clear();
        for &[a, _, _] in law.higher().iter().rev() {
            let n = (scratch.kap.len() as isize - kk).unsigned_abs() as f64;
            scratch
                .kap
                .push(Complex::from_polar(0.5 * k * a, -n * phase_rad));
        }
        scratch.kap.extend(one);
        for (i, &[a, _, _]) in law.higher().iter().enumerate() {
            let n = (i + 2) as f64;
            scratch
                .kap
                .push(Complex::from_polar(0.5 * k * a, n * phase_rad));
        }
        &scratch.kap
    };
    // w_pm = k(theta) (x -+ b): exponential coefficients, j = -(h+1)..=h+1.
    let nw = (2 * hk + 1) as usize;
    scratch.w_hi.clear();
    scratch.w_hi.resize(nw, Complex::new(0.0, 0.0));
    for j in -(h as isize)..=(h as isize) {
        let c = cx(&scratch.x, j);
        if kk == 1 {
            for (d, kd) in (-1isize..=1).zip(one) {
                scratch.w_hi[(j + d + hk) as usize] += c * kd;
            }
        } else {
            for (d, kd) in (-kk..=kk).zip(kap) {
                scratch.w_hi[(j + d + hk) as usize] += c * kd;
            }
        }
    }
    scratch.w_lo.clear();
    scratch.w_lo.extend_from_slice(&scratch.w_hi);
    for (d, kd) in (-kk..=kk).zip(kap) {
        scratch.w_hi[(d + hk) as usize] -= kd * b;
        scratch.w_lo[(d + hk) as usize] += kd * b;
    }
    // Contact switches: the roots of x -+ b.
    let eval = |t: f64| eval_coef(&scratch.x, h, t);
    scratch.cuts.clear();
    scratch.cuts.push(0.0);
    contact_switches(
        table,
        &scratch.x,
        b,
        &mut scratch.dx,
        &mut scratch.pieces,
        &mut scratch.cuts,
    );
    scratch.cuts.push(2.0 * PI);
    scratch.cuts.sort_by(f64::total_cmp);
    // Integrate interval by interval.
    let mmax = 2 * h as isize + 1 + kk;
    let nf = (2 * mmax + 1) as usize;
    scratch.e_int.clear();
    scratch.e_int.resize(nf, Complex::new(0.0, 0.0));
    let mut fz = vec![Complex::new(0.0, 0.0); h + 1];
    for sl in slope.iter_mut() {
        *sl = Complex::new(0.0, 0.0);
    }
    for w in scratch.cuts.windows(2) {
        let (a, bb) = (w[0], w[1]);
        if bb - a <= 0.0 {
            continue;
        }
        let xm = eval(0.5 * (a + bb));
        let coeffs = if xm > b {
            &scratch.w_hi
        } else if xm < -b {
            &scratch.w_lo
        } else {
            continue;
        };
        // E_m = int_a^b e^{i m theta} dtheta for m = -mmax..=mmax.
        let (ea, eb) = (Complex::from_polar(1.0, a), Complex::from_polar(1.0, bb));
        let (mut pa, mut pb) = (Complex::new(1.0, 0.0), Complex::new(1.0, 0.0));
        scratch.e_int[mmax as usize] = Complex::new(bb - a, 0.0);
        for m in 1..=mmax {
            pa *= ea;
            pb *= eb;
            let diff = pb - pa;
            let mf = m as f64;
            // (e^{imb} - e^{ima}) / (i m) and its conjugate for -m.
            let e = Complex::new(diff.im / mf, -diff.re / mf);
            scratch.e_int[(mmax + m) as usize] = e;
            scratch.e_int[(mmax - m) as usize] = e.conj();
        }
        // Force: F_p = (1/2pi) sum_j w_j E_{j - p}, p = 0..=h.
        for (p, f) in fz.iter_mut().enumerate() {
            let mut acc = Complex::new(0.0, 0.0);
            for (jj, wj) in coeffs.iter().enumerate() {
                let m = jj as isize - hk - p as isize;
                acc += wj * scratch.e_int[(m + mmax) as usize];
            }
            *f += acc;
        }
        // Slope: s_l = (1/2pi) sum_d kappa_d E_{d - l}, l = 0..=2h.
        for (l, sl) in slope.iter_mut().enumerate() {
            let mut acc = Complex::new(0.0, 0.0);
            if kk == 1 {
                // The seed's one harmonic: a fixed range the loop unrolls.
                for (d, kd) in (-1isize..=1).zip(one) {
                    let m = d - l as isize;
                    acc += kd * scratch.e_int[(m + mmax) as usize];
                }
            } else {
                for (d, kd) in (-kk..=kk).zip(kap) {
                    let m = d - l as isize;
                    acc += kd * scratch.e_int[(m + mmax) as usize];
                }
            }
            *sl += acc;
        }
    }
    let inv = 1.0 / (2.0 * PI);
    force[0] = fz[0].re * inv;
    for p in 1..=h {
        force[2 * p - 1] = 2.0 * fz[p].re * inv;
        force[2 * p] = -2.0 * fz[p].im * inv;
    }
    for sl in slope.iter_mut() {
        *sl *= inv;
    }
    true
}

/// The trigonometric basis on `max(64, 16 (2h + 1))` equally spaced phases,
/// on which [`contact_switches`] brackets its roots.
#[derive(Debug, Clone, PartialEq)]
pub struct SwitchTable {
    h: usize,
    samples: usize,
    /// `basis[c * samples + i]`: basis function `c` at phase `i`, so that a
    /// function's samples accumulate coefficient by coefficient.
    basis: Vec<f64>,
}

impl SwitchTable {
    /// The table for `h` harmonics.
    pub fn new(h: usize) -> Self {
        let nc = n_coef(h);
        let samples = 64.max(16 * nc);
        let basis = (0..nc)
            .flat_map(|c| {
                (0..samples).map(move |i| {
                    let t = 2.0 * PI * i as f64 / samples as f64;
                    match c {
                        0 => 1.0,
                        c if c % 2 == 1 => (c.div_ceil(2) as f64 * t).cos(),
                        c => ((c / 2) as f64 * t).sin(),
                    }
                })
            })
            .collect();
        SwitchTable { h, samples, basis }
    }

    /// The samples of the functions with coefficients `a` and `b` into
    /// `out_a` and `out_b`, in one pass over the table.
    fn sample_pair(&self, a: &[f64], b: &[f64], out_a: &mut [f64], out_b: &mut [f64]) {
        // With the widest vector instructions (the same bits, `crate::simd`).
        crate::simd::dispatch(
            #[inline(always)]
            || self.sample_pair_here(a, b, out_a, out_b),
        )
    }

    /// [`SwitchTable::sample_pair`]'s body, inlined into the dispatch.
    #[cfg_attr(target_arch = "x86_64", inline(always))]
    fn sample_pair_here(&self, a: &[f64], b: &[f64], out_a: &mut [f64], out_b: &mut [f64]) {
        let n = self.samples;
        out_a.fill(0.0);
        out_b.fill(0.0);
        for ((row, &ca), &cb) in self.basis.chunks_exact(n).zip(a).zip(b) {
            for ((oa, ob), &v) in out_a.iter_mut().zip(out_b.iter_mut()).zip(row) {
                *oa += v * ca;
                *ob += v * cb;
            }
        }
    }
}

/// Appends to `out` every phase in `(0, 2 pi)` where the trigonometric
/// polynomial `x` (coefficients up to `table`'s `h`) crosses `b` or `-b`.
///
/// The period is first cut into monotone pieces (at the table's samples and
/// at the zeros of `x'` between them), so a brief excursion across `+-b`
/// between two samples is not missed: each monotone piece holds at most one
/// root per side. Roots are refined by the Illinois method to round-off.
/// `dx` (the derivative's coefficients, then the samples of `x` and `x'`)
/// and `pieces` are scratch buffers.
pub fn contact_switches(
    table: &SwitchTable,
    x: &[f64],
    b: f64,
    dx: &mut Vec<f64>,
    pieces: &mut Vec<(f64, f64)>,
    out: &mut Vec<f64>,
) {
    let h = table.h;
    let nc = n_coef(h);
    let samples = table.samples;
    // `|x(theta) - x_0|` is at most the sum of the harmonics' amplitudes:
    // if that band around the mean stays clear of `b` and `-b`, `x` crosses
    // neither (the band lies wholly in contact, or wholly in the gap), and
    // the sampling below would find no sign change.
    let amplitude: f64 = (1..=h).map(|k| x[2 * k - 1].hypot(x[2 * k])).sum();
    let clear = |side: f64| (x[0] - side).abs() > amplitude;
    if clear(b) && clear(-b) {
        return;
    }
    dx.clear();
    dx.push(0.0);
    for k in 1..=h {
        let kf = k as f64;
        dx.push(kf * x[2 * k]);
        dx.push(-kf * x[2 * k - 1]);
    }
    dx.resize(nc + 2 * samples, 0.0);
    let (dcoef, rest) = dx.split_at_mut(nc);
    let (xs, ds) = rest.split_at_mut(samples);
    table.sample_pair(x, dcoef, xs, ds);
    let dcoef = &*dcoef;
    let eval = |t: f64| eval_coef(x, h, t);
    let slope_at = |t: f64| eval_coef(dcoef, h, t);
    // Between two samples where x' changes sign, x moves by at most
    // `max|x''| dt^2 / 2` from either sample. An extremum that cannot reach
    // `+-b` by twice that margin brackets no root and need not be located:
    // the pieces it would split see no sign change either way.
    let dt = 2.0 * PI / samples as f64;
    let curvature: f64 = (1..=h)
        .map(|k| (k * k) as f64 * (x[2 * k - 1].abs() + x[2 * k].abs()))
        .sum();
    let reach = curvature * dt * dt + 1e-12 * (1.0 + b.abs() + x[0].abs());
    let far = |xa: f64| (xa - b).abs() > reach && (xa + b).abs() > reach;
    pieces.clear();
    let mut x0 = xs[0];
    pieces.push((0.0, x0));
    let mut t0 = 0.0;
    let mut d0 = ds[0];
    for i in 1..=samples {
        let t1 = 2.0 * PI * i as f64 / samples as f64;
        let d1 = ds[i % samples];
        let x1 = xs[i % samples];
        if (d0 > 0.0) != (d1 > 0.0) && !(far(x0) && far(x1)) {
            let te = illinois(&slope_at, t0, t1, d0, d1);
            pieces.push((te, eval(te)));
        }
        pieces.push((t1, x1));
        t0 = t1;
        d0 = d1;
        x0 = x1;
    }
    for w in pieces.windows(2) {
        let ((ta, xa), (tb, xb)) = (w[0], w[1]);
        for side in [b, -b] {
            if (xa - side > 0.0) != (xb - side > 0.0) {
                let t = illinois(&|t| eval(t) - side, ta, tb, xa - side, xb - side);
                if t > 0.0 && t < 2.0 * PI {
                    out.push(t);
                }
            }
            if b == 0.0 {
                break;
            }
        }
    }
}

/// The TE of a mesh law as real coefficients `mean, cos 1, sin 1, cos 2,
/// ...` in theta, up to its highest harmonic (zip it with a coefficient
/// vector: a balance never keeps fewer harmonics than the excitation has,
/// `HbmModel::check_harmonics`).
pub(crate) fn te_real_coefficients(law: &Law) -> impl Iterator<Item = f64> + '_ {
    te_first_coefficients(law)
        .into_iter()
        .chain(law.te_higher_theta().flatten())
}

/// The TE's `[mean, cos 1, sin 1]` in theta.
fn te_first_coefficients(law: &Law) -> [f64; 3] {
    law.te_terms()
        .map_or([0.0; 3], |(phase, [mean, cos, sin])| {
            // c cos(t + p) + s sin(t + p) = (c cos p + s sin p) cos t + (s cos p - c sin p) sin t
            let (sp, cp) = phase.sin_cos();
            [mean, cos * cp + sin * sp, sin * cp - cos * sp]
        })
}

/// A root of `g` in `[a, b]` where `g(a) = ga` and `g(b) = gb` differ in
/// sign: regula falsi with the Illinois modification, to round-off.
fn illinois(g: &dyn Fn(f64) -> f64, mut a: f64, mut b: f64, mut ga: f64, mut gb: f64) -> f64 {
    let mut side = 0;
    for _ in 0..60 {
        let c = (a * gb - b * ga) / (gb - ga);
        if !(c > a && c < b) || b - a < 1e-14 {
            return 0.5 * (a + b);
        }
        let gc = g(c);
        if gc == 0.0 {
            return c;
        }
        if (gc > 0.0) == (gb > 0.0) {
            b = c;
            gb = gc;
            if side == -1 {
                ga *= 0.5;
            }
            side = -1;
        } else {
            a = c;
            ga = gc;
            if side == 1 {
                gb *= 0.5;
            }
            side = 1;
        }
        if gc.abs() < 1e-13 * (1.0 + ga.abs().max(gb.abs())) {
            return c;
        }
    }
    0.5 * (a + b)
}

/// Scratch buffers of [`channel_exact`].
#[derive(Debug, Clone, Default)]
pub(crate) struct ExactScratch {
    x: Vec<f64>,
    dx: Vec<f64>,
    pieces: Vec<(f64, f64)>,
    w_hi: Vec<Complex<f64>>,
    w_lo: Vec<Complex<f64>>,
    cuts: Vec<f64>,
    e_int: Vec<Complex<f64>>,
    kap: Vec<Complex<f64>>,
}
