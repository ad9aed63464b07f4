//! The `te_file` target: the TE table reader and its fit
//! ([`solver::te_file::parse`], [`solver::te_file::fit_into`]), which the
//! command line's `--te-file` and the page's dropped files feed with
//! whatever a user has. Inputs: real tables (fraction, roll angle, time)
//! with hostile cells, headers, comments and row orders, and raw text. A
//! table it accepts must hold what the module promises (an abscissa at 0
//! or above, increasing, finite TE); a fit it accepts finite coefficients
//! on the kind's keys, the model built or refused without a panic.

use crate::{Rng, HOSTILE};
use solver::params::{ModelKind, ModelParams};
use solver::te_file;

const FIRST: &[&str] = &[
    "fraction",
    "roll_deg",
    "Roll angle (deg)",
    "time_s",
    "Time (s)",
    "mesh_cycle",
    "speed",
    "",
];
const SECOND: &[&str] = &["te_um", "TE (µm)", "te_nm", "te_mm", "te_m", "te", ""];

/// One input: a table's text.
pub fn te_input(r: &mut Rng) -> String {
    if r.chance(10) {
        // Raw text of hostile words and separators.
        return (0..r.below(40))
            .map(|_| *r.pick(HOSTILE, &""))
            .collect::<Vec<_>>()
            .join(*r.pick(&[",", "\n", ";", "\t", "#"], &","));
    }
    let mut t = String::new();
    if r.chance(30) {
        let v = if r.chance(50) {
            format!("{}", 1e-3 * (1 + r.below(10)) as f64)
        } else {
            r.pick(HOSTILE, &"").to_string()
        };
        t.push_str(&format!("# mesh_period_s = {v}\n"));
    }
    let sep = *r.pick(&[",", ";", "\t"], &",");
    t.push_str(&format!(
        "{}{sep}{}\n",
        r.pick(FIRST, &""),
        r.pick(SECOND, &"")
    ));
    let n = r.below(60);
    let span = *r.pick(&[1.0, 2.0, 12.0, 0.5, 1e-3, 1e300], &1.0);
    // Most tables have one bad row, or a pair of rows swapped.
    let bad = r.chance(60).then(|| (r.below(n.max(1)), r.below(4)));
    let mut rows: Vec<String> = (0..n)
        .map(|i| {
            let x = span * i as f64 / n.max(1) as f64;
            let e = (std::f64::consts::TAU * i as f64 / n.max(1) as f64).sin() * 10.0;
            let (mut xs, mut es) = (format!("{x}"), format!("{e}"));
            match bad {
                Some((b, 0)) if b == i => xs = r.pick(HOSTILE, &"").to_string(),
                Some((b, 1)) if b == i => es = r.pick(HOSTILE, &"").to_string(),
                Some((b, 2)) if b == i => return xs,
                _ => {}
            }
            format!("{xs}{sep}{es}")
        })
        .collect();
    if let (Some((b, 3)), true) = (bad, b_ok(bad, n)) {
        rows.swap(b, b + 1);
    }
    for row in rows {
        t.push_str(&row);
        t.push('\n');
    }
    t
}

/// Whether a swap of row `b` with the next is inside `n` rows.
fn b_ok(bad: Option<(usize, usize)>, n: usize) -> bool {
    bad.is_some_and(|(b, _)| b + 1 < n)
}

/// Parses and fits `text` (to `harmonics` harmonics, on either model),
/// checking what an accepted table and fit promise.
pub fn check_te(text: &str, harmonics: usize, pair: bool) -> Result<(), String> {
    let Ok(table) = te_file::parse(text) else {
        return Ok(());
    };
    if table.x.is_empty() || table.x.len() != table.te_um.len() {
        return Err("accepted table without matching points".into());
    }
    if table.x.first().is_some_and(|x| *x < 0.0) || table.x.windows(2).any(|w| w[1] <= w[0]) {
        return Err("accepted abscissa negative or not increasing".into());
    }
    if table.te_um.iter().chain(&table.x).any(|v| !v.is_finite()) {
        return Err("accepted a value that is not finite".into());
    }
    let kind = if pair { "pair" } else { "s2b" };
    let mut p = ModelParams::defaults(if pair {
        ModelKind::GearPair
    } else {
        ModelKind::Ravigneaux
    });
    let before = p.clone();
    match te_file::fit_into(&mut p, kind, &table, harmonics) {
        Err(_) if p != before => Err("a refused fit changed the parameters".into()),
        Err(_) => Ok(()),
        Ok(fit) => {
            let coefs = fit.harmonics_um.iter().flatten().chain([&fit.mean_um]);
            if coefs.clone().any(|c| !c.is_finite()) || !fit.rms_residual_um.is_finite() {
                return Err(format!("a fit that is not finite: {fit:?}"));
            }
            let _ = solver::model::Model::new(&p);
            Ok(())
        }
    }
}
