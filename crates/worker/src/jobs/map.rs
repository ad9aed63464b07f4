//! The impact-regime map (`ViewId::Map`): one worker's share of the rows, a slice
//! of one cell's steady state per step.

use super::{failed, Job, SLICE_STEPS};
use figures::protocol::{FromWorker, JobId, MapSample};
use solver::map::{MapSpec, RegimeMap};
use solver::params::ModelParams;

/// A share of an impact-regime map in progress.
pub(crate) struct MapJob {
    id: JobId,
    map: RegimeMap,
}

impl MapJob {
    /// Starts the share of `params`' map that `spec` names.
    pub(crate) fn start(
        id: JobId,
        params: &ModelParams,
        spec: MapSpec,
    ) -> Result<(Self, Vec<FromWorker>), FromWorker> {
        match RegimeMap::new(params, spec) {
            Ok(map) => {
                let job = MapJob { id, map };
                let out = vec![job.progress_message()];
                Ok((job, out))
            }
            Err(e) => Err(failed(id, e.to_string())),
        }
    }
}

impl Job for MapJob {
    fn id(&self) -> JobId {
        self.id
    }

    fn step(&mut self) -> Vec<FromWorker> {
        let mut out = Vec::new();
        let cells: Vec<MapSample> = self
            .map
            .advance_steps(SLICE_STEPS)
            .into_iter()
            .map(MapSample::from)
            .collect();
        if !cells.is_empty() {
            out.push(FromWorker::MapCells { id: self.id, cells });
        }
        if self.map.is_finished() {
            out.push(FromWorker::Done { id: self.id });
        }
        out
    }

    fn finished(&self) -> bool {
        self.map.is_finished()
    }

    fn progress(&self) -> (usize, usize) {
        (self.map.done(), self.map.total())
    }
}
