//! Shareable links: the whole [`Settings`] as a URL query string, and back.
//!
//! Parameters use the solver's flat keys (`solver::keys`), exactly as the
//! CLI's `--set KEY=VALUE` and JSON parameter files do; view options use
//! [`crate::settings::VIEW_KEYS`]. A link writes `model`, the parameters that
//! differ from that model's defaults (the backlash and TE shortcuts when they
//! say the same thing more briefly) and every view option. Numbers are
//! written in Rust's shortest round-trip form, so opening a link restores
//! every value exactly.
//!
//! A/B comparison: a pinned state "A" travels in the one key `a`, whose
//! value is A's own link (percent-encoded), so a link restores both the
//! current state B and the comparison; an `a` inside `a` is ignored, and so
//! (with a message) is an `a` that names no setting at all (`a=x`), rather
//! than turning the comparison on with defaults.
//!
//! Decoding never fails and never panics: a malformed or out-of-range value
//! yields a message naming the key and its allowed range, and that key keeps
//! its default while the others apply. The text of a link is untrusted: the
//! page shows these messages with `textContent` only.

use crate::family_spec::{FamilySpec, FAMILY_KEY};
use crate::panels::PANELS_KEY;
use crate::settings::{fmt_exact, mesh_names, view_key, Settings, ViewOptions, AXIS_KEY};
use solver::keys::{self, Value};
use solver::model::Model;
use solver::params::{ModelKind, ModelParams};

/// At most this many `key=value` pairs are read from one link.
pub const MAX_PAIRS: usize = 400;
/// Links longer than this (characters) are cut before decoding.
pub const MAX_LINK_CHARS: usize = 64 * 1024;

/// The result of decoding a link.
#[derive(Debug, Clone, PartialEq)]
pub struct Decoded {
    /// The settings: the link's valid values over the defaults.
    pub settings: Settings,
    /// One message per rejected key or pair, naming it and what is allowed.
    pub issues: Vec<String>,
    /// The pinned state A of an A/B comparison, if the link carries one.
    pub pinned: Option<Settings>,
    /// The parameter family (`family=KEY:V1,V2,...`), if the link carries a
    /// valid one; its first value is applied to `settings`.
    pub family: Option<FamilySpec>,
    /// The meshes of the frequency response's side-by-side panels
    /// (`panels=MESH,MESH,...`), if the link carries valid ones.
    pub panels: Option<Vec<String>>,
}

/// The key that carries the pinned state A.
pub const PINNED_KEY: &str = "a";

/// Percent-decodes a query component (`+` is a space). Invalid escapes stay
/// as written; invalid UTF-8 becomes U+FFFD.
pub fn percent_decode(s: &str) -> String {
    let bytes = s.as_bytes();
    let mut out = Vec::with_capacity(bytes.len());
    let mut i = 0;
    while i < bytes.len() {
        match bytes[i] {
            b'+' => out.push(b' '),
            b'%' if i + 2 < bytes.len() => {
                let hex = |b: u8| (b as char).to_digit(16);
                match (hex(bytes[i + 1]), hex(bytes[i + 2])) {
                    (Some(h), Some(l)) => {
                        out.push((h * 16 + l) as u8);
                        i += 2;
                    }
                    _ => out.push(b'%'),
                }
            }
            b => out.push(b),
        }
        i += 1;
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Percent-encodes a query component: everything but `A-Z a-z 0-9 - _ . ~`.
pub fn percent_encode(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for b in s.bytes() {
        if b.is_ascii_alphanumeric() || matches!(b, b'-' | b'_' | b'.' | b'~') {
            out.push(b as char);
        } else {
            out.push_str(&format!("%{b:02X}"));
        }
    }
    out
}

/// Splits a query string (with or without the leading `?`) into decoded pairs.
fn pairs(query: &str, issues: &mut Vec<String>) -> Vec<(String, String)> {
    let mut query = query.strip_prefix('?').unwrap_or(query);
    if query.len() > MAX_LINK_CHARS {
        let mut cut = MAX_LINK_CHARS;
        while !query.is_char_boundary(cut) {
            cut -= 1;
        }
        query = &query[..cut];
        issues.push(format!(
            "the link is longer than {MAX_LINK_CHARS} characters; the rest was ignored"
        ));
    }
    let mut out: Vec<(String, String)> = Vec::new();
    for (n, part) in query.split('&').filter(|p| !p.is_empty()).enumerate() {
        if n >= MAX_PAIRS {
            issues.push(format!(
                "the link has more than {MAX_PAIRS} settings; the rest were ignored"
            ));
            break;
        }
        match part.split_once('=') {
            Some((k, v)) => {
                let (k, v) = (percent_decode(k), percent_decode(v));
                // A key given twice is named, not settled silently: the
                // last value counts (a setting added to the end of a link
                // overrides), the earlier one is dropped.
                if let Some(i) = out.iter().position(|(seen, _)| *seen == k) {
                    let (_, earlier) = out.remove(i);
                    issues.push(format!(
                        "`{}` is given twice; its last value `{}` counts, `{}` was ignored",
                        keys::truncate(&k, 40),
                        keys::truncate(&v, 40),
                        keys::truncate(&earlier, 40)
                    ));
                }
                out.push((k, v));
            }
            None => issues.push(format!(
                "`{}` is not of the form key=value; ignored",
                keys::truncate(&percent_decode(part), 40)
            )),
        }
    }
    out
}

/// A value as a link writes it: a number exactly, a text as it is.
pub fn value_text(v: &Value) -> String {
    match v {
        Value::Num(x) => fmt_exact(*x),
        Value::Text(t) => t.clone(),
    }
}

/// Applies one parameter key; the error names the key and the allowed range.
fn apply_param(params: &mut ModelParams, key: &str, text: &str) -> Result<(), solver::SolverError> {
    keys::set(params, key, keys::parse_value(key, text)?)
}

/// Decodes a query string into settings plus messages (and the pinned
/// state A, if any). Never panics.
pub fn decode(query: &str) -> Decoded {
    let mut issues = Vec::new();
    let mut all = pairs(query, &mut issues);
    let family_text = all
        .iter()
        .rev()
        .find(|(k, _)| k == FAMILY_KEY)
        .map(|(_, v)| v.clone());
    all.retain(|(k, _)| k != FAMILY_KEY);
    let panels_text = all
        .iter()
        .rev()
        .find(|(k, _)| k == PANELS_KEY)
        .map(|(_, v)| v.clone());
    all.retain(|(k, _)| k != PANELS_KEY);
    let mut pinned = None;
    if let Some(pos) = all.iter().rposition(|(k, _)| k == PINNED_KEY) {
        let (_, inner) = all.remove(pos);
        all.retain(|(k, _)| k != PINNED_KEY);
        let (a, a_issues) = decode_one(&inner);
        if names_a_setting(&inner) {
            issues.extend(a_issues.into_iter().map(|i| format!("A (pinned): {i}")));
            pinned = Some(a);
        } else {
            issues.push(format!(
                "a = {} names no setting, so it is no pinned state A; ignored",
                keys::truncate(&inner, 40)
            ));
        }
    }
    let (mut settings, more) = decode_one_pairs(all);
    issues.extend(more);
    let family = family_text.and_then(|t| match crate::family_spec::parse(&t, &settings.params) {
        Ok(f) => {
            // The first member is the current state.
            match f.member_params(&settings.params, 0) {
                Ok(p) => {
                    settings.params = p;
                    Some(f)
                }
                Err(e) => {
                    issues.push(e.to_string());
                    None
                }
            }
        }
        Err(e) => {
            issues.push(e.to_string());
            None
        }
    });
    let panels = panels_text.and_then(|t| {
        crate::panels::parse(&t, &mesh_names(&settings.params))
            .map_err(|e| issues.push(e.to_string()))
            .ok()
    });
    Decoded {
        settings,
        issues,
        pinned,
        family,
        panels,
    }
}

/// Whether a pinned state's text has at least one `key=value` pair whose key
/// is a parameter or view key (its value may still be refused, with a
/// message): a link made by [`encode_ab`] always starts with `model=`.
fn names_a_setting(query: &str) -> bool {
    let mut ignored = Vec::new();
    pairs(query, &mut ignored)
        .iter()
        .any(|(k, _)| k != PINNED_KEY && (keys::spec(k).is_some() || view_key(k).is_some()))
}

/// Decodes one state (a nested `a` is named and ignored).
fn decode_one(query: &str) -> (Settings, Vec<String>) {
    let mut issues = Vec::new();
    let mut all = pairs(query, &mut issues);
    if all.iter().any(|(k, _)| k == PINNED_KEY) {
        all.retain(|(k, _)| k != PINNED_KEY);
        issues.push("a pinned state inside the pinned state was ignored".into());
    }
    let (settings, more) = decode_one_pairs(all);
    issues.extend(more);
    (settings, issues)
}

/// A link's bad value in a sentence ("From the link: Backlash must be
/// between 0 and 1000 µm (not 5000); the default was kept."); other
/// problems (a key the model does not take, an unknown key) as they are.
fn plain_issue(k: &str, v: &str, e: impl std::fmt::Display) -> String {
    let out_of_range = match keys::spec(k) {
        Some(_) => keys::parse_value(k, v).is_err(),
        None => view_key(k).is_some_and(|vk| !matches!(vk.ty, crate::settings::ViewType::Mesh)),
    };
    if out_of_range {
        let m = crate::words::must_be(k, v);
        format!(
            "From the link: {}; the default was kept.",
            m.trim_end_matches('.')
        )
    } else {
        e.to_string()
    }
}

fn decode_one_pairs(all: Vec<(String, String)>) -> (Settings, Vec<String>) {
    let mut issues = Vec::new();
    let mut settings = Settings::default();

    // The model first: it resets the parameters to that model's defaults.
    if let Some((_, v)) = all.iter().rev().find(|(k, _)| k == "model") {
        if let Err(e) = apply_param(&mut settings.params, "model", v) {
            issues.push(e.to_string());
        }
    }
    let model = settings.params.kind();
    let is_param = |k: &str| k != "model" && view_key(k).is_none();
    // Then shortcuts, then the rest, so a per-kind key beats `backlash_um`.
    let mut param_pairs: Vec<&(String, String)> = all.iter().filter(|(k, _)| is_param(k)).collect();
    param_pairs.sort_by_key(|(k, _)| !keys::is_shortcut(k, model));
    let mut applied: Vec<&(String, String)> = Vec::new();
    for pair in param_pairs {
        match apply_param(&mut settings.params, &pair.0, &pair.1) {
            Ok(()) => applied.push(pair),
            Err(e) => issues.push(plain_issue(&pair.0, &pair.1, e)),
        }
    }
    // Cross-key rules (tooth counts, torque balance): if the combination
    // cannot be built, re-apply key by key and drop those that break it.
    if Model::new(&settings.params).is_err() {
        let mut params = ModelParams::defaults(model);
        for (k, v) in applied {
            let mut candidate = params.clone();
            if apply_param(&mut candidate, k, v).is_ok() {
                match Model::new(&candidate) {
                    Ok(_) => params = candidate,
                    Err(e) => issues.push(format!(
                        "{} = {} was not applied: {e}",
                        keys::truncate(k, 40),
                        keys::truncate(v, 40)
                    )),
                }
            }
        }
        settings.params = params;
    }

    let meshes = mesh_names(&settings.params);
    if let Some(first) = meshes.first() {
        // The default plotted mesh must exist in the chosen model.
        if !meshes.contains(&settings.view.mesh.text().to_string()) {
            settings.view.mesh = crate::settings::MeshSel::Named(first.clone());
        }
    }
    for (k, v) in all.iter().filter(|(k, _)| view_key(k).is_some()) {
        if let Err(e) = settings.view.set(k, v, &meshes) {
            issues.push(plain_issue(k, v, e));
        }
    }
    if let Some(e) = settings.view.check_range() {
        issues.push(e);
    }
    (settings, issues)
}

/// The parameter assignments that differ from the model's defaults, in key
/// table order, with the backlash and TE shortcuts used where they apply.
pub fn param_diff(params: &ModelParams) -> Vec<(String, String)> {
    let kind = params.kind();
    let defaults = ModelParams::defaults(kind);
    let mut out = Vec::new();
    let mut skip: Vec<&str> = Vec::new();
    if kind == ModelKind::Ravigneaux {
        for (shortcut, covers) in [
            (
                "backlash_um",
                &[
                    "backlash_s1a_um",
                    "backlash_s2b_um",
                    "backlash_ab_um",
                    "backlash_rb_um",
                ][..],
            ),
            ("te_um", &["te_sin_s1a_um"][..]),
        ] {
            let now = keys::get(params, shortcut);
            let was = keys::get(&defaults, shortcut);
            if let Some(Value::Num(x)) = now {
                if x.is_finite() {
                    skip.extend_from_slice(covers);
                    if now != was {
                        out.push((shortcut.to_string(), fmt_exact(x)));
                    }
                }
            }
        }
    }
    for spec in keys::primary_keys(kind) {
        if spec.name == "model" || skip.contains(&spec.name) {
            continue;
        }
        let now = keys::get(params, spec.name);
        if now != keys::get(&defaults, spec.name) {
            if let Some(v) = now {
                out.push((spec.name.to_string(), value_text(&v)));
            }
        }
    }
    out
}

/// Encodes settings as a query string (without the `?`).
pub fn encode(settings: &Settings) -> String {
    let mut parts = vec![format!("model={}", settings.params.kind().name())];
    for (k, v) in param_diff(&settings.params) {
        parts.push(format!("{}={}", percent_encode(&k), percent_encode(&v)));
    }
    for key in crate::settings::VIEW_KEYS {
        if let Some(v) = settings.view.get(key.name) {
            // The speed axes' unit and Kv's inputs only when they are
            // not the defaults, so that a link of the default state is
            // what it always was.
            if crate::settings::SPARSE_KEYS.contains(&key.name)
                && ViewOptions::default().get(key.name).as_deref() == Some(v.as_str())
            {
                continue;
            }
            parts.push(format!("{}={}", key.name, percent_encode(&v)));
        }
    }
    parts.join("&")
}

/// Encodes the current state and, if pinned, the state A (in `a`).
pub fn encode_ab(settings: &Settings, pinned: Option<&Settings>) -> String {
    let mut q = encode(settings);
    if let Some(a) = pinned {
        q.push_str(&format!("&{PINNED_KEY}={}", percent_encode(&encode(a))));
    }
    q
}

/// Encodes the current state, the pinned state A (in `a`) if any, the
/// parameter family (in `family`) if any and the frequency response's
/// mesh panels (in `panels`) if any.
pub fn encode_all(
    settings: &Settings,
    pinned: Option<&Settings>,
    family: Option<&FamilySpec>,
    panels: Option<&[String]>,
) -> String {
    let mut q = encode_ab(settings, pinned);
    if let Some(f) = family {
        q.push_str(&format!("&{FAMILY_KEY}={}", percent_encode(&f.encode())));
    }
    if let Some(p) = panels {
        let text = crate::panels::encode(p);
        q.push_str(&format!("&{PANELS_KEY}={}", percent_encode(&text)));
    }
    q
}

/// The settings in which A and B differ, as `key=value` texts for A and
/// for B (at most `max` keys each; "same settings" if none).
pub fn ab_difference(a: &Settings, b: &Settings, max: usize) -> (String, String) {
    let pairs_of = |s: &Settings| -> Vec<(String, String)> {
        let mut v = vec![("model".to_string(), s.params.kind().name().to_string())];
        v.extend(param_diff(&s.params));
        // The speed axes' unit is how a state is read, not the state.
        for key in crate::settings::VIEW_KEYS
            .iter()
            .filter(|k| k.name != AXIS_KEY)
        {
            if let Some(t) = s.view.get(key.name) {
                v.push((key.name.to_string(), t));
            }
        }
        v
    };
    let (pa, pb) = (pairs_of(a), pairs_of(b));
    // A key's value in a state: its own text, or the state's value of a
    // parameter that equals its model's default (and so is not in the link).
    let value_in = |v: &[(String, String)], s: &Settings, k: &str| {
        v.iter()
            .find(|(kk, _)| kk == k)
            .map(|(_, x)| x.clone())
            .or_else(|| keys::get(&s.params, k).map(|x| value_text(&x)))
            .unwrap_or_else(|| "-".into())
    };
    let mut keys_seen: Vec<String> = Vec::new();
    for (k, _) in pa.iter().chain(pb.iter()) {
        if !keys_seen.contains(k) && value_in(&pa, a, k) != value_in(&pb, b, k) {
            keys_seen.push(k.clone());
        }
    }

    // Model parameters first, then view options.
    keys_seen.sort_by_key(|k| view_key(k).is_some());
    if keys_seen.is_empty() {
        return ("same settings".into(), "same settings".into());
    }
    let more = keys_seen.len().saturating_sub(max);
    let text = |v: &[(String, String)], s: &Settings| {
        let mut t: Vec<String> = keys_seen
            .iter()
            .take(max)
            .map(|k| crate::words::setting(k, &value_in(v, s, k)))
            .collect();
        if more > 0 {
            t.push(format!("+{more} more"));
        }
        t.join(", ")
    };
    (text(&pa, a), text(&pb, b))
}

#[cfg(test)]
#[path = "link_tests.rs"]
mod tests;
