//! The key table itself: every user-facing key with its unit, type and
//! range, the models it applies to and its one-line meaning.

use super::{Applies, KeySpec, KeyType};

const TEETH: KeyType = KeyType::Int { min: 6, max: 500 };
const INERTIA: KeyType = KeyType::Float {
    min: 1e-6,
    max: 1e3,
};
const MESH_K: KeyType = KeyType::Float {
    min: 1e6,
    max: 1e12,
};
const BACKLASH: KeyType = KeyType::Float {
    min: 0.0,
    max: 1000.0,
};
const TE: KeyType = KeyType::Float {
    min: -1000.0,
    max: 1000.0,
};
const PHASE: KeyType = KeyType::Float {
    min: -360.0,
    max: 360.0,
};

macro_rules! key {
    ($name:expr, $unit:expr, $ty:expr, $applies:ident, $desc:expr) => {
        KeySpec {
            name: $name,
            unit: $unit,
            ty: $ty,
            applies: Applies::$applies,
            shortcut: false,
            extension: false,
            description: $desc,
        }
    };
    ($name:expr, $unit:expr, $ty:expr, $applies:ident, shortcut, $desc:expr) => {
        KeySpec {
            name: $name,
            unit: $unit,
            ty: $ty,
            applies: Applies::$applies,
            shortcut: true,
            extension: false,
            description: $desc,
        }
    };
}

macro_rules! per_kind_keys {
    ($prefix:expr, $suffix:expr, $unit:expr, $ty:expr, $what:expr) => {
        [
            key!(
                concat!($prefix, "s1a", $suffix),
                $unit,
                $ty,
                Ravigneaux,
                concat!($what, " of the s1a (small sun / short planet) meshes")
            ),
            key!(
                concat!($prefix, "s2b", $suffix),
                $unit,
                $ty,
                Ravigneaux,
                concat!($what, " of the s2b (large sun / long planet) meshes")
            ),
            key!(
                concat!($prefix, "ab", $suffix),
                $unit,
                $ty,
                Ravigneaux,
                concat!($what, " of the ab (short planet / long planet) meshes")
            ),
            key!(
                concat!($prefix, "rb", $suffix),
                $unit,
                $ty,
                Ravigneaux,
                concat!($what, " of the rb (ring / long planet) meshes")
            ),
        ]
    };
}

/// The whole key table, in the order of docs and JSON output.
pub static KEYS: std::sync::LazyLock<Vec<KeySpec>> = std::sync::LazyLock::new(build_keys);

fn build_keys() -> Vec<KeySpec> {
    let mut keys = vec![
        key!(
            "model",
            "-",
            KeyType::Choice(&["ravigneaux", "gear-pair"]),
            Both,
            "which built-in model: the compound planetary set or a single gear pair"
        ),
        key!(
            "backlash_um",
            "um",
            BACKLASH,
            Both,
            "backlash: half-width b of the dead zone, on all meshes"
        ),
        key!(
            "te_um",
            "um",
            TE,
            Both,
            "transmission error sine amplitude (compound set: on the meshes named by te_meshes)"
        ),
        key!(
            "te_meshes",
            "-",
            KeyType::Choice(&["s1a", "all"]),
            Ravigneaux,
            "where te_um acts: the s1a meshes only (the paper's Table 1) or every mesh \
             (its Fig. 2 'Ec_all' read as all meshes); switching copies or clears the other kinds' sine"
        ),
        key!(
            "stiffness_variation",
            "-",
            KeyType::Float {
                min: 0.0,
                max: 0.95
            },
            Both,
            "mesh stiffness fluctuation v: half the peak-to-peak stiffness over its mean; \
             k(t) = k_m (1 + v cos(omega t + gamma)) for the cosine waveform"
        ),
        key!(
            "damping_ratio",
            "-",
            KeyType::Float { min: 0.0, max: 1.0 },
            Both,
            "mesh damping ratio xi: c = 2 xi sqrt(k_m m_e)"
        ),
        key!(
            "torque_s1_nm",
            "N m",
            KeyType::Float {
                min: 0.0,
                max: 1e6
            },
            Ravigneaux,
            "input torque on the small sun s1"
        ),
        key!(
            "torque_s2_nm",
            "N m",
            KeyType::FloatOrAuto {
                min: -1e6,
                max: 1e6
            },
            Ravigneaux,
            "torque on the large sun s2; auto = the value that balances torque_s1_nm"
        ),
        key!(
            "planets",
            "-",
            KeyType::Int { min: 3, max: 6 },
            Ravigneaux,
            "number of planet pairs N"
        ),
        key!(
            "phasing",
            "-",
            KeyType::Choice(&["in-phase", "sequential"]),
            Ravigneaux,
            "mesh phasing between planets"
        ),
        key!(
            "module_mm",
            "mm",
            KeyType::Float {
                min: 0.5,
                max: 50.0
            },
            Both,
            "gear module m"
        ),
        key!(
            "pressure_angle_deg",
            "deg",
            KeyType::Float {
                min: 10.0,
                max: 35.0
            },
            Both,
            "pressure angle alpha"
        ),
        key!(
            "teeth_s1",
            "-",
            TEETH,
            Ravigneaux,
            "teeth of the small sun s1"
        ),
        key!(
            "teeth_s2",
            "-",
            TEETH,
            Ravigneaux,
            "teeth of the large sun s2"
        ),
        key!(
            "teeth_a",
            "-",
            TEETH,
            Ravigneaux,
            "teeth of a short planet a"
        ),
        key!(
            "teeth_r",
            "-",
            TEETH,
            Ravigneaux,
            "teeth of the ring r (long planet: (teeth_r - teeth_s2)/2)"
        ),
        key!(
            "inertia_s1_kg_m2",
            "kg m^2",
            INERTIA,
            Ravigneaux,
            "moment of inertia of the small sun"
        ),
        key!(
            "inertia_s2_kg_m2",
            "kg m^2",
            INERTIA,
            Ravigneaux,
            "moment of inertia of the large sun"
        ),
        key!(
            "inertia_r_kg_m2",
            "kg m^2",
            INERTIA,
            Ravigneaux,
            "moment of inertia of the ring"
        ),
        key!(
            "inertia_c_kg_m2",
            "kg m^2",
            INERTIA,
            Ravigneaux,
            "moment of inertia of the bare carrier"
        ),
        key!(
            "inertia_a_kg_m2",
            "kg m^2",
            INERTIA,
            Ravigneaux,
            "moment of inertia of a short planet about its axis"
        ),
        key!(
            "inertia_b_kg_m2",
            "kg m^2",
            INERTIA,
            Ravigneaux,
            "moment of inertia of a long planet about its axis"
        ),
        key!(
            "mass_a_kg",
            "kg",
            KeyType::Float { min: 0.0, max: 1e4 },
            Ravigneaux,
            "mass of a short planet (adds m r_ca^2 to the carrier)"
        ),
        key!(
            "mass_b_kg",
            "kg",
            KeyType::Float { min: 0.0, max: 1e4 },
            Ravigneaux,
            "mass of a long planet (adds m r_cb^2 to the carrier)"
        ),
        key!(
            "ring_support_n_m",
            "N/m",
            KeyType::Float {
                min: 1e3,
                max: 1e13
            },
            Ravigneaux,
            "torsional support stiffness of the ring, on its base circle"
        ),
        key!(
            "ring_support_radius_mm",
            "mm",
            KeyType::FloatOrAuto {
                min: 1.0,
                max: 1000.0
            },
            Ravigneaux,
            "radius at which ring_support_n_m acts; auto = the ring's base radius \
             (157.9 mm by default; the paper prints 15.79 mm)"
        ),
    ];
    keys.extend(per_kind_keys!(
        "stiffness_",
        "_n_m",
        "N/m",
        MESH_K,
        "mean mesh stiffness k_m"
    ));
    keys.extend(per_kind_keys!(
        "backlash_",
        "_um",
        "um",
        BACKLASH,
        "backlash half-width b"
    ));
    keys.extend(per_kind_keys!(
        "te_sin_",
        "_um",
        "um",
        TE,
        "TE sine amplitude"
    ));
    keys.extend(per_kind_keys!(
        "te_cos_",
        "_um",
        "um",
        TE,
        "TE cosine amplitude"
    ));
    keys.extend(per_kind_keys!(
        "te_mean_",
        "_um",
        "um",
        TE,
        "TE mean (static offset)"
    ));
    keys.extend(per_kind_keys!(
        "phase_",
        "_deg",
        "deg",
        PHASE,
        "mesh phase offset gamma"
    ));
    keys.extend([
        key!(
            "teeth_pinion",
            "-",
            TEETH,
            GearPair,
            "teeth of the pinion (driver)"
        ),
        key!(
            "teeth_gear",
            "-",
            TEETH,
            GearPair,
            "teeth of the gear (driven)"
        ),
        key!(
            "inertia_pinion_kg_m2",
            "kg m^2",
            INERTIA,
            GearPair,
            "moment of inertia of the pinion"
        ),
        key!(
            "inertia_gear_kg_m2",
            "kg m^2",
            INERTIA,
            GearPair,
            "moment of inertia of the gear"
        ),
        key!(
            "stiffness_n_m",
            "N/m",
            MESH_K,
            GearPair,
            "mean mesh stiffness k_m"
        ),
        key!("te_cos_um", "um", TE, GearPair, "TE cosine amplitude"),
        key!("te_mean_um", "um", TE, GearPair, "TE mean (static offset)"),
        key!(
            "torque_pinion_nm",
            "N m",
            KeyType::Float { min: 0.0, max: 1e6 },
            GearPair,
            "torque on the pinion (the gear carries the balancing torque)"
        ),
    ]);
    let mut extension = excitation_keys();
    extension.iter_mut().for_each(|k| k.extension = true);
    keys.extend(extension);
    keys
}

const CONTACT_RATIO: KeyType = KeyType::FloatOrAuto {
    min: crate::waveform::CONTACT_RATIO_RANGE.0,
    max: crate::waveform::CONTACT_RATIO_RANGE.1,
};
const WAVE: KeyType = KeyType::Choice(&crate::waveform::Wave::NAMES);

macro_rules! te_harmonic_keys {
    ($keys:ident, $n:literal) => {
        $keys.extend(per_kind_keys!(
            concat!("te_cos", $n, "_"),
            "_um",
            "um",
            TE,
            concat!("TE cosine amplitude of harmonic ", $n)
        ));
        $keys.extend(per_kind_keys!(
            concat!("te_sin", $n, "_"),
            "_um",
            "um",
            TE,
            concat!("TE sine amplitude of harmonic ", $n)
        ));
        $keys.push(key!(
            concat!("te_cos", $n, "_um"),
            "um",
            TE,
            GearPair,
            concat!("TE cosine amplitude of harmonic ", $n)
        ));
        $keys.push(key!(
            concat!("te_sin", $n, "_um"),
            "um",
            TE,
            GearPair,
            concat!("TE sine amplitude of harmonic ", $n)
        ));
    };
}

/// The excitation's waveforms (after the seed's single harmonic): written
/// by `to_json` only where they differ from the defaults.
fn excitation_keys() -> Vec<KeySpec> {
    let mut keys = vec![
        key!(
            "stiffness_wave",
            "-",
            WAVE,
            GearPair,
            "mesh stiffness waveform: the paper's cosine, or single and double tooth contact \
             (rectangular, or trapezoid with linear ramps) from the contact ratio"
        ),
        key!(
            "contact_ratio",
            "-",
            CONTACT_RATIO,
            GearPair,
            "contact ratio of the rectangular and trapezoid stiffness (double contact for its \
             fractional part of each mesh period); auto = from teeth, module and pressure angle"
        ),
    ];
    keys.extend(per_kind_keys!(
        "stiffness_wave_",
        "",
        "-",
        WAVE,
        "stiffness waveform (cosine, rectangular, trapezoid)"
    ));
    keys.extend(per_kind_keys!(
        "contact_ratio_",
        "",
        "-",
        CONTACT_RATIO,
        "contact ratio of the rectangular and trapezoid stiffness (auto = from the geometry)"
    ));
    keys.extend([
        key!(
            "stiffness_ramp",
            "-",
            KeyType::Float { min: 0.0, max: 0.5 },
            Both,
            "width of each ramp of the trapezoid stiffness, as a fraction of the mesh period"
        ),
        key!(
            "stiffness_harmonics",
            "-",
            KeyType::Int { min: 1, max: 15 },
            Both,
            "harmonics the rectangular and trapezoid stiffness are cut to (the solver sees \
             this Fourier series; the harmonic balance needs at least as many)"
        ),
    ]);
    te_harmonic_keys!(keys, "2");
    te_harmonic_keys!(keys, "3");
    te_harmonic_keys!(keys, "4");
    te_harmonic_keys!(keys, "5");
    te_harmonic_keys!(keys, "6");
    keys
}
