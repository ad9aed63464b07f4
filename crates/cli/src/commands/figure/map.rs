//! `gearshock figure map --out DIR [--link QUERY]`: the page's
//! impact-regime map of a link (the page's defaults without one) with its
//! boundaries traced as curves over it, drawn by the page's own plotting
//! code: `map.svg`, the cells as `map.csv`, and `map.json` (the cells, the
//! curves and cusps as `gearshock boundaries` names them, the cells that
//! disagree with the curves). The map and the trace are the page's: the
//! link's grid, mesh, periods and harmonics, 5 levels and 50 points. A
//! link that says `boundaries=off` gets the map alone (and its note says
//! so); one that does not say, the boundaries too (as the page, where they
//! are on by default).

use super::{write_all, FigureArgs, Files};
use crate::budget::{largest_within, StepCost, MAX_BOUNDARY_WORK, MAX_STEPS};
use crate::failure::{usage, Failure};
use crate::{output, progress};
use figures::protocol::{BoundaryCurve, MapSample};
use figures::views::boundaries::{
    boundaries_json, disagreements, BoundaryStore, BOUNDARY_LEVELS, BOUNDARY_POINTS,
};
use figures::views::map::{map_csv, map_json, MapGrid, MapStore, MapView};
use serde_json::{json, Value};
use solver::boundaries::{BoundarySpec, BoundaryTrace};
use solver::map::{MapSpec, RegimeMap};
use solver::params::ModelParams;
use solver::steady::Model;

/// Size of the SVG (the page's map canvas).
const SIZE: (u32, u32) = (figures::plots::WIDTH, 460);

/// Checks the map's cells against [`MAX_STEPS`]: their periods' budget
/// first (every cell running its whole transient), and where that is over,
/// the estimate from a few pilot cells (most cells settle or find chaos
/// long before their budget); over that too, refuses naming the estimate
/// and how many cells would fit.
fn check_cells(
    model: &Model,
    map: &RegimeMap,
    grid: &MapGrid,
    v: &figures::settings::ViewOptions,
) -> Result<(), Failure> {
    let cells = grid.cells() as u64;
    let periods = u64::from(v.map_transient_periods) + u64::from(v.map_record_periods);
    let per_period =
        StepCost::of(model).mean_per_period(grid.omega_from, grid.omega_to, grid.omega_points);
    if cells as f64 * periods as f64 * per_period <= MAX_STEPS {
        return Ok(());
    }
    let (steps, _) = map.estimated_steps(Some(MAX_STEPS))?;
    if steps <= MAX_STEPS {
        return Ok(());
    }
    let per_cell = steps / cells as f64;
    Err(usage(format!(
        "figure map --link: about {steps:.1e} integration steps ({per_cell:.0} or more a cell on this \
         model), over the {MAX_STEPS:.0e} limit: allowed map_omega_points x map_value_points ..= {}, \
         or fewer map periods",
        (MAX_STEPS / per_cell).floor()
    )))
}

/// Checks the boundary trace's estimated work against
/// [`MAX_BOUNDARY_WORK`]; over it, refuses naming the harmonics that fit.
fn check_trace(params: &ModelParams, bs: &BoundarySpec) -> Result<(), Failure> {
    let work = bs.estimated_work(params)?;
    if work <= MAX_BOUNDARY_WORK {
        return Ok(());
    }
    let fits = largest_within(1, bs.harmonics as u32, MAX_BOUNDARY_WORK, |h| {
        let mut s = bs.clone();
        s.harmonics = h as usize;
        s.estimated_work(params).map_err(Failure::from)
    })?;
    Err(usage(format!(
        "figure map --link harmonics={}: the boundary trace would take about {work:.1e} work units \
         (about a microsecond each) on this model, over the {MAX_BOUNDARY_WORK:.1e} limit: allowed \
         harmonics 1 ..= {}",
        bs.harmonics,
        fits.map_or("none".to_string(), |h| h.to_string())
    )))
}

/// Runs the map figure.
pub(crate) fn run(args: &FigureArgs) -> Result<Value, Failure> {
    if args.shard.is_some() {
        return Err(usage(
            "figure map --shard: not sharded; shard `gearshock map` instead",
        ));
    }
    for (flag, given) in [
        ("--points", args.points.is_some()),
        ("--transient-periods", args.transient_periods.is_some()),
        ("--record-periods", args.record_periods.is_some()),
    ] {
        if given {
            return Err(usage(format!(
                "figure map {flag}: the map takes its grid and periods from --link (map_omega_points, map_transient_periods, ...)"
            )));
        }
    }
    let out = args
        .out
        .as_ref()
        .ok_or_else(|| usage("figure map: --out DIR is required"))?;
    let query = args.link.as_deref().unwrap_or("");
    let query = query.split_once('?').map_or(query, |(_, q)| q);
    let d = figures::link::decode(query);
    if let Some(issue) = d.issues.first() {
        return Err(usage(format!("figure map --link: {issue}")));
    }
    let settings = d.settings;
    let v = &settings.view;
    let params = &settings.params;
    let model = Model::new(params)?;
    let grid = MapGrid::of(v);
    let mesh = settings.mesh_index(&model);
    let mut spec = MapSpec::new(
        (grid.omega_from, grid.omega_to, grid.omega_points),
        &grid.key,
        (grid.value_from, grid.value_to, grid.value_points),
    );
    spec.steady.transient_periods = v.map_transient_periods;
    spec.steady.record_periods = v.map_record_periods;
    spec.mesh = mesh;
    let mut map = RegimeMap::new(params, spec)?;
    check_cells(&model, &map, &grid, v)?;
    let mut bs = BoundarySpec::new(
        &grid.key,
        (grid.value_from, grid.value_to),
        (grid.omega_from, grid.omega_to),
    );
    bs.levels = BOUNDARY_LEVELS;
    bs.points = BOUNDARY_POINTS;
    bs.harmonics = v.harmonics as usize;
    // As the page: traced unless the link says boundaries=off.
    let traced = v.boundaries;
    if traced {
        check_trace(params, &bs)?;
    }
    output::check_dir("--out", out)?;
    let mut bar = progress::Progress::new(
        map.total() + 1000,
        "cells and per mille of the boundaries",
        false,
    );
    let mut store = MapStore::new(grid.clone(), String::new());
    while !map.is_finished() {
        let new: Vec<MapSample> = map.advance(1).into_iter().map(MapSample::from).collect();
        store.add(new);
        bar.update(store.done);
    }
    let mut failure = None;
    let boundaries = if traced {
        let mut trace = BoundaryTrace::new(params, bs)?;
        while !trace.is_finished() {
            if let Err(e) = trace.advance(8) {
                failure = Some(e);
                break;
            }
            bar.update(store.done + (1000.0 * trace.progress()) as usize);
        }
        BoundaryStore {
            curves: trace.curves().iter().map(BoundaryCurve::from).collect(),
            cusps: trace.cusps().iter().map(|c| (c.omega, c.value)).collect(),
            notes: trace.notes().to_vec(),
            finished: failure.is_none(),
            signature: String::new(),
        }
    } else {
        BoundaryStore {
            curves: Vec::new(),
            cusps: Vec::new(),
            notes: vec!["The link says boundaries=off: no boundary was traced.".to_string()],
            finished: true,
            signature: String::new(),
        }
    };
    bar.finish();
    let shown = boundaries.shown(mesh);
    let (disagree, judged) = disagreements(&grid, &store, &shown);
    let names: Vec<String> = model.system.meshes.iter().map(|m| m.name.clone()).collect();
    let value = solver::keys::get(params, &grid.key).and_then(|x| match x {
        solver::keys::Value::Num(x) => Some(x),
        _ => None,
    });
    let view = MapView {
        store: &store,
        mesh_label: match mesh.and_then(|m| names.get(m)) {
            Some(n) => format!("mesh {n}"),
            None => "most severe of all meshes".into(),
        },
        selected: (v.omega, value),
        boundaries: shown,
        cusps: boundaries.cusps.clone(),
        disagree: disagree.clone(),
        picked: None,
        speed: figures::speed::SpeedAxis::new(v.axis, Some(&model)),
    };
    let svg = figures::plots::maps::map_svg(&view, SIZE).map_err(|e| Failure {
        code: 1,
        message: format!("cannot draw map.svg: {e}"),
    })?;
    let mut data = map_json(&store);
    if let Some(o) = data.as_object_mut() {
        o.insert("boundaries".into(), boundaries_json(&boundaries, &names));
        o.insert(
            "disagree".into(),
            json!({
                "judged": judged,
                "cells": disagree.iter().map(|&(r, c)| json!({"row": r, "column": c})).collect::<Vec<_>>(),
            }),
        );
    }
    let files: Files = vec![
        ("map.svg".into(), svg),
        ("map.json".into(), format!("{data}\n")),
        ("map.csv".into(), map_csv(&store)),
    ];
    write_all(out, &files)?;
    if let Some(e) = failure {
        return Err(Failure {
            code: 1,
            message: format!(
                "figure map: the boundary trace failed ({e}); the {} curves traced before it are drawn",
                boundaries.curves.len()
            ),
        });
    }
    Ok(json!({
        "id": "map",
        "title": "Impact-regime map with its traced boundaries",
        "out": out.display().to_string(),
        "panels": [{
            "panel": "map",
            "files": ["map.svg", "map.json", "map.csv"],
            "boundaries": if traced { "on" } else { "off" },
            "curves": boundaries.curves.len(),
            "cusps": boundaries.cusps.len(),
            "judged": judged,
            "disagree": disagree.len(),
        }],
    }))
}
