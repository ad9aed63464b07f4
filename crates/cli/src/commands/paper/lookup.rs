//! Looking up the record: a value it must hold, Fig. 2's rows and
//! windows, harmonic-balance cells, and the words for where back flanks
//! touch and in which of the paper's frequency sections.

use super::fig2::{Hbm, Row};
use super::record::Record;
use super::scale::PAPER_SECTIONS;
use super::sweeps::Sweep;
use super::words::{ints, over};
use crate::failure::Failure;

/// A value the record must hold.
pub fn need<T>(x: Option<T>, what: &str) -> Result<T, Failure> {
    x.ok_or_else(|| Failure {
        code: 1,
        message: format!("the record lacks {what}"),
    })
}

/// Fig. 2's x_s1a1 row of a reading (its words), method and TE.
pub fn row<'a>(
    r: &'a Record,
    reading: &str,
    one_harmonic: bool,
    te: u32,
) -> Result<&'a Row, Failure> {
    need(
        r.fig2
            .rows
            .iter()
            .find(|x| x.reading == reading && x.one_harmonic == one_harmonic && x.te_um == te),
        &format!("Fig. 2's row {reading}, TE {te} µm"),
    )
}

/// The index of Fig. 2's window centred nearest `w`.
pub fn anchor(r: &Record, w: f64) -> Result<usize, Failure> {
    let (i, a) = need(
        r.fig2
            .anchors
            .iter()
            .enumerate()
            .min_by(|a, b| (a.1.omega - w).abs().total_cmp(&(b.1.omega - w).abs())),
        "Fig. 2's windows",
    )?;
    if (a.omega - w).abs() > 0.01 {
        return Err(Failure {
            code: 1,
            message: format!("Fig. 2 has no window near Ω {w}"),
        });
    }
    Ok(i)
}

/// Whether a harmonic-balance amplitude stands on stable points only.
pub fn stable_only(h: &Hbm) -> bool {
    h.stable_um.is_some() && h.unstable_um.is_none()
}

/// The stable amplitude of a cell (NaN if none).
pub fn stable_um(h: &Hbm) -> f64 {
    h.stable_um.unwrap_or(f64::NAN)
}

/// Words for where the back flanks of some mesh touch along sweeps that
/// differ in one value (`label` names it): "the back flanks of some mesh
/// touch with 30 µm TE over Ω 0.40–0.45, 0.65 and 0.75; with 0 and 20 µm
/// nowhere".
pub fn back_words(sweeps: &[Sweep], label: fn(&Sweep) -> u32, unit: &str) -> String {
    let mut parts = Vec::new();
    let mut none = Vec::new();
    for s in sweeps {
        if s.any_back.is_empty() {
            none.push(label(s));
        } else {
            parts.push(format!(
                "with {} µm{unit} {}",
                label(s),
                over_omega(&s.any_back)
            ));
        }
    }
    if !none.is_empty() {
        parts.push(format!("with {} µm nowhere", ints(&none)));
    }
    format!("the back flanks of some mesh touch {}", parts.join("; "))
}

/// "over Ω 0.40–0.45 and 0.65", "at Ω 1.35", "nowhere".
pub fn over_omega(s: &super::data::Spans) -> String {
    let w = over(s);
    match w.split_once(' ') {
        Some((prep, rest)) if prep == "over" || prep == "at" => format!("{prep} Ω {rest}"),
        _ => w,
    }
}

/// The paper's frequency section of `w` on its own scale (`factor` 1) or
/// matched (`factor` the scale's).
pub fn section(w: f64, factor: f64) -> &'static str {
    for (name, _, hi) in PAPER_SECTIONS {
        if w <= hi * factor + 1e-9 {
            return name;
        }
    }
    "above"
}

/// The sections that spans of grid points touch, in order.
pub fn sections_of(s: &super::data::Spans, factor: f64, step: f64) -> Vec<&'static str> {
    let mut out: Vec<&'static str> = Vec::new();
    for &(a, b) in s {
        let mut w = a;
        while w <= b + 1e-9 {
            let name = section(w, factor);
            if !out.contains(&name) {
                out.push(name);
            }
            w += step;
        }
    }
    out
}
