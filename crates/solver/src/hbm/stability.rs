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
/// `gearshock bench --multipliers` measures it on the benchmark sweep.
pub const ORBIT_STEPS_PER_FASTEST: f64 = 16.0;

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
#[derive(Clone)]
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
    /// Over a piece whose meshes' stiffness is a trigonometric polynomial
    /// in theta, `K_eff(theta) = trig[0] + sum_n (cos(n theta) trig[2n - 1]
    /// - sin(n theta) trig[2n])`, each `m x m` row-major ([`Self::set_piece`]).
    trig: Vec<Vec<f64>>,
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
            trig: Vec::new(),
        }
    }

    /// Prepares [`Self::trig`] for a piece: every channel `j` with
    /// `active[j]` adds `w_j k_j (1 + sum_n a_jn cos(n (theta + phase_j)))
    /// v_j v_j^T`, split by the angle-sum formula into its constant part and
    /// the coefficients of `cos(n theta)` and `sin(n theta)`.
    fn set_piece(&mut self, active: &[bool], terms: &[MeshTerms]) {
        let m = self.m;
        let harmonics = terms.iter().map(|t| t.a.len()).max().unwrap_or(0);
        self.trig.resize_with(1 + 2 * harmonics, Vec::new);
        for (i, t) in self.trig.iter_mut().enumerate() {
            t.clear();
            if i == 0 {
                t.extend_from_slice(&self.k0);
            } else {
                t.resize(m * m, 0.0);
            }
        }
        for (((w, v), t), _) in self
            .channels
            .iter()
            .zip(terms)
            .zip(active)
            .filter(|(_, &on)| on)
        {
            let wk = w * t.k;
            add_outer(&mut self.trig[0], wk, v);
            for (n, &a) in t.a.iter().enumerate() {
                let (sin_p, cos_p) = ((n + 1) as f64 * t.phase_rad).sin_cos();
                add_outer(&mut self.trig[2 * n + 1], wk * a * cos_p, v);
                add_outer(&mut self.trig[2 * n + 2], wk * a * sin_p, v);
            }
        }
    }

    /// `K_eff` at theta into slot `slot` from [`Self::trig`], given
    /// `(cos(n theta), sin(n theta))` for `n = 1, 2, ...`.
    #[cfg_attr(target_arch = "x86_64", inline(always))]
    fn set_stiffness_trig(&mut self, slot: usize, cos_sin: &[(f64, f64)]) {
        let k_eff = &mut self.k_eff[slot];
        k_eff.copy_from_slice(&self.trig[0]);
        for (pair, &(c, s)) in self.trig[1..].chunks_exact(2).zip(cos_sin) {
            for ((k, pc), ps) in k_eff.iter_mut().zip(&pair[0]).zip(&pair[1]) {
                *k += c * pc - s * ps;
            }
        }
    }

    /// `K_eff = K0 + sum_j w_j s_j v_j v_j^T` for the channel slopes `s` into slot `slot`.
    #[cfg_attr(target_arch = "x86_64", inline(always))]
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

    /// `stage = A(theta) z` (the derivative in tau) with `K_eff` from
    /// `slot`; `z` is the monodromy or the stage point `tmp`.
    #[cfg_attr(target_arch = "x86_64", inline(always))]
    fn deriv(&mut self, slot: usize, z_is_tmp: bool) {
        let z = if z_is_tmp { &self.tmp } else { &self.phi };
        let (k_eff, c, out) = (&self.k_eff[slot], &self.c, &mut self.stage);
        // The usual block sizes (the symmetric set and its planet block) with
        // the row length known to the compiler, which keeps a row in registers.
        match self.m {
            5 => deriv_fixed::<5, 10>(k_eff, c, z, out),
            2 => deriv_fixed::<2, 4>(k_eff, c, z, out),
            1 => deriv_fixed::<1, 2>(k_eff, c, z, out),
            m => deriv_any(m, k_eff, c, z, out),
        }
    }

    /// One classical Runge–Kutta step of size `ht` in tau (`theta / omega`)
    /// with the stiffness slots 0, 1 and 2 set for its start, middle and end.
    #[cfg_attr(target_arch = "x86_64", inline(always))]
    fn rk4(&mut self, ht: f64) {
        // Each stage's two updates in one pass (the same operations on
        // each entry as one pass each).
        self.deriv(0, false);
        let (phi, stage) = (&self.phi, &self.stage);
        for ((a, t), (p, k)) in self
            .acc
            .iter_mut()
            .zip(&mut self.tmp)
            .zip(phi.iter().zip(stage))
        {
            *a = *k;
            *t = p + 0.5 * ht * k;
        }
        self.deriv(1, true);
        let (phi, stage) = (&self.phi, &self.stage);
        for ((a, t), (p, k)) in self
            .acc
            .iter_mut()
            .zip(&mut self.tmp)
            .zip(phi.iter().zip(stage))
        {
            *a += 2.0 * k;
            *t = p + 0.5 * ht * k;
        }
        self.deriv(1, true);
        let (phi, stage) = (&self.phi, &self.stage);
        for ((a, t), (p, k)) in self
            .acc
            .iter_mut()
            .zip(&mut self.tmp)
            .zip(phi.iter().zip(stage))
        {
            *a += 2.0 * k;
            *t = p + ht * k;
        }
        self.deriv(2, true);
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

/// A mesh channel's stiffness `k (1 + sum_n a[n-1] cos(n (theta + phase_rad)))`
/// (`a[0]` the variation, then the higher harmonics' amplitudes).
struct MeshTerms {
    k: f64,
    a: Vec<f64>,
    phase_rad: f64,
}

impl MeshTerms {
    /// Every channel's terms, or `None` if one is not a mesh (its slope
    /// then depends on the orbit, not on theta alone).
    fn of(channels: &[super::model::Channel]) -> Option<Vec<MeshTerms>> {
        channels
            .iter()
            .map(|ch| match ch.law {
                Law::Mesh {
                    k,
                    variation,
                    phase_rad,
                    ref higher,
                    ..
                } => Some(MeshTerms {
                    k,
                    a: std::iter::once(variation)
                        .chain(higher.iter().map(|h| h[0]))
                        .collect(),
                    phase_rad,
                }),
                Law::Cubic { .. } => None,
            })
            .collect()
    }
}

/// `mat += coef v v^T` (`mat` row-major, `v.len()` square).
fn add_outer(mat: &mut [f64], coef: f64, v: &[f64]) {
    if coef == 0.0 {
        return;
    }
    for (row, &vr) in mat.chunks_exact_mut(v.len()).zip(v) {
        let a = coef * vr;
        for (x, &vc) in row.iter_mut().zip(v) {
            *x += a * vc;
        }
    }
}

/// `out = A z` for `A = [[0, I], [-K_eff, -C]]` (`m x m` blocks,
/// row-major `2m x 2m` matrices), any `m`.
#[cfg_attr(target_arch = "x86_64", inline(always))]
fn deriv_any(m: usize, k_eff: &[f64], c: &[f64], z: &[f64], out: &mut [f64]) {
    let n2 = 2 * m;
    // Position rows: the velocity rows.
    out[..m * n2].copy_from_slice(&z[m * n2..]);
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
    }
}

/// [`deriv_any`] for `m = M`, `2m = N2` (the same operations in the same
/// order), on fixed-size rows: no bounds checks in the loops.
#[cfg_attr(target_arch = "x86_64", inline(always))]
fn deriv_fixed<const M: usize, const N2: usize>(
    k_eff: &[f64],
    c: &[f64],
    z: &[f64],
    out: &mut [f64],
) {
    let (z, _) = z.as_chunks::<N2>();
    let (out, _) = out.as_chunks_mut::<N2>();
    let (k_rows, _) = k_eff.as_chunks::<M>();
    let (c_rows, _) = c.as_chunks::<M>();
    let (z, out) = (&z[..N2], &mut out[..N2]);
    let (z_x, z_v) = z.split_at(M);
    out[..M].copy_from_slice(z_v);
    for ((k_row, c_row), out_row) in k_rows[..M].iter().zip(&c_rows[..M]).zip(&mut out[M..]) {
        let mut row = [0.0; N2];
        // No test for a zero factor (as `deriv_any` has): subtracting its
        // zero product leaves every finite entry's bits as they were, since
        // a row that starts at +0 never holds -0.
        for (((&kl, &cl), zx), zv) in k_row.iter().zip(c_row).zip(z_x).zip(z_v) {
            for (o, &v) in row.iter_mut().zip(zx) {
                *o -= kl * v;
            }
            for (o, &v) in row.iter_mut().zip(zv) {
                *o -= cl * v;
            }
        }
        *out_row = row;
    }
}

/// Computes the Floquet multipliers of the orbit `x` at frequency `omega`.
/// `None` if the eigenvalue iteration did not converge.
pub fn floquet(asm: &Assembly, x: &[f64], omega: f64) -> Option<Floquet> {
    floquet_with_steps(asm, x, omega, ORBIT_STEPS_PER_FASTEST)
}

/// [`floquet`] with `steps_per_fastest` RK4 steps per period of the
/// fastest mode instead of [`ORBIT_STEPS_PER_FASTEST`]: the multipliers'
/// accuracy measured against a finer integration of the same monodromy.
pub fn floquet_with_steps(
    asm: &Assembly,
    x: &[f64],
    omega: f64,
    steps_per_fastest: f64,
) -> Option<Floquet> {
    let (coefs, cuts) = orbit_pieces(asm, x);
    monodromy(asm, omega, &cuts, Some(&coefs), steps_per_fastest)
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
    let (main, planet) = orbit_blocks(asm, x, omega, BOTH)?;
    let planet = match planet {
        Some(pb) => Some(finite_matrix(&pb)?),
        None => None,
    };
    Some((finite_matrix(&main)?, planet))
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
    let (main, planet) = orbit_blocks(asm, x, omega, [block == 0, block == 1])?;
    finite_matrix(&if block == 0 { main } else { planet? })
}

/// The blocks `blocks` of the orbit `x`'s monodromy at `omega`, integrated
/// as [`floquet`] integrates them.
fn orbit_blocks(
    asm: &Assembly,
    x: &[f64],
    omega: f64,
    blocks: [bool; 2],
) -> Option<(LtpBlock, Option<LtpBlock>)> {
    let (coefs, cuts) = orbit_pieces(asm, x);
    integrate_blocks(
        asm,
        omega,
        &cuts,
        Some(&coefs),
        ORBIT_STEPS_PER_FASTEST,
        blocks,
    )
}

/// A block's monodromy as a matrix; `None` if it is not finite.
fn finite_matrix(b: &LtpBlock) -> Option<DMatrix<f64>> {
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
    // Every law a mesh's (the default): the stiffness over a piece is a
    // trigonometric polynomial in theta, assembled per piece.
    let terms = MeshTerms::of(&model.channels);
    let harmonics = terms
        .as_ref()
        .map_or(0, |t| t.iter().map(|t| t.a.len()).max().unwrap_or(0));
    let mut cos_sin = vec![(0.0, 0.0); harmonics];
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
        if let Some(terms) = &terms {
            if blocks[0] {
                main.set_piece(&active, terms);
            }
            if let Some(pb) = planet.as_mut() {
                pb.set_piece(&active, terms);
            }
        }
        // A law that is not a mesh's: each channel's slope at theta.
        let slopes_at = |theta: f64, out: &mut [f64]| {
            for (j, (ch, o)) in model.channels.iter().zip(out.iter_mut()).enumerate() {
                *o = if !active[j] {
                    0.0
                } else {
                    match ch.law {
                        Law::Mesh { .. } => ch.law.stiffness(theta),
                        Law::Cubic { .. } => ch.law.force(theta, u_at(j, theta)).1,
                    }
                };
            }
        };
        let steps = ((b - a) / h_theta_max).ceil().max(1.0) as usize;
        let ht = (b - a) / steps as f64;
        // The piece's steps with the widest vector instructions (the same
        // bits, `crate::simd`).
        crate::simd::dispatch(
            #[inline(always)]
            || {
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
                        if terms.is_some() {
                            // cos(n theta) and sin(n theta) by the angle-sum formula.
                            let (s1, c1) = theta.sin_cos();
                            let (mut c, mut s) = (1.0, 0.0);
                            for cs in cos_sin.iter_mut() {
                                (c, s) = (c * c1 - s * s1, s * c1 + c * s1);
                                *cs = (c, s);
                            }
                            if blocks[0] {
                                main.set_stiffness_trig(slot, &cos_sin);
                            }
                            if let Some(pb) = planet.as_mut() {
                                pb.set_stiffness_trig(slot, &cos_sin);
                            }
                        } else {
                            slopes_at(theta, &mut slopes);
                            if blocks[0] {
                                main.set_stiffness(slot, &slopes);
                            }
                            if let Some(pb) = planet.as_mut() {
                                pb.set_stiffness(slot, &slopes);
                            }
                        }
                    }
                    // The step in tau.
                    let h_tau = ht / omega;
                    if blocks[0] {
                        main.rk4(h_tau);
                    }
                    if let Some(pb) = planet.as_mut() {
                        pb.rk4(h_tau);
                    }
                }
            },
        );
    }
    Some((main, planet))
}

#[cfg(test)]
mod tests {
    // Tests may panic: that is how they fail.
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;

    /// A mesh law with `variation` and the higher stiffness harmonics `a`.
    fn mesh(k: f64, variation: f64, phase_rad: f64, a: &[f64]) -> Law {
        Law::Mesh {
            k,
            variation,
            phase_rad,
            backlash_um: 1.0,
            te_mean_um: 0.0,
            te_cos_um: 0.0,
            te_sin_um: 0.0,
            higher: a.iter().map(|&a| [a, 0.0, 0.0]).collect(),
        }
    }

    /// The stiffness assembled per piece from the angle-sum formula equals
    /// the one summed channel by channel from each law's own stiffness at
    /// theta (one and five harmonics, one channel out of contact).
    #[test]
    fn the_pieces_trigonometric_stiffness_is_the_laws() {
        let channels = [
            (mesh(2.0, 0.3, 0.4, &[]), 3.0, vec![1.0, -0.5, 0.2]),
            (
                mesh(1.5, 0.2, -1.1, &[0.1, -0.05, 0.02, 0.01]),
                1.0,
                vec![0.3, 0.8, -0.4],
            ),
            (mesh(0.7, 0.25, 2.0, &[0.05]), 2.0, vec![-0.6, 0.1, 0.9]),
        ];
        let k0 = vec![1.0, 0.1, 0.0, 0.1, 2.0, 0.3, 0.0, 0.3, 3.0];
        let mut block = LtpBlock::new(
            3,
            k0,
            vec![0.0; 9],
            channels.iter().map(|(_, w, v)| (*w, v.clone())).collect(),
        );
        let terms = MeshTerms::of(
            &channels
                .iter()
                .map(|(law, w, v)| super::super::model::Channel {
                    d: v.clone(),
                    multiplicity: *w,
                    law: law.clone(),
                    damping: 0.0,
                    meshes: Vec::new(),
                })
                .collect::<Vec<_>>(),
        )
        .expect("meshes");
        let active = [true, true, false];
        block.set_piece(&active, &terms);
        for theta in [0.0, 0.7, 2.5, 4.0, 6.1] {
            let cos_sin: Vec<(f64, f64)> = (1..=5)
                .map(|n| ((n as f64 * theta).cos(), (n as f64 * theta).sin()))
                .collect();
            block.set_stiffness_trig(0, &cos_sin);
            let slopes: Vec<f64> = channels
                .iter()
                .zip(active)
                .map(|((law, _, _), on)| if on { law.stiffness(theta) } else { 0.0 })
                .collect();
            block.set_stiffness(1, &slopes);
            for (a, b) in block.k_eff[0].iter().zip(&block.k_eff[1]) {
                assert!(
                    (a - b).abs() <= 1e-13 * (1.0 + b.abs()),
                    "theta {theta}: {a} vs {b}"
                );
            }
        }
    }

    /// A step run through the vector unit's dispatch (AVX2 where the
    /// processor has it) gives the same bits as the step compiled for the
    /// baseline: every block size the solver uses, dense stiffness and
    /// damping.
    #[test]
    fn the_dispatched_step_has_the_baseline_bits() {
        for m in [1, 2, 3, 5] {
            let fill = |seed: f64| -> Vec<f64> {
                (0..m * m)
                    .map(|i| {
                        (seed + 0.37 * i as f64).sin() + if i % (m + 1) == 0 { 3.0 } else { 0.0 }
                    })
                    .collect()
            };
            let channel = (2.0, (0..m).map(|i| (0.5 * i as f64).cos()).collect());
            let mut plain = LtpBlock::new(m, fill(0.1), fill(1.3), vec![channel]);
            for slot in 0..3 {
                plain.set_stiffness(slot, &[0.4 + 0.1 * slot as f64]);
            }
            let mut dispatched = plain.clone();
            for _ in 0..7 {
                plain.rk4(0.05);
                crate::simd::dispatch(
                    #[inline(always)]
                    || dispatched.rk4(0.05),
                );
            }
            assert_eq!(plain.phi, dispatched.phi, "m = {m}");
        }
    }
}
