//! Renders the document and the page's claims from the record: every
//! named value ([`super::intro`], [`super::frequency`], [`super::time`],
//! [`super::speed`], [`super::tables`],
//! the commands below), the claims' texts ([`super::claims`]) filled with
//! them, then the template; nothing is written if a premise of the words
//! fails.

use super::claims::CLAIMS;
use super::fill::Values;
use super::record::Record;
use super::{advice, fig2, fig3, orbits, scale, sweeps};
use crate::failure::Failure;
use serde::Serialize;

/// The document's template.
const TEMPLATE: &str = include_str!("template.md");

/// One claim as the page reads it (`crates/app/src/claims.rs`' `Claim`).
#[derive(Serialize)]
struct PageClaim {
    id: String,
    says: String,
    verdict: String,
    evidence: String,
    figure: Option<String>,
    command: String,
    with: String,
}

/// The document and the claims' JSON.
pub fn render(record: &Record) -> Result<(String, String), Failure> {
    let mut v = Values::default();
    super::intro::set(&mut v, record)?;
    super::frequency::set(&mut v, record)?;
    super::time::set(&mut v, record)?;
    super::speed::set(&mut v, record)?;
    for (name, table) in super::tables::all(record) {
        v.set(name, table);
    }
    commands(&mut v, record);
    let mut page = Vec::new();
    let mut glance = vec![
        "| # | the paper says | verdict |".to_string(),
        "|---|---|---|".to_string(),
    ];
    for c in CLAIMS {
        let says = v.fill(c.says)?;
        let verdict = v.fill(c.verdict)?;
        let evidence = v.fill(c.evidence)?;
        let command = need(&v, c.command)?;
        let with = if c.with.is_empty() {
            String::new()
        } else {
            need(&v, c.with)?.replace('`', "")
        };
        if c.id.starts_with(|ch: char| ch.is_ascii_digit()) {
            glance.push(format!("| {} | {says} | {verdict} |", c.id));
        }
        v.set(&format!("claim.{}.verdict", c.id), verdict.clone());
        v.set(&format!("claim.{}.evidence", c.id), evidence.clone());
        page.push(PageClaim {
            id: c.id.to_string(),
            says,
            verdict,
            evidence,
            figure: Some(c.figure.to_string()),
            command,
            with,
        });
    }
    v.set("table.glance", glance.join("\n"));
    let doc = super::wrap::rewrap(&v.fill(TEMPLATE)?);
    v.premises()?;
    let claims = serde_json::to_string_pretty(&page).map_err(|e| Failure {
        code: 1,
        message: format!("the claims are not JSON: {e}"),
    })?;
    Ok((doc, format!("{claims}\n")))
}

fn need(v: &Values, name: &str) -> Result<String, Failure> {
    v.get(name).map(str::to_string).ok_or_else(|| Failure {
        code: 1,
        message: format!("no value for {name}"),
    })
}

/// The quoted commands and the values of their placeholders.
fn commands(v: &mut Values, r: &Record) {
    let h1 = fig2::ONE_HARMONIC;
    v.set("cmd.modes", scale::MODES);
    v.set("cmd.modes_printed", scale::MODES_PRINTED);
    v.set("cmd.instability", scale::INSTABILITY);
    v.set("cmd.sweep", sweeps::SWEEP);
    v.set("cmd.fine", sweeps::FINE);
    v.set("cmd.lyapunov", sweeps::lyapunov_template());
    v.set("cmd.fig2", fig2::SINE);
    v.set("cmd.fig2_cos", fig2::COSINE);
    v.set("cmd.fig2_h1", format!("{}{h1}", fig2::SINE));
    v.set("cmd.fig2_cos_h1", format!("{}{h1}", fig2::COSINE));
    v.set("cmd.fig2_linear", fig2::SINE.replace("$reading", "s1a"));
    v.set("cmd.fig3", fig3::SIMULATE);
    v.set("cmd.fig3_mean", fig3::MEAN);
    v.set(
        "cmd.fig3_all",
        fig3::SIMULATE.replace(" --mesh", &format!("{} --mesh", fig3::EVERY_MESH)),
    );
    v.set("readings.every_mesh_set", fig3::EVERY_MESH.trim());
    v.set("cmd.fig3_frf", fig3::FRF);
    v.set("cmd.fig3_frf_h1", format!("{}{h1}", fig3::FRF));
    v.set("cmd.te", orbits::TE);
    v.set("cmd.backlash", orbits::BACKLASH);

    let readings: Vec<String> = fig2::READINGS
        .iter()
        .filter(|x| !x.2.is_empty())
        .map(|x| x.2.to_string())
        .collect();
    v.set(
        "with.fig2",
        format!(
            "`reading` = {}, `te` = {}",
            readings.join(" or "),
            fig2::TES.map(|t| t.to_string()).join(" or ")
        ),
    );
    let omegas: Vec<String> = r
        .fig3
        .omegas
        .iter()
        .enumerate()
        .map(|(i, w)| {
            if i < r.fig3.omegas.len() / 2 {
                super::words::omega_arg(*w)
            } else {
                super::words::om3(*w)
            }
        })
        .collect();
    v.set(
        "with.fig3",
        format!(
            "`b` = {}; `w` = {}",
            fig3::BACKLASHES.map(|b| b.to_string()).join(", "),
            omegas.join(", ")
        ),
    );
    v.set(
        "with.fig4",
        format!(
            "`b` = {} and `te` = {}",
            super::record::FIG4_BACKLASH,
            orbits::TES.map(|t| t.to_string()).join(", ")
        ),
    );
    v.set(
        "with.fig8",
        format!(
            "`b` = {} and `te` = {}",
            orbits::BACKLASHES.map(|b| b.to_string()).join(", "),
            super::record::FIG8_TE
        ),
    );
    let grids = sweeps::FINE_GRIDS
        .iter()
        .map(|(a, b, n)| {
            format!(
                "{}, {}, {n}",
                super::words::omega_arg(*a),
                super::words::omega_arg(*b)
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    v.set("with.fine_grids", format!("`from`, `to`, `n` = {grids}"));
    v.set(
        "with.fine4",
        format!(
            "`b` = {}, `te` = {}; `from`, `to`, `n` = {grids}",
            super::record::FIG4_BACKLASH,
            orbits::TES.map(|t| t.to_string()).join(", ")
        ),
    );
    v.set(
        "with.fine10",
        format!(
            "(`b`, `te`) = {}; `from`, `to`, `n` = {grids}",
            advice::CASES
                .iter()
                .map(|(b, te)| format!("({b}, {te})"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    );
    let figure_omegas = |figures: &[(u32, f64, bool)]| {
        let literal: Vec<String> = figures
            .iter()
            .map(|f| super::words::omega_arg(f.1))
            .collect();
        let matched: Vec<String> = figures
            .iter()
            .map(|f| super::words::om3(r.scale.matched(f.1)))
            .collect();
        format!("{} and matched {}", literal.join(", "), matched.join(", "))
    };
    let te_figures: Vec<(u32, f64, bool)> =
        orbits::FIGURES.iter().copied().filter(|f| !f.2).collect();
    let b_figures: Vec<(u32, f64, bool)> =
        orbits::FIGURES.iter().copied().filter(|f| f.2).collect();
    v.set(
        "with.te",
        format!(
            "`x` = {}; `w` = {}",
            orbits::TES.map(|t| t.to_string()).join(", "),
            figure_omegas(&te_figures)
        ),
    );
    v.set(
        "with.backlash",
        format!(
            "`x` = {}; `w` = {}",
            orbits::BACKLASHES.map(|t| t.to_string()).join(", "),
            figure_omegas(&b_figures)
        ),
    );
}
