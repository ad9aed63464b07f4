//! The values of claim 10, the paper's advice on speed: the windows of
//! Omega free of impacts per case, with the premises their fixed words
//! rest on.

use super::advice::{CaseWindows, Window};
use super::fill::Values;
use super::lookup::need;
use super::record::Record;
use super::words::{and, grouped, ints, om3, omega_arg, omf, spanf, spans3_and};
use crate::failure::Failure;

/// A window as a sentence writes it, with its spikes.
fn window_words(w: &Window) -> String {
    let mut out = spanf(&w.free);
    let widths: Vec<String> = w
        .spikes
        .iter()
        .map(|s| omega_arg(s.between.1 - s.between.0))
        .collect();
    let at = and(&w.spikes.iter().map(|s| spanf(&s.parts)).collect::<Vec<_>>());
    match w.spikes.len() {
        0 => {}
        1 => out.push_str(&format!(
            " (a spike of impact at {at}, under {} wide)",
            widths[0]
        )),
        _ if widths.windows(2).all(|p| p[0] == p[1]) => {
            out.push_str(&format!(
                " (spikes of impact at {at}, each under {} wide)",
                widths[0]
            ));
        }
        _ => out.push_str(&format!(
            " (spikes of impact at {}, under {} wide)",
            at,
            and(&widths)
        )),
    }
    out
}

fn windows_and(ws: &[Window]) -> String {
    and(&ws.iter().map(window_words).collect::<Vec<_>>())
}

/// Sets every value of claim 10.
pub fn set(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let s = &r.scale;
    let cases = &r.advice.cases;
    let by = |b: u32, te: u32| {
        need(
            cases.iter().find(|c| c.backlash_um == b && c.te_um == te),
            &format!("claim 10's case {b} µm, {te} µm"),
        )
    };
    let range = need(cases.first(), "claim 10's cases")?.range;
    v.set(
        "c10.range",
        format!("{}–{}", omega_arg(range.0), omega_arg(range.1)),
    );
    v.ensure(
        cases
            .iter()
            .all(|c| !c.every_mesh.is_empty() && c.every_mesh[0].free.0 < 0.8),
        "every case has an impact-free window below the paper's 0.8",
    );
    // With 20 µm TE: the same windows at every backlash.
    let te20: Vec<&CaseWindows> = cases
        .iter()
        .filter(|c| c.te_um == super::record::FIG8_TE)
        .collect();
    let w20 = need(te20.first(), "claim 10's cases with 20 µm TE")?;
    v.ensure(
        te20.iter().all(|c| c.every_mesh == w20.every_mesh),
        "with 20 µm TE the windows are the same for every backlash",
    );
    v.set("c10.windows_20", windows_and(&w20.every_mesh));
    let mut bs: Vec<u32> = te20.iter().map(|c| c.backlash_um).collect();
    bs.sort_unstable();
    v.set("c10.backlashes_20", ints(&bs));
    // The verdict: one line per TE.
    let mut glance = Vec::new();
    let mut tes: Vec<u32> = cases.iter().map(|c| c.te_um).collect();
    tes.sort_unstable();
    tes.dedup();
    for te in &tes {
        let c = need(cases.iter().find(|c| c.te_um == *te), "a case")?;
        let below: Vec<String> = c
            .every_mesh
            .iter()
            .filter(|w| w.free.0 < 0.8)
            .map(|w| spanf(&w.free))
            .collect();
        let label = if *te == 0 {
            "without TE".to_string()
        } else if cases.iter().filter(|x| x.te_um == *te).count() > 1 {
            format!("{te} µm TE at every backlash")
        } else {
            format!("{te} µm TE")
        };
        glance.push(format!("{label}: Ω {}", and(&below)));
    }
    v.set("c10.glance", glance.join("; "));
    // Every window with TE lies below the paper's 0.8 on both scales.
    let with_te: Vec<&CaseWindows> = cases.iter().filter(|c| c.te_um > 0).collect();
    let top_te = with_te
        .iter()
        .filter_map(|c| c.every_mesh.last().map(|w| w.free.1))
        .fold(f64::NEG_INFINITY, f64::max);
    v.ensure(
        top_te < s.matched(0.8),
        "with TE every window lies below the paper's 0.8 on both scales",
    );
    v.set("c10.top_te", omf(top_te));
    v.set("c10.top_te_paper", om3(top_te / s.factor));
    v.set("c10.top_te_rpm", grouped(top_te * s.rpm_per_omega));
    // The impacts between the windows with 20 µm TE.
    let gaps: Vec<(f64, f64)> = w20
        .every_mesh
        .windows(2)
        .map(|p| (p[0].free.1, p[1].free.0))
        .collect();
    let holding = |w: f64| gaps.iter().copied().find(|(a, b)| *a < w && w < *b);
    let g1 = need(holding(s.first_mode), "an impact range at the first mode")?;
    let m2 = need(s.rotational.get(1).copied(), "the second mode")?;
    let g2 = need(holding(m2 / 2.0), "an impact range at half the second mode")?;
    v.set(
        "c10.first_mode_gap",
        format!("between the windows, {}–{}", omf(g1.0), omf(g1.1)),
    );
    v.set(
        "c10.half_second_gap",
        format!("{}–{}", omf(g2.0), omf(g2.1)),
    );
    v.ensure(
        w20.every_mesh.iter().any(|w| {
            w.spikes
                .iter()
                .any(|k| (k.parts.0 - s.first_mode / 2.0).abs() < 0.005)
        }),
        "a spike of impact sits at half the first mode",
    );
    v.ensure(
        w20.every_mesh
            .last()
            .is_some_and(|w| (w.free.1 - top_te).abs() < 1e-9)
            && with_te
                .iter()
                .all(|c| c.every_mesh.iter().all(|w| w.free.1 <= top_te + 1e-9)),
        "between the last window with TE and 0.8 the flanks of some mesh part everywhere",
    );
    let smallest = need(bs.first().copied(), "the smallest backlash")?;
    let b50 = by(smallest, super::record::FIG8_TE)?;
    let (back, mesh) = need(
        b50.first_back.clone(),
        "the first back-flank contact with 50 µm",
    )?;
    v.ensure(
        back > top_te,
        "the back flanks first touch above every window",
    );
    v.ensure(
        cases
            .iter()
            .filter(|c| c.backlash_um > smallest)
            .all(|c| c.first_back.is_none()),
        "only the smallest backlash reaches the back flanks on the finer grids",
    );
    v.set("c10.b50", b50.backlash_um.to_string());
    v.set("c10.b50_back", omf(back));
    v.set("c10.b50_back_mesh", mesh);
    let te0 = by(super::record::FIG4_BACKLASH, 0)?;
    let high: Vec<Window> = te0
        .every_mesh
        .iter()
        .filter(|w| w.free.0 > 0.8)
        .cloned()
        .collect();
    v.ensure(!high.is_empty(), "without TE there are windows above 0.8");
    v.set("c10.high_te0", windows_and(&high));
    // s1a1 alone.
    v.ensure(
        cases.iter().all(|c| {
            c.every_mesh.iter().all(|w| {
                c.s1a1
                    .iter()
                    .any(|x| x.free.0 <= w.free.0 + 1e-9 && w.free.1 <= x.free.1 + 1e-9)
            })
        }),
        "the windows of s1a1 alone hold those of every mesh",
    );
    let s1a1_first = need(w20.s1a1.first(), "s1a1's windows")?;
    v.set("c10.s1a1_top", window_words(s1a1_first));
    let any_first = w20
        .every_mesh
        .iter()
        .flat_map(|w| w.spikes.iter().map(|k| k.parts.0))
        .chain(w20.every_mesh.first().map(|w| w.free.1))
        .fold(f64::INFINITY, f64::min);
    v.set("c10.any_first", omf(any_first));
    v.ensure(
        s1a1_first.free.1 > top_te,
        "s1a1 alone keeps contact beyond every window of all the meshes",
    );
    // The harmonic balance without backlash.
    v.set("c10.linear_20", spans3_and(&w20.linear_kept));
    let ti: Vec<(f64, f64)> = {
        // The time integration's windows with their spikes cut out.
        let mut out = Vec::new();
        for w in &w20.every_mesh {
            let mut start = w.free.0;
            for k in &w.spikes {
                out.push((start, k.between.0));
                start = k.between.1;
            }
            out.push((start, w.free.1));
        }
        out
    };
    // The branch starts at Omega 0.1, the sweeps lower: compare from there.
    let from = w20.linear_kept.first().map_or(0.0, |w| w.0);
    let near = |a: &[(f64, f64)], b: &[(f64, f64)]| {
        a.iter().all(|(x, y)| {
            b.iter()
                .any(|(p, q)| (x.max(from) - p.max(from)).abs() < 0.01 && (y - q).abs() < 0.01)
        })
    };
    v.set(
        "c10.windows_20_plain",
        and(&ti.iter().map(spanf).collect::<Vec<_>>()),
    );
    v.ensure(
        near(&w20.linear_kept, &ti) && near(&ti, &w20.linear_kept),
        "the harmonic balance without backlash gives the same windows as the time integration",
    );
    v.set("c10.spike", omega_arg(super::advice::SPIKE));
    Ok(())
}
