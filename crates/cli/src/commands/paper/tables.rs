//! The document's tables, each rendered from the record as Markdown.

use super::advice::{CaseWindows, Window};
use super::fig2::{Anchor, Hbm};
use super::orbits::{self, Orbit};
use super::record::Record;
use super::scale::{Scale, PAPER_OMEGAS};
use super::sweeps::{Sweep, HIGH};
use super::words::{grouped, hbm, m_s, om, om3, spans, um};

/// A Markdown table.
pub fn table(header: &[String], rows: &[Vec<String>]) -> String {
    let line = |cells: &[String]| format!("| {} |", cells.join(" | "));
    let mut out = vec![line(header), format!("|{}", "---|".repeat(header.len()))];
    out.extend(rows.iter().map(|r| line(r)));
    out.join("\n")
}

fn strings(xs: &[&str]) -> Vec<String> {
    xs.iter().map(|s| (*s).to_string()).collect()
}

/// Every table, by its placeholder's name.
pub fn all(r: &Record) -> Vec<(&'static str, String)> {
    vec![
        ("table.matched", matched(&r.scale)),
        ("table.impact", impact(r)),
        ("table.fig2", fig2(r)),
        ("table.fig2_panels", fig2_panels(r)),
        ("table.fig2_peaks", fig2_peaks(r)),
        ("table.contact", contact(r)),
        (
            "table.fig3",
            fig3(r, |o| {
                format!("{} ({}, {})", um(o.amplitude_um), o.impact, o.motion)
            }),
        ),
        ("table.fig3_rb", fig3(r, |o| um(o.rb1_amplitude_um))),
        ("table.fig3_other", fig3_other(r)),
        ("table.fig4", fig4(r)),
        ("table.fig4_motion", fig4_motion(&r.fig4)),
        ("table.orbits_te", orbit_rows(r, false)),
        ("table.orbits_backlash", orbit_rows(r, true)),
        ("table.windows", windows(r, |c| &c.every_mesh)),
        ("table.windows_s1a1", windows(r, |c| &c.s1a1)),
    ]
}

/// The paper's Omegas on both scales, with the input speed.
fn matched(s: &Scale) -> String {
    let rows: Vec<Vec<String>> = PAPER_OMEGAS
        .iter()
        .map(|&w| {
            let m = s.matched(w);
            vec![
                om(w),
                grouped(w * s.rpm_per_omega),
                om3(m),
                grouped(m * s.rpm_per_omega),
            ]
        })
        .collect();
    table(
        &strings(&[
            "the paper's Ω",
            "input speed, read literally (rpm)",
            "matched on the first mode",
            "input speed, matched (rpm)",
        ]),
        &rows,
    )
}

/// Fig. 8's impacts, motion and chaos per backlash.
fn impact(r: &Record) -> String {
    let rows: Vec<Vec<String>> = r
        .fig8
        .iter()
        .zip(&r.chaos)
        .map(|(s, c)| {
            vec![
                format!("{} µm", s.case.backlash_um),
                spans(&s.x_negative),
                spans(&s.s1a1_back),
                spans(&s.any_back),
                s.first_not_period_1.map_or("none".into(), om),
                s.fine
                    .as_ref()
                    .and_then(|f| f.first_not_period_1)
                    .map_or("none".into(), super::words::omf),
                spans(&c.chaotic),
                format!("{:.2}", c.largest),
            ]
        })
        .collect();
    table(
        &strings(&[
            "backlash",
            "x negative (paper)",
            "back flanks touch, s1a1",
            "back flanks touch, any mesh",
            "first Ω without period 1",
            "the same, finer grid",
            "chaos (Lyapunov)",
            "largest exponent per period",
        ]),
        &rows,
    )
}

/// A window's centre as a column heading.
fn anchor_heading(a: &Anchor, first: bool) -> String {
    let mut why = Vec::new();
    if a.peak {
        why.push("peak".to_string());
    }
    if let Some(p) = a.paper {
        why.push(format!("the paper's {}", super::words::omega_arg(p)));
    }
    if let Some(p) = a.matched_from {
        why.push(format!(
            "the paper's {} matched",
            super::words::omega_arg(p)
        ));
    }
    let w = om3(a.omega);
    format!("{}{w}: {}", if first { "Ω " } else { "" }, why.join("; "))
}

fn anchor_header(first: &str, anchors: &[Anchor]) -> Vec<String> {
    let mut h = vec![first.to_string()];
    h.extend(
        anchors
            .iter()
            .enumerate()
            .map(|(i, a)| anchor_heading(a, i == 0)),
    );
    h
}

fn cells(first: String, cells: &[Hbm]) -> Vec<String> {
    let mut row = vec![first];
    row.extend(cells.iter().map(hbm));
    row
}

fn method(one_harmonic: bool) -> &'static str {
    if one_harmonic {
        "one harmonic"
    } else {
        "7 harmonics"
    }
}

/// Fig. 2's s1a1 under every reading and method.
fn fig2(r: &Record) -> String {
    let rows: Vec<Vec<String>> = r
        .fig2
        .rows
        .iter()
        .map(|row| {
            cells(
                format!(
                    "TE {} µm, {}, {}",
                    row.te_um,
                    row.reading,
                    method(row.one_harmonic)
                ),
                &row.cells,
            )
        })
        .collect();
    table(
        &anchor_header("TE, reading and method", &r.fig2.anchors),
        &rows,
    )
}

/// Fig. 2's panels b-d.
fn fig2_panels(r: &Record) -> String {
    let rows: Vec<Vec<String>> = r
        .fig2
        .panels
        .iter()
        .map(|p| cells(format!("x_{}, TE {} µm", p.mesh, p.te_um), &p.cells))
        .collect();
    table(&anchor_header("mesh and TE", &r.fig2.anchors), &rows)
}

/// Peaks with the unstable ones marked.
pub fn peaks(ps: &[(f64, bool)]) -> String {
    if ps.is_empty() {
        return "none".into();
    }
    ps.iter()
        .map(|&(w, stable)| {
            if stable {
                om3(w)
            } else {
                format!("{} (unstable)", om3(w))
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// Every branch's peaks.
fn fig2_peaks(r: &Record) -> String {
    let mut rows: Vec<Vec<String>> = r
        .fig2
        .rows
        .iter()
        .map(|row| {
            vec![
                format!(
                    "x_s1a1, TE {} µm, {}, {}",
                    row.te_um,
                    row.reading,
                    method(row.one_harmonic)
                ),
                peaks(&row.peaks),
            ]
        })
        .collect();
    rows.extend(r.fig2.panels.iter().map(|p| {
        vec![
            format!(
                "x_{}, TE {} µm, sine, every mesh, 7 harmonics",
                p.mesh, p.te_um
            ),
            peaks(&p.peaks),
        ]
    }));
    table(&strings(&["branch", "peaks (Ω)"]), &rows)
}

/// Real Omegas to 3 decimals as a table's cell.
fn spans3_cell(s: &super::data::Spans, each: impl Fn(f64) -> String) -> String {
    if s.is_empty() {
        "none".into()
    } else {
        s.iter()
            .map(|(a, b)| format!("{}–{}", each(*a), each(*b)))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// Where Fig. 2's TE leaves every mesh in contact.
fn contact(r: &Record) -> String {
    let s = &r.scale;
    let rows: Vec<Vec<String>> = r
        .fig2
        .contact
        .iter()
        .map(|c| {
            vec![
                format!("{}, TE {} µm", c.reading, c.te_um),
                spans3_cell(&c.kept, om3),
                spans3_cell(&c.kept, |w| om3(w / s.factor)),
                spans3_cell(&c.kept, |w| grouped(w * s.rpm_per_omega)),
            ]
        })
        .collect();
    table(
        &strings(&[
            "reading and TE",
            "Ω (gearshock's, and the paper's read literally)",
            "the paper's Ω, matched",
            "input speed (rpm)",
        ]),
        &rows,
    )
}

fn fig3_header(r: &Record) -> Vec<String> {
    let n = r.fig3.omegas.len() / 2;
    let mut h = vec!["backlash".to_string()];
    for (i, w) in r.fig3.omegas.iter().enumerate() {
        if i < n {
            h.push(format!("Ω {}", super::words::omega_arg(*w)));
        } else {
            h.push(format!(
                "Ω {} (the paper's {} matched)",
                om3(*w),
                super::words::omega_arg(r.fig3.omegas[i - n])
            ));
        }
    }
    h
}

/// Fig. 3 by time integration, one cell per Omega written by `cell`.
fn fig3(r: &Record, cell: fn(&Orbit) -> String) -> String {
    let rows: Vec<Vec<String>> = r
        .fig3
        .rows
        .iter()
        .map(|row| {
            let mut out = vec![format!("{} µm", row.backlash_um)];
            out.extend(row.orbits.iter().map(cell));
            out
        })
        .collect();
    table(&fig3_header(r), &rows)
}

/// Fig. 3's other readings: the mean TE and the one-harmonic branch.
fn fig3_other(r: &Record) -> String {
    let mut rows: Vec<Vec<String>> = r
        .fig3
        .mean
        .iter()
        .map(|(b, xs)| {
            let mut out = vec![format!("{b} µm, mean TE (time integration)")];
            out.extend(xs.iter().map(|&x| um(x)));
            out
        })
        .collect();
    rows.extend(r.fig3.every_mesh.iter().map(|row| {
        let mut out = vec![format!(
            "{} µm, TE on every mesh (time integration)",
            row.backlash_um
        )];
        out.extend(
            row.orbits
                .iter()
                .map(|o| format!("{} ({}, {})", um(o.amplitude_um), o.impact, o.motion)),
        );
        out
    }));
    rows.extend(r.fig3.one_harmonic.iter().map(|(b, hs)| {
        let mut out = vec![format!("{b} µm, one harmonic (harmonic balance)")];
        out.extend(hs.iter().map(hbm));
        out
    }));
    let mut h = fig3_header(r);
    h[0] = "backlash and reading".into();
    table(&h, &rows)
}

/// Fig. 4's amplitudes.
fn fig4(r: &Record) -> String {
    let hm = r
        .fig4
        .first()
        .map_or((f64::NAN, f64::NAN), |s| s.high_matched);
    let mut h = vec!["TE".to_string()];
    h.extend(
        super::sweeps::AMPLITUDE_AT
            .iter()
            .map(|w| format!("Ω {}", super::words::omega_arg(*w))),
    );
    h.push("first-mode peak (finer grid)".into());
    h.push(format!(
        "largest at Ω {}–{}",
        super::words::omega_arg(HIGH.0),
        super::words::omega_arg(HIGH.1)
    ));
    h.push(format!(
        "largest at Ω {}–{} (the paper's {}–{} matched)",
        om(hm.0),
        om(hm.1),
        super::words::omega_arg(HIGH.0),
        super::words::omega_arg(HIGH.1)
    ));
    h.push(format!(
        "delta at Ω {}",
        super::words::omega_arg(super::sweeps::AMPLITUDE_AT[1])
    ));
    let rows: Vec<Vec<String>> = r
        .fig4
        .iter()
        .map(|s| {
            let mut out = vec![format!("{} µm", s.case.te_um)];
            out.extend(s.amplitude_at.iter().map(|&x| um(x)));
            out.push(s.fine.as_ref().map_or("–".into(), |f| {
                format!(
                    "{} at Ω {}",
                    um(f.first_mode_peak.1),
                    super::words::omf(f.first_mode_peak.0)
                )
            }));
            out.push(um(s.largest_high_um));
            out.push(um(s.largest_high_matched_um));
            out.push(um(s.delta_at_025_um));
            out
        })
        .collect();
    table(&h, &rows)
}

/// Fig. 4's motion and impacts per TE.
fn fig4_motion(sweeps: &[Sweep]) -> String {
    let rows: Vec<Vec<String>> = sweeps
        .iter()
        .map(|s| {
            vec![
                format!("{} µm", s.case.te_um),
                s.first_not_period_1.map_or("none".into(), om),
                spans(&s.not_periodic),
                um(s.lowest_x_um.0),
                spans(&s.s1a1_parts),
                spans(&s.any_parts),
                spans(&s.x_negative),
                spans(&s.any_back),
            ]
        })
        .collect();
    table(
        &strings(&[
            "TE",
            "first Ω without period 1",
            "not periodic",
            "lowest x (µm)",
            "drive flanks part, s1a1",
            "drive flanks part, any mesh",
            "x negative",
            "back flanks touch, any mesh",
        ]),
        &rows,
    )
}

/// An orbit as a table's cell.
pub fn orbit_cell(o: &Orbit) -> String {
    let mut s = format!(
        "{}, {}, {} µm, {} m/s",
        o.motion,
        o.impact,
        um(o.amplitude_um),
        m_s(o.velocity_m_s)
    );
    if !o.back_flanks.is_empty() {
        s.push_str(&format!(
            "; back flanks touch on {}",
            o.back_flanks.join(", ")
        ));
    }
    s
}

/// Figs. 5-7 (`backlash` false) or 9-11 (true).
fn orbit_rows(r: &Record, backlash: bool) -> String {
    let chosen: Vec<&orbits::Row> = r
        .orbits
        .iter()
        .filter(|row| {
            orbits::FIGURES
                .iter()
                .any(|f| f.0 == row.figure && f.2 == backlash)
        })
        .collect();
    let values = chosen.first().map_or(Vec::new(), |row| row.values.clone());
    let mut h = vec!["figure".to_string()];
    h.extend(values.iter().map(|v| {
        if backlash {
            format!("backlash {v} µm")
        } else {
            format!("TE {v} µm")
        }
    }));
    let rows: Vec<Vec<String>> = chosen
        .iter()
        .map(|row| {
            let w = row.orbits.first().map_or(f64::NAN, |o| o.omega);
            let mut out = vec![if row.matched {
                format!(
                    "Fig. {}, Ω {} (the paper's {} matched)",
                    row.figure,
                    om3(w),
                    super::words::omega_arg(row.paper_omega)
                )
            } else {
                format!("Fig. {}, Ω {}", row.figure, super::words::omega_arg(w))
            }];
            out.extend(row.orbits.iter().map(orbit_cell));
            out
        })
        .collect();
    table(&h, &rows)
}

/// A spike inside a window as a table writes it.
fn spike_cell(w: &Window) -> String {
    if w.spikes.is_empty() {
        return "none".into();
    }
    w.spikes
        .iter()
        .map(|s| {
            format!(
                "{} (under {} wide)",
                super::words::spanf(&s.parts),
                super::words::omega_arg(s.between.1 - s.between.0)
            )
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// Claim 10's windows, one row each.
fn windows(r: &Record, which: fn(&CaseWindows) -> &Vec<Window>) -> String {
    let s = &r.scale;
    let mut rows = Vec::new();
    for c in &r.advice.cases {
        for w in which(c) {
            let (a, b) = w.free;
            rows.push(vec![
                format!("{} µm", c.backlash_um),
                format!("{} µm", c.te_um),
                super::words::spanf(&w.free),
                super::words::pair(a / s.factor, b / s.factor, om3),
                super::words::pair(a * s.rpm_per_omega, b * s.rpm_per_omega, grouped),
                spike_cell(w),
            ]);
        }
    }
    table(
        &strings(&[
            "backlash",
            "TE",
            "Ω (gearshock's, and the paper's read literally)",
            "the paper's Ω, matched",
            "input speed (rpm)",
            "spikes of impact inside (Ω)",
        ]),
        &rows,
    )
}
