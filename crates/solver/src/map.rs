//! Impact-regime maps: the steady response's regime over a grid of Omega and
//! a second parameter (any numeric key, typically `backlash_um` or `te_um`).
//!
//! Each row holds the second parameter fixed and sweeps Omega upward, each
//! cell starting from the previous cell's end state (as an upward
//! bifurcation sweep does, so a row shows the jumps an upward run-up meets).
//! Rows are independent: shard `i` of `n` computes rows `i, i + n, ...`, so
//! workers or cluster jobs split a map by rows and [`canonical_cells`]
//! restores the order. Work per call is bounded: [`RegimeMap::advance`]
//! computes at most `k` cells, and [`RegimeMap::advance_steps`] at most a
//! given number of integrator steps of one cell's steady state (paused and
//! resumed without changing a bit).

use crate::error::{Result, SolverError};
use crate::keys::{self, Value};
use crate::params::ModelParams;
use crate::steady::{Impact, LyapunovEvidence, Model, Motion, SteadyOptions, SteadyRun};
use crate::sweep::severity;

/// What to compute.
#[derive(Debug, Clone, PartialEq)]
pub struct MapSpec {
    /// First Omega (columns).
    pub omega_from: f64,
    /// Last Omega.
    pub omega_to: f64,
    /// Number of Omega values (>= 2).
    pub omega_points: u32,
    /// The parameter key of the rows.
    pub key: String,
    /// First value of the key.
    pub value_from: f64,
    /// Last value of the key.
    pub value_to: f64,
    /// Number of rows (>= 1).
    pub value_points: u32,
    /// Steady-state options per cell (its `omega` is overwritten).
    pub steady: SteadyOptions,
    /// Mesh whose regime is reported; `None` for the worst over all meshes.
    pub mesh: Option<usize>,
    /// Shard `(i, n)`: only rows `i, i + n, ...`.
    pub shard: Option<(u32, u32)>,
}

impl MapSpec {
    /// A map over `backlash_um` or `te_um` (or any numeric key) with 300 + 100 periods per cell.
    pub fn new(omega: (f64, f64, u32), key: &str, values: (f64, f64, u32)) -> Self {
        MapSpec {
            omega_from: omega.0,
            omega_to: omega.1,
            omega_points: omega.2,
            key: key.into(),
            value_from: values.0,
            value_to: values.1,
            value_points: values.2,
            steady: SteadyOptions::new(omega.0),
            mesh: None,
            shard: None,
        }
    }

    /// The Omega of column `c`.
    pub fn omega(&self, c: u32) -> f64 {
        self.omega_from
            + (self.omega_to - self.omega_from) * f64::from(c) / f64::from(self.omega_points - 1)
    }

    /// The key's value on row `r`.
    pub fn value(&self, r: u32) -> f64 {
        if self.value_points == 1 {
            return self.value_from;
        }
        self.value_from
            + (self.value_to - self.value_from) * f64::from(r) / f64::from(self.value_points - 1)
    }

    fn validate(&self) -> Result<()> {
        let bad = |option: &str, value: String, allowed: &str| {
            SolverError::bad_option(option, value, allowed)
        };
        if !(self.omega_from.is_finite() && (0.01..=20.0).contains(&self.omega_from)) {
            return bad("omega-from", format!("{}", self.omega_from), "0.01 ..= 20");
        }
        if !(self.omega_to.is_finite() && self.omega_to > self.omega_from && self.omega_to <= 20.0)
        {
            return bad(
                "omega-to",
                format!("{}", self.omega_to),
                "omega-from < omega-to <= 20",
            );
        }
        if !(2..=2000).contains(&self.omega_points) {
            return bad("omega-points", self.omega_points.to_string(), "2 ..= 2000");
        }
        if !(1..=2000).contains(&self.value_points) {
            return bad("value-points", self.value_points.to_string(), "1 ..= 2000");
        }
        if u64::from(self.omega_points) * u64::from(self.value_points) > 1_000_000 {
            return bad(
                "cells",
                (u64::from(self.omega_points) * u64::from(self.value_points)).to_string(),
                "at most 1000000",
            );
        }
        if !(self.value_from.is_finite() && self.value_to.is_finite()) {
            return bad(
                "values",
                format!("{}..{}", self.value_from, self.value_to),
                "finite numbers",
            );
        }
        if let Some((i, n)) = self.shard {
            if n == 0 || i >= n || n > 10_000 {
                return bad("shard", format!("{i}/{n}"), "i/n with 0 <= i < n <= 10000");
            }
        }
        self.steady.validate()
    }
}

/// One cell of the map.
#[derive(Debug, Clone, PartialEq)]
pub struct MapCell {
    /// Row (index of the key's value).
    pub row: u32,
    /// Column (index of Omega).
    pub column: u32,
    /// Dimensionless frequency.
    pub omega: f64,
    /// The key's value.
    pub value: f64,
    /// Regime of the reported mesh (or the worst over all meshes).
    pub impact: Impact,
    /// Period of the Poincaré orbit in mesh periods, `None` if not periodic.
    pub period: Option<u32>,
    /// The steady state's classification (exact orbit, periodic by
    /// integration, not periodic, ...): not periodic for a failed cell.
    pub motion: Motion,
    /// The Lyapunov probe's evidence, where it ran.
    pub lyapunov: Option<LyapunovEvidence>,
    /// A solver failure at this cell (the cell then has no regime).
    pub error: Option<String>,
}

/// A regime map in progress.
#[derive(Debug, Clone)]
pub struct RegimeMap {
    base: ModelParams,
    spec: MapSpec,
    rows: Vec<u32>,
    next_row: usize,
    next_column: u32,
    model: Option<Model>,
    /// The last cell's end state, and whether its run found chaos (the
    /// next cell continues from both: [`SteadyRun::continued`]).
    state: Option<(Vec<f64>, bool)>,
    /// The cell in progress of [`Self::advance_steps`].
    pending: Option<SteadyRun>,
    done: usize,
    /// Integration steps of the cells done so far (see [`cell_steps`]).
    steps: u64,
}

/// A steady state's work in integration steps: its run, its shooting
/// attempts and its Lyapunov probe's neighbour.
fn cell_steps(ss: &crate::steady::SteadyState) -> u64 {
    ss.stats.integrator.steps + ss.stats.shooting_steps + ss.stats.probe_steps
}

/// Pilot cells of [`RegimeMap::estimated_steps`].
const PILOT_CELLS: u32 = 4;
/// A map's cell costs this much of a pilot cell: it goes on from its
/// neighbour's end state, which has settled (or found chaos) already,
/// where a pilot starts from rest (measured: 0.4 to 1.1 on both models).
const FROM_REST: f64 = 0.8;

impl RegimeMap {
    /// Checks the spec and that every row's parameter set is valid (so a bad
    /// range fails at once, naming the key and the value).
    pub fn new(base: &ModelParams, spec: MapSpec) -> Result<Self> {
        spec.validate()?;
        if let Some((i, n)) = spec.shard {
            if n > spec.value_points {
                return SolverError::bad_option(
                    "shard",
                    format!("{i}/{n}"),
                    &format!(
                        "at most as many shards as rows: n <= --value-points {}",
                        spec.value_points
                    ),
                );
            }
        }
        // An integer key (planets) takes whole values only: every row's,
        // checked before any cell is computed.
        if let Some(k) = keys::spec(&spec.key) {
            if matches!(k.ty, keys::KeyType::Int { .. }) {
                if let Some(r) = (0..spec.value_points).find(|&r| spec.value(r).fract() != 0.0) {
                    return SolverError::bad_option(
                        "value-points",
                        spec.value_points,
                        &format!(
                            "a count whose rows give {} whole values (row {} would be {})",
                            spec.key,
                            r + 1,
                            spec.value(r)
                        ),
                    );
                }
            }
        }
        for r in [0, spec.value_points - 1] {
            let mut p = base.clone();
            keys::set(&mut p, &spec.key, Value::Num(spec.value(r)))?;
            Model::new(&p)?;
        }
        let rows: Vec<u32> = (0..spec.value_points)
            .filter(|r| spec.shard.is_none_or(|(i, n)| r % n == i))
            .collect();
        Ok(RegimeMap {
            base: base.clone(),
            spec,
            rows,
            next_row: 0,
            next_column: 0,
            model: None,
            state: None,
            pending: None,
            done: 0,
            steps: 0,
        })
    }

    /// Integration steps of the cells computed so far: each cell's run,
    /// shooting attempts and Lyapunov probe.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// The estimated integration steps of the whole map (or shard), and
    /// the steps its pilot took. A cell's cost depends on its motion far
    /// more than on its periods' budget (a periodic cell settles and is
    /// shot in a few dozen periods, a chaotic one is probed, one that is
    /// neither runs its whole transient): the pilot computes up to
    /// [`PILOT_CELLS`] cells spread over the grid, each from rest with the
    /// map's options, and the estimate is the cells times their mean,
    /// times [`FROM_REST`]. Measured, it was within a factor of 2.5 of the
    /// map's steps on both models (`crates/solver/tests/budgets.rs`).
    ///
    /// With a `budget` (steps), a pilot cell stops once it alone shows
    /// the map over it (at 1.25 times the budget's share of a cell, before
    /// [`FROM_REST`]) and counts as that many steps: the estimate is then a
    /// lower bound, enough to tell the map does not fit, and the pilot
    /// costs at most five budget shares of a cell.
    pub fn estimated_steps(&self, budget: Option<f64>) -> Result<(f64, u64)> {
        let total = self.total() as u32;
        let cell_cap = budget.map_or(u64::MAX, |b| {
            (1.25 * b / (FROM_REST * f64::from(total.max(1)))).ceil() as u64
        });
        let pilots = PILOT_CELLS.min(total).max(1);
        let mut pilot = 0u64;
        for k in 0..pilots {
            // Evenly spread over the cells in row order, centred in each share.
            let index = (2 * k + 1) * total / (2 * pilots);
            let (row, column) = (
                self.rows[(index / self.spec.omega_points) as usize],
                index % self.spec.omega_points,
            );
            let mut p = self.base.clone();
            keys::set(&mut p, &self.spec.key, Value::Num(self.spec.value(row)))?;
            let model = Model::new(&p)?;
            let mut opts = self.spec.steady.clone();
            opts.omega = self.spec.omega(column);
            opts.samples_per_period = 0;
            opts.history_meshes.clear();
            let mut run = SteadyRun::new(&model, &opts, None)?;
            pilot += match run.advance(&model, cell_cap) {
                Ok(Some(ss)) => cell_steps(&ss),
                Ok(None) => cell_cap,
                // A failed cell costs what it took.
                Err(_) => run.steps(),
            };
        }
        let mean = pilot as f64 / f64::from(pilots);
        Ok((FROM_REST * mean * f64::from(total), pilot))
    }

    /// The specification.
    pub fn spec(&self) -> &MapSpec {
        &self.spec
    }

    /// Cells this map (or shard) computes.
    pub fn total(&self) -> usize {
        self.rows.len() * self.spec.omega_points as usize
    }

    /// Cells computed so far.
    pub fn done(&self) -> usize {
        self.done
    }

    /// Whether every cell is computed.
    pub fn is_finished(&self) -> bool {
        self.next_row >= self.rows.len()
    }

    /// Computes up to `k` further cells. A failing cell is reported in its
    /// `error` field and the row goes on from the static equilibrium.
    pub fn advance(&mut self, k: usize) -> Vec<MapCell> {
        let mut out = Vec::with_capacity(k.min(self.total() - self.done));
        while out.len() < k && !self.is_finished() {
            out.extend(self.advance_steps(u64::MAX));
        }
        out
    }

    /// Continues the next cell's steady state for at most `max_steps`
    /// integrator steps ([`SteadyRun::advance`]): the cells completed (one,
    /// or a whole row's when its model cannot be built), none while the
    /// cell is paused or when the map is finished. Cells are the same bits
    /// as [`Self::advance`]'s, whatever the slices.
    pub fn advance_steps(&mut self, max_steps: u64) -> Vec<MapCell> {
        if self.is_finished() {
            return Vec::new();
        }
        let row = self.rows[self.next_row];
        let value = self.spec.value(row);
        let column = self.next_column;
        let omega = self.spec.omega(column);
        let cell = |impact, motion: Motion, lyapunov, error| MapCell {
            row,
            column,
            omega,
            value,
            impact,
            period: motion.period(),
            motion,
            lyapunov,
            error,
        };
        if self.model.is_none() {
            let mut p = self.base.clone();
            let built =
                keys::set(&mut p, &self.spec.key, Value::Num(value)).and_then(|()| Model::new(&p));
            match built {
                Ok(m) => self.model = Some(m),
                Err(e) => {
                    // Skip the row: every cell carries the error.
                    let cells: Vec<MapCell> = (column..self.spec.omega_points)
                        .map(|c| MapCell {
                            row,
                            column: c,
                            omega: self.spec.omega(c),
                            value,
                            impact: Impact::None,
                            period: None,
                            motion: Motion::NotPeriodic,
                            lyapunov: None,
                            error: Some(e.to_string()),
                        })
                        .collect();
                    self.done += cells.len();
                    self.finish_row();
                    return cells;
                }
            }
        }
        let Some(model) = self.model.as_ref() else {
            return Vec::new();
        };
        let run = match self.pending.as_mut() {
            Some(run) => run,
            None => {
                let mut opts = self.spec.steady.clone();
                opts.omega = omega;
                opts.samples_per_period = 0;
                opts.history_meshes.clear();
                let from = self.state.as_ref().map(|(y, chaos)| (y.as_slice(), *chaos));
                match SteadyRun::continued(model, &opts, from) {
                    Ok(run) => self.pending.insert(run),
                    Err(e) => {
                        return vec![self.cell_done(
                            cell(Impact::None, Motion::NotPeriodic, None, Some(e.to_string())),
                            None,
                        )]
                    }
                }
            }
        };
        let c = match run.advance(model, max_steps) {
            Ok(None) => return Vec::new(),
            Ok(Some(ss)) => {
                let impact = match self.spec.mesh {
                    Some(j) => ss.meshes.get(j).map_or(Impact::None, |m| m.impact),
                    None => ss
                        .meshes
                        .iter()
                        .map(|m| m.impact)
                        .max_by_key(|&i| severity(i))
                        .unwrap_or(Impact::None),
                };
                self.steps += cell_steps(&ss);
                let c = cell(impact, ss.motion, ss.lyapunov, None);
                let chaos = ss.found_chaos();
                self.cell_done(c, Some((ss.end_state, chaos)))
            }
            Err(e) => self.cell_done(
                cell(Impact::None, Motion::NotPeriodic, None, Some(e.to_string())),
                None,
            ),
        };
        vec![c]
    }

    /// Records cell `c` as done; the row goes on from `end` (the static
    /// equilibrium after a failure).
    fn cell_done(&mut self, c: MapCell, end: Option<(Vec<f64>, bool)>) -> MapCell {
        self.pending = None;
        self.state = end;
        self.done += 1;
        self.next_column += 1;
        if self.next_column >= self.spec.omega_points {
            self.finish_row();
        }
        c
    }

    fn finish_row(&mut self) {
        self.pending = None;
        self.next_row += 1;
        self.next_column = 0;
        self.model = None;
        self.state = None;
    }
}

/// Sorts cells row by row, then by column (the order of an unsharded map).
pub fn canonical_cells(cells: &mut [MapCell]) {
    cells.sort_by_key(|c| (c.row, c.column));
}
