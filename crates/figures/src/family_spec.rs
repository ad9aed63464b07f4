//! Parameter families: one model parameter at several values, drawn as
//! overlaid curves (the frequency response) or as small multiples side by
//! side (the bifurcation diagram, phase portrait and Poincaré section), as
//! the paper's figures are.
//!
//! A family travels in a link as `family=KEY:V1,V2,...` (e.g.
//! `family=te_um:0,20,30`). Its first value is the current state's own
//! value of the key (member 0 is the page's main computation); the others
//! are computed as extra jobs in the workers. Parsing never panics: an
//! unknown key, too few or too many values, a value that is not a number,
//! out of range or that makes a model that cannot be built, is refused with
//! a message in words naming the value and the allowed range.

use crate::settings::fmt_exact;
use solver::keys::{self, KeyType, Value};
use solver::model::Model;
use solver::params::ModelParams;

/// Most members of a family (the work grows with each).
pub const MAX_MEMBERS: usize = 6;
/// Fewest members (one value is no family).
pub const MIN_MEMBERS: usize = 2;
/// The link key that carries the family.
pub const FAMILY_KEY: &str = "family";

/// A parameter a family can vary: its link key, its name in words and its
/// unit as people write it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FamilyKey {
    /// The link key, e.g. `te_um`.
    pub key: &'static str,
    /// Words, e.g. `TE`.
    pub words: &'static str,
    /// Unit as written after the number (empty if none).
    pub unit: &'static str,
}

/// The parameters a family can vary, in menu order.
pub const FAMILY_KEYS: &[FamilyKey] = &[
    FamilyKey {
        key: "te_um",
        words: "TE",
        unit: "µm",
    },
    FamilyKey {
        key: "backlash_um",
        words: "backlash",
        unit: "µm",
    },
    FamilyKey {
        key: "damping_ratio",
        words: "damping ratio",
        unit: "",
    },
    FamilyKey {
        key: "stiffness_variation",
        words: "stiffness variation",
        unit: "",
    },
    FamilyKey {
        key: "torque_s1_nm",
        words: "input torque",
        unit: "N m",
    },
];

/// Finds a family key by its link key.
pub fn family_key(key: &str) -> Option<&'static FamilyKey> {
    FAMILY_KEYS.iter().find(|k| k.key == key)
}

/// One parameter at several values.
#[derive(Debug, Clone, PartialEq)]
pub struct FamilySpec {
    /// The varied parameter.
    pub key: &'static FamilyKey,
    /// Its values; the first is the current state's.
    pub values: Vec<f64>,
}

impl FamilyKey {
    /// A value in words and units: "TE 20 µm", "damping ratio 0.06".
    pub fn label(&self, x: f64) -> String {
        if self.unit.is_empty() {
            format!("{} {}", self.words, fmt_exact(x))
        } else {
            format!("{} {} {}", self.words, fmt_exact(x), self.unit)
        }
    }

    /// The allowed values in words: "0 to 1000 µm".
    pub fn allowed(&self) -> String {
        let range = match keys::spec(self.key).map(|s| s.ty) {
            Some(KeyType::Float { min, max }) | Some(KeyType::FloatOrAuto { min, max }) => {
                format!("{} to {}", fmt_exact(min), fmt_exact(max))
            }
            Some(KeyType::Int { min, max }) => format!("whole numbers {min} to {max}"),
            _ => "numbers".into(),
        };
        if self.unit.is_empty() {
            range
        } else {
            format!("{range} {}", self.unit)
        }
    }
}

impl FamilySpec {
    /// Member `i`'s value in words, e.g. "TE 20 µm".
    pub fn label(&self, i: usize) -> String {
        self.values
            .get(i)
            .map_or_else(String::new, |x| self.key.label(*x))
    }

    /// The link value, e.g. `te_um:0,20,30` (numbers in their shortest
    /// exact form, so the link restores them exactly).
    pub fn encode(&self) -> String {
        let v: Vec<String> = self.values.iter().map(|x| fmt_exact(*x)).collect();
        format!("{}:{}", self.key.key, v.join(","))
    }

    /// Member `i`'s parameters: `base` with the key set to its value.
    pub fn member_params(
        &self,
        base: &ModelParams,
        i: usize,
    ) -> Result<ModelParams, solver::SolverError> {
        let mut p = base.clone();
        let x = self.values.get(i).copied().unwrap_or(f64::NAN);
        keys::set(&mut p, self.key.key, Value::Num(x))?;
        Ok(p)
    }
}

/// Parses the parts of a family: its key and its values as text ("0, 20,
/// 30" or "0,20,30"), checking each value against `base` (the model every
/// member shares). The message names the offending value and what is
/// allowed, in words.
pub fn parse_parts(key: &str, values: &str, base: &ModelParams) -> Result<FamilySpec, FamilyError> {
    let Some(fk) = family_key(key.trim()) else {
        let allowed: Vec<String> = FAMILY_KEYS
            .iter()
            .map(|k| format!("{} ({})", k.words, k.key))
            .collect();
        return Err(FamilyError::NotAFamilyKey {
            key: keys::truncate(key.trim(), 30),
            allowed: allowed.join(", "),
        });
    };
    let texts: Vec<&str> = values
        .split([',', ';', ' '])
        .map(str::trim)
        .filter(|t| !t.is_empty())
        .collect();
    if texts.len() < MIN_MEMBERS || texts.len() > MAX_MEMBERS {
        return Err(FamilyError::Count {
            words: fk.words,
            given: texts.len().min(1000),
        });
    }
    let mut out = Vec::with_capacity(texts.len());
    for t in texts {
        let bad = || FamilyError::NotAllowed {
            words: fk.words,
            value: keys::truncate(t, 20),
            allowed: fk.allowed(),
        };
        let x: f64 = t.parse().map_err(|_| bad())?;
        if !x.is_finite() {
            return Err(bad());
        }
        let x = if x == 0.0 { 0.0 } else { x };
        let mut p = base.clone();
        keys::set(&mut p, fk.key, Value::Num(x)).map_err(|_| bad())?;
        if let Err(source) = Model::new(&p) {
            return Err(FamilyError::CannotCompute {
                member: fk.label(x),
                source,
            });
        }
        if out.contains(&x) {
            return Err(FamilyError::Twice {
                member: fk.label(x),
            });
        }
        out.push(x);
    }
    Ok(FamilySpec {
        key: fk,
        values: out,
    })
}

/// Parses a link's family value, `KEY:V1,V2,...`.
pub fn parse(text: &str, base: &ModelParams) -> Result<FamilySpec, FamilyError> {
    match text.split_once(':') {
        Some((k, v)) => parse_parts(k, v, base),
        None => Err(FamilyError::NotKeyValues {
            text: keys::truncate(text, 40),
        }),
    }
}

/// Why a family typed on the page or carried by a link was refused: the
/// value and what is allowed, in words.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FamilyError {
    /// A key no family varies.
    #[error("A family cannot vary `{key}`; it can vary {allowed}.")]
    NotAFamilyKey {
        /// The key as given (shortened).
        key: String,
        /// The keys a family varies, in words with their keys.
        allowed: String,
    },
    /// Too few or too many values.
    #[error(
        "A family of {words} needs {MIN_MEMBERS} to {MAX_MEMBERS} values; {given} were given."
    )]
    Count {
        /// The varied parameter in words.
        words: &'static str,
        /// How many values were given (at most 1000 said).
        given: usize,
    },
    /// A value that is not a number in the key's range.
    #[error("{words} {value} is not allowed in a family: allowed {allowed}.")]
    NotAllowed {
        /// The varied parameter in words.
        words: &'static str,
        /// The value as given (shortened).
        value: String,
        /// The allowed range in words.
        allowed: String,
    },
    /// A member whose model cannot be built.
    #[error("{member} cannot be computed with these settings: {source}")]
    CannotCompute {
        /// The member in words ("TE 20 µm").
        member: String,
        /// The solver's reason.
        source: solver::SolverError,
    },
    /// A value given twice.
    #[error("{member} appears twice in the family.")]
    Twice {
        /// The member in words.
        member: String,
    },
    /// A link's family value without its colon.
    #[error("family = {text} is not of the form parameter:values (e.g. te_um:0,20,30); ignored.")]
    NotKeyValues {
        /// The value as given (shortened).
        text: String,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    fn base() -> ModelParams {
        ModelParams::default()
    }

    #[test]
    fn a_family_round_trips_exactly() {
        let f = parse("te_um:0,20,30", &base()).unwrap();
        assert_eq!(f.key.key, "te_um");
        assert_eq!(f.values, vec![0.0, 20.0, 30.0]);
        assert_eq!(f.encode(), "te_um:0,20,30");
        assert_eq!(f.label(1), "TE 20 µm");
        let g = parse("backlash_um:50,100.125,0.1,200", &base()).unwrap();
        assert_eq!(parse(&g.encode(), &base()).unwrap(), g);
        assert_eq!(g.label(0), "backlash 50 µm");
        let d = parse("damping_ratio:0.03, 0.06", &base()).unwrap();
        assert_eq!(d.label(1), "damping ratio 0.06");
        // Each member's parameters carry its value.
        let p = f.member_params(&base(), 2).unwrap();
        assert_eq!(keys::get(&p, "te_um"), Some(Value::Num(30.0)));
    }

    #[test]
    fn bad_families_are_named_with_the_value_and_the_range() {
        let b = base();
        let e = parse("foo_um:1,2", &b).unwrap_err().to_string();
        assert!(e.contains("foo_um") && e.contains("TE (te_um)"), "{e}");
        let e = parse("te_um:1,2,3,4,5,6,7", &b).unwrap_err().to_string();
        assert!(e.contains("2 to 6") && e.contains('7'), "{e}");
        let e = parse("te_um:20", &b).unwrap_err().to_string();
        assert!(e.contains("2 to 6"), "{e}");
        let e = parse("te_um:0,NaN", &b).unwrap_err().to_string();
        assert!(e.contains("TE NaN") && e.contains("µm"), "{e}");
        let e = parse("backlash_um:50,5000", &b).unwrap_err().to_string();
        assert!(
            e.contains("backlash 5000") && e.contains("0 to 1000 µm"),
            "{e}"
        );
        let e = parse("te_um:0,abc", &b).unwrap_err().to_string();
        assert!(e.contains("TE abc"), "{e}");
        let e = parse("te_um:inf,1", &b).unwrap_err().to_string();
        assert!(e.contains("TE inf"), "{e}");
        let e = parse("te_um:10,10", &b).unwrap_err().to_string();
        assert!(e.contains("twice"), "{e}");
        let e = parse("te_um", &b).unwrap_err().to_string();
        assert!(e.contains("parameter:values"), "{e}");
        // Words only in the allowed range, no key syntax there.
        assert_eq!(family_key("te_um").unwrap().allowed(), "-1000 to 1000 µm");
    }
}
