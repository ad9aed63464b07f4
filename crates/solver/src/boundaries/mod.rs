//! The regime map's boundaries traced as curves in two parameters, Omega
//! and a key `p` (backlash, TE amplitude, damping ratio, torque, ...): the
//! folds of the harmonic-balance branch (where the response jumps) and the
//! contact boundaries of the periodic branch (where an extreme of a mesh's
//! relative displacement reaches `+b` or `-b`), with the cusps where two
//! folds meet and the jump disappears.
//!
//! - [`bordered`]: what the systems share (an evaluation, the bordered test).
//! - [`doubling`]: the period-doubling test function on the monodromy.
//! - [`estimate`]: what a trace will cost, before it starts.
//! - [`family`]: the harmonic-balance residual as a function of `p`.
//! - [`systems`]: the augmented systems (the branch equations plus the
//!   condition that vanishes on the boundary).
//! - [`trace`]: pseudo-arclength continuation of their solution curves.
//! - [`run`]: a curve traced both ways, its points, ends and cusps.
//! - [`starts`]: where the curves start: one-parameter branches at a few
//!   levels of `p`, their located folds and contact changes.
//!
//! How. [`BoundaryTrace`] first follows the one-parameter branch
//! ([`crate::hbm::FrfContinuation`]) over the Omega range at `levels`
//! values of `p` spread over its range. Each located fold and each change
//! of contact between two neighbouring branch points starts a curve: the
//! start is corrected at its `p`, then continued both ways by
//! pseudo-arclength in `(X, Omega, p)` until the curve leaves the box of
//! the two ranges or closes. A start that lies on a curve already traced
//! (its kind and mesh, within `1e-3` of the box) is skipped, so the upper
//! and lower fold of one jump give one curve through the cusp. Work is
//! bounded per call: [`BoundaryTrace::advance`] computes at most `k`
//! branch or curve points.
//!
//! Period doublings: the seeding branches compute Floquet stability and
//! label where a real multiplier passes -1; each such point starts a
//! curve of the bordered test function on the monodromy `M + I`
//! ([`doubling`]).

mod bordered;
mod doubling;
mod estimate;
mod family;
mod run;
mod starts;
mod systems;
mod trace;

use crate::error::{Result, SolverError};
use crate::hbm::{BranchPoint, FrfContinuation, FrfSpec, Method};
use crate::keys;
use crate::params::ModelParams;
use family::Family;
use starts::Start;
use trace::{Traced, Tracer};

pub use trace::TraceEnd;

/// What a boundary curve marks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CurveKind {
    /// A fold of the periodic branch: the jump.
    Fold,
    /// A Floquet multiplier of the periodic branch at -1: period doubling begins.
    PeriodDoubling,
    /// The smallest relative displacement reaches `+b`: the drive flanks
    /// start to part (single-sided impact begins).
    DriveFlanksPart,
    /// The smallest relative displacement reaches `-b`: the back flanks
    /// start to touch (double-sided impact begins).
    BackFlanksTouch,
    /// The largest relative displacement reaches `+b`: the drive flanks
    /// start to touch (a mesh without load starts to impact).
    DriveFlanksTouch,
}

impl CurveKind {
    /// Every kind, in output order.
    pub const ALL: [CurveKind; 5] = [
        CurveKind::Fold,
        CurveKind::PeriodDoubling,
        CurveKind::DriveFlanksPart,
        CurveKind::BackFlanksTouch,
        CurveKind::DriveFlanksTouch,
    ];

    /// Name for output.
    pub fn name(self) -> &'static str {
        match self {
            CurveKind::Fold => "fold",
            CurveKind::PeriodDoubling => "period-doubling",
            CurveKind::DriveFlanksPart => "drive-flanks-part",
            CurveKind::BackFlanksTouch => "back-flanks-touch",
            CurveKind::DriveFlanksTouch => "drive-flanks-touch",
        }
    }

    /// What it means, in plain words.
    pub fn meaning(self) -> &'static str {
        match self {
            CurveKind::Fold => "the jump",
            CurveKind::PeriodDoubling => "period doubling begins",
            CurveKind::DriveFlanksPart => {
                "the drive flanks start to part (single-sided impact begins)"
            }
            CurveKind::BackFlanksTouch => {
                "the back flanks start to touch (double-sided impact begins)"
            }
            CurveKind::DriveFlanksTouch => "the drive flanks start to touch",
        }
    }
}

/// The side of a curve, in the plane of Omega and the key, on which the
/// change it marks has not happened: the branch still exists (a fold), or
/// the contact has not begun (a contact boundary).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Toward lower Omega.
    LowerOmega,
    /// Toward higher Omega.
    HigherOmega,
    /// Toward lower values of the key.
    LowerValue,
    /// Toward higher values of the key.
    HigherValue,
}

impl Side {
    /// Name for output.
    pub fn name(self) -> &'static str {
        match self {
            Side::LowerOmega => "lower-omega",
            Side::HigherOmega => "higher-omega",
            Side::LowerValue => "lower-value",
            Side::HigherValue => "higher-value",
        }
    }

    /// The axis direction closest to a normal `(omega, value)` given in
    /// units of the box.
    fn of(normal: (f64, f64)) -> Self {
        if normal.0.abs() >= normal.1.abs() {
            if normal.0 >= 0.0 {
                Side::HigherOmega
            } else {
                Side::LowerOmega
            }
        } else if normal.1 >= 0.0 {
            Side::HigherValue
        } else {
            Side::LowerValue
        }
    }
}

/// One point of a boundary curve.
#[derive(Debug, Clone, PartialEq)]
pub struct CurvePoint {
    /// Dimensionless frequency.
    pub omega: f64,
    /// The key's value.
    pub value: f64,
    /// See [`Side`].
    pub stable_side: Side,
    /// The side's normal in units of the box (`omega / range`, `value / range`), unit length.
    pub normal: (f64, f64),
    /// Period doublings only: whether the orbit's other Floquet multipliers
    /// are inside the unit circle, so that the doubling happens on a stable
    /// orbit and time integration sees it (`false`: it happens on an
    /// unstable part of the branch, which the gears do not follow).
    pub others_stable: Option<bool>,
}

/// A traced boundary.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    /// What it marks.
    pub kind: CurveKind,
    /// The physical mesh whose contact it follows (its kind's first mesh
    /// under the symmetric reduction); `None` for a fold.
    pub mesh: Option<usize>,
    /// Its points, in order along the curve.
    pub points: Vec<CurvePoint>,
    /// How each end came about (first end, last end).
    pub ends: [TraceEnd; 2],
}

/// Where two folds meet and the jump disappears.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cusp {
    /// Dimensionless frequency.
    pub omega: f64,
    /// The key's value.
    pub value: f64,
    /// Index of the fold curve it lies on.
    pub curve: usize,
}

/// Options of a boundary trace.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundarySpec {
    /// The key varied with Omega.
    pub key: String,
    /// Its range.
    pub value_from: f64,
    /// See `value_from`.
    pub value_to: f64,
    /// Omega range.
    pub omega_from: f64,
    /// See `omega_from`.
    pub omega_to: f64,
    /// Values of the key at which one-parameter branches seed the curves.
    pub levels: u32,
    /// Resolution: a curve's step moves at most `1 / points` of the box,
    /// and the seeding branches use `points` nominal points.
    pub points: u32,
    /// Harmonics H.
    pub harmonics: usize,
    /// How the nonlinear forces are balanced: [`Method::Exact`] only
    /// (see [`ONLY_EXACT`]).
    pub method: Method,
    /// Use the cyclic-symmetry reduction when the planets allow it.
    pub symmetric: bool,
    /// Only the contact boundaries of this mesh (with its copies at the
    /// other planets, which the symmetric reduction makes one): the curves
    /// a map of that mesh's regime needs. `None`: every mesh's. Folds and
    /// period doublings belong to the whole set and are always traced. An
    /// index past the model's meshes traces no contact boundary.
    pub contact_mesh: Option<usize>,
}

impl BoundarySpec {
    /// Defaults: 5 levels, 100 points, H = 7, exact method, symmetric.
    pub fn new(key: &str, values: (f64, f64), omegas: (f64, f64)) -> Self {
        BoundarySpec {
            key: key.into(),
            value_from: values.0,
            value_to: values.1,
            omega_from: omegas.0,
            omega_to: omegas.1,
            levels: 5,
            points: 100,
            harmonics: 7,
            method: Method::Exact,
            symmetric: true,
            contact_mesh: None,
        }
    }

    /// The key's value at level `i`.
    pub fn level(&self, i: u32) -> f64 {
        if self.levels <= 1 {
            return self.value_from;
        }
        self.value_from
            + (self.value_to - self.value_from) * f64::from(i) / f64::from(self.levels - 1)
    }

    fn validate(&self, base: &ModelParams) -> Result<()> {
        let bad = SolverError::bad_option::<()>;
        for (name, v) in [("omega-from", self.omega_from), ("omega-to", self.omega_to)] {
            if !(v.is_finite() && (0.01..=20.0).contains(&v)) {
                return bad(name, format!("{v}"), "0.01 ..= 20");
            }
        }
        if self.omega_to <= self.omega_from {
            return bad(
                "omega-to",
                format!("{}", self.omega_to),
                &format!("more than --omega-from {}", self.omega_from),
            );
        }
        if !(self.value_from.is_finite() && self.value_to.is_finite()) {
            return bad(
                "value-to",
                format!("{}..{}", self.value_from, self.value_to),
                "finite numbers",
            );
        }
        if self.value_to <= self.value_from {
            return bad(
                "value-to",
                format!("{}", self.value_to),
                &format!("more than --value-from {}", self.value_from),
            );
        }
        if !(2..=50).contains(&self.levels) {
            return bad("levels", self.levels.to_string(), "2 ..= 50");
        }
        if !(10..=2000).contains(&self.points) {
            return bad("points", self.points.to_string(), "10 ..= 2000");
        }
        if self.harmonics == 0 || self.harmonics > 40 {
            return bad("harmonics", self.harmonics.to_string(), "1 ..= 40");
        }
        if self.method != Method::Exact {
            return bad("method", self.method.name().to_string(), ONLY_EXACT);
        }
        // Both ends must be values the key takes (its own range message).
        for v in [self.value_from, self.value_to] {
            let mut p = base.clone();
            keys::set(&mut p, &self.key, keys::Value::Num(v))?;
        }
        Ok(())
    }
}

/// Why the trace takes the exact method only. AFT's Jacobian samples the
/// dead zone's slope on the time grid, so it is constant in the orbit
/// until a sample crosses a contact: the fold's test function, whose
/// gradient is the Jacobian's derivative, has none to follow (every fold
/// start of the gear pair's te_um box wandered off to Omega 5e12).
pub const ONLY_EXACT: &str =
    "exact (a fold's test function needs the Jacobian's derivative, which AFT's \
     sampled Jacobian does not have)";

/// Counters of a trace.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct BoundaryStats {
    /// Points of the seeding one-parameter branches.
    pub level_points: u64,
    /// Points of the traced curves.
    pub curve_points: u64,
    /// Newton iterations of the curves' correctors.
    pub newton_iterations: u64,
    /// Work units ([`crate::hbm::HbmCost`]) of the seeding branches: their
    /// Newton iterations and monodromies.
    pub level_work: u64,
    /// Work units of the curves: every evaluation, assembly, monodromy and
    /// factorization of their correctors.
    pub curve_work: u64,
}

impl BoundaryStats {
    /// Work units of the whole trace.
    pub fn work(&self) -> u64 {
        self.level_work + self.curve_work
    }
}

/// The keys whose value the trace can vary: those that change only the
/// contact laws, the transmission error, the loads or the damping, never
/// the modes the harmonic balance is written in.
pub(crate) const VARIABLE_KEYS: &str =
    "backlash_um, te_um, damping_ratio, stiffness_variation, the torques \
     and the per-mesh backlash and TE keys";

/// A curve being traced.
#[derive(Debug, Clone)]
struct Running {
    kind: CurveKind,
    mesh: Option<usize>,
    tracer: Tracer,
    /// The tracer and point at the start, for the second direction.
    start: (Tracer, Traced),
    forward: Vec<Traced>,
    backward: Vec<Traced>,
    first_end: Option<TraceEnd>,
}

/// A boundary trace in progress; [`BoundaryTrace::advance`] computes a
/// bounded number of points per call.
#[derive(Debug, Clone)]
pub struct BoundaryTrace {
    spec: BoundarySpec,
    fam: Family,
    /// The level being followed and its continuation.
    level: u32,
    level_run: Option<(FrfContinuation, Vec<BranchPoint>)>,
    starts: Vec<Start>,
    next_start: usize,
    running: Option<Running>,
    curves: Vec<Curve>,
    cusps: Vec<Cusp>,
    notes: Vec<String>,
    /// Work so far.
    pub stats: BoundaryStats,
    /// The work estimated before it started ([`BoundarySpec::estimated_work`]).
    estimated_work: f64,
}

impl BoundaryTrace {
    /// Prepares the trace; bad options and keys fail here, naming them.
    pub fn new(base: &ModelParams, spec: BoundarySpec) -> Result<Self> {
        let estimated_work = spec.estimated_work(base)?;
        let fam = Family::new(
            base,
            &spec.key,
            spec.harmonics,
            spec.method,
            spec.symmetric,
            spec.value_to - spec.value_from,
        )?;
        let mid = 0.5 * (spec.value_from + spec.value_to);
        if !(fam.same_basis(spec.value_from, spec.value_to)?
            && fam.same_basis(spec.value_from, mid)?)
        {
            return Err(SolverError::BadOption {
                option: "key".into(),
                value: spec.key.clone(),
                allowed: format!("a key that leaves the natural modes unchanged: {VARIABLE_KEYS}"),
            });
        }
        Ok(BoundaryTrace {
            spec,
            fam,
            level: 0,
            level_run: None,
            starts: Vec::new(),
            next_start: 0,
            running: None,
            curves: Vec::new(),
            cusps: Vec::new(),
            notes: Vec::new(),
            stats: BoundaryStats::default(),
            estimated_work,
        })
    }

    /// The work units estimated before the trace started
    /// ([`BoundarySpec::estimated_work`]), beside [`BoundaryStats::work`].
    pub fn estimated_work(&self) -> f64 {
        self.estimated_work
    }

    /// The options.
    pub fn spec(&self) -> &BoundarySpec {
        &self.spec
    }

    /// The curves traced so far.
    pub fn curves(&self) -> &[Curve] {
        &self.curves
    }

    /// The cusps found so far.
    pub fn cusps(&self) -> &[Cusp] {
        &self.cusps
    }

    /// Plain sentences on what the trace could not do (a seeding branch
    /// that failed, a start the corrector did not reach).
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// Whether every level and every start is done.
    pub fn is_finished(&self) -> bool {
        self.level >= self.spec.levels
            && self.running.is_none()
            && self.next_start >= self.starts.len()
    }

    /// A rough fraction done, for progress bars: the levels count half,
    /// the starts the other half.
    pub fn progress(&self) -> f64 {
        let levels = f64::from(self.level.min(self.spec.levels)) / f64::from(self.spec.levels);
        let starts = if self.level < self.spec.levels || self.starts.is_empty() {
            0.0
        } else {
            self.next_start as f64 / self.starts.len() as f64
        };
        (0.5 * levels + 0.5 * starts).clamp(0.0, 1.0)
    }

    /// Computes at most `k` branch or curve points; returns how many.
    pub fn advance(&mut self, k: usize) -> Result<usize> {
        let mut done = 0;
        while done < k && !self.is_finished() {
            if self.level < self.spec.levels {
                done += self.advance_level(k - done)?;
            } else if self.running.is_some() {
                done += self.advance_curve(k - done);
            } else {
                self.begin_next_curve();
                done += 1;
            }
            self.stats.curve_work = self.fam.work.round() as u64;
        }
        Ok(done)
    }

    /// Follows the current level's one-parameter branch by at most `k` points.
    fn advance_level(&mut self, k: usize) -> Result<usize> {
        let p = self.spec.level(self.level);
        let (mut c, mut points) = match self.level_run.take() {
            Some(run) => run,
            None => {
                let model = self.fam.model_at(p)?;
                let mut fs =
                    FrfSpec::new(self.spec.omega_from, self.spec.omega_to, self.spec.points);
                fs.harmonics = self.spec.harmonics;
                fs.method = self.spec.method;
                fs.symmetric = self.spec.symmetric;
                fs.stability = true;
                (FrfContinuation::new(&model, fs)?, Vec::new())
            }
        };
        let mut failed = None;
        let before = points.len();
        match c.advance(k) {
            Ok(new) => points.extend(new),
            Err(e) => failed = Some(e),
        }
        let got = (points.len() - before).max(1);
        self.stats.level_points += (points.len() - before) as u64;
        if failed.is_none() && !c.is_finished() {
            self.level_run = Some((c, points));
            return Ok(got);
        }
        let cost = self.fam.cost();
        let work = c.stats.jacobians as f64 * cost.newton_iteration()
            + c.stats.monodromies as f64
                * cost.mean_monodromy(self.spec.omega_from, self.spec.omega_to);
        self.stats.level_work += work.round() as u64;
        if let Some(e) = failed {
            self.notes.push(format!(
                "The branch at {} = {p} failed ({e}); its points before the failure seed the curves.",
                self.spec.key
            ));
        }
        let found = starts::find(&mut self.fam, &points, p, self.spec.contact_mesh);
        self.starts.extend(found);
        self.level += 1;
        if self.level >= self.spec.levels {
            starts::order(&mut self.starts);
        }
        Ok(got)
    }
}
