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
use crate::settings::{fmt_exact, mesh_names, view_key, Settings};
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
    let mut out = Vec::new();
    for (n, part) in query.split('&').filter(|p| !p.is_empty()).enumerate() {
        if n >= MAX_PAIRS {
            issues.push(format!(
                "the link has more than {MAX_PAIRS} settings; the rest were ignored"
            ));
            break;
        }
        match part.split_once('=') {
            Some((k, v)) => out.push((percent_decode(k), percent_decode(v))),
            None => issues.push(format!(
                "`{}` is not of the form key=value; ignored",
                keys::truncate(&percent_decode(part), 40)
            )),
        }
    }
    out
}

pub(crate) fn value_text(v: &Value) -> String {
    match v {
        Value::Num(x) => fmt_exact(*x),
        Value::Text(t) => t.clone(),
    }
}

/// Applies one parameter key; the error names the key and the allowed range.
fn apply_param(params: &mut ModelParams, key: &str, text: &str) -> Result<(), String> {
    let value = keys::parse_value(key, text).map_err(|e| e.to_string())?;
    keys::set(params, key, value).map_err(|e| e.to_string())
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
                    issues.push(e);
                    None
                }
            }
        }
        Err(e) => {
            issues.push(e);
            None
        }
    });
    let panels = panels_text.and_then(|t| {
        crate::panels::parse(&t, &mesh_names(&settings.params))
            .map_err(|e| issues.push(e))
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
fn plain_issue(k: &str, v: &str, e: String) -> String {
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
        e
    }
}

fn decode_one_pairs(all: Vec<(String, String)>) -> (Settings, Vec<String>) {
    let mut issues = Vec::new();
    let mut settings = Settings::default();

    // The model first: it resets the parameters to that model's defaults.
    if let Some((_, v)) = all.iter().rev().find(|(k, _)| k == "model") {
        if let Err(e) = apply_param(&mut settings.params, "model", v) {
            issues.push(e);
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
        for key in crate::settings::VIEW_KEYS {
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
mod tests {
    use super::*;
    use crate::settings::{MeshSel, ViewOptions};
    use proptest::prelude::*;

    #[test]
    fn defaults_round_trip() {
        let s = Settings::default();
        let q = encode(&s);
        assert!(
            q.starts_with("model=ravigneaux&omega=0.35&mesh=s1a1"),
            "{q}"
        );
        let d = decode(&q);
        assert!(d.issues.is_empty(), "{:?}", d.issues);
        assert_eq!(d.settings, s);
    }

    #[test]
    fn changed_values_restore_exactly() {
        let mut s = Settings::default();
        keys::set_assignment(&mut s.params, "backlash_um=123.456789012345").unwrap();
        keys::set_assignment(&mut s.params, "te_um=0.1").unwrap();
        keys::set_assignment(&mut s.params, "te_cos_rb_um=-7.25").unwrap();
        keys::set_assignment(&mut s.params, "phasing=sequential").unwrap();
        keys::set_assignment(&mut s.params, "planets=5").unwrap();
        keys::set_assignment(&mut s.params, "damping_ratio=0.0333333333333333").unwrap();
        s.view.omega = 1.0 / 3.0;
        s.view.mesh = MeshSel::Worst;
        s.view.bif_dir = solver::sweep::Directions::Down;
        let q = encode(&s);
        assert!(q.contains("backlash_um=123.456789012345"), "{q}");
        assert!(
            q.contains("te_um=0.1") && !q.contains("te_sin_s1a_um"),
            "{q}"
        );
        let d = decode(&q);
        assert!(d.issues.is_empty(), "{:?}", d.issues);
        assert_eq!(d.settings, s);
        // Per-kind backlash that differ are written per kind.
        keys::set_assignment(&mut s.params, "backlash_ab_um=40").unwrap();
        let q = encode(&s);
        assert!(
            q.contains("backlash_ab_um=40") && !q.contains("backlash_um="),
            "{q}"
        );
        assert_eq!(decode(&q).settings, s);
    }

    #[test]
    fn gear_pair_round_trips() {
        let mut s = Settings::default();
        keys::set_assignment(&mut s.params, "model=gear-pair").unwrap();
        keys::set_assignment(&mut s.params, "backlash_um=55").unwrap();
        s.view.mesh = MeshSel::Named("pg".into());
        let d = decode(&encode(&s));
        assert!(d.issues.is_empty(), "{:?}", d.issues);
        assert_eq!(d.settings, s);
        // A compound-only key on the gear pair is named, the rest applies.
        let d = decode("model=gear-pair&planets=4&backlash_um=20");
        assert_eq!(d.issues.len(), 1, "{:?}", d.issues);
        assert!(d.issues[0].contains("planets"));
        assert_eq!(
            keys::get(&d.settings.params, "backlash_um"),
            Some(Value::Num(20.0))
        );
        assert_eq!(d.settings.view.mesh, MeshSel::Named("pg".into()));
    }

    #[test]
    fn bad_values_are_named_with_their_range_and_others_kept() {
        let d = decode("?backlash_um=5000&te_um=30&omega=abc&bif_points=100000000&damping_ratio=NaN&foo=1&oops");
        let all = d.issues.join("\n");
        assert!(
            all.contains("Backlash must be between 0 and 1000 µm (not 5000)"),
            "{all}"
        );
        assert!(
            all.contains("Selected Ω must be between 0.01 and 20 (not abc)"),
            "{all}"
        );
        assert!(
            all.contains("Bifurcation points must be a whole number between 2 and 1000"),
            "{all}"
        );
        assert!(all.contains("Damping ratio ξ must be"), "{all}");
        assert!(!all.contains("..="), "{all}");
        assert!(all.contains("foo"), "{all}");
        assert!(all.contains("oops"), "{all}");
        assert_eq!(
            keys::get(&d.settings.params, "te_um"),
            Some(Value::Num(30.0))
        );
        assert_eq!(
            keys::get(&d.settings.params, "backlash_um"),
            Some(Value::Num(100.0))
        );
        assert_eq!(
            d.settings.view.bif_points,
            ViewOptions::default().bif_points
        );
    }

    #[test]
    fn combinations_that_cannot_be_built_drop_the_breaking_key() {
        // An explicit s2 torque that does not balance s1: the model refuses it.
        let d = decode("torque_s2_nm=5&backlash_um=150");
        assert!(
            d.issues.iter().any(|i| i.contains("torque_s2_nm")),
            "{:?}",
            d.issues
        );
        assert_eq!(
            keys::get(&d.settings.params, "backlash_um"),
            Some(Value::Num(150.0))
        );
        assert!(Model::new(&d.settings.params).is_ok());
    }

    #[test]
    fn a_pinned_state_rides_along_and_restores_exactly() {
        let mut a = Settings::default();
        keys::set_assignment(&mut a.params, "backlash_um=100").unwrap();
        a.view.omega = 0.5;
        let mut b = Settings::default();
        keys::set_assignment(&mut b.params, "backlash_um=150").unwrap();
        keys::set_assignment(&mut b.params, "te_um=35").unwrap();
        let q = encode_ab(&b, Some(&a));
        assert!(q.contains("&a=model%3Dravigneaux"), "{q}");
        let d = decode(&q);
        assert!(d.issues.is_empty(), "{:?}", d.issues);
        assert_eq!(d.settings, b);
        assert_eq!(d.pinned.as_ref(), Some(&a));
        // Without a pinned state there is no `a`, and none comes back.
        assert_eq!(decode(&encode_ab(&b, None)).pinned, None);
        // The difference names the keys that differ, per side.
        let (ta, tb) = ab_difference(&a, &b, 3);
        assert!(
            ta.contains("backlash 100 µm") && tb.contains("backlash 150 µm"),
            "{ta} | {tb}"
        );
        assert!(
            ta.contains("selected Ω 0.5") && tb.contains("TE amplitude 35 µm"),
            "{ta} | {tb}"
        );
        assert_eq!(ab_difference(&a, &a, 3).0, "same settings");
        // Bad values inside A are named as A's; a nested `a` is ignored.
        let d = decode("backlash_um=150&a=backlash_um%3D5000%26a%3Dx");
        assert_eq!(d.issues.len(), 2, "{:?}", d.issues);
        assert!(d.issues.iter().all(|i| i.starts_with("A (pinned): ")));
        assert!(d.pinned.is_some());
    }

    #[test]
    fn a_pinned_state_that_names_no_setting_is_reported_and_ignored() {
        // `?a=x` turned the comparison on with default settings.
        for q in [
            "a=x",
            "a=",
            "backlash_um=150&a=%%%",
            "a=foo%3D1",
            "a=a%3Dmodel",
        ] {
            let d = decode(q);
            assert_eq!(d.pinned, None, "{q}");
            assert_eq!(d.issues.len(), 1, "{q}: {:?}", d.issues);
            assert!(
                d.issues[0].starts_with("a = ") && d.issues[0].contains("ignored"),
                "{q}: {:?}",
                d.issues
            );
        }
        assert_eq!(
            keys::get(
                &decode("backlash_um=150&a=x").settings.params,
                "backlash_um"
            ),
            Some(Value::Num(150.0))
        );
        // A pinned state with only a view option, or only the model, is one.
        assert!(decode("a=omega%3D0.5").pinned.is_some());
        assert!(decode("a=model%3Dgear-pair").pinned.is_some());
    }

    #[test]
    fn both_inverted_ranges_are_reset_like_one() {
        let d = decode("omega_from=1.5&omega_to=1&map_from=50&map_to=10");
        let v = &d.settings.view;
        let def = ViewOptions::default();
        assert_eq!((v.omega_from, v.omega_to), (def.omega_from, def.omega_to));
        assert_eq!((v.map_from, v.map_to), (def.map_from, def.map_to));
        let all = d.issues.join("\n");
        assert!(
            all.contains("frequency range") && all.contains("map's range"),
            "{all}"
        );
        // Only the map's range inverted: the same reset.
        let d = decode("map_from=50&map_to=10");
        assert_eq!(
            (d.settings.view.map_from, d.settings.view.map_to),
            (def.map_from, def.map_to)
        );
    }

    #[test]
    fn minus_zero_is_normalized_to_zero() {
        let d = decode("te_um=-0&map_from=-0&te_cos_rb_um=-0.0");
        assert!(d.issues.is_empty(), "{:?}", d.issues);
        let q = encode(&d.settings);
        assert!(!q.contains("-0"), "{q}");
        assert_eq!(
            keys::get(&d.settings.params, "te_um"),
            Some(Value::Num(0.0))
        );
        assert!(d.settings.view.map_from.is_sign_positive());
    }

    #[test]
    fn a_family_rides_along_and_restores_exactly() {
        let d = decode("te_um=5&backlash_um=200&family=te_um%3A0%2C20.5%2C30");
        assert!(d.issues.is_empty(), "{:?}", d.issues);
        let f = d.family.clone().unwrap();
        assert_eq!(f.values, vec![0.0, 20.5, 30.0]);
        // The first member is the current state.
        assert_eq!(
            keys::get(&d.settings.params, "te_um"),
            Some(Value::Num(0.0))
        );
        let q = encode_all(&d.settings, None, Some(&f), None);
        assert!(q.ends_with("&family=te_um%3A0%2C20.5%2C30"), "{q}");
        let again = decode(&q);
        assert!(again.issues.is_empty(), "{:?}", again.issues);
        assert_eq!(again.family, d.family);
        assert_eq!(again.settings, d.settings);
        // Unencoded too, as a person types it.
        assert_eq!(decode("family=te_um:0,20.5,30").family, d.family);
        // A bad family is named and dropped; the rest of the link applies.
        let d = decode("backlash_um=150&family=backlash_um:50,5000");
        assert_eq!(d.family, None);
        assert_eq!(d.issues.len(), 1, "{:?}", d.issues);
        assert!(d.issues[0].contains("backlash 5000"), "{:?}", d.issues);
        assert_eq!(
            keys::get(&d.settings.params, "backlash_um"),
            Some(Value::Num(150.0))
        );
    }

    #[test]
    fn percent_codec_round_trips_and_tolerates_garbage() {
        for s in ["a b&c=d", "µm Ω 漢字", "%%%", "100%"] {
            assert_eq!(percent_decode(&percent_encode(s)), s);
        }
        assert_eq!(percent_decode("%zz%4"), "%zz%4");
        assert_eq!(percent_decode("%C3"), "\u{FFFD}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(300))]

        #[test]
        fn decode_never_panics_on_random_text(s in "\\PC{0,300}") {
            let d = decode(&s);
            prop_assert!(d.settings.view.bif_points <= crate::settings::MAX_BIF_POINTS);
        }

        #[test]
        fn decode_never_panics_on_hostile_pairs(
            pairs in proptest::collection::vec(
                (
                    prop_oneof![
                        Just("backlash_um".to_string()),
                        Just("te_um".to_string()),
                        Just("model".to_string()),
                        Just("planets".to_string()),
                        Just("omega".to_string()),
                        Just("mesh".to_string()),
                        Just("bif_points".to_string()),
                        Just("torque_s2_nm".to_string()),
                        Just("map_key".to_string()),
                        Just("map_from".to_string()),
                        Just("map_to".to_string()),
                        Just("map_omega_points".to_string()),
                        Just("map_value_points".to_string()),
                        Just("lyap_points".to_string()),
                        Just("a".to_string()),
                        Just("family".to_string()),
                        Just("panels".to_string()),
                        Just("teeth_r".to_string()),
                        "[a-z_%0-9]{0,12}",
                        "\\PC{0,8}",
                    ],
                    prop_oneof![
                        Just("NaN".to_string()),
                        Just("inf".to_string()),
                        Just("-inf".to_string()),
                        Just("1e308".to_string()),
                        Just("1e309".to_string()),
                        Just("-0".to_string()),
                        Just("auto".to_string()),
                        Just("gear-pair".to_string()),
                        Just("%FF%FE".to_string()),
                        Just("worst".to_string()),
                        Just("te_um:0,20,30".to_string()),
                        Just("s1a1,rb1".to_string()),
                        Just("backlash_um:50,1e9".to_string()),
                        any::<f64>().prop_map(|x| x.to_string()),
                        any::<i64>().prop_map(|x| x.to_string()),
                        "\\PC{0,20}",
                    ],
                ),
                0..40,
            )
        ) {
            let q: Vec<String> = pairs.iter().map(|(k, v)| format!("{k}={v}")).collect();
            let d = decode(&q.join("&"));
            // Whatever the link said, the result is a buildable model with capped jobs.
            prop_assert!(Model::new(&d.settings.params).is_ok());
            let v = &d.settings.view;
            prop_assert!(v.omega_from < v.omega_to);
            prop_assert!(v.fr_points <= crate::settings::MAX_FR_POINTS);
            prop_assert!(v.transient_periods <= crate::settings::MAX_TRANSIENT);
            prop_assert!(v.record_periods <= crate::settings::MAX_RECORD);
            prop_assert!(v.map_from < v.map_to);
            prop_assert!(v.map_omega_points <= crate::settings::MAX_MAP_OMEGA_POINTS);
            prop_assert!(v.map_value_points <= crate::settings::MAX_MAP_VALUE_POINTS);
            prop_assert!(crate::settings::MAP_KEYS.contains(&v.map_key.as_str()));
            // And it round-trips, with its pinned state if it had one.
            let again = decode(&encode_all(
                &d.settings,
                d.pinned.as_ref(),
                d.family.as_ref(),
                d.panels.as_deref(),
            ));
            prop_assert!(again.issues.is_empty(), "{:?}", again.issues);
            prop_assert_eq!(again.settings, d.settings);
            prop_assert_eq!(again.pinned, d.pinned);
            prop_assert_eq!(again.family, d.family);
            prop_assert_eq!(again.panels, d.panels);
        }

        #[test]
        fn decode_survives_100_kb(c in "\\PC", v in "[0-9eE.+-]{1,30}") {
            let big = format!("backlash_um={v}&{}", c.repeat(100_000 / c.len().max(1)));
            let d = decode(&big);
            prop_assert!(d.issues.len() <= 4);
            let huge = "x=1&".repeat(30_000);
            let d = decode(&huge);
            prop_assert!(d.issues.len() <= MAX_PAIRS + 2);
        }
    }
}
