//! The one loop every sweep command runs: bounded work per call, progress
//! after each call, each result streamed as a JSON line (`--format jsonl`)
//! or kept for the document written at the end.

use crate::args::{Format, ParamArgs};
use crate::failure::Failure;
use crate::output::emit_line;
use crate::progress::Progress;
use serde_json::Value;
use solver::map::RegimeMap;
use solver::sweep::{BifurcationSweep, SweepPoint};

/// A computation that advances by bounded steps (the solver's sweeps, a
/// continuation, a list of points).
pub trait Sweep {
    /// One result (a point, a cell).
    type Item;
    /// How many units the progress counts in all.
    fn total(&self) -> usize;
    /// How many units are done.
    fn done(&self) -> usize;
    /// Whether every result has been returned.
    fn is_finished(&self) -> bool;
    /// Computes the next few results.
    fn advance(&mut self) -> Result<Vec<Self::Item>, Failure>;
}

/// How a sweep's results are streamed with `--format jsonl`.
pub struct Lines<'a, T> {
    /// The first line: model, parameters and spec.
    pub header: Value,
    /// One result's line.
    pub line: &'a dyn Fn(&T) -> Value,
    /// What the closing line `{"complete": true, COUNT: n}` counts.
    pub count: &'static str,
}

/// Runs `sweep` to its end, with progress in `unit`s (`--progress`).
/// Streamed (`lines` given and `--format jsonl`): the header, a line per
/// result and the closing line are written, and `None` is returned;
/// otherwise every result, in the order computed.
pub fn run<S: Sweep>(
    sweep: &mut S,
    p: &ParamArgs,
    unit: &'static str,
    lines: Option<Lines<'_, S::Item>>,
) -> Result<Option<Vec<S::Item>>, Failure> {
    let mut bar = Progress::new(sweep.total(), unit, p.progress);
    let lines = lines.filter(|_| p.format == Format::Jsonl);
    if let Some(l) = &lines {
        emit_line(&l.header)?;
    }
    // A first line at once (after the header, so a reader already gone
    // hears nothing): a log shows the run started, however long its first
    // item takes.
    bar.update(0);
    let mut kept = Vec::new();
    let mut streamed = 0usize;
    while !sweep.is_finished() {
        for item in sweep.advance()? {
            match &lines {
                Some(l) => {
                    emit_line(&(l.line)(&item))?;
                    streamed += 1;
                }
                None => kept.push(item),
            }
        }
        bar.update(sweep.done());
    }
    bar.finish();
    match lines {
        Some(l) => {
            emit_line(&serde_json::json!({ "complete": true, l.count: streamed }))?;
            Ok(None)
        }
        None => Ok(Some(kept)),
    }
}

impl Sweep for BifurcationSweep {
    type Item = SweepPoint;
    fn total(&self) -> usize {
        BifurcationSweep::total(self)
    }
    fn done(&self) -> usize {
        BifurcationSweep::done(self)
    }
    fn is_finished(&self) -> bool {
        BifurcationSweep::is_finished(self)
    }
    fn advance(&mut self) -> Result<Vec<SweepPoint>, Failure> {
        Ok(BifurcationSweep::advance(self, 1))
    }
}

impl Sweep for RegimeMap {
    type Item = solver::map::MapCell;
    fn total(&self) -> usize {
        RegimeMap::total(self)
    }
    fn done(&self) -> usize {
        RegimeMap::done(self)
    }
    fn is_finished(&self) -> bool {
        RegimeMap::is_finished(self)
    }
    fn advance(&mut self) -> Result<Vec<Self::Item>, Failure> {
        Ok(RegimeMap::advance(self, 1))
    }
}

/// A list of Omegas computed one by one with `f`.
pub struct Points<F> {
    omegas: Vec<f64>,
    next: usize,
    f: F,
}

impl<F> Points<F> {
    /// Computes `f(omega)` for each of `omegas` in turn.
    pub fn new(omegas: Vec<f64>, f: F) -> Self {
        Points { omegas, next: 0, f }
    }
}

impl<T, F: FnMut(f64) -> Result<T, Failure>> Sweep for Points<F> {
    type Item = T;
    fn total(&self) -> usize {
        self.omegas.len()
    }
    fn done(&self) -> usize {
        self.next
    }
    fn is_finished(&self) -> bool {
        self.next >= self.omegas.len()
    }
    fn advance(&mut self) -> Result<Vec<T>, Failure> {
        let item = (self.f)(self.omegas[self.next])?;
        self.next += 1;
        Ok(vec![item])
    }
}
