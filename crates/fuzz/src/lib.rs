//! gearshock's fuzz harness, on stable Rust (cargo-fuzz needs nightly):
//! deterministic pseudo-random and mutated inputs for the readers of
//! untrusted text, each checked for panics and for the invariants its
//! output promises.
//!
//! - `link`: the page's link decoder ([`figures::link::decode`]) on random
//!   pairs of real and junk keys with hostile values, nested pinned states,
//!   mutated real links and raw bytes. The result must build, keep every
//!   job capped and round-trip through [`figures::link::encode_ab`].
//! - `params`: the parameter JSON ([`solver::keys::from_json_str`]) on
//!   random objects, mutated real parameter files and raw text. A set it
//!   accepts must round-trip through [`solver::keys::to_json`].
//! - `shards`: the shard merger ([`report::merge_shards`],
//!   [`report::merge_maps`]) on real shards of a tiny sweep and map
//!   with forged fields (per-point and per-cell contents aimed at field by
//!   field too: an accepted merge's points must have whole counters and
//!   Poincaré arrays of `record_periods` entries, its cells a period, motion
//!   and regime gearshock writes), dropped, doubled or swapped shards and
//!   mutated text. A merge it accepts must hold every grid point exactly
//!   once, each one of its inputs' items verbatim.
//! - `te_file`: the TE table reader and its fit (`te_file.rs`) on real
//!   tables with hostile cells, headers and rows, and raw text.
//! - figure shards: forged shard sets of a real figure
//!   ([`figure_shards_input`]: members, smuggled file text, forged data and
//!   options) checked by [`check_figure_merge`]; the figure merge draws
//!   its files in the CLI, so `crates/cli/tests/figure_shards_fuzz.rs`
//!   runs this target on the `gearshock` binary.
//!
//! Inputs are reproducible from the seed and the input number. `cargo test
//! -p fuzz` runs a short version; `gearshock-fuzz` (src/main.rs) the long one.

use serde_json::{json, Map, Value};
use std::panic::{catch_unwind, AssertUnwindSafe};

mod shards;
mod te_file;
pub use shards::{
    base_shards, check_figure_merge, check_shards, figure_shards_input, shards_input,
};
pub use te_file::{check_te, te_input};

/// The targets, in run order.
pub const TARGETS: &[&str] = &["link", "params", "shards", "te_file"];

/// The outcome of a run.
#[derive(Debug, Default)]
pub struct Report {
    /// Inputs tried.
    pub inputs: u64,
    /// One line per input that panicked or broke an invariant (the input
    /// number, what went wrong and the input, shortened).
    pub failures: Vec<String>,
}

/// A small, fast, deterministic generator (SplitMix64).
#[derive(Debug, Clone)]
pub struct Rng(u64);

impl Rng {
    /// A generator for input `n` of a run with `seed`.
    pub fn new(seed: u64, n: u64) -> Self {
        let mut r = Rng(seed ^ n.wrapping_mul(0xD134_2543_DE82_EF95));
        r.bits();
        r
    }

    /// The next 64 random bits.
    pub fn bits(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number in `0 .. n` (0 if `n` is 0).
    pub fn below(&mut self, n: usize) -> usize {
        if n == 0 {
            0
        } else {
            (self.bits() % n as u64) as usize
        }
    }

    /// True with probability `percent` / 100.
    pub fn chance(&mut self, percent: u64) -> bool {
        self.bits() % 100 < percent
    }

    /// One of `xs` (which must not be empty; `fallback` if it is).
    pub fn pick<'a, T>(&mut self, xs: &'a [T], fallback: &'a T) -> &'a T {
        xs.get(self.below(xs.len())).unwrap_or(fallback)
    }
}

/// Values that have broken parsers before.
const HOSTILE: &[&str] = &[
    "NaN",
    "nan",
    "inf",
    "-inf",
    "infinity",
    "1e308",
    "1e309",
    "-1e309",
    "-0",
    "0",
    "-1",
    "1",
    "0.5",
    "2.5",
    "1e-320",
    "4294967295",
    "4294967296",
    "18446744073709551616",
    "-9223372036854775809",
    "0x10",
    "1_000",
    "+5",
    " 7 ",
    "auto",
    "Auto",
    "gear-pair",
    "ravigneaux",
    "sequential",
    "in-phase",
    "worst",
    "up",
    "down",
    "both",
    "backlash_um",
    "te_um",
    "",
    " ",
    "%",
    "%%",
    "%4",
    "%zz",
    "%FF%FE",
    "%C3",
    "%00",
    "%3D",
    "%26",
    "=",
    "&",
    "+",
    "a=b",
    "model=gear-pair",
    "٣",
    "漢字",
    "µm",
    "\u{0}",
    "\u{202e}",
    "💥",
    "<script>",
];

/// A number as text, from several distributions.
fn number_text(r: &mut Rng) -> String {
    match r.below(6) {
        0 => format!("{}", f64::from_bits(r.bits())),
        1 => format!("{}", r.bits() as i64),
        2 => format!("{}", r.below(2000)),
        3 => format!("{}", (r.below(2_000_000) as f64) / 1000.0 - 500.0),
        4 => format!(
            "{:e}",
            (r.bits() % 1000) as f64 * 10f64.powi(r.below(40) as i32 - 20)
        ),
        _ => format!("-{}", r.below(100)),
    }
}

/// Random printable and unprintable characters.
fn junk_text(r: &mut Rng, max_len: usize) -> String {
    let n = r.below(max_len + 1);
    let mut bytes = Vec::with_capacity(n);
    for _ in 0..n {
        bytes.push(match r.below(4) {
            0 => r.bits() as u8,
            1 => b"=&%+?#;a0._-"[r.below(12)],
            _ => b'a' + r.below(26) as u8,
        });
    }
    String::from_utf8_lossy(&bytes).into_owned()
}

fn value_text(r: &mut Rng) -> String {
    match r.below(4) {
        0 | 1 => r.pick(HOSTILE, &"").to_string(),
        2 => number_text(r),
        _ => junk_text(r, 12),
    }
}

/// Every key a link or parameter file may hold: both models' parameter
/// keys (with the shortcuts), `model`, the view keys and `a`. Of the TE's
/// harmonics only the second's keys: the others take the same path, and
/// forty more keys would make a random parameter file that a model accepts
/// rare.
pub fn all_keys() -> Vec<String> {
    use solver::params::ModelKind;
    let mut keys: Vec<String> = vec!["model".into(), "backlash_um".into(), "te_um".into()];
    let higher_harmonic = |name: &str| {
        (3..=solver::params::TE_HARMONICS).any(|n| {
            name.starts_with(&format!("te_cos{n}")) || name.starts_with(&format!("te_sin{n}"))
        })
    };
    for kind in [ModelKind::Ravigneaux, ModelKind::GearPair] {
        for k in solver::keys::primary_keys(kind) {
            if !higher_harmonic(k.name) && !keys.iter().any(|x| x == k.name) {
                keys.push(k.name.to_string());
            }
        }
    }
    keys.extend(
        figures::settings::VIEW_KEYS
            .iter()
            .map(|k| k.name.to_string()),
    );
    keys.push(figures::link::PINNED_KEY.to_string());
    keys
}

fn key_text(r: &mut Rng, keys: &[String]) -> String {
    match r.below(10) {
        0 => junk_text(r, 10),
        1 => r.pick(HOSTILE, &"").to_string(),
        _ => r.pick(keys, &String::new()).clone(),
    }
}

/// Byte-level mutations of a text: flips, insertions, deletions, cuts and
/// repeated chunks.
pub fn mutate_text(r: &mut Rng, text: &str) -> String {
    let mut b = text.as_bytes().to_vec();
    for _ in 0..1 + r.below(4) {
        let at = r.below(b.len() + 1);
        match r.below(6) {
            0 if at < b.len() => b[at] = r.bits() as u8,
            1 => b.insert(at, r.bits() as u8),
            2 if at < b.len() => {
                b.remove(at);
            }
            3 => b.truncate(at),
            4 => {
                let end = (at + 1 + r.below(16)).min(b.len());
                let chunk = b.get(at..end).map(<[u8]>::to_vec).unwrap_or_default();
                for _ in 0..r.below(4) {
                    b.splice(at..at, chunk.iter().copied());
                }
            }
            _ => {
                let s = r.pick(HOSTILE, &"").as_bytes().to_vec();
                b.splice(at..at, s);
            }
        }
    }
    String::from_utf8_lossy(&b).into_owned()
}

/// A random link query.
pub fn link_input(r: &mut Rng, keys: &[String]) -> String {
    match r.below(10) {
        // Pairs of real and junk keys with hostile values.
        0..=5 => {
            let mut parts = Vec::new();
            for _ in 0..r.below(30) {
                // The pinned state's key as often whatever the number of
                // keys (each view key the page gains would make it rarer).
                let k = if r.chance(2) {
                    figures::link::PINNED_KEY.to_string()
                } else {
                    key_text(r, keys)
                };
                let v = if k == figures::link::PINNED_KEY && r.chance(70) {
                    let inner = link_input(&mut r.clone(), keys);
                    r.bits();
                    figures::link::percent_encode(&inner)
                } else {
                    value_text(r)
                };
                let (k, v) = if r.chance(20) {
                    (
                        figures::link::percent_encode(&k),
                        figures::link::percent_encode(&v),
                    )
                } else {
                    (k, v)
                };
                parts.push(if r.chance(3) { k } else { format!("{k}={v}") });
            }
            let q = parts.join("&");
            if r.chance(30) {
                format!("?{q}")
            } else {
                q
            }
        }
        // A real link, mutated.
        6..=8 => {
            let mut inner = r.clone();
            r.bits();
            let d = figures::link::decode(&link_input(&mut inner, keys));
            let q = figures::link::encode_ab(&d.settings, d.pinned.as_ref());
            mutate_text(r, &q)
        }
        // Raw junk, sometimes longer than the decoder reads.
        _ => {
            let chunk = junk_text(r, 200);
            if r.chance(2) {
                chunk.repeat(70_000 / chunk.len().max(1))
            } else {
                chunk
            }
        }
    }
}

fn random_json(r: &mut Rng, depth: usize) -> Value {
    match r.below(if depth > 3 { 6 } else { 8 }) {
        0 => Value::Null,
        1 => Value::Bool(r.chance(50)),
        2 => json!(r.bits() as i64),
        3 => json!(r.bits()),
        4 => serde_json::Number::from_f64(f64::from_bits(r.bits()))
            .map_or(Value::Null, Value::Number),
        5 => Value::String(value_text(r)),
        6 => Value::Array((0..r.below(4)).map(|_| random_json(r, depth + 1)).collect()),
        _ => {
            let mut m = Map::new();
            for _ in 0..r.below(4) {
                m.insert(junk_text(r, 6), random_json(r, depth + 1));
            }
            Value::Object(m)
        }
    }
}

/// A value of the kind a parameter key takes, or not.
fn param_value(r: &mut Rng) -> Value {
    match r.below(5) {
        0 => random_json(r, 2),
        1 => Value::String(value_text(r)),
        _ => {
            let t = number_text(r);
            serde_json::from_str::<Value>(&t).unwrap_or(Value::String(t))
        }
    }
}

/// A random parameter file's text.
pub fn params_input(r: &mut Rng, keys: &[String]) -> String {
    match r.below(10) {
        0..=5 => {
            let mut m = Map::new();
            for _ in 0..r.below(12) {
                let k = key_text(r, keys);
                m.insert(k, param_value(r));
            }
            if r.chance(30) {
                m.insert("model".into(), param_value(r));
            }
            Value::Object(m).to_string()
        }
        6..=8 => {
            let mut inner = r.clone();
            r.bits();
            let base =
                solver::keys::from_json_str(&params_input(&mut inner, keys)).unwrap_or_default();
            let text = Value::Object(solver::keys::to_json(&base)).to_string();
            mutate_text(r, &text)
        }
        _ => match r.below(3) {
            0 => "[".repeat(r.below(400)),
            1 => junk_text(r, 100),
            _ => random_json(r, 0).to_string(),
        },
    }
}

/// Checks the link decoder on one input; `Err` says what broke.
pub fn check_link(query: &str) -> Result<(), String> {
    use figures::link::{decode, encode_ab};
    let d = decode(query);
    solver::steady::Model::new(&d.settings.params)
        .map_err(|e| format!("decoded parameters do not build: {e}"))?;
    let v = &d.settings.view;
    if !(v.omega_from < v.omega_to && v.map_from < v.map_to) {
        return Err("a decoded range is not increasing".into());
    }
    if v.bif_points > figures::settings::MAX_BIF_POINTS
        || v.record_periods > figures::settings::MAX_RECORD
        || v.map_omega_points > figures::settings::MAX_MAP_OMEGA_POINTS
    {
        return Err("a decoded job is over its cap".into());
    }
    let again = decode(&encode_ab(&d.settings, d.pinned.as_ref()));
    if !again.issues.is_empty() || again.settings != d.settings || again.pinned != d.pinned {
        return Err(format!("no round trip: {:?}", again.issues));
    }
    Ok(())
}

/// Checks the parameter reader on one input.
pub fn check_params(text: &str) -> Result<(), String> {
    let Ok(p) = solver::keys::from_json_str(text) else {
        return Ok(());
    };
    let back = solver::keys::from_json(&solver::keys::to_json(&p))
        .map_err(|e| format!("accepted set does not read back: {e}"))?;
    if back != p {
        return Err("accepted set reads back different".into());
    }
    // Building may refuse the set (geometry, torques), but must not panic.
    let _ = solver::steady::Model::new(&p);
    Ok(())
}

/// Runs `inputs` inputs of `target` from `seed`; panics are caught and
/// reported as failures, like broken invariants.
pub fn run(target: &str, seed: u64, inputs: u64) -> Report {
    let keys = all_keys();
    let (sweeps, maps) = if target == "shards" {
        base_shards()
    } else {
        (Vec::new(), Vec::new())
    };
    let mut report = Report::default();
    if target == "shards" && (sweeps.len() != 2 || maps.len() != 2) {
        report
            .failures
            .push("the base shards could not be computed".into());
        return report;
    }
    for n in 0..inputs {
        let mut r = Rng::new(seed, n);
        let (shown, outcome) = match target {
            "link" => {
                let q = link_input(&mut r, &keys);
                let out = catch_unwind(AssertUnwindSafe(|| check_link(&q)));
                (q, out)
            }
            "params" => {
                let t = params_input(&mut r, &keys);
                let out = catch_unwind(AssertUnwindSafe(|| check_params(&t)));
                (t, out)
            }
            "te_file" => {
                let t = te_input(&mut r);
                let (h, pair) = (1 + r.below(7), r.chance(50));
                let out = catch_unwind(AssertUnwindSafe(|| check_te(&t, h, pair)));
                (t, out)
            }
            "shards" => {
                let s = shards_input(&mut r, &sweeps, &maps);
                let out = catch_unwind(AssertUnwindSafe(|| check_shards(&s)));
                (Value::Array(s).to_string(), out)
            }
            other => {
                report.failures.push(format!("unknown target {other}"));
                return report;
            }
        };
        report.inputs += 1;
        let what = match outcome {
            Ok(Ok(())) => continue,
            Ok(Err(e)) => e,
            Err(_) => "panicked".to_string(),
        };
        report.failures.push(format!(
            "input {n} (seed {seed}): {what}: {}",
            solver::keys::truncate(&shown, 300)
        ));
    }
    report
}
