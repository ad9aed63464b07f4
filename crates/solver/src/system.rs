//! The compiled model: a linear mechanical system joined by backlash meshes.
//!
//! Both built-in models compile to one [`MeshSystem`]: generalized coordinates
//! `q`, a constant mass matrix `M`, a support stiffness, constant external
//! loads `tau`, and meshes `j` whose deflections are linear in `q`,
//! `delta_j = w_j . q`, with the force law of `docs/model.md`:
//!
//! ```text
//! F_j = k_j(t) g_j(delta_j - e_j(t)) + c_j (delta_j' - e_j'(t))
//! M q'' + sum_j w_j F_j + K_sup q = tau
//! ```
//!
//! Everything derivable is derived here from the parameters: radii, the long
//! planet's tooth count, the carrier arm radii, equivalent masses, damping
//! coefficients, `omega_ref`, the rigid-body mode and the balancing torque.
//!
//! Mesh phasing. With `phasing = sequential`, planet `n` (position angle
//! `psi_n = 2 pi (n - 1) / N`) gets the mesh phases of Parker & Lin (2004):
//! `gamma_s1a,n = z_s1 psi_n`, `gamma_s2b,n = z_s2 psi_n`,
//! `gamma_rb,n = -z_r psi_n` and `gamma_ab,n = gamma_s1a,n` (the a-b contact is
//! fixed on the short planet relative to its s1-a contact), all modulo 2 pi,
//! plus the per-kind offset `phase_<kind>_deg`. The phase shifts both the
//! stiffness fluctuation and the transmission error of that mesh, since both
//! repeat with the same tooth engagement. With the default tooth counts
//! (36, 48, 84) every product `z psi_n` is a whole number of turns for
//! N = 3, 4 and 6, so sequential equals in-phase there; N = 5 differs.

use crate::error::{Result, SolverError};
use crate::params::{GearPairParams, MeshKind, ModelKind, ModelParams, Phasing, RavigneauxParams};
use crate::rpm::SpeedInfo;
use crate::waveform;
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// Relative tolerance on the torque balance over the rigid-body mode.
pub(crate) const TORQUE_BALANCE_RTOL: f64 = 1e-5;

/// One mesh: its sparse mesh vector and force law.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// Name, e.g. `s1a1`, `a2b2`, `rb3`, `pg`.
    pub name: String,
    /// Which bodies it joins.
    pub kind: MeshKind,
    /// Planet pair index (0-based) for the compound set, 0 for the gear pair.
    pub planet: usize,
    /// Non-zero entries of the mesh vector `w_j` (metres per radian).
    pub w: Vec<(usize, f64)>,
    /// Mean mesh stiffness k_m (N/m).
    pub stiffness_mean_n_m: f64,
    /// The stiffness's first harmonic relative to the mean: `v` for the
    /// seed's cosine, `v a_1` for the other waveforms (`crate::waveform`).
    pub stiffness_variation: f64,
    /// The stiffness's harmonics 2, 3, ... relative to the mean (cosines
    /// in `theta = omega t + gamma`); empty for the seed's cosine.
    pub stiffness_harmonics: Vec<f64>,
    /// Mesh phase gamma (rad).
    pub phase_rad: f64,
    /// Backlash half-width b (m).
    pub backlash_m: f64,
    /// TE mean (m).
    pub te_mean_m: f64,
    /// TE cosine amplitude (m).
    pub te_cos_m: f64,
    /// TE sine amplitude (m).
    pub te_sin_m: f64,
    /// The TE's `[cos, sin]` amplitudes (m) of harmonics 2, 3, ... (in
    /// `n theta`); empty for a one-harmonic TE.
    pub te_harmonics_m: Vec<[f64; 2]>,
    /// Equivalent mass 1 / (w^T M^-1 w) (kg).
    pub equivalent_mass_kg: f64,
    /// Viscous damping coefficient c (N s/m).
    pub damping_n_s_m: f64,
}

impl Mesh {
    /// Deflection `w . x` for a state vector `x` (positions or velocities).
    #[inline]
    pub fn dot(&self, x: &[f64]) -> f64 {
        self.w.iter().map(|&(i, wi)| wi * x[i]).sum()
    }

    /// Stiffness k(t), TE e(t) and its rate e'(t), given cos and sin of `omega t`.
    #[inline]
    pub fn excitation(&self, omega_rad_s: f64, cos_wt: f64, sin_wt: f64) -> (f64, f64, f64) {
        let (sg, cg) = self.phase_rad.sin_cos();
        let c = cos_wt * cg - sin_wt * sg;
        let s = sin_wt * cg + cos_wt * sg;
        let k = self.stiffness_mean_n_m * (1.0 + self.stiffness_variation * c);
        let e = self.te_mean_m + self.te_cos_m * c + self.te_sin_m * s;
        let de = omega_rad_s * (-self.te_cos_m * s + self.te_sin_m * c);
        if self.stiffness_harmonics.is_empty() && self.te_harmonics_m.is_empty() {
            return (k, e, de);
        }
        let (mut k, mut e, mut de) = (k, e, de);
        let (mut cn, mut sn) = (c, s);
        let top = self.excitation_harmonics();
        for n in 2..=top {
            (cn, sn) = (cn * c - sn * s, sn * c + cn * s);
            if let Some(a) = self.stiffness_harmonics.get(n - 2) {
                k += self.stiffness_mean_n_m * a * cn;
            }
            if let Some(&[tc, ts]) = self.te_harmonics_m.get(n - 2) {
                e += tc * cn + ts * sn;
                de += omega_rad_s * n as f64 * (ts * cn - tc * sn);
            }
        }
        (k, e, de)
    }

    /// The highest harmonic of the mesh's excitation (stiffness or TE), at least 1.
    pub fn excitation_harmonics(&self) -> usize {
        1 + self
            .stiffness_harmonics
            .len()
            .max(self.te_harmonics_m.len())
    }

    /// The mesh force for deflection `delta`, rate `delta_dot` at the given excitation.
    #[inline]
    pub fn force(&self, k: f64, e: f64, de: f64, delta: f64, delta_dot: f64) -> f64 {
        k * dead_zone(delta - e, self.backlash_m) + self.damping_n_s_m * (delta_dot - de)
    }
}

/// The backlash function g: `x - b` above `b`, `0` inside, `x + b` below `-b`.
#[inline]
pub fn dead_zone(x: f64, b: f64) -> f64 {
    if x > b {
        x - b
    } else if x < -b {
        x + b
    } else {
        0.0
    }
}

/// Contact state of a mesh at an instant.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Contact {
    /// Drive flanks pressed together (`delta - e > b`).
    Drive,
    /// Teeth apart (`|delta - e| <= b`).
    Apart,
    /// Back flanks pressed together (`delta - e < -b`).
    Back,
}

impl Contact {
    /// Classifies a relative displacement `x = delta - e` against backlash `b`.
    pub fn of(x: f64, b: f64) -> Self {
        if x > b {
            Contact::Drive
        } else if x < -b {
            Contact::Back
        } else {
            Contact::Apart
        }
    }

    /// Lower-case name for output.
    pub fn name(self) -> &'static str {
        match self {
            Contact::Drive => "drive",
            Contact::Apart => "apart",
            Contact::Back => "back",
        }
    }
}

/// A sparse matrix in compressed rows, for the right-hand side's hot loop.
#[derive(Debug, Clone, PartialEq)]
pub struct SparseRows {
    /// Start of each row in `cols`/`vals`, plus the end.
    pub row_start: Vec<usize>,
    /// Column index of each entry.
    pub cols: Vec<usize>,
    /// Value of each entry.
    pub vals: Vec<f64>,
}

impl SparseRows {
    /// Keeps the entries of `m` whose magnitude exceeds `1e-14` times the largest.
    pub fn from_dense(m: &DMatrix<f64>) -> Self {
        let scale = m.amax();
        let mut row_start = vec![0];
        let mut cols = Vec::new();
        let mut vals = Vec::new();
        for i in 0..m.nrows() {
            for j in 0..m.ncols() {
                let v = m[(i, j)];
                if v.abs() > 1e-14 * scale {
                    cols.push(j);
                    vals.push(v);
                }
            }
            row_start.push(cols.len());
        }
        SparseRows {
            row_start,
            cols,
            vals,
        }
    }

    /// `out = A x`.
    #[inline]
    pub fn mul(&self, x: &[f64], out: &mut [f64]) {
        for (o, range) in out.iter_mut().zip(self.row_start.windows(2)) {
            let cols = &self.cols[range[0]..range[1]];
            let vals = &self.vals[range[0]..range[1]];
            *o = cols.iter().zip(vals).map(|(&c, &v)| v * x[c]).sum();
        }
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.vals.len()
    }
}

/// The compiled model.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshSystem {
    /// Which model it was built from.
    pub model: ModelKind,
    /// Names of the generalized coordinates, e.g. `theta_s1`, `phi_a2`.
    pub dof_names: Vec<String>,
    /// Mass matrix M (kg m^2).
    pub mass: DMatrix<f64>,
    /// M^-1, sparse.
    pub mass_inv: SparseRows,
    /// Support stiffness K_sup (N m / rad), sparse.
    pub support: SparseRows,
    /// External generalized loads tau (N m), with any round-off imbalance
    /// over the rigid-body mode projected out.
    pub load_nm: Vec<f64>,
    /// The meshes.
    pub meshes: Vec<Mesh>,
    /// The rigid-body mode from kinematics (speed ratios from tooth counts), `theta_c = 1`
    /// for the compound set, `theta_pinion = 1` for the pair.
    pub rigid_mode: Vec<f64>,
    /// omega_ref = sqrt(k_m / m_e) of the first mesh (rad/s).
    pub omega_ref_rad_s: f64,
    /// The torque on s2 that balances the input torque (compound set), or the
    /// gear torque (pair), in N m.
    pub balancing_torque_nm: f64,
    /// Teeth of the member whose speed defines the mesh frequency and its
    /// speed ratio: `(z, n_member / n_ref)` used for `f_mesh = z |n_member - n_c|`.
    pub speed: SpeedInfo,
    /// Things the user should know that do not stop the computation.
    pub warnings: Vec<String>,
}

/// Derived geometry of the compound set, in metres and radians.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RavigneauxGeometry {
    /// Teeth of the long planet, (z_r - z_s2)/2.
    pub teeth_b: u32,
    /// Base radius of the small sun.
    pub rho_s1_m: f64,
    /// Base radius of the large sun.
    pub rho_s2_m: f64,
    /// Base radius of the short planet.
    pub rho_a_m: f64,
    /// Base radius of the long planet.
    pub rho_b_m: f64,
    /// Base radius of the ring.
    pub rho_r_m: f64,
    /// Carrier arm radius of the short planets, R_s1 + R_a.
    pub r_ca_m: f64,
    /// Carrier arm radius of the long planets, R_s2 + R_b.
    pub r_cb_m: f64,
    /// Angle from a short planet to its long planet about the centre.
    pub pair_angle_rad: f64,
}

impl RavigneauxGeometry {
    /// Derives the geometry from module, tooth counts and pressure angle.
    pub fn derive(p: &RavigneauxParams) -> Result<Self> {
        let geo = |message: String| SolverError::Geometry { message };
        if p.teeth_r <= p.teeth_s2 || !(p.teeth_r - p.teeth_s2).is_multiple_of(2) {
            return Err(geo(format!(
                "teeth_r - teeth_s2 = {} - {} must be positive and even (the long planet has (teeth_r - teeth_s2)/2 teeth)",
                p.teeth_r, p.teeth_s2
            )));
        }
        let teeth_b = (p.teeth_r - p.teeth_s2) / 2;
        if teeth_b < 6 {
            return Err(geo(format!(
                "the long planet would have (teeth_r - teeth_s2)/2 = {teeth_b} teeth; at least 6 are needed"
            )));
        }
        let m = p.module_mm * 1e-3;
        let cos_a = p.pressure_angle_deg.to_radians().cos();
        let pitch = |z: u32| m * f64::from(z) / 2.0;
        let (ra, rb) = (pitch(p.teeth_a), pitch(teeth_b));
        let r_ca = pitch(p.teeth_s1) + ra;
        let r_cb = pitch(p.teeth_s2) + rb;
        let d_ab = ra + rb;
        let cos_pair = (r_ca * r_ca + r_cb * r_cb - d_ab * d_ab) / (2.0 * r_ca * r_cb);
        if !(-1.0..=1.0).contains(&cos_pair) {
            return Err(geo(format!(
                "short and long planets cannot mesh: their centres sit at radii {:.1} and {:.1} mm but \
                 must be {:.1} mm apart (teeth_s1 = {}, teeth_a = {}, teeth_s2 = {}, teeth_r = {})",
                r_ca * 1e3,
                r_cb * 1e3,
                d_ab * 1e3,
                p.teeth_s1,
                p.teeth_a,
                p.teeth_s2,
                p.teeth_r
            )));
        }
        Ok(RavigneauxGeometry {
            teeth_b,
            rho_s1_m: pitch(p.teeth_s1) * cos_a,
            rho_s2_m: pitch(p.teeth_s2) * cos_a,
            rho_a_m: ra * cos_a,
            rho_b_m: rb * cos_a,
            rho_r_m: pitch(p.teeth_r) * cos_a,
            r_ca_m: r_ca,
            r_cb_m: r_cb,
            pair_angle_rad: cos_pair.acos(),
        })
    }

    /// Physical clashes of N equally spaced planet pairs (tip circles overlapping).
    fn interference(&self, p: &RavigneauxParams) -> Vec<String> {
        let m = p.module_mm * 1e-3;
        let tip_a = m * f64::from(p.teeth_a) / 2.0 + m;
        let tip_b = m * f64::from(self.teeth_b) / 2.0 + m;
        let n = f64::from(p.planets);
        let dist =
            |r1: f64, r2: f64, angle: f64| (r1 * r1 + r2 * r2 - 2.0 * r1 * r2 * angle.cos()).sqrt();
        let step = 2.0 * PI / n;
        let mut out = Vec::new();
        let checks = [
            (
                "short planets",
                dist(self.r_ca_m, self.r_ca_m, step),
                2.0 * tip_a,
            ),
            (
                "long planets",
                dist(self.r_cb_m, self.r_cb_m, step),
                2.0 * tip_b,
            ),
            (
                "a long planet and the next pair's short planet",
                dist(self.r_ca_m, self.r_cb_m, step - self.pair_angle_rad),
                tip_a + tip_b,
            ),
        ];
        for (what, d, need) in checks {
            if d < need {
                out.push(format!(
                    "with planets = {} equally spaced, {what} would overlap ({:.1} mm apart, {:.1} mm needed); \
                     the torsional model still runs, but no real gear set is built this way",
                    p.planets,
                    d * 1e3,
                    need * 1e3
                ));
            }
        }
        out
    }
}

impl MeshSystem {
    /// The conversion between Omega and the input member's speed.
    pub fn rpm_scale(&self) -> crate::rpm::RpmScale {
        crate::rpm::RpmScale {
            omega_ref_rad_s: self.omega_ref_rad_s,
            speed: self.speed,
        }
    }

    /// How much of the in-phase excitation of a mesh kind survives the sum
    /// over its `N` planet meshes at mesh order `k`: `|sum_n exp(i k
    /// gamma_n)| / N` with the meshes' phases `gamma_n`, for `k = 1 ..=
    /// max_order`, rounded to 1e-6 (exact zeros read as zeros). Sequential
    /// phasing cancels order `k` in the net torque on the central members
    /// when `k z / N` is not a whole number (Parker & Lin 2004). Empty when
    /// the system has no mesh of that kind.
    pub fn phasing_factors(&self, kind: MeshKind, max_order: u32) -> Vec<f64> {
        let phases: Vec<f64> = self
            .meshes
            .iter()
            .filter(|m| m.kind == kind)
            .map(|m| m.phase_rad)
            .collect();
        if phases.is_empty() {
            return Vec::new();
        }
        let n = phases.len() as f64;
        (1..=max_order)
            .map(|k| {
                let (c, s) = phases.iter().fold((0.0, 0.0), |(c, s), g| {
                    let a = f64::from(k) * g;
                    (c + a.cos(), s + a.sin())
                });
                let f = (c * c + s * s).sqrt() / n;
                (f * 1e6).round() / 1e6
            })
            .collect()
    }

    /// Validates the parameters and builds the system.
    pub fn build(params: &ModelParams) -> Result<Self> {
        validate_keys(params)?;
        Self::build_validated(params)
    }

    /// Builds the system of parameters already validated: a set that
    /// [`MeshSystem::build`] accepted with one key then changed through
    /// [`crate::keys::set`], which checks that key's range (a boundary
    /// trace builds one per value of its key: validating every key again
    /// took a seventh of the trace).
    pub(crate) fn build_validated(params: &ModelParams) -> Result<Self> {
        match params {
            ModelParams::Ravigneaux(p) => build_ravigneaux(p),
            ModelParams::GearPair(p) => build_gear_pair(p),
        }
    }

    /// Number of generalized coordinates.
    pub fn dof(&self) -> usize {
        self.dof_names.len()
    }

    /// Index of a mesh by name.
    pub fn mesh_index(&self, name: &str) -> Option<usize> {
        self.meshes.iter().position(|m| m.name == name)
    }

    /// The mean stiffness matrix K = sum_j k_jm w_j w_j^T + K_sup.
    pub fn mean_stiffness(&self) -> DMatrix<f64> {
        let n = self.dof();
        let mut k = DMatrix::zeros(n, n);
        for i in 0..n {
            for idx in self.support.row_start[i]..self.support.row_start[i + 1] {
                k[(i, self.support.cols[idx])] += self.support.vals[idx];
            }
        }
        for mesh in &self.meshes {
            for &(a, wa) in &mesh.w {
                for &(b, wb) in &mesh.w {
                    k[(a, b)] += mesh.stiffness_mean_n_m * wa * wb;
                }
            }
        }
        k
    }

    /// The mean damping matrix C = sum_j c_j w_j w_j^T.
    pub fn damping_matrix(&self) -> DMatrix<f64> {
        let n = self.dof();
        let mut c = DMatrix::zeros(n, n);
        for mesh in &self.meshes {
            for &(a, wa) in &mesh.w {
                for &(b, wb) in &mesh.w {
                    c[(a, b)] += mesh.damping_n_s_m * wa * wb;
                }
            }
        }
        c
    }

    /// The dense mesh vector of mesh `j`.
    pub fn mesh_vector(&self, j: usize) -> DVector<f64> {
        let mut w = DVector::zeros(self.dof());
        for &(i, wi) in &self.meshes[j].w {
            w[i] = wi;
        }
        w
    }

    /// A characteristic length (m) per coordinate: the largest mesh-vector
    /// entry acting on it, so that `length * angle` is an arc length. Used to
    /// scale integration tolerances.
    pub fn dof_length_m(&self) -> Vec<f64> {
        let mut len = vec![0.0_f64; self.dof()];
        for mesh in &self.meshes {
            for &(i, wi) in &mesh.w {
                len[i] = len[i].max(wi.abs());
            }
        }
        len.iter().map(|&l| if l > 0.0 { l } else { 1.0 }).collect()
    }

    /// Mesh frequency (Hz) at dimensionless frequency `omega`.
    pub fn mesh_freq_hz(&self, omega: f64) -> f64 {
        self.rpm_scale().mesh_hz(omega)
    }
}

fn validate_keys(params: &ModelParams) -> Result<()> {
    for spec in crate::keys::primary_keys(params.kind()) {
        if let Some(v) = crate::keys::get(params, spec.name) {
            // Round-trips through the key table's range check.
            let mut scratch = params.clone();
            crate::keys::set(&mut scratch, spec.name, v)?;
        }
    }
    Ok(())
}

fn equivalent_masses(mass: &DMatrix<f64>, meshes: &mut [Mesh], damping_ratio: f64) -> Result<()> {
    let n = mass.nrows();
    let chol = mass
        .clone()
        .cholesky()
        .ok_or_else(|| SolverError::Singular {
            what: "mass matrix (an inertia is zero or negative)".into(),
        })?;
    for mesh in meshes.iter_mut() {
        let mut w = DVector::zeros(n);
        for &(i, wi) in &mesh.w {
            w[i] = wi;
        }
        let minv_w = chol.solve(&w);
        let me = 1.0 / w.dot(&minv_w);
        mesh.equivalent_mass_kg = me;
        mesh.damping_n_s_m = 2.0 * damping_ratio * (mesh.stiffness_mean_n_m * me).sqrt();
    }
    Ok(())
}

fn inverse(mass: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    mass.clone()
        .cholesky()
        .map(|c| c.inverse())
        .ok_or_else(|| SolverError::Singular {
            what: "mass matrix".into(),
        })
}

/// Removes the component of `tau` that would accelerate the rigid mode `u`
/// (within the balance tolerance this is round-off, e.g. 969.69 vs 969.697 N m).
fn project_load(tau: &mut [f64], u: &[f64], mass: &DMatrix<f64>) {
    let n = tau.len();
    let uv = DVector::from_column_slice(u);
    let mu = mass * &uv;
    let umu = uv.dot(&mu);
    let ut: f64 = (0..n).map(|i| u[i] * tau[i]).sum();
    for i in 0..n {
        tau[i] -= mu[i] * ut / umu;
    }
}

fn build_ravigneaux(p: &RavigneauxParams) -> Result<MeshSystem> {
    let g = RavigneauxGeometry::derive(p)?;
    let n_pl = p.planets as usize;
    let n = 4 + 2 * n_pl;
    let (s1, s2, c, r) = (0, 1, 2, 3);
    let a = |i: usize| 4 + i;
    let b = |i: usize| 4 + n_pl + i;
    let mut names: Vec<String> = ["theta_s1", "theta_s2", "theta_c", "theta_r"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    names.extend((1..=n_pl).map(|i| format!("phi_a{i}")));
    names.extend((1..=n_pl).map(|i| format!("phi_b{i}")));

    // Mass matrix from the exact kinetic energy of docs/model.md.
    let nf = n_pl as f64;
    let mut mass = DMatrix::zeros(n, n);
    mass[(s1, s1)] = p.inertia_s1_kg_m2;
    mass[(s2, s2)] = p.inertia_s2_kg_m2;
    mass[(r, r)] = p.inertia_r_kg_m2;
    mass[(c, c)] = p.inertia_c_kg_m2
        + nf * p.mass_a_kg * g.r_ca_m.powi(2)
        + nf * p.mass_b_kg * g.r_cb_m.powi(2)
        + nf * (p.inertia_a_kg_m2 + p.inertia_b_kg_m2);
    for i in 0..n_pl {
        mass[(c, a(i))] = p.inertia_a_kg_m2;
        mass[(a(i), c)] = p.inertia_a_kg_m2;
        mass[(a(i), a(i))] = p.inertia_a_kg_m2;
        mass[(c, b(i))] = p.inertia_b_kg_m2;
        mass[(b(i), c)] = p.inertia_b_kg_m2;
        mass[(b(i), b(i))] = p.inertia_b_kg_m2;
    }

    let psi = |i: usize| 2.0 * PI * i as f64 / nf;
    let phase = |kind: MeshKind, i: usize| -> f64 {
        let seq = match (p.phasing, kind) {
            (Phasing::InPhase, _) => 0.0,
            (Phasing::Sequential, MeshKind::S1A | MeshKind::AB) => f64::from(p.teeth_s1) * psi(i),
            (Phasing::Sequential, MeshKind::S2B) => f64::from(p.teeth_s2) * psi(i),
            (Phasing::Sequential, MeshKind::RB) => -f64::from(p.teeth_r) * psi(i),
            (Phasing::Sequential, MeshKind::Pair) => 0.0,
        };
        (seq + p.phase_deg.get(kind).to_radians()).rem_euclid(2.0 * PI)
    };

    let series = MeshKind::COMPOUND
        .iter()
        .map(|&kind| {
            let shape = p.stiffness_shape[RavigneauxParams::kind_index(kind)];
            let contact_ratio = match shape.contact_ratio {
                Some(e) => e,
                None => {
                    let (z1, z2, internal) =
                        p.mesh_teeth(kind).ok_or_else(|| SolverError::Geometry {
                            message: format!("mesh kind {} has no teeth", kind.key()),
                        })?;
                    waveform::contact_ratio(z1, z2, internal, p.module_mm, p.pressure_angle_deg)
                }
            };
            waveform::stiffness_series(
                kind.key(),
                shape.wave,
                p.stiffness_variation,
                contact_ratio,
                p.stiffness_ramp,
                p.stiffness_harmonics as usize,
            )
        })
        .collect::<Result<Vec<_>>>()?;
    let mut meshes = Vec::with_capacity(4 * n_pl);
    for kind in MeshKind::COMPOUND {
        for i in 0..n_pl {
            let (name, w) = match kind {
                MeshKind::S1A => (
                    format!("s1a{}", i + 1),
                    vec![(s1, g.rho_s1_m), (c, -g.rho_s1_m), (a(i), g.rho_a_m)],
                ),
                MeshKind::S2B => (
                    format!("s2b{}", i + 1),
                    vec![(s2, g.rho_s2_m), (c, -g.rho_s2_m), (b(i), g.rho_b_m)],
                ),
                MeshKind::AB => (
                    format!("a{0}b{0}", i + 1),
                    vec![(a(i), -g.rho_a_m), (b(i), -g.rho_b_m)],
                ),
                MeshKind::RB | MeshKind::Pair => (
                    format!("rb{}", i + 1),
                    vec![(c, g.rho_r_m), (r, -g.rho_r_m), (b(i), g.rho_b_m)],
                ),
            };
            let te = p.te_um[RavigneauxParams::kind_index(kind)];
            let series = &series[RavigneauxParams::kind_index(kind)];
            meshes.push(Mesh {
                name,
                kind,
                planet: i,
                w,
                stiffness_mean_n_m: p.stiffness_n_m.get(kind),
                stiffness_variation: series[0],
                stiffness_harmonics: series[1..].to_vec(),
                phase_rad: phase(kind, i),
                backlash_m: p.backlash_um.get(kind) * 1e-6,
                te_mean_m: te.mean * 1e-6,
                te_cos_m: te.cos * 1e-6,
                te_sin_m: te.sin * 1e-6,
                te_harmonics_m: te.higher_m(),
                equivalent_mass_kg: 0.0,
                damping_n_s_m: 0.0,
            });
        }
    }
    equivalent_masses(&mass, &mut meshes, p.damping_ratio)?;

    // Rigid-body mode from tooth counts: ring held, carrier turning once.
    let zr = f64::from(p.teeth_r);
    let mut u = vec![0.0; n];
    u[s1] = 1.0 - zr / f64::from(p.teeth_s1);
    u[s2] = 1.0 + zr / f64::from(p.teeth_s2);
    u[c] = 1.0;
    for i in 0..n_pl {
        u[a(i)] = zr / f64::from(p.teeth_a);
        u[b(i)] = -zr / f64::from(g.teeth_b);
    }
    let balancing = -p.torque_s1_nm * u[s1] / u[s2];
    let torque_s2 = p.torque_s2_nm.unwrap_or(balancing);
    let imbalance = p.torque_s1_nm * u[s1] + torque_s2 * u[s2];
    let scale = (p.torque_s1_nm * u[s1]).abs() + (torque_s2 * u[s2]).abs();
    if imbalance.abs() > TORQUE_BALANCE_RTOL * scale.max(1e-9) {
        return Err(SolverError::UnbalancedTorque {
            torque_s1_nm: p.torque_s1_nm,
            torque_s2_nm: torque_s2,
            balancing_s2_nm: balancing,
        });
    }
    let mut load = vec![0.0; n];
    load[s1] = p.torque_s1_nm;
    load[s2] = torque_s2;
    project_load(&mut load, &u, &mass);

    let mut support = DMatrix::zeros(n, n);
    // The ring's support spring acts on its base circle unless a radius is given.
    let support_radius_m = p.ring_support_radius_mm.map_or(g.rho_r_m, |r| r * 1e-3);
    support[(r, r)] = p.ring_support_n_m * support_radius_m.powi(2);

    let mut warnings = g.interference(p);
    if p.phasing == Phasing::Sequential && !(p.teeth_r + p.teeth_s2).is_multiple_of(p.planets) {
        warnings.push(format!(
            "(teeth_r + teeth_s2) = {} is not a multiple of planets = {}: equally spaced long planets \
             cannot be assembled; the sequential phases are still those of equal spacing",
            p.teeth_r + p.teeth_s2,
            p.planets
        ));
    }

    let omega_ref = (meshes[0].stiffness_mean_n_m / meshes[0].equivalent_mass_kg).sqrt();
    Ok(MeshSystem {
        model: ModelKind::Ravigneaux,
        dof_names: names,
        mass_inv: SparseRows::from_dense(&inverse(&mass)?),
        mass,
        support: SparseRows::from_dense(&support),
        load_nm: load,
        meshes,
        rigid_mode: u,
        omega_ref_rad_s: omega_ref,
        balancing_torque_nm: balancing,
        speed: SpeedInfo {
            input_teeth: p.teeth_s1,
            // n_s1 - n_c = (1 - z_r/z_s1 - 1) n_c and n_s1 = (1 - z_r/z_s1) n_c.
            relative_per_input: (-zr / f64::from(p.teeth_s1)) / (1.0 - zr / f64::from(p.teeth_s1)),
        },
        warnings,
    })
}

fn build_gear_pair(p: &GearPairParams) -> Result<MeshSystem> {
    let m = p.module_mm * 1e-3;
    let cos_a = p.pressure_angle_deg.to_radians().cos();
    let rho_p = m * f64::from(p.teeth_pinion) / 2.0 * cos_a;
    let rho_g = m * f64::from(p.teeth_gear) / 2.0 * cos_a;
    let mass = DMatrix::from_diagonal(&DVector::from_vec(vec![
        p.inertia_pinion_kg_m2,
        p.inertia_gear_kg_m2,
    ]));
    let series = waveform::stiffness_series(
        "gear pair",
        p.stiffness_shape.wave,
        p.stiffness_variation,
        p.stiffness_shape.contact_ratio.unwrap_or_else(|| {
            let (z1, z2) = (p.teeth_pinion, p.teeth_gear);
            waveform::contact_ratio(z1, z2, false, p.module_mm, p.pressure_angle_deg)
        }),
        p.stiffness_ramp,
        p.stiffness_harmonics as usize,
    )?;
    let mut meshes = vec![Mesh {
        name: "pg".into(),
        kind: MeshKind::Pair,
        planet: 0,
        w: vec![(0, rho_p), (1, rho_g)],
        stiffness_mean_n_m: p.stiffness_n_m,
        stiffness_variation: series[0],
        stiffness_harmonics: series[1..].to_vec(),
        phase_rad: 0.0,
        backlash_m: p.backlash_um * 1e-6,
        te_mean_m: p.te_um.mean * 1e-6,
        te_cos_m: p.te_um.cos * 1e-6,
        te_sin_m: p.te_um.sin * 1e-6,
        te_harmonics_m: p.te_um.higher_m(),
        equivalent_mass_kg: 0.0,
        damping_n_s_m: 0.0,
    }];
    equivalent_masses(&mass, &mut meshes, p.damping_ratio)?;
    let u = vec![1.0, -f64::from(p.teeth_pinion) / f64::from(p.teeth_gear)];
    // The gear's torque balances the pinion's over the rigid mode.
    let balancing = -p.torque_pinion_nm * u[0] / u[1];
    let load = vec![p.torque_pinion_nm, balancing];
    let omega_ref = (meshes[0].stiffness_mean_n_m / meshes[0].equivalent_mass_kg).sqrt();
    Ok(MeshSystem {
        model: ModelKind::GearPair,
        dof_names: vec!["theta_pinion".into(), "theta_gear".into()],
        mass_inv: SparseRows::from_dense(&inverse(&mass)?),
        mass,
        support: SparseRows::from_dense(&DMatrix::zeros(2, 2)),
        load_nm: load,
        meshes,
        rigid_mode: u,
        omega_ref_rad_s: omega_ref,
        balancing_torque_nm: balancing,
        speed: SpeedInfo {
            input_teeth: p.teeth_pinion,
            relative_per_input: 1.0,
        },
        warnings: Vec::new(),
    })
}
