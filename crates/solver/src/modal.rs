//! Statics, natural modes and the linear receptance of a [`MeshSystem`].
//!
//! The modes are those of the mean-stiffness system, from the generalized
//! symmetric eigenproblem `K phi = lambda M phi`, solved by nalgebra as
//! `L^-1 K L^-T y = lambda y` with `M = L L^T`. The rigid-body mode (zero
//! frequency) is recognised by comparing with the kinematic mode of the
//! system; each elastic mode of the compound set is labelled *rotational*
//! (every planet pair moves alike, Lin & Parker 1999) or *planet* (the
//! central members stand still).
//!
//! The static solution is the loaded equilibrium with mean stiffness, mean
//! TE and backlash, found by an active-set iteration on the contact side of
//! each mesh, in the elastic subspace (the rigid mode pinned to zero).

use crate::error::{Result, SolverError};
use crate::system::{dead_zone, Contact, MeshSystem};
use nalgebra::{Complex, DMatrix, DVector};
use std::f64::consts::PI;

/// How a mode moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModeKind {
    /// The gear train turning as a mechanism (zero frequency).
    RigidBody,
    /// All planet pairs move alike; the central members rotate.
    Rotational,
    /// Only the planets move; the central members stand still.
    Planet,
}

impl ModeKind {
    /// Lower-case name for output.
    pub fn name(self) -> &'static str {
        match self {
            ModeKind::RigidBody => "rigid-body",
            ModeKind::Rotational => "rotational",
            ModeKind::Planet => "planet",
        }
    }
}

/// One natural mode.
#[derive(Debug, Clone, PartialEq)]
pub struct Mode {
    /// Natural frequency (Hz); exactly 0 for the rigid-body mode.
    pub frequency_hz: f64,
    /// Dimensionless natural frequency omega_n / omega_ref.
    pub omega: f64,
    /// Rigid-body, rotational or planet mode.
    pub kind: ModeKind,
    /// How many modes share this frequency (relative gap below 1e-6).
    pub multiplicity: usize,
    /// Modal damping ratio `phi^T C phi / (2 omega_n)` of the mesh dampers
    /// (the diagonal of the non-proportional damping in modal coordinates);
    /// 0 for the rigid-body mode.
    pub damping_ratio: f64,
    /// Mode shape in the generalized coordinates, mass-normalized (phi^T M phi = 1).
    pub shape: Vec<f64>,
}

/// All modes, ascending in frequency.
#[derive(Debug, Clone, PartialEq)]
pub struct Modes {
    /// The modes.
    pub modes: Vec<Mode>,
}

impl Modes {
    /// Natural frequencies (Hz), ascending, the rigid mode as 0.
    pub fn frequencies_hz(&self) -> Vec<f64> {
        self.modes.iter().map(|m| m.frequency_hz).collect()
    }

    /// The elastic modes only.
    pub fn elastic(&self) -> impl Iterator<Item = &Mode> {
        self.modes.iter().filter(|m| m.kind != ModeKind::RigidBody)
    }

    /// The slowest modal decay rate `min_k zeta_k omega_k` (1/s) of the
    /// elastic modes: how fast the most lightly damped transient dies.
    pub fn slowest_decay_rate(&self, omega_ref_rad_s: f64) -> f64 {
        self.elastic()
            .map(|m| m.damping_ratio * m.omega * omega_ref_rad_s)
            .fold(f64::INFINITY, f64::min)
    }
}

/// Computes the natural modes of the mean-stiffness system.
pub fn modes(sys: &MeshSystem) -> Result<Modes> {
    let n = sys.dof();
    let k = sys.mean_stiffness();
    let chol = sys
        .mass
        .clone()
        .cholesky()
        .ok_or_else(|| SolverError::Singular {
            what: "mass matrix".into(),
        })?;
    let l = chol.l();
    let l_inv = l
        .clone()
        .try_inverse()
        .ok_or_else(|| SolverError::Singular {
            what: "Cholesky factor of the mass matrix".into(),
        })?;
    let a = &l_inv * &k * l_inv.transpose();
    let a = (&a + a.transpose()) * 0.5;
    let eig = a.symmetric_eigen();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j]));
    let lambda_max = eig.eigenvalues.amax().max(f64::MIN_POSITIVE);
    let u = DVector::from_column_slice(&sys.rigid_mode);
    let mu = &sys.mass * &u;
    let unorm = u.dot(&mu).sqrt();
    let damping = sys.damping_matrix();

    let mut out: Vec<Mode> = Vec::with_capacity(n);
    for &i in &order {
        let y = eig.eigenvectors.column(i);
        let phi = l_inv.transpose() * y;
        let lambda = eig.eigenvalues[i];
        // The rigid mode: numerically zero eigenvalue, parallel (in the mass
        // metric) to the kinematic mode.
        let overlap = (phi.dot(&mu) / unorm).abs();
        let is_rigid = lambda.abs() <= 1e-9 * lambda_max && overlap > 1.0 - 1e-6;
        let omega_rad_s = if is_rigid {
            0.0
        } else {
            lambda.max(0.0).sqrt()
        };
        let kind = if is_rigid {
            ModeKind::RigidBody
        } else {
            classify(sys, phi.as_slice())
        };
        let damping_ratio = if omega_rad_s > 0.0 {
            phi.dot(&(&damping * &phi)) / (2.0 * omega_rad_s)
        } else {
            0.0
        };
        out.push(Mode {
            frequency_hz: omega_rad_s / (2.0 * PI),
            omega: omega_rad_s / sys.omega_ref_rad_s,
            kind,
            multiplicity: 1,
            damping_ratio,
            shape: phi.iter().copied().collect(),
        });
    }
    if out.iter().filter(|m| m.kind == ModeKind::RigidBody).count() != 1 {
        return Err(SolverError::Singular {
            what: "stiffness matrix: expected exactly one rigid-body mode (is a support stiffness zero?)"
                .into(),
        });
    }
    // Multiplicities: runs of frequencies within a relative gap of 1e-6.
    let f: Vec<f64> = out.iter().map(|m| m.frequency_hz).collect();
    for i in 0..n {
        out[i].multiplicity = (0..n)
            .filter(|&j| (f[j] - f[i]).abs() <= 1e-6 * f[i].max(f[j]).max(1e-300))
            .count();
    }
    Ok(Modes { modes: out })
}

/// Rotational or planet mode, from the kinetic energy of the central members.
fn classify(sys: &MeshSystem, phi: &[f64]) -> ModeKind {
    if sys.model == crate::params::ModelKind::GearPair {
        return ModeKind::Rotational;
    }
    let v = DVector::from_column_slice(phi);
    let total = v.dot(&(&sys.mass * &v));
    let central: f64 = (0..4).map(|i| sys.mass[(i, i)] * phi[i] * phi[i]).sum();
    if central <= 1e-8 * total {
        ModeKind::Planet
    } else {
        ModeKind::Rotational
    }
}

/// The loaded static equilibrium.
#[derive(Debug, Clone, PartialEq)]
pub struct StaticSolution {
    /// Generalized coordinates (rad), rigid-mode component zero.
    pub q: Vec<f64>,
    /// Mesh deflection delta_j (m).
    pub mesh_deflection_m: Vec<f64>,
    /// Static mesh force F_j (N).
    pub mesh_force_n: Vec<f64>,
    /// Contact state of each mesh.
    pub contact: Vec<Contact>,
}

/// Solves `K q = tau + sum_j w_j k_j (e_j + s_j b_j)` for the contact sides `s_j`
/// by an active-set iteration, in the elastic subspace.
pub fn statics(sys: &MeshSystem, modes: &Modes) -> Result<StaticSolution> {
    let n = sys.dof();
    let tau = DVector::from_column_slice(&sys.load_nm);
    let mut side = vec![1.0_f64; sys.meshes.len()];
    for _ in 0..=2 * sys.meshes.len() {
        let mut f = tau.clone();
        for (j, mesh) in sys.meshes.iter().enumerate() {
            let offset = mesh.stiffness_mean_n_m * (mesh.te_mean_m + side[j] * mesh.backlash_m);
            for &(i, wi) in &mesh.w {
                f[i] += wi * offset;
            }
        }
        let mut q = DVector::zeros(n);
        for mode in modes.elastic() {
            let phi = DVector::from_column_slice(&mode.shape);
            let lambda = (mode.frequency_hz * 2.0 * PI).powi(2);
            q += &phi * (phi.dot(&f) / lambda);
        }
        let q: Vec<f64> = q.iter().copied().collect();
        let mut changed = false;
        let mut force = Vec::with_capacity(sys.meshes.len());
        let mut defl = Vec::with_capacity(sys.meshes.len());
        for (j, mesh) in sys.meshes.iter().enumerate() {
            let d = mesh.dot(&q);
            let x = d - mesh.te_mean_m;
            let fj = mesh.stiffness_mean_n_m * dead_zone(x, mesh.backlash_m);
            // A mesh assumed on one flank whose deflection says the other
            // flank flips side; one inside the dead zone carries no load.
            let want = if x > mesh.backlash_m {
                1.0
            } else if x < -mesh.backlash_m {
                -1.0
            } else {
                side[j]
            };
            if want != side[j] {
                side[j] = want;
                changed = true;
            }
            force.push(fj);
            defl.push(d);
        }
        if !changed {
            let contact = sys
                .meshes
                .iter()
                .zip(&defl)
                .map(|(m, &d)| Contact::of(d - m.te_mean_m, m.backlash_m * (1.0 - 1e-12)))
                .collect();
            return Ok(StaticSolution {
                q,
                mesh_deflection_m: defl,
                mesh_force_n: force,
                contact,
            });
        }
    }
    Err(SolverError::Singular {
        what: "static equilibrium: the contact sides of the meshes did not settle".into(),
    })
}

/// The steady response of the linear system (b = 0 on every mesh, v = 0) to
/// its transmission errors, in the generalized coordinates:
/// `q(t) = q_static + Re(q_hat e^{i omega t})` with
/// `q_hat = (K - omega^2 M + i omega C)^-1 sum_l w_l (k_l + i omega c_l) E_l`.
/// Backlash and stiffness fluctuation are ignored: the caller checks they are zero.
pub fn linear_response(sys: &MeshSystem, omega_rad_s: f64) -> Result<Vec<Complex<f64>>> {
    linear_response_harmonic(sys, omega_rad_s, 1)
}

/// The same at harmonic `n` of the mesh frequency: the response at
/// `n omega` to the TE's harmonic `n` (`q_static` aside,
/// `Re(q_hat e^{i n omega t})`), zero where no mesh's TE has that harmonic.
pub fn linear_response_harmonic(
    sys: &MeshSystem,
    omega_rad_s: f64,
    harmonic: usize,
) -> Result<Vec<Complex<f64>>> {
    let omega_rad_s = omega_rad_s * harmonic as f64;
    let n = sys.dof();
    let k = sys.mean_stiffness();
    let c = sys.damping_matrix();
    let mut dyn_stiffness = DMatrix::<Complex<f64>>::zeros(n, n);
    for i in 0..n {
        for j in 0..n {
            dyn_stiffness[(i, j)] = Complex::new(
                k[(i, j)] - omega_rad_s * omega_rad_s * sys.mass[(i, j)],
                omega_rad_s * c[(i, j)],
            );
        }
    }
    let mut rhs = DVector::<Complex<f64>>::zeros(n);
    for mesh in &sys.meshes {
        // e(t) = Ec cos(n (wt + g)) + Es sin(n (wt + g)) = Re((Ec - i Es) e^{i n g} e^{i n w t}).
        let [te_cos_m, te_sin_m] = match harmonic {
            1 => [mesh.te_cos_m, mesh.te_sin_m],
            n => mesh
                .te_harmonics_m
                .get(n.wrapping_sub(2))
                .copied()
                .unwrap_or([0.0; 2]),
        };
        let e_hat = Complex::new(te_cos_m, -te_sin_m)
            * Complex::from_polar(1.0, harmonic as f64 * mesh.phase_rad);
        let gain = Complex::new(mesh.stiffness_mean_n_m, omega_rad_s * mesh.damping_n_s_m) * e_hat;
        for &(i, wi) in &mesh.w {
            rhs[i] += gain * wi;
        }
    }
    let sol = dyn_stiffness
        .lu()
        .solve(&rhs)
        .ok_or_else(|| SolverError::Singular {
            what: format!("dynamic stiffness at omega = {omega_rad_s} rad/s"),
        })?;
    Ok(sol.iter().copied().collect())
}

/// The complex amplitude of each mesh deflection in the linear steady
/// response ([`linear_response`]): `delta_j(t) = mean_j + Re(amp_j e^{i omega t})`.
pub fn linear_receptance(sys: &MeshSystem, omega_rad_s: f64) -> Result<Vec<Complex<f64>>> {
    let q = linear_response(sys, omega_rad_s)?;
    Ok(sys
        .meshes
        .iter()
        .map(|m| m.w.iter().map(|&(i, wi)| q[i] * wi).sum())
        .collect())
}
