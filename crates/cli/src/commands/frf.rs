//! `gearshock frf`: the frequency response by harmonic balance with
//! arclength continuation. A solver failure still writes the branch up to
//! there, marked incomplete, and exits with code 1.

use crate::args::{meshes, IsoArgs, OmegaRange, ParamArgs};
use crate::budget::{largest_within, MAX_FRF_WORK, MAX_STEPS};
use crate::csv;
use crate::failure::{usage, Failure};
use crate::output::{note, output};
use crate::sweep::{self, Sweep};
use clap::Args;
use solver::hbm::{BranchPoint, FrfContinuation, FrfSpec, Method};
use solver::keys;
use solver::orbits::{ShootFrfSpec, ShootingContinuation};
use solver::sweep::Direction;
use solver::SolverError;

/// Options of `gearshock frf`.
#[derive(Debug, Args)]
pub struct FrfArgs {
    #[command(flatten)]
    p: ParamArgs,
    #[command(flatten)]
    range: OmegaRange,
    /// Nominal points: the largest continuation step is range / points.
    #[arg(long, default_value_t = 400)]
    points: u32,
    /// Harmonics H (1 ..= 40; default 7). Not with --method shooting.
    #[arg(long)]
    harmonics: Option<usize>,
    /// aft (time grid, any H), exact (closed-form integration between the
    /// contact switches, any H), describing-function (the seed's Eqs. 9-13,
    /// H = 1) or shooting (periodic orbits of the time integration by
    /// Newton, continued in Omega; period doublings followed).
    #[arg(long, default_value = "exact")]
    method: String,
    /// With --method shooting: the first branch's period in mesh periods
    /// (default 1).
    #[arg(long)]
    period: Option<u32>,
    /// With --method shooting: do not follow the period-doubled branches.
    #[arg(long)]
    no_switch: bool,
    /// Continue up from --omega-from or down from --omega-to.
    #[arg(long, default_value = "up")]
    direction: String,
    /// AFT time-grid size (default: max(64 H, 256) rounded up to a power of
    /// two). Not with --method shooting.
    #[arg(long)]
    grid: Option<usize>,
    /// Skip the Floquet stability of each point. Not with --method
    /// shooting, whose corrector needs each point's monodromy.
    #[arg(long)]
    no_stability: bool,
    /// Floquet stability from a monodromy at every Nth point only (1 ..=
    /// 64, default 1: every point), at each piece's first point and at
    /// every fold; the points between two samples of the same stability,
    /// both clear of the unit circle, take it (`stability_from:
    /// neighbours`, no multipliers), and a change is located by
    /// monodromies between. Faster, but blind to a window shorter than N
    /// points (docs/performance.md). Not with --method shooting or
    /// --no-stability.
    #[arg(long)]
    stability_stride: Option<u32>,
    /// Mesh to report, or `all`.
    #[arg(long)]
    mesh: Option<String>,
    #[command(flatten)]
    iso: IsoArgs,
}

/// The continuation as a sweep of per mille of the Omega range; a failure
/// ends it and is kept, so the branch up to there is still written.
struct Branch {
    c: FrfContinuation,
    failure: Option<SolverError>,
    per_mille: usize,
}

impl Sweep for Branch {
    type Item = BranchPoint;
    fn total(&self) -> usize {
        1000
    }
    fn done(&self) -> usize {
        self.per_mille
    }
    fn is_finished(&self) -> bool {
        self.failure.is_some() || self.c.is_finished()
    }
    fn advance(&mut self) -> Result<Vec<BranchPoint>, Failure> {
        match self.c.advance(16) {
            Ok(points) => {
                self.per_mille = (self.c.progress() * 1000.0) as usize;
                Ok(points)
            }
            Err(e) => {
                self.failure = Some(e);
                Ok(Vec::new())
            }
        }
    }
}

/// The harmonics when none are given.
const DEFAULT_HARMONICS: usize = 7;

/// Refuses the flags a method ignores, naming the flag and the method:
/// the harmonic balance's (`--harmonics`, `--grid`, `--no-stability`)
/// with shooting, shooting's (`--period`, `--no-switch`) with the others.
fn refuse_ignored(a: &FrfArgs) -> Result<(), Failure> {
    let shooting = a.method == "shooting";
    if a.no_stability && a.stability_stride.is_some() {
        return Err(usage(
            "--stability-stride: --no-stability computes no stability to sample".to_string(),
        ));
    }
    let given: [(&str, bool, bool); 6] = [
        ("--harmonics", a.harmonics.is_some(), false),
        ("--grid", a.grid.is_some(), false),
        ("--no-stability", a.no_stability, false),
        ("--stability-stride", a.stability_stride.is_some(), false),
        ("--period", a.period.is_some(), true),
        ("--no-switch", a.no_switch, true),
    ];
    for (flag, is_given, for_shooting) in given {
        if is_given && for_shooting != shooting {
            return Err(usage(if shooting {
                format!("{flag}: --method shooting does not take it (it belongs to the harmonic balance)")
            } else {
                format!(
                    "{flag}: only --method shooting takes it, not --method {}",
                    keys::truncate(&a.method, 30)
                )
            }));
        }
    }
    Ok(())
}

/// Checks the options and the budget, follows the branch and prints it.
pub fn run(a: &FrfArgs) -> Result<(), Failure> {
    refuse_ignored(a)?;
    if a.method == "shooting" {
        return run_shooting(a);
    }
    let iso = a.iso.inputs()?;
    let (params, model) = a.p.load()?;
    let (omega_from, omega_to) = a.range.omegas(&model)?;
    let mut spec = FrfSpec::new(omega_from, omega_to, a.points);
    spec.harmonics = a.harmonics.unwrap_or(DEFAULT_HARMONICS);
    spec.method = Method::from_name(&a.method).ok_or_else(|| {
        usage(format!(
            "--method {}: allowed aft, exact, describing-function, shooting",
            keys::truncate(&a.method, 30)
        ))
    })?;
    spec.direction = Direction::from_name(&a.direction).ok_or_else(|| {
        usage(format!(
            "--direction {}: allowed up, down",
            keys::truncate(&a.direction, 20)
        ))
    })?;
    spec.grid = a.grid;
    spec.stability = !a.no_stability;
    if let Some(n) = a.stability_stride {
        spec.stability_stride = n;
    }
    let meshes = meshes(&model, a.mesh.as_deref())?;
    // Larger H is refused by the solver's own check, naming it.
    let (points, harmonics) = (a.points, spec.harmonics);
    if harmonics <= 40 {
        let work = u64::from(points) * (2 * harmonics as u64 + 1).pow(3);
        if work > MAX_FRF_WORK {
            return Err(usage(format!(
                "--points {points} x (2 x --harmonics {harmonics} + 1)^3 = {work} is more than the {} \
                 one frequency response may take: use fewer points or harmonics",
                MAX_FRF_WORK
            )));
        }
    }
    let mut branch = Branch {
        c: FrfContinuation::new(&model, spec)?,
        failure: None,
        per_mille: 0,
    };
    let points = sweep::run(&mut branch, &a.p, "per mille of the range", None)?.unwrap_or_default();
    let Branch { c, failure, .. } = branch;
    let mut value = report::frf_json(&model, &params, &c, &points, &meshes, failure.as_ref());
    report::add_branch_iso6336(&mut value, &params, &model, &iso);
    output(a.p.format, &value, csv::frf)?;
    // Restarts and left-out gaps are in the JSON; say them here too.
    for n in c.notes() {
        note(&format!("note: {n}"));
    }
    if failure.is_none() && c.left_at_start() {
        note(&format!(
            "note: the branch turned back at a fold and left the range at its start; \
             continue from the other end with --direction {} to see the rest",
            if c.spec().direction == Direction::Up {
                "down"
            } else {
                "up"
            }
        ));
    }
    match failure {
        // The partial branch is written (marked `complete: false`),
        // and the failure is reported with exit code 1.
        Some(e) => Err(Failure {
            code: 1,
            message: format!("{e} (the branch up to there was written, marked incomplete)"),
        }),
        None => Ok(()),
    }
}

/// Checks a shooting branch's estimated work (`ShootFrfSpec::estimate`:
/// a pilot integration prices a period on this model) against
/// [`MAX_STEPS`]; over it, refuses naming the estimate and the points that
/// would fit.
fn check_shooting(model: &solver::steady::Model, spec: &ShootFrfSpec) -> Result<(), Failure> {
    let est = spec.estimate(model)?;
    let work = est.work(spec.points);
    if work <= MAX_STEPS {
        return Ok(());
    }
    let fits = largest_within(2, spec.points, MAX_STEPS, |p| Ok(est.work(p)))?;
    Err(usage(format!(
        "frf --method shooting --points {}: about {work:.1e} integration steps ({:.0} a branch point \
         on this model), over the {MAX_STEPS:.0e} limit: allowed {}",
        spec.points,
        est.steps_per_point,
        match fits {
            Some(p) => format!("--points 2 ..= {p} over this Omega range"),
            None => "a narrower Omega range".to_string(),
        }
    )))
}

/// `--method shooting`: the periodic branches by shooting continuation.
fn run_shooting(a: &FrfArgs) -> Result<(), Failure> {
    let iso = a.iso.inputs()?;
    let (params, model) = a.p.load()?;
    let (omega_from, omega_to) = a.range.omegas(&model)?;
    let mut spec = ShootFrfSpec::new(omega_from, omega_to, a.points);
    spec.direction = Direction::from_name(&a.direction).ok_or_else(|| {
        usage(format!(
            "--direction {}: allowed up, down",
            keys::truncate(&a.direction, 20)
        ))
    })?;
    spec.period = a.period.unwrap_or(1);
    spec.switch_branches = !a.no_switch;
    let meshes = meshes(&model, a.mesh.as_deref())?;
    check_shooting(&model, &spec)?;
    let mut c = ShootingContinuation::new(&model, spec)?;
    let mut points = vec![c.first_point()?];
    let mut failure = None;
    while !c.is_finished() {
        match c.advance(8) {
            Ok(p) => points.extend(p),
            Err(e) => {
                failure = Some(e);
                break;
            }
        }
        if a.p.progress {
            if let Some(p) = points.last() {
                note(&format!(
                    "{} points, Omega {:.4}",
                    points.len(),
                    p.point.omega
                ));
            }
        }
    }
    let mut value =
        report::shooting_frf_json(&model, &params, &c, &points, &meshes, failure.as_ref());
    report::add_branch_iso6336(&mut value, &params, &model, &iso);
    output(a.p.format, &value, csv::shooting_frf)?;
    for n in c.notes() {
        note(&format!("note: {n}"));
    }
    match failure {
        Some(e) => Err(Failure {
            code: 1,
            message: format!("{e} (the branch up to there was written, marked incomplete)"),
        }),
        None => Ok(()),
    }
}
