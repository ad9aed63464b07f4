//! The one flat set of user-facing parameter keys.
//!
//! The same keys are used by the CLI (`--set KEY=VALUE`), JSON parameter
//! files (a flat object) and the page's URL. [`KEYS`] is the single table of
//! names, units, ranges and descriptions; [`get`] and [`set`] read and write a
//! [`ModelParams`] by key; [`to_json`] and [`from_json`] convert whole sets.
//!
//! Two keys of the compound model are shortcuts: `backlash_um` sets the
//! backlash of all four mesh kinds and `te_um` is the TE sine amplitude on the
//! meshes named by `te_meshes` (`te_sin_s1a_um` by default; every kind's
//! `te_sin_*_um` with `te_meshes=all`). When a JSON object holds both a
//! shortcut and a per-kind key, the per-kind key wins whatever the order.
//!
//! Two keys are readings of the seed paper where it is ambiguous:
//! `te_meshes` (its Fig. 2 varies a TE written `Ec_all`: on every mesh, or on
//! the s1a meshes as its Table 1's sun-s1 error) and `ring_support_radius_mm`
//! (its Table 1 prints the ring's radius as 15.79 mm, which `MODEL.md` reads
//! as a slip for the base radius 157.9 mm; the support spring acts there).

use crate::error::{Result, SolverError};
use crate::params::{
    GearPairParams, MeshKind, ModelKind, ModelParams, PerKind, Phasing, RavigneauxParams, TeMeshes,
};
use serde_json::{Map, Value as Json};

/// The type and allowed range of a key's value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KeyType {
    /// A finite real number in `min ..= max`.
    Float {
        /// Smallest allowed value.
        min: f64,
        /// Largest allowed value.
        max: f64,
    },
    /// An integer in `min ..= max`.
    Int {
        /// Smallest allowed value.
        min: i64,
        /// Largest allowed value.
        max: i64,
    },
    /// One of a fixed set of words.
    Choice(&'static [&'static str]),
    /// A finite real number in `min ..= max`, or the word `auto`.
    FloatOrAuto {
        /// Smallest allowed value.
        min: f64,
        /// Largest allowed value.
        max: f64,
    },
}

impl KeyType {
    /// The allowed values in words, for messages and docs.
    pub fn allowed(&self) -> String {
        match self {
            KeyType::Float { min, max } => format!("{} ..= {}", fmt_num(*min), fmt_num(*max)),
            KeyType::Int { min, max } => format!("integer {min} ..= {max}"),
            KeyType::Choice(words) => format!("one of {}", words.join(", ")),
            KeyType::FloatOrAuto { min, max } => {
                format!("auto or {} ..= {}", fmt_num(*min), fmt_num(*max))
            }
        }
    }
}

fn fmt_num(x: f64) -> String {
    if x != 0.0 && (x.abs() >= 1e6 || x.abs() < 1e-3) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// A typed parameter value.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A number (integers too).
    Num(f64),
    /// A word (choices and `auto`).
    Text(String),
}

/// Which models a key applies to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Applies {
    /// Both models.
    Both,
    /// Only the compound planetary set.
    Ravigneaux,
    /// Only the gear pair.
    GearPair,
}

impl Applies {
    /// Whether the key applies to `model`.
    pub fn includes(self, model: ModelKind) -> bool {
        matches!(
            (self, model),
            (Applies::Both, _)
                | (Applies::Ravigneaux, ModelKind::Ravigneaux)
                | (Applies::GearPair, ModelKind::GearPair)
        )
    }
}

/// One user-facing key.
#[derive(Debug, Clone, Copy)]
pub struct KeySpec {
    /// The key, e.g. `backlash_um`.
    pub name: &'static str,
    /// The unit, or `-` for dimensionless.
    pub unit: &'static str,
    /// Type and allowed range.
    pub ty: KeyType,
    /// Models that accept the key.
    pub applies: Applies,
    /// A shortcut or alias on the compound model (not written by [`to_json`] there).
    pub shortcut: bool,
    /// One line for docs and tooltips.
    pub description: &'static str,
}

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
            description: $desc,
        }
    };
}

macro_rules! per_kind_keys {
    ($prefix:literal, $suffix:literal, $unit:expr, $ty:expr, $what:literal) => {
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
            "mesh stiffness fluctuation v: k(t) = k_m (1 + v cos(omega t + gamma))"
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
                min: -1e6,
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
            KeyType::Float {
                min: -1e6,
                max: 1e6
            },
            GearPair,
            "torque on the pinion (the gear carries the balancing torque)"
        ),
    ]);
    keys
}

/// Whether `name` is a shortcut on `model` (written as per-kind keys by [`to_json`]).
pub fn is_shortcut(name: &str, model: ModelKind) -> bool {
    model == ModelKind::Ravigneaux && matches!(name, "backlash_um" | "te_um")
}

/// Looks a key up in [`KEYS`].
pub fn spec(name: &str) -> Option<&'static KeySpec> {
    KEYS.iter().find(|k| k.name == name)
}

fn unknown(name: &str) -> SolverError {
    // "Did you mean": the known key nearest in edit distance, if close.
    let best = KEYS
        .iter()
        .map(|k| (edit_distance(k.name, name), k.name))
        .min_by_key(|(d, _)| *d);
    let hint = match best {
        Some((d, n)) if d <= 3 && name.len() < 64 => format!(" (did you mean `{n}`?)"),
        _ => String::new(),
    };
    SolverError::UnknownKey {
        key: truncate(name, 60),
        hint,
    }
}

/// Levenshtein distance, capped for long inputs (hostile links).
fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().take(64).collect();
    let b: Vec<char> = b.chars().take(64).collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.iter().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != cb);
            cur[j + 1] = sub.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// Shortens untrusted text for messages.
pub fn truncate(s: &str, max_chars: usize) -> String {
    if s.chars().count() <= max_chars {
        s.to_string()
    } else {
        let mut t: String = s.chars().take(max_chars).collect();
        t.push('…');
        t
    }
}

/// Parses a value written as text (CLI, URL) for a key, checking its type and range.
pub fn parse_value(name: &str, text: &str) -> Result<Value> {
    let spec = spec(name).ok_or_else(|| unknown(name))?;
    let text = text.trim();
    let bad = |message: &str| SolverError::InvalidValue {
        key: name.to_string(),
        value: truncate(text, 40),
        message: message.to_string(),
    };
    let value = match spec.ty {
        KeyType::Choice(_) => Value::Text(text.to_string()),
        KeyType::FloatOrAuto { .. } if text == "auto" => Value::Text(text.to_string()),
        KeyType::Float { .. } | KeyType::FloatOrAuto { .. } | KeyType::Int { .. } => {
            let x: f64 = text
                .parse()
                .map_err(|_| bad(&format!("not a number; allowed {}", spec.ty.allowed())))?;
            Value::Num(x)
        }
    };
    check(spec, &value, text)?;
    Ok(value)
}

/// Checks a typed value against a key's type and range.
fn check(spec: &KeySpec, value: &Value, shown: &str) -> Result<()> {
    let out_of_range = || SolverError::OutOfRange {
        key: spec.name.to_string(),
        value: truncate(shown, 40),
        allowed: spec.ty.allowed(),
    };
    match (spec.ty, value) {
        (KeyType::Float { min, max }, Value::Num(x))
        | (KeyType::FloatOrAuto { min, max }, Value::Num(x)) => {
            if x.is_finite() && *x >= min && *x <= max {
                Ok(())
            } else {
                Err(out_of_range())
            }
        }
        (KeyType::FloatOrAuto { .. }, Value::Text(t)) if t == "auto" => Ok(()),
        (KeyType::Int { min, max }, Value::Num(x)) => {
            if x.is_finite() && x.fract() == 0.0 && *x >= min as f64 && *x <= max as f64 {
                Ok(())
            } else {
                Err(out_of_range())
            }
        }
        (KeyType::Choice(words), Value::Text(t)) => {
            if words.contains(&t.as_str()) {
                Ok(())
            } else {
                Err(out_of_range())
            }
        }
        _ => Err(SolverError::InvalidValue {
            key: spec.name.to_string(),
            value: truncate(shown, 40),
            message: format!("wrong type; allowed {}", spec.ty.allowed()),
        }),
    }
}

fn kind_of(name: &str, prefix: &str, suffix: &str) -> Option<MeshKind> {
    let mid = name.strip_prefix(prefix)?.strip_suffix(suffix)?;
    MeshKind::COMPOUND.into_iter().find(|k| k.key() == mid)
}

fn num(v: &Value) -> f64 {
    match v {
        Value::Num(x) => *x,
        Value::Text(_) => f64::NAN,
    }
}

fn text(v: &Value) -> &str {
    match v {
        Value::Text(t) => t,
        Value::Num(_) => "",
    }
}

/// Reads a key's value. `None` if the key is unknown or does not apply to the model.
pub fn get(params: &ModelParams, name: &str) -> Option<Value> {
    let n = Value::Num;
    match (params, name) {
        (_, "model") => Some(Value::Text(params.kind().name().to_string())),
        (ModelParams::Ravigneaux(p), _) => get_ravigneaux(p, name),
        (ModelParams::GearPair(p), _) => Some(n(match name {
            "backlash_um" => p.backlash_um,
            "te_um" => p.te_um.sin,
            "te_cos_um" => p.te_um.cos,
            "te_mean_um" => p.te_um.mean,
            "stiffness_variation" => p.stiffness_variation,
            "damping_ratio" => p.damping_ratio,
            "module_mm" => p.module_mm,
            "pressure_angle_deg" => p.pressure_angle_deg,
            "teeth_pinion" => f64::from(p.teeth_pinion),
            "teeth_gear" => f64::from(p.teeth_gear),
            "inertia_pinion_kg_m2" => p.inertia_pinion_kg_m2,
            "inertia_gear_kg_m2" => p.inertia_gear_kg_m2,
            "stiffness_n_m" => p.stiffness_n_m,
            "torque_pinion_nm" => p.torque_pinion_nm,
            _ => return None,
        })),
    }
}

fn get_ravigneaux(p: &RavigneauxParams, name: &str) -> Option<Value> {
    let n = |x: f64| Some(Value::Num(x));
    let te = |kind: MeshKind| &p.te_um[RavigneauxParams::kind_index(kind)];
    match name {
        "backlash_um" => {
            let b = p.backlash_um;
            n(if b.s1a == b.s2b && b.s1a == b.ab && b.s1a == b.rb {
                b.s1a
            } else {
                f64::NAN
            })
        }
        "te_um" => n(p.te_um[0].sin),
        "te_meshes" => Some(Value::Text(p.te_meshes.name().into())),
        "ring_support_radius_mm" => Some(match p.ring_support_radius_mm {
            Some(r) => Value::Num(r),
            None => Value::Text("auto".into()),
        }),
        "stiffness_variation" => n(p.stiffness_variation),
        "damping_ratio" => n(p.damping_ratio),
        "torque_s1_nm" => n(p.torque_s1_nm),
        "torque_s2_nm" => Some(match p.torque_s2_nm {
            Some(t) => Value::Num(t),
            None => Value::Text("auto".into()),
        }),
        "planets" => n(f64::from(p.planets)),
        "phasing" => Some(Value::Text(p.phasing.name().into())),
        "module_mm" => n(p.module_mm),
        "pressure_angle_deg" => n(p.pressure_angle_deg),
        "teeth_s1" => n(f64::from(p.teeth_s1)),
        "teeth_s2" => n(f64::from(p.teeth_s2)),
        "teeth_a" => n(f64::from(p.teeth_a)),
        "teeth_r" => n(f64::from(p.teeth_r)),
        "inertia_s1_kg_m2" => n(p.inertia_s1_kg_m2),
        "inertia_s2_kg_m2" => n(p.inertia_s2_kg_m2),
        "inertia_r_kg_m2" => n(p.inertia_r_kg_m2),
        "inertia_c_kg_m2" => n(p.inertia_c_kg_m2),
        "inertia_a_kg_m2" => n(p.inertia_a_kg_m2),
        "inertia_b_kg_m2" => n(p.inertia_b_kg_m2),
        "mass_a_kg" => n(p.mass_a_kg),
        "mass_b_kg" => n(p.mass_b_kg),
        "ring_support_n_m" => n(p.ring_support_n_m),
        _ => {
            if let Some(k) = kind_of(name, "stiffness_", "_n_m") {
                n(p.stiffness_n_m.get(k))
            } else if let Some(k) = kind_of(name, "backlash_", "_um") {
                n(p.backlash_um.get(k))
            } else if let Some(k) = kind_of(name, "te_sin_", "_um") {
                n(te(k).sin)
            } else if let Some(k) = kind_of(name, "te_cos_", "_um") {
                n(te(k).cos)
            } else if let Some(k) = kind_of(name, "te_mean_", "_um") {
                n(te(k).mean)
            } else if let Some(k) = kind_of(name, "phase_", "_deg") {
                n(p.phase_deg.get(k))
            } else {
                None
            }
        }
    }
}

/// Writes a key's value after checking its type and range. Setting `model`
/// replaces the whole set by that model's defaults.
pub fn set(params: &mut ModelParams, name: &str, value: Value) -> Result<()> {
    let spec = spec(name).ok_or_else(|| unknown(name))?;
    let shown = match &value {
        Value::Num(x) => format!("{x}"),
        Value::Text(t) => t.clone(),
    };
    check(spec, &value, &shown)?;
    // A typed -0 is stored (and so written back in links) as 0.
    let value = match value {
        Value::Num(x) => Value::Num(x + 0.0),
        v => v,
    };
    if name == "model" {
        let kind = ModelKind::from_name(text(&value)).unwrap_or(ModelKind::Ravigneaux);
        if kind != params.kind() {
            *params = ModelParams::defaults(kind);
        }
        return Ok(());
    }
    if !spec.applies.includes(params.kind()) {
        return Err(SolverError::KeyNotForModel {
            key: name.to_string(),
            model: params.kind().name().to_string(),
        });
    }
    let x = num(&value);
    let int = x as u32;
    match params {
        ModelParams::Ravigneaux(p) => set_ravigneaux(p, name, &value, x, int),
        ModelParams::GearPair(p) => set_gear_pair(p, name, x, int),
    }
    Ok(())
}

fn set_gear_pair(p: &mut GearPairParams, name: &str, x: f64, int: u32) {
    match name {
        "backlash_um" => p.backlash_um = x,
        "te_um" => p.te_um.sin = x,
        "te_cos_um" => p.te_um.cos = x,
        "te_mean_um" => p.te_um.mean = x,
        "stiffness_variation" => p.stiffness_variation = x,
        "damping_ratio" => p.damping_ratio = x,
        "module_mm" => p.module_mm = x,
        "pressure_angle_deg" => p.pressure_angle_deg = x,
        "teeth_pinion" => p.teeth_pinion = int,
        "teeth_gear" => p.teeth_gear = int,
        "inertia_pinion_kg_m2" => p.inertia_pinion_kg_m2 = x,
        "inertia_gear_kg_m2" => p.inertia_gear_kg_m2 = x,
        "stiffness_n_m" => p.stiffness_n_m = x,
        "torque_pinion_nm" => p.torque_pinion_nm = x,
        _ => {}
    }
}

fn set_ravigneaux(p: &mut RavigneauxParams, name: &str, value: &Value, x: f64, int: u32) {
    match name {
        "backlash_um" => p.backlash_um = PerKind::all(x),
        "te_um" => match p.te_meshes {
            TeMeshes::S1a => p.te_um[0].sin = x,
            TeMeshes::All => p.te_um.iter_mut().for_each(|te| te.sin = x),
        },
        "te_meshes" => {
            let now = if text(value) == "all" {
                TeMeshes::All
            } else {
                TeMeshes::S1a
            };
            // Switching the reading moves the shortcut's amplitude with it:
            // onto every kind, or off every kind but s1a.
            if now != p.te_meshes {
                let amplitude = p.te_um[0].sin;
                for te in p.te_um.iter_mut().skip(1) {
                    te.sin = if now == TeMeshes::All { amplitude } else { 0.0 };
                }
                p.te_meshes = now;
            }
        }
        "ring_support_radius_mm" => {
            p.ring_support_radius_mm = match value {
                Value::Num(r) => Some(*r),
                Value::Text(_) => None,
            }
        }
        "stiffness_variation" => p.stiffness_variation = x,
        "damping_ratio" => p.damping_ratio = x,
        "torque_s1_nm" => p.torque_s1_nm = x,
        "torque_s2_nm" => {
            p.torque_s2_nm = match value {
                Value::Num(t) => Some(*t),
                Value::Text(_) => None,
            }
        }
        "planets" => p.planets = int,
        "phasing" => {
            p.phasing = if text(value) == "sequential" {
                Phasing::Sequential
            } else {
                Phasing::InPhase
            }
        }
        "module_mm" => p.module_mm = x,
        "pressure_angle_deg" => p.pressure_angle_deg = x,
        "teeth_s1" => p.teeth_s1 = int,
        "teeth_s2" => p.teeth_s2 = int,
        "teeth_a" => p.teeth_a = int,
        "teeth_r" => p.teeth_r = int,
        "inertia_s1_kg_m2" => p.inertia_s1_kg_m2 = x,
        "inertia_s2_kg_m2" => p.inertia_s2_kg_m2 = x,
        "inertia_r_kg_m2" => p.inertia_r_kg_m2 = x,
        "inertia_c_kg_m2" => p.inertia_c_kg_m2 = x,
        "inertia_a_kg_m2" => p.inertia_a_kg_m2 = x,
        "inertia_b_kg_m2" => p.inertia_b_kg_m2 = x,
        "mass_a_kg" => p.mass_a_kg = x,
        "mass_b_kg" => p.mass_b_kg = x,
        "ring_support_n_m" => p.ring_support_n_m = x,
        _ => {
            let te = |k: MeshKind| RavigneauxParams::kind_index(k);
            if let Some(k) = kind_of(name, "stiffness_", "_n_m") {
                *p.stiffness_n_m.get_mut(k) = x;
            } else if let Some(k) = kind_of(name, "backlash_", "_um") {
                *p.backlash_um.get_mut(k) = x;
            } else if let Some(k) = kind_of(name, "te_sin_", "_um") {
                p.te_um[te(k)].sin = x;
            } else if let Some(k) = kind_of(name, "te_cos_", "_um") {
                p.te_um[te(k)].cos = x;
            } else if let Some(k) = kind_of(name, "te_mean_", "_um") {
                p.te_um[te(k)].mean = x;
            } else if let Some(k) = kind_of(name, "phase_", "_deg") {
                *p.phase_deg.get_mut(k) = x;
            }
        }
    }
}

/// Parses `KEY=VALUE` and applies it.
pub fn set_assignment(params: &mut ModelParams, assignment: &str) -> Result<()> {
    let (name, text) = assignment.split_once('=').ok_or_else(|| {
        SolverError::Parse(format!(
            "`{}` is not of the form KEY=VALUE",
            truncate(assignment, 60)
        ))
    })?;
    let value = parse_value(name.trim(), text)?;
    set(params, name.trim(), value)
}

/// The keys [`to_json`] writes for a model: all that apply, shortcuts excluded.
pub fn primary_keys(model: ModelKind) -> impl Iterator<Item = &'static KeySpec> {
    KEYS.iter()
        .filter(move |k| k.applies.includes(model) && !is_shortcut(k.name, model))
}

/// The whole parameter set as a flat JSON object (`model` first).
pub fn to_json(params: &ModelParams) -> Map<String, Json> {
    let mut map = Map::new();
    for spec in primary_keys(params.kind()) {
        if let Some(v) = get(params, spec.name) {
            map.insert(spec.name.to_string(), value_to_json(&v));
        }
    }
    map
}

/// Converts a typed value to JSON.
pub fn value_to_json(v: &Value) -> Json {
    match v {
        Value::Num(x) if x.fract() == 0.0 && x.abs() < 1e15 => Json::from(*x as i64),
        Value::Num(x) => serde_json::Number::from_f64(*x).map_or(Json::Null, Json::Number),
        Value::Text(t) => Json::String(t.clone()),
    }
}

fn json_to_value(name: &str, j: &Json) -> Result<Value> {
    match j {
        Json::Number(n) => n
            .as_f64()
            .map(Value::Num)
            .ok_or_else(|| SolverError::InvalidValue {
                key: name.to_string(),
                value: n.to_string(),
                message: "not representable as a number".into(),
            }),
        Json::String(s) => {
            // Numbers written as strings are accepted, like on the command line.
            parse_value(name, s)
        }
        other => Err(SolverError::InvalidValue {
            key: name.to_string(),
            value: truncate(&other.to_string(), 40),
            message: "expected a number or a word".into(),
        }),
    }
}

/// Applies every key of a flat JSON object (a parameter file) on top of
/// `params`. `model` is applied first, then shortcuts, then the rest.
pub fn apply_json(params: &mut ModelParams, object: &Map<String, Json>) -> Result<()> {
    if let Some(m) = object.get("model") {
        let v = json_to_value("model", m)?;
        set(params, "model", v)?;
    }
    let model = params.kind();
    let mut ordered: Vec<(&String, &Json)> = object.iter().filter(|(k, _)| *k != "model").collect();
    ordered.sort_by_key(|(k, _)| !is_shortcut(k, model));
    for (name, j) in ordered {
        let v = json_to_value(name, j)?;
        set(params, name, v)?;
    }
    Ok(())
}

/// Builds a parameter set from a flat JSON object: the named model's
/// defaults (Ravigneaux if `model` is absent) with the object's keys applied.
pub fn from_json(object: &Map<String, Json>) -> Result<ModelParams> {
    let mut params = ModelParams::default();
    apply_json(&mut params, object)?;
    Ok(params)
}

/// Parses a JSON text holding a flat parameter object.
pub fn from_json_str(text: &str) -> Result<ModelParams> {
    let json: Json = serde_json::from_str(text)
        .map_err(|e| SolverError::Parse(format!("parameter file is not valid JSON: {e}")))?;
    match json {
        Json::Object(map) => from_json(&map),
        _ => Err(SolverError::Parse(
            "parameter file must hold one flat JSON object of KEY: VALUE".into(),
        )),
    }
}
