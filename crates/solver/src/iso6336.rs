//! The dynamic factor K_v of ISO 6336-1 (method B) for one mesh, to set
//! beside the nonlinear model's own dynamic factor (largest mesh force over
//! the static one).
//!
//! Method B (clause 6.5 of ISO 6336-1:2006 and :2019) treats a mesh as one
//! linear mass-spring pair excited by its pitch and profile deviations:
//!
//! - the resonance ratio N = n1 / n_E1 with n_E1 = 30 000 / (pi z1)
//!   sqrt(c_gamma_alpha / m_red): here the mesh frequency over
//!   sqrt(k / m_red) / (2 pi), the same thing, since c_gamma_alpha / m_red
//!   per unit face width is the mesh stiffness k over the reduced mass;
//! - the ranges: subcritical N <= N_S (N_S = 0.85, or 0.5 + 0.35
//!   sqrt(w / 100) below a line load w = K_A F_t / b of 100 N/mm), main
//!   resonance N_S < N <= 1.15, intermediate 1.15 < N < 1.5 (linear
//!   between the two neighbours' values at 1.15 and 1.5), supercritical
//!   N >= 1.5;
//! - K_v = N (C_v1 B_p + C_v2 B_f + C_v3 B_k) + 1 (subcritical),
//!   C_v1 B_p + C_v2 B_f + C_v4 B_k + 1 (main resonance),
//!   C_v5 B_p + C_v6 B_f + C_v7 (supercritical), with
//!   B_p = c' f_pb,eff / w, B_f = c' f_f,eff / w, B_k = |1 - c' C_a / w|
//!   and the C_v of the standard's table (by the contact ratio eps_gamma,
//!   here the transverse ratio eps_alpha: every mesh is spur).
//!
//! What the model has, and what is an input ([`IsoInputs`]):
//!
//! - From the model: tooth counts, module, pressure angle (standard
//!   addendum m, no profile shift, standard centre distance: the contact
//!   ratio follows), the mesh's mean stiffness k (taken as
//!   c_gamma_alpha b), the static mesh force (F_t = F cos alpha at the
//!   reference circle) and the moments of inertia (the reduced mass).
//! - Inputs with defaults: the face width b (50 mm: what makes the model's
//!   1e9 N/m the standard's typical c_gamma_alpha of 20 N/(mm um)); the
//!   accuracy grade (6), giving f_pb = f_pT cos alpha and f_f_alpha by
//!   ISO 1328-1:2013's formulas at the gear's reference diameter, not
//!   rounded, the larger of the two gears; the application factor K_A
//!   (1); the tip relief C_a (none given: the running-in amount C_ay of
//!   the standard, (sigma_Hlim / 97 - 18.45)^2 / 18 + 1.5 um); the
//!   running-in allowances y_p and y_f (case-hardened steel: 0.075 times
//!   the deviation, at most 3 um); sigma_Hlim (1500 N/mm^2).
//! - c' = c_gamma_alpha / (0.75 eps_alpha + 0.25).
//!
//! Planetary meshes (the standard's rule for planetary gears, in its
//! clause on the reduced mass, 6.5.9 of the 2006 edition): each sun-planet
//! and planet-ring mesh is rated as a gear pair. The sun meshes with p
//! planets at once, so a mesh sees 1/p of its mass: m_red = m_P m_S /
//! (m_S + p m_P). The ring is taken as infinitely heavy: m_red = m_P.
//! m_X = J_X / r_bX^2 is a gear's moment of inertia over its base radius
//! squared (the planet's spin only, as in the standard, not its mass
//! carried round by the carrier). The standard has no rule for the
//! Ravigneaux set's planet-planet mesh: it is rated as a plain pair,
//! m_red = m_a m_b / (m_a + m_b). The model's own equivalent mass of a
//! mesh couples every body (carrier, ring spring, the other planets), so
//! its resonances differ from the standard's n_E1.

use std::f64::consts::PI;

use crate::error::{Result, SolverError};
use crate::params::{MeshKind, ModelParams};
use crate::Model;

/// The inputs the standard needs and the model lacks.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IsoInputs {
    /// Accuracy grade by ISO 1328-1 (1 ..= 11).
    pub accuracy_grade: f64,
    /// Face width b (mm).
    pub face_width_mm: f64,
    /// Application factor K_A.
    pub application_factor: f64,
    /// Tip relief C_a (um); `None`: the running-in amount C_ay.
    pub tip_relief_um: Option<f64>,
    /// Running-in allowance of the base pitch deviation y_p (um); `None`:
    /// case-hardened steel, 0.075 f_pb, at most 3 um.
    pub running_in_pitch_um: Option<f64>,
    /// Running-in allowance of the profile form deviation y_f (um); `None`:
    /// 0.075 f_f_alpha, at most 3 um.
    pub running_in_profile_um: Option<f64>,
    /// Allowable contact stress number sigma_Hlim (N/mm^2), for C_ay.
    pub sigma_hlim_n_mm2: f64,
}

impl Default for IsoInputs {
    fn default() -> Self {
        IsoInputs {
            accuracy_grade: 6.0,
            face_width_mm: 50.0,
            application_factor: 1.0,
            tip_relief_um: None,
            running_in_pitch_um: None,
            running_in_profile_um: None,
            sigma_hlim_n_mm2: 1500.0,
        }
    }
}

/// One mesh as the standard sees it: the pair's geometry, its reduced
/// mass, stiffness and load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IsoMesh {
    /// Teeth of the first (external) gear.
    pub teeth_1: u32,
    /// Teeth of the second gear (the ring when `internal`).
    pub teeth_2: u32,
    /// Whether the second gear is internal (a ring).
    pub internal: bool,
    /// Module (mm).
    pub module_mm: f64,
    /// Pressure angle (degrees).
    pub pressure_angle_deg: f64,
    /// Reduced mass on the line of action over the whole face width (kg).
    pub reduced_mass_kg: f64,
    /// Mean mesh stiffness over the whole face width (N/m).
    pub stiffness_n_m: f64,
    /// Nominal tangential load at the reference circle F_t (N).
    pub tangential_load_n: f64,
}

/// The standard's speed ranges.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SpeedRange {
    /// N <= N_S.
    Subcritical,
    /// N_S < N <= 1.15.
    MainResonance,
    /// 1.15 < N < 1.5.
    Intermediate,
    /// N >= 1.5.
    Supercritical,
}

impl SpeedRange {
    /// The range's name in words (and in JSON).
    pub fn name(self) -> &'static str {
        match self {
            SpeedRange::Subcritical => "subcritical",
            SpeedRange::MainResonance => "main resonance",
            SpeedRange::Intermediate => "intermediate",
            SpeedRange::Supercritical => "supercritical",
        }
    }
}

/// Everything of method B for one mesh that does not depend on speed.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshRating {
    /// Transverse contact ratio eps_alpha (= eps_gamma: spur).
    pub contact_ratio: f64,
    /// Mesh stiffness c_gamma_alpha (N/(mm um)).
    pub mesh_stiffness_n_mm_um: f64,
    /// Single stiffness c' (N/(mm um)).
    pub single_stiffness_n_mm_um: f64,
    /// Reduced mass per unit face width m_red (kg/mm).
    pub reduced_mass_kg_mm: f64,
    /// Mesh frequency at the main resonance, N = 1 (Hz).
    pub resonance_mesh_freq_hz: f64,
    /// Line load w = K_A F_t / b (N/mm).
    pub line_load_n_mm: f64,
    /// Transverse base pitch deviation f_pb (um).
    pub pitch_deviation_um: f64,
    /// Profile form deviation f_f_alpha (um).
    pub profile_deviation_um: f64,
    /// Running-in allowance y_p (um).
    pub running_in_pitch_um: f64,
    /// Running-in allowance y_f (um).
    pub running_in_profile_um: f64,
    /// Tip relief C_a used (um).
    pub tip_relief_um: f64,
    /// B_p.
    pub b_p: f64,
    /// B_f.
    pub b_f: f64,
    /// B_k.
    pub b_k: f64,
    /// N_S, the lower end of the main resonance range.
    pub n_s: f64,
    /// C_v1 ..= C_v7.
    pub c_v: [f64; 7],
}

fn out_of_range(key: &str, value: f64, allowed: &str) -> SolverError {
    SolverError::OutOfRange {
        key: key.into(),
        value: format!("{value}"),
        allowed: allowed.into(),
    }
}

/// `value` must be finite and in `lo ..= hi`.
fn check(key: &str, value: f64, lo: f64, hi: f64, allowed: &str) -> Result<()> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(())
    } else {
        Err(out_of_range(key, value, allowed))
    }
}

impl IsoInputs {
    /// Refuses values outside the standard's scope, naming the value.
    pub fn validate(&self) -> Result<()> {
        let g = self.accuracy_grade;
        if !(g.is_finite() && g.fract() == 0.0 && (1.0..=11.0).contains(&g)) {
            return Err(out_of_range(
                "accuracy grade",
                g,
                "a whole number 1 ..= 11 (ISO 1328-1)",
            ));
        }
        check(
            "face width (mm)",
            self.face_width_mm,
            1.0,
            2000.0,
            "1 ..= 2000 mm",
        )?;
        check(
            "application factor K_A",
            self.application_factor,
            1.0,
            5.0,
            "1 ..= 5",
        )?;
        for (key, v) in [
            ("tip relief (um)", self.tip_relief_um),
            ("running-in allowance y_p (um)", self.running_in_pitch_um),
            ("running-in allowance y_f (um)", self.running_in_profile_um),
        ] {
            if let Some(v) = v {
                check(key, v, 0.0, 200.0, "0 ..= 200 um")?;
            }
        }
        check(
            "sigma_Hlim (N/mm^2)",
            self.sigma_hlim_n_mm2,
            200.0,
            2000.0,
            "200 ..= 2000 N/mm^2",
        )
    }
}

/// ISO 1328-1:2013's single pitch tolerance f_pT (um) at reference
/// diameter `d_mm`, module `m_mm` and grade `grade`.
pub fn single_pitch_tolerance_um(d_mm: f64, m_mm: f64, grade: f64) -> f64 {
    (0.001 * d_mm + 0.4 * m_mm + 5.0) * 2f64.sqrt().powf(grade - 5.0)
}

/// ISO 1328-1:2013's profile form tolerance f_f_alpha_T (um).
pub fn profile_form_tolerance_um(m_mm: f64, grade: f64) -> f64 {
    (0.55 * m_mm + 5.0) * 2f64.sqrt().powf(grade - 5.0)
}

/// The C_v factors of the standard's table for contact ratio `eps`.
pub fn c_v(eps: f64) -> [f64; 7] {
    let (c2, c3, c4, c6) = if eps <= 2.0 {
        (0.34, 0.23, 0.90, 0.47)
    } else {
        (
            0.57 / (eps - 0.3),
            0.096 / (eps - 1.56),
            (0.57 - 0.05 * eps) / (eps - 1.44),
            0.12 / (eps - 1.74),
        )
    };
    let c7 = if eps <= 1.5 {
        0.75
    } else if eps <= 2.5 {
        0.125 * (PI * (eps - 2.0)).sin() + 0.875
    } else {
        1.0
    };
    [0.32, c2, c3, c4, 0.47, c6, c7]
}

/// A running-in allowance by the case-hardened steel rule.
fn running_in_um(deviation_um: f64) -> f64 {
    (0.075 * deviation_um).min(3.0)
}

impl MeshRating {
    /// Rates one mesh; refuses inputs outside the standard's scope, naming
    /// the value.
    pub fn new(mesh: &IsoMesh, inputs: &IsoInputs) -> Result<Self> {
        inputs.validate()?;
        if mesh.teeth_1 < 6 || mesh.teeth_2 < 6 {
            return Err(out_of_range(
                "teeth",
                f64::from(mesh.teeth_1.min(mesh.teeth_2)),
                "at least 6",
            ));
        }
        check("module (mm)", mesh.module_mm, 0.1, 100.0, "0.1 ..= 100 mm")?;
        check(
            "pressure angle (degrees)",
            mesh.pressure_angle_deg,
            10.0,
            35.0,
            "10 ..= 35 degrees",
        )?;
        let positive = |key: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(out_of_range(key, v, "a positive number"))
            }
        };
        positive("reduced mass (kg)", mesh.reduced_mass_kg)?;
        positive("mesh stiffness (N/m)", mesh.stiffness_n_m)?;
        positive("tangential load (N)", mesh.tangential_load_n)?;
        let alpha = mesh.pressure_angle_deg.to_radians();
        // The transverse contact ratio of standard teeth, as the
        // rectangular stiffness takes it.
        let eps = crate::waveform::contact_ratio(
            mesh.teeth_1,
            mesh.teeth_2,
            mesh.internal,
            mesh.module_mm,
            mesh.pressure_angle_deg,
        );
        if !(eps.is_finite() && eps > 1.0) {
            return Err(out_of_range(
                "contact ratio",
                eps,
                "above 1 (the teeth must overlap)",
            ));
        }
        let b = inputs.face_width_mm;
        // k (N/m) = c_gamma_alpha (N/(mm um)) * b (mm) * 1e6.
        let c_gamma = mesh.stiffness_n_m * 1e-6 / b;
        let c_single = c_gamma / (0.75 * eps + 0.25);
        let w = inputs.application_factor * mesh.tangential_load_n / b;
        let grade = inputs.accuracy_grade;
        let d_max = mesh.module_mm * f64::from(mesh.teeth_1.max(mesh.teeth_2));
        let f_pb = single_pitch_tolerance_um(d_max, mesh.module_mm, grade) * alpha.cos();
        let f_fa = profile_form_tolerance_um(mesh.module_mm, grade);
        let y_p = inputs.running_in_pitch_um.unwrap_or(running_in_um(f_pb));
        let y_f = inputs.running_in_profile_um.unwrap_or(running_in_um(f_fa));
        let c_a = inputs
            .tip_relief_um
            .unwrap_or((inputs.sigma_hlim_n_mm2 / 97.0 - 18.45).powi(2) / 18.0 + 1.5);
        let n_s = if w < 100.0 {
            0.5 + 0.35 * (w / 100.0).sqrt()
        } else {
            0.85
        };
        Ok(MeshRating {
            contact_ratio: eps,
            mesh_stiffness_n_mm_um: c_gamma,
            single_stiffness_n_mm_um: c_single,
            reduced_mass_kg_mm: mesh.reduced_mass_kg / b,
            resonance_mesh_freq_hz: (mesh.stiffness_n_m / mesh.reduced_mass_kg).sqrt() / (2.0 * PI),
            line_load_n_mm: w,
            pitch_deviation_um: f_pb,
            profile_deviation_um: f_fa,
            running_in_pitch_um: y_p,
            running_in_profile_um: y_f,
            tip_relief_um: c_a,
            b_p: c_single * (f_pb - y_p).max(0.0) / w,
            b_f: c_single * (f_fa - y_f).max(0.0) / w,
            b_k: (1.0 - c_single * c_a / w).abs(),
            n_s,
            c_v: c_v(eps),
        })
    }

    /// The resonance ratio N at mesh frequency `mesh_freq_hz`.
    pub fn resonance_ratio(&self, mesh_freq_hz: f64) -> f64 {
        mesh_freq_hz / self.resonance_mesh_freq_hz
    }

    /// The speed range of resonance ratio `n`.
    pub fn range(&self, n: f64) -> SpeedRange {
        if n <= self.n_s {
            SpeedRange::Subcritical
        } else if n <= 1.15 {
            SpeedRange::MainResonance
        } else if n < 1.5 {
            SpeedRange::Intermediate
        } else {
            SpeedRange::Supercritical
        }
    }

    /// K_v at resonance ratio `n` (>= 0).
    pub fn kv(&self, n: f64) -> f64 {
        self.kv_in(self.range(n), n)
    }

    /// K_v by the formula of range `range` at `n` (a range's formula
    /// continued past its ends: a curve's pieces end exactly there).
    pub fn kv_in(&self, range: SpeedRange, n: f64) -> f64 {
        let [c1, c2, c3, c4, c5, c6, c7] = self.c_v;
        let main = c1 * self.b_p + c2 * self.b_f + c4 * self.b_k + 1.0;
        let supercritical = c5 * self.b_p + c6 * self.b_f + c7;
        match range {
            SpeedRange::Subcritical => n * (c1 * self.b_p + c2 * self.b_f + c3 * self.b_k) + 1.0,
            SpeedRange::MainResonance => main,
            SpeedRange::Intermediate => supercritical + (main - supercritical) * (1.5 - n) / 0.35,
            SpeedRange::Supercritical => supercritical,
        }
    }
}

/// One mesh of a model rated by the standard.
#[derive(Debug, Clone, PartialEq)]
pub struct ModelMeshRating {
    /// The mesh as the standard sees it.
    pub mesh: IsoMesh,
    /// Its rating.
    pub rating: MeshRating,
}

/// A gear's mass on its line of action, J / r_b^2 (kg).
fn line_mass(inertia_kg_m2: f64, teeth: u32, module_mm: f64, cos_alpha: f64) -> f64 {
    let rb_m = module_mm * 1e-3 * f64::from(teeth) / 2.0 * cos_alpha;
    inertia_kg_m2 / (rb_m * rb_m)
}

/// The standard's view of mesh `j` of `model` (built from `params`): tooth
/// counts, the reduced mass by the planetary rules of this module's doc,
/// the mean stiffness and the static load.
pub fn iso_mesh(params: &ModelParams, model: &Model, j: usize) -> Option<IsoMesh> {
    let mesh = model.system.meshes.get(j)?;
    let force_n = model.statics.mesh_force_n.get(j)?.abs();
    let pair = |a: f64, b: f64| a * b / (a + b);
    let (teeth_1, teeth_2, internal, module_mm, alpha_deg, reduced) = match params {
        ModelParams::GearPair(p) => {
            let c = p.pressure_angle_deg.to_radians().cos();
            let m1 = line_mass(p.inertia_pinion_kg_m2, p.teeth_pinion, p.module_mm, c);
            let m2 = line_mass(p.inertia_gear_kg_m2, p.teeth_gear, p.module_mm, c);
            (
                p.teeth_pinion,
                p.teeth_gear,
                false,
                p.module_mm,
                p.pressure_angle_deg,
                pair(m1, m2),
            )
        }
        ModelParams::Ravigneaux(p) => {
            let c = p.pressure_angle_deg.to_radians().cos();
            let teeth_b = p.teeth_r.checked_sub(p.teeth_s2)? / 2;
            let mass = |j: f64, z: u32| line_mass(j, z, p.module_mm, c);
            let (m_s1, m_s2) = (
                mass(p.inertia_s1_kg_m2, p.teeth_s1),
                mass(p.inertia_s2_kg_m2, p.teeth_s2),
            );
            let (m_a, m_b) = (
                mass(p.inertia_a_kg_m2, p.teeth_a),
                mass(p.inertia_b_kg_m2, teeth_b),
            );
            let planets = f64::from(p.planets);
            let sun = |m_s: f64, m_p: f64| m_p * m_s / (m_s + planets * m_p);
            let (z1, z2, internal, reduced) = match mesh.kind {
                MeshKind::S1A | MeshKind::Pair => (p.teeth_s1, p.teeth_a, false, sun(m_s1, m_a)),
                MeshKind::S2B => (p.teeth_s2, teeth_b, false, sun(m_s2, m_b)),
                MeshKind::AB => (p.teeth_a, teeth_b, false, pair(m_a, m_b)),
                MeshKind::RB => (teeth_b, p.teeth_r, true, m_b),
            };
            (z1, z2, internal, p.module_mm, p.pressure_angle_deg, reduced)
        }
    };
    Some(IsoMesh {
        teeth_1,
        teeth_2,
        internal,
        module_mm,
        pressure_angle_deg: alpha_deg,
        reduced_mass_kg: reduced,
        stiffness_n_m: mesh.stiffness_mean_n_m,
        tangential_load_n: force_n * alpha_deg.to_radians().cos(),
    })
}

/// Every mesh of `model` rated by the standard, in the model's order; the
/// first refusal (a mesh without static load, an input out of range) as
/// the error, naming the mesh.
pub fn rate_model(
    params: &ModelParams,
    model: &Model,
    inputs: &IsoInputs,
) -> Result<Vec<ModelMeshRating>> {
    inputs.validate()?;
    (0..model.system.meshes.len())
        .map(|j| {
            let name = &model.system.meshes[j].name;
            let mesh = iso_mesh(params, model, j).ok_or_else(|| SolverError::Geometry {
                message: format!("mesh {name} has no geometry for ISO 6336-1"),
            })?;
            let rating = MeshRating::new(&mesh, inputs).map_err(|e| match e {
                SolverError::OutOfRange {
                    key,
                    value,
                    allowed,
                } => SolverError::OutOfRange {
                    key: format!("{key} of mesh {name}"),
                    value,
                    allowed,
                },
                e => e,
            })?;
            Ok(ModelMeshRating { mesh, rating })
        })
        .collect()
}

#[cfg(test)]
mod tests;
