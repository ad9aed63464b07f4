//! Stability of a harmonic-balance orbit: Floquet multipliers from the
//! monodromy matrix of the variational equations over one period.
//!
//! Along the orbit the linearized equations are `z' = A(theta) z` with
//! `A = [[0, I], [-(K + sum_j n_j s_j(theta) d_j d_j^T), -C]]` and the slope
//! `s_j = k_j(theta) g_j'(x_j(theta))`, which jumps where the mesh's
//! relative displacement crosses `+-b`. The period is split at those
//! crossings (located on the orbit's trigonometric polynomial by bisection),
//! so that each piece has a fixed contact state and a smooth coefficient,
//! and each piece is integrated by the classical Runge–Kutta method with at
//! least [`ORBIT_STEPS_PER_FASTEST`] steps per period of the fastest mode
//! (the engaged system's scan: [`ENGAGED_STEPS_PER_FASTEST`]). The multipliers are the
//! eigenvalues of the monodromy matrix (a real Schur decomposition).
//!
//! Under the symmetric reduction the planet block (central members at rest,
//! N - 1 identical copies) is integrated alongside; its multipliers count
//! N - 1 times.

use super::assembly::Assembly;
use super::harmonic::{contact_switches, n_coef, te_real_coefficients};
// The Fourier evaluator lives in `harmonic` (stability depends on harmonic,
// never the reverse); re-exported here because `hbm::mod` imports it from
// `stability` (that file belongs to the continuation's owner).
pub(crate) use super::harmonic::eval_coef;
use super::model::Law;
use nalgebra::Complex;
use nalgebra::DMatrix;
use std::f64::consts::PI;

/// RK4 steps per period of the fastest mode (or of the mesh, if it is
/// faster) for an orbit's multipliers. RK4's global error falls as the
/// fourth power of the step: at 8 the largest multiplier of Fig. 2's linear
/// set at Omega 1.875 was 3.7e-4 off the shooting monodromy's (at rtol
/// 1e-13), at 16 it is 2.2e-5, within the 1e-4 at which the branch's
/// stability is compared with shooting (`crates/solver/tests/floquet.rs`).
pub(crate) const ORBIT_STEPS_PER_FASTEST: f64 = 16.0;

/// The same for the engaged system's spectral radius (`gearshock
/// instability`, the page's grey bands), held to 1e-6 of the shooting
/// monodromy's: at 32 steps it was 1.8e-6 off at Omega 1.875, at 128 it is
/// 7e-9 (a 400-point scan still takes well under a second).
pub(crate) const ENGAGED_STEPS_PER_FASTEST: f64 = 128.0;

/// Floquet multipliers of an orbit.
#[derive(Debug, Clone, PartialEq)]
pub struct Floquet {
    /// Multipliers of the (symmetric or full) block.
    pub multipliers: Vec<Complex<f64>>,
    /// Multipliers of the planet block (each N - 1 times), if reduced.
    pub planet_multipliers: Vec<Complex<f64>>,
}

impl Floquet {
    /// All multipliers.
    pub fn all(&self) -> impl Iterator<Item = &Complex<f64>> {
        self.multipliers.iter().chain(&self.planet_multipliers)
    }

    /// The largest modulus.
    pub fn spectral_radius(&self) -> f64 {
        self.all().map(|z| z.norm()).fold(0.0, f64::max)
    }
}

/// Phases in `(0, 2 pi)` where some mesh channel switches contact state,
/// found as the exact method finds them ([`contact_switches`]).
fn switch_phases(asm: &Assembly, coefs: &[Vec<f64>]) -> Vec<f64> {
    let (mut dx, mut pieces, mut out) = (Vec::new(), Vec::new(), Vec::new());
    for (ch, coef) in asm.model.channels.iter().zip(coefs) {
        if !matches!(ch.law, Law::Mesh { .. }) {
            continue;
        }
        let mut rel = coef.clone();
        for (r, t) in rel.iter_mut().zip(te_real_coefficients(&ch.law)) {
            *r -= t;
        }
        let b = ch.law.backlash_um();
        contact_switches(&asm.switch_table, &rel, b, &mut dx, &mut pieces, &mut out);
    }
    out.sort_by(f64::total_cmp);
    out.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    out
}

/// A linear time-periodic block `y'' + C y' + (K0 + sum_j w_j s_j(theta) v_j v_j^T) y = 0`
/// in M-orthonormal coordinates, with its monodromy accumulated in place.
///
/// All buffers are allocated once per orbit; a step reuses them.
struct LtpBlock {
    m: usize,
    k0: Vec<f64>,
    c: Vec<f64>,
    /// (weight, vector) per channel, in channel order.
    channels: Vec<(f64, Vec<f64>)>,
    /// The monodromy so far, row-major `2m x 2m`.
    phi: Vec<f64>,
    /// `K_eff` at the start, middle and end of the current step, row-major `m x m`.
    k_eff: [Vec<f64>; 3],
    /// The current stage derivative.
    stage: Vec<f64>,
    /// `k1 + 2 k2 + 2 k3 + k4`, accumulated stage by stage.
    acc: Vec<f64>,
    tmp: Vec<f64>,
}

impl LtpBlock {
    fn new(m: usize, k0: Vec<f64>, c: Vec<f64>, channels: Vec<(f64, Vec<f64>)>) -> Self {
        let n2 = 2 * m;
        let mut phi = vec![0.0; n2 * n2];
        for i in 0..n2 {
            phi[i * n2 + i] = 1.0;
        }
        LtpBlock {
            m,
            k0,
            c,
            channels,
            phi,
            k_eff: std::array::from_fn(|_| vec![0.0; m * m]),
            stage: vec![0.0; n2 * n2],
            acc: vec![0.0; n2 * n2],
            tmp: vec![0.0; n2 * n2],
        }
    }

    /// `K_eff = K0 + sum_j w_j s_j v_j v_j^T` for the channel slopes `s` into slot `slot`.
    fn set_stiffness(&mut self, slot: usize, slopes: &[f64]) {
        let m = self.m;
        let k_eff = &mut self.k_eff[slot];
        k_eff.copy_from_slice(&self.k0);
        for ((w, v), &s) in self.channels.iter().zip(slopes) {
            if s == 0.0 {
                continue;
            }
            let ws = w * s;
            for r in 0..m {
                let a = ws * v[r];
                if a == 0.0 {
                    continue;
                }
                for (kk, &vc) in k_eff[r * m..(r + 1) * m].iter_mut().zip(v) {
                    *kk += a * vc;
                }
            }
        }
    }

    /// `stage = A(theta) z / omega` with `K_eff` from `slot`; `z` is the
    /// monodromy or the stage point `tmp`.
    fn deriv(&mut self, slot: usize, inv: f64, z_is_tmp: bool) {
        let z = if z_is_tmp { &self.tmp } else { &self.phi };
        let (k_eff, c, out) = (&self.k_eff[slot], &self.c, &mut self.stage);
        // The usual block sizes (the symmetric set and its planet block) with
        // the row length known to the compiler, which keeps a row in registers.
        match self.m {
            5 => deriv_fixed::<5, 10>(k_eff, c, z, out, inv),
            2 => deriv_fixed::<2, 4>(k_eff, c, z, out, inv),
            1 => deriv_fixed::<1, 2>(k_eff, c, z, out, inv),
            m => deriv_any(m, k_eff, c, z, out, inv),
        }
    }

    /// One classical Runge–Kutta step of size `ht` in theta with the
    /// stiffness slots 0, 1 and 2 set for its start, middle and end.
    fn rk4(&mut self, ht: f64, omega: f64) {
        let inv = 1.0 / omega;
        self.deriv(0, inv, false);
        self.acc.copy_from_slice(&self.stage);
        for (t, (p, k)) in self.tmp.iter_mut().zip(self.phi.iter().zip(&self.stage)) {
            *t = p + 0.5 * ht * k;
        }
        self.deriv(1, inv, true);
        for (a, k) in self.acc.iter_mut().zip(&self.stage) {
            *a += 2.0 * k;
        }
        for (t, (p, k)) in self.tmp.iter_mut().zip(self.phi.iter().zip(&self.stage)) {
            *t = p + 0.5 * ht * k;
        }
        self.deriv(1, inv, true);
        for (a, k) in self.acc.iter_mut().zip(&self.stage) {
            *a += 2.0 * k;
        }
        for (t, (p, k)) in self.tmp.iter_mut().zip(self.phi.iter().zip(&self.stage)) {
            *t = p + ht * k;
        }
        self.deriv(2, inv, true);
        for ((p, a), k) in self.phi.iter_mut().zip(&self.acc).zip(&self.stage) {
            *p += ht / 6.0 * (a + k);
        }
    }

    fn multipliers(&self) -> Option<Vec<Complex<f64>>> {
        let n2 = 2 * self.m;
        let mat = DMatrix::from_row_slice(n2, n2, &self.phi);
        crate::dense::eigenvalues_with(&mat, 1e-14, 100_000)
    }
}

/// `out = A z / omega` for `A = [[0, I], [-K_eff, -C]]` (`m x m` blocks,
/// row-major `2m x 2m` matrices), any `m`.
fn deriv_any(m: usize, k_eff: &[f64], c: &[f64], z: &[f64], out: &mut [f64], inv: f64) {
    let n2 = 2 * m;
    // Position rows: the velocity rows.
    for (o, &v) in out[..m * n2].iter_mut().zip(&z[m * n2..]) {
        *o = v * inv;
    }
    // Velocity rows: -(K_eff z_x + C z_v).
    for r in 0..m {
        let row = &mut out[(m + r) * n2..(m + r + 1) * n2];
        row.fill(0.0);
        for l in 0..m {
            let (kl, cl) = (k_eff[r * m + l], c[r * m + l]);
            if kl != 0.0 {
                for (o, &v) in row.iter_mut().zip(&z[l * n2..(l + 1) * n2]) {
                    *o -= kl * v;
                }
            }
            if cl != 0.0 {
                for (o, &v) in row.iter_mut().zip(&z[(m + l) * n2..(m + l + 1) * n2]) {
                    *o -= cl * v;
                }
            }
        }
        for x in row.iter_mut() {
            *x *= inv;
        }
    }
}

/// [`deriv_any`] for `m = M`, `2m = N2` (the same operations in the same order).
fn deriv_fixed<const M: usize, const N2: usize>(
    k_eff: &[f64],
    c: &[f64],
    z: &[f64],
    out: &mut [f64],
    inv: f64,
) {
    let (z, _) = z.as_chunks::<N2>();
    let (out, _) = out.as_chunks_mut::<N2>();
    for r in 0..M {
        for (o, &v) in out[r].iter_mut().zip(&z[M + r]) {
            *o = v * inv;
        }
    }
    for r in 0..M {
        let mut row = [0.0; N2];
        for l in 0..M {
            let (kl, cl) = (k_eff[r * M + l], c[r * M + l]);
            if kl != 0.0 {
                for (o, &v) in row.iter_mut().zip(&z[l]) {
                    *o -= kl * v;
                }
            }
            if cl != 0.0 {
                for (o, &v) in row.iter_mut().zip(&z[M + l]) {
                    *o -= cl * v;
                }
            }
        }
        for (o, &v) in out[M + r].iter_mut().zip(&row) {
            *o = v * inv;
        }
    }
}

/// Computes the Floquet multipliers of the orbit `x` at frequency `omega`.
/// `None` if the eigenvalue iteration did not converge.
pub fn floquet(asm: &Assembly, x: &[f64], omega: f64) -> Option<Floquet> {
    let (coefs, cuts) = orbit_pieces(asm, x);
    monodromy(asm, omega, &cuts, Some(&coefs), ORBIT_STEPS_PER_FASTEST)
}

/// The orbit `x`'s channel coefficients (each channel's relative
/// displacement in the Fourier basis) and the phases that cut one period
/// into pieces of constant contact state (0, the switches, 2 pi).
fn orbit_pieces(asm: &Assembly, x: &[f64]) -> (Vec<Vec<f64>>, Vec<f64>) {
    let model = &asm.model;
    let m = model.m;
    let h = asm.h;
    let nc = n_coef(h);
    let coefs: Vec<Vec<f64>> = model
        .channels
        .iter()
        .map(|ch| {
            (0..nc)
                .map(|c| (0..m).map(|i| ch.d[i] * x[c * m + i]).sum())
                .collect()
        })
        .collect();
    let mut cuts = vec![0.0];
    cuts.extend(switch_phases(asm, &coefs));
    cuts.push(2.0 * PI);
    (coefs, cuts)
}

/// The Floquet multipliers of the linear time-periodic system with every
/// mesh in contact (the dead zone's slope 1 everywhere): the linearization
/// of any motion large against the backlash. A multiplier outside the unit
/// circle means such motion grows without bound (a parametric instability
/// of the time-varying mesh stiffness). `None` if the eigenvalue iteration
/// did not converge.
///
/// With [`ENGAGED_STEPS_PER_FASTEST`] RK4 steps per period of the fastest
/// mode (more than the orbits' [`ORBIT_STEPS_PER_FASTEST`]): RK4's
/// artificial damping of an oscillation, `(omega h)^6 / 144` per step,
/// would otherwise shift `ln rho` where the fastest mode decides it (a
/// single gear pair at low Omega), and the spectral radius is the
/// reference the other methods' multipliers are checked against.
pub(crate) fn floquet_engaged(asm: &Assembly, omega: f64) -> Option<Floquet> {
    monodromy(
        asm,
        omega,
        &[0.0, 2.0 * PI],
        None,
        ENGAGED_STEPS_PER_FASTEST,
    )
}

/// The monodromy over one period split at `cuts` (contact switches), the
/// contact state of each piece read from the orbit's channel coefficients
/// `coefs`, or every channel in contact without them; at least
/// `steps_per_fastest` RK4 steps per period of the fastest mode.
fn monodromy(
    asm: &Assembly,
    omega: f64,
    cuts: &[f64],
    coefs: Option<&[Vec<f64>]>,
    steps_per_fastest: f64,
) -> Option<Floquet> {
    let (main, planet) = integrate_blocks(asm, omega, cuts, coefs, steps_per_fastest, BOTH)?;
    let multipliers = main.multipliers()?;
    let planet_multipliers = match &planet {
        Some(pb) => pb.multipliers()?,
        None => Vec::new(),
    };
    Some(Floquet {
        multipliers,
        planet_multipliers,
    })
}

/// The monodromy matrices (`2m x 2m`, then the planet block's `4 x 4` under
/// the symmetric reduction) of the orbit `x` at `omega`, as [`floquet`]
/// computes them: for test functions on the multipliers (the boundaries'
/// period doublings). `None` if they are not finite.
pub(crate) fn monodromy_matrices(
    asm: &Assembly,
    x: &[f64],
    omega: f64,
) -> Option<(DMatrix<f64>, Option<DMatrix<f64>>)> {
    let (coefs, cuts) = orbit_pieces(asm, x);
    let (main, planet) = integrate_blocks(
        asm,
        omega,
        &cuts,
        Some(&coefs),
        ORBIT_STEPS_PER_FASTEST,
        BOTH,
    )?;
    let finite = |b: &LtpBlock| b.phi.iter().all(|v| v.is_finite());
    if !finite(&main) || planet.as_ref().is_some_and(|p| !finite(p)) {
        return None;
    }
    let mat = |b: &LtpBlock| DMatrix::from_row_slice(2 * b.m, 2 * b.m, &b.phi);
    Some((mat(&main), planet.as_ref().map(mat)))
}

/// The monodromy matrix of one block of the orbit `x` at `omega` (0: the
/// main block, 1: the planet block), the same as
/// [`monodromy_matrices`]'s: the blocks are integrated over the same
/// steps, each on its own, so the other is not integrated (a boundary
/// trace's differenced test function needs one block, on the planet
/// block a fraction of the main block's work). `None` if there is no such
/// block or the matrix is not finite.
pub(crate) fn monodromy_block(
    asm: &Assembly,
    x: &[f64],
    omega: f64,
    block: usize,
) -> Option<DMatrix<f64>> {
    let (coefs, cuts) = orbit_pieces(asm, x);
    let only = [block == 0, block == 1];
    let (main, planet) = integrate_blocks(
        asm,
        omega,
        &cuts,
        Some(&coefs),
        ORBIT_STEPS_PER_FASTEST,
        only,
    )?;
    let b = if block == 0 { main } else { planet? };
    b.phi
        .iter()
        .all(|v| v.is_finite())
        .then(|| DMatrix::from_row_slice(2 * b.m, 2 * b.m, &b.phi))
}

/// Both blocks integrated ([`integrate_blocks`]'s `blocks`).
const BOTH: [bool; 2] = [true, true];

/// Integrates the main and planet blocks over the period split at `cuts`;
/// a block whose entry of `blocks` (main, planet) is false is left at the
/// identity.
fn integrate_blocks(
    asm: &Assembly,
    omega: f64,
    cuts: &[f64],
    coefs: Option<&[Vec<f64>]>,
    steps_per_fastest: f64,
    blocks: [bool; 2],
) -> Option<(LtpBlock, Option<LtpBlock>)> {
    let model = &asm.model;
    let m = model.m;
    let h = asm.h;
    let u_at = |j: usize, theta: f64| coefs.map_or(0.0, |c| eval_coef(&c[j], h, theta));
    // Steps in theta: at least `steps_per_fastest` per period of the
    // fastest mode (in tau), or of the mesh where it is faster.
    let h_theta_max = omega * 2.0 * PI / (steps_per_fastest * model.omega_max.max(omega));
    let flat = |mat: &DMatrix<f64>| -> Vec<f64> {
        (0..mat.nrows())
            .flat_map(|r| (0..mat.ncols()).map(move |c| mat[(r, c)]))
            .collect()
    };
    let mut main = LtpBlock::new(
        m,
        flat(&model.stiffness),
        flat(&model.damping),
        model
            .channels
            .iter()
            .map(|ch| (ch.multiplicity, ch.d.clone()))
            .collect(),
    );
    let mut planet = model.planet_block.as_ref().filter(|_| blocks[1]).map(|pb| {
        LtpBlock::new(
            2,
            vec![0.0; 4],
            vec![
                pb.damping[0][0],
                pb.damping[0][1],
                pb.damping[1][0],
                pb.damping[1][1],
            ],
            pb.p.iter().map(|p| (1.0, p.to_vec())).collect(),
        )
    });
    // Each channel's phase as its cosine and sine: the seed's one-harmonic
    // stiffness at `theta` is then one `sin_cos` of `theta` for all channels.
    let phases: Vec<(f64, f64)> = model
        .channels
        .iter()
        .map(|ch| match ch.law {
            Law::Mesh { phase_rad, .. } => (phase_rad.cos(), phase_rad.sin()),
            Law::Cubic { .. } => (1.0, 0.0),
        })
        .collect();
    let mut active = vec![false; model.channels.len()];
    let mut slopes = vec![0.0; model.channels.len()];
    for w in cuts.windows(2) {
        let (a, b) = (w[0], w[1]);
        if b - a <= 0.0 {
            continue;
        }
        // The contact state is fixed inside the piece: read it at the middle.
        let mid = 0.5 * (a + b);
        for (j, ch) in model.channels.iter().enumerate() {
            active[j] = coefs.is_none() || ch.law.force(mid, u_at(j, mid)).1 != 0.0;
        }
        let slopes_at = |theta: f64, out: &mut [f64]| {
            let (sin_t, cos_t) = theta.sin_cos();
            for (j, (ch, o)) in model.channels.iter().zip(out.iter_mut()).enumerate() {
                *o = if !active[j] {
                    0.0
                } else {
                    match ch.law {
                        // The seed's one harmonic, as written before the waveforms.
                        Law::Mesh {
                            k,
                            variation,
                            ref higher,
                            ..
                        } if higher.is_empty() => {
                            // cos(theta + phase), from the angle-sum formula.
                            let (cos_p, sin_p) = phases[j];
                            k * (1.0 + variation * (cos_t * cos_p - sin_t * sin_p))
                        }
                        Law::Mesh { .. } => ch.law.stiffness(theta),
                        Law::Cubic { .. } => ch.law.force(theta, u_at(j, theta)).1,
                    }
                };
            }
        };
        let steps = ((b - a) / h_theta_max).ceil().max(1.0) as usize;
        let ht = (b - a) / steps as f64;
        for step in 0..steps {
            let t0 = a + step as f64 * ht;
            // The end of a step is the start of the next (up to the
            // rounding of theta): its stiffness is kept.
            let first = if step == 0 {
                0
            } else {
                main.k_eff.swap(0, 2);
                if let Some(pb) = planet.as_mut() {
                    pb.k_eff.swap(0, 2);
                }
                1
            };
            for (slot, theta) in [t0, t0 + 0.5 * ht, t0 + ht]
                .into_iter()
                .enumerate()
                .skip(first)
            {
                slopes_at(theta, &mut slopes);
                if blocks[0] {
                    main.set_stiffness(slot, &slopes);
                }
                if let Some(pb) = planet.as_mut() {
                    pb.set_stiffness(slot, &slopes);
                }
            }
            if blocks[0] {
                main.rk4(ht, omega);
            }
            if let Some(pb) = planet.as_mut() {
                pb.rk4(ht, omega);
            }
        }
    }
    Some((main, planet))
}
