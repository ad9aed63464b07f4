//! The largest Lyapunov exponent over Omega (under `ViewId::Bif`): one chain of
//! Benettin runs over its share of the Omega grid, each continued from the
//! previous end state and computed in slices ([`LyapunovRun`]).

use super::chain::{Chain, ChainJob, ChainKind};
use super::failed;
use figures::protocol::{FromWorker, JobId, LyapSample};
use solver::lyapunov::{LyapunovOptions, LyapunovRun};
use solver::model::Model;

/// Benettin runs of `periods` after `transient_periods`.
pub(crate) struct Lyap {
    transient_periods: u32,
    periods: u32,
}

/// Starts chain `shard` of `chains` over `points` equally spaced Omegas.
pub(crate) fn start(
    id: JobId,
    model: Model,
    (omega_from, omega_to, points): (f64, f64, u32),
    (chains, shard): (u32, u32),
    (transient_periods, periods): (u32, u32),
) -> Result<(ChainJob<Lyap>, Vec<FromWorker>), FromWorker> {
    if points < 2 || omega_to.partial_cmp(&omega_from) != Some(std::cmp::Ordering::Greater) {
        return Err(failed(
            id,
            "Lyapunov: at least 2 points over an increasing Omega range",
        ));
    }
    let step = (omega_to - omega_from) / f64::from(points - 1);
    let chain = Chain::new(points, (chains, shard), |i| {
        omega_from + step * f64::from(i)
    });
    let kind = Lyap {
        transient_periods,
        periods,
    };
    Ok(ChainJob::start(id, model, chain, kind))
}

impl ChainKind for Lyap {
    type Sample = LyapSample;
    type Run = LyapunovRun;
    const PROGRESS: bool = false;

    fn start(
        &self,
        model: &Model,
        from: Option<&[f64]>,
        (_, omega): (u32, f64),
    ) -> solver::Result<LyapunovRun> {
        let mut opts = LyapunovOptions::new(omega);
        opts.transient_periods = self.transient_periods;
        opts.periods = self.periods;
        LyapunovRun::new(model, &opts, from)
    }

    fn advance(
        &self,
        model: &Model,
        run: &mut LyapunovRun,
        (index, omega): (u32, f64),
        max_steps: u64,
    ) -> solver::Result<Option<(LyapSample, Vec<f64>)>> {
        let Some(l) = run.advance(model, max_steps)? else {
            return Ok(None);
        };
        let sample = LyapSample {
            index,
            omega,
            per_period: Some(l.per_period),
            per_s: Some(l.per_s),
            error: None,
        };
        Ok(Some((sample, l.end_state)))
    }

    fn failed((index, omega): (u32, f64), error: String) -> LyapSample {
        LyapSample {
            index,
            omega,
            per_period: None,
            per_s: None,
            error: Some(error),
        }
    }

    fn message(id: JobId, points: Vec<LyapSample>) -> FromWorker {
        FromWorker::LyapPoints { id, points }
    }
}
