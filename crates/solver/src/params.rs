//! Parameter sets of the two built-in models, with the defaults of
//! `docs/model.md`.
//!
//! The structs hold the user's physical inputs only; everything derivable
//! (radii, the long planet's tooth count, equivalent masses, damping
//! coefficients, the balancing torque) is derived in [`crate::system`], never
//! typed in. Reading and writing them by flat user-facing keys lives in
//! [`crate::keys`].

/// Which built-in model a parameter set describes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ModelKind {
    /// The Ravigneaux-type compound planetary gear set of the seed paper.
    Ravigneaux,
    /// A single spur gear pair (Kahraman & Singh, 1990), for teaching.
    GearPair,
}

impl ModelKind {
    /// The name used in keys, links and the CLI's `--model`.
    pub fn name(self) -> &'static str {
        match self {
            ModelKind::Ravigneaux => "ravigneaux",
            ModelKind::GearPair => "gear-pair",
        }
    }

    /// Parses a model name as written by [`ModelKind::name`].
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "ravigneaux" => Some(ModelKind::Ravigneaux),
            "gear-pair" => Some(ModelKind::GearPair),
            _ => None,
        }
    }
}

/// How the planets' meshes are phased against each other.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phasing {
    /// All planets mesh in phase (`gamma_j = 0` plus the per-kind offset).
    InPhase,
    /// Each planet's mesh phase follows from its position angle and the tooth
    /// counts (see [`crate::system`] for the formula).
    Sequential,
}

impl Phasing {
    /// The name used in keys.
    pub fn name(self) -> &'static str {
        match self {
            Phasing::InPhase => "in-phase",
            Phasing::Sequential => "sequential",
        }
    }
}

/// Where the `te_um` shortcut puts the TE sine amplitude on the compound set.
///
/// The seed's Table 1 gives sun s1 a 20 um eccentricity error and zero
/// elsewhere, but its Fig. 2 varies a TE it writes `Ec_all`, which can also
/// be read as a TE on every mesh. This is that reading, as a setting.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TeMeshes {
    /// On the `s1a` meshes only (`docs/model.md`'s reading, the default).
    S1a,
    /// The same sine amplitude on every mesh kind.
    All,
}

impl TeMeshes {
    /// The name used in keys.
    pub fn name(self) -> &'static str {
        match self {
            TeMeshes::S1a => "s1a",
            TeMeshes::All => "all",
        }
    }
}

/// One value per mesh kind of the compound set: `s1a`, `s2b`, `ab`, `rb`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PerKind {
    /// Small sun to short planet.
    pub s1a: f64,
    /// Large sun to long planet.
    pub s2b: f64,
    /// Short planet to long planet.
    pub ab: f64,
    /// Ring to long planet.
    pub rb: f64,
}

impl PerKind {
    /// The same value on every kind.
    pub const fn all(x: f64) -> Self {
        PerKind {
            s1a: x,
            s2b: x,
            ab: x,
            rb: x,
        }
    }

    /// The value for a kind.
    pub fn get(&self, kind: MeshKind) -> f64 {
        match kind {
            MeshKind::S1A => self.s1a,
            MeshKind::S2B => self.s2b,
            MeshKind::AB => self.ab,
            MeshKind::RB => self.rb,
            MeshKind::Pair => self.s1a,
        }
    }

    /// A mutable reference to the value for a kind.
    pub fn get_mut(&mut self, kind: MeshKind) -> &mut f64 {
        match kind {
            MeshKind::S1A | MeshKind::Pair => &mut self.s1a,
            MeshKind::S2B => &mut self.s2b,
            MeshKind::AB => &mut self.ab,
            MeshKind::RB => &mut self.rb,
        }
    }
}

/// The kind of a mesh: which two bodies it joins.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum MeshKind {
    /// Small sun `s1` to short planet `a_n`.
    S1A,
    /// Large sun `s2` to long planet `b_n`.
    S2B,
    /// Short planet `a_n` to long planet `b_n`.
    AB,
    /// Ring `r` to long planet `b_n`.
    RB,
    /// The single mesh of the gear pair model.
    Pair,
}

impl MeshKind {
    /// The four kinds of the compound set, in the order meshes are numbered.
    pub const COMPOUND: [MeshKind; 4] = [MeshKind::S1A, MeshKind::S2B, MeshKind::AB, MeshKind::RB];

    /// Short name used in keys (`backlash_s1a_um`).
    pub fn key(self) -> &'static str {
        match self {
            MeshKind::S1A => "s1a",
            MeshKind::S2B => "s2b",
            MeshKind::AB => "ab",
            MeshKind::RB => "rb",
            MeshKind::Pair => "pair",
        }
    }
}

/// The highest harmonic of the transmission error a key can set.
pub const TE_HARMONICS: usize = 6;

/// Transmission error components of one mesh kind, in micrometres:
/// `e(t) = mean + cos * cos(theta) + sin * sin(theta) + sum_n (higher[n - 2][0] cos(n theta)
/// + higher[n - 2][1] sin(n theta))` with `theta = omega t + gamma`, `n = 2 ..=` [`TE_HARMONICS`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TeUm {
    /// Mean (static) part.
    pub mean: f64,
    /// Cosine amplitude.
    pub cos: f64,
    /// Sine amplitude.
    pub sin: f64,
    /// Cosine and sine amplitudes of harmonics 2, 3, ...
    pub higher: [[f64; 2]; TE_HARMONICS - 1],
}

impl TeUm {
    /// No transmission error.
    pub const ZERO: TeUm = TeUm {
        mean: 0.0,
        cos: 0.0,
        sin: 0.0,
        higher: [[0.0; 2]; TE_HARMONICS - 1],
    };

    /// The `[cos, sin]` amplitudes of harmonics 2, 3, ... up to the last
    /// non-zero one (empty for a one-harmonic TE).
    pub fn higher_used(&self) -> &[[f64; 2]] {
        let n = self
            .higher
            .iter()
            .rposition(|h| h[0] != 0.0 || h[1] != 0.0)
            .map_or(0, |i| i + 1);
        &self.higher[..n]
    }

    /// [`TeUm::higher_used`] in metres.
    pub fn higher_m(&self) -> Vec<[f64; 2]> {
        self.higher_used()
            .iter()
            .map(|&[c, s]| [c * 1e-6, s * 1e-6])
            .collect()
    }
}

/// The stiffness waveform settings of one mesh kind.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StiffnessShape {
    /// The waveform.
    pub wave: crate::waveform::Wave,
    /// The contact ratio; `None` = computed from the tooth counts, module
    /// and pressure angle (full-depth standard teeth).
    pub contact_ratio: Option<f64>,
}

impl StiffnessShape {
    /// The seed's cosine.
    pub const COSINE: StiffnessShape = StiffnessShape {
        wave: crate::waveform::Wave::Cosine,
        contact_ratio: None,
    };
}

/// Default trapezoid ramp width (mesh periods).
pub const DEFAULT_RAMP: f64 = 0.1;

/// Default number of harmonics of a rectangular or trapezoidal stiffness.
pub const DEFAULT_STIFFNESS_HARMONICS: u32 = 5;

/// Parameters of the Ravigneaux compound planetary gear set (`docs/model.md`).
#[derive(Debug, Clone, PartialEq)]
pub struct RavigneauxParams {
    /// Number of planet pairs N (3..=6).
    pub planets: u32,
    /// Mesh phasing between planets.
    pub phasing: Phasing,
    /// Module m in millimetres.
    pub module_mm: f64,
    /// Pressure angle alpha in degrees.
    pub pressure_angle_deg: f64,
    /// Teeth of the small sun.
    pub teeth_s1: u32,
    /// Teeth of the large sun.
    pub teeth_s2: u32,
    /// Teeth of the short planet.
    pub teeth_a: u32,
    /// Teeth of the ring; the long planet has (teeth_r - teeth_s2)/2.
    pub teeth_r: u32,
    /// Moment of inertia of the small sun (kg m^2).
    pub inertia_s1_kg_m2: f64,
    /// Moment of inertia of the large sun (kg m^2).
    pub inertia_s2_kg_m2: f64,
    /// Moment of inertia of the ring (kg m^2).
    pub inertia_r_kg_m2: f64,
    /// Moment of inertia of the bare carrier (kg m^2).
    pub inertia_c_kg_m2: f64,
    /// Moment of inertia of a short planet about its own axis (kg m^2).
    pub inertia_a_kg_m2: f64,
    /// Moment of inertia of a long planet about its own axis (kg m^2).
    pub inertia_b_kg_m2: f64,
    /// Mass of a short planet (kg), carried by the carrier at radius r_ca.
    pub mass_a_kg: f64,
    /// Mass of a long planet (kg), carried by the carrier at radius r_cb.
    pub mass_b_kg: f64,
    /// Mean mesh stiffness per kind (N/m).
    pub stiffness_n_m: PerKind,
    /// Torsional support stiffness of the ring, on its base circle (N/m).
    pub ring_support_n_m: f64,
    /// Radius (mm) at which `ring_support_n_m` acts; `None` = the ring's base
    /// radius (`docs/model.md`). The seed prints 15.79 mm, read there as a
    /// slip.
    pub ring_support_radius_mm: Option<f64>,
    /// Stiffness fluctuation coefficient v (all meshes): half the
    /// peak-to-peak stiffness over its mean (`crate::waveform`).
    pub stiffness_variation: f64,
    /// Stiffness waveform per kind (s1a, s2b, ab, rb).
    pub stiffness_shape: [StiffnessShape; 4],
    /// Trapezoid ramp width, as a fraction of the mesh period.
    pub stiffness_ramp: f64,
    /// Harmonics the rectangle and trapezoid are cut to.
    pub stiffness_harmonics: u32,
    /// Mesh damping ratio xi (all meshes).
    pub damping_ratio: f64,
    /// Backlash half-width b per kind (micrometres).
    pub backlash_um: PerKind,
    /// Transmission error per kind.
    pub te_um: [TeUm; 4],
    /// Where the `te_um` shortcut writes (and which kinds it mirrors).
    pub te_meshes: TeMeshes,
    /// Common phase offset gamma per kind (degrees), added to the phasing.
    pub phase_deg: PerKind,
    /// Input torque on the small sun (N m).
    pub torque_s1_nm: f64,
    /// Torque on the large sun (N m); `None` = the balancing value.
    pub torque_s2_nm: Option<f64>,
}

impl Default for RavigneauxParams {
    /// The Table 1 reading of `docs/model.md`.
    fn default() -> Self {
        let mut te_um = [TeUm::ZERO; 4];
        te_um[0].sin = 20.0;
        RavigneauxParams {
            planets: 3,
            phasing: Phasing::InPhase,
            module_mm: 4.0,
            pressure_angle_deg: 20.0,
            teeth_s1: 36,
            teeth_s2: 48,
            teeth_a: 21,
            teeth_r: 84,
            inertia_s1_kg_m2: 0.015,
            inertia_s2_kg_m2: 0.059,
            inertia_r_kg_m2: 0.152,
            inertia_c_kg_m2: 0.08,
            inertia_a_kg_m2: 0.0019,
            inertia_b_kg_m2: 0.0022,
            mass_a_kg: 1.997,
            mass_b_kg: 3.139,
            stiffness_n_m: PerKind::all(1e9),
            ring_support_n_m: 1e9,
            ring_support_radius_mm: None,
            stiffness_variation: 0.3,
            stiffness_shape: [StiffnessShape::COSINE; 4],
            stiffness_ramp: DEFAULT_RAMP,
            stiffness_harmonics: DEFAULT_STIFFNESS_HARMONICS,
            damping_ratio: 0.06,
            backlash_um: PerKind::all(100.0),
            te_um,
            te_meshes: TeMeshes::S1a,
            phase_deg: PerKind::all(0.0),
            torque_s1_nm: 2000.0,
            torque_s2_nm: None,
        }
    }
}

impl RavigneauxParams {
    /// Index of a kind in [`RavigneauxParams::te_um`].
    pub fn kind_index(kind: MeshKind) -> usize {
        match kind {
            MeshKind::S1A | MeshKind::Pair => 0,
            MeshKind::S2B => 1,
            MeshKind::AB => 2,
            MeshKind::RB => 3,
        }
    }
}

/// Parameters of the single spur gear pair (Kahraman & Singh, 1990).
#[derive(Debug, Clone, PartialEq)]
pub struct GearPairParams {
    /// Module m in millimetres.
    pub module_mm: f64,
    /// Pressure angle alpha in degrees.
    pub pressure_angle_deg: f64,
    /// Teeth of the pinion (driver).
    pub teeth_pinion: u32,
    /// Teeth of the gear (driven).
    pub teeth_gear: u32,
    /// Moment of inertia of the pinion (kg m^2).
    pub inertia_pinion_kg_m2: f64,
    /// Moment of inertia of the gear (kg m^2).
    pub inertia_gear_kg_m2: f64,
    /// Mean mesh stiffness (N/m).
    pub stiffness_n_m: f64,
    /// Stiffness fluctuation coefficient v: half the peak-to-peak
    /// stiffness over its mean (`crate::waveform`).
    pub stiffness_variation: f64,
    /// Stiffness waveform.
    pub stiffness_shape: StiffnessShape,
    /// Trapezoid ramp width, as a fraction of the mesh period.
    pub stiffness_ramp: f64,
    /// Harmonics the rectangle and trapezoid are cut to.
    pub stiffness_harmonics: u32,
    /// Mesh damping ratio xi.
    pub damping_ratio: f64,
    /// Backlash half-width b (micrometres).
    pub backlash_um: f64,
    /// Transmission error.
    pub te_um: TeUm,
    /// Torque on the pinion (N m); the gear carries the balancing torque.
    pub torque_pinion_nm: f64,
}

impl Default for GearPairParams {
    /// A steel pair, module 4 mm, 30/45 teeth, 30 mm face width (inertias of
    /// solid discs), loaded to a static deflection of 8.9 um against a 100 um
    /// backlash half-width: the proportions of Kahraman & Singh's examples.
    fn default() -> Self {
        GearPairParams {
            module_mm: 4.0,
            pressure_angle_deg: 20.0,
            teeth_pinion: 30,
            teeth_gear: 45,
            inertia_pinion_kg_m2: 0.0048,
            inertia_gear_kg_m2: 0.0243,
            stiffness_n_m: 1e9,
            stiffness_variation: 0.2,
            stiffness_shape: StiffnessShape::COSINE,
            stiffness_ramp: DEFAULT_RAMP,
            stiffness_harmonics: DEFAULT_STIFFNESS_HARMONICS,
            damping_ratio: 0.06,
            backlash_um: 100.0,
            te_um: TeUm {
                sin: 20.0,
                ..TeUm::ZERO
            },
            torque_pinion_nm: 500.0,
        }
    }
}

/// A parameter set of either built-in model.
// Parameter sets are few and long-lived; boxing the larger one buys nothing.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum ModelParams {
    /// The compound planetary gear set.
    Ravigneaux(RavigneauxParams),
    /// The single gear pair.
    GearPair(GearPairParams),
}

impl Default for ModelParams {
    fn default() -> Self {
        ModelParams::Ravigneaux(RavigneauxParams::default())
    }
}

impl RavigneauxParams {
    /// The teeth of a mesh kind's two gears and whether the mesh is
    /// internal: (z1, z2, internal), the long planet having (z_r - z_s2) / 2
    /// teeth. `None` for the gear pair's kind or a ring smaller than the
    /// large sun.
    pub fn mesh_teeth(&self, kind: MeshKind) -> Option<(u32, u32, bool)> {
        let teeth_b = self.teeth_r.checked_sub(self.teeth_s2)? / 2;
        Some(match kind {
            MeshKind::S1A => (self.teeth_s1, self.teeth_a, false),
            MeshKind::S2B => (self.teeth_s2, teeth_b, false),
            MeshKind::AB => (self.teeth_a, teeth_b, false),
            MeshKind::RB => (teeth_b, self.teeth_r, true),
            MeshKind::Pair => return None,
        })
    }
}

impl ModelParams {
    /// The contact ratio the teeth of a mesh kind give (`"pair"` on the gear
    /// pair, `"s1a"`, `"s2b"`, `"ab"`, `"rb"` on the compound set): what a
    /// rectangular or trapezoid stiffness uses when no contact ratio is given.
    /// `None` for a kind the model has not, or a ring too small for its sun.
    pub fn auto_contact_ratio(&self, kind: &str) -> Option<f64> {
        let (z1, z2, internal, m, alpha) = match self {
            ModelParams::GearPair(p) if kind == "pair" => (
                p.teeth_pinion,
                p.teeth_gear,
                false,
                p.module_mm,
                p.pressure_angle_deg,
            ),
            ModelParams::Ravigneaux(p) => {
                let kind = MeshKind::COMPOUND.into_iter().find(|k| k.key() == kind)?;
                let (z1, z2, internal) = p.mesh_teeth(kind)?;
                (z1, z2, internal, p.module_mm, p.pressure_angle_deg)
            }
            ModelParams::GearPair(_) => return None,
        };
        Some(crate::waveform::contact_ratio(z1, z2, internal, m, alpha)).filter(|e| e.is_finite())
    }

    /// The defaults of a model.
    pub fn defaults(kind: ModelKind) -> Self {
        match kind {
            ModelKind::Ravigneaux => ModelParams::Ravigneaux(RavigneauxParams::default()),
            ModelKind::GearPair => ModelParams::GearPair(GearPairParams::default()),
        }
    }

    /// Which model this is.
    pub fn kind(&self) -> ModelKind {
        match self {
            ModelParams::Ravigneaux(_) => ModelKind::Ravigneaux,
            ModelParams::GearPair(_) => ModelKind::GearPair,
        }
    }
}
