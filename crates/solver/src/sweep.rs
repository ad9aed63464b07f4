//! Bifurcation sweeps over the dimensionless mesh frequency Omega.
//!
//! A sweep runs a steady-state response at each point of an Omega grid, up,
//! down or both (up, then back down), each point starting from the previous
//! point's end state so that hysteresis and jumps show. Work per call is
//! bounded: [`BifurcationSweep::advance`] computes at most `k` points and
//! returns them, so a caller can show progress and cancel by simply not
//! calling again (the browser does this in a worker).
//!
//! Chains. The continuation runs along `chains` interleaved chains: grid
//! point `i` belongs to chain `i mod chains`, and each point continues from
//! the previous point *of its chain*. With one chain this is the classic
//! sweep. Chains are independent, so they can run in separate workers or
//! machines (`shard`), and the results are bit-for-bit those of one run with
//! the same number of chains, whatever the split. With `chains = n` a chain
//! steps n grid points at a time, so keep `points / chains` dense enough to
//! follow a branch.

use crate::error::{Result, SolverError};
use crate::steady::{
    Impact, LyapunovEvidence, Model, Motion, SteadyOptions, SteadyRun, SteadyState, SteadyStats,
};

/// Direction of one swept point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Direction {
    /// Omega increasing.
    Up,
    /// Omega decreasing.
    Down,
}

impl Direction {
    /// Name for output.
    pub fn name(self) -> &'static str {
        match self {
            Direction::Up => "up",
            Direction::Down => "down",
        }
    }

    /// Parses `up` / `down`.
    pub fn from_name(s: &str) -> Option<Self> {
        match s {
            "up" => Some(Direction::Up),
            "down" => Some(Direction::Down),
            _ => None,
        }
    }
}

/// Which directions a sweep covers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Directions {
    /// Up only.
    Up,
    /// Down only.
    Down,
    /// Up, then down from where the up sweep ended.
    Both,
}

impl Directions {
    /// Name for output.
    pub fn name(self) -> &'static str {
        match self {
            Directions::Up => "up",
            Directions::Down => "down",
            Directions::Both => "both",
        }
    }

    /// Parses `up` / `down` / `both`.
    pub fn from_name(s: &str) -> Option<Self> {
        match s {
            "up" => Some(Directions::Up),
            "down" => Some(Directions::Down),
            "both" => Some(Directions::Both),
            _ => None,
        }
    }

    /// The directions swept, in order (up first).
    pub fn list(self) -> &'static [Direction] {
        match self {
            Directions::Up => &[Direction::Up],
            Directions::Down => &[Direction::Down],
            Directions::Both => &[Direction::Up, Direction::Down],
        }
    }
}

/// What to sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepSpec {
    /// First grid frequency.
    pub omega_from: f64,
    /// Last grid frequency.
    pub omega_to: f64,
    /// Number of grid points.
    pub points: u32,
    /// Directions.
    pub directions: Directions,
    /// Steady-state options (their `omega` is ignored).
    pub steady: SteadyOptions,
    /// Meshes whose Poincaré samples are kept (indices).
    pub meshes: Vec<usize>,
    /// Number of interleaved continuation chains.
    pub chains: u32,
    /// Compute only this chain (a shard), or all.
    pub shard: Option<u32>,
}

/// Largest number of grid points accepted.
pub const MAX_POINTS: u32 = 100_000;

impl SweepSpec {
    /// A sweep of `points` points from `omega_from` to `omega_to`, up, one chain.
    pub fn new(omega_from: f64, omega_to: f64, points: u32) -> Self {
        let mut steady = SteadyOptions::new(omega_from);
        steady.samples_per_period = 0;
        SweepSpec {
            omega_from,
            omega_to,
            points,
            directions: Directions::Up,
            steady,
            meshes: vec![0],
            chains: 1,
            shard: None,
        }
    }

    /// Grid frequency of point `i`.
    pub fn omega(&self, i: u32) -> f64 {
        if self.points <= 1 {
            self.omega_from
        } else {
            self.omega_from
                + (self.omega_to - self.omega_from) * f64::from(i) / f64::from(self.points - 1)
        }
    }

    /// Checks ranges.
    pub fn validate(&self, n_meshes: usize) -> Result<()> {
        let bad = |option: &str, value: String, allowed: String| {
            Err(SolverError::BadOption {
                option: option.into(),
                value,
                allowed,
            })
        };
        for (name, v) in [("omega-from", self.omega_from), ("omega-to", self.omega_to)] {
            if !(v.is_finite() && (0.01..=20.0).contains(&v)) {
                return bad(name, format!("{v}"), "0.01 ..= 20".into());
            }
        }
        if self.omega_to < self.omega_from {
            return bad(
                "omega-to",
                format!("{}", self.omega_to),
                format!(">= omega-from = {}", self.omega_from),
            );
        }
        if self.points == 0 || self.points > MAX_POINTS {
            return bad(
                "points",
                self.points.to_string(),
                format!("1 ..= {MAX_POINTS}"),
            );
        }
        if self.chains == 0 || self.chains > self.points {
            return bad(
                "chains",
                self.chains.to_string(),
                format!("1 ..= points ({})", self.points),
            );
        }
        if let Some(s) = self.shard {
            if s >= self.chains {
                return bad(
                    "shard",
                    format!("{s}/{}", self.chains),
                    "i/n with 0 <= i < n".into(),
                );
            }
        }
        if let Some(&j) = self.meshes.iter().find(|&&j| j >= n_meshes) {
            return bad("mesh", j.to_string(), format!("0 ..= {}", n_meshes - 1));
        }
        let mut steady = self.steady.clone();
        steady.omega = self.omega_from;
        steady.validate()
    }
}

/// One mesh's data at a swept point.
#[derive(Debug, Clone, PartialEq)]
pub struct PointMesh {
    /// Mesh index.
    pub mesh: usize,
    /// Poincaré samples of delta (m), the rotations' part.
    pub poincare_delta_m: Vec<f64>,
    /// Poincaré samples of delta' (m/s), the rotations' part.
    pub poincare_velocity_m_s: Vec<f64>,
    /// Poincaré samples of the tooth deflection x = delta - e (m), TE included.
    pub poincare_x_m: Vec<f64>,
    /// Poincaré samples of x' (m/s).
    pub poincare_x_velocity_m_s: Vec<f64>,
    /// Smallest delta over the recorded periods (m), the rotations' part.
    pub delta_min_m: f64,
    /// Largest delta (m), the rotations' part.
    pub delta_max_m: f64,
    /// Smallest tooth deflection x = delta - e over the recorded periods
    /// (m), TE included: the seed's plotted quantity.
    pub rel_min_m: f64,
    /// Largest tooth deflection x = delta - e (m), TE included.
    pub rel_max_m: f64,
    /// Impact regime.
    pub impact: Impact,
    /// max F / F_static.
    pub dynamic_factor: Option<f64>,
    /// The largest mesh force over the recorded periods (N).
    pub force_max_n: f64,
}

/// One computed point of a sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepPoint {
    /// Grid index.
    pub index: u32,
    /// Dimensionless frequency.
    pub omega: f64,
    /// Sweep direction.
    pub direction: Direction,
    /// Data of the requested meshes (empty if the point failed).
    pub meshes: Vec<PointMesh>,
    /// The most severe impact regime over all meshes.
    pub impact_worst: Impact,
    /// The mesh with the largest dynamic factor.
    pub worst_mesh: usize,
    /// Period of the Poincaré orbit, if periodic.
    pub period: Option<u32>,
    /// The classification of the steady state (not periodic for a failed point).
    pub motion: Motion,
    /// The Lyapunov probe's evidence, where it ran (see `steady::probe`).
    pub lyapunov: Option<LyapunovEvidence>,
    /// Work figures.
    pub stats: SteadyStats,
    /// Why the point failed (solver failure is reported, never shown as data).
    pub error: Option<String>,
}

/// Orders impact regimes from mild to severe (for "worst over meshes").
pub(crate) fn severity(i: Impact) -> u8 {
    match i {
        Impact::NoContact => 0,
        Impact::NoGap => 1,
        Impact::None => 2,
        Impact::SingleSided => 3,
        Impact::DoubleSided => 4,
    }
}

#[derive(Debug, Clone, Copy)]
struct Task {
    direction: Direction,
    chain: u32,
    index: u32,
}

/// A sweep in progress.
#[derive(Debug, Clone)]
pub struct BifurcationSweep {
    model: Model,
    spec: SweepSpec,
    tasks: Vec<Task>,
    next: usize,
    /// Each chain's last end state, and whether its run found chaos (the
    /// next point continues from both: [`SteadyRun::continued`]).
    chain_state: Vec<Option<(Vec<f64>, bool)>>,
    /// The point in progress of [`Self::advance_steps`] and its run.
    pending: Option<(Task, SteadyRun)>,
}

impl BifurcationSweep {
    /// Prepares a sweep (no work is done until [`Self::advance`]).
    pub fn new(model: Model, spec: SweepSpec) -> Result<Self> {
        spec.validate(model.system.meshes.len())?;
        let mut tasks = Vec::new();
        let chains: Vec<u32> = match spec.shard {
            Some(s) => vec![s],
            None => (0..spec.chains).collect(),
        };
        for &direction in spec.directions.list() {
            // Each chain's points in sweep order; chains interleaved round
            // robin so that progress fills the whole range evenly.
            let per_chain: Vec<Vec<u32>> = chains
                .iter()
                .map(|&c| {
                    let mut idx: Vec<u32> =
                        (c..spec.points).step_by(spec.chains as usize).collect();
                    if direction == Direction::Down {
                        idx.reverse();
                    }
                    idx
                })
                .collect();
            let longest = per_chain.iter().map(Vec::len).max().unwrap_or(0);
            for s in 0..longest {
                for (ci, list) in per_chain.iter().enumerate() {
                    if let Some(&index) = list.get(s) {
                        tasks.push(Task {
                            direction,
                            chain: chains[ci],
                            index,
                        });
                    }
                }
            }
        }
        let n_chains = spec.chains as usize;
        Ok(BifurcationSweep {
            model,
            spec,
            tasks,
            next: 0,
            chain_state: vec![None; n_chains],
            pending: None,
        })
    }

    /// Points in this sweep (this shard's, if sharded).
    pub fn total(&self) -> usize {
        self.tasks.len()
    }

    /// Points computed so far.
    pub fn done(&self) -> usize {
        self.next
    }

    /// Whether every point has been computed.
    pub fn is_finished(&self) -> bool {
        self.next >= self.tasks.len()
    }

    /// The sweep's specification.
    pub fn spec(&self) -> &SweepSpec {
        &self.spec
    }

    /// The model being swept.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// Computes up to `max_points` further points and returns them.
    pub fn advance(&mut self, max_points: usize) -> Vec<SweepPoint> {
        let mut out = Vec::with_capacity(max_points.min(self.tasks.len() - self.next));
        while out.len() < max_points && self.next < self.tasks.len() {
            if let Some(p) = self.advance_steps(u64::MAX) {
                out.push(p);
            }
        }
        out
    }

    /// Continues the next point's steady state for at most `max_steps`
    /// integrator steps ([`SteadyRun::advance`]): the point once it is
    /// complete, `None` while it is paused or when the sweep is finished.
    /// Points are the same bits as [`Self::advance`]'s, whatever the slices.
    pub fn advance_steps(&mut self, max_steps: u64) -> Option<SweepPoint> {
        if self.pending.is_none() {
            let task = *self.tasks.get(self.next)?;
            let mut opts = self.spec.steady.clone();
            opts.omega = self.spec.omega(task.index);
            let start = self.chain_state[task.chain as usize].take();
            let from = start.as_ref().map(|(y, chaos)| (y.as_slice(), *chaos));
            match SteadyRun::continued(&self.model, &opts, from) {
                Ok(run) => self.pending = Some((task, run)),
                Err(e) => {
                    self.next += 1;
                    return Some(self.point(task, Err(e)));
                }
            }
        }
        let (task, run) = self.pending.as_mut()?;
        let result = match run.advance(&self.model, max_steps) {
            Ok(None) => return None,
            Ok(Some(ss)) => Ok(ss),
            Err(e) => Err(e),
        };
        let task = *task;
        self.pending = None;
        self.next += 1;
        Some(self.point(task, result))
    }

    /// The sweep point of `task` from its steady state (or failure); a
    /// success's end state continues the task's chain.
    fn point(&mut self, task: Task, result: Result<SteadyState>) -> SweepPoint {
        let omega = self.spec.omega(task.index);
        match result {
            Ok(ss) => {
                self.chain_state[task.chain as usize] =
                    Some((ss.end_state.clone(), ss.found_chaos()));
                let worst_mesh = ss.worst_mesh();
                let impact_worst = ss
                    .meshes
                    .iter()
                    .map(|m| m.impact)
                    .max_by_key(|&i| severity(i))
                    .unwrap_or(Impact::None);
                SweepPoint {
                    index: task.index,
                    omega,
                    direction: task.direction,
                    meshes: self
                        .spec
                        .meshes
                        .iter()
                        .map(|&j| {
                            let m = &ss.meshes[j];
                            PointMesh {
                                mesh: j,
                                poincare_delta_m: m.poincare_delta_m.clone(),
                                poincare_velocity_m_s: m.poincare_velocity_m_s.clone(),
                                poincare_x_m: m.poincare_x_m.clone(),
                                poincare_x_velocity_m_s: m.poincare_x_velocity_m_s.clone(),
                                delta_min_m: m.delta_min_m,
                                delta_max_m: m.delta_max_m,
                                rel_min_m: m.rel_min_m,
                                rel_max_m: m.rel_max_m,
                                impact: m.impact,
                                dynamic_factor: m.dynamic_factor,
                                force_max_n: m.force_max_n,
                            }
                        })
                        .collect(),
                    impact_worst,
                    worst_mesh,
                    period: ss.period,
                    motion: ss.motion,
                    lyapunov: ss.lyapunov,
                    stats: ss.stats,
                    error: None,
                }
            }
            Err(e) => SweepPoint {
                // The chain restarts from the static equilibrium at its next point.
                index: task.index,
                omega,
                direction: task.direction,
                meshes: Vec::new(),
                impact_worst: Impact::None,
                worst_mesh: 0,
                period: None,
                motion: Motion::NotPeriodic,
                lyapunov: None,
                stats: SteadyStats::default(),
                error: Some(e.to_string()),
            },
        }
    }
}

/// Canonical order of a sweep's points for output: up points by ascending
/// Omega, then down points by descending Omega. Merged shards sorted this way
/// equal an unsharded run.
pub fn canonical_order(points: &mut [SweepPoint]) {
    points.sort_by_key(|p| match p.direction {
        Direction::Up => (0, i64::from(p.index)),
        Direction::Down => (1, -i64::from(p.index)),
    });
}
