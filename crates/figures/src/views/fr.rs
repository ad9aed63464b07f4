//! `ViewId::Fr`, the frequency response: its stores, its view model and its
//! CSV export.
//!
//! It is the harmonic-balance branch of
//! `solver::hbm` ([`HbmStore`], [`FrSource::Hbm`]): points in continuation
//! order with Floquet stability, and bifurcation markers (folds, period
//! doubling, Neimark–Sacker, branch points). A solver failure ends the
//! branch: the points before it are kept and labelled partial, the failure
//! is reported, and nothing is invented past it. Optionally, extremes of
//! time-integration steady states on a grid ([`FrStore`]) are overlaid as
//! dots, with the largest distance between them and the branch as the
//! discrepancy figure.

use super::{csv_num, csv_opt, distinct, NaturalFreq, ViewContext};
use crate::protocol::{BifSample, BranchBif, FrSample, HbmSample, MeshExtremes, Regime};
use serde::Serialize;

/// Where a frequency response comes from.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "method", rename_all = "snake_case")]
pub enum FrSource {
    /// Extremes of time-integration steady states on a grid (upward continuation).
    TimeIntegration {
        /// Maximum transient periods per point.
        transient_periods: u32,
        /// Recorded periods per point.
        record_periods: u32,
    },
    /// The bifurcation sweep's steady states (its upward sweep, else its
    /// downward one): the same time integration, at no extra cost.
    Sweep {
        /// Maximum transient periods per point.
        transient_periods: u32,
        /// Recorded periods per point.
        record_periods: u32,
    },
    /// Harmonic balance (exact method) with pseudo-arclength continuation (`solver::hbm`).
    Hbm {
        /// Harmonics retained.
        harmonics: u32,
    },
}

impl FrSource {
    /// The method in words, for captions and the page's status.
    pub fn label(&self) -> String {
        match self {
            FrSource::TimeIntegration { .. } => "time-integration steady states".into(),
            FrSource::Sweep { .. } => {
                "time-integration steady states of the bifurcation sweep".into()
            }
            FrSource::Hbm { harmonics } => format!("harmonic balance, H = {harmonics}, exact"),
        }
    }
}

/// One point of a frequency-response branch.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrCurvePoint {
    /// Dimensionless frequency.
    pub omega: f64,
    /// Largest x = delta - e over a period (um).
    pub max_um: f64,
    /// Smallest x (um).
    pub min_um: f64,
    /// Stability (HBM: Floquet); `None` when not computed.
    pub stable: Option<bool>,
    /// Impact regime, if known.
    pub regime: Option<Regime>,
    /// Period of the response in mesh periods, if known.
    pub period: Option<u32>,
    /// A bifurcation detected between the previous point and this one (HBM).
    pub bifurcation: Option<FrMarkerKind>,
    /// The piece of the branch it belongs to: a line joins only points of
    /// one piece (a restarted continuation starts a new piece).
    pub piece: u32,
}

impl FrCurvePoint {
    /// Whether a line may join `self` to `next` (both on one piece).
    pub fn joins(&self, next: &FrCurvePoint) -> bool {
        self.piece == next.piece
    }
}

/// A continuous branch of solutions.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrBranch {
    /// Legend text.
    pub label: String,
    /// Points in continuation order.
    pub points: Vec<FrCurvePoint>,
    /// Drawn faded: the previous settings' result while a new one computes.
    pub faded: bool,
    /// The pinned state A of an A/B comparison (drawn in A's colours).
    #[serde(default)]
    pub pinned: bool,
    /// A parameter family's member (drawn in that member's colour).
    #[serde(default)]
    pub member: Option<usize>,
}

/// A bifurcation found along a branch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum FrMarkerKind {
    /// Saddle-node (fold, jump) point.
    Fold,
    /// Period-doubling (flip) point.
    PeriodDoubling,
    /// Neimark–Sacker (torus) point.
    NeimarkSacker,
    /// A real multiplier crossing +1 without a turn (symmetry breaking).
    BranchPoint,
}

impl FrMarkerKind {
    /// All kinds, in legend order.
    pub const ALL: [FrMarkerKind; 4] = [
        FrMarkerKind::Fold,
        FrMarkerKind::PeriodDoubling,
        FrMarkerKind::NeimarkSacker,
        FrMarkerKind::BranchPoint,
    ];

    /// Legend text.
    pub fn label(self) -> &'static str {
        match self {
            FrMarkerKind::Fold => "fold (jump)",
            FrMarkerKind::PeriodDoubling => "period doubling",
            FrMarkerKind::NeimarkSacker => "Neimark-Sacker",
            FrMarkerKind::BranchPoint => "branch point",
        }
    }

    /// What the bifurcation means, in one plain line (the full key and the
    /// bifurcation diagram say it where the kind is drawn).
    pub fn explain(self) -> &'static str {
        match self {
            FrMarkerKind::Fold => {
                "fold: the curve turns back; sweeping Ω past it, the response jumps to another curve"
            }
            FrMarkerKind::PeriodDoubling => {
                "period doubling: the motion starts repeating every two mesh periods instead of every one"
            }
            FrMarkerKind::NeimarkSacker => {
                "Neimark–Sacker: a second, slower rhythm appears, so the motion no longer repeats and its Poincaré dots trace a closed curve"
            }
            FrMarkerKind::BranchPoint => {
                "branch point: another curve of repeating motion crosses this one here"
            }
        }
    }
}

impl From<BranchBif> for FrMarkerKind {
    fn from(b: BranchBif) -> Self {
        match b {
            BranchBif::Fold => FrMarkerKind::Fold,
            BranchBif::PeriodDoubling => FrMarkerKind::PeriodDoubling,
            BranchBif::NeimarkSacker => FrMarkerKind::NeimarkSacker,
            BranchBif::BranchPoint => FrMarkerKind::BranchPoint,
        }
    }
}

/// A marked bifurcation point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrMarker {
    /// Dimensionless frequency.
    pub omega: f64,
    /// Where on the x axis of the plot (um).
    pub value_um: f64,
    /// What it is.
    pub kind: FrMarkerKind,
}

/// What the frequency-response plot draws.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrView {
    /// Method of the branches.
    pub source: FrSource,
    /// [`FrSource::label`] of `source`.
    pub method: String,
    /// The plotted mesh, e.g. `s1a1` or `with the largest peak-to-peak x`.
    pub mesh_label: String,
    /// Distinct backlash half-widths of the plotted meshes (um): the ±b lines.
    pub backlash_um: Vec<f64>,
    /// The pinned state A's ±b (A/B comparison; empty if none).
    pub pinned_backlash_um: Vec<f64>,
    /// Solution branches (the previous settings' branch first, faded).
    pub branches: Vec<FrBranch>,
    /// Bifurcation markers of the current branch.
    pub markers: Vec<FrMarker>,
    /// Time-integration steady states drawn as dots over the branch (empty
    /// when the overlay is off).
    pub overlay: Vec<FrCurvePoint>,
    /// How the overlay was computed, if it is on.
    pub overlay_source: Option<FrSource>,
    /// How the overlay compares with the branch.
    pub discrepancy: Discrepancy,
    /// Natural frequencies in range.
    pub natural: Vec<NaturalFreq>,
    /// Omega range of the axis.
    pub omega_from: f64,
    /// Upper end of the axis.
    pub omega_to: f64,
    /// Selected Omega (the cursor).
    pub selected_omega: f64,
    /// The classification of the steady state at the selected Omega, once
    /// its full run has ended (not a preview): the sentence under the plot
    /// joins it with the branch's stability there.
    pub selected_motion: Option<crate::protocol::Motion>,
    /// The solver failure that ended the branch early, at which Omega: the
    /// branch is partial (reported, never plotted as data).
    pub branch_error: Option<(f64, String)>,
    /// Overlay Omegas where time integration failed (reported, not plotted).
    pub failed: Vec<(f64, String)>,
    /// Points on the current branch.
    pub done: usize,
    /// Fraction of the Omega range the branch covers so far (0 ..= 1).
    pub progress: f64,
    /// Whether the branch has ended (range covered or failed).
    pub finished: bool,
    /// What the continuation did to cover the range (restarts, left-out
    /// gaps), in plain sentences.
    pub branch_notes: Vec<String>,
    /// The axis of x shows the whole clearance ±b (else it fits the data).
    #[serde(skip)]
    pub whole_clearance: bool,
    /// What the speed axis shows.
    #[serde(skip)]
    pub speed: crate::speed::SpeedAxis,
}

/// The harmonic-balance branch as it arrives, for one job.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct HbmStore {
    /// Harmonics of the job.
    pub harmonics: u32,
    /// Points in continuation order.
    pub points: Vec<HbmSample>,
    /// Fraction of the range covered.
    pub progress: f64,
    /// The branch has ended.
    pub finished: bool,
    /// The failure that ended it, if it failed.
    pub error: Option<String>,
    /// What the continuation did to cover the range (restarts, gaps).
    pub notes: Vec<String>,
}

impl HbmStore {
    /// An empty store for a new job.
    pub fn new(harmonics: u32) -> Self {
        HbmStore {
            harmonics,
            ..HbmStore::default()
        }
    }

    /// Adds a chunk of points and the job's state after it.
    pub fn add(
        &mut self,
        points: Vec<HbmSample>,
        progress: f64,
        finished: bool,
        error: Option<String>,
    ) {
        self.points.extend(points);
        self.progress = progress.clamp(0.0, 1.0);
        self.finished |= finished;
        if error.is_some() {
            self.error = error;
        }
    }

    /// Whether the branch covered the whole range without a failure.
    pub fn is_complete(&self) -> bool {
        self.finished && self.error.is_none()
    }

    /// The branch of mesh `mesh` (`None` = each point's mesh with the largest
    /// peak-to-peak x) and its bifurcation markers (on the max x curve).
    pub fn curve(&self, mesh: Option<usize>) -> (Vec<FrCurvePoint>, Vec<FrMarker>) {
        let mut pts = Vec::with_capacity(self.points.len());
        let mut markers = Vec::new();
        for s in &self.points {
            let Some(j) = pick(&s.meshes, mesh, |m| m.rel_max_um - m.rel_min_um) else {
                continue;
            };
            let m = &s.meshes[j];
            let kind = s.bifurcation.map(FrMarkerKind::from);
            if let Some(kind) = kind {
                markers.push(FrMarker {
                    omega: s.omega,
                    value_um: m.rel_max_um,
                    kind,
                });
            }
            pts.push(FrCurvePoint {
                omega: s.omega,
                max_um: m.rel_max_um,
                min_um: m.rel_min_um,
                stable: s.stable,
                regime: Some(m.regime),
                period: Some(1),
                bifurcation: kind,
                piece: s.piece,
            });
        }
        (pts, markers)
    }
}

/// Frequency-response points as they arrive, for one job.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FrStore {
    /// One slot per grid point.
    pub points: Vec<Option<FrSample>>,
    /// Periods used.
    pub transient_periods: u32,
    /// Recorded periods used.
    pub record_periods: u32,
    /// The points are the bifurcation sweep's steady states.
    pub from_sweep: bool,
}

/// Picks the plotted mesh of a set: the given one, or the one with the
/// largest `size` (`ViewId::Fr`: peak-to-peak x).
fn pick<T>(items: &[T], mesh: Option<usize>, size: impl Fn(&T) -> f64) -> Option<usize> {
    match mesh {
        Some(j) => (j < items.len()).then_some(j),
        None => items
            .iter()
            .enumerate()
            .max_by(|a, b| size(a.1).total_cmp(&size(b.1)))
            .map(|(j, _)| j),
    }
}

impl FrStore {
    /// An empty store for a new job over `points` grid points.
    pub fn new(points: u32, transient_periods: u32, record_periods: u32) -> Self {
        FrStore {
            points: vec![None; points as usize],
            transient_periods,
            record_periods,
            from_sweep: false,
        }
    }

    /// The bifurcation sweep's steady states as overlay points: the upward
    /// sweep's (the way the overlay job runs), or the downward one's when
    /// the sweep runs only down. Each carries every mesh's extremes of x.
    pub fn from_sweep(samples: &[BifSample], transient_periods: u32, record_periods: u32) -> Self {
        let up = samples.iter().any(|s| s.up);
        let mut chosen: Vec<&BifSample> = samples.iter().filter(|s| s.up == up).collect();
        chosen.sort_by_key(|s| s.index);
        let points = chosen
            .into_iter()
            .map(|s| {
                Some(FrSample {
                    index: s.index,
                    omega: s.omega,
                    meshes: s
                        .meshes
                        .iter()
                        .map(|m| MeshExtremes {
                            rel_min_um: m.rel_min_um,
                            rel_max_um: m.rel_max_um,
                            regime: m.regime,
                            dynamic_factor: m.dynamic_factor,
                        })
                        .collect(),
                    period: s.period,
                    error: s.error.clone(),
                })
            })
            .collect();
        FrStore {
            points,
            transient_periods,
            record_periods,
            from_sweep: true,
        }
    }

    /// Adds arriving points (ignores indices outside the grid).
    pub fn add(&mut self, samples: Vec<FrSample>) {
        for s in samples {
            if let Some(slot) = self.points.get_mut(s.index as usize) {
                *slot = Some(s);
            }
        }
    }

    /// Points computed so far.
    pub fn done(&self) -> usize {
        self.points.iter().filter(|p| p.is_some()).count()
    }

    /// How the points were computed.
    pub fn source(&self) -> FrSource {
        if self.from_sweep {
            return FrSource::Sweep {
                transient_periods: self.transient_periods,
                record_periods: self.record_periods,
            };
        }
        FrSource::TimeIntegration {
            transient_periods: self.transient_periods,
            record_periods: self.record_periods,
        }
    }

    /// The points of mesh `mesh` (`None` = each point's mesh with the
    /// largest peak-to-peak x, as for the branch) and the failed Omegas.
    pub fn curve(&self, mesh: Option<usize>) -> (Vec<FrCurvePoint>, Vec<(f64, String)>) {
        let mut pts = Vec::new();
        let mut failed = Vec::new();
        for s in self.points.iter().flatten() {
            if let Some(e) = &s.error {
                failed.push((s.omega, e.clone()));
                continue;
            }
            let Some(j) = pick(&s.meshes, mesh, |m| m.rel_max_um - m.rel_min_um) else {
                continue;
            };
            let m = &s.meshes[j];
            pts.push(FrCurvePoint {
                omega: s.omega,
                max_um: m.rel_max_um,
                min_um: m.rel_min_um,
                stable: None,
                regime: Some(m.regime),
                period: s.period,
                bifurcation: None,
                piece: 0,
            });
        }
        (pts, failed)
    }
}

/// How the time-integration overlay compares with the branch.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Discrepancy {
    /// Largest distance (um, the larger of the two extremes' misses) between
    /// an overlay point and the nearest stable stretch of the branch at its
    /// Omega; `None` if no point could be compared.
    pub max_um: Option<f64>,
    /// Overlay points compared.
    pub compared: usize,
    /// Overlay points at an Omega where the branch has no stable (or
    /// unknown-stability) stretch: time integration settled on a response
    /// the branch does not hold (e.g. past a period doubling), or the branch
    /// ended before.
    pub off_branch: usize,
}

/// Compares the overlay with the branch. Where the branch is multi-valued
/// (between folds) the nearest stable (or unknown-stability) stretch counts,
/// since time integration only settles on stable responses.
pub fn discrepancy(branch: &[FrCurvePoint], overlay: &[FrCurvePoint]) -> Discrepancy {
    let mut out = Discrepancy::default();
    for q in overlay {
        let mut best: Option<f64> = None;
        for w in branch.windows(2) {
            let (a, b) = (&w[0], &w[1]);
            if a.stable == Some(false) || b.stable == Some(false) || !a.joins(b) {
                continue;
            }
            let (lo, hi) = if a.omega <= b.omega {
                (a.omega, b.omega)
            } else {
                (b.omega, a.omega)
            };
            if q.omega < lo || q.omega > hi {
                continue;
            }
            let t = if hi > lo {
                (q.omega - a.omega) / (b.omega - a.omega)
            } else {
                0.0
            };
            let max = a.max_um + t * (b.max_um - a.max_um);
            let min = a.min_um + t * (b.min_um - a.min_um);
            let d = (max - q.max_um).abs().max((min - q.min_um).abs());
            best = Some(best.map_or(d, |x: f64| x.min(d)));
        }
        match best {
            Some(d) => {
                out.compared += 1;
                out.max_um = Some(out.max_um.map_or(d, |x: f64| x.max(d)));
            }
            None => out.off_branch += 1,
        }
    }
    out
}

/// Everything `ViewId::Fr` draws: the current branch, the previous settings'
/// complete branch (faded, while the current one computes), and the
/// time-integration overlay if it is on. `mesh = None` plots each point's
/// mesh with the largest peak-to-peak x.
pub fn fr_view(
    hbm: &HbmStore,
    previous: Option<&HbmStore>,
    overlay: Option<&FrStore>,
    mesh: Option<usize>,
    backlash_um: &[f64],
    ctx: &ViewContext,
) -> FrView {
    let source = FrSource::Hbm {
        harmonics: hbm.harmonics,
    };
    let method = source.label();
    let (points, markers) = hbm.curve(mesh);
    let mut branches = Vec::new();
    if let Some(prev) = previous {
        branches.push(FrBranch {
            label: "previous settings".into(),
            points: prev.curve(mesh).0,
            faded: true,
            pinned: false,
            member: None,
        });
    }
    let branch_error = hbm.error.as_ref().map(|e| {
        let at = hbm.points.last().map_or(ctx.omega_from, |p| p.omega);
        (at, e.clone())
    });
    let label = if branch_error.is_some() {
        format!("HBM, H = {}; partial: solver failed", hbm.harmonics)
    } else {
        format!("HBM, H = {}", hbm.harmonics)
    };
    let (overlay_pts, failed, overlay_source) = match overlay {
        Some(st) => {
            let (p, f) = st.curve(mesh);
            (p, f, Some(st.source()))
        }
        None => (Vec::new(), Vec::new(), None),
    };
    let discrepancy = discrepancy(&points, &overlay_pts);
    let mesh_label = if mesh.is_none() {
        // Not "worst mesh": that is the largest dynamic factor (one
        // definition, `SteadyState::worst_mesh`); the harmonic balance's
        // points rank the meshes by what this plot shows.
        "with the largest peak-to-peak x".to_string()
    } else {
        ctx.mesh_label.clone()
    };
    branches.push(FrBranch {
        label,
        points,
        faded: false,
        pinned: false,
        member: None,
    });
    FrView {
        source,
        method,
        mesh_label,
        backlash_um: distinct(backlash_um, mesh),
        pinned_backlash_um: Vec::new(),
        branches,
        markers,
        overlay: overlay_pts,
        overlay_source,
        discrepancy,
        natural: ctx.natural.clone(),
        omega_from: ctx.omega_from,
        omega_to: ctx.omega_to,
        selected_omega: ctx.selected_omega,
        selected_motion: None,
        branch_error,
        failed,
        done: hbm.points.len(),
        progress: hbm.progress,
        finished: hbm.finished,
        branch_notes: hbm.notes.clone(),
        whole_clearance: true,
        speed: ctx.speed,
    }
}

/// The frequency response as CSV: the current branch (`hbm` rows, in
/// continuation order), then the time-integration overlay, if on.
pub fn fr_csv(v: &FrView) -> String {
    let mut s = String::from("branch,omega,x_max_um,x_min_um,stable,regime,period,bifurcation\n");
    // A family's curves say whose they are: "hbm (TE 20 µm)".
    let current = v.branches.iter().filter(|b| !b.faded).map(|b| {
        let name = match b.member {
            Some(_) => format!("hbm ({})", b.label.replace(',', ";")),
            None => "hbm".to_string(),
        };
        (name, b)
    });
    let overlay = v
        .overlay
        .iter()
        .map(|p| ("time-integration".to_string(), p));
    let rows = current
        .flat_map(|(name, b)| b.points.iter().map(move |p| (name.clone(), p)))
        .chain(overlay);
    for (name, p) in rows {
        s.push_str(&format!(
            "{name},{},{},{},{},{},{},{}\n",
            csv_num(p.omega),
            csv_num(p.max_um),
            csv_num(p.min_um),
            csv_opt(p.stable),
            p.regime.map_or("", |r| r.solver_name()),
            csv_opt(p.period),
            p.bifurcation.map_or("", |k| k.label())
        ));
    }
    s
}

/// The note under `ViewId::Fr`: the method, and how to see the overlay.
pub fn fr_note(v: &FrView) -> String {
    let overlay = match v.overlay_source {
        Some(FrSource::Sweep { .. }) => {
            " Hollow dots: the actual response, from time integration (the bifurcation diagram's steady states)."
        }
        Some(_) => " Hollow dots: the actual response, from time integration (upward sweep).",
        None => " Hollow dots, when the bifurcation diagram has run: the actual response, from time integration.",
    };
    let mut note = format!(
        "Method: {} (mesh forces integrated in closed form between the contact switches), pseudo-arclength continuation upward in Ω with Floquet stability.{overlay}",
        v.method
    );
    for n in &v.branch_notes {
        note.push(' ');
        note.push_str(n);
    }
    note
}

/// The note under `ViewId::Fr` when it shows mesh panels: the method, and that
/// the panels hold the branches only (the time-integration dots are of
/// the plotted mesh alone).
pub fn fr_panels_note(v: &FrView) -> String {
    let mut note = format!(
        "Method: {}, pseudo-arclength continuation upward in Ω with Floquet stability: the branches only, one panel per mesh. Where a branch is dashed (unstable) the actual response differs; choose a mesh in the settings to see it alone with the time-integration dots of the actual response.",
        v.method
    );
    for n in &v.branch_notes {
        note.push(' ');
        note.push_str(n);
    }
    note
}

/// The caption's status of `ViewId::Fr`: progress over the Omega range while the
/// branch computes, and a partial branch said as such.
pub fn fr_caption_suffix(running: bool, v: &FrView) -> String {
    if v.branch_error.is_some() {
        " (partial: solver failed)".into()
    } else if running {
        format!(" (computing, {:.0}% of Ω range)", 100.0 * v.progress)
    } else {
        String::new()
    }
}

#[cfg(test)]
mod tests;
