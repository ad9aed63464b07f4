//! The Campbell diagram's view model: the natural frequencies (Hz) of the
//! linear model against the input member's speed (rpm, from standstill to
//! the speed of the page's highest Omega), the lines of mesh orders 1 to
//! [`ORDERS`], and their crossings, the critical speeds, each with its
//! Omega so that a click on one selects that state. Its words (the plot's
//! text alternative, the caption under it) and its CSV.
//!
//! The frequencies and crossings are `solver::campbell`'s (modal analysis
//! of the mean-stiffness model, cheap enough for the main thread); this
//! module chooses what the page shows of them: the chart's frequency axis
//! reaches the highest order's mesh frequency at the top speed, so every
//! order line ends inside the plot, and only modes under it are drawn.

use crate::plots::PlotFrame;
use solver::campbell::{rpm_at, Campbell, CANCELLED};
use solver::modal::ModeKind;
use solver::model::Model;

/// The mesh orders the diagram draws, 1 ..= this.
pub const ORDERS: u32 = 4;

/// How many critical speeds the text alternative names.
pub const NAMED: usize = 3;

/// How close (pixels) a click must come to a crossing to pick it.
pub const PICK_PX: f64 = 12.0;

/// One natural frequency drawn as a horizontal line.
#[derive(Debug, Clone, PartialEq)]
pub struct CampbellMode {
    /// Natural frequency (Hz).
    pub frequency_hz: f64,
    /// Its place among the elastic frequencies, ascending (0 is the first).
    pub rank: usize,
    /// Rotational or planet mode.
    pub kind: ModeKind,
}

/// One critical speed: a mesh order crossing a natural frequency.
#[derive(Debug, Clone, PartialEq)]
pub struct CampbellCrossing {
    /// The mesh-frequency order.
    pub order: u32,
    /// The mode's place among the elastic frequencies (0 is the first).
    pub rank: usize,
    /// The mode's natural frequency (Hz).
    pub frequency_hz: f64,
    /// Input member speed (rpm).
    pub rpm: f64,
    /// Omega at that speed.
    pub omega: f64,
    /// Whether the meshes excite it (the planets' phasing does not cancel it).
    pub excited: bool,
}

/// What the Campbell plot draws.
#[derive(Debug, Clone, PartialEq)]
pub struct CampbellView {
    /// The top of the speed axis (rpm): the speed of the highest Omega.
    pub rpm_max: f64,
    /// The top of the frequency axis (Hz).
    pub hz_max: f64,
    /// Mesh frequency per input rpm (Hz / rpm): order `k` is `k` times it.
    pub mesh_hz_per_rpm: f64,
    /// The natural frequencies under `hz_max`, ascending.
    pub modes: Vec<CampbellMode>,
    /// The crossings, ascending in speed.
    pub crossings: Vec<CampbellCrossing>,
    /// The selected Omega's speed (rpm).
    pub selected_rpm: f64,
    /// The selected Omega.
    pub selected_omega: f64,
}

impl CampbellView {
    /// The diagram of `model` from standstill to the speed of `omega_max`,
    /// with `selected_omega` marked; a model the modal analysis refuses is
    /// the solver's reason.
    pub fn new(model: &Model, omega_max: f64, selected_omega: f64) -> Result<Self, String> {
        let rpm_max = rpm_at(model, omega_max);
        let c = Campbell::new(model, 0.0, rpm_max, ORDERS).map_err(|e| e.to_string())?;
        let hz_max = f64::from(ORDERS) * c.mesh_hz_per_rpm * rpm_max * 1.04;
        let modes = c
            .modes
            .iter()
            .enumerate()
            .filter(|(_, m)| m.frequency_hz <= hz_max)
            .map(|(rank, m)| CampbellMode {
                frequency_hz: m.frequency_hz,
                rank,
                kind: m.kind,
            })
            .collect();
        let crossings = c
            .crossings
            .iter()
            .filter(|x| x.rpm > 0.0)
            .map(|x| CampbellCrossing {
                order: x.order,
                rank: x.mode,
                frequency_hz: c.modes[x.mode].frequency_hz,
                rpm: x.rpm,
                omega: x.omega,
                excited: x.participation > CANCELLED,
            })
            .collect();
        Ok(CampbellView {
            rpm_max,
            hz_max,
            mesh_hz_per_rpm: c.mesh_hz_per_rpm,
            modes,
            crossings,
            selected_rpm: rpm_at(model, selected_omega),
            selected_omega,
        })
    }

    /// The crossing nearest the pixel `(px, py)` of a plot drawn with
    /// `frame`, if one is within [`PICK_PX`].
    pub fn pick(&self, frame: &PlotFrame, px: f64, py: f64) -> Option<&CampbellCrossing> {
        self.crossings
            .iter()
            .map(|c| {
                (
                    c,
                    frame
                        .to_px(c.rpm, c.frequency_hz)
                        .distance(glam::DVec2::new(px, py)),
                )
            })
            .filter(|(_, d)| *d <= PICK_PX)
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(c, _)| c)
    }

    /// The first [`NAMED`] excited critical speeds in words, for the
    /// caption and the plot's text alternative.
    pub fn label(&self) -> String {
        let excited: Vec<String> = self
            .crossings
            .iter()
            .filter(|c| c.excited)
            .take(NAMED)
            .map(crossing_words)
            .collect();
        let head = format!(
            "Campbell diagram: natural frequencies against input speed, 0 to {} rpm, with mesh orders 1 to {ORDERS}.",
            grouped(self.rpm_max)
        );
        if excited.is_empty() {
            format!("{head} No mesh order meets a natural frequency the meshes excite in this speed range.")
        } else {
            format!("{head} Critical speeds: {}.", excited.join("; "))
        }
    }
}

/// One critical speed in words: "order 1 meets the first mode (1 257 Hz)
/// at 1 197 rpm, Ω 0.232".
pub fn crossing_words(c: &CampbellCrossing) -> String {
    format!(
        "order {} meets the {} mode ({} Hz) at {} rpm, Ω {:.3}",
        c.order,
        ordinal(c.rank),
        grouped(c.frequency_hz),
        grouped(c.rpm),
        c.omega
    )
}

/// "first", "second", ... for a mode's place (0-based), then "11th".
pub fn ordinal(rank: usize) -> String {
    const WORDS: [&str; 10] = [
        "first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth", "ninth",
        "tenth",
    ];
    WORDS
        .get(rank)
        .map_or_else(|| format!("{}th", rank + 1), |w| (*w).to_string())
}

/// `x` rounded to a whole number, its thousands set apart by a no-break
/// space as people write them ("1 257").
pub fn grouped(x: f64) -> String {
    let n = x.round();
    if !n.is_finite() {
        return format!("{x}");
    }
    let digits = format!("{}", n.abs() as u64);
    let mut out = String::new();
    for (i, ch) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push('\u{a0}');
        }
        out.push(ch);
    }
    if n < 0.0 {
        format!("-{out}")
    } else {
        out
    }
}

/// The critical speeds as CSV, one row per crossing.
pub fn campbell_csv(v: &CampbellView) -> String {
    let mut s = String::from("order,mode,natural_frequency_hz,rpm,omega,excited\n");
    for c in &v.crossings {
        s.push_str(&format!(
            "{},{},{},{},{},{}\n",
            c.order,
            c.rank + 1,
            c.frequency_hz,
            c.rpm,
            c.omega,
            c.excited
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model(q: &str) -> Model {
        Model::new(&crate::link::decode(q).settings.params).unwrap()
    }

    /// Each crossing lies where order k's mesh frequency equals the
    /// natural frequency: f_n / k in Hz, omega_n / k in Omega.
    #[test]
    fn crossings_sit_at_the_natural_frequency_over_the_order() {
        let m = model("");
        let v = CampbellView::new(&m, 2.0, 0.5).unwrap();
        assert!(!v.crossings.is_empty());
        let elastic: Vec<f64> = {
            let mut f: Vec<(f64, f64)> = m
                .modes
                .elastic()
                .map(|x| (x.frequency_hz, x.omega))
                .collect();
            f.dedup_by(|a, b| (a.0 - b.0).abs() <= 1e-6 * b.0);
            f.iter().map(|x| x.1).collect()
        };
        for c in &v.crossings {
            let k = f64::from(c.order);
            let mesh_hz = c.rpm * v.mesh_hz_per_rpm;
            assert!((mesh_hz - c.frequency_hz / k).abs() <= 1e-9 * c.frequency_hz);
            assert!((c.omega - elastic[c.rank] / k).abs() <= 1e-9 * elastic[c.rank]);
            assert!(c.rpm > 0.0 && c.rpm <= v.rpm_max);
            assert!(c.frequency_hz <= v.hz_max);
        }
        assert!((v.selected_rpm - v.rpm_max * 0.25).abs() <= 1e-9 * v.rpm_max);
    }

    /// With sequential phasing of five planets, orders 1 to 4 excite no
    /// rotational mode: every crossing of a rotational mode is hollow.
    #[test]
    fn the_phasing_cancels_crossings_it_should() {
        let v = CampbellView::new(&model("planets=5&phasing=sequential"), 2.0, 0.5).unwrap();
        let rotational: Vec<&CampbellCrossing> = v
            .crossings
            .iter()
            .filter(|c| {
                v.modes
                    .iter()
                    .any(|m| m.rank == c.rank && m.kind == ModeKind::Rotational)
            })
            .collect();
        assert!(!rotational.is_empty());
        assert!(rotational.iter().all(|c| !c.excited));
    }

    #[test]
    fn the_label_names_the_first_critical_speeds_in_plain_words() {
        let c = CampbellCrossing {
            order: 1,
            rank: 0,
            frequency_hz: 1257.2,
            rpm: 1196.8,
            omega: 0.2321,
            excited: true,
        };
        assert_eq!(
            crossing_words(&c),
            "order 1 meets the first mode (1\u{a0}257 Hz) at 1\u{a0}197 rpm, Ω 0.232"
        );
        assert_eq!(grouped(1234567.4), "1\u{a0}234\u{a0}567");
        assert_eq!(grouped(999.6), "1\u{a0}000");
        assert_eq!(ordinal(11), "12th");
        let v = CampbellView::new(&model(""), 2.0, 0.5).unwrap();
        let label = v.label();
        assert!(label.starts_with("Campbell diagram: natural frequencies"));
        let first = v.crossings.iter().find(|c| c.excited).unwrap();
        assert!(label.contains(&crossing_words(first)), "{label}");
        assert!(label.matches(" meets ").count() <= NAMED);
        assert_eq!(campbell_csv(&v).lines().count(), v.crossings.len() + 1);
    }

    #[test]
    fn a_click_near_a_crossing_picks_it() {
        let v = CampbellView::new(&model(""), 2.0, 0.5).unwrap();
        let frame = PlotFrame {
            top_left: glam::DVec2::new(80.0, 40.0),
            bottom_right: glam::DVec2::new(740.0, 300.0),
            x_range: (0.0, v.rpm_max),
            y_range: (0.0, v.hz_max),
        };
        let c = &v.crossings[0];
        let p = frame.to_px(c.rpm, c.frequency_hz);
        assert_eq!(v.pick(&frame, p.x + 3.0, p.y - 2.0), Some(c));
        // At standstill, the top of the axis: no crossing is near.
        assert_eq!(v.pick(&frame, 80.0, 40.0), None);
    }
}
