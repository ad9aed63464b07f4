//! The dynamic factor's view model (`ViewId::Dynamic`): for the selected
//! mesh, the model's dynamic factor over Omega (largest mesh force over
//! the static one, read from the frequency response's steady states, the
//! time-integration points or the bifurcation sweep's) beside K_v by
//! ISO 6336-1 method B over the same range (`solver::iso6336`, closed
//! form, computed here on the main thread), and for the selected state
//! how the planets share the load, and over Omega the planets' load-sharing
//! factor at each steady state (each mesh's largest force is its dynamic
//! factor times its static force; `solver::sharing::sharing_of_peaks`).
//! Its words (the note over the plot and its text alternative), CSV and
//! JSON.
//!
//! K_v is piecewise linear in the resonance ratio N, which is
//! proportional to Omega: its curve is the four ranges' end points,
//! exact, with the jump at N_S where the main resonance begins.

use serde_json::json;
use solver::iso6336::{iso_mesh, IsoInputs, MeshRating, SpeedRange};
use solver::model::Model;
use solver::params::ModelParams;

use super::campbell::grouped;
use super::fr::FrStore;
use super::{csv_num, NaturalFreq, ViewContext};
use crate::protocol::{OmegaResult, Regime};

/// The nonlinear factor at the selected Omega, from its steady state.
#[derive(Debug, Clone, PartialEq)]
pub struct SelectedFactor {
    /// max F / F_static of the mesh (`None`: no static load).
    pub factor: Option<f64>,
    /// The mesh's contact regime there.
    pub regime: Regime,
    /// The state is the page's short preview run.
    pub preview: bool,
}

/// One mesh kind's load sharing at the selected state, in words.
#[derive(Debug, Clone, PartialEq)]
pub struct SharingRow {
    /// The kind's key (`s1a`, `s2b`, `ab`, `rb`).
    pub kind: String,
    /// The kind in plain words ("small sun – short planet").
    pub words: &'static str,
    /// Each planet's peak mesh force (N).
    pub peak_force_n: Vec<f64>,
    /// Largest over mean.
    pub factor: Option<f64>,
}

/// What the dynamic-factor plot draws and says.
#[derive(Debug, Clone, PartialEq)]
pub struct DynamicView {
    /// The mesh shown (model index) and its name.
    pub mesh: usize,
    /// Its name (`s1a1`).
    pub mesh_name: String,
    /// The Omega axis.
    pub omega_from: f64,
    /// Its top.
    pub omega_to: f64,
    /// The selected Omega.
    pub selected_omega: f64,
    /// Input member speed (rpm) per unit Omega.
    pub rpm_per_omega: f64,
    /// The model's factor at each computed steady state, by rising Omega.
    pub nonlinear: Vec<(f64, f64)>,
    /// How many steady states the frequency response has computed (with
    /// or without a factor).
    pub states: usize,
    /// K_v over the Omega axis: one polyline per range (broken at N_S).
    pub kv: Vec<Vec<(f64, f64)>>,
    /// Omega per unit resonance ratio N.
    pub omega_per_n: f64,
    /// The standard's rating of the mesh.
    pub rating: MeshRating,
    /// The inputs it used.
    pub inputs: IsoInputs,
    /// The selected state's factor, once its steady state is in.
    pub selected: Option<SelectedFactor>,
    /// How the planets share the load at the selected state (empty for
    /// the gear pair, or before the state is in).
    pub sharing: Vec<SharingRow>,
    /// "in-phase" or "sequential" (`None`: the gear pair).
    pub phasing: Option<&'static str>,
    /// Planets of the set (0 for the gear pair).
    pub planets: u32,
    /// Natural frequencies in range.
    pub natural: Vec<NaturalFreq>,
    /// The load sharing at each computed steady state, by rising Omega
    /// (empty for the gear pair).
    pub sharing_over_speed: Vec<SharingAt>,
}

/// How the planets share the load at one steady state of the sweep.
#[derive(Debug, Clone, PartialEq)]
pub struct SharingAt {
    /// Omega.
    pub omega: f64,
    /// Each mesh kind's sharing (`solver::sharing`'s order).
    pub kinds: Vec<SharingRow>,
}

impl SharingAt {
    /// The largest factor over the kinds.
    pub fn worst(&self) -> Option<f64> {
        self.kinds
            .iter()
            .filter_map(|k| k.factor)
            .fold(None, |m: Option<f64>, f| Some(m.map_or(f, |m| m.max(f))))
    }
}

/// A mesh kind in plain words.
pub fn kind_words(kind: &str) -> &'static str {
    match kind {
        "s1a" => "small sun – short planet",
        "s2b" => "large sun – long planet",
        "ab" => "short planet – long planet",
        "rb" => "ring – long planet",
        _ => "pinion – gear",
    }
}

impl DynamicView {
    /// The view of mesh `mesh` of `model` (built from `params`) over the
    /// range of `ctx`, with the frequency response's steady states
    /// `states` and the selected state `omega`, K_v rated with `inputs`;
    /// the standard's refusal (a mesh without load, an input out of its
    /// range) as the reason.
    pub fn new(
        params: &ModelParams,
        model: &Model,
        ctx: &ViewContext,
        mesh: usize,
        states: Option<&FrStore>,
        omega: Option<&OmegaResult>,
        inputs: &IsoInputs,
    ) -> Result<Self, super::ViewError> {
        let inputs = *inputs;
        let name = model
            .system
            .meshes
            .get(mesh)
            .map(|m| m.name.clone())
            .ok_or(super::ViewError::NoMesh(mesh))?;
        let iso = iso_mesh(params, model, mesh)
            .ok_or_else(|| super::ViewError::NoIsoGeometry(name.clone()))?;
        let rating = MeshRating::new(&iso, &inputs).map_err(|source| super::ViewError::Rating {
            mesh: name.clone(),
            source,
        })?;
        let hz_per_omega = model.system.mesh_freq_hz(1.0);
        let omega_per_n = rating.resonance_mesh_freq_hz / hz_per_omega;
        let (from, to) = (ctx.omega_from, ctx.omega_to);
        let computed: Vec<_> = states
            .map(|s| s.points.iter().flatten().collect())
            .unwrap_or_default();
        let mut nonlinear: Vec<(f64, f64)> = computed
            .iter()
            .filter_map(|p| {
                let f = p.meshes.get(mesh)?.dynamic_factor?;
                f.is_finite().then_some((p.omega, f))
            })
            .collect();
        nonlinear.sort_by(|a, b| a.0.total_cmp(&b.0));
        let statics = &model.statics.mesh_force_n;
        let mut sharing_over_speed: Vec<SharingAt> = computed
            .iter()
            .filter_map(|p| {
                let peaks: Option<Vec<f64>> = p
                    .meshes
                    .iter()
                    .zip(statics)
                    .map(|(m, s)| m.dynamic_factor.map(|f| f * s))
                    .collect();
                let kinds: Vec<SharingRow> =
                    solver::sharing::sharing_of_peaks(&model.system, &peaks?)
                        .into_iter()
                        .map(|k| SharingRow {
                            kind: k.kind.key().to_string(),
                            words: kind_words(k.kind.key()),
                            peak_force_n: k.peak_force_n,
                            factor: k.factor,
                        })
                        .collect();
                (!kinds.is_empty()).then_some(SharingAt {
                    omega: p.omega,
                    kinds,
                })
            })
            .collect();
        sharing_over_speed.sort_by(|a, b| a.omega.total_cmp(&b.omega));
        let selected = omega
            .filter(|r| (r.omega - ctx.selected_omega).abs() < 1e-12)
            .and_then(|r| {
                let m = r.all_meshes.get(mesh)?;
                Some(SelectedFactor {
                    factor: m.dynamic_factor,
                    regime: m.regime,
                    preview: r.preview,
                })
            });
        let sharing = omega
            .filter(|r| (r.omega - ctx.selected_omega).abs() < 1e-12)
            .map(|r| {
                r.load_sharing
                    .iter()
                    .map(|k| SharingRow {
                        kind: k.kind.clone(),
                        words: kind_words(&k.kind),
                        peak_force_n: k.peak_force_n.clone(),
                        factor: k.factor,
                    })
                    .collect()
            })
            .unwrap_or_default();
        let (phasing, planets) = match params {
            ModelParams::Ravigneaux(p) => (Some(p.phasing.name()), p.planets),
            ModelParams::GearPair(_) => (None, 0),
        };
        let mut v = DynamicView {
            mesh,
            mesh_name: name,
            omega_from: from,
            omega_to: to,
            selected_omega: ctx.selected_omega,
            rpm_per_omega: model.system.rpm_scale().rpm(1.0),
            nonlinear,
            states: computed.len(),
            kv: Vec::new(),
            omega_per_n,
            rating,
            inputs,
            selected,
            sharing,
            phasing,
            planets,
            natural: ctx.natural.clone(),
            sharing_over_speed,
        };
        v.kv = v.kv_curve();
        Ok(v)
    }

    /// The resonance ratio N at `omega`.
    pub fn n_at(&self, omega: f64) -> f64 {
        omega / self.omega_per_n
    }

    /// K_v at `omega`.
    pub fn kv_at(&self, omega: f64) -> f64 {
        self.rating.kv(self.n_at(omega))
    }

    /// The range of `omega`.
    pub fn range_at(&self, omega: f64) -> SpeedRange {
        self.rating.range(self.n_at(omega))
    }

    /// The Omega where the standard's main resonance begins, its centre
    /// (N = 1) and where it ends.
    pub fn main_band(&self) -> (f64, f64, f64) {
        let o = self.omega_per_n;
        (self.rating.n_s * o, o, 1.15 * o)
    }

    /// K_v's polylines over the axis: each range from its start to its
    /// end within the axis (a range is linear in N, so its ends suffice),
    /// a new polyline where K_v jumps (at N_S).
    fn kv_curve(&self) -> Vec<Vec<(f64, f64)>> {
        let o = self.omega_per_n;
        let edges = [self.rating.n_s * o, 1.15 * o, 1.5 * o];
        let (from, to) = (self.omega_from, self.omega_to);
        let mut cuts = vec![from];
        cuts.extend(edges.iter().copied().filter(|e| *e > from && *e < to));
        cuts.push(to);
        let mut lines: Vec<Vec<(f64, f64)>> = Vec::new();
        for w in cuts.windows(2) {
            let (a, b) = (w[0], w[1]);
            // The piece's own formula at both ends (an edge belongs to the
            // range below it, but the piece above starts from its value).
            let range = self.range_at(0.5 * (a + b));
            let at = |x: f64| self.rating.kv_in(range, self.n_at(x));
            let (pa, pb) = ((a, at(a)), (b, at(b)));
            match lines.last_mut() {
                Some(l) if l.last().is_some_and(|q| (q.1 - pa.1).abs() <= 1e-9) => l.push(pb),
                _ => lines.push(vec![pa, pb]),
            }
        }
        lines
    }

    /// Input member speed (rpm) at `omega`.
    pub fn rpm_at(&self, omega: f64) -> f64 {
        omega * self.rpm_per_omega
    }

    /// The sentence on load sharing at the selected state.
    pub fn sharing_words(&self) -> String {
        let Some(phasing) = self.phasing else {
            return "The gear pair has one mesh: no load to share.".into();
        };
        let over = self.sharing_range().map_or(String::new(), |(lo, hi)| {
            format!(
                " Over the {} steady states the largest factor of any kind runs from {lo:.3} to {hi:.3}{}.",
                self.sharing_over_speed.len(),
                if phasing == "in-phase" {
                    " (in phase, equal planets move alike, giving 1, unless their motion loses its symmetry)"
                } else {
                    ""
                }
            )
        });
        if self.sharing.is_empty() {
            return format!("Load sharing: waiting for the selected state.{over}");
        }
        let parts: Vec<String> = self
            .sharing
            .iter()
            .map(|k| {
                let f = k.factor.map_or("n/a".into(), |f| format!("{f:.3}"));
                format!("{} {f}", k.words)
            })
            .collect();
        format!(
            "Load-sharing factor (largest planet mesh force over the mean), {} planets, {phasing} phasing: {}.{over}",
            self.planets,
            parts.join(", ")
        )
    }

    /// The smallest and largest of the worst kind's factor over the
    /// steady states, if any.
    pub fn sharing_range(&self) -> Option<(f64, f64)> {
        let w: Vec<f64> = self
            .sharing_over_speed
            .iter()
            .filter_map(SharingAt::worst)
            .collect();
        let lo = w.iter().copied().reduce(f64::min)?;
        let hi = w.iter().copied().reduce(f64::max)?;
        Some((lo, hi))
    }

    /// The note over the plot: the two factors at the selected speed, where
    /// the standard's resonance is, why they differ here, and load sharing.
    pub fn note(&self) -> String {
        let o = self.selected_omega;
        let n = self.n_at(o);
        let kv = self.kv_at(o);
        let model = match &self.selected {
            None => "the model's dynamic factor: computing".to_string(),
            Some(SelectedFactor { factor: None, .. }) => {
                "the model's dynamic factor: n/a (no static load)".into()
            }
            Some(s) => format!(
                "the model's dynamic factor {:.2}{}",
                s.factor.unwrap_or(f64::NAN),
                if s.preview { " (preview)" } else { "" }
            ),
        };
        let (_, centre, _) = self.main_band();
        let why = match self.selected.as_ref().map(|s| s.regime) {
            Some(Regime::SingleSided | Regime::DoubleSided | Regime::NoContact) => {
                " Here the teeth part and strike again (backlash), which the standard's linear pair never does.".to_string()
            }
            Some(_) => format!(
                " Here the teeth stay in contact: the difference is the model's transmission error, its mesh stiffness varying with the mesh cycle and the coupled bodies, against the standard's single pair excited by the deviations of grade {}.",
                self.inputs.accuracy_grade
            ),
            None => String::new(),
        };
        format!(
            "At Ω {o:.3} ({} rpm), mesh {}: {model}; dynamic factor Kv (ISO 6336-1, method B) {kv:.2} ({} range, resonance ratio N = {n:.2}). The standard puts this mesh's main resonance at Ω {centre:.2} ({} rpm).{why} {}",
            crate::speed::grouped_fine(self.rpm_at(o)),
            self.mesh_name,
            self.range_at(o).name(),
            grouped(self.rpm_at(centre)),
            self.sharing_words()
        )
    }

    /// The text alternative of the plot.
    pub fn label(&self) -> String {
        format!(
            "Dynamic factor of mesh {} over Ω {} to {}: the model's from {} steady states beside Kv by ISO 6336-1 method B. {}",
            self.mesh_name,
            self.omega_from,
            self.omega_to,
            self.nonlinear.len(),
            self.note()
        )
    }
}

/// The curves as CSV: every Omega of either curve, by rising Omega, the
/// model's factor blank where it has no steady state.
pub fn dynamic_csv(v: &DynamicView) -> String {
    let mut rows: Vec<(f64, Option<f64>)> = v.nonlinear.iter().map(|p| (p.0, Some(p.1))).collect();
    for p in v.kv.iter().flatten() {
        if !rows.iter().any(|r| r.0 == p.0) {
            rows.push((p.0, None));
        }
    }
    rows.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut out =
        String::from("omega,input_speed_rpm,dynamic_factor,kv_iso6336,iso_range,resonance_ratio\n");
    for (o, f) in rows {
        out.push_str(&format!(
            "{},{},{},{},{},{}\n",
            csv_num(o),
            csv_num(v.rpm_at(o)),
            f.map_or(String::new(), csv_num),
            csv_num(v.kv_at(o)),
            v.range_at(o).name(),
            csv_num(v.n_at(o)),
        ));
    }
    out
}

/// The view as JSON: the mesh, the standard's inputs and quantities, both
/// curves, the selected state and its load sharing.
pub fn dynamic_json(v: &DynamicView) -> serde_json::Value {
    let r = &v.rating;
    let i = &v.inputs;
    let (start, centre, end) = v.main_band();
    json!({
        "mesh": v.mesh_name,
        "method": "ISO 6336-1, method B",
        "inputs": {
            "accuracy_grade": i.accuracy_grade,
            "face_width_mm": i.face_width_mm,
            "application_factor": i.application_factor,
            "tip_relief_um": r.tip_relief_um,
            "running_in_pitch_um": r.running_in_pitch_um,
            "running_in_profile_um": r.running_in_profile_um,
            "sigma_hlim_n_mm2": i.sigma_hlim_n_mm2,
        },
        "iso6336": {
            "contact_ratio": r.contact_ratio,
            "mesh_stiffness_n_mm_um": r.mesh_stiffness_n_mm_um,
            "single_stiffness_n_mm_um": r.single_stiffness_n_mm_um,
            "reduced_mass_kg_mm": r.reduced_mass_kg_mm,
            "line_load_n_mm": r.line_load_n_mm,
            "pitch_deviation_um": r.pitch_deviation_um,
            "profile_deviation_um": r.profile_deviation_um,
            "b_p": r.b_p,
            "b_f": r.b_f,
            "b_k": r.b_k,
            "n_s": r.n_s,
            "main_resonance_omega": [start, end],
            "resonance_omega": centre,
            "resonance_input_speed_rpm": v.rpm_at(centre),
        },
        "dynamic_factor": v.nonlinear.iter().map(|p| json!({
            "omega": p.0,
            "input_speed_rpm": v.rpm_at(p.0),
            "dynamic_factor": p.1,
            "kv_iso6336": v.kv_at(p.0),
        })).collect::<Vec<_>>(),
        "kv_iso6336": v.kv.iter().map(|l| l.iter().map(|p| [p.0, p.1]).collect::<Vec<_>>()).collect::<Vec<_>>(),
        "selected": {
            "omega": v.selected_omega,
            "input_speed_rpm": v.rpm_at(v.selected_omega),
            "dynamic_factor": v.selected.as_ref().and_then(|s| s.factor),
            "kv_iso6336": v.kv_at(v.selected_omega),
            "iso_range": v.range_at(v.selected_omega).name(),
            "resonance_ratio": v.n_at(v.selected_omega),
        },
        "load_sharing": {
            "phasing": v.phasing,
            "planets": v.planets,
            "kinds": v.sharing.iter().map(|k| json!({
                "kind": k.kind,
                "peak_force_n": k.peak_force_n,
                "factor": k.factor,
            })).collect::<Vec<_>>(),
            "over_speed": v.sharing_over_speed.iter().map(|s| json!({
                "omega": s.omega,
                "input_speed_rpm": v.rpm_at(s.omega),
                "kinds": s.kinds.iter().map(|k| json!({
                    "kind": k.kind,
                    "peak_force_n": k.peak_force_n,
                    "factor": k.factor,
                })).collect::<Vec<_>>(),
            })).collect::<Vec<_>>(),
        },
    })
}

#[cfg(test)]
mod tests;
