//! `gearshock figure ID --out DIR`: computes every panel of one of the
//! paper's figures (a preset of `figures::presets`, the page's own table) and
//! writes, per panel, an SVG drawn by the page's plotting code (plotters'
//! SVG backend) and the panel's data as JSON and CSV.
//!
//! Orbit figures (5-7, 9-11): panels a-c are the phase portraits of the
//! family's members, d-f their Poincaré sections. Bifurcation figures (4, 8):
//! panels a-c, one sweep per member. Frequency-response figures (2, 3):
//! panels a-d, one mesh kind each, every member's harmonic-balance branch in
//! each panel's data and every member's curve overlaid in its SVG, one
//! colour per value named in words, as the page's frequency response draws
//! a family.
//!
//! `figure map` ([`map`]): the page's impact-regime map of a link with its
//! boundaries traced over it.
//!
//! Sharding (the heavy figures, 4-11): `--shard i/n` computes the sweeps or
//! orbits of members i, i + n, ... only and prints them as one JSON shard
//! ([`shard`]); `gearshock merge --out DIR` checks them against the
//! figure's definition and draws every file itself, as the unsharded run
//! does (which draws from the same JSON), so the files are the unsharded
//! run's byte for byte and no file text is ever passed through. Figs. 2 and
//! 3 are not sharded: each of their panels holds every member's branch.

mod cost;
mod map;
pub mod shard;

use crate::failure::{usage, Failure};
use crate::{output, progress};
use clap::Args;
use figures::presets::{preset, Preset};
use figures::protocol::{OmegaResult, RunOptions};
use figures::views::bif::{BifPoint, BifView};
use figures::views::omega::OmegaView;
use plotters::prelude::{IntoDrawingArea, SVGBackend};
use serde_json::{json, Value};
use solver::hbm::{FrfContinuation, FrfSpec};
use solver::steady::Model;
use solver::sweep::{canonical_order, BifurcationSweep, Direction, SweepSpec};
use std::path::{Path, PathBuf};
use worker::jobs::omega::{omega_result, selected_spec, OmegaJob};

/// Size of each panel's SVG (pixels).
const SIZE: (u32, u32) = (800, 500);

/// Options of `gearshock figure`.
#[derive(Debug, Args)]
pub struct FigureArgs {
    /// The figure's preset id, e.g. fig5 (see `gearshock presets`).
    pub(crate) id: String,
    /// Directory for the SVG, JSON and CSV files (created if missing);
    /// not with --shard, whose JSON goes to `gearshock merge --out DIR`.
    #[arg(long, value_name = "DIR")]
    pub(crate) out: Option<PathBuf>,
    /// Omega points of a bifurcation panel, or the nominal points of a
    /// frequency-response branch (default: the preset's, 100 or 150).
    #[arg(long)]
    pub(crate) points: Option<u32>,
    /// Maximum transient mesh periods (default: the preset's, 300).
    #[arg(long)]
    pub(crate) transient_periods: Option<u32>,
    /// Recorded mesh periods (default: the preset's, 100).
    #[arg(long)]
    pub(crate) record_periods: Option<u32>,
    /// Compute only shard i of n (the panels of members i, i + n, ...) of
    /// a bifurcation or orbit figure and print it as JSON; join the shards
    /// with `gearshock merge --out DIR`.
    #[arg(long, value_name = "I/N")]
    pub(crate) shard: Option<String>,
    /// `figure map` only: the page's link (or its query) whose map to
    /// draw, e.g. `model=gear-pair&map_omega_points=30` (default: the
    /// page's defaults).
    #[arg(long, value_name = "QUERY")]
    pub(crate) link: Option<String>,
}

/// The files of a figure's panels, in order: (file name, contents).
pub(crate) type Files = Vec<(String, String)>;

/// One member of the family: its link and decoded settings.
pub(crate) struct Member {
    pub(crate) query: String,
    pub(crate) settings: figures::settings::Settings,
    pub(crate) model: Model,
}

pub(crate) fn members(p: &Preset) -> Result<Vec<Member>, Failure> {
    let count = p.family.map_or(1, |f| f.values.len());
    (0..count)
        .map(|m| {
            let query = p.member_query(m, 0);
            let d = figures::link::decode(&query);
            if let Some(issue) = d.issues.first() {
                return Err(usage(format!("figure {}: {issue}", p.id)));
            }
            let model = Model::new(&d.settings.params)?;
            Ok(Member {
                query,
                settings: d.settings,
                model,
            })
        })
        .collect()
}

fn drawn<T, E: std::fmt::Display>(name: &str, result: Result<T, E>) -> Result<T, Failure> {
    result.map_err(|e| Failure {
        code: crate::output::EXIT_IO,
        message: format!("cannot draw {name}: {e}"),
    })
}

/// The member's value in words, for the panel's caption: ", TE 20 µm".
fn member_label(p: &Preset, i: usize) -> String {
    match p.family {
        Some(f) => {
            let what = match f.key {
                "te_um" => "TE",
                "backlash_um" => "backlash",
                other => other,
            };
            let x = f.values.get(i).copied().unwrap_or(f64::NAN);
            format!(", {what} {x} µm")
        }
        None => String::new(),
    }
}

pub(crate) fn panel_letter(i: usize) -> char {
    char::from(b'a' + (i % 26) as u8)
}

/// The options' ranges (a merge checks a shard's options by them too).
pub(crate) fn check_options(args: &FigureArgs) -> Result<(), Failure> {
    for (flag, value, min, max) in [
        ("--points", args.points, 2, 2000),
        ("--transient-periods", args.transient_periods, 1, 100_000),
        ("--record-periods", args.record_periods, 1, 10_000),
    ] {
        if let Some(v) = value.filter(|v| !(min..=max).contains(v)) {
            return Err(usage(format!(
                "{flag} {v} is out of range: allowed {min} ..= {max}"
            )));
        }
    }
    Ok(())
}

/// Runs the command; returns the list of panels and files written.
pub fn run(args: &FigureArgs) -> Result<Value, Failure> {
    if args.id == "map" {
        return map::run(args);
    }
    if args.link.is_some() {
        return Err(usage(format!(
            "figure {} --link: only `figure map` takes a link",
            solver::keys::truncate(&args.id, 30)
        )));
    }
    let Some(p) = preset(&args.id) else {
        let ids: Vec<&str> = figures::presets::PRESETS
            .iter()
            .map(|p| p.id)
            .filter(|id| id.starts_with("fig"))
            .collect();
        return Err(usage(format!(
            "figure {}: no such figure; allowed {}, map",
            solver::keys::truncate(&args.id, 30),
            ids.join(", ")
        )));
    };
    check_options(args)?;
    let is = |key: &str| p.settings.iter().any(|(k, _)| *k == key);
    if p.family.is_none() {
        return Err(usage(format!(
            "figure {}: not one of the paper's figures (no family of panels)",
            p.id
        )));
    }
    let members = members(p)?;
    let heavy = is("bif_dir") || is("omega");
    let panels = if is("bif_dir") {
        cost::Panels::Bifurcation
    } else if heavy {
        cost::Panels::Orbits
    } else {
        cost::Panels::FrequencyResponse
    };

    let shard = match &args.shard {
        None => None,
        Some(_) if !heavy => {
            return Err(usage(format!(
                "figure {} --shard: not sharded (each panel holds every member's branch); allowed for figures 4-11",
                p.id
            )))
        }
        Some(_) if args.out.is_some() => {
            return Err(usage(
                "figure --shard prints its shard as JSON: give --out to `gearshock merge --out DIR` instead",
            ))
        }
        Some(text) => {
            let (i, n) = crate::args::parse_shard(text)?;
            if n as usize > members.len() {
                return Err(usage(format!(
                    "--shard {text}: figure {} has {} members (one per panel), so at most {} shards",
                    p.id,
                    members.len(),
                    members.len()
                )));
            }
            Some((i as usize, n as usize))
        }
    };
    // The work of this command's members (a shard's only), before any.
    let mine: Vec<&Member> = members
        .iter()
        .enumerate()
        .filter(|(k, _)| shard.is_none_or(|(i, n)| k % n == i))
        .map(|(_, m)| m)
        .collect();
    cost::check(p.id, panels, &mine, args)?;
    if let Some((i, n)) = shard {
        // One shard: its members' sweeps or orbits as JSON; the merge draws.
        return shard::compute(p, &members, args, (i, n), is("bif_dir"));
    }
    let out = args
        .out
        .as_ref()
        .ok_or_else(|| usage("figure: --out DIR is required (or --shard i/n)"))?;
    // Before the work: a folder that cannot take the files would lose it.
    output::check_dir("--out", out)?;
    let mut files = Files::new();
    let panels = if is("bif_dir") {
        bifurcation_panels(p, &members, args, &mut files)?
    } else if is("omega") {
        orbit_panels(p, &members, args, &mut files)?
    } else {
        frf_panels(p, &members, args, &mut files)?
    };
    write_all(out, &files)?;
    Ok(listing(p, out, panels))
}

/// The command's report: the figure and its panels, sorted a, b, c, ...
pub(crate) fn listing(p: &Preset, out: &Path, mut panels: Vec<Value>) -> Value {
    panels.sort_by(|a, b| a["panel"].as_str().cmp(&b["panel"].as_str()));
    json!({ "id": p.id, "title": p.title, "out": out.display().to_string(), "panels": panels })
}

/// Creates `out` and writes the files into it, each whole or not at all.
pub(crate) fn write_all(out: &Path, files: &Files) -> Result<(), Failure> {
    output::check_dir("--out", out)?;
    output::write_files(out, files)
}

/// Panels a-d: one mesh each; every member's branch on every panel.
fn frf_panels(
    p: &Preset,
    members: &[Member],
    args: &FigureArgs,
    files: &mut Files,
) -> Result<Vec<Value>, Failure> {
    let names: &[&str] = p.meshes.unwrap_or(&[]);
    let mut bar = progress::Progress::new(members.len() * 1000, "per mille of the branches", false);
    // Per member: the JSON of its branch on each panel's mesh, and the
    // branch as the page's store (for the SVG's overlaid curves).
    let mut per_panel: Vec<Vec<Value>> = vec![Vec::new(); names.len()];
    let mut stores: Vec<figures::views::fr::HbmStore> = Vec::new();
    let mut failures = Vec::new();
    for (i, m) in members.iter().enumerate() {
        let v = &m.settings.view;
        let mut spec = FrfSpec::new(v.omega_from, v.omega_to, args.points.unwrap_or(v.fr_points));
        spec.harmonics = v.harmonics as usize;
        let mut c = FrfContinuation::new(&m.model, spec)?;
        let mut branch = Vec::new();
        let mut failure = None;
        while !c.is_finished() {
            match c.advance(16) {
                Ok(pts) => branch.extend(pts),
                Err(e) => {
                    failure = Some(e);
                    break;
                }
            }
            bar.update(i * 1000 + (c.progress() * 1000.0) as usize);
        }
        if let Some(e) = &failure {
            failures.push(format!("{}: {e}", m.query));
        }
        stores.push(figures::views::fr::HbmStore {
            harmonics: v.harmonics,
            points: branch.iter().map(worker::jobs::hbm::hbm_sample).collect(),
            progress: c.progress(),
            finished: true,
            error: failure.as_ref().map(ToString::to_string),
            notes: c.notes(),
        });
        for (k, name) in names.iter().enumerate() {
            let j =
                m.model.system.mesh_index(name).ok_or_else(|| {
                    usage(format!("figure {}: no mesh {name} in this model", p.id))
                })?;
            let mut data = report::frf_json(
                &m.model,
                &m.settings.params,
                &c,
                &branch,
                &[j],
                failure.as_ref(),
            );
            data["query"] = json!(m.query);
            data["member"] = json!(p.family.and_then(|f| f.values.get(i).copied()));
            per_panel[k].push(data);
        }
    }
    bar.finish();
    let mut out = Vec::new();
    for (k, (name, branches)) in names.iter().zip(per_panel).enumerate() {
        let panel = format!("{}{}", p.id, panel_letter(k));
        let mut csv =
            String::from("member,omega,delta_max_m,delta_min_m,delta_amplitude_m,stable\n");
        for b in &branches {
            for pt in b["branch"].as_array().into_iter().flatten() {
                csv.push_str(&format!(
                    "{},{},{},{},{},{}\n",
                    b["member"],
                    pt["omega"],
                    pt["delta_max_m"],
                    pt["delta_min_m"],
                    pt["delta_amplitude_m"],
                    pt["stable"]
                ));
            }
        }
        let complete = branches.iter().all(|b| b["complete"] == true);
        let svg = format!("{panel}.svg");
        let view = frf_view(p, members, &stores, name)?;
        let mut text = String::new();
        {
            let size = (figures::plots::WIDTH, figures::plots::HEIGHT);
            let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
            drawn(&svg, figures::plots::draw_fr(&root, &view, "").map(|_| ()))?;
        }
        files.push((svg, text));
        let data = json!({
            "mesh": name,
            "family": p.family.map(|f| json!({ "key": f.key, "values": f.values })),
            "members": branches,
        });
        files.push((format!("{panel}.json"), data.to_string()));
        files.push((format!("{panel}.csv"), csv));
        out.push(json!({
            "panel": panel,
            "view": "frequency-response",
            "mesh": name,
            "complete": complete,
            "svg": format!("{panel}.svg"),
            "files": [format!("{panel}.svg"), format!("{panel}.json"), format!("{panel}.csv")],
        }));
    }
    if !failures.is_empty() {
        // Reported, never shown as a result: the partial branches were
        // written, marked incomplete.
        return Err(Failure {
            code: 1,
            message: format!(
                "figure {}: the branch stopped early for {} (the partial branches were written, marked incomplete)",
                p.id,
                failures.join("; ")
            ),
        });
    }
    Ok(out)
}

/// The page's frequency-response view of one panel: every member's branch
/// on mesh `name`, one colour each, named in words ("TE 20 µm"), with every
/// member's ±b.
fn frf_view(
    p: &Preset,
    members: &[Member],
    stores: &[figures::views::fr::HbmStore],
    name: &str,
) -> Result<figures::views::fr::FrView, Failure> {
    let first = members
        .first()
        .ok_or_else(|| usage(format!("figure {}: no members", p.id)))?;
    let mesh = |m: &Member| {
        m.model
            .system
            .mesh_index(name)
            .ok_or_else(|| usage(format!("figure {}: no mesh {name} in this model", p.id)))
    };
    let j = mesh(first)?;
    let v = &first.settings.view;
    let ctx = figures::views::ViewContext {
        omega_from: v.omega_from,
        omega_to: v.omega_to,
        selected_omega: v.omega,
        mesh_label: name.to_string(),
        natural: figures::views::natural_in_range(&first.model, v.omega_from, v.omega_to),
        speed: figures::speed::SpeedAxis::new(v.axis, Some(&first.model)),
    };
    let b_um = |m: &Member, j: usize| (m.model.system.meshes[j].backlash_m * 1e9).round() / 1e3;
    let mut levels = Vec::new();
    for m in members {
        levels.push(b_um(m, mesh(m)?));
    }
    let store = stores
        .first()
        .ok_or_else(|| usage(format!("figure {}: no branches", p.id)))?;
    let mut view = figures::views::fr::fr_view(store, None, None, Some(j), &levels, &ctx);
    view.backlash_um = figures::views::distinct(&levels, None);
    let label = |i: usize| match p.family {
        Some(f) => {
            let x = f.values.get(i).copied().unwrap_or(f64::NAN);
            figures::family_spec::family_key(f.key)
                .map_or_else(|| format!("{} {x}", f.key), |k| k.label(x))
        }
        None => String::new(),
    };
    let partial =
        |s: &figures::views::fr::HbmStore| if s.error.is_some() { "; partial" } else { "" };
    for br in view.branches.iter_mut() {
        br.member = Some(0);
        br.label = format!("{}{}", label(0), partial(store));
    }
    for (i, (m, s)) in members.iter().zip(stores).enumerate().skip(1) {
        let (points, markers) = s.curve(Some(mesh(m)?));
        view.markers.extend(markers);
        view.branches.push(figures::views::fr::FrBranch {
            label: format!("{}{}", label(i), partial(s)),
            points,
            faded: false,
            pinned: false,
            member: Some(i),
        });
    }
    Ok(view)
}

pub(crate) fn run_options(m: &Member, args: &FigureArgs) -> RunOptions {
    RunOptions {
        transient_periods: args
            .transient_periods
            .unwrap_or(m.settings.view.transient_periods),
        record_periods: args
            .record_periods
            .unwrap_or(m.settings.view.record_periods),
    }
}

/// The steady states of the members `only` keeps, at each member's
/// selected Omega: (member, orbit as [`shard::orbit_json`] writes it).
pub(crate) fn orbits(
    members: &[Member],
    args: &FigureArgs,
    only: &dyn Fn(usize) -> bool,
) -> Result<Vec<(usize, Value)>, Failure> {
    let mine = (0..members.len()).filter(|&i| only(i)).count();
    let mut bar = progress::Progress::new(mine, "panels", false);
    let mut out = Vec::new();
    for (i, m) in members.iter().enumerate().filter(|(i, _)| only(*i)) {
        let job = OmegaJob {
            id: i as u64,
            model: m.model.clone(),
            spec: selected_spec(&m.settings, &m.model, run_options(m, args)),
        };
        let r = omega_result(&job, None).map_err(|e| Failure {
            code: 1,
            message: e.to_string(),
        })?;
        out.push((i, shard::orbit_json(&r)));
        bar.update(out.len());
    }
    bar.finish();
    Ok(out)
}

/// Member `i`'s two panels (its phase portrait `i`, its Poincaré section
/// `n + i`), drawn from its orbit `r`: the files pushed to `files`, the
/// listing entries returned.
pub(crate) fn orbit_files(
    p: &Preset,
    (i, n): (usize, usize),
    m: &Member,
    r: &OmegaResult,
    files: &mut Files,
) -> Result<Vec<Value>, Failure> {
    // The title names the member and the motion, from the one
    // classification the page's panel titles use (`figures::story`).
    let verdict = figures::story::motion_tag(r.motion);
    let label = format!("{}: {verdict}", member_label(p, i));
    let mut out = Vec::new();
    for (k, view) in [(i, OmegaView::Phase), (n + i, OmegaView::Poincare)] {
        let name = format!("{}{}", p.id, panel_letter(k));
        let svg = format!("{name}.svg");
        let mut text = String::new();
        {
            let root = SVGBackend::with_string(&mut text, SIZE).into_drawing_area();
            drawn(
                &svg,
                match view {
                    OmegaView::Poincare => figures::plots::draw_poincare(&root, r, &label),
                    _ => figures::plots::draw_phase(&root, r, &label),
                },
            )?;
        }
        files.push((svg, text));
        let mut data = figures::views::omega::omega_json(r, view);
        data["query"] = json!(m.query);
        files.push((format!("{name}.json"), data.to_string()));
        files.push((
            format!("{name}.csv"),
            figures::views::omega::omega_csv(r, view),
        ));
        out.push(json!({
            "panel": name,
            "view": if matches!(view, OmegaView::Poincare) { "poincare" } else { "phase" },
            "query": m.query,
            "period": r.period,
            "motion": r.motion.name(),
            "exact": r.motion.is_exact(),
            "verdict": verdict,
            "impact": r.regime.solver_name(),
            "files": [format!("{name}.svg"), format!("{name}.json"), format!("{name}.csv")],
        }));
    }
    Ok(out)
}

/// Panels a-c: phase portraits; d-f: Poincaré sections. Every panel is
/// drawn from its orbit read back from JSON, as a merge of shards draws it.
fn orbit_panels(
    p: &Preset,
    members: &[Member],
    args: &FigureArgs,
    files: &mut Files,
) -> Result<Vec<Value>, Failure> {
    let n = members.len();
    let mut out = Vec::new();
    for (i, orbit) in orbits(members, args, &|_| true)? {
        let r =
            shard::orbit_from_json(&orbit, &members[i], args, "figure").map_err(|e| Failure {
                code: 1,
                message: e,
            })?;
        out.extend(orbit_files(p, (i, n), &members[i], &r, files)?);
    }
    out.sort_by(|a, b| a["panel"].as_str().cmp(&b["panel"].as_str()));
    Ok(out)
}

/// The sweep spec of member `m`'s bifurcation panel.
pub(crate) fn bif_spec(m: &Member, args: &FigureArgs) -> SweepSpec {
    let v = &m.settings.view;
    let mut spec = SweepSpec::new(
        v.omega_from,
        v.omega_to,
        args.points.unwrap_or(v.bif_points),
    );
    let run = run_options(m, args);
    spec.steady.transient_periods = run.transient_periods;
    spec.steady.record_periods = run.record_periods;
    spec.directions = v.bif_dir;
    spec.meshes = vec![m.settings.mesh_index(&m.model).unwrap_or(0)];
    spec
}

/// The sweeps of the members `only` keeps: (member, `gearshock
/// bifurcation` JSON of its sweep).
pub(crate) fn sweeps(
    members: &[Member],
    args: &FigureArgs,
    only: &dyn Fn(usize) -> bool,
) -> Result<Vec<(usize, Value)>, Failure> {
    let mut sweeps = Vec::new();
    for (i, m) in members.iter().enumerate() {
        let spec = bif_spec(m, args);
        sweeps.push((
            i,
            spec.clone(),
            BifurcationSweep::new(m.model.clone(), spec)?,
        ));
    }
    sweeps.retain(|(i, _, _)| only(*i));
    let total: usize = sweeps.iter().map(|(_, _, s)| s.total()).sum();
    let mut bar = progress::Progress::new(total, "points", false);
    let mut done = 0;
    let mut out = Vec::new();
    for (i, spec, mut sweep) in sweeps {
        let m = &members[i];
        let mut pts = Vec::with_capacity(sweep.total());
        while !sweep.is_finished() {
            pts.extend(sweep.advance(1));
            bar.update(done + sweep.done());
        }
        done += sweep.total();
        canonical_order(&mut pts);
        out.push((
            i,
            report::sweep_json(&m.model, &m.settings.params, &spec, &pts),
        ));
    }
    bar.finish();
    Ok(out)
}

/// Member `i`'s bifurcation panel drawn from its sweep's JSON `data`: the
/// files pushed to `files`, the listing entry returned.
pub(crate) fn bif_files(
    p: &Preset,
    i: usize,
    m: &Member,
    spec: &SweepSpec,
    data: &Value,
    files: &mut Files,
) -> Result<Value, Failure> {
    let name = format!("{}{}", p.id, panel_letter(i));
    files.push((format!("{name}.json"), data.to_string()));
    files.push((format!("{name}.csv"), crate::csv::sweep(data)));
    let view = bif_view(m, spec, data)?;
    let natural = figures::views::natural_in_range(&m.model, spec.omega_from, spec.omega_to);
    let svg = format!("{name}.svg");
    let text = drawn(&svg, bif_svg(&view, &natural, &member_label(p, i)))?;
    files.push((svg, text));
    let pts = data["points"].as_array().map_or(&[][..], Vec::as_slice);
    let failed = pts.iter().filter(|p| p.get("error").is_some()).count();
    Ok(json!({
        "panel": name,
        "view": "bifurcation",
        "query": m.query,
        "points": pts.len(),
        "failed": failed,
        "files": [format!("{name}.svg"), format!("{name}.json"), format!("{name}.csv")],
    }))
}

/// Panels a-c: one bifurcation diagram per member.
fn bifurcation_panels(
    p: &Preset,
    members: &[Member],
    args: &FigureArgs,
    files: &mut Files,
) -> Result<Vec<Value>, Failure> {
    let mut out = Vec::new();
    for (i, data) in sweeps(members, args, &|_| true)? {
        let m = &members[i];
        out.push(bif_files(p, i, m, &bif_spec(m, args), &data, files)?);
    }
    Ok(out)
}

/// The bifurcation diagram as SVG text, its dots inside (as the page's
/// SVG export draws it).
fn bif_svg(
    view: &BifView,
    natural: &[figures::views::NaturalFreq],
    status: &str,
) -> Result<String, String> {
    let mut chart = String::new();
    let groups = {
        let root = SVGBackend::with_string(&mut chart, SIZE).into_drawing_area();
        figures::plots::draw_bif(&root, view, natural, status)
            .map_err(|e| e.to_string())?
            .1
    };
    figures::plots::svg_with_dots(&chart, SIZE, &groups).map_err(|e| e.to_string())
}

/// The page's bifurcation view of one sweep, from its JSON (one mesh, its
/// fields inline): Poincaré samples of x = delta - e.
fn bif_view(m: &Member, spec: &SweepSpec, data: &Value) -> Result<BifView, solver::SolverError> {
    let mesh = spec.meshes[0];
    let def = &m.model.system.meshes[mesh];
    let mut points = Vec::new();
    let mut failed = Vec::new();
    let pts = data["points"].as_array().map_or(&[][..], Vec::as_slice);
    for p in pts {
        let omega = p["omega"].as_f64().unwrap_or(f64::NAN);
        if let Some(e) = p.get("error") {
            failed.push((omega, e.as_str().unwrap_or_default().to_string()));
            continue;
        }
        let w = omega * m.model.system.omega_ref_rad_s;
        // The TE at the Poincaré phase (t = n T).
        let (_, e0, _) = def.excitation(w, 1.0, 0.0);
        let regime = report::impact_of(&p["impact"]).unwrap_or(solver::steady::Impact::None);
        let up = p["direction"].as_str() == Some(Direction::Up.name());
        let deltas = p["poincare_delta_m"]
            .as_array()
            .map_or(&[][..], Vec::as_slice);
        // null is what JSON holds for a non-finite number.
        points.extend(deltas.iter().map(|d| BifPoint {
            omega,
            x_um: (d.as_f64().unwrap_or(f64::NAN) - e0) * 1e6,
            regime: regime.into(),
            up,
        }));
    }
    Ok(BifView {
        mesh_label: def.name.clone(),
        // To the nanometre: the metre value read back in µm is not exact.
        backlash_um: vec![(def.backlash_m * 1e9).round() / 1e3],
        points,
        omega_from: spec.omega_from,
        omega_to: spec.omega_to,
        selected_omega: m.settings.view.omega,
        failed,
        // Shaded as on the page: where the engaged system is parametrically unstable.
        unstable_bands: solver::parametric::Parametric::new(&m.model).and_then(|p| {
            p.unstable_bands(
                (spec.omega_from, spec.omega_to),
                worker::jobs::bif::BAND_SAMPLES,
            )
        })?,
        pinned: Vec::new(),
        pinned_backlash_um: Vec::new(),
        ab_labels: None,
        branches: Vec::new(),
        branch_markers: Vec::new(),
        motions: Vec::new(),
        done: pts.len(),
        total: pts.len(),
        whole_clearance: true,
        speed: figures::speed::SpeedAxis::new(m.settings.view.axis, Some(&m.model)),
    })
}
