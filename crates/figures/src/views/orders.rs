//! The mesh force by order's view model (`ViewId::Orders`): at the
//! selected speed, the plotted mesh's force spectrum in orders of the mesh
//! frequency (order 1 is the mesh frequency; `solver::orders`, computed by
//! the selected-Omega job) with its peaks labelled "1×", "1/2×", and the
//! force summed over the planets' meshes of its kind, drawn per planet
//! (the sum over N) so that in phase it lies on the one mesh's lines and
//! sequential phasing shows as the lines it cancels. Its words (the note
//! over the plot, its text alternative), CSV and JSON.

use serde_json::json;
use solver::params::ModelParams;

use super::csv_num;
use super::dynamic::kind_words;
use crate::protocol::{ForceByOrder, OmegaResult, OrderPeak};
use crate::speed::grouped;

/// How many peaks the words name.
pub const NAMED: usize = 6;

/// The sum over the planets, as drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct SumView {
    /// The mesh kind's key.
    pub kind: String,
    /// Planets summed.
    pub planets: usize,
    /// The sum over the planets divided by their number, at each order
    /// above 0: `(order, N)`.
    pub lines: Vec<(f64, f64)>,
    /// The sum's labelled peaks (amplitudes of the sum, N).
    pub peaks: Vec<OrderPeak>,
    /// The whole orders the phasing cancels.
    pub cancelled: Vec<u32>,
}

/// What the plot of the mesh force by order draws and says.
#[derive(Debug, Clone, PartialEq)]
pub struct OrdersView {
    /// The selected Omega.
    pub omega: f64,
    /// The input member's speed there (rpm).
    pub rpm: f64,
    /// The plotted mesh's name.
    pub mesh_name: String,
    /// The state is the page's short preview run.
    pub preview: bool,
    /// Mesh periods recorded.
    pub record_periods: u32,
    /// The mean force (N).
    pub mean_n: f64,
    /// The mesh force's lines above order 0: `(order, N)`.
    pub lines: Vec<(f64, f64)>,
    /// Its labelled peaks.
    pub peaks: Vec<OrderPeak>,
    /// The planets' sum, for the compound set.
    pub sum: Option<SumView>,
    /// "in-phase" or "sequential" (`None`: the gear pair).
    pub phasing: Option<&'static str>,
    /// Whether one relabelling of the planets shifts every kind's phase
    /// alike (`z_s1`, `z_s2` and `-z_r` equal modulo N): then planet n's
    /// motion is planet 1's shifted in time and the cancelled orders leave
    /// nothing in the sum.
    pub alike: bool,
}

impl OrdersView {
    /// The view of the selected state `r` (its force by order) of the set
    /// `params`, with `rpm_per_omega` the input speed per unit Omega;
    /// `None` before the state has its force by order.
    pub fn new(r: &OmegaResult, params: &ModelParams, rpm_per_omega: f64) -> Option<Self> {
        let f: &ForceByOrder = r.force_orders.as_ref()?;
        let above = |amp: &[f64], scale: f64| -> Vec<(f64, f64)> {
            f.order
                .iter()
                .zip(amp)
                .filter(|(o, _)| **o > 0.0)
                .map(|(&o, &a)| (o, a / scale))
                .collect()
        };
        let (phasing, alike) = match params {
            ModelParams::Ravigneaux(p) => {
                let n = i64::from(p.planets.max(1));
                let m = |z: i64| z.rem_euclid(n);
                let alike = m(i64::from(p.teeth_s1)) == m(i64::from(p.teeth_s2))
                    && m(i64::from(p.teeth_s1)) == m(-i64::from(p.teeth_r));
                (Some(p.phasing.name()), alike)
            }
            ModelParams::GearPair(_) => (None, true),
        };
        Some(OrdersView {
            omega: r.omega,
            rpm: r.omega * rpm_per_omega,
            mesh_name: r.mesh_name.clone(),
            preview: r.preview,
            record_periods: f.record_periods,
            mean_n: f.amplitude_n.first().copied().unwrap_or(0.0),
            lines: above(&f.amplitude_n, 1.0),
            peaks: f.peaks.clone(),
            sum: f.sum.as_ref().map(|s| SumView {
                kind: s.kind.clone(),
                planets: s.planets,
                lines: above(&s.amplitude_n, s.planets.max(1) as f64),
                peaks: s.peaks.clone(),
                cancelled: s.cancelled.clone(),
            }),
            phasing,
            alike,
        })
    }

    /// The largest amplitude drawn (N), of either series.
    pub fn top_n(&self) -> f64 {
        let sum = self.sum.iter().flat_map(|s| s.lines.iter());
        self.lines
            .iter()
            .chain(sum)
            .fold(0.0, |m: f64, l| m.max(l.1))
    }

    /// The note over the plot: the largest lines in words, then what the
    /// planets' sum keeps and what the phasing cancels.
    pub fn note(&self) -> String {
        let mut named: Vec<&OrderPeak> = self.peaks.iter().collect();
        named.sort_by(|a, b| b.amplitude_n.total_cmp(&a.amplitude_n));
        named.truncate(NAMED);
        named.sort_by(|a, b| a.order.total_cmp(&b.order));
        let lines = if named.is_empty() {
            "no line above 1 % of the largest".to_string()
        } else {
            named
                .iter()
                .map(|p| format!("{} {} N", p.label, grouped(p.amplitude_n)))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let fractional = self.peaks.iter().filter(|p| !p.whole).count();
        let sub = if fractional > 0 {
            format!(
                " {fractional} of the labelled lines lie between the mesh orders: the motion repeats only every few mesh periods, or not at all."
            )
        } else {
            String::new()
        };
        let preview = if self.preview { "Preview: " } else { "" };
        format!(
            "{preview}Mesh {} at Ω {:.3} ({} rpm): mean force {} N; its lines by order of the mesh frequency: {lines}.{sub} {}",
            self.mesh_name,
            self.omega,
            grouped(self.rpm),
            grouped(self.mean_n),
            self.sum_words()
        )
    }

    /// What the planets' sum keeps and cancels, in words.
    pub fn sum_words(&self) -> String {
        let (Some(s), Some(phasing)) = (&self.sum, self.phasing) else {
            return "The gear pair has one mesh: no planets to sum.".into();
        };
        let kept: Vec<String> = s
            .peaks
            .iter()
            .map(|p| format!("{} {} N", p.label, grouped(p.amplitude_n)))
            .collect();
        let kept = if kept.is_empty() {
            "no line above 1 % of its largest".into()
        } else {
            kept.join(", ")
        };
        let cancelled: Vec<String> = s.cancelled.iter().map(|k| format!("{k}×")).collect();
        let rule = if cancelled.is_empty() {
            "the phasing cancels no mesh order".to_string()
        } else {
            format!(
                "the phasing cancels mesh orders {} in it (order k survives when k times the central member's teeth over {} is whole)",
                cancelled.join(", "),
                s.planets
            )
        };
        let left = s
            .peaks
            .iter()
            .any(|p| p.whole && s.cancelled.contains(&(p.order.round() as u32)));
        let why = if left && !self.alike {
            " Lines remain at cancelled orders because the suns' and the ring's teeth differ modulo the number of planets, so one planet's motion is not the next one's shifted in time."
        } else {
            ""
        };
        format!(
            "Summed over the {} planets' {} meshes ({phasing} phasing; drawn divided by {}): {kept}; {rule}.{why}",
            s.planets,
            kind_words(&s.kind),
            s.planets
        )
    }

    /// The text alternative of the plot.
    pub fn label(&self) -> String {
        format!(
            "Mesh force by order: amplitude (N) against the order of the mesh frequency, over {} recorded mesh periods. {}",
            self.record_periods,
            self.note()
        )
    }
}

/// The lines as CSV: the order, the mesh's amplitude, and the planets'
/// sum over their number (blank for the gear pair).
pub fn orders_csv(v: &OrdersView) -> String {
    let mut out = String::from("order,amplitude_n,planets_sum_per_planet_n\n");
    out.push_str(&format!("0,{},\n", csv_num(v.mean_n)));
    for (i, (o, a)) in v.lines.iter().enumerate() {
        let s = v
            .sum
            .as_ref()
            .and_then(|s| s.lines.get(i))
            .map_or(String::new(), |l| csv_num(l.1));
        out.push_str(&format!("{},{},{s}\n", csv_num(*o), csv_num(*a)));
    }
    out
}

fn peaks_json(p: &[OrderPeak]) -> serde_json::Value {
    p.iter()
        .map(|p| json!({"order": p.order, "label": p.label, "whole": p.whole, "amplitude_n": p.amplitude_n}))
        .collect()
}

/// The view as JSON: the state, both series and their labelled peaks.
pub fn orders_json(v: &OrdersView) -> serde_json::Value {
    json!({
        "omega": v.omega,
        "input_speed_rpm": v.rpm,
        "mesh": v.mesh_name,
        "record_periods": v.record_periods,
        "mean_force_n": v.mean_n,
        "order": v.lines.iter().map(|l| l.0).collect::<Vec<_>>(),
        "amplitude_n": v.lines.iter().map(|l| l.1).collect::<Vec<_>>(),
        "peaks": peaks_json(&v.peaks),
        "planet_sum": v.sum.as_ref().map(|s| json!({
            "kind": s.kind,
            "planets": s.planets,
            "phasing": v.phasing,
            "per_planet_n": s.lines.iter().map(|l| l.1).collect::<Vec<_>>(),
            "peaks": peaks_json(&s.peaks),
            "cancelled_orders": s.cancelled,
        })),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::PlanetSumOrders;

    fn peak(order: f64, label: &str, amplitude_n: f64) -> OrderPeak {
        OrderPeak {
            order,
            label: label.into(),
            whole: (order - order.round()).abs() < 1e-12,
            amplitude_n,
        }
    }

    /// A period-2 state on five sequential planets: the words name the
    /// half order, the cancelled orders and why lines remain at them.
    #[test]
    fn the_words_name_the_orders_and_the_phasing() {
        let mut r = super::super::test_support::omega_result();
        let order: Vec<f64> = (0..=8).map(|k| f64::from(k) * 0.5).collect();
        let amp = vec![20_000.0, 500.0, 3000.0, 0.0, 1000.0, 0.0, 0.0, 0.0, 0.0];
        r.force_orders = Some(ForceByOrder {
            record_periods: 2,
            order,
            amplitude_n: amp.clone(),
            peaks: vec![
                peak(0.5, "1/2×", 500.0),
                peak(1.0, "1×", 3000.0),
                peak(2.0, "2×", 1000.0),
            ],
            sum: Some(PlanetSumOrders {
                kind: "s1a".into(),
                planets: 5,
                amplitude_n: amp.iter().map(|a| a * 0.1).collect(),
                peaks: vec![peak(2.0, "2×", 100.0)],
                phasing: vec![0.0, 0.0, 0.0, 0.0],
                cancelled: vec![1, 2, 3, 4],
            }),
        });
        let p = crate::link::decode("planets=5&phasing=sequential")
            .settings
            .params;
        let v = OrdersView::new(&r, &p, 5000.0).unwrap();
        assert!(!v.alike, "36, 48, -84 modulo 5: 1, 3, 1");
        assert_eq!(v.lines.len(), 8);
        let s = v.sum.as_ref().unwrap();
        assert!((s.lines[3].1 - 100.0 / 5.0).abs() < 1e-12, "{:?}", s.lines);
        let note = v.note();
        for want in [
            "1/2× 500 N",
            "1× 3\u{a0}000 N",
            "2× 1\u{a0}000 N",
            "mesh orders 1×, 2×, 3×, 4×",
            "between the mesh orders",
            "Lines remain",
        ] {
            assert!(note.contains(want), "{want}: {note}");
        }
        let csv = orders_csv(&v);
        assert!(
            csv.starts_with("order,amplitude_n,planets_sum_per_planet_n\n0,20000,\n0.5,500,10\n"),
            "{csv}"
        );
        assert_eq!(orders_json(&v)["peaks"][0]["label"], "1/2×");
        // Teeth alike modulo 5 (46 ≡ 1): no "why".
        let p = crate::link::decode("planets=5&phasing=sequential&teeth_s2=46")
            .settings
            .params;
        assert!(OrdersView::new(&r, &p, 5000.0).unwrap().alike);
    }
}
