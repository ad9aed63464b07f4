//! `gearshock boundaries`: the regime map's boundaries traced as curves in
//! Omega and one key (folds of the periodic branch, where the response
//! jumps; where the drive flanks start to part and the back flanks start
//! to touch; the cusps where a jump disappears). A solver failure still
//! writes the curves traced up to there, marked incomplete, and exits
//! with code 1.

use crate::args::{KeyRange, OmegaRange, ParamArgs};
use crate::budget::{largest_within, MAX_BOUNDARY_WORK};
use crate::csv;
use crate::failure::{usage, Failure};
use crate::output::{note, output};
use crate::sweep::{self, Sweep};
use clap::Args;
use solver::boundaries::{BoundarySpec, BoundaryTrace};
use solver::hbm::Method;
use solver::keys;
use solver::params::ModelParams;
use solver::SolverError;

/// Options of `gearshock boundaries`.
#[derive(Debug, Args)]
pub struct BoundariesArgs {
    #[command(flatten)]
    p: ParamArgs,
    #[command(flatten)]
    range: OmegaRange,
    #[command(flatten)]
    rows: KeyRange,
    /// Values of the key (spread over its range) at which a frequency
    /// response seeds the curves (2 ..= 50).
    #[arg(long, default_value_t = 5)]
    levels: u32,
    /// Resolution: a curve's step moves at most 1 / points of the plane,
    /// and each seeding response has this many nominal points (10 ..= 2000).
    #[arg(long, default_value_t = 100)]
    points: u32,
    /// Harmonics H (1 ..= 40).
    #[arg(long, default_value_t = 7)]
    harmonics: usize,
    /// exact (closed-form integration between the contact switches), the
    /// one method whose Jacobian has the derivative a fold's test needs;
    /// aft is refused.
    #[arg(long, default_value = "exact")]
    method: String,
    /// Trace the contact boundaries of this mesh only (with its copies at
    /// the other planets), e.g. s1a1; by default every mesh's. Folds and
    /// period doublings are always traced.
    #[arg(long)]
    mesh: Option<String>,
}

/// The trace as a sweep of per mille of its work (levels, then curves); a
/// failure ends it and is kept, so the curves up to there are still written.
struct Trace {
    t: BoundaryTrace,
    failure: Option<SolverError>,
}

impl Sweep for Trace {
    type Item = ();
    fn total(&self) -> usize {
        1000
    }
    fn done(&self) -> usize {
        (self.t.progress() * 1000.0) as usize
    }
    fn is_finished(&self) -> bool {
        self.failure.is_some() || self.t.is_finished()
    }
    fn advance(&mut self) -> Result<Vec<()>, Failure> {
        if let Err(e) = self.t.advance(16) {
            self.failure = Some(e);
        }
        Ok(Vec::new())
    }
}

/// Checks a trace's estimated work on `params` against
/// [`MAX_BOUNDARY_WORK`]; over it, refuses naming the estimate and the
/// points (or else the harmonics) that would fit. `context` prefixes the
/// refusal (`figure map --link ` names the link's settings instead of
/// flags: `points` and `harmonics` then).
pub(crate) fn check_trace(
    params: &ModelParams,
    spec: &BoundarySpec,
    context: &str,
) -> Result<(), Failure> {
    let work = spec.estimated_work(params)?;
    if work <= MAX_BOUNDARY_WORK {
        return Ok(());
    }
    let with = |f: &dyn Fn(&mut BoundarySpec)| {
        let mut s = spec.clone();
        f(&mut s);
        s.estimated_work(params).map_err(Failure::from)
    };
    let flag = |name: &str| {
        if context.is_empty() {
            format!("--{name}")
        } else {
            name.to_string()
        }
    };
    let fits = match largest_within(10, spec.points, MAX_BOUNDARY_WORK, |p| {
        with(&|s| s.points = p)
    })? {
        Some(p) => format!(
            "{} 10 ..= {p} at {} {}",
            flag("points"),
            flag("harmonics"),
            spec.harmonics
        ),
        None => match largest_within(1, spec.harmonics as u32, MAX_BOUNDARY_WORK, |h| {
            with(&|s| {
                s.points = 10;
                s.harmonics = h as usize;
            })
        })? {
            Some(h) => format!("{} 1 ..= {h} at {} 10", flag("harmonics"), flag("points")),
            None => "a narrower Omega range or fewer levels".to_string(),
        },
    };
    Err(usage(format!(
        "{context}boundaries: about {work:.1e} work units (about a microsecond each) on this model, \
         over the {MAX_BOUNDARY_WORK:.1e} one trace may take: allowed {fits}, --levels {}",
        spec.levels
    )))
}

/// Checks the options and the budget, traces the curves and prints them.
pub fn run(a: &BoundariesArgs) -> Result<(), Failure> {
    let (params, model) = a.p.load()?;
    let (omega_from, omega_to) = a.range.omegas(&model)?;
    let mut spec = BoundarySpec::new(
        &a.rows.key,
        (a.rows.value_from + 0.0, a.rows.value_to + 0.0),
        (omega_from, omega_to),
    );
    spec.levels = a.levels;
    spec.points = a.points;
    spec.harmonics = a.harmonics;
    if let Some(name) = a.mesh.as_deref() {
        spec.contact_mesh = Some(crate::args::mesh_index(&model, Some(name))?);
    }
    spec.method = match Method::from_name(&a.method) {
        Some(Method::Exact) => Method::Exact,
        _ => {
            return Err(usage(format!(
                "--method {}: allowed {}",
                keys::truncate(&a.method, 30),
                solver::boundaries::ONLY_EXACT
            )))
        }
    };
    // Out-of-range levels, points and harmonics are refused by the
    // estimate's own check (the solver's), naming them.
    check_trace(&params, &spec, "")?;
    let mut run = Trace {
        t: BoundaryTrace::new(&params, spec)?,
        failure: None,
    };
    sweep::run(&mut run, &a.p, "per mille of the work", None)?;
    let Trace { t: trace, failure } = run;
    let value = report::boundaries_json(&model, &params, &trace, failure.as_ref());
    output(a.p.format, &value, csv::boundaries)?;
    for n in trace.notes() {
        note(&format!("note: {n}"));
    }
    match failure {
        Some(e) => Err(Failure {
            code: 1,
            message: format!("{e} (the curves up to there were written, marked incomplete)"),
        }),
        None => Ok(()),
    }
}
