//! Plain words for what a user reads: a key's name as a label ("backlash"),
//! a setting with its unit ("backlash 60 µm"), an allowed range in a
//! sentence ("between 0 and 1000 µm") and the message for a value out of
//! range ("Backlash must be between 0 and 1000 µm."). Key names and Rust
//! ranges stay in links, JSON and the CLI; the page shows these.

use crate::settings::{view_key, ViewType};
use solver::keys::{self, KeyType};

/// A unit as people write it (`µm`, `N m`), empty for dimensionless keys.
pub fn unit(key: &str) -> &'static str {
    let u = keys::spec(key)
        .map(|s| s.unit)
        .or_else(|| view_key(key).map(|v| v.unit))
        .unwrap_or("-");
    match u {
        "-" => "",
        "um" => "µm",
        "nm" | "N m" => "N m",
        other => other,
    }
}

/// A key's label for sentences, lower case: the control's label without
/// its parenthesis ("backlash b"), else the key in words with its unit
/// suffix dropped ("torque s2").
pub fn label(key: &str) -> String {
    if key == "model" {
        return "model".into();
    }
    if let Some(c) = crate::controls::controls()
        .into_iter()
        .find(|c| c.key == key)
    {
        let l = c.label.split(" (").next().unwrap_or(&c.label).trim();
        return lower_first(l);
    }
    let mut k = key;
    for suffix in ["_um", "_nm", "_deg", "_n_m", "_kg_m2", "_kg"] {
        if let Some(s) = k.strip_suffix(suffix) {
            k = s;
            break;
        }
    }
    k.replace('_', " ")
}

fn lower_first(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        // Keep symbols and abbreviations (Ω, TE, HBM) as written.
        Some(_) if c.clone().next().is_some_and(|n| n.is_uppercase()) => s.to_string(),
        Some(f) => f.to_lowercase().chain(c).collect(),
        None => String::new(),
    }
}

fn upper_first(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_uppercase().chain(c).collect(),
        None => String::new(),
    }
}

/// A number for a sentence: at most two decimals, no trailing zeros (0.45, 1.7, 2).
pub fn short(x: f64) -> String {
    let s = format!("{x:.2}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".into()
    } else {
        s.to_string()
    }
}

fn num(x: f64) -> String {
    if x != 0.0 && x.is_finite() && (x.abs() >= 1e6 || x.abs() < 1e-3) {
        // The exponent of the magnitude: a negative bound has one too.
        let e = x.abs().log10().floor();
        let m = x / 10f64.powf(e);
        format!("{}×10^{}", short(m), e as i32)
    } else {
        format!("{x}")
    }
}

/// [`label`] without a trailing one-letter symbol: "backlash 60 µm", not
/// "backlash b 60 µm" (the letter reads as part of the number); Ω and ξ stay.
fn short_label(key: &str) -> String {
    let l = label(key);
    match l.rsplit_once(' ') {
        Some((head, sym)) if sym.len() == 1 && sym.chars().all(|c| c.is_ascii_alphabetic()) => {
            head.to_string()
        }
        _ => l,
    }
}

/// A setting in words: "backlash 60 µm", "bifurcation sweep both".
pub fn setting(key: &str, value: &str) -> String {
    let u = unit(key);
    let v = match value.parse::<f64>() {
        Ok(x) => num(x),
        Err(_) => value.to_string(),
    };
    let l = short_label(key);
    if u.is_empty() || value == "auto" {
        format!("{l} {v}")
    } else {
        format!("{l} {v} {u}")
    }
}

/// What a key allows, in words: "between 0 and 1000 µm", "a whole number
/// between 2 and 400", "one of up, down, both".
pub fn allowed(key: &str) -> String {
    let u = unit(key);
    let with_unit = |x: String| if u.is_empty() { x } else { format!("{x} {u}") };
    if let Some(s) = keys::spec(key) {
        return match s.ty {
            KeyType::Float { min, max } => {
                with_unit(format!("between {} and {}", num(min), num(max)))
            }
            KeyType::Int { min, max } => format!("a whole number between {min} and {max}"),
            KeyType::Choice(w) => format!("one of {}", w.join(", ")),
            KeyType::FloatOrAuto { min, max } => with_unit(format!(
                "empty (computed) or between {} and {}",
                num(min),
                num(max)
            )),
        };
    }
    match view_key(key).map(|v| v.ty) {
        Some(ViewType::Float { min, max }) => {
            with_unit(format!("between {} and {}", num(min), num(max)))
        }
        Some(ViewType::Int { min, max }) => format!("a whole number between {min} and {max}"),
        Some(ViewType::Choice(w)) => {
            let w: Vec<String> = w.iter().map(|w| plain(w)).collect();
            format!("one of {}", w.join(", "))
        }
        Some(ViewType::Mesh) => "one of the model's meshes, or the worst".into(),
        None => "a known setting".into(),
    }
}

/// A control's tooltip in plain words: what the setting does and what it
/// allows ("Backlash: half-width b of the dead zone, on all meshes.
/// Allowed: between 0 and 1000 µm.").
pub fn tooltip(key: &str, description: &str) -> String {
    format!(
        "{}. Allowed: {}.",
        upper_first(&plain(description)),
        allowed(key)
    )
}

/// The symbols and key names of the settings' descriptions (written for
/// the command line) in words and symbols as people write them.
const PLAIN: [(&str, &str); 14] = [
    ("te_meshes", "the TE meshes setting"),
    ("torque_s1_nm", "the torque on s1"),
    (
        "(teeth_r - teeth_s2)/2",
        "(ring teeth − large-sun teeth) / 2",
    ),
    ("'Ec_all'", "“all meshes” curve"),
    (
        "k(t) = k_m (1 + v cos(omega t + gamma))",
        "k(t) = kₘ (1 + v cos(ωt + γ))",
    ),
    ("c = 2 xi sqrt(k_m m_e)", "c = 2 ξ √(kₘ mₑ)"),
    ("ratio xi", "ratio ξ"),
    (
        "adds m r_ca^2 to the carrier",
        "adds its mass times its orbit radius squared to the carrier",
    ),
    (
        "adds m r_cb^2 to the carrier",
        "adds its mass times its orbit radius squared to the carrier",
    ),
    (
        "auto = from teeth, module and pressure angle",
        "left empty, it is computed from the tooth counts, module and pressure angle",
    ),
    (
        "(auto = from the geometry)",
        "(left empty: computed from the teeth)",
    ),
    ("stiffness k_m", "stiffness kₘ"),
    ("backlash_um", "backlash b"),
    ("te_um", "TE amplitude"),
];

/// A description in plain words: the phrases of [`PLAIN`] replaced, and
/// Omega written Ω.
fn plain(text: &str) -> String {
    let mut t = text.to_string();
    for (from, to) in PLAIN {
        t = t.replace(from, to);
    }
    t.split(' ')
        .map(|w| if w == "Omega" { "Ω" } else { w })
        .collect::<Vec<_>>()
        .join(" ")
}

/// The message for a value a key does not allow, in a sentence:
/// "Backlash must be between 0 and 1000 µm (not 5000)."
pub fn must_be(key: &str, typed: &str) -> String {
    let typed = typed.trim();
    let shown = keys::truncate(typed, 40);
    let not = if typed.is_empty() {
        String::new()
    } else {
        format!(" (not {shown})")
    };
    format!(
        "{} must be {}{not}.",
        upper_first(&short_label(key)),
        allowed(key)
    )
}

/// `s` with its first letter in upper case ("TE 20 µm" stays as it is).
pub fn capitalize(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_uppercase().chain(c).collect(),
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every control's tooltip in plain words: no key name, no Rust range,
    /// the allowed values said. (Keys that are plain words, such as
    /// "model", may appear as words.)
    #[test]
    fn every_tooltip_is_plain_words() {
        for c in crate::controls::controls() {
            let t = tooltip(c.key, c.description);
            assert!(!c.key.contains('_') || !t.contains(c.key), "{t}");
            let code = t
                .split(|ch: char| !(ch.is_ascii_alphanumeric() || ch == '_'))
                .any(|w| w.contains('_'));
            assert!(!code && !t.contains("..="), "{t}");
            assert!(t.contains(&allowed(c.key)) && t.ends_with('.'), "{t}");
            assert!(!t.contains("NaN") && !t.contains("inf"), "{t}");
        }
        // A negative bound is written with its own exponent (the torque
        // tooltip once read "between NaN x 10^0 and 1 x 10^6 N m").
        assert_eq!(num(-1e6), "-1×10^6");
        assert_eq!(num(-2.5e-4), "-2.5×10^-4");
        assert_eq!(
            tooltip("backlash_um", "backlash: half-width b of the dead zone, on all meshes"),
            "Backlash: half-width b of the dead zone, on all meshes. Allowed: between 0 and 1000 µm."
        );
    }

    /// Every range reads as numbers, negative bounds included (a torque's
    /// range read "NaN×10^0").
    #[test]
    fn every_range_is_numbers() {
        assert_eq!(num(-1e6), "-1×10^6");
        assert_eq!(num(2.5e-5), "2.5×10^-5");
        for k in keys::KEYS
            .iter()
            .map(|k| k.name)
            .chain(crate::settings::VIEW_KEYS.iter().map(|k| k.name))
        {
            let text = allowed(k);
            assert!(
                !text.contains("NaN") && !text.contains("inf"),
                "{k}: {text}"
            );
        }
    }

    /// Every key the page can set reads without key names or Rust ranges.
    #[test]
    fn settings_and_messages_read_as_sentences() {
        assert_eq!(setting("backlash_um", "60"), "backlash 60 µm");
        assert_eq!(
            must_be("backlash_um", "5000"),
            "Backlash must be between 0 and 1000 µm (not 5000)."
        );
        assert_eq!(
            must_be("bif_points", "1.5"),
            "Bifurcation points must be a whole number between 2 and 1000 (not 1.5)."
        );
        assert_eq!(unit("damping_ratio"), "");
        assert!(setting("damping_ratio", "0.1").starts_with("damping ratio ξ"));
        for k in keys::KEYS
            .iter()
            .map(|k| k.name)
            .chain(crate::settings::VIEW_KEYS.iter().map(|k| k.name))
        {
            for text in [must_be(k, "x"), setting(k, "1")] {
                assert!(
                    !text.contains("..=")
                        && (!k.contains('_') || !text.contains(k))
                        && !text.contains(" um"),
                    "{text}"
                );
            }
        }
    }
}
