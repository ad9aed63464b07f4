//! The data behind each view: stores filled by worker replies, and the view
//! models the plots draw (and the CSV/JSON exports write).
//!
//! The frequency response is modelled for the harmonic-balance engine that
//! is being added to the solver (`solver::hbm`): branches of points with a
//! stability flag, and bifurcation markers (folds, period doubling,
//! Neimark–Sacker). Until it lands, [`FrStore`] fills the same type from
//! time-integration steady states ([`FrSource::TimeIntegration`]), which the
//! plot labels as a fallback: no curve is ever invented.

use crate::protocol::{BifSample, FrSample, OmegaResult, Regime};
use crate::worker_core::severity;
use serde::Serialize;
use solver::modal::ModeKind;
use solver::steady::Model;

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
    /// Harmonic balance with continuation (`solver::hbm`).
    Hbm {
        /// Harmonics retained.
        harmonics: u32,
    },
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
}

impl FrMarkerKind {
    /// Legend text.
    pub fn label(self) -> &'static str {
        match self {
            FrMarkerKind::Fold => "fold",
            FrMarkerKind::PeriodDoubling => "period doubling",
            FrMarkerKind::NeimarkSacker => "Neimark-Sacker",
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

/// A natural frequency of the mean-stiffness linear system.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NaturalFreq {
    /// Dimensionless frequency omega_n / omega_ref.
    pub omega: f64,
    /// Hz.
    pub frequency_hz: f64,
    /// `rotational` or `planet`.
    pub kind: String,
    /// Repeated modes.
    pub multiplicity: usize,
}

/// The elastic natural frequencies (repeated ones once) within `lo ..= hi`.
pub fn natural_in_range(model: &Model, lo: f64, hi: f64) -> Vec<NaturalFreq> {
    let mut out: Vec<NaturalFreq> = Vec::new();
    for m in model.modes.elastic() {
        if m.omega < lo || m.omega > hi {
            continue;
        }
        if out
            .last()
            .is_some_and(|p| (p.omega - m.omega).abs() <= 1e-6 * m.omega)
        {
            continue;
        }
        out.push(NaturalFreq {
            omega: m.omega,
            frequency_hz: m.frequency_hz,
            kind: match m.kind {
                ModeKind::Planet => "planet".into(),
                ModeKind::Rotational | ModeKind::RigidBody => "rotational".into(),
            },
            multiplicity: m.multiplicity,
        });
    }
    out
}

/// What the frequency-response plot draws.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrView {
    /// Method.
    pub source: FrSource,
    /// The plotted mesh, e.g. `s1a1` or `worst mesh`.
    pub mesh_label: String,
    /// Distinct backlash half-widths of the plotted meshes (um): the ±b lines.
    pub backlash_um: Vec<f64>,
    /// Solution branches.
    pub branches: Vec<FrBranch>,
    /// Bifurcation markers.
    pub markers: Vec<FrMarker>,
    /// Natural frequencies in range.
    pub natural: Vec<NaturalFreq>,
    /// Omega range of the axis.
    pub omega_from: f64,
    /// Upper end of the axis.
    pub omega_to: f64,
    /// Selected Omega (the cursor).
    pub selected_omega: f64,
    /// Omegas where the solver failed (reported, not plotted as data).
    pub failed: Vec<(f64, String)>,
    /// Points computed and in all.
    pub done: usize,
    /// Points in all.
    pub total: usize,
}

/// Frequency-response points as they arrive, for one job.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FrStore {
    /// The job these points belong to.
    pub id: u64,
    /// One slot per grid point.
    pub points: Vec<Option<FrSample>>,
    /// Periods used.
    pub transient_periods: u32,
    /// Recorded periods used.
    pub record_periods: u32,
}

/// Picks the plotted mesh of a set: the given one, or the one with the
/// largest dynamic factor.
fn pick<T>(items: &[T], mesh: Option<usize>, dynamic: impl Fn(&T) -> f64) -> Option<usize> {
    match mesh {
        Some(j) => (j < items.len()).then_some(j),
        None => items
            .iter()
            .enumerate()
            .max_by(|a, b| dynamic(a.1).total_cmp(&dynamic(b.1)))
            .map(|(j, _)| j),
    }
}

impl FrStore {
    /// An empty store for a new job over `points` grid points.
    pub fn new(id: u64, points: u32, transient_periods: u32, record_periods: u32) -> Self {
        FrStore {
            id,
            points: vec![None; points as usize],
            transient_periods,
            record_periods,
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

    /// The view of mesh `mesh` (`None` = worst per point).
    pub fn view(&self, mesh: Option<usize>, backlash_um: &[f64], ctx: &ViewContext) -> FrView {
        let mut pts = Vec::new();
        let mut failed = Vec::new();
        for s in self.points.iter().flatten() {
            if let Some(e) = &s.error {
                failed.push((s.omega, e.clone()));
                continue;
            }
            let Some(j) = pick(&s.meshes, mesh, |m| m.dynamic_factor.unwrap_or(0.0)) else {
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
            });
        }
        FrView {
            source: FrSource::TimeIntegration {
                transient_periods: self.transient_periods,
                record_periods: self.record_periods,
            },
            mesh_label: ctx.mesh_label.clone(),
            backlash_um: distinct(backlash_um, mesh),
            branches: vec![FrBranch {
                label: "time integration, upward sweep".into(),
                points: pts,
                faded: false,
            }],
            markers: Vec::new(),
            natural: ctx.natural.clone(),
            omega_from: ctx.omega_from,
            omega_to: ctx.omega_to,
            selected_omega: ctx.selected_omega,
            failed,
            done: self.done(),
            total: self.points.len(),
        }
    }
}

/// The distinct ±b values of the plotted mesh (all meshes' for "worst").
fn distinct(backlash_um: &[f64], mesh: Option<usize>) -> Vec<f64> {
    let mut out: Vec<f64> = match mesh {
        Some(j) => backlash_um.get(j).copied().into_iter().collect(),
        None => backlash_um.to_vec(),
    };
    out.sort_by(f64::total_cmp);
    out.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    out
}

/// What every view shares: the axis range, the cursor, the mesh label and
/// the natural frequencies.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ViewContext {
    /// Lower end of the Omega axis.
    pub omega_from: f64,
    /// Upper end.
    pub omega_to: f64,
    /// The cursor.
    pub selected_omega: f64,
    /// E.g. `s1a1` or `worst mesh`.
    pub mesh_label: String,
    /// Natural frequencies in range.
    pub natural: Vec<NaturalFreq>,
}

/// One dot of the bifurcation diagram.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BifPoint {
    /// Dimensionless frequency.
    pub omega: f64,
    /// Poincaré sample of x = delta - e (um).
    pub x_um: f64,
    /// Impact regime at this Omega.
    pub regime: Regime,
    /// Upward sweep (else downward).
    pub up: bool,
}

/// What the bifurcation diagram draws.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BifView {
    /// The plotted mesh.
    pub mesh_label: String,
    /// ±b lines (um).
    pub backlash_um: Vec<f64>,
    /// The dots.
    pub points: Vec<BifPoint>,
    /// Lower end of the axis.
    pub omega_from: f64,
    /// Upper end.
    pub omega_to: f64,
    /// The cursor.
    pub selected_omega: f64,
    /// Failed points.
    pub failed: Vec<(f64, String)>,
    /// Swept points received.
    pub done: usize,
    /// Swept points in all.
    pub total: usize,
}

/// Bifurcation points as they arrive from both workers, for one job.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BifStore {
    /// The job.
    pub id: u64,
    /// Samples in arrival order.
    pub samples: Vec<BifSample>,
    /// Swept points in all (both shards).
    pub total: usize,
}

impl BifStore {
    /// An empty store for a new job.
    pub fn new(id: u64, total: usize) -> Self {
        BifStore {
            id,
            samples: Vec::new(),
            total,
        }
    }

    /// The view of mesh `mesh` (`None` = each point's worst mesh).
    pub fn view(&self, mesh: Option<usize>, backlash_um: &[f64], ctx: &ViewContext) -> BifView {
        let mut points = Vec::new();
        let mut failed = Vec::new();
        for s in &self.samples {
            if let Some(e) = &s.error {
                failed.push((s.omega, e.clone()));
                continue;
            }
            let j = mesh.unwrap_or(s.worst_mesh);
            let Some(m) = s.meshes.get(j) else { continue };
            points.extend(m.x_um.iter().map(|&x| BifPoint {
                omega: s.omega,
                x_um: x,
                regime: m.regime,
                up: s.up,
            }));
        }
        BifView {
            mesh_label: ctx.mesh_label.clone(),
            backlash_um: distinct(backlash_um, mesh),
            points,
            omega_from: ctx.omega_from,
            omega_to: ctx.omega_to,
            selected_omega: ctx.selected_omega,
            failed,
            done: self.samples.len(),
            total: self.total,
        }
    }
}

/// The most severe regime of a sample's meshes.
pub fn worst_regime(s: &BifSample) -> Option<Regime> {
    s.meshes
        .iter()
        .map(|m| m.regime)
        .max_by_key(|&r| severity(r))
}

/// The one-line summary at the selected Omega (view 6).
pub fn summary_line(r: &OmegaResult, natural: &[NaturalFreq]) -> String {
    let period = match r.period {
        Some(p) => format!("period {p}"),
        None => "not periodic (within the recorded periods)".into(),
    };
    let df = r.dynamic_factor.map_or("n/a".into(), |d| format!("{d:.3}"));
    let nat = if natural.is_empty() {
        "none in range".to_string()
    } else {
        natural
            .iter()
            .map(|n| format!("{:.3}", n.omega))
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!(
        "Omega = {:.4} ({:.0} Hz mesh frequency), mesh {}: {}, {}, dynamic factor {}. Natural frequencies in range (Omega): {}.",
        r.omega,
        r.mesh_freq_hz,
        r.mesh_name,
        r.regime.label(),
        period,
        df,
        nat
    )
}

fn csv_num(x: f64) -> String {
    if x.is_finite() {
        format!("{x}")
    } else {
        String::new()
    }
}

fn csv_opt<T: std::fmt::Display>(x: Option<T>) -> String {
    x.map_or(String::new(), |v| v.to_string())
}

/// The frequency response as CSV.
pub fn fr_csv(v: &FrView) -> String {
    let mut s = String::from("branch,omega,x_max_um,x_min_um,stable,regime,period\n");
    for (b, br) in v.branches.iter().enumerate() {
        for p in &br.points {
            s.push_str(&format!(
                "{b},{},{},{},{},{},{}\n",
                csv_num(p.omega),
                csv_num(p.max_um),
                csv_num(p.min_um),
                csv_opt(p.stable),
                p.regime.map_or("", |r| r.solver_name()),
                csv_opt(p.period)
            ));
        }
    }
    s
}

/// The bifurcation diagram as CSV.
pub fn bif_csv(v: &BifView) -> String {
    let mut s = String::from("omega,direction,x_um,regime\n");
    for p in &v.points {
        s.push_str(&format!(
            "{},{},{},{}\n",
            csv_num(p.omega),
            if p.up { "up" } else { "down" },
            csv_num(p.x_um),
            p.regime.solver_name()
        ));
    }
    s
}

/// Which of the selected-Omega views.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OmegaView {
    /// Phase portrait.
    Phase,
    /// Poincaré section.
    Poincare,
    /// Time history.
    Time,
    /// Spectrum.
    Spectrum,
}

/// A selected-Omega view as CSV.
pub fn omega_csv(r: &OmegaResult, which: OmegaView) -> String {
    let spp = f64::from(r.samples_per_period.max(1));
    match which {
        OmegaView::Phase | OmegaView::Time => {
            let mut s = String::from("t_periods,x_um,xdot_m_s\n");
            for (k, (x, v)) in r.x_um.iter().zip(&r.xdot_m_s).enumerate() {
                s.push_str(&format!(
                    "{},{},{}\n",
                    k as f64 / spp,
                    csv_num(*x),
                    csv_num(*v)
                ));
            }
            s
        }
        OmegaView::Poincare => {
            let mut s = String::from("n,x_um,xdot_m_s\n");
            for (k, (x, v)) in r.poincare_x_um.iter().zip(&r.poincare_xdot_m_s).enumerate() {
                s.push_str(&format!("{k},{},{}\n", csv_num(*x), csv_num(*v)));
            }
            s
        }
        OmegaView::Spectrum => {
            let mut s = String::from("order,amplitude_um\n");
            for (o, a) in r.spectrum_order.iter().zip(&r.spectrum_um) {
                s.push_str(&format!("{},{}\n", csv_num(*o), csv_num(*a)));
            }
            s
        }
    }
}

/// A selected-Omega view's data as JSON (the plotted series plus context).
pub fn omega_json(r: &OmegaResult, which: OmegaView) -> serde_json::Value {
    use serde_json::json;
    let head = json!({
        "omega": r.omega,
        "mesh": r.mesh_name,
        "backlash_um": r.backlash_um,
        "impact": r.regime.solver_name(),
        "period": r.period,
        "dynamic_factor": r.dynamic_factor,
        "samples_per_period": r.samples_per_period,
        "record_periods": r.record_periods,
    });
    let body = match which {
        OmegaView::Phase | OmegaView::Time => json!({
            "x_um": r.x_um, "xdot_m_s": r.xdot_m_s,
            "poincare_x_um": r.poincare_x_um, "poincare_xdot_m_s": r.poincare_xdot_m_s,
        }),
        OmegaView::Poincare => json!({
            "poincare_x_um": r.poincare_x_um, "poincare_xdot_m_s": r.poincare_xdot_m_s,
        }),
        OmegaView::Spectrum => json!({
            "order": r.spectrum_order, "amplitude_um": r.spectrum_um,
        }),
    };
    json!({ "view": head, "data": body })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::{BifMesh, MeshExtremes};

    fn ext(lo: f64, hi: f64, df: f64) -> MeshExtremes {
        MeshExtremes {
            rel_min_um: lo,
            rel_max_um: hi,
            regime: Regime::SingleSided,
            dynamic_factor: Some(df),
        }
    }

    fn ctx() -> ViewContext {
        ViewContext {
            omega_from: 0.1,
            omega_to: 2.0,
            selected_omega: 0.5,
            mesh_label: "s1a1".into(),
            natural: vec![],
        }
    }

    #[test]
    fn fr_store_orders_by_grid_and_picks_meshes() {
        let mut st = FrStore::new(1, 3, 300, 30);
        st.add(vec![FrSample {
            index: 2,
            omega: 2.0,
            meshes: vec![ext(1.0, 2.0, 1.1), ext(-5.0, 9.0, 3.0)],
            period: Some(1),
            error: None,
        }]);
        st.add(vec![FrSample {
            index: 0,
            omega: 0.1,
            meshes: vec![],
            period: None,
            error: Some("blew up".into()),
        }]);
        st.add(vec![FrSample {
            index: 7,
            omega: 9.0,
            meshes: vec![],
            period: None,
            error: None,
        }]);
        assert_eq!(st.done(), 2);
        let v = st.view(Some(0), &[100.0, 50.0], &ctx());
        assert_eq!(v.branches[0].points.len(), 1);
        assert_eq!(v.branches[0].points[0].max_um, 2.0);
        assert_eq!(v.backlash_um, vec![100.0]);
        assert_eq!(v.failed.len(), 1);
        let w = st.view(None, &[100.0, 50.0], &ctx());
        assert_eq!(w.branches[0].points[0].max_um, 9.0);
        assert_eq!(w.backlash_um, vec![50.0, 100.0]);
        assert!(fr_csv(&w)
            .lines()
            .nth(1)
            .unwrap()
            .starts_with("0,2,9,-5,,single-sided,1"));
    }

    #[test]
    fn bif_store_flattens_poincare_samples() {
        let mut st = BifStore::new(3, 4);
        st.samples.push(BifSample {
            index: 0,
            omega: 0.5,
            up: false,
            meshes: vec![BifMesh {
                x_um: vec![1.0, 2.0],
                regime: Regime::DoubleSided,
            }],
            worst_mesh: 0,
            period: Some(2),
            error: None,
        });
        let v = st.view(None, &[100.0], &ctx());
        assert_eq!(v.points.len(), 2);
        assert!(!v.points[0].up);
        assert_eq!(v.done, 1);
        assert_eq!(bif_csv(&v).lines().count(), 3);
        assert_eq!(worst_regime(&st.samples[0]), Some(Regime::DoubleSided));
    }
}
