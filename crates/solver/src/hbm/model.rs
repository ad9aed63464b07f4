//! The harmonic-balance problem: a linear system in scaled modal coordinates
//! plus nonlinear "channels" (one per mesh, or per mesh kind under the
//! cyclic symmetry of in-phase planets).
//!
//! Scaling. Coordinates are the M-orthonormal elastic modes of the
//! mean-stiffness system (the rigid-body mode is dropped, so the Jacobian is
//! regular), in units such that a channel displacement `u_j = d_j . x` reads
//! in micrometres; time is `tau = omega_ref t` and the excitation phase is
//! `theta = Omega tau`. The equations become
//!
//! ```text
//! x'' + C x' + K x + sum_j n_j d_j k_j(theta) g_j(u_j - e_j(theta)) = f0 + f_e(theta)
//! ```
//!
//! with `K` the support stiffness, `C` the mesh dampers (linear, so they stay
//! out of the alternating frequency-time step), `n_j` the channel's
//! multiplicity, `k_j = k_mj (1 + v cos(theta + gamma_j)) / omega_ref^2`, and
//! `f_e` the dampers' share of the transmission-error excitation
//! `sum_j n_j c_j d_j e_j'(theta)`.
//!
//! Cyclic symmetry. With in-phase planets and identical planet pairs the
//! response in which every planet moves alike is an exact solution; on it the
//! model reduces to the six symmetric coordinates (s1, s2, c, r, a, b; five
//! elastic) and four mesh kinds of multiplicity N. Its stability still needs
//! the asymmetric perturbations: the linearization splits into the symmetric
//! block and N - 1 identical planet blocks (central members at rest, one
//! short and one long planet), kept here as [`PlanetBlock`].

use crate::error::{Result, SolverError};
use crate::params::{MeshKind, ModelKind};
use crate::system::MeshSystem;
use nalgebra::{DMatrix, DVector};

/// The force law of a channel, in the scaled units (micrometres, `tau`).
#[derive(Debug, Clone, PartialEq)]
pub enum Law {
    /// A backlash mesh: `k(theta) g(u - e(theta))`.
    Mesh {
        /// Mean stiffness over `omega_ref^2`.
        k: f64,
        /// Stiffness fluctuation v.
        variation: f64,
        /// Mesh phase gamma (rad).
        phase_rad: f64,
        /// Backlash half-width (um).
        backlash_um: f64,
        /// TE mean (um).
        te_mean_um: f64,
        /// TE cosine amplitude (um).
        te_cos_um: f64,
        /// TE sine amplitude (um).
        te_sin_um: f64,
        /// Harmonics 2, 3, ... of the excitation in `n (theta + phase)`:
        /// `[stiffness cosine relative to k, TE cosine (um), TE sine (um)]`;
        /// empty for the seed's one-harmonic excitation.
        higher: Vec<[f64; 3]>,
    },
    /// A cubic spring `alpha u^3` (the Duffing test model).
    Cubic {
        /// Cubic coefficient.
        alpha: f64,
    },
}

impl Law {
    /// Force and its slope `dF/du` at phase `theta` for displacement `u`.
    #[inline]
    pub fn force(&self, theta: f64, u: f64) -> (f64, f64) {
        match *self {
            Law::Mesh {
                k,
                variation,
                phase_rad,
                backlash_um,
                te_mean_um,
                te_cos_um,
                te_sin_um,
                ref higher,
            } => {
                let (s, c) = crate::trig::phase_sin_cos(theta + phase_rad);
                let (kt, x) = if higher.is_empty() {
                    let kt = k * (1.0 + variation * c);
                    (kt, u - (te_mean_um + te_cos_um * c + te_sin_um * s))
                } else {
                    let mut kt = k * (1.0 + variation * c);
                    let mut x = u - (te_mean_um + te_cos_um * c + te_sin_um * s);
                    let (mut cn, mut sn) = (c, s);
                    for &[a, tc, ts] in higher {
                        (cn, sn) = (cn * c - sn * s, sn * c + cn * s);
                        kt += k * a * cn;
                        x -= tc * cn + ts * sn;
                    }
                    (kt, x)
                };
                if x > backlash_um {
                    (kt * (x - backlash_um), kt)
                } else if x < -backlash_um {
                    (kt * (x + backlash_um), kt)
                } else {
                    (0.0, 0.0)
                }
            }
            Law::Cubic { alpha } => (alpha * u * u * u, 3.0 * alpha * u * u),
        }
    }

    /// A mesh law's TE terms: its phase (rad) and `[mean, cos, sin]` (um) of
    /// `e = mean + cos cos(theta + phase) + sin sin(theta + phase)`; `None`
    /// for non-mesh laws.
    pub fn te_terms(&self) -> Option<(f64, [f64; 3])> {
        match *self {
            Law::Mesh {
                phase_rad,
                te_mean_um,
                te_cos_um,
                te_sin_um,
                ..
            } => Some((phase_rad, [te_mean_um, te_cos_um, te_sin_um])),
            Law::Cubic { .. } => None,
        }
    }

    /// The transmission error `e(theta)` (um); zero for non-mesh laws.
    pub fn te(&self, theta: f64) -> f64 {
        self.te_terms().map_or(0.0, |(phase, [mean, cos, sin])| {
            let (s, c) = crate::trig::phase_sin_cos(theta + phase);
            let mut e = mean + cos * c + sin * s;
            let (mut cn, mut sn) = (c, s);
            for &[_, tc, ts] in self.higher() {
                (cn, sn) = (cn * c - sn * s, sn * c + cn * s);
                e += tc * cn + ts * sn;
            }
            e
        })
    }

    /// The stiffness `k(theta)` (scaled); zero for non-mesh laws.
    #[inline]
    pub fn stiffness(&self, theta: f64) -> f64 {
        match *self {
            Law::Mesh {
                k,
                variation,
                phase_rad,
                ref higher,
                ..
            } => {
                let kt = k * (1.0 + variation * (theta + phase_rad).cos());
                if higher.is_empty() {
                    return kt;
                }
                higher.iter().enumerate().fold(kt, |kt, (i, &[a, _, _])| {
                    kt + k * a * ((i + 2) as f64 * (theta + phase_rad)).cos()
                })
            }
            Law::Cubic { .. } => 0.0,
        }
    }

    /// A mesh law's harmonics 2, 3, ... (`[stiffness, TE cos, TE sin]`).
    #[inline]
    pub fn higher(&self) -> &[[f64; 3]] {
        match self {
            Law::Mesh { higher, .. } => higher,
            Law::Cubic { .. } => &[],
        }
    }

    /// The TE's real coefficients in `theta` (mean, cos 1, sin 1, cos 2,
    /// ...) of harmonics 2, 3, ...: `[cos n, sin n]` for each.
    pub fn te_higher_theta(&self) -> impl Iterator<Item = [f64; 2]> + '_ {
        let phase = match *self {
            Law::Mesh { phase_rad, .. } => phase_rad,
            Law::Cubic { .. } => 0.0,
        };
        self.higher()
            .iter()
            .enumerate()
            .map(move |(i, &[_, c, s])| {
                let (sp, cp) = ((i + 2) as f64 * phase).sin_cos();
                [c * cp + s * sp, s * cp - c * sp]
            })
    }

    /// Whether `other` has the same stiffness and TE (so the same tables
    /// on a grid), bit for bit: equal but for the backlash.
    pub fn same_tables(&self, other: &Law) -> bool {
        let tables = |l: &Law| match *l {
            Law::Mesh {
                k,
                variation,
                phase_rad,
                te_mean_um,
                te_cos_um,
                te_sin_um,
                ref higher,
                ..
            } => Some((
                [k, variation, phase_rad, te_mean_um, te_cos_um, te_sin_um].map(f64::to_bits),
                higher
                    .iter()
                    .map(|h| h.map(f64::to_bits))
                    .collect::<Vec<_>>(),
            )),
            // A cubic law has no tables.
            Law::Cubic { .. } => None,
        };
        tables(self) == tables(other)
    }

    /// Backlash half-width (um); zero for non-mesh laws.
    pub fn backlash_um(&self) -> f64 {
        match *self {
            Law::Mesh { backlash_um, .. } => backlash_um,
            Law::Cubic { .. } => 0.0,
        }
    }
}

/// One nonlinear channel.
#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    /// Channel displacement `u = d . x` (um).
    pub d: Vec<f64>,
    /// How many identical meshes it stands for (N under symmetry, else 1).
    pub multiplicity: f64,
    /// Force law.
    pub law: Law,
    /// Damping coefficient over `omega_ref` (for the TE-rate excitation).
    pub damping: f64,
    /// The physical meshes it represents (indices into the system's meshes).
    pub meshes: Vec<usize>,
}

/// The asymmetric (planet) block of the linearization about a symmetric
/// orbit, in M-orthonormal coordinates of one short and one long planet.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanetBlock {
    /// Per channel (mesh kind, in channel order): its vector in the block.
    pub p: Vec<[f64; 2]>,
    /// Constant damping matrix of the block (over omega_ref).
    pub damping: [[f64; 2]; 2],
}

/// Which reduction a model uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Reduction {
    /// All elastic coordinates and every mesh.
    Full,
    /// The symmetric subspace of in-phase identical planets.
    Symmetric,
}

/// A harmonic-balance problem.
#[derive(Debug, Clone, PartialEq)]
pub struct HbmModel {
    /// Number of coordinates.
    pub m: usize,
    /// Constant stiffness K (scaled).
    pub stiffness: DMatrix<f64>,
    /// Constant damping C (scaled).
    pub damping: DMatrix<f64>,
    /// Constant load f0 (scaled).
    pub load: Vec<f64>,
    /// External first-harmonic forcing `f_c cos theta + f_s sin theta` (scaled),
    /// independent of Omega (used by test models).
    pub force_cos: Vec<f64>,
    /// See `force_cos`.
    pub force_sin: Vec<f64>,
    /// Nonlinear channels.
    pub channels: Vec<Channel>,
    /// Highest natural frequency of the linearized system over omega_ref
    /// (sets the step count of the monodromy integration).
    pub omega_max: f64,
    /// Reduction used.
    pub reduction: Reduction,
    /// The asymmetric block, for stability under the symmetric reduction.
    pub planet_block: Option<PlanetBlock>,
    /// Number of physical meshes of the system it came from.
    pub n_meshes: usize,
    /// Backlash (um) of each physical mesh.
    pub mesh_backlash_um: Vec<f64>,
    /// The n x m map to generalized coordinates: `q = transform x 1e-6`
    /// (`None` for models without a gear system).
    pub transform: Option<DMatrix<f64>>,
}

impl HbmModel {
    /// The Duffing oscillator `x'' + 2 zeta x' + x + alpha x^3 = force cos(theta)`.
    pub fn duffing(zeta: f64, alpha: f64, force: f64) -> Self {
        HbmModel {
            m: 1,
            stiffness: DMatrix::from_element(1, 1, 1.0),
            damping: DMatrix::from_element(1, 1, 2.0 * zeta),
            load: vec![0.0],
            force_cos: vec![force],
            force_sin: vec![0.0],
            channels: vec![Channel {
                d: vec![1.0],
                multiplicity: 1.0,
                law: Law::Cubic { alpha },
                damping: 0.0,
                meshes: vec![0],
            }],
            omega_max: (1.0 + 3.0 * alpha.abs()).sqrt(),
            reduction: Reduction::Full,
            planet_block: None,
            n_meshes: 1,
            mesh_backlash_um: vec![0.0],
            transform: None,
        }
    }

    /// Builds the problem for a gear model. With `symmetric` and a model
    /// whose planets are in phase and identical, the symmetric reduction is
    /// used; otherwise the full model.
    pub fn from_system(sys: &MeshSystem, symmetric: bool) -> Result<Self> {
        let n = sys.dof();
        let use_symmetric =
            symmetric && sys.model == ModelKind::Ravigneaux && planets_identical(sys);
        // Basis B of the subspace, n x r.
        let (basis, groups): (DMatrix<f64>, Vec<Vec<usize>>) = if use_symmetric {
            let n_pl = (n - 4) / 2;
            let mut b = DMatrix::zeros(n, 6);
            for i in 0..4 {
                b[(i, i)] = 1.0;
            }
            for p in 0..n_pl {
                b[(4 + p, 4)] = 1.0;
                b[(4 + n_pl + p, 5)] = 1.0;
            }
            let groups = MeshKind::COMPOUND
                .iter()
                .map(|&k| {
                    sys.meshes
                        .iter()
                        .enumerate()
                        .filter(|(_, m)| m.kind == k)
                        .map(|(j, _)| j)
                        .collect()
                })
                .collect();
            (b, groups)
        } else {
            (
                DMatrix::identity(n, n),
                (0..sys.meshes.len()).map(|j| vec![j]).collect(),
            )
        };
        let mass_r = basis.transpose() * &sys.mass * &basis;
        let k_mean_r = basis.transpose() * sys.mean_stiffness() * &basis;
        let (phi, omegas) = elastic_modes(&mass_r, &k_mean_r)?;
        // q = T eta with T = B Phi (n x m); eta = 1e-6 x.
        let t = &basis * &phi;
        let m = t.ncols();
        let wr = sys.omega_ref_rad_s;
        let w_of = |j: usize| sys.mesh_vector(j);
        let mut damping = DMatrix::zeros(m, m);
        for (j, mesh) in sys.meshes.iter().enumerate() {
            let d = t.transpose() * w_of(j);
            damping += (&d * d.transpose()) * (mesh.damping_n_s_m / wr);
        }
        let support = {
            let mut k = DMatrix::zeros(n, n);
            for i in 0..n {
                for idx in sys.support.row_start[i]..sys.support.row_start[i + 1] {
                    k[(i, sys.support.cols[idx])] += sys.support.vals[idx];
                }
            }
            k
        };
        let stiffness = t.transpose() * support * &t / (wr * wr);
        let load = (t.transpose() * DVector::from_column_slice(&sys.load_nm)) * (1e6 / (wr * wr));
        let channels: Vec<Channel> = groups
            .iter()
            .map(|g| {
                let j = g[0];
                let mesh = &sys.meshes[j];
                let d = t.transpose() * w_of(j);
                Channel {
                    d: d.iter().copied().collect(),
                    multiplicity: g.len() as f64,
                    law: Law::Mesh {
                        k: mesh.stiffness_mean_n_m / (wr * wr),
                        variation: mesh.stiffness_variation,
                        phase_rad: mesh.phase_rad,
                        backlash_um: mesh.backlash_m * 1e6,
                        te_mean_um: mesh.te_mean_m * 1e6,
                        te_cos_um: mesh.te_cos_m * 1e6,
                        te_sin_um: mesh.te_sin_m * 1e6,
                        higher: (2..=mesh.excitation_harmonics())
                            .map(|n| {
                                let a = mesh.stiffness_harmonics.get(n - 2).copied().unwrap_or(0.0);
                                let [c, s] =
                                    mesh.te_harmonics_m.get(n - 2).copied().unwrap_or([0.0; 2]);
                                [a, c * 1e6, s * 1e6]
                            })
                            .collect(),
                    },
                    damping: mesh.damping_n_s_m / wr,
                    meshes: g.clone(),
                }
            })
            .collect();
        let mut omega_max = omegas.iter().copied().fold(0.0, f64::max) / wr;
        let planet_block = if use_symmetric {
            let (pb, w_planet) = planet_block(sys, &channels)?;
            omega_max = omega_max.max(w_planet);
            Some(pb)
        } else {
            None
        };
        Ok(HbmModel {
            m,
            stiffness,
            damping,
            load: load.iter().copied().collect(),
            force_cos: vec![0.0; m],
            force_sin: vec![0.0; m],
            channels,
            omega_max,
            reduction: if use_symmetric {
                Reduction::Symmetric
            } else {
                Reduction::Full
            },
            planet_block,
            n_meshes: sys.meshes.len(),
            mesh_backlash_um: sys.meshes.iter().map(|m| m.backlash_m * 1e6).collect(),
            transform: Some(t),
        })
    }

    /// The highest harmonic of any channel's excitation (stiffness or TE), at least 1.
    pub fn excitation_harmonics(&self) -> usize {
        1 + self
            .channels
            .iter()
            .map(|c| c.law.higher().len())
            .max()
            .unwrap_or(0)
    }

    /// The TE-rate excitation's harmonic `n >= 2` per unit Omega, as
    /// [`HbmModel::te_rate_forcing`] for the first.
    pub fn te_rate_forcing_harmonic(&self, n: usize) -> (Vec<f64>, Vec<f64>) {
        let mut fc = vec![0.0; self.m];
        let mut fs = vec![0.0; self.m];
        for ch in &self.channels {
            let Some([c, s]) = ch.law.higher().get(n.wrapping_sub(2)).map(|h| [h[1], h[2]]) else {
                continue;
            };
            let Law::Mesh { phase_rad, .. } = ch.law else {
                continue;
            };
            // d/dtheta of c cos(n (theta + g)) + s sin(n (theta + g)), as in the first harmonic.
            let nf = n as f64;
            let (sg, cg) = (nf * phase_rad).sin_cos();
            let a = nf * (s * cg - c * sg);
            let b = -nf * (c * cg + s * sg);
            let scale = ch.multiplicity * ch.damping;
            for i in 0..self.m {
                fc[i] += scale * ch.d[i] * a;
                fs[i] += scale * ch.d[i] * b;
            }
        }
        (fc, fs)
    }

    /// The TE-rate excitation's first harmonic per unit Omega: `f_e = Omega (a cos + b sin)`.
    pub fn te_rate_forcing(&self) -> (Vec<f64>, Vec<f64>) {
        let mut fc = self.force_cos.iter().map(|_| 0.0).collect::<Vec<f64>>();
        let mut fs = fc.clone();
        for ch in &self.channels {
            if let Law::Mesh {
                phase_rad,
                te_cos_um,
                te_sin_um,
                ..
            } = ch.law
            {
                // de/dtheta = cos(theta) (Es cos g - Ec sin g) - sin(theta) (Ec cos g + Es sin g).
                let (sg, cg) = phase_rad.sin_cos();
                let a = te_sin_um * cg - te_cos_um * sg;
                let b = -(te_cos_um * cg + te_sin_um * sg);
                let scale = ch.multiplicity * ch.damping;
                for i in 0..self.m {
                    fc[i] += scale * ch.d[i] * a;
                    fs[i] += scale * ch.d[i] * b;
                }
            }
        }
        (fc, fs)
    }
}

/// Whether every planet pair has the same mesh parameters (in-phase, equal).
fn planets_identical(sys: &MeshSystem) -> bool {
    sys.meshes.iter().all(|m| {
        sys.meshes.iter().filter(|o| o.kind == m.kind).all(|o| {
            o.stiffness_mean_n_m == m.stiffness_mean_n_m
                && o.stiffness_variation == m.stiffness_variation
                && (o.phase_rad - m.phase_rad).abs() < 1e-12
                && o.backlash_m == m.backlash_m
                && o.te_mean_m == m.te_mean_m
                && o.te_cos_m == m.te_cos_m
                && o.te_sin_m == m.te_sin_m
                && o.stiffness_harmonics == m.stiffness_harmonics
                && o.te_harmonics_m == m.te_harmonics_m
        })
    })
}

/// Elastic modes of `(M, K)`: M-orthonormal shapes (r x m) without the
/// zero-frequency mode(s), and their circular frequencies.
fn elastic_modes(
    mass: &DMatrix<f64>,
    stiffness: &DMatrix<f64>,
) -> Result<(DMatrix<f64>, Vec<f64>)> {
    let r = mass.nrows();
    let chol = mass
        .clone()
        .cholesky()
        .ok_or_else(|| SolverError::Singular {
            what: "reduced mass matrix".into(),
        })?;
    let l_inv = chol
        .l()
        .try_inverse()
        .ok_or_else(|| SolverError::Singular {
            what: "Cholesky factor of the reduced mass matrix".into(),
        })?;
    let a = &l_inv * stiffness * l_inv.transpose();
    let a = (&a + a.transpose()) * 0.5;
    let eig = a.symmetric_eigen();
    let lmax = eig.eigenvalues.amax();
    let keep: Vec<usize> = (0..r)
        .filter(|&i| eig.eigenvalues[i] > 1e-9 * lmax)
        .collect();
    let mut phi = DMatrix::zeros(r, keep.len());
    let mut omegas = Vec::with_capacity(keep.len());
    for (c, &i) in keep.iter().enumerate() {
        let v = l_inv.transpose() * eig.eigenvectors.column(i);
        phi.set_column(c, &v);
        omegas.push(eig.eigenvalues[i].sqrt());
    }
    Ok((phi, omegas))
}

/// The planet block: one short and one long planet with the central members
/// at rest, M-orthonormalized; returns it and its highest natural frequency
/// over omega_ref (with all meshes in contact).
fn planet_block(sys: &MeshSystem, channels: &[Channel]) -> Result<(PlanetBlock, f64)> {
    let n = sys.dof();
    let n_pl = (n - 4) / 2;
    let (ia, ib) = (4, 4 + n_pl);
    let (ja, jb) = (sys.mass[(ia, ia)], sys.mass[(ib, ib)]);
    let wr = sys.omega_ref_rad_s;
    let mut p = Vec::with_capacity(channels.len());
    let mut damping = [[0.0; 2]; 2];
    let mut k = [[0.0; 2]; 2];
    for ch in channels {
        let j = ch.meshes[0];
        let w = sys.mesh_vector(j);
        // Planet 1's coordinates only, scaled to M-orthonormal coordinates.
        let v = [w[ia] / ja.sqrt(), w[ib] / jb.sqrt()];
        let mesh = &sys.meshes[j];
        for r in 0..2 {
            for c in 0..2 {
                damping[r][c] += mesh.damping_n_s_m / wr * v[r] * v[c];
                k[r][c] += mesh.stiffness_mean_n_m / (wr * wr) * v[r] * v[c];
            }
        }
        p.push(v);
    }
    // Largest eigenvalue of the symmetric 2x2 K.
    let tr = k[0][0] + k[1][1];
    let det = k[0][0] * k[1][1] - k[0][1] * k[1][0];
    let lmax = 0.5 * (tr + (tr * tr - 4.0 * det).max(0.0).sqrt());
    Ok((PlanetBlock { p, damping }, lmax.sqrt()))
}
