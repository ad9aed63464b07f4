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

pub use crate::speed::grouped;
use crate::speed::{AxisUnit, SpeedAxis};
use solver::campbell::{rpm_at, Campbell, CANCELLED};
use solver::modal::ModeKind;
use solver::model::Model;
use solver::params::{ModelParams, Phasing};

/// The mesh orders the diagram draws, 1 ..= this.
pub const ORDERS: u32 = 4;

/// How many critical speeds the text alternative names.
pub const NAMED: usize = 3;

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

/// A planet-pass order crossing a natural frequency.
#[derive(Debug, Clone, PartialEq)]
pub struct PassCrossing {
    /// The planet-pass order.
    pub order: u32,
    /// The mode's place among the elastic frequencies (0 is the first).
    pub rank: usize,
    /// The mode's natural frequency (Hz).
    pub frequency_hz: f64,
    /// Input member speed (rpm).
    pub rpm: f64,
    /// Omega at that speed.
    pub omega: f64,
}

/// The planet-pass orders, drawn with sequentially phased planets.
#[derive(Debug, Clone, PartialEq)]
pub struct PlanetPassLines {
    /// Planets N.
    pub planets: u32,
    /// Planet-pass frequency (order 1) per input rpm (Hz / rpm).
    pub hz_per_rpm: f64,
    /// Its crossings of the drawn modes, ascending in speed.
    pub crossings: Vec<PassCrossing>,
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
    /// What its speed axis shows (Ω or rpm; the data are rpm).
    pub speed: SpeedAxis,
    /// The planet-pass orders 1 ..= [`ORDERS`], with sequential phasing.
    pub planet_pass: Option<PlanetPassLines>,
}

impl CampbellView {
    /// The diagram of `model` from standstill to the speed of `omega_max`,
    /// with `selected_omega` marked; a model the modal analysis refuses is
    /// the solver's reason.
    pub fn new(
        model: &Model,
        omega_max: f64,
        selected_omega: f64,
    ) -> Result<Self, super::ViewError> {
        let rpm_max = rpm_at(model, omega_max);
        let c = Campbell::new(model, 0.0, rpm_max, ORDERS)?;
        // Up to the highest mode an order can reach, so that the crossings
        // spread over the plot; the order lines are cut where they leave it.
        let reach = f64::from(ORDERS) * c.mesh_hz_per_rpm * rpm_max;
        let top_mode = c
            .modes
            .iter()
            .map(|m| m.frequency_hz)
            .filter(|f| *f <= reach)
            .fold(0.0, f64::max);
        let hz_max = if top_mode > 0.0 {
            (top_mode * 1.12).min(reach * 1.04)
        } else {
            reach * 1.04
        };
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
            speed: SpeedAxis::new(AxisUnit::Omega, Some(model)),
            planet_pass: None,
        })
    }

    /// The diagram with the planet-pass orders of the set `params` when its
    /// planets are sequentially phased (`solver::campbell`: `N` planets on
    /// the carrier, the ring held); unchanged otherwise.
    pub fn with_planet_pass(
        mut self,
        model: &Model,
        params: &ModelParams,
    ) -> Result<Self, super::ViewError> {
        let ModelParams::Ravigneaux(p) = params else {
            return Ok(self);
        };
        if p.phasing != Phasing::Sequential {
            return Ok(self);
        }
        let carrier = model.system.speed.carrier_per_input();
        let c = Campbell::new(model, 0.0, self.rpm_max, ORDERS)
            .and_then(|c| c.with_planet_pass(p.planets, carrier, ORDERS))?;
        let Some(pp) = &c.planet_pass else {
            return Ok(self);
        };
        let crossings = pp
            .crossings
            .iter()
            .filter(|x| x.rpm > 0.0 && c.modes[x.mode].frequency_hz <= self.hz_max)
            .map(|x| PassCrossing {
                order: x.order,
                rank: x.mode,
                frequency_hz: c.modes[x.mode].frequency_hz,
                rpm: x.rpm,
                omega: x.omega,
            })
            .collect();
        self.planet_pass = Some(PlanetPassLines {
            planets: pp.planets,
            hz_per_rpm: pp.hz_per_rpm,
            crossings,
        });
        Ok(self)
    }

    /// The planet-pass crossings in words, if the diagram has the orders.
    pub fn pass_words(&self) -> Option<String> {
        let pp = self.planet_pass.as_ref()?;
        let head = format!(
            "Planet-pass orders ({} planets passing the ring, {} Hz per 1 000 rpm at order 1):",
            pp.planets,
            crate::words::short(pp.hz_per_rpm * 1000.0)
        );
        let body = if pp.crossings.is_empty() {
            " none meets a drawn mode in this speed range.".to_string()
        } else {
            let named: Vec<String> = pp
                .crossings
                .iter()
                .take(NAMED)
                .map(|c| {
                    format!(
                        " planet-pass order {} meets the {} mode ({} Hz) at {} rpm",
                        c.order,
                        ordinal(c.rank),
                        grouped(c.frequency_hz),
                        grouped(c.rpm)
                    )
                })
                .collect();
            format!("{}.", named.join(";"))
        };
        Some(format!(
            "{head}{body} Nothing in the model excites them (it has no carrier or planet position errors); they mark where a real gearbox's would meet a mode."
        ))
    }

    /// The excited critical speeds in the order the label names them:
    /// the lowest order first (the mesh frequency itself excites most),
    /// each order's from the slowest.
    pub fn by_order(&self) -> Vec<&CampbellCrossing> {
        let mut v: Vec<&CampbellCrossing> = self.crossings.iter().filter(|c| c.excited).collect();
        v.sort_by(|a, b| a.order.cmp(&b.order).then(a.rpm.total_cmp(&b.rpm)));
        v
    }

    /// The first [`NAMED`] excited critical speeds of [`Self::by_order`]
    /// in words, for the caption and the plot's text alternative.
    pub fn label(&self) -> String {
        let excited: Vec<String> = self
            .by_order()
            .into_iter()
            .take(NAMED)
            .map(crossing_words)
            .collect();
        let head = format!(
            "Campbell diagram: natural frequencies against input speed, 0 to {} rpm, with mesh orders 1 to {ORDERS}.",
            grouped(self.rpm_max)
        );
        format!("{head} {}", self.note_with(&excited))
    }

    /// The note over the plot: the first critical speeds in words.
    pub fn note(&self) -> String {
        let excited: Vec<String> = self
            .by_order()
            .into_iter()
            .take(NAMED)
            .map(crossing_words)
            .collect();
        self.note_with(&excited)
    }

    fn note_with(&self, excited: &[String]) -> String {
        let mesh = if excited.is_empty() {
            "No mesh order meets a natural frequency the meshes excite in this speed range.".into()
        } else {
            format!(
                "Critical speeds, lowest order first: {}.",
                excited.join("; ")
            )
        };
        match self.pass_words() {
            Some(p) => format!("{mesh} {p}"),
            None => mesh,
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

/// The critical speeds as CSV, one row per crossing: the mesh orders',
/// then the planet-pass orders' (`line` says which; never excited by the
/// model).
pub fn campbell_csv(v: &CampbellView) -> String {
    let mut s = String::from("order,mode,natural_frequency_hz,rpm,omega,excited,line\n");
    for c in &v.crossings {
        s.push_str(&format!(
            "{},{},{},{},{},{},mesh order\n",
            c.order,
            c.rank + 1,
            c.frequency_hz,
            c.rpm,
            c.omega,
            c.excited
        ));
    }
    for c in v.planet_pass.iter().flat_map(|p| &p.crossings) {
        s.push_str(&format!(
            "{},{},{},{},{},false,planet-pass order\n",
            c.order,
            c.rank + 1,
            c.frequency_hz,
            c.rpm,
            c.omega
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
        let first = v.by_order()[0];
        assert_eq!((first.order, first.rank), (1, 0));
        assert!(label.contains(&crossing_words(first)), "{label}");
        assert!(label.matches(" meets ").count() <= NAMED);
        assert_eq!(campbell_csv(&v).lines().count(), v.crossings.len() + 1);
    }

    /// Sequentially phased planets add the planet-pass orders: order m at
    /// m N 3/4 / 60 Hz per rpm (the carrier turning 36 / (36 - 84) times
    /// the small sun), each crossing at f_n over that; in phase, none.
    #[test]
    fn sequential_planets_draw_the_planet_pass_orders() {
        let q = "planets=5&phasing=sequential";
        let m = model(q);
        let p = crate::link::decode(q).settings.params;
        let v = CampbellView::new(&m, 2.0, 0.5)
            .unwrap()
            .with_planet_pass(&m, &p)
            .unwrap();
        let pp = v.planet_pass.as_ref().unwrap();
        assert!((pp.hz_per_rpm - 5.0 * 0.75 / 60.0).abs() <= 1e-15);
        assert!(!pp.crossings.is_empty());
        for c in &pp.crossings {
            let rpm = c.frequency_hz / (f64::from(c.order) * pp.hz_per_rpm);
            assert!((c.rpm - rpm).abs() <= 1e-9 * rpm, "{c:?}");
            assert!(c.rpm <= v.rpm_max && c.frequency_hz <= v.hz_max);
        }
        assert!(v.note().contains("planet-pass order"), "{}", v.note());
        assert!(campbell_csv(&v).contains(",planet-pass order\n"));
        let q = "planets=5&phasing=in-phase";
        let p = crate::link::decode(q).settings.params;
        let m = model(q);
        let v = CampbellView::new(&m, 2.0, 0.5)
            .unwrap()
            .with_planet_pass(&m, &p)
            .unwrap();
        assert!(v.planet_pass.is_none() && !v.note().contains("planet-pass"));
    }
}
