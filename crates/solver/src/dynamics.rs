//! The equations of motion of a [`MeshSystem`] as a first-order ODE, with the
//! contact switches as event functions.
//!
//! State `y = (q, q')`. The right-hand side exploits the sparse mesh vectors:
//! each mesh touches at most three coordinates, so a deflection and its rate
//! cost six multiply-adds; the mesh force then enters the acceleration
//! through the precomputed `M^-1 w_j` (a contiguous AXPY), and one `sin_cos`
//! serves all meshes. For the default compound set (12 meshes, 10
//! coordinates) one evaluation is 12 x (6 + 10) + 10 = 202 multiply-adds
//! plus about 15 operations of force law per mesh: some 600 flops.

use crate::ode::Ode;
use crate::system::{dead_zone, MeshSystem};
use crate::trig::phase_sin_cos;

/// Largest number of coordinates a mesh vector touches (sun, carrier, planet).
const MAX_W: usize = 3;

/// The acceleration columns are padded to a multiple of this many entries;
/// up to 16 (the compound set with six planet pairs has 16 coordinates) the
/// right-hand side accumulates in a fixed-size local array that stays in
/// registers.
const PAD: usize = 4;

/// Per-mesh data laid out for the hot loop: a fixed three-entry mesh vector
/// (padded with zero weights) so the deflection needs no inner loop.
#[derive(Debug, Clone)]
struct HotMesh {
    cols: [usize; MAX_W],
    /// `cols` and their rates' places `n + cols`: what the mesh's state reads.
    state_cols: [usize; 2 * MAX_W],
    w: [f64; MAX_W],
    k_mean: f64,
    variation: f64,
    backlash: f64,
    te_mean: f64,
    te_cos: f64,
    te_sin: f64,
    damping: f64,
    cos_g: f64,
    sin_g: f64,
    /// Harmonics 2, 3, ... of the excitation: `[k_m a_n, te cos, te sin]`
    /// (empty for the seed's one-harmonic excitation, the fast path).
    higher: Vec<[f64; 3]>,
}

impl HotMesh {
    #[inline(always)]
    fn dot(&self, x: &[f64]) -> f64 {
        self.w[0] * x[self.cols[0]] + self.w[1] * x[self.cols[1]] + self.w[2] * x[self.cols[2]]
    }
}

/// The gear model's ODE at one mesh frequency.
///
/// The acceleration is assembled as `M^-1 tau - sum_c q_c M^-1 K_sup e_c -
/// sum_j F_j a_j` with the precomputed `a_j = M^-1 w_j`: contiguous AXPYs
/// of length n, no scatter and no separate solve with M.
#[derive(Debug, Clone)]
pub struct MeshOde {
    n: usize,
    omega_rad_s: f64,
    meshes: Vec<HotMesh>,
    /// `n` rounded up to a multiple of [`PAD`]: the stride of the columns below.
    padded: usize,
    /// `a_j = M^-1 w_j`, mesh after mesh, `padded` entries each (zeros past n).
    accel_per_force: Vec<f64>,
    /// `M^-1 tau`, padded.
    accel_load: Vec<f64>,
    /// Columns of K_sup with a non-zero entry and `M^-1 K_sup e_c` for each, padded.
    support_cols: Vec<usize>,
    accel_per_support: Vec<f64>,
    /// The last `(t, sin wt, cos wt)`: DOPRI5's last two stages share a time.
    phase_cache: (f64, f64, f64),
    /// Event list: (mesh index, side) with `g = (delta - e) - side * b`.
    events: Vec<(usize, f64)>,
    /// Scratch for [`MeshOde::tangent`]: each mesh's stiffness slope.
    slopes: Vec<f64>,
}

/// Kinematic and force state of one mesh at an instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshInstant {
    /// Deflection delta (m).
    pub delta: f64,
    /// Deflection rate delta' (m/s).
    pub delta_dot: f64,
    /// Relative displacement x = delta - e (m), which the backlash acts on.
    pub rel: f64,
    /// Its rate x' (m/s).
    pub rel_dot: f64,
    /// Mesh force F (N).
    pub force: f64,
}

impl MeshOde {
    /// The ODE of `sys` at mesh frequency `omega_rad_s`.
    pub fn new(sys: &MeshSystem, omega_rad_s: f64) -> Self {
        let n = sys.dof();
        let padded = n.div_ceil(PAD) * PAD;
        let mut meshes = Vec::with_capacity(sys.meshes.len());
        let mut events = Vec::new();
        let mut accel_per_force = Vec::with_capacity(padded * sys.meshes.len());
        let minv = |x: &[f64]| {
            let mut out = vec![0.0; padded];
            sys.mass_inv.mul(x, &mut out[..n]);
            out
        };
        for (j, m) in sys.meshes.iter().enumerate() {
            let mut cols = [0; MAX_W];
            let mut w = [0.0; MAX_W];
            let mut dense = vec![0.0; n];
            for (k, &(i, wi)) in m.w.iter().take(MAX_W).enumerate() {
                cols[k] = i;
                w[k] = wi;
                dense[i] = wi;
            }
            accel_per_force.extend(minv(&dense));
            let (sin_g, cos_g) = m.phase_rad.sin_cos();
            meshes.push(HotMesh {
                cols,
                state_cols: std::array::from_fn(|i| {
                    if i < MAX_W {
                        cols[i]
                    } else {
                        n + cols[i - MAX_W]
                    }
                }),
                w,
                k_mean: m.stiffness_mean_n_m,
                variation: m.stiffness_variation,
                backlash: m.backlash_m,
                te_mean: m.te_mean_m,
                te_cos: m.te_cos_m,
                te_sin: m.te_sin_m,
                damping: m.damping_n_s_m,
                cos_g,
                sin_g,
                higher: (2..=m.excitation_harmonics())
                    .map(|n| {
                        let a = m.stiffness_harmonics.get(n - 2).copied().unwrap_or(0.0);
                        let [tc, ts] = m.te_harmonics_m.get(n - 2).copied().unwrap_or([0.0; 2]);
                        [m.stiffness_mean_n_m * a, tc, ts]
                    })
                    .collect(),
            });
            // With b = 0 the force law has no kink: no event needed.
            if m.backlash_m > 0.0 {
                events.push((j, 1.0));
                events.push((j, -1.0));
            }
        }
        let mut support_cols = Vec::new();
        let mut accel_per_support = Vec::new();
        for c in 0..n {
            let mut column = vec![0.0; n];
            let mut any = false;
            for (i, entry) in column.iter_mut().enumerate() {
                let range = sys.support.row_start[i]..sys.support.row_start[i + 1];
                for k in range {
                    if sys.support.cols[k] == c {
                        *entry = sys.support.vals[k];
                        any = true;
                    }
                }
            }
            if any {
                support_cols.push(c);
                accel_per_support.extend(minv(&column));
            }
        }
        MeshOde {
            n,
            padded,
            omega_rad_s,
            meshes,
            accel_per_force,
            accel_load: minv(&sys.load_nm),
            support_cols,
            accel_per_support,
            phase_cache: (f64::NAN, 0.0, 1.0),
            events,
            slopes: Vec::new(),
        }
    }

    /// Mesh frequency (rad/s).
    pub fn omega_rad_s(&self) -> f64 {
        self.omega_rad_s
    }

    /// Number of generalized coordinates.
    pub fn dof(&self) -> usize {
        self.n
    }

    /// The event list: (mesh, side) pairs.
    pub fn event_list(&self) -> &[(usize, f64)] {
        &self.events
    }

    #[inline]
    fn dot(&self, m: &HotMesh, x: &[f64]) -> f64 {
        m.dot(x)
    }

    /// Stiffness, TE and TE rate of mesh `m` at phase `(cos wt, sin wt)`.
    #[inline]
    fn excitation(&self, m: &HotMesh, c: f64, s: f64) -> (f64, f64, f64) {
        let cc = c * m.cos_g - s * m.sin_g;
        let ss = s * m.cos_g + c * m.sin_g;
        let k = m.k_mean * (1.0 + m.variation * cc);
        let e = m.te_mean + m.te_cos * cc + m.te_sin * ss;
        let de = self.omega_rad_s * (m.te_sin * cc - m.te_cos * ss);
        if m.higher.is_empty() {
            (k, e, de)
        } else {
            self.higher_harmonics(m, cc, ss, (k, e, de))
        }
    }

    /// Adds harmonics 2, 3, ... of a mesh's excitation (the cosines and
    /// sines of `n theta` by the angle-addition recurrence).
    #[inline(never)]
    fn higher_harmonics(
        &self,
        m: &HotMesh,
        c: f64,
        s: f64,
        (mut k, mut e, mut de): (f64, f64, f64),
    ) -> (f64, f64, f64) {
        let (mut cn, mut sn) = (c, s);
        for (i, &[ka, tc, ts]) in m.higher.iter().enumerate() {
            (cn, sn) = (cn * c - sn * s, sn * c + cn * s);
            k += ka * cn;
            e += tc * cn + ts * sn;
            de += self.omega_rad_s * (i + 2) as f64 * (ts * cn - tc * sn);
        }
        (k, e, de)
    }

    /// The state of mesh `j` at `(t, y)`.
    pub fn mesh_instant(&self, j: usize, t: f64, y: &[f64]) -> MeshInstant {
        let (s, c) = self.phase_seen(t);
        self.instant_at_phase(j, c, s, y)
    }

    #[inline]
    fn instant_at_phase(&self, j: usize, c: f64, s: f64, y: &[f64]) -> MeshInstant {
        let (q, v) = y.split_at(self.n);
        let m = &self.meshes[j];
        let delta = self.dot(m, q);
        let delta_dot = self.dot(m, v);
        let (k, e, de) = self.excitation(m, c, s);
        let rel = delta - e;
        let rel_dot = delta_dot - de;
        MeshInstant {
            delta,
            delta_dot,
            rel,
            rel_dot,
            force: k * dead_zone(rel, m.backlash) + m.damping * rel_dot,
        }
    }

    /// The components of the state `(q, q')` that mesh `j`'s
    /// [`MeshOde::mesh_instant`] reads.
    pub fn mesh_components(&self, j: usize) -> &[usize] {
        &self.meshes[j].state_cols
    }

    /// All meshes' states at `(t, y)`, into `out`.
    pub fn mesh_instants(&self, t: f64, y: &[f64], out: &mut Vec<MeshInstant>) {
        let (s, c) = self.phase_seen(t);
        out.clear();
        out.extend((0..self.meshes.len()).map(|j| self.instant_at_phase(j, c, s, y)));
    }

    /// All mesh deflections `w_j . q` for positions `q` (no excitation needed).
    pub fn deflections(&self, q: &[f64], out: &mut [f64]) {
        for (o, m) in out.iter_mut().zip(&self.meshes) {
            *o = self.dot(m, q);
        }
    }

    /// The deflection `w_j . q` of mesh `j` for positions `q`.
    pub fn deflection(&self, j: usize, q: &[f64]) -> f64 {
        self.dot(&self.meshes[j], q)
    }

    /// The mesh force of `m` at positions `q`, rates `v` and phase `(c, s)`.
    #[inline(always)]
    fn mesh_force(&self, m: &HotMesh, q: &[f64], v: &[f64], c: f64, s: f64) -> f64 {
        let delta = m.dot(q);
        let delta_dot = m.dot(v);
        let (k, e, de) = self.excitation(m, c, s);
        k * dead_zone(delta - e, m.backlash) + m.damping * (delta_dot - de)
    }

    /// The accelerations `dv` for a padded dimension `P`: the sum
    /// `M^-1 tau - sum_c q_c M^-1 K_sup e_c - sum_j F_j a_j` accumulates in a
    /// local `[f64; P]` (registers, not memory), each entry in the same order
    /// of operations as [`MeshOde::accelerations_any`].
    #[inline(always)]
    fn accelerations<const P: usize>(&self, q: &[f64], v: &[f64], c: f64, s: f64, dv: &mut [f64]) {
        let mut acc = [0.0; P];
        let (load, _) = self.accel_load.as_chunks::<P>();
        if let Some(load) = load.first() {
            acc = *load;
        }
        let (support, _) = self.accel_per_support.as_chunks::<P>();
        for (&col, a) in self.support_cols.iter().zip(support) {
            let qc = q[col];
            for i in 0..P {
                acc[i] -= qc * a[i];
            }
        }
        let (forces, _) = self.accel_per_force.as_chunks::<P>();
        for (m, a) in self.meshes.iter().zip(forces) {
            let force = self.mesh_force(m, q, v, c, s);
            for i in 0..P {
                acc[i] -= force * a[i];
            }
        }
        dv.copy_from_slice(&acc[..dv.len()]);
    }

    /// The accelerations for any dimension: AXPYs into `dv`.
    fn accelerations_any(&self, q: &[f64], v: &[f64], c: f64, s: f64, dv: &mut [f64]) {
        let (n, p) = (self.n, self.padded);
        dv.copy_from_slice(&self.accel_load[..n]);
        for (&col, a) in self
            .support_cols
            .iter()
            .zip(self.accel_per_support.chunks_exact(p))
        {
            let qc = q[col];
            for (d, &ai) in dv.iter_mut().zip(a) {
                *d -= qc * ai;
            }
        }
        for (m, a) in self.meshes.iter().zip(self.accel_per_force.chunks_exact(p)) {
            let force = self.mesh_force(m, q, v, c, s);
            for (d, &ai) in dv.iter_mut().zip(a) {
                *d -= force * ai;
            }
        }
    }

    /// The right-hand side's Jacobian applied to tangent vectors: `z` holds
    /// vectors `(dq, dv)` of `2n` entries one after another, and `dz`
    /// receives `(dv, -M^-1 (K_sup dq + sum_j w_j (k_j(t) g_j'(x_j) w_j.dq
    /// + c_j w_j.dv)))` for each. The dead zone's slope `g_j'` is 1 in
    /// contact and 0 apart, on the side [`crate::system::dead_zone`] takes
    /// at `x = +-b`; the variational equations of shooting integrate it
    /// alongside the orbit (`crate::shooting`).
    ///
    /// Each vector's accelerations accumulate in a local `[f64; P]` for the
    /// usual padded dimensions (registers, not memory: 1.24 times fewer
    /// instructions than AXPYs into `dz` on the compound set's default
    /// sweep, under callgrind), each entry
    /// in the same order of operations as [`MeshOde::tangent_any`], so both
    /// forms give the same bits (unit test below).
    pub fn tangent(&mut self, t: f64, y: &[f64], z: &[f64], dz: &mut [f64]) {
        let q = &y[..self.n];
        // The right-hand side has just taken the same instant's phase.
        let (s, c) = self.phase_at(t);
        let mut slopes = std::mem::take(&mut self.slopes);
        slopes.clear();
        slopes.extend(self.meshes.iter().map(|m| {
            let (k, e, _) = self.excitation(m, c, s);
            let x = m.dot(q) - e;
            if x > m.backlash || x < -m.backlash {
                k
            } else {
                0.0
            }
        }));
        match self.padded {
            4 => self.tangent_fixed::<4>(&slopes, z, dz),
            8 => self.tangent_fixed::<8>(&slopes, z, dz),
            12 => self.tangent_fixed::<12>(&slopes, z, dz),
            16 => self.tangent_fixed::<16>(&slopes, z, dz),
            _ => self.tangent_any(&slopes, z, dz),
        }
        self.slopes = slopes;
    }

    /// [`MeshOde::tangent`] for a padded dimension `P`, with each mesh's
    /// stiffness slope given.
    #[inline(always)]
    fn tangent_fixed<const P: usize>(&self, slopes: &[f64], z: &[f64], dz: &mut [f64]) {
        let n = self.n;
        let (support, _) = self.accel_per_support.as_chunks::<P>();
        let (forces, _) = self.accel_per_force.as_chunks::<P>();
        for (zc, dc) in z.chunks_exact(2 * n).zip(dz.chunks_exact_mut(2 * n)) {
            let (dq, dv) = zc.split_at(n);
            let (ddq, ddv) = dc.split_at_mut(n);
            ddq.copy_from_slice(dv);
            let mut acc = [0.0; P];
            for (&col, a) in self.support_cols.iter().zip(support) {
                let qc = dq[col];
                for i in 0..P {
                    acc[i] -= qc * a[i];
                }
            }
            for ((m, a), &slope) in self.meshes.iter().zip(forces).zip(slopes) {
                let f = slope * m.dot(dq) + m.damping * m.dot(dv);
                for i in 0..P {
                    acc[i] -= f * a[i];
                }
            }
            ddv.copy_from_slice(&acc[..n]);
        }
    }

    /// [`MeshOde::tangent`] for any dimension: AXPYs into `dz`.
    fn tangent_any(&self, slopes: &[f64], z: &[f64], dz: &mut [f64]) {
        let (n, p) = (self.n, self.padded);
        for (zc, dc) in z.chunks_exact(2 * n).zip(dz.chunks_exact_mut(2 * n)) {
            let (dq, dv) = zc.split_at(n);
            let (ddq, ddv) = dc.split_at_mut(n);
            ddq.copy_from_slice(dv);
            ddv.fill(0.0);
            for (&col, a) in self
                .support_cols
                .iter()
                .zip(self.accel_per_support.chunks_exact(p))
            {
                let qc = dq[col];
                for (d, &ai) in ddv.iter_mut().zip(a) {
                    *d -= qc * ai;
                }
            }
            for ((m, a), &slope) in self
                .meshes
                .iter()
                .zip(self.accel_per_force.chunks_exact(p))
                .zip(slopes)
            {
                let f = slope * m.dot(dq) + m.damping * m.dot(dv);
                for (d, &ai) in ddv.iter_mut().zip(a) {
                    *d -= f * ai;
                }
            }
        }
    }

    /// `(sin, cos)` of the mesh phase at `t`, remembered for the last `t`
    /// asked (the same bits as computing it afresh).
    #[inline]
    fn phase_at(&mut self, t: f64) -> (f64, f64) {
        let (s, c) = self.phase_seen(t);
        self.phase_cache = (t, s, c);
        (s, c)
    }

    /// [`Self::phase_at`] without remembering: the remembered phase if `t`
    /// is its instant (a step's end, where the integrator's last stage was
    /// evaluated), else computed afresh; the same bits either way.
    #[inline]
    fn phase_seen(&self, t: f64) -> (f64, f64) {
        if t == self.phase_cache.0 {
            (self.phase_cache.1, self.phase_cache.2)
        } else {
            phase_sin_cos(self.omega_rad_s * t)
        }
    }

    /// Number of meshes.
    pub fn n_meshes(&self) -> usize {
        self.meshes.len()
    }

    /// Backlash of mesh `j` (m).
    pub fn backlash(&self, j: usize) -> f64 {
        self.meshes[j].backlash
    }
}

impl Ode for MeshOde {
    fn dim(&self) -> usize {
        2 * self.n
    }

    fn rhs(&mut self, t: f64, y: &[f64], dy: &mut [f64]) {
        let n = self.n;
        let (q, v) = y.split_at(n);
        let (s, c) = self.phase_at(t);
        let (dq, dv) = dy.split_at_mut(n);
        dq.copy_from_slice(v);
        // The register-resident accumulator pays in WebAssembly (the 100 x 4
        // regime map 5 % faster in node) but not in native x86-64 code (3 to
        // 10 % slower there): each build takes its faster form. Both give
        // the same bits (unit test below).
        if cfg!(target_arch = "wasm32") {
            match self.padded {
                4 => self.accelerations::<4>(q, v, c, s, dv),
                8 => self.accelerations::<8>(q, v, c, s, dv),
                12 => self.accelerations::<12>(q, v, c, s, dv),
                16 => self.accelerations::<16>(q, v, c, s, dv),
                _ => self.accelerations_any(q, v, c, s, dv),
            }
        } else {
            self.accelerations_any(q, v, c, s, dv);
        }
    }

    fn n_events(&self) -> usize {
        self.events.len()
    }

    fn events(&mut self, t: f64, y: &[f64], _dy: &[f64], g: &mut [f64], dg: &mut [f64]) {
        let (q, v) = y.split_at(self.n);
        let (s, c) = self.phase_at(t);
        let mut idx = 0;
        while idx < self.events.len() {
            let j = self.events[idx].0;
            let m = &self.meshes[j];
            let (_, e, de) = self.excitation(m, c, s);
            let x = m.dot(q) - e;
            let xd = m.dot(v) - de;
            // Events come in (+1, -1) pairs per mesh.
            g[idx] = x - m.backlash;
            dg[idx] = xd;
            g[idx + 1] = x + m.backlash;
            dg[idx + 1] = xd;
            idx += 2;
        }
    }

    fn event_dim(&self) -> usize {
        self.n
    }

    fn event_components(&self, i: usize) -> Option<&[usize]> {
        Some(&self.meshes[self.events[i].0].cols)
    }

    fn event(&mut self, i: usize, t: f64, y: &[f64]) -> f64 {
        let (j, side) = self.events[i];
        let m = &self.meshes[j];
        let (s, c) = phase_sin_cos(self.omega_rad_s * t);
        let (_, e, _) = self.excitation(m, c, s);
        self.dot(m, &y[..self.n]) - e - side * m.backlash
    }
}

/// The integrator's tolerances for a run at `omega`: `atol_m` as a mesh
/// deflection, scaled to each coordinate's length (and, for rates, by the
/// larger of the mesh and reference frequencies); steps between
/// `h_min_periods` and an eighth of a mesh period.
pub(crate) fn tolerances(
    sys: &crate::system::MeshSystem,
    omega: f64,
    rtol: f64,
    atol_m: f64,
    period: f64,
    h_min_periods: f64,
) -> crate::ode::Tolerances {
    let lengths = sys.dof_length_m();
    let v_scale = sys.omega_ref_rad_s * omega.max(1.0);
    let mut atol: Vec<f64> = lengths.iter().map(|l| atol_m / l).collect();
    atol.extend(lengths.iter().map(|l| atol_m / l * v_scale));
    crate::ode::Tolerances {
        rtol,
        atol,
        h_min: period * h_min_periods,
        h_max: period / 8.0,
    }
}

#[cfg(test)]
mod tests {
    // Tests may panic: that is how they fail.
    #![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

    use super::*;
    use crate::keys;
    use crate::params::ModelParams;
    use crate::steady::Model;

    /// The compound set and the gear pair, each with its ODE at Omega 1.3.
    fn both_models() -> Vec<(&'static str, Model, MeshOde)> {
        ["ravigneaux", "gear-pair"]
            .into_iter()
            .map(|model| {
                let mut p = ModelParams::default();
                keys::set_assignment(&mut p, &format!("model={model}")).unwrap();
                let m = Model::new(&p).unwrap();
                let ode = MeshOde::new(&m.system, 1.3 * m.system.omega_ref_rad_s);
                (model, m, ode)
            })
            .collect()
    }

    /// The fixed-size accumulator (the wasm build's form) and the AXPY form
    /// (the native build's) compute the same bits, for the compound set (10
    /// coordinates, padded to 12) and the gear pair, at states in and out of
    /// contact.
    #[test]
    fn both_forms_of_the_accelerations_agree_to_the_bit() {
        for (model, m, ode) in both_models() {
            let n = ode.dof();
            let lengths = m.system.dof_length_m();
            for k in 0..50 {
                let y: Vec<f64> = m
                    .static_state()
                    .iter()
                    .enumerate()
                    .map(|(i, y)| {
                        let scale = lengths[i % n] * if i < n { 1.0 } else { 3e4 };
                        y + 2e-4 / scale * (0.7 * (i + 3 * k) as f64).sin()
                    })
                    .collect();
                let (q, v) = y.split_at(n);
                let (s, c) = phase_sin_cos(0.37 * k as f64);
                let mut a = vec![0.0; n];
                let mut b = vec![0.0; n];
                ode.accelerations_any(q, v, c, s, &mut a);
                match ode.padded {
                    4 => ode.accelerations::<4>(q, v, c, s, &mut b),
                    12 => ode.accelerations::<12>(q, v, c, s, &mut b),
                    other => panic!("padded {other}"),
                }
                assert_eq!(a, b, "{model}, state {k}");
                assert!(a.iter().all(|x| x.is_finite() && *x != 0.0));
            }
        }
    }

    /// The tangent's fixed-size accumulator and its AXPY form compute the
    /// same bits, for the compound set and the gear pair, with every mesh's
    /// slope in and out of contact.
    #[test]
    fn both_forms_of_the_tangent_agree_to_the_bit() {
        for (model, _, ode) in both_models() {
            let n = ode.dof();
            let cols = 2 * n - 2;
            for k in 0..20 {
                let z: Vec<f64> = (0..2 * n * cols)
                    .map(|i| 1e-6 * (0.37 * (i + 7 * k) as f64).sin())
                    .collect();
                let slopes: Vec<f64> = (0..ode.n_meshes())
                    .map(|j| {
                        if (j + k) % 3 == 0 {
                            0.0
                        } else {
                            1e9 * (1.0 + 0.1 * j as f64)
                        }
                    })
                    .collect();
                let mut a = vec![0.0; z.len()];
                let mut b = vec![0.0; z.len()];
                ode.tangent_any(&slopes, &z, &mut a);
                match ode.padded {
                    4 => ode.tangent_fixed::<4>(&slopes, &z, &mut b),
                    12 => ode.tangent_fixed::<12>(&slopes, &z, &mut b),
                    other => panic!("padded {other}"),
                }
                assert_eq!(a, b, "{model}, vectors {k}");
                assert!(a.iter().all(|x| x.is_finite()) && a.iter().any(|x| *x != 0.0));
            }
        }
    }
}
