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
//! The excitation's waveforms (`stiffness_wave*`, `contact_ratio*`,
//! `stiffness_ramp`, `stiffness_harmonics`, and the TE's harmonics 2 to 6,
//! `te_cos<n>_*um`, `te_sin<n>_*um`) are written by [`to_json`] only where
//! they differ from the defaults: see [`crate::waveform`].
//!
//! Two keys are readings of the seed paper where it is ambiguous:
//! `te_meshes` (its Fig. 2 varies a TE written `Ec_all`: on every mesh, or on
//! the s1a meshes as its Table 1's sun-s1 error) and `ring_support_radius_mm`
//! (its Table 1 prints the ring's radius as 15.79 mm, which `docs/model.md`
//! reads as a slip for the base radius 157.9 mm; the support spring acts
//! there).

use crate::error::{Result, SolverError};
use crate::params::{
    GearPairParams, MeshKind, ModelKind, ModelParams, PerKind, Phasing, RavigneauxParams, TeMeshes,
};
use serde_json::{Map, Value as Json};

mod access;
mod table;

pub use access::{get, set};
pub use table::KEYS;

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
    /// A key of the excitation's waveforms, written by [`to_json`] only
    /// where it differs from the model's default (so every output of the
    /// seed's one-harmonic model stays as it was).
    pub extension: bool,
    /// One line for docs and tooltips.
    pub description: &'static str,
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
    let defaults = ModelParams::defaults(params.kind());
    for spec in primary_keys(params.kind()) {
        if let Some(v) = get(params, spec.name) {
            if spec.extension && get(&defaults, spec.name).as_ref() == Some(&v) {
                continue;
            }
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
