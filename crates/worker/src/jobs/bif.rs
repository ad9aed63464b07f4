//! The bifurcation sweep (`ViewId::Bif`): one worker's shard of the sweep's
//! chains, a slice of a steady state per step, kept when finished for the CLI JSON
//! export; shard 0 first sends the parametric-instability bands of the range,
//! in its first step unless the last ones stand (not at its start, so the
//! worker's selected-Omega job, served first, is not kept waiting for them).

use super::{excitation_at, failed, Job, SLICE_STEPS};
use figures::protocol::um;
use figures::protocol::{BifMesh, BifSample, FromWorker, JobId, RunOptions};
use serde_json::Value;
use solver::keys;
use solver::model::Model;
use solver::parametric::Parametric;
use solver::params::ModelParams;
use solver::sweep::{canonical_order, BifurcationSweep, Directions, SweepPoint, SweepSpec};
use std::cell::RefCell;
use std::rc::Rc;

/// Omega samples of the parametric-instability scan over the sweep's range
/// (a band narrower than the spacing can slip between them).
pub const BAND_SAMPLES: u32 = 300;

/// A bifurcation shard in progress (or finished, kept for export).
pub(crate) struct BifJob {
    id: JobId,
    params: ModelParams,
    sweep: BifurcationSweep,
    points: Vec<SweepPoint>,
    /// Shard 0's instability bands still to compute, the worker's cache
    /// and the range, in its first step.
    bands_due: Option<(SharedBands, (f64, f64))>,
}

/// The worker's bands cache, shared with the shard that computes them.
pub(crate) type SharedBands = Rc<RefCell<BandsCache>>;

/// What a bifurcation job's sweep covers.
pub(crate) struct BifSpec<'a> {
    /// Omega range and points.
    pub(crate) grid: (f64, f64, u32),
    /// `up`, `down` or `both`.
    pub(crate) directions: &'a str,
    /// Chains in all and this shard's.
    pub(crate) chains: (u32, u32),
    /// Periods per steady state.
    pub(crate) run: RunOptions,
}

/// The last parametric-instability bands and what they depend on (the
/// parameters without backlash and TE, the Omega range): a backlash or TE
/// drag restarts the sweep but not the scan.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct BandsCache {
    last: Option<CachedBands>,
}

/// Bands, the parameters (without backlash and TE) and the range they are of.
type CachedBands = (ModelParams, (f64, f64), Vec<(f64, f64)>);

impl BandsCache {
    /// The cached bands of `params` over `range`, if only the backlash or
    /// the TE changed since they were computed; the cache's key.
    fn cached(
        &self,
        params: &ModelParams,
        range: (f64, f64),
    ) -> (Option<Vec<(f64, f64)>>, ModelParams) {
        let mut key = params.clone();
        // Both models have these keys; should one ever be refused, the key
        // keeps its value and the cache only hits less often.
        let neutral = keys::set(&mut key, "backlash_um", keys::Value::Num(0.0))
            .and_then(|()| keys::set(&mut key, "te_um", keys::Value::Num(0.0)))
            .is_ok();
        let hit = self
            .last
            .as_ref()
            .filter(|(p, r, _)| neutral && *p == key && *r == range)
            .map(|(_, _, bands)| bands.clone());
        (hit, key)
    }

    /// The instability bands of `model` over `range`, from the cache when
    /// only the backlash or the TE changed.
    fn bands(
        &mut self,
        params: &ModelParams,
        model: &Model,
        range: (f64, f64),
    ) -> Result<Vec<(f64, f64)>, solver::SolverError> {
        let (hit, key) = self.cached(params, range);
        if let Some(bands) = hit {
            return Ok(bands);
        }
        let bands = Parametric::new(model).and_then(|p| p.unstable_bands(range, BAND_SAMPLES))?;
        self.last = Some((key, range, bands.clone()));
        Ok(bands)
    }
}

impl BifJob {
    /// Starts the shard that `spec` names (shard 0 first sends the bands).
    pub(crate) fn start(
        id: JobId,
        params: ModelParams,
        model: Model,
        spec: BifSpec<'_>,
        bands: &SharedBands,
    ) -> Result<(Self, Vec<FromWorker>), FromWorker> {
        let BifSpec {
            grid: (omega_from, omega_to, points),
            directions,
            chains: (chains, shard),
            run,
        } = spec;
        let mut spec = SweepSpec::new(omega_from, omega_to, points);
        spec.chains = chains;
        spec.shard = Some(shard);
        spec.directions = match Directions::from_name(directions) {
            Some(d) => d,
            None => return Err(failed(id, "directions: allowed up, down, both")),
        };
        spec.steady.transient_periods = run.transient_periods;
        spec.steady.record_periods = run.record_periods;
        spec.meshes = (0..model.system.meshes.len()).collect();
        // Shard 0 also sends the instability bands of the range: at once
        // if they stand, else in its first step.
        let range = (omega_from, omega_to);
        let (hit, _) = bands.borrow().cached(&params, range);
        let (ready, bands_due) = match (shard, hit) {
            (0, Some(b)) => (Some(bands_message(id, Ok(b))), None),
            (0, None) => (None, Some((Rc::clone(bands), range))),
            _ => (None, None),
        };
        match BifurcationSweep::new(model, spec) {
            Ok(sweep) => {
                let job = BifJob {
                    id,
                    params,
                    sweep,
                    points: Vec::new(),
                    bands_due,
                };
                let out = ready.into_iter().chain([job.progress_message()]).collect();
                Ok((job, out))
            }
            Err(e) => Err(failed(id, e.to_string())),
        }
    }

    /// The finished sweep as `gearshock bifurcation` JSON, for mesh `mesh`
    /// (all when `None`), merged with the other shards' JSON `other`.
    fn export_json(&self, mesh: Option<usize>, other: &[String]) -> FromWorker {
        let (id, job) = (self.id, self);
        let mut spec = job.sweep.spec().clone();
        let model = job.sweep.model();
        let mut points = job.points.clone();
        if let Some(j) = mesh {
            if j >= model.system.meshes.len() {
                return failed(id, format!("no mesh {j}"));
            }
            spec.meshes = vec![j];
            for p in &mut points {
                p.meshes.retain(|m| m.mesh == j);
            }
        }
        canonical_order(&mut points);
        let mine = report::sweep_json(model, &job.params, &spec, &points);
        if other.is_empty() {
            return FromWorker::Export {
                id,
                text: mine.to_string(),
            };
        }
        let mut shards = vec![mine];
        for text in other {
            match serde_json::from_str::<Value>(text) {
                Ok(v) => shards.push(v),
                Err(e) => return failed(id, format!("cannot read the other shard: {e}")),
            }
        }
        match report::merge_shards(&shards) {
            Ok(v) => FromWorker::Export {
                id,
                text: v.to_string(),
            },
            Err(e) => failed(id, e.to_string()),
        }
    }
}

impl Job for BifJob {
    fn id(&self) -> JobId {
        self.id
    }

    fn step(&mut self) -> Vec<FromWorker> {
        if let Some((cache, range)) = self.bands_due.take() {
            let bands = cache
                .borrow_mut()
                .bands(&self.params, self.sweep.model(), range);
            return vec![bands_message(self.id, bands)];
        }
        let mut out = Vec::new();
        // A slice of the next point's steady state: a newer job waits at
        // most SLICE_STEPS integrator steps.
        let pts: Vec<SweepPoint> = self.sweep.advance_steps(SLICE_STEPS).into_iter().collect();
        let samples: Vec<BifSample> = pts.iter().map(|p| bif_sample(&self.sweep, p)).collect();
        self.points.extend(pts);
        if samples.is_empty() {
            // Paused inside a steady state: nothing to say yet.
            return out;
        }
        out.push(FromWorker::BifPoints {
            id: self.id,
            points: samples,
        });
        out.push(self.progress_message());
        if self.sweep.is_finished() {
            out.push(FromWorker::Done { id: self.id });
        }
        out
    }

    fn finished(&self) -> bool {
        self.sweep.is_finished()
    }

    fn progress(&self) -> (usize, usize) {
        (self.sweep.done(), self.sweep.total())
    }

    fn export(&self, mesh: Option<usize>, other: &[String]) -> Option<FromWorker> {
        Some(self.export_json(mesh, other))
    }

    fn exports(&self) -> bool {
        true
    }
}

fn bif_sample(sweep: &BifurcationSweep, p: &SweepPoint) -> BifSample {
    let model = sweep.model();
    let omega_rad_s = p.omega * model.system.omega_ref_rad_s;
    BifSample {
        index: p.index,
        omega: p.omega,
        up: p.direction == solver::sweep::Direction::Up,
        meshes: p
            .meshes
            .iter()
            .map(|m| {
                let (e0, _) = excitation_at(model, m.mesh, omega_rad_s, 0.0);
                BifMesh {
                    x_um: m.poincare_delta_m.iter().map(|d| um(d - e0)).collect(),
                    rel_min_um: um(m.rel_min_m),
                    rel_max_um: um(m.rel_max_m),
                    regime: m.impact.into(),
                    dynamic_factor: m.dynamic_factor,
                }
            })
            .collect(),
        worst_mesh: p.worst_mesh,
        period: p.period,
        motion: p.motion,
        error: p.error.clone(),
    }
}

/// The bands' message: the bands, or why they could not be computed.
fn bands_message(id: JobId, bands: Result<Vec<(f64, f64)>, solver::SolverError>) -> FromWorker {
    match bands {
        Ok(bands) => FromWorker::Bands {
            id,
            bands,
            error: None,
        },
        Err(e) => FromWorker::Bands {
            id,
            bands: Vec::new(),
            error: Some(e.to_string()),
        },
    }
}
