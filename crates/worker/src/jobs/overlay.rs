//! The time-integration overlay of the frequency response (`ViewId::Fr`): one
//! continuation chain of steady states over its share of the Omega grid,
//! each computed in slices ([`SteadyRun`]).

use super::chain::{Chain, ChainJob, ChainKind};
use super::failed;
use figures::protocol::um;
use figures::protocol::{FrSample, FromWorker, JobId, MeshExtremes, RunOptions};
use solver::model::Model;
use solver::steady::{SteadyOptions, SteadyRun};
use solver::sweep::SweepSpec;

/// Steady states for the overlay, `run` periods each.
pub(crate) struct Overlay {
    run: RunOptions,
}

/// Starts chain `shard` of `chains` over `points` Omegas of the range
/// (spaced as the solver's sweeps space them).
pub(crate) fn start(
    id: JobId,
    model: Model,
    (omega_from, omega_to, points): (f64, f64, u32),
    (chains, shard): (u32, u32),
    run: RunOptions,
) -> Result<(ChainJob<Overlay>, Vec<FromWorker>), FromWorker> {
    let mut spec = SweepSpec::new(omega_from, omega_to, points);
    spec.chains = chains;
    spec.shard = Some(shard);
    spec.steady.transient_periods = run.transient_periods;
    spec.steady.record_periods = run.record_periods;
    if let Err(e) = spec.validate(model.system.meshes.len()) {
        return Err(failed(id, e.to_string()));
    }
    let chain = Chain::new(points, (chains, shard), |i| spec.omega(i));
    Ok(ChainJob::start(id, model, chain, Overlay { run }))
}

impl ChainKind for Overlay {
    type Sample = FrSample;
    type Run = SteadyRun;
    const PROGRESS: bool = true;

    fn start(
        &self,
        model: &Model,
        from: Option<&[f64]>,
        (_, omega): (u32, f64),
    ) -> solver::Result<SteadyRun> {
        let mut opts = SteadyOptions::new(omega);
        opts.transient_periods = self.run.transient_periods;
        opts.record_periods = self.run.record_periods;
        opts.samples_per_period = 0;
        SteadyRun::new(model, &opts, from)
    }

    fn advance(
        &self,
        model: &Model,
        run: &mut SteadyRun,
        (index, omega): (u32, f64),
        max_steps: u64,
    ) -> solver::Result<Option<(FrSample, Vec<f64>)>> {
        let Some(ss) = run.advance(model, max_steps)? else {
            return Ok(None);
        };
        let meshes = ss
            .meshes
            .iter()
            .map(|m| MeshExtremes {
                rel_min_um: um(m.rel_min_m),
                rel_max_um: um(m.rel_max_m),
                regime: m.impact.into(),
                dynamic_factor: m.dynamic_factor,
            })
            .collect();
        let sample = FrSample {
            index,
            omega,
            meshes,
            period: ss.period,
            error: None,
        };
        Ok(Some((sample, ss.end_state)))
    }

    fn failed((index, omega): (u32, f64), error: String) -> FrSample {
        FrSample {
            index,
            omega,
            meshes: Vec::new(),
            period: None,
            error: Some(error),
        }
    }

    fn message(id: JobId, points: Vec<FrSample>) -> FromWorker {
        FromWorker::OverlayPoints { id, points }
    }
}
