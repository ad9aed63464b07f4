//! A measured or computed transmission error read from a table and fitted
//! to the model's harmonics of the mesh frequency.
//!
//! The text is CSV: an optional header of comment lines (`#`), then a
//! header row naming the two columns with their units, then one row per
//! point. The first column is the abscissa, one of
//!
//! - `fraction` (or `mesh_cycle`): the mesh-cycle fraction, one mesh period is 1;
//! - `roll_deg` (or `roll_angle_deg`, `Roll angle (deg)`): the roll angle of
//!   the mesh's driving member, one mesh period is `360 / z` degrees;
//! - `time_s` (or `Time (s)`): seconds, with the mesh period given in a
//!   comment line `# mesh_period_s = 0.00125`;
//!
//! the second the TE: `te_um` (`TE (um)`, `te_µm`), `te_nm`, `te_mm` or `te_m`.
//! The abscissa must start at 0 or above, increase strictly and span at
//! least one mesh period.
//!
//! The fit is linear least squares (nalgebra's SVD) on `mean + sum_n (c_n
//! cos(n theta) + s_n sin(n theta))`, `theta = 2 pi x / period`, so the
//! coefficients are the model's `te_mean`, `te_cos<n>`, `te_sin<n>` keys
//! directly. Each is rounded to the resolution the fit supports: the RMS
//! residual, at least 1e-6 um, as a power of ten; a file holding an exact
//! few-harmonic curve so gives back its coefficients as typed.

use crate::error::{Result, SolverError};
use crate::keys;
use crate::params::{ModelKind, ModelParams, TE_HARMONICS};
use nalgebra::{DMatrix, DVector};
use std::f64::consts::PI;

/// The largest TE file a reader should accept (bytes).
pub const MAX_TE_FILE_BYTES: u64 = 10 << 20;

/// The abscissa of a TE table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Abscissa {
    /// Mesh-cycle fraction (period 1).
    Fraction,
    /// Roll angle in degrees (period `360 / z`).
    RollDeg,
    /// Time in seconds (period from the file's `mesh_period_s` comment).
    TimeS,
}

/// A TE table as read: the abscissa's kind, its points and the TE in um.
#[derive(Debug, Clone, PartialEq)]
pub struct TeTable {
    /// What the first column holds.
    pub abscissa: Abscissa,
    /// The first column.
    pub x: Vec<f64>,
    /// The TE (um).
    pub te_um: Vec<f64>,
    /// The mesh period from a `# mesh_period_s = ...` comment, if any.
    pub mesh_period_s: Option<f64>,
}

/// The fit of a TE table.
#[derive(Debug, Clone, PartialEq)]
pub struct TeFit {
    /// Mean (um).
    pub mean_um: f64,
    /// `[cos, sin]` (um) of harmonics 1, 2, ...
    pub harmonics_um: Vec<[f64; 2]>,
    /// RMS of the residual of the unrounded fit (um).
    pub rms_residual_um: f64,
    /// RMS of the TE about its mean (um).
    pub rms_um: f64,
    /// Decimal places the coefficients were rounded to.
    pub decimals: u32,
    /// Points fitted.
    pub points: usize,
    /// Mesh periods the table spans.
    pub periods: f64,
}

fn refuse(line: usize, reason: impl Into<String>) -> SolverError {
    SolverError::Parse(if line == 0 {
        reason.into()
    } else {
        format!("line {line}: {}", reason.into())
    })
}

/// A header cell in a canonical form: `Roll angle (deg)` -> `roll_angle_deg`.
fn canonical(cell: &str) -> String {
    cell.trim()
        .trim_matches('"')
        .to_lowercase()
        .replace('µ', "u")
        .replace(['(', ')'], " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join("_")
}

/// Reads a TE table (see the module doc), refusing with the line and reason.
pub fn parse(text: &str) -> Result<TeTable> {
    let mut header: Option<(Abscissa, f64)> = None;
    let mut mesh_period_s = None;
    let (mut x, mut te_um) = (Vec::new(), Vec::new());
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let l = raw.trim();
        if l.is_empty() {
            continue;
        }
        if let Some(comment) = l.strip_prefix('#') {
            if let Some((k, v)) = comment.split_once('=') {
                if canonical(k) == "mesh_period_s" {
                    let p: f64 = v.trim().parse().map_err(|_| {
                        refuse(
                            line,
                            format!("mesh_period_s `{}` is not a number", v.trim()),
                        )
                    })?;
                    if !(p.is_finite() && p > 0.0) {
                        return Err(refuse(line, format!("mesh_period_s {p} must be above 0")));
                    }
                    mesh_period_s = Some(p);
                }
            }
            continue;
        }
        let cells: Vec<&str> = l.split([',', ';', '\t']).map(str::trim).collect();
        if cells.len() < 2 {
            return Err(refuse(
                line,
                "one column; two are needed (the abscissa and the TE, comma separated)",
            ));
        }
        let Some((_, scale)) = header else {
            header = Some(read_header(line, cells[0], cells[1])?);
            continue;
        };
        let number = |cell: &str, what: &str| -> Result<f64> {
            let v: f64 = cell.parse().map_err(|_| {
                refuse(
                    line,
                    format!(
                        "{what} `{}` is not a number",
                        crate::keys::truncate(cell, 20)
                    ),
                )
            })?;
            if v.is_finite() {
                Ok(v)
            } else {
                Err(refuse(line, format!("{what} is {v}; only finite numbers")))
            }
        };
        let xi = number(cells[0], "the abscissa")?;
        let ti = number(cells[1], "the TE")?;
        if xi < 0.0 {
            return Err(refuse(
                line,
                format!("the abscissa {xi} is negative; allowed 0 and above"),
            ));
        }
        if let Some(&prev) = x.last() {
            if xi <= prev {
                return Err(refuse(
                    line,
                    format!("the abscissa {xi} does not increase (the line before has {prev})"),
                ));
            }
        }
        if !(ti * scale).is_finite() {
            return Err(refuse(
                line,
                format!(
                    "the TE {} is too large in µm; only finite numbers",
                    crate::keys::truncate(cells[1], 20)
                ),
            ));
        }
        x.push(xi);
        te_um.push(ti * scale);
    }
    let Some((abscissa, _)) = header else {
        return Err(refuse(0, "the file is empty: no header row and no points"));
    };
    if x.is_empty() {
        return Err(refuse(0, "the file has a header but no points"));
    }
    if abscissa == Abscissa::TimeS && mesh_period_s.is_none() {
        return Err(refuse(
            0,
            "a table against time needs its mesh period: add a line `# mesh_period_s = ...`",
        ));
    }
    Ok(TeTable {
        abscissa,
        x,
        te_um,
        mesh_period_s,
    })
}

fn read_header(line: usize, first: &str, second: &str) -> Result<(Abscissa, f64)> {
    let abscissa = match canonical(first).as_str() {
        "fraction" | "mesh_cycle" | "mesh_cycle_fraction" => Abscissa::Fraction,
        "roll_deg" | "roll_angle_deg" | "angle_deg" => Abscissa::RollDeg,
        "time_s" | "t_s" => Abscissa::TimeS,
        other => {
            return Err(refuse(
                line,
                format!(
                    "the first column `{}` is not one of fraction, roll_deg, time_s \
                     (a header row naming the columns with their units comes first)",
                    crate::keys::truncate(other, 30)
                ),
            ))
        }
    };
    let scale = match canonical(second).as_str() {
        "te_um" => 1.0,
        "te_nm" => 1e-3,
        "te_mm" => 1e3,
        "te_m" => 1e6,
        other => {
            return Err(refuse(
                line,
                format!(
                    "the second column `{}` is not one of te_um, te_nm, te_mm, te_m",
                    crate::keys::truncate(other, 30)
                ),
            ))
        }
    };
    Ok((abscissa, scale))
}

/// Fits `harmonics` harmonics of the mesh period `period` (in the
/// abscissa's unit) to a table, coefficients rounded (see the module doc).
pub fn fit(table: &TeTable, period: f64, harmonics: usize) -> Result<TeFit> {
    let n = table.x.len();
    let nc = 2 * harmonics + 1;
    if n < nc + 1 {
        return Err(refuse(
            0,
            format!(
                "{n} points cannot fit {harmonics} harmonics: at least {} are needed",
                nc + 1
            ),
        ));
    }
    let (first, last) = (table.x[0], table.x[n - 1]);
    // Points spread evenly over k periods span (k - 1/n) of them.
    let periods = (last - first) / period * n as f64 / (n as f64 - 1.0);
    // Phases beyond 1e9 periods lose their digits (and beyond the range
    // of numbers the fit would not end).
    let reach = last / period;
    if !(periods.is_finite() && reach.is_finite() && periods <= 1e6 && reach <= 1e9) {
        return Err(refuse(
            0,
            format!(
                "the table spans {periods:.3e} mesh periods and reaches {reach:.3e}; \
                 allowed 1 to 1e6 periods, reaching at most 1e9"
            ),
        ));
    }
    if periods < 1.0 - 1e-9 {
        return Err(refuse(
            0,
            format!(
                "the table spans {periods:.3} mesh periods; at least one is needed to fit its harmonics"
            ),
        ));
    }
    let a = DMatrix::from_fn(n, nc, |i, c| {
        let theta = 2.0 * PI * table.x[i] / period;
        match c {
            0 => 1.0,
            c if c % 2 == 1 => (c.div_ceil(2) as f64 * theta).cos(),
            c => ((c / 2) as f64 * theta).sin(),
        }
    });
    let b = DVector::from_column_slice(&table.te_um);
    let coef = a
        .clone()
        .svd(true, true)
        .solve(&b, 1e-12)
        .map_err(|e| refuse(0, format!("the fit failed: {e}")))?;
    let residual = &a * &coef - &b;
    let rms_residual_um = (residual.norm_squared() / n as f64).sqrt();
    let mean = b.mean();
    let rms_um = (b.iter().map(|t| (t - mean).powi(2)).sum::<f64>() / n as f64).sqrt();
    let step = rms_residual_um.max(1e-6);
    let decimals = (-step.log10()).ceil().clamp(0.0, 9.0) as u32;
    let round = |v: f64| -> f64 {
        let s = format!("{v:.*}", decimals as usize);
        s.parse::<f64>().map_or(v, |r| r + 0.0)
    };
    Ok(TeFit {
        mean_um: round(coef[0]),
        harmonics_um: (1..=harmonics)
            .map(|k| [round(coef[2 * k - 1]), round(coef[2 * k])])
            .collect(),
        rms_residual_um,
        rms_um,
        decimals,
        points: n,
        periods,
    })
}

impl TeFit {
    /// The fitted TE (um) at the mesh phase `theta` (rad).
    pub fn value_um(&self, theta: f64) -> f64 {
        self.harmonics_um
            .iter()
            .enumerate()
            .fold(self.mean_um, |e, (i, [c, s])| {
                let n = (i + 1) as f64;
                e + c * (n * theta).cos() + s * (n * theta).sin()
            })
    }
}

/// The mesh kinds a model's TE can be fitted to: `pair` on the gear
/// pair, the four kinds on the compound set.
pub fn kinds(params: &ModelParams) -> &'static [&'static str] {
    match params.kind() {
        ModelKind::GearPair => &["pair"],
        ModelKind::Ravigneaux => &["s1a", "s2b", "ab", "rb"],
    }
}

/// The key of a TE coefficient: `part` `mean`, `cos` or `sin`, harmonic
/// `n` (1 ..= [`TE_HARMONICS`]; ignored for the mean), of mesh kind `kind`
/// (`pair`: the gear pair's keys, where the first sine is `te_um`).
pub fn te_key(kind: &str, part: &str, n: usize) -> String {
    let n = if n < 2 || part == "mean" {
        String::new()
    } else {
        n.to_string()
    };
    match (kind, part, n.is_empty()) {
        ("pair", "sin", true) => "te_um".into(),
        ("pair", _, _) => format!("te_{part}{n}_um"),
        _ => format!("te_{part}{n}_{kind}_um"),
    }
}

/// One mesh period in the table's abscissa: 1 for a fraction, `360 / z`
/// degrees of roll of the mesh kind's driving member (the pinion; s1, s2,
/// a, or the ring), the file's period for time.
pub fn mesh_period(params: &ModelParams, kind: &str, table: &TeTable) -> f64 {
    let teeth_key = match kind {
        "pair" => "teeth_pinion",
        "s1a" => "teeth_s1",
        "s2b" => "teeth_s2",
        "ab" => "teeth_a",
        _ => "teeth_r",
    };
    match table.abscissa {
        Abscissa::Fraction => 1.0,
        Abscissa::RollDeg => match keys::get(params, teeth_key) {
            Some(keys::Value::Num(z)) if z > 0.0 => 360.0 / z,
            _ => 1.0,
        },
        Abscissa::TimeS => table.mesh_period_s.unwrap_or(1.0),
    }
}

/// Fits `harmonics` harmonics to `table` for the mesh kind `kind` and sets
/// that kind's TE mean and every harmonic's keys to the fit (zero above
/// `harmonics`): what `--te-file KIND=FILE` and the page's TE file do.
/// Refused, `params` unchanged: a kind the model has not, `harmonics`
/// outside 1 ..= [`TE_HARMONICS`], a table the fit cannot take.
pub fn fit_into(
    params: &mut ModelParams,
    kind: &str,
    table: &TeTable,
    harmonics: usize,
) -> Result<TeFit> {
    let known = kinds(params);
    if !known.contains(&kind) {
        return Err(refuse(
            0,
            format!(
                "the mesh kind `{}` is not one of {}",
                keys::truncate(kind, 20),
                known.join(", ")
            ),
        ));
    }
    if !(1..=TE_HARMONICS).contains(&harmonics) {
        return Err(refuse(
            0,
            format!("{harmonics} harmonics is out of range: allowed 1 to {TE_HARMONICS}"),
        ));
    }
    let fit = fit(table, mesh_period(params, kind, table), harmonics)?;
    let mut next = params.clone();
    keys::set(
        &mut next,
        &te_key(kind, "mean", 0),
        keys::Value::Num(fit.mean_um),
    )?;
    for n in 1..=TE_HARMONICS {
        let [c, s] = fit.harmonics_um.get(n - 1).copied().unwrap_or([0.0; 2]);
        keys::set(&mut next, &te_key(kind, "cos", n), keys::Value::Num(c))?;
        keys::set(&mut next, &te_key(kind, "sin", n), keys::Value::Num(s))?;
    }
    *params = next;
    Ok(fit)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_exact_three_harmonic_curve_is_fitted_back_to_its_coefficients() {
        let mut text = String::from("# a test\nRoll angle (deg),TE (µm)\n");
        let z = 30.0;
        for i in 0..240 {
            // Two mesh periods of 12 degrees.
            let x = 24.0 * f64::from(i) / 240.0;
            let t = 2.0 * PI * x * z / 360.0;
            let e = 1.5 + 4.0 * t.sin() - 2.25 * t.cos() + 0.5 * (2.0 * t).cos()
                - 0.75 * (3.0 * t).sin();
            text.push_str(&format!("{x:.9},{e:.9}\n"));
        }
        let table = parse(&text).unwrap();
        assert_eq!(table.abscissa, Abscissa::RollDeg);
        let f = fit(&table, 360.0 / z, 6).unwrap();
        assert_eq!(f.mean_um, 1.5);
        assert_eq!(
            f.harmonics_um,
            vec![
                [-2.25, 4.0],
                [0.5, 0.0],
                [0.0, -0.75],
                [0.0, 0.0],
                [0.0, 0.0],
                [0.0, 0.0]
            ]
        );
        assert!(f.rms_residual_um < 1e-8, "{}", f.rms_residual_um);
        assert!((f.periods - 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_fit_sets_the_kinds_keys_and_a_refusal_changes_nothing() {
        // 1 + 3 cos(2 theta) - 2 sin(theta) against roll angle of a 30-tooth
        // sun s1: one mesh period is 12 degrees.
        let mut text = String::from("roll_deg,te_um\n");
        for i in 0..48 {
            let x = 12.0 * f64::from(i) / 48.0;
            let t = 2.0 * PI * x / 12.0;
            let e = 1.0 + 3.0 * (2.0 * t).cos() - 2.0 * t.sin();
            text.push_str(&format!("{x:.9},{e:.12}\n"));
        }
        let table = parse(&text).unwrap();
        let mut p = ModelParams::defaults(ModelKind::Ravigneaux);
        keys::set(&mut p, "teeth_s1", keys::Value::Num(30.0)).unwrap();
        keys::set(&mut p, "te_sin5_s2b_um", keys::Value::Num(4.0)).unwrap();
        let before = p.clone();
        let num = |p: &ModelParams, k: &str| match keys::get(p, k) {
            Some(keys::Value::Num(x)) => x,
            other => panic!("{k}: {other:?}"),
        };
        let f = fit_into(&mut p, "s1a", &table, 3).unwrap();
        assert!((f.value_um(0.0) - 4.0).abs() < 1e-6, "{f:?}");
        assert_eq!(num(&p, "te_mean_s1a_um"), 1.0);
        assert_eq!(num(&p, "te_sin_s1a_um"), -2.0);
        assert_eq!(num(&p, "te_cos2_s1a_um"), 3.0);
        assert_eq!(num(&p, "te_cos_s1a_um"), 0.0);
        // Another kind's TE is not touched.
        assert_eq!(num(&p, "te_sin5_s2b_um"), 4.0);
        let mut q = before.clone();
        for (kind, h) in [("pair", 3), ("s1a", 0), ("s1a", 7), ("s1a", 6)] {
            assert!(fit_into(&mut q, kind, &table, h).is_ok() == (h == 6 && kind == "s1a"));
            if h != 6 {
                assert_eq!(q, before, "{kind} {h}");
            }
        }
        let mut pair = ModelParams::defaults(ModelKind::GearPair);
        fit_into(
            &mut pair,
            "pair",
            &parse("fraction,te_um\n0,1\n0.25,3\n0.5,1\n0.75,-1\n").unwrap(),
            1,
        )
        .unwrap();
        // 1 + 2 sin(theta) through the four points: the pair's sine is te_um.
        assert_eq!(num(&pair, "te_um"), 2.0);
        assert_eq!(num(&pair, "te_mean_um"), 1.0);
    }

    #[test]
    fn bad_tables_are_refused_with_the_line_and_the_reason() {
        let cases = [
            ("", "empty"),
            ("fraction,te_um\n", "no points"),
            ("fraction,te_um\n0,1\n0.5\n", "line 3: one column"),
            (
                "fraction,te_um\n0,1\n0.5,abc\n",
                "line 3: the TE `abc` is not a number",
            ),
            ("fraction,te_um\n0,1\n0.5,NaN\n", "line 3: the TE is NaN"),
            (
                "fraction,te_um\n0,1\n0.5,2\n0.4,3\n",
                "line 4: the abscissa 0.4 does not increase",
            ),
            ("speed,te_um\n0,1\n", "line 1: the first column `speed`"),
            (
                "fraction,te_um\n-0.1,1\n0.5,2\n",
                "line 2: the abscissa -0.1 is negative; allowed 0 and above",
            ),
            ("time_s,te_um\n0,1\n", "mesh_period_s"),
        ];
        for (text, want) in cases {
            let e = parse(text).unwrap_err().to_string();
            assert!(e.contains(want), "{text:?}: {e}");
        }
        let short = parse("fraction,te_um\n0,1\n0.25,2\n0.5,3\n0.75,4\n").unwrap();
        assert!(fit(&short, 1.0, 2)
            .unwrap_err()
            .to_string()
            .contains("at least 6"));
        let part = "fraction,te_um\n".to_string()
            + &(0..20)
                .map(|i| format!("{},1\n", f64::from(i) * 0.01))
                .collect::<String>();
        let e = fit(&parse(&part).unwrap(), 1.0, 1).unwrap_err().to_string();
        assert!(e.contains("spans 0.200 mesh periods"), "{e}");
        // A period so short that the phases are not numbers any more.
        let tiny = "time_s,te_um\n# mesh_period_s = 1e-320\n".to_string()
            + &(0..20)
                .map(|i| format!("{},1\n", f64::from(i) * 0.01))
                .collect::<String>();
        let e = fit(&parse(&tiny).unwrap(), 1e-320, 1)
            .unwrap_err()
            .to_string();
        assert!(e.contains("allowed 1 to 1e6 periods"), "{e}");
        let e = parse("fraction,te_m\n0,1e305\n").unwrap_err().to_string();
        assert!(e.contains("line 2: the TE 1e305 is too large in µm"), "{e}");
    }
}
