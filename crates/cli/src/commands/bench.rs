//! `gearshock bench`: the solver's speed figures, as medians over repeats.
//!
//! Timing lives here, not in the solver (which has no clock). Every figure
//! is the median of `repeats` runs on the default model; docs/performance.md
//! quotes them with their commands.

use serde_json::{json, Value};
use solver::dynamics::MeshOde;
use solver::hbm::{
    BranchPoint, FrfContinuation, FrfSpec, HbmModel, StepControl, SAMPLED_STABILITY_STRIDE,
};
use solver::map::{MapSpec, RegimeMap};
use solver::ode::Ode;
use solver::params::ModelParams;
use solver::steady::{steady_state, Model, SteadyOptions};
use solver::sweep::{BifurcationSweep, SweepSpec};
use solver::SolverError;
use std::time::Instant;

mod multipliers;
mod problem;

/// Options of `gearshock bench`.
#[derive(Debug, clap::Args)]
pub struct BenchArgs {
    /// Repeats per figure.
    #[arg(long, default_value_t = 5)]
    repeats: u32,
    /// Fewer points and periods (for smoke tests).
    #[arg(long)]
    quick: bool,
    /// Only the steady-state pipeline's figure: the default bifurcation
    /// diagram by fixed integration, with the early-settle test, and by the
    /// pipeline.
    #[arg(long)]
    pipeline_only: bool,
    /// Only the pipeline's classification check: at a dozen Omega values,
    /// the pipeline's verdict (300 + 100 periods) beside 20 000 + 100
    /// periods of plain integration.
    #[arg(long)]
    classification: bool,
    /// Only the harmonic balance's branch figure (H = 7, Omega 0.1 to 0.5,
    /// with stability: both step controls, sampled stability, the LU).
    /// The same sweep beside pyHarm, both run: scripts/bench-pyharm.sh.
    #[arg(long)]
    hbm_only: bool,
    /// Only the accuracy of the harmonic balance's Floquet multipliers: on
    /// the same sweep, each point's monodromy at 8, 16 (the default) and 32
    /// RK4 steps a period of the fastest mode against 128.
    #[arg(long)]
    multipliers: bool,
    /// Only the shooting branches' figure: the page's branch job natively
    /// (the compound set's first 300 points at 100 nominal points) and the
    /// gear pair's whole branch.
    #[arg(long)]
    branches_only: bool,
    /// Print, instead of timing anything, the harmonic-balance problem that
    /// `gearshock frf` solves on the default model (its scaled modal
    /// coordinates, channels and force laws) as JSON, so that another code
    /// can solve the same equations (scripts/bench-pyharm.sh).
    #[arg(long)]
    hbm_problem: bool,
    /// A key of the model every figure but the branches' runs on, e.g.
    /// `--set stiffness_wave_s1a=rectangular` (repeatable; the default
    /// model otherwise). A figure the model refuses is reported, not run.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    set: Vec<String>,
}

/// Checks the options, runs every benchmark and prints the figures.
pub fn run_command(a: &BenchArgs) -> Result<(), crate::failure::Failure> {
    if a.repeats == 0 || a.repeats > 100 {
        return Err(crate::failure::usage(format!(
            "--repeats {} is out of range: allowed 1 ..= 100",
            a.repeats
        )));
    }
    let mut base = ModelParams::default();
    for given in &a.set {
        solver::keys::set_assignment(&mut base, given)
            .map_err(|e| crate::failure::usage(format!("--set {e}")))?;
    }
    let base = &base;
    if a.hbm_problem {
        let model = Model::new(&ModelParams::default()).map_err(crate::failure::Failure::from)?;
        let hbm =
            HbmModel::from_system(&model.system, true).map_err(crate::failure::Failure::from)?;
        return crate::output::emit(&problem::hbm_problem(&model, &hbm));
    }
    if a.classification {
        let model = Model::new(base).map_err(crate::failure::Failure::from)?;
        let long = if a.quick { 600 } else { 20_000 };
        let v = classification_check(&model, long).map_err(crate::failure::Failure::from)?;
        return crate::output::emit(&json!({ "classification": v }));
    }
    if a.hbm_only {
        let model = Model::new(base).map_err(crate::failure::Failure::from)?;
        let v = hbm_branch_bench(&model, if a.quick { 1 } else { a.repeats })
            .map_err(crate::failure::Failure::from)?;
        return crate::output::emit(&json!({ "hbm_branch": v }));
    }
    if a.multipliers {
        let model = Model::new(base).map_err(crate::failure::Failure::from)?;
        let v = multipliers::multiplier_accuracy(&model, a.quick)
            .map_err(crate::failure::Failure::from)?;
        return crate::output::emit(&json!({ "multiplier_accuracy": v }));
    }
    if a.branches_only {
        let v = branches_bench(if a.quick { 1 } else { a.repeats }, a.quick)
            .map_err(crate::failure::Failure::from)?;
        return crate::output::emit(&json!({ "shooting_branches": v }));
    }
    if a.pipeline_only {
        let model = Model::new(base).map_err(crate::failure::Failure::from)?;
        let (points, transient, record) = if a.quick {
            (4, 30, 10)
        } else {
            (200, 300, 100)
        };
        let v = pipeline_bench(&model, points, a.repeats, transient, record)
            .map_err(crate::failure::Failure::from)?;
        return crate::output::emit(&json!({ "bifurcation_pipeline": v }));
    }
    crate::output::emit(&run(base, a.repeats, a.quick)?)
}

fn median(mut xs: Vec<f64>) -> f64 {
    xs.sort_by(f64::total_cmp);
    let n = xs.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        xs[n / 2]
    } else {
        0.5 * (xs[n / 2 - 1] + xs[n / 2])
    }
}

/// Runs every benchmark and returns the figures.
pub fn run(base: &ModelParams, repeats: u32, quick: bool) -> Result<Value, SolverError> {
    let model = Model::new(base)?;
    let omega = 0.5;

    // Right-hand side evaluations per second, on states along a real orbit.
    let mut opts = SteadyOptions::new(omega);
    opts.transient_periods = 20;
    opts.record_periods = 1;
    opts.early_settle = false;
    let ss = steady_state(&model, &opts, None)?;
    let mut ode = MeshOde::new(&model.system, ss.omega_rad_s);
    let y = ss.end_state.clone();
    let mut dy = vec![0.0; y.len()];
    let evals: u32 = if quick { 20_000 } else { 1_000_000 };
    let mut rhs_rates = Vec::new();
    for _ in 0..repeats {
        let start = Instant::now();
        let mut acc = 0.0;
        for k in 0..evals {
            ode.rhs(f64::from(k) * 1e-7, &y, &mut dy);
            acc += dy[12];
        }
        let dt = start.elapsed().as_secs_f64();
        std::hint::black_box(acc);
        rhs_rates.push(f64::from(evals) / dt);
    }

    // One simulate of 300 + 100 periods at Omega = 0.5, as the CLI runs it.
    let (transient, record) = if quick { (30, 10) } else { (300, 100) };
    let mut sim_ms = Vec::new();
    let mut period_rates = Vec::new();
    let mut sim_stats = None;
    for _ in 0..repeats {
        let mut o = SteadyOptions::new(omega);
        o.transient_periods = transient;
        o.record_periods = record;
        o.history_meshes = vec![0];
        let start = Instant::now();
        let r = steady_state(&model, &o, None)?;
        let dt = start.elapsed().as_secs_f64();
        sim_ms.push(dt * 1e3);
        period_rates.push(f64::from(r.stats.transient_periods_run + record) / dt);
        sim_stats = Some(r.stats);
    }
    let sim_stats = sim_stats.unwrap_or_default();

    // A bifurcation sweep of 300 + 100 periods per point, single-threaded.
    let points = if quick { 4 } else { 200 };
    let sweep_repeats = if quick { 1 } else { repeats.min(3) };
    let mut sweep_s = Vec::new();
    let mut settled_points = 0;
    for _ in 0..sweep_repeats {
        let mut spec = SweepSpec::new(0.05, 2.0, points);
        spec.steady.transient_periods = transient;
        spec.steady.record_periods = record;
        let mut sweep = BifurcationSweep::new(model.clone(), spec)?;
        let start = Instant::now();
        let pts = sweep.advance(points as usize);
        sweep_s.push(start.elapsed().as_secs_f64());
        settled_points = pts.iter().filter(|p| p.stats.settled).count();
    }
    let sweep_median = median(sweep_s.clone());

    // The default bifurcation diagram (the default model, Omega 0.1 ..= 2,
    // 200 points up and down: 400 steady states) integrated with a fixed
    // 300 + 100 periods, with the early-settle test, and by the pipeline
    // (transient, candidate period, shooting), in one run.
    let pipeline = pipeline_bench(
        &model,
        if quick { 4 } else { 200 },
        sweep_repeats,
        transient,
        record,
    )?;

    // A regime map of the page's default kind: Omega 0.1..2 in 100 columns,
    // backlash 10..200 um in 4 rows (a tenth of the page's 100 x 40 map).
    let (columns, rows) = if quick { (4, 1) } else { (100, 4) };
    let mut map_s = Vec::new();
    for _ in 0..sweep_repeats {
        let mut spec = MapSpec::new((0.1, 2.0, columns), "backlash_um", (10.0, 200.0, rows));
        spec.steady.transient_periods = transient;
        spec.steady.record_periods = record;
        let mut map = RegimeMap::new(base, spec)?;
        let start = Instant::now();
        while !map.is_finished() {
            map.advance(64);
        }
        map_s.push(start.elapsed().as_secs_f64());
    }
    let map_median = median(map_s);

    // Harmonic balance: the default model's frequency response over
    // Omega 0.1 ..= 2 with 400 nominal points, stability included.
    let mut hbm = serde_json::Map::new();
    for h in [1usize, 7] {
        let (nominal, runs) = if quick {
            (40, 1)
        } else {
            (400, repeats.min(5))
        };
        let mut secs = Vec::new();
        let mut secs_no_stability = Vec::new();
        let mut branch_points = 0;
        let mut refused = None;
        'runs: for stability in [true, false] {
            for _ in 0..runs {
                let mut spec = FrfSpec::new(0.1, 2.0, nominal);
                spec.harmonics = h;
                spec.stability = stability;
                let start = Instant::now();
                // A balance of fewer harmonics than the excitation's is refused.
                let mut c = match FrfContinuation::new(&model, spec) {
                    Ok(c) => c,
                    Err(e) => {
                        refused = Some(e.to_string());
                        break 'runs;
                    }
                };
                let mut n = 0;
                while !c.is_finished() {
                    n += c.advance(64)?.len();
                }
                let dt = start.elapsed().as_secs_f64();
                if stability {
                    secs.push(dt);
                } else {
                    secs_no_stability.push(dt);
                }
                branch_points = n;
            }
        }
        if let Some(why) = refused {
            hbm.insert(format!("h{h}"), json!({ "refused": why }));
            continue;
        }
        let med = median(secs);
        hbm.insert(
            format!("h{h}"),
            json!({
                "harmonics": h,
                "nominal_points": nominal,
                "branch_points": branch_points,
                "median_ms": med * 1e3,
                "median_ms_without_stability": median(secs_no_stability) * 1e3,
                "us_per_branch_point": med * 1e6 / branch_points.max(1) as f64,
            }),
        );
    }

    let branch = hbm_branch_bench(&model, if quick { 1 } else { repeats.min(5) })?;

    // The sliders' grid: backlash x TE x damping ratio over
    // Omega 0.1 ..= 2 at H = 5, 150 nominal points (the page's), once.
    let mut grid = Vec::new();
    let grid_start = Instant::now();
    if !quick {
        for zeta in [0.02, 0.06] {
            for b in [0.0, 20.0, 50.0, 100.0, 200.0] {
                for te in [0.0, 20.0, 60.0] {
                    let mut p = base.clone();
                    for a in [
                        format!("backlash_um={b}"),
                        format!("te_um={te}"),
                        format!("damping_ratio={zeta}"),
                    ] {
                        solver::keys::set_assignment(&mut p, &a)?;
                    }
                    let m = Model::new(&p)?;
                    let start = Instant::now();
                    let mut c = FrfContinuation::new(&m, FrfSpec::new(0.1, 2.0, 150))?;
                    let mut n = 0;
                    let mut error = None;
                    while !c.is_finished() {
                        match c.advance(64) {
                            Ok(pts) => n += pts.len(),
                            Err(e) => {
                                error = Some(e.to_string());
                                break;
                            }
                        }
                    }
                    grid.push(json!({
                        "backlash_um": b,
                        "te_um": te,
                        "damping_ratio": zeta,
                        "complete": error.is_none(),
                        "error": error,
                        "branch_points": n,
                        "restarts": c.restarts().len(),
                        "left_out": c.left_out().iter().map(|l| json!([l.from, l.to, l.reason_name()])).collect::<Vec<_>>(),
                        "ms": start.elapsed().as_secs_f64() * 1e3,
                    }));
                }
            }
        }
    }
    let grid_s = grid_start.elapsed().as_secs_f64();
    let grid_complete = grid.iter().filter(|g| g["complete"] == json!(true)).count();

    Ok(json!({
        "hbm": Value::Object(hbm),
        "hbm_branch": branch,
        "hbm_slider_grid": {
            "cases": grid.len(),
            "complete": grid_complete,
            "total_s": grid_s,
            "runs": grid,
        },
        "machine_threads": std::thread::available_parallelism().map_or(1, |n| n.get()),
        "repeats": repeats,
        "quick": quick,
        "rhs": {
            "evaluations_per_s": median(rhs_rates),
        },
        "simulate": {
            "omega": omega,
            "transient_periods": transient,
            "record_periods": record,
            "median_ms": median(sim_ms),
            "mesh_periods_per_s": median(period_rates),
            "transient_periods_run": sim_stats.transient_periods_run,
            "steps": sim_stats.integrator.steps,
            "rejected_steps": sim_stats.integrator.rejected_steps,
            "event_retakes": sim_stats.integrator.event_retakes,
            "rhs_evaluations": sim_stats.integrator.rhs_evaluations,
            "contact_switches": sim_stats.integrator.events,
        },
        "map": {
            "omega_points": columns,
            "backlash_um_points": rows,
            "transient_periods": transient,
            "record_periods": record,
            "median_s": map_median,
            "ms_per_cell": map_median * 1e3 / f64::from(columns * rows),
        },
        "bifurcation_pipeline": pipeline,
        "bifurcation": {
            "omega_from": 0.05,
            "omega_to": 2.0,
            "points": points,
            "transient_periods": transient,
            "record_periods": record,
            "median_s": sweep_median,
            "points_per_s": f64::from(points) / sweep_median,
            "points_settled_early": settled_points,
        },
    }))
}

/// The harmonic balance's branch figure: H = 7 over Omega 0.1 ..= 0.5 with
/// stability, by the two step controls and with sampled stability,
/// alternating in one run (`runs` rounds), medians.
fn hbm_branch_bench(model: &Model, runs: u32) -> Result<Value, SolverError> {
    // The step control on the corrector's iterations (400 nominal points,
    // the CLI's default) against the one on the curve's geometry (50
    // nominal points, which it needs for the same folds), and the geometry
    // control with the monodromy on sampled points only (the default
    // stride) against every point (stride 1).
    let mut iterations_s = Vec::new();
    let mut geometry_s = Vec::new();
    let mut sampled_s = Vec::new();
    let (mut geometry_cpu, mut sampled_cpu) = (Vec::new(), Vec::new());
    let mut iterations_points = 0;
    let mut geometry_points = 0;
    let mut iterations_branch = Vec::new();
    let mut geometry_branch = Vec::new();
    let mut sampled_branch = Vec::new();
    let (mut geometry_monodromies, mut sampled_monodromies) = (0, 0);
    for _ in 0..runs {
        for (control, nominal, stride) in [
            (StepControl::Iterations, 400, 1),
            (StepControl::Geometry, 50, 1),
            (StepControl::Geometry, 50, SAMPLED_STABILITY_STRIDE),
        ] {
            let mut spec = FrfSpec::new(0.1, 0.5, nominal);
            spec.harmonics = 7;
            spec.step_control = control;
            spec.stability_stride = stride;
            let cpu_start = thread_cpu_s();
            let start = Instant::now();
            let mut c = FrfContinuation::new(model, spec)?;
            let mut pts = Vec::new();
            while !c.is_finished() {
                pts.extend(c.advance(64)?);
            }
            let dt = start.elapsed().as_secs_f64();
            let cpu = match (cpu_start, thread_cpu_s()) {
                (Some(a), Some(b)) => Some(b - a),
                _ => None,
            };
            if control == StepControl::Iterations {
                iterations_s.push(dt);
                iterations_points = pts.len();
                iterations_branch = pts;
            } else if stride == 1 {
                geometry_s.push(dt);
                geometry_cpu.extend(cpu);
                geometry_points = pts.len();
                geometry_monodromies = c.stats.monodromies;
                geometry_branch = pts;
            } else {
                sampled_s.push(dt);
                sampled_cpu.extend(cpu);
                sampled_monodromies = c.stats.monodromies;
                sampled_branch = pts;
            }
        }
    }
    let sampled_med = median(sampled_s);
    // Points whose stability flag or label differs between the two routes.
    let differing = geometry_branch
        .iter()
        .zip(&sampled_branch)
        .filter(|(a, b)| a.stable != b.stable || a.bifurcation != b.bifurcation)
        .count()
        + geometry_branch.len().abs_diff(sampled_branch.len());
    let (iterations_med, geometry_med) = (median(iterations_s), median(geometry_s));
    let folds = |pts: &[BranchPoint]| -> Vec<f64> {
        pts.iter()
            .filter(|p| p.bifurcation == Some(solver::hbm::Bifurcation::Fold))
            .map(|p| p.omega)
            .collect()
    };
    Ok(json!({
        "harmonics": 7,
        "omega_from": 0.1,
        "omega_to": 0.5,
        "iterations_control": {
            "step_control": "iterations",
            "nominal_points": 400,
            "branch_points": iterations_points,
            "median_ms": iterations_med * 1e3,
            "folds": folds(&iterations_branch),
        },
        "geometry_control": {
            "step_control": "geometry",
            "nominal_points": 50,
            "branch_points": geometry_points,
            "median_ms": geometry_med * 1e3,
            "folds": folds(&geometry_branch),
        },
        "sampled_stability": {
            "stride": SAMPLED_STABILITY_STRIDE,
            "branch_points": sampled_branch.len(),
            "monodromies": sampled_monodromies,
            "monodromies_every_point": geometry_monodromies,
            "median_ms": sampled_med * 1e3,
            "cpu_median_ms": (!sampled_cpu.is_empty()).then(|| median(sampled_cpu) * 1e3),
            "cpu_median_ms_every_point": (!geometry_cpu.is_empty()).then(|| median(geometry_cpu) * 1e3),
            "folds": folds(&sampled_branch),
            "points_differing_from_every_point": differing,
            "speedup_vs_every_point": geometry_med / sampled_med,
        },
        "geometry_speedup_vs_iterations": iterations_med / geometry_med,
        "point_ratio_iterations_to_geometry": iterations_points as f64 / geometry_points.max(1) as f64,
        "lu": lu_bench(runs),
    }))
}

/// The solver's LU (`solver::dense::Lu`) against nalgebra's on the H = 7
/// branch's bordered Jacobian size (76 x 76): 2 000 factorizations and
/// solves each, alternating, `runs` rounds, medians. The two give the
/// same bits (a unit test checks it); this is their speed.
fn lu_bench(runs: u32) -> Value {
    const N: usize = 76;
    const COUNT: u32 = 2000;
    // A deterministic pseudo-random fill (a linear congruential
    // generator), which pivots at nearly every step as the Jacobian does.
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    let a = nalgebra::DMatrix::from_fn(N, N, |_, _| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    });
    let b = nalgebra::DVector::from_element(N, 1.0);
    let (mut ours, mut theirs) = (Vec::new(), Vec::new());
    let mut sink = 0.0;
    for _ in 0..runs.max(1) {
        let start = Instant::now();
        for _ in 0..COUNT {
            sink += solver::dense::Lu::new(a.clone())
                .solve(&b)
                .map_or(0.0, |x| x[0]);
        }
        ours.push(start.elapsed().as_secs_f64());
        let start = Instant::now();
        for _ in 0..COUNT {
            sink += a.clone().lu().solve(&b).map_or(0.0, |x| x[0]);
        }
        theirs.push(start.elapsed().as_secs_f64());
    }
    std::hint::black_box(sink);
    let (ours, theirs) = (median(ours), median(theirs));
    json!({
        "order": N,
        "factorizations": COUNT,
        "solver_ms": ours * 1e3,
        "nalgebra_ms": theirs * 1e3,
        "speedup": theirs / ours,
    })
}

/// The pipeline's figure (see `run`): the default diagram by fixed
/// integration, by integration with the early-settle test and by the
/// pipeline, medians over `repeats` of one single-chain sweep each, and
/// what each called the 400 steady states.
fn pipeline_bench(
    model: &Model,
    points: u32,
    repeats: u32,
    transient: u32,
    record: u32,
) -> Result<Value, SolverError> {
    let variants: [(&str, bool, bool); 3] = [
        ("fixed_integration", false, false),
        ("early_settle_integration", true, false),
        ("pipeline", true, true),
    ];
    let mut out = serde_json::Map::new();
    let mut medians = Vec::new();
    let mut cpu_medians = Vec::new();
    for (name, early_settle, shooting) in variants {
        let mut secs = Vec::new();
        let mut cpu = Vec::new();
        let mut verdicts = std::collections::BTreeMap::new();
        let mut work = [0u64; 4];
        for _ in 0..repeats {
            let mut spec = SweepSpec::new(0.1, 2.0, points);
            spec.directions = solver::sweep::Directions::Both;
            spec.chains = 1;
            spec.steady.transient_periods = transient;
            spec.steady.record_periods = record;
            spec.steady.early_settle = early_settle;
            spec.steady.shooting = shooting;
            let mut sweep = BifurcationSweep::new(model.clone(), spec)?;
            let start = Instant::now();
            let cpu_start = thread_cpu_s();
            let mut pts = Vec::new();
            while !sweep.is_finished() {
                pts.extend(sweep.advance(16));
            }
            secs.push(start.elapsed().as_secs_f64());
            if let (Some(a), Some(b)) = (cpu_start, thread_cpu_s()) {
                cpu.push(b - a);
            }
            verdicts.clear();
            work = [0u64; 4];
            for p in &pts {
                work[0] += p.stats.integrator.steps;
                work[1] += u64::from(p.stats.shooting_attempts);
                work[2] += p.stats.shooting_steps;
                work[3] += p.stats.probe_steps;
                let key = match p.motion.period() {
                    Some(n) if p.motion.is_exact() => format!("period {n} (exact)"),
                    Some(n) => format!("period {n}"),
                    None => p.motion.name().to_string(),
                };
                *verdicts.entry(key).or_insert(0u32) += 1;
            }
        }
        let med = median(secs.clone());
        medians.push(med);
        let cpu_med = (!cpu.is_empty()).then(|| median(cpu.clone()));
        cpu_medians.push(cpu_med);
        out.insert(
            name.into(),
            json!({
                "median_s": med,
                "runs_s": secs,
                "cpu_median_s": cpu_med,
                "cpu_runs_s": cpu,
                "verdicts": verdicts,
                "steps": work[0],
                "shooting_attempts": work[1],
                "shooting_steps": work[2],
                "probe_steps": work[3],
            }),
        );
    }
    out.insert("steady_states".into(), json!(2 * points));
    out.insert("transient_periods".into(), json!(transient));
    out.insert("record_periods".into(), json!(record));
    out.insert("speedup_vs_fixed".into(), json!(medians[0] / medians[2]));
    out.insert(
        "speedup_vs_early_settle".into(),
        json!(medians[1] / medians[2]),
    );
    if let [Some(fixed), Some(early), Some(pipe)] = cpu_medians[..] {
        out.insert("cpu_speedup_vs_fixed".into(), json!(fixed / pipe));
        out.insert("cpu_speedup_vs_early_settle".into(), json!(early / pipe));
    }
    Ok(Value::Object(out))
}

/// The calling thread's CPU time (s), from Linux's
/// `/proc/thread-self/schedstat` (nanoseconds on the CPU): on a shared
/// machine the wall clock also counts the other programs' turns. `None`
/// elsewhere.
fn thread_cpu_s() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/thread-self/schedstat").ok()?;
    let ns: f64 = s.split_whitespace().next()?.parse().ok()?;
    Some(ns * 1e-9)
}

/// The Omega values of the classification check: the default model's
/// period-1 branch below the main resonance, the onset of chaos near 0.5,
/// the chaotic band, and the periodic and quasi-periodic motion above it.
pub const CHECK_OMEGAS: [f64; 12] = [
    0.15, 0.3, 0.45, 0.5, 0.6, 0.7, 0.84, 1.0, 1.2, 1.36, 1.6, 1.9,
];

/// The classification check: at each of [`CHECK_OMEGAS`], from
/// the static equilibrium, the pipeline at the page's defaults (300 + 100
/// periods) and plain integration (no early settle, no shooting) over
/// `long` + 100 periods. They agree when both find the same period, or
/// both none within the largest period classified.
fn classification_check(model: &Model, long: u32) -> Result<Value, SolverError> {
    let mut rows = Vec::new();
    let mut agree = 0;
    for &omega in &CHECK_OMEGAS {
        let pipe = steady_state(model, &SteadyOptions::new(omega), None)?;
        let mut o = SteadyOptions::new(omega);
        o.transient_periods = long;
        o.early_settle = false;
        o.shooting = false;
        o.samples_per_period = 0;
        let reference = steady_state(model, &o, None)?;
        let same = pipe.motion.period() == reference.motion.period();
        agree += u32::from(same);
        rows.push(json!({
            "omega": omega,
            "pipeline": pipe.verdict(),
            "pipeline_transient_periods": pipe.stats.transient_periods_run,
            "reference": reference.motion.words(reference.stats.transient_periods_run),
            "agree": same,
        }));
    }
    Ok(json!({
        "reference_transient_periods": long,
        "record_periods": 100,
        "agree": agree,
        "of": CHECK_OMEGAS.len(),
        "rows": rows,
    }))
}

/// The shooting branches' figure: medians over `repeats` of the page's
/// branch job natively (the default compound set over Omega 0.1 to 2 at
/// 100 nominal points, up to the page's cap of 300 points) and of the gear
/// pair's whole branch (Omega 0.3 to 1.5, 400 nominal points, the period-2
/// branches included), with each run's points, corrector iterations,
/// integrator steps and the Omega reached.
fn branches_bench(repeats: u32, quick: bool) -> Result<Value, SolverError> {
    use solver::orbits::{ShootFrfSpec, ShootingContinuation};
    let compound = Model::new(&ModelParams::default())?;
    let mut p = ModelParams::default();
    solver::keys::set_assignment(&mut p, "model=gear-pair")?;
    let pair = Model::new(&p)?;
    let cases: [(&str, &Model, f64, f64, u32, usize); 2] = [
        (
            "compound_page_300_points",
            &compound,
            0.1,
            2.0,
            100,
            if quick { 20 } else { 300 },
        ),
        ("gear_pair_whole_branch", &pair, 0.3, 1.5, 400, usize::MAX),
    ];
    let mut out = serde_json::Map::new();
    for (name, model, from, to, points, cap) in cases {
        let mut secs = Vec::new();
        let mut last = json!(null);
        for _ in 0..repeats {
            let start = Instant::now();
            let mut c = ShootingContinuation::new(model, ShootFrfSpec::new(from, to, points))?;
            let mut pts = vec![c.first_point()?];
            while !c.is_finished() && pts.len() < cap {
                pts.extend(c.advance(1)?);
            }
            secs.push(start.elapsed().as_secs_f64());
            let reach = pts.iter().map(|p| p.point.omega).fold(f64::NAN, f64::max);
            last = json!({
                "points": pts.len(),
                "newton_iterations": c.stats.newton_iterations,
                "integrator_steps": c.stats.integrator_steps,
                "omega_reached": reach,
            });
        }
        out.insert(
            name.into(),
            json!({ "median_s": median(secs.clone()), "runs_s": secs, "last_run": last }),
        );
    }
    Ok(Value::Object(out))
}
