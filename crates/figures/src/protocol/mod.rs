//! The messages between the page and its Web Workers, carried as JSON text.
//!
//! Protocol. A worker posts [`FromWorker::Ready`] once its wasm has loaded;
//! the page queues jobs until then (messages posted earlier would be lost).
//! Every job carries an id and a [`Target`]: the computation it belongs to
//! (the current state, the pinned A, a family member). A worker holds at
//! most one job of each [`JobKind`] per target (further `Run` messages with
//! the same id are more shards of it): a newer job of a kind replaces
//! (cancels) the older one, and the page ignores replies whose id is not
//! the current one of that kind. Workers
//! compute in bounded chunks (a slice of a steady state, one steady state or
//! map cell) and yield to their event loop between chunks, so a newer job or
//! a cancel arrives within one chunk. Bifurcation sweeps, the Lyapunov curve
//! and the time-integration overlay of the frequency response are split into
//! interleaved continuation chains (`chains` fixed by the points, one
//! message per `shard`, dealt over the pool); the merged result equals an
//! unsharded run with as many chains. The harmonic-balance branch
//! ([`JobSpec::HarmonicBalance`]) is one continuation on one worker, advanced a few
//! points per chunk.
//!
//! These are the serializable DTOs of the boundary; solver types stay inside
//! the worker, but for the few that serialize as they are ([`Motion`],
//! `Impact`).

use serde::{Deserialize, Serialize};
use serde_json::{Map, Value};
use solver::steady::Impact;

/// Identifies one job; increases monotonically on the page.
pub type JobId = u64;

mod boundaries;
mod kinds;
mod orbits;
mod orders;
mod sharing;
pub use boundaries::{BoundaryCurve, BoundaryKind, BoundaryPoint};
pub use kinds::{JobKind, KindSet, Target};
pub use orbits::OrbitSample;
pub use orders::{ForceByOrder, OrderPeak, PlanetSumOrders};
pub use sharing::KindSharing;
/// The solver's verdict on a steady state, sent as it is (one definition:
/// the page's words about the motion are all built from it in `crate::story`).
pub use solver::steady::Motion;

/// Transient and recorded mesh periods of each steady state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct RunOptions {
    /// Maximum transient periods (the transient ends early once settled).
    pub transient_periods: u32,
    /// Recorded periods.
    pub record_periods: u32,
}

/// The selected-Omega run: one steady state with the time history of one
/// mesh. The worker's job, the page's preview and the CLI's figures run
/// this one spec.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct OmegaSpec {
    /// Dimensionless mesh frequency.
    pub omega: f64,
    /// Mesh index, or `None` for the worst mesh (largest dynamic factor).
    pub mesh: Option<usize>,
    /// Periods.
    pub run: RunOptions,
    /// Uniform samples per mesh period of the history.
    pub samples_per_period: u32,
    /// Highest mesh order of the spectrum.
    pub max_order: f64,
}

/// What a job computes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum JobSpec {
    /// One steady state with the time history of one mesh.
    Omega(OmegaSpec),
    /// The harmonic-balance frequency response (`solver::hbm`): one
    /// pseudo-arclength continuation upward from `omega_from`, with Floquet
    /// stability and bifurcation labels.
    HarmonicBalance {
        /// Start of the Omega range.
        omega_from: f64,
        /// End of the Omega range.
        omega_to: f64,
        /// Nominal points (the largest arclength step is range / points).
        points: u32,
        /// Harmonics H (exact method).
        harmonics: u32,
        /// Compute Floquet stability at every point.
        stability: bool,
    },
    /// Steady-state extremes of every mesh over an Omega grid (upward
    /// continuation along interleaved chains; this worker does `shard`): the
    /// time-integration overlay of the frequency response.
    Overlay {
        /// First grid Omega.
        omega_from: f64,
        /// Last grid Omega.
        omega_to: f64,
        /// Grid points.
        points: u32,
        /// Interleaved chains.
        chains: u32,
        /// The chain this worker computes.
        shard: u32,
        /// Periods.
        run: RunOptions,
    },
    /// One shard of a bifurcation sweep (`solver::sweep`), all meshes recorded.
    Bif {
        /// First grid Omega.
        omega_from: f64,
        /// Last grid Omega.
        omega_to: f64,
        /// Grid points.
        points: u32,
        /// `up`, `down` or `both`.
        directions: String,
        /// Interleaved chains.
        chains: u32,
        /// The chain this worker computes.
        shard: u32,
        /// Periods.
        run: RunOptions,
    },
    /// Rows `shard, shard + shards, ...` of an impact-regime map
    /// (`solver::map`): each row sweeps Omega upward at one value of `key`.
    Map {
        /// The rows' key (`backlash_um` or `te_um`).
        key: String,
        /// First Omega (column 0).
        omega_from: f64,
        /// Last Omega.
        omega_to: f64,
        /// Columns.
        omega_points: u32,
        /// The key's value on row 0.
        value_from: f64,
        /// Its value on the last row.
        value_to: f64,
        /// Rows.
        value_points: u32,
        /// Mesh whose regime is mapped, or `None` for the most severe of all meshes.
        mesh: Option<usize>,
        /// The workers sharing the rows.
        shards: u32,
        /// This worker's share.
        shard: u32,
        /// Periods per cell.
        run: RunOptions,
    },
    /// One chain of the largest Lyapunov exponent of the Poincaré map over
    /// an Omega grid (`solver::lyapunov`), upward, each point starting from
    /// the previous point's end state.
    Lyap {
        /// First grid Omega.
        omega_from: f64,
        /// Last grid Omega.
        omega_to: f64,
        /// Grid points.
        points: u32,
        /// Interleaved chains.
        chains: u32,
        /// The chain this worker computes.
        shard: u32,
        /// Transient periods before measuring.
        transient_periods: u32,
        /// Periods averaged over.
        periods: u32,
    },
    /// The periodic orbits' branches by shooting continuation
    /// (`solver::orbits`) over the range, period doublings followed: drawn
    /// on the bifurcation diagram.
    Orbits {
        /// Start of the Omega range.
        omega_from: f64,
        /// End of the Omega range.
        omega_to: f64,
        /// Resolution (the largest step is range / points).
        points: u32,
    },
    /// The map's boundaries as curves in Omega and `key` (`solver::boundaries`).
    Boundaries {
        /// The map's key.
        key: String,
        /// Start of the Omega range.
        omega_from: f64,
        /// End of the Omega range.
        omega_to: f64,
        /// The key's lowest value.
        value_from: f64,
        /// Its highest value.
        value_to: f64,
        /// Values of the key whose one-parameter branches seed the curves.
        levels: u32,
        /// Resolution (a curve's step moves at most 1 / points of the box).
        points: u32,
        /// Harmonics H.
        harmonics: usize,
        /// The map's mesh, whose contact boundaries are traced (`None`: all).
        #[serde(default)]
        contact_mesh: Option<usize>,
    },
}

/// A message from the page to a worker.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum ToWorker {
    /// Start a job of `target`'s computation, replacing that computation's
    /// job of the same kind (a further shard of the same id joins it).
    Run {
        /// Whose job it is.
        target: Target,
        /// Job id.
        id: JobId,
        /// The parameter set as the flat key object of `solver::keys::to_json`.
        params: Map<String, Value>,
        /// What to compute.
        job: JobSpec,
    },
    /// Drop `target`'s job of a kind (or all its jobs).
    Cancel {
        /// Whose job.
        target: Target,
        /// Which kind, or every kind.
        kind: Option<JobKind>,
    },
    /// The finished bifurcation shard as the CLI's JSON (`gearshock
    /// bifurcation`), restricted to one mesh (or all meshes if `None`). With
    /// `other`, the other shard's JSON text is merged in (`report::merge_shards`).
    ExportBif {
        /// The sweep's job id.
        id: JobId,
        /// Mesh index, or all meshes.
        mesh: Option<usize>,
        /// The other shards' JSON texts to merge with this one.
        other: Vec<String>,
    },
}

/// Impact regime of a steady response, as the page shows it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Regime {
    /// The drive flanks never separate.
    NoImpact,
    /// They separate, but the back flanks never touch.
    SingleSided,
    /// The back flanks touch.
    DoubleSided,
    /// The teeth never touch.
    NoContact,
    /// No backlash: no gap to cross, the mesh a linear spring.
    NoGap,
}

impl Regime {
    /// All regimes, mildest first.
    pub const ALL: [Regime; 5] = [
        Regime::NoGap,
        Regime::NoImpact,
        Regime::SingleSided,
        Regime::DoubleSided,
        Regime::NoContact,
    ];

    /// Words for legends and the summary.
    pub fn label(self) -> &'static str {
        Impact::from(self).words()
    }

    /// The solver's name (as in the CLI's JSON).
    pub fn solver_name(self) -> &'static str {
        Impact::from(self).name()
    }
}

impl From<Impact> for Regime {
    fn from(i: Impact) -> Self {
        match i {
            Impact::None => Regime::NoImpact,
            Impact::SingleSided => Regime::SingleSided,
            Impact::DoubleSided => Regime::DoubleSided,
            Impact::NoContact => Regime::NoContact,
            Impact::NoGap => Regime::NoGap,
        }
    }
}

impl From<Regime> for Impact {
    fn from(r: Regime) -> Self {
        match r {
            Regime::NoImpact => Impact::None,
            Regime::SingleSided => Impact::SingleSided,
            Regime::DoubleSided => Impact::DoubleSided,
            Regime::NoContact => Impact::NoContact,
            Regime::NoGap => Impact::NoGap,
        }
    }
}

/// One mesh's steady-state extremes at one Omega.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshExtremes {
    /// Smallest relative displacement x = delta - e (um).
    pub rel_min_um: f64,
    /// Largest relative displacement (um).
    pub rel_max_um: f64,
    /// Impact regime.
    pub regime: Regime,
    /// max F / F_static.
    pub dynamic_factor: Option<f64>,
}

/// One computed point of the time-integration overlay grid of the frequency response.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FrSample {
    /// Grid index.
    pub index: u32,
    /// Dimensionless frequency.
    pub omega: f64,
    /// Every mesh, in the model's order (empty if the point failed).
    pub meshes: Vec<MeshExtremes>,
    /// Period of the Poincaré orbit in mesh periods, if periodic.
    pub period: Option<u32>,
    /// Why the point failed.
    pub error: Option<String>,
}

/// A bifurcation detected on a harmonic-balance branch (between the
/// previous point and this one).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BranchBif {
    /// The branch turns back in Omega (a jump in a sweep).
    Fold,
    /// A real Floquet multiplier crosses -1.
    PeriodDoubling,
    /// A complex pair of multipliers crosses the unit circle.
    NeimarkSacker,
    /// A real multiplier crosses +1 without a turn.
    BranchPoint,
}

impl From<solver::hbm::Bifurcation> for BranchBif {
    fn from(b: solver::hbm::Bifurcation) -> Self {
        use solver::hbm::Bifurcation as B;
        match b {
            B::Fold => BranchBif::Fold,
            B::PeriodDoubling => BranchBif::PeriodDoubling,
            B::NeimarkSacker => BranchBif::NeimarkSacker,
            B::BranchPoint => BranchBif::BranchPoint,
        }
    }
}

/// One mesh on a harmonic-balance branch point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HbmMesh {
    /// Smallest x = delta - e over the period (um).
    pub rel_min_um: f64,
    /// Largest x (um).
    pub rel_max_um: f64,
    /// Contact regime of the reconstructed orbit.
    pub regime: Regime,
}

/// One point of a harmonic-balance branch.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HbmSample {
    /// Dimensionless frequency.
    pub omega: f64,
    /// Every mesh, in the model's order.
    pub meshes: Vec<HbmMesh>,
    /// Floquet stability, `None` if not computed.
    pub stable: Option<bool>,
    /// A bifurcation between the previous point and this one.
    pub bifurcation: Option<BranchBif>,
    /// The piece of the branch (0, then one more after each automatic
    /// restart of the continuation): the curve is broken between pieces.
    #[serde(default)]
    pub piece: u32,
}

/// One mesh's Poincaré samples at a swept point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BifMesh {
    /// Poincaré samples of x = delta - e (um), one per recorded period.
    pub x_um: Vec<f64>,
    /// Smallest x = delta - e over the recorded periods (um): the sweep's
    /// steady state doubles as a time-integration point of the frequency response.
    #[serde(default)]
    pub rel_min_um: f64,
    /// Largest x over the recorded periods (um).
    #[serde(default)]
    pub rel_max_um: f64,
    /// Impact regime.
    pub regime: Regime,
    /// max F / F_static over the recorded periods.
    #[serde(default)]
    pub dynamic_factor: Option<f64>,
}

/// One computed point of a bifurcation sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BifSample {
    /// Grid index.
    pub index: u32,
    /// Dimensionless frequency.
    pub omega: f64,
    /// Swept upwards (else downwards).
    pub up: bool,
    /// Every mesh, in the model's order (empty if the point failed).
    pub meshes: Vec<BifMesh>,
    /// The mesh with the largest dynamic factor.
    pub worst_mesh: usize,
    /// Period of the Poincaré orbit, if periodic.
    pub period: Option<u32>,
    /// The classification of the point's steady state.
    #[serde(default)]
    pub motion: Motion,
    /// Why the point failed.
    pub error: Option<String>,
}

/// One cell of an impact-regime map.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MapSample {
    /// Row (index of the key's value).
    pub row: u32,
    /// Column (index of Omega).
    pub column: u32,
    /// Dimensionless frequency.
    pub omega: f64,
    /// The key's value (um).
    pub value: f64,
    /// Impact regime.
    pub regime: Regime,
    /// Period in mesh periods, if periodic.
    pub period: Option<u32>,
    /// Why the cell failed.
    pub error: Option<String>,
}

impl From<solver::map::MapCell> for MapSample {
    fn from(c: solver::map::MapCell) -> Self {
        MapSample {
            row: c.row,
            column: c.column,
            omega: c.omega,
            value: c.value,
            regime: c.impact.into(),
            period: c.period,
            error: c.error,
        }
    }
}

/// One point of the Lyapunov-exponent curve.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LyapSample {
    /// Grid index.
    pub index: u32,
    /// Dimensionless frequency.
    pub omega: f64,
    /// Largest exponent of the Poincaré map per mesh period (`None` if failed).
    pub per_period: Option<f64>,
    /// The same per second (1/s).
    pub per_s: Option<f64>,
    /// Why the point failed.
    pub error: Option<String>,
}

/// Summary of one mesh at the selected Omega.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshSummary {
    /// Mesh name.
    pub name: String,
    /// Impact regime.
    pub regime: Regime,
    /// max F / F_static.
    pub dynamic_factor: Option<f64>,
}

/// Every mesh's history over the window the time-history view shows, for
/// the animated gear set.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct AnimHistory {
    /// The window's first sample, as an index into [`OmegaResult::x_um`].
    pub start_sample: u32,
    /// x = delta - e (um) of every mesh over the window, `[mesh][sample]`.
    pub x_um: Vec<Vec<f64>>,
    /// Every mesh's backlash half-width (um).
    pub backlash_um: Vec<f64>,
}

/// Periods shown in the time history.
pub const HISTORY_PERIODS: u32 = 12;

/// The first sample of the window the time history shows (the last
/// [`HISTORY_PERIODS`] recorded periods) in a record of `len` samples: the
/// time-history view and the gear-set animation both start there.
pub fn history_start(len: usize, samples_per_period: u32, record_periods: u32) -> usize {
    let shown = HISTORY_PERIODS.min(record_periods) as usize;
    len.saturating_sub(shown * samples_per_period.max(1) as usize)
}

/// The steady state at the selected Omega, for the selected-Omega views (`ViewId::Phase`, `Poincare`, `Time`, `Spectrum`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct OmegaResult {
    /// Dimensionless frequency.
    pub omega: f64,
    /// The plotted mesh (resolved if "worst" was asked).
    pub mesh: usize,
    /// Its name.
    pub mesh_name: String,
    /// Its backlash half-width (um).
    pub backlash_um: f64,
    /// Impact regime of the plotted mesh.
    pub regime: Regime,
    /// Period in mesh periods, `None` if not periodic within the record.
    pub period: Option<u32>,
    /// The classification (exact orbit, periodic, still settling, not
    /// periodic): the one source of the page's words about the motion.
    #[serde(default)]
    pub motion: Motion,
    /// Dynamic factor of the plotted mesh.
    pub dynamic_factor: Option<f64>,
    /// Mesh frequency (Hz).
    pub mesh_freq_hz: f64,
    /// Transient periods actually run.
    pub transient_periods_run: u32,
    /// Whether the early-settle test ended the transient.
    pub settled: bool,
    /// Samples per mesh period of the history.
    pub samples_per_period: u32,
    /// Recorded periods.
    pub record_periods: u32,
    /// x = delta - e (um) at uniform samples over the recorded periods
    /// (carried as [`f64_bytes`]: 64 000 of them at 1000 periods).
    #[serde(with = "f64_bytes")]
    pub x_um: Vec<f64>,
    /// dx/dt (m/s) at the same samples.
    #[serde(with = "f64_bytes")]
    pub xdot_m_s: Vec<f64>,
    /// Poincaré samples of x (um).
    pub poincare_x_um: Vec<f64>,
    /// Poincaré samples of dx/dt (m/s).
    pub poincare_xdot_m_s: Vec<f64>,
    /// Spectrum lines (mesh orders).
    pub spectrum_order: Vec<f64>,
    /// Spectrum amplitudes of x (um).
    pub spectrum_um: Vec<f64>,
    /// Every mesh's regime and dynamic factor.
    pub all_meshes: Vec<MeshSummary>,
    /// Every mesh's history over the shown window (the animation).
    #[serde(default)]
    pub anim: AnimHistory,
    /// How the planets share the load, per mesh kind (none: the gear pair).
    #[serde(default)]
    pub load_sharing: Vec<KindSharing>,
    /// The plotted mesh's force by order (none where the run kept no
    /// history of it).
    #[serde(default)]
    pub force_orders: Option<ForceByOrder>,
    /// Integrator steps taken.
    pub steps: u64,
    /// `gearshock simulate` JSON of this run (the CLI's format); empty for
    /// a preview.
    pub cli_json: String,
    /// A preview: a short run continued from the previous result's end
    /// state, shown while the full steady state computes.
    #[serde(default)]
    pub preview: bool,
    /// The state at the end of the run (generalized coordinates and rates),
    /// where the next preview starts.
    #[serde(default)]
    pub end_state: Vec<f64>,
}

/// A message from a worker to the page.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum FromWorker {
    /// The worker's wasm is loaded; jobs may be posted.
    Ready,
    /// New points of the time-integration overlay of the frequency response.
    OverlayPoints {
        /// Job id.
        id: JobId,
        /// The points.
        points: Vec<FrSample>,
    },
    /// New points of the harmonic-balance branch, in continuation order.
    HbmPoints {
        /// Job id.
        id: JobId,
        /// The points.
        points: Vec<HbmSample>,
        /// Fraction of the Omega range covered (0 ..= 1).
        progress: f64,
        /// The branch has ended (left the range, or failed).
        finished: bool,
        /// The solver failure that ended the branch, if it failed: the
        /// points before it stay valid, the branch is partial.
        error: Option<String>,
        /// With the last chunk: what the continuation did to cover the range
        /// (restarts, left-out gaps), in plain sentences.
        #[serde(default)]
        notes: Vec<String>,
    },
    /// The Omega bands of a bifurcation job's range where the set with every
    /// tooth pair in contact is parametrically unstable (sent by shard 0
    /// when the job starts).
    Bands {
        /// The bifurcation job's id.
        id: JobId,
        /// The bands `(from, to)` in Omega (empty when the scan failed).
        bands: Vec<(f64, f64)>,
        /// Why the scan failed, if it did.
        #[serde(default, skip_serializing_if = "Option::is_none")]
        error: Option<String>,
    },
    /// New points of a bifurcation job.
    BifPoints {
        /// Job id.
        id: JobId,
        /// The points.
        points: Vec<BifSample>,
    },
    /// New points of the shooting branches (`JobSpec::Orbits`).
    OrbitPoints {
        /// Job id.
        id: JobId,
        /// The points, in continuation order.
        points: Vec<OrbitSample>,
        /// Every branch has ended (or the budget ran out, or it failed).
        finished: bool,
        /// The failure that ended the continuation, if any: the points
        /// before it stay valid.
        error: Option<String>,
    },
    /// Boundary curves finished since the last message
    /// (`JobSpec::Boundaries`), with every cusp found so far.
    BoundaryCurves {
        /// Job id.
        id: JobId,
        /// The new curves.
        curves: Vec<BoundaryCurve>,
        /// Every cusp so far: `(omega, value)`.
        cusps: Vec<(f64, f64)>,
        /// New plain sentences on what the trace could not do.
        notes: Vec<String>,
        /// Per mille done.
        permille: usize,
        /// Every curve is traced.
        finished: bool,
    },
    /// New cells of a map job.
    MapCells {
        /// Job id.
        id: JobId,
        /// The cells.
        cells: Vec<MapSample>,
    },
    /// New points of a Lyapunov job.
    LyapPoints {
        /// Job id.
        id: JobId,
        /// The points.
        points: Vec<LyapSample>,
    },
    /// The result of an Omega job.
    Omega {
        /// Job id.
        id: JobId,
        /// The steady state.
        result: Box<OmegaResult>,
    },
    /// Work done so far on a job.
    Progress {
        /// Job id.
        id: JobId,
        /// Units done.
        done: usize,
        /// Units in all.
        total: usize,
    },
    /// A job finished.
    Done {
        /// Job id.
        id: JobId,
    },
    /// A job could not run (bad parameters or a solver failure).
    Failed {
        /// Job id (0 if the message itself was unreadable).
        id: JobId,
        /// What went wrong, for the user.
        message: String,
    },
    /// Exported JSON text.
    Export {
        /// The job id it belongs to.
        id: JobId,
        /// The JSON text.
        text: String,
    },
}

/// A length in metres as µm rounded to 1e-6 µm: the deflections and the backlash
/// the page shows and exports (`worker::jobs::omega` scales the spectrum itself).
pub fn um(metres: f64) -> f64 {
    (metres * 1e6 * 1e6).round() / 1e6
}

/// Serializes a message; serialization of these plain types cannot fail,
/// but a failure would still come back as text rather than a panic.
pub fn encode<T: Serialize>(msg: &T) -> String {
    serde_json::to_string(msg).unwrap_or_else(|e| {
        format!("{{\"type\":\"failed\",\"id\":0,\"message\":\"cannot encode a message: {e}\"}}")
    })
}

mod f64_bytes;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_round_trip_as_json() {
        let msgs = vec![
            FromWorker::Ready,
            FromWorker::Progress {
                id: 3,
                done: 1,
                total: 9,
            },
            FromWorker::OverlayPoints {
                id: 4,
                points: vec![FrSample {
                    index: 2,
                    omega: 0.5,
                    meshes: vec![MeshExtremes {
                        rel_min_um: -3.5,
                        rel_max_um: 120.25,
                        regime: Regime::DoubleSided,
                        dynamic_factor: Some(1.5),
                    }],
                    period: Some(2),
                    error: None,
                }],
            },
        ];
        for m in msgs {
            let text = encode(&m);
            let back: FromWorker = serde_json::from_str(&text).unwrap();
            assert_eq!(back, m);
        }
        assert_eq!(encode(&FromWorker::Ready), r#"{"type":"ready"}"#);
    }

    #[test]
    fn regimes_map_to_solver_impacts_and_back() {
        for r in Regime::ALL {
            assert_eq!(Regime::from(Impact::from(r)), r);
            assert!(Impact::from_name(r.solver_name()).is_some());
        }
    }
}
