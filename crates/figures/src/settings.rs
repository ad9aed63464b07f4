//! Everything a link restores: the model parameters (the solver's flat keys,
//! as on the CLI) and the page's own view options (frequency range, grid
//! sizes, periods, harmonics, plotted mesh, selected Omega).
//!
//! View options have their own small key table, [`VIEW_KEYS`], with ranges
//! that cap every job: no link can start an unbounded computation.

use crate::protocol::{JobKind as K, KindSet};
use crate::speed::AxisUnit;
use solver::iso6336::IsoInputs;
use solver::model::Model;
use solver::params::ModelParams;
use solver::sweep::Directions;

/// Why a view key's text was refused, in the link's terms (the page says
/// it in words with [`crate::words::must_be`]).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ViewKeyError {
    /// No view key has this name.
    #[error("unknown key `{key}`")]
    Unknown {
        /// The name as given (shortened).
        key: String,
    },
    /// Not a value of the key's type, or outside its range.
    #[error("{key} = {value} is out of range: allowed {allowed}")]
    OutOfRange {
        /// The key.
        key: String,
        /// The text as given (shortened).
        value: String,
        /// The allowed range or words.
        allowed: String,
    },
    /// A mesh the model does not have.
    #[error("mesh = {value} is not a mesh of this model: allowed {meshes}, worst")]
    NotAMesh {
        /// The text as given (shortened).
        value: String,
        /// The model's meshes, comma separated.
        meshes: String,
    },
}

/// The type and range of a view option.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ViewType {
    /// A finite number in `min ..= max`.
    Float {
        /// Smallest allowed value.
        min: f64,
        /// Largest allowed value.
        max: f64,
    },
    /// An integer in `min ..= max`.
    Int {
        /// Smallest allowed value.
        min: u32,
        /// Largest allowed value.
        max: u32,
    },
    /// One of some words.
    Choice(&'static [&'static str]),
    /// A mesh name of the current model, or `worst`.
    Mesh,
}

impl ViewType {
    /// The allowed values in words.
    pub fn allowed(&self) -> String {
        match self {
            ViewType::Float { min, max } => format!("{min} ..= {max}"),
            ViewType::Int { min, max } => format!("integer {min} ..= {max}"),
            ViewType::Choice(w) => format!("one of {}", w.join(", ")),
            ViewType::Mesh => "a mesh name of the model (e.g. s1a1, s2b2, a3b3, rb1; pg for the gear pair) or worst".into(),
        }
    }
}

/// Where a view option lives in [`ViewOptions`]: its getter and setter.
#[derive(Clone, Copy)]
pub enum Field {
    /// A number.
    Num(fn(&ViewOptions) -> f64, fn(&mut ViewOptions, f64)),
    /// A count.
    Count(fn(&ViewOptions) -> u32, fn(&mut ViewOptions, u32)),
    /// A word (a choice or a mesh name), set from checked text.
    Word(fn(&ViewOptions) -> String, fn(&mut ViewOptions, &str)),
}

impl std::fmt::Debug for Field {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Field::Num(..) => "Num",
            Field::Count(..) => "Count",
            Field::Word(..) => "Word",
        })
    }
}

/// One view option key: its link name, unit, type and range, words, where
/// it lives, and the jobs a change of it restarts (every view is redrawn
/// regardless: they share the mesh and the range).
#[derive(Debug, Clone, Copy)]
pub struct ViewKey {
    /// The key in links.
    pub name: &'static str,
    /// Unit, `-` if none.
    pub unit: &'static str,
    /// Type and range.
    pub ty: ViewType,
    /// One line for tooltips.
    pub description: &'static str,
    /// Its getter and setter.
    pub field: Field,
    /// The job kinds a change restarts.
    pub restarts: KindSet,
}

/// Largest nominal point count of the harmonic-balance branch.
pub const MAX_FR_POINTS: u32 = 400;
/// Largest time-integration overlay grid of the frequency response.
pub const MAX_FR_TI_POINTS: u32 = 200;
/// Most harmonics of the harmonic-balance branch (the work grows like H^3).
pub const MAX_HARMONICS: u32 = 15;
/// Largest Omega grid of the bifurcation diagram.
pub const MAX_BIF_POINTS: u32 = 1000;
/// Largest transient of one steady state (mesh periods).
pub const MAX_TRANSIENT: u32 = 3000;
/// Largest record of one steady state (mesh periods).
pub const MAX_RECORD: u32 = 1000;
/// Most Omega columns of the impact-regime map.
pub const MAX_MAP_OMEGA_POINTS: u32 = 200;
/// Most value rows of the impact-regime map.
pub const MAX_MAP_VALUE_POINTS: u32 = 100;
/// Most Omega points of the Lyapunov-exponent curve.
pub const MAX_LYAP_POINTS: u32 = 400;
/// The keys an impact-regime map can run over (its rows).
pub const MAP_KEYS: &[&str] = &["backlash_um", "te_um"];

/// The default value range of a map key's rows (um).
pub fn map_default_range(key: &str) -> (f64, f64) {
    match key {
        "te_um" => (0.0, 60.0),
        _ => (0.0, 200.0),
    }
}

const OMEGA: ViewType = ViewType::Float {
    min: 0.01,
    max: 20.0,
};

/// The view option keys, in link order.
pub const VIEW_KEYS: &[ViewKey] = &[
    ViewKey {
        name: "omega",
        field: Field::Num(|v| v.omega, |v, x| v.omega = x),
        restarts: KindSet::of(&[K::Omega]),
        unit: "-",
        ty: OMEGA,
        description: "selected dimensionless mesh frequency Omega for the phase portrait, Poincaré section, history and spectrum",
    },
    ViewKey {
        name: "mesh",
        field: Field::Word(|v| v.mesh.text().to_string(), |v, t| v.mesh = if t == "worst" { MeshSel::Worst } else { MeshSel::Named(t.to_string()) }),
        restarts: KindSet::of(&[K::Omega, K::Map, K::Boundaries]),
        unit: "-",
        ty: ViewType::Mesh,
        description: "which mesh to plot, or the worst mesh at each Ω: the mesh with the largest dynamic factor (the peak mesh force over the static one); the frequency response instead plots the mesh with the largest peak-to-peak x and says so in its title",
    },
    ViewKey {
        name: "omega_from",
        field: Field::Num(|v| v.omega_from, |v, x| v.omega_from = x),
        restarts: KindSet::ALL,
        unit: "-",
        ty: OMEGA,
        description: "lowest Omega of the frequency response and bifurcation diagram",
    },
    ViewKey {
        name: "omega_to",
        field: Field::Num(|v| v.omega_to, |v, x| v.omega_to = x),
        restarts: KindSet::ALL,
        unit: "-",
        ty: OMEGA,
        description: "highest Omega of the frequency response and bifurcation diagram",
    },
    ViewKey {
        name: "fr_points",
        field: Field::Count(|v| v.fr_points, |v, n| v.fr_points = n),
        restarts: KindSet::of(&[K::HarmonicBalance]),
        unit: "-",
        ty: ViewType::Int {
            min: 2,
            max: MAX_FR_POINTS,
        },
        description: "nominal points of the harmonic-balance frequency response (largest continuation step = range / points; resonances get more)",
    },
    ViewKey {
        name: "fr_ti_points",
        field: Field::Count(|v| v.fr_ti_points, |v, n| v.fr_ti_points = n),
        restarts: KindSet::of(&[K::Overlay]),
        unit: "-",
        ty: ViewType::Int {
            min: 0,
            max: MAX_FR_TI_POINTS,
        },
        description: "Omega points of a time-integration run of its own for the frequency response's dots (0: the dots are the bifurcation sweep's steady states)",
    },
    ViewKey {
        name: "fr_record_periods",
        field: Field::Count(|v| v.fr_record_periods, |v, n| v.fr_record_periods = n),
        restarts: KindSet::of(&[K::Overlay]),
        unit: "periods",
        ty: ViewType::Int { min: 1, max: 200 },
        description: "recorded mesh periods per time-integration overlay point of the frequency response",
    },
    ViewKey {
        name: "bif_points",
        field: Field::Count(|v| v.bif_points, |v, n| v.bif_points = n),
        restarts: KindSet::of(&[K::Bif]),
        unit: "-",
        ty: ViewType::Int {
            min: 2,
            max: MAX_BIF_POINTS,
        },
        description: "Omega points of the bifurcation diagram",
    },
    ViewKey {
        name: "bif_dir",
        field: Field::Word(|v| v.bif_dir.name().to_string(), |v, t| v.bif_dir = Directions::from_name(t).unwrap_or(v.bif_dir)),
        restarts: KindSet::of(&[K::Bif]),
        unit: "-",
        ty: ViewType::Choice(&["up", "down", "both"]),
        description: "bifurcation sweep direction: up, down, or up then down",
    },
    ViewKey {
        name: "transient_periods",
        field: Field::Count(|v| v.transient_periods, |v, n| v.transient_periods = n),
        restarts: KindSet::of(&[K::Omega, K::Overlay, K::Bif]),
        unit: "periods",
        ty: ViewType::Int {
            min: 0,
            max: MAX_TRANSIENT,
        },
        description: "maximum transient mesh periods per steady state (ends early once settled)",
    },
    ViewKey {
        name: "record_periods",
        field: Field::Count(|v| v.record_periods, |v, n| v.record_periods = n),
        restarts: KindSet::of(&[K::Omega, K::Bif]),
        unit: "periods",
        ty: ViewType::Int {
            min: 1,
            max: MAX_RECORD,
        },
        description: "recorded mesh periods per steady state (Poincaré samples, history)",
    },
    ViewKey {
        name: "harmonics",
        field: Field::Count(|v| v.harmonics, |v, n| v.harmonics = n),
        restarts: KindSet::of(&[K::HarmonicBalance, K::Boundaries]),
        unit: "-",
        ty: ViewType::Int {
            min: 1,
            max: MAX_HARMONICS,
        },
        description: "harmonics H of the harmonic-balance frequency response",
    },
    ViewKey {
        name: "map_key",
        field: Field::Word(|v| v.map_key.clone(), |v, t| v.map_key = t.to_string()),
        restarts: KindSet::of(&[K::Map, K::Boundaries]),
        unit: "-",
        ty: ViewType::Choice(MAP_KEYS),
        description: "the parameter on the vertical axis of the impact-regime map: backlash b or TE amplitude",
    },
    ViewKey {
        name: "map_from",
        field: Field::Num(|v| v.map_from, |v, x| v.map_from = x),
        restarts: KindSet::of(&[K::Map, K::Boundaries]),
        unit: "um",
        ty: ViewType::Float {
            min: 0.0,
            max: 1000.0,
        },
        description: "lowest value of the map's parameter (bottom row)",
    },
    ViewKey {
        name: "map_to",
        field: Field::Num(|v| v.map_to, |v, x| v.map_to = x),
        restarts: KindSet::of(&[K::Map, K::Boundaries]),
        unit: "um",
        ty: ViewType::Float {
            min: 0.0,
            max: 1000.0,
        },
        description: "highest value of the map's parameter (top row)",
    },
    ViewKey {
        name: "map_omega_points",
        field: Field::Count(|v| v.map_omega_points, |v, n| v.map_omega_points = n),
        restarts: KindSet::of(&[K::Map]),
        unit: "-",
        ty: ViewType::Int {
            min: 2,
            max: MAX_MAP_OMEGA_POINTS,
        },
        description: "Omega columns of the impact-regime map (over the frequency range)",
    },
    ViewKey {
        name: "map_value_points",
        field: Field::Count(|v| v.map_value_points, |v, n| v.map_value_points = n),
        restarts: KindSet::of(&[K::Map]),
        unit: "-",
        ty: ViewType::Int {
            min: 1,
            max: MAX_MAP_VALUE_POINTS,
        },
        description: "rows of the impact-regime map (values of its parameter)",
    },
    ViewKey {
        name: "map_transient_periods",
        field: Field::Count(|v| v.map_transient_periods, |v, n| v.map_transient_periods = n),
        restarts: KindSet::of(&[K::Map]),
        unit: "periods",
        ty: ViewType::Int {
            min: 0,
            max: MAX_TRANSIENT,
        },
        description: "maximum transient mesh periods per map cell (ends early once settled)",
    },
    ViewKey {
        name: "map_record_periods",
        field: Field::Count(|v| v.map_record_periods, |v, n| v.map_record_periods = n),
        restarts: KindSet::of(&[K::Map]),
        unit: "periods",
        ty: ViewType::Int {
            min: 1,
            max: MAX_RECORD,
        },
        description: "recorded mesh periods per map cell (regime and period detection)",
    },
    ViewKey {
        name: "lyap_points",
        field: Field::Count(|v| v.lyap_points, |v, n| v.lyap_points = n),
        restarts: KindSet::of(&[K::Lyap]),
        unit: "-",
        ty: ViewType::Int {
            min: 0,
            max: MAX_LYAP_POINTS,
        },
        description: "Omega points of the largest Lyapunov exponent under the bifurcation diagram (0 = off)",
    },
    ViewKey {
        name: "lyap_transient_periods",
        field: Field::Count(|v| v.lyap_transient_periods, |v, n| v.lyap_transient_periods = n),
        restarts: KindSet::of(&[K::Lyap]),
        unit: "periods",
        ty: ViewType::Int {
            min: 0,
            max: MAX_TRANSIENT,
        },
        description: "transient mesh periods before the Lyapunov exponent is measured (ends early once settled)",
    },
    ViewKey {
        name: "lyap_periods",
        field: Field::Count(|v| v.lyap_periods, |v, n| v.lyap_periods = n),
        restarts: KindSet::of(&[K::Lyap]),
        unit: "periods",
        ty: ViewType::Int {
            min: 10,
            max: MAX_RECORD,
        },
        description: "mesh periods over which the Lyapunov exponent is averaged",
    },
    ViewKey {
        name: "branches",
        field: Field::Word(|v| if v.branches { "on" } else { "off" }.to_string(), |v, t| v.branches = t == "on"),
        restarts: KindSet::of(&[K::Orbits]),
        unit: "-",
        ty: ViewType::Choice(&["on", "off"]),
        description: "the branches of periodic motion found by shooting, drawn on the bifurcation diagram (stable solid, unstable thin)",
    },
    ViewKey {
        name: "boundaries",
        field: Field::Word(|v| if v.boundaries { "on" } else { "off" }.to_string(), |v, t| v.boundaries = t == "on"),
        restarts: KindSet::of(&[K::Boundaries]),
        unit: "-",
        ty: ViewType::Choice(&["on", "off"]),
        description: "the map's boundaries traced as curves by harmonic balance (the jump, period doubling, where flanks part or touch), drawn over the map",
    },
    ViewKey {
        name: "clearance",
        field: Field::Word(|v| if v.whole_clearance { "whole" } else { "fit" }.to_string(), |v, t| v.whole_clearance = t == "whole"),
        restarts: KindSet::NONE,
        unit: "-",
        ty: ViewType::Choice(&["fit", "whole"]),
        description: "the axes of x: fit the data (the ±b lines drawn where they fall in range) or show the whole clearance from −b to +b",
    },
    ViewKey {
        name: AXIS_KEY,
        field: Field::Word(|v| v.axis.name().to_string(), |v, t| v.axis = AxisUnit::from_name(t).unwrap_or(v.axis)),
        restarts: KindSet::NONE,
        unit: "-",
        ty: ViewType::Choice(&["omega", "rpm"]),
        description: "the speed axes, range fields and readouts: the dimensionless Ω or the input member's speed in rpm (the small sun s1, or the pinion); values are kept as Ω",
    },
    ViewKey {
        name: "accuracy_grade",
        field: Field::Count(|v| v.accuracy_grade, |v, n| v.accuracy_grade = n),
        restarts: KindSet::NONE,
        unit: "-",
        ty: ViewType::Int { min: 1, max: 11 },
        description: "accuracy grade by ISO 1328-1 of the dynamic factor Kv by ISO 6336-1 (view 11): it sets the pitch and profile deviations that excite the standard's mesh",
    },
    ViewKey {
        name: "face_width_mm",
        field: Field::Num(|v| v.face_width_mm, |v, x| v.face_width_mm = x),
        restarts: KindSet::NONE,
        unit: "mm",
        ty: ViewType::Float {
            min: 1.0,
            max: 2000.0,
        },
        description: "face width of every mesh for the dynamic factor Kv by ISO 6336-1 (view 11): the model's mesh stiffness and load are spread over it",
    },
];

/// The view keys a link carries only when they differ from their
/// defaults, so that a link of the default state is what it was before
/// they existed: the speed axes' unit and the inputs of Kv.
pub const SPARSE_KEYS: &[&str] = &[AXIS_KEY, "accuracy_grade", "face_width_mm"];

/// The key of the speed axes' unit; a link carries it only when it is not
/// the default Ω, so links made before it are unchanged.
pub const AXIS_KEY: &str = "axis";

/// The view keys whose values are speeds (Ω): their fields take rpm when
/// the speed axes show rpm.
pub const SPEED_KEYS: &[&str] = &["omega", "omega_from", "omega_to"];

/// Looks up a view key.
pub fn view_key(name: &str) -> Option<&'static ViewKey> {
    VIEW_KEYS.iter().find(|k| k.name == name)
}

/// Which mesh the views plot.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum MeshSel {
    /// A mesh by name (e.g. `s1a1`).
    Named(String),
    /// The mesh with the largest dynamic factor.
    Worst,
}

impl MeshSel {
    /// The link text.
    pub fn text(&self) -> &str {
        match self {
            MeshSel::Named(n) => n,
            MeshSel::Worst => "worst",
        }
    }
}

/// The page's view options.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewOptions {
    /// Selected Omega.
    pub omega: f64,
    /// Plotted mesh.
    pub mesh: MeshSel,
    /// Lowest Omega of the sweeps.
    pub omega_from: f64,
    /// Highest Omega of the sweeps.
    pub omega_to: f64,
    /// Nominal points of the harmonic-balance branch.
    pub fr_points: u32,
    /// Time-integration overlay grid points (0: no overlay).
    pub fr_ti_points: u32,
    /// Recorded periods per overlay point.
    pub fr_record_periods: u32,
    /// Bifurcation grid points.
    pub bif_points: u32,
    /// Bifurcation sweep directions.
    pub bif_dir: Directions,
    /// Maximum transient periods.
    pub transient_periods: u32,
    /// Recorded periods.
    pub record_periods: u32,
    /// HBM harmonics.
    pub harmonics: u32,
    /// The key of the map's rows (`backlash_um` or `te_um`).
    pub map_key: String,
    /// Bottom row's value (um).
    pub map_from: f64,
    /// Top row's value (um).
    pub map_to: f64,
    /// Omega columns of the map.
    pub map_omega_points: u32,
    /// Rows of the map.
    pub map_value_points: u32,
    /// Maximum transient periods per map cell.
    pub map_transient_periods: u32,
    /// Recorded periods per map cell.
    pub map_record_periods: u32,
    /// Omega points of the Lyapunov curve (0: off).
    pub lyap_points: u32,
    /// Transient periods before each exponent.
    pub lyap_transient_periods: u32,
    /// Periods each exponent averages over.
    pub lyap_periods: u32,
    /// The axes of x show the whole clearance ±b (else they fit the data).
    pub whole_clearance: bool,
    /// The shooting branches on the bifurcation diagram.
    pub branches: bool,
    /// The traced boundaries over the map.
    pub boundaries: bool,
    /// What the speed axes show.
    pub axis: AxisUnit,
    /// The accuracy grade of the dynamic factor Kv (ISO 1328-1, 1 ..= 11).
    pub accuracy_grade: u32,
    /// The face width of the dynamic factor Kv (mm).
    pub face_width_mm: f64,
}

/// The selected Ω the page opens on: a periodic state (period 1, found
/// exactly; no impact on s1a1, largest Floquet multiplier 0.90 at the
/// default parameters) that the tour's first step explains, outside every
/// band of parametric instability (so the Fig. 2 preset, linear, is period
/// 1 there too). At Ω 0.84 the default motion is chaotic (largest
/// Lyapunov exponent 0.23 per period), a confusing first sight. The
/// periodic states with impact near Ω 1.87 lie at the edge of a band,
/// where the linear Fig. 2 case grows without bound. At Ω 0.35 a mesh
/// period takes more integrator steps than the page's slider preview
/// allows, so a slider change there shows the full run only.
pub const DEFAULT_OMEGA: f64 = 0.35;

impl Default for ViewOptions {
    fn default() -> Self {
        ViewOptions {
            omega: DEFAULT_OMEGA,
            mesh: MeshSel::Named("s1a1".into()),
            omega_from: 0.1,
            omega_to: 2.0,
            fr_points: 150,
            fr_ti_points: 0,
            fr_record_periods: 30,
            bif_points: 100,
            bif_dir: Directions::Both,
            transient_periods: 300,
            record_periods: 100,
            harmonics: 5,
            map_key: "backlash_um".into(),
            map_from: 0.0,
            map_to: 200.0,
            map_omega_points: 40,
            map_value_points: 16,
            map_transient_periods: 300,
            map_record_periods: 50,
            lyap_points: 40,
            lyap_transient_periods: 150,
            lyap_periods: 100,
            whole_clearance: false,
            branches: true,
            boundaries: true,
            axis: AxisUnit::Omega,
            // The standard's inputs as `gearshock simulate` defaults them.
            accuracy_grade: IsoInputs::default().accuracy_grade as u32,
            face_width_mm: IsoInputs::default().face_width_mm,
        }
    }
}

/// Formats a number so that parsing it gives the same `f64` back (Rust's
/// shortest round-trip form).
pub fn fmt_exact(x: f64) -> String {
    format!("{x}")
}

impl ViewOptions {
    /// Whether the frequency response has a time-integration overlay job
    /// of its own (otherwise its dots are the sweep's steady states).
    pub fn overlay_on(&self) -> bool {
        self.fr_ti_points > 0
    }

    /// The inputs of ISO 6336-1's K_v: the grade and face width set here,
    /// the rest the standard's defaults (as `gearshock simulate` takes
    /// them without flags).
    pub fn iso_inputs(&self) -> IsoInputs {
        IsoInputs {
            accuracy_grade: f64::from(self.accuracy_grade),
            face_width_mm: self.face_width_mm,
            ..IsoInputs::default()
        }
    }

    /// Whether the Lyapunov curve is computed (two points at least).
    pub fn lyap_on(&self) -> bool {
        self.lyap_points >= 2
    }

    /// The value of a view key as link text.
    pub fn get(&self, name: &str) -> Option<String> {
        Some(match view_key(name)?.field {
            Field::Num(get, _) => fmt_exact(get(self)),
            Field::Count(get, _) => get(self).to_string(),
            Field::Word(get, _) => get(self),
        })
    }

    /// Sets a view key from text, checking its type and range. `meshes`
    /// lists the mesh names of the current model. The error names the key,
    /// the value and the allowed range.
    pub fn set(&mut self, name: &str, text: &str, meshes: &[String]) -> Result<(), ViewKeyError> {
        let key = view_key(name).ok_or_else(|| ViewKeyError::Unknown {
            key: solver::keys::truncate(name, 40),
        })?;
        let text = text.trim();
        let bad = || ViewKeyError::OutOfRange {
            key: name.to_string(),
            value: solver::keys::truncate(text, 40),
            allowed: key.ty.allowed(),
        };
        match (key.ty, key.field) {
            (ViewType::Float { min, max }, Field::Num(_, set)) => {
                let x: f64 = text.parse().map_err(|_| bad())?;
                if !(x.is_finite() && x >= min && x <= max) {
                    return Err(bad());
                }
                // A typed -0 is kept (and written back in links) as 0.
                set(self, x + 0.0);
            }
            (ViewType::Int { min, max }, Field::Count(_, set)) => {
                let x: f64 = text.parse().map_err(|_| bad())?;
                if !(x.is_finite()
                    && x.fract() == 0.0
                    && x >= f64::from(min)
                    && x <= f64::from(max))
                {
                    return Err(bad());
                }
                set(self, x as u32);
            }
            (ViewType::Choice(words), Field::Word(_, set)) => {
                if !words.contains(&text) {
                    return Err(bad());
                }
                set(self, text);
            }
            (ViewType::Mesh, Field::Word(_, set)) => {
                if text != "worst" && !meshes.iter().any(|m| m == text) {
                    return Err(ViewKeyError::NotAMesh {
                        value: solver::keys::truncate(text, 40),
                        meshes: meshes.join(", "),
                    });
                }
                set(self, text);
            }
            _ => return Err(bad()),
        }
        Ok(())
    }

    /// Cross-key rules: every range must be increasing. Each range that is
    /// not is restored to its defaults, and named in the message (both
    /// ranges are checked, so one bad range never hides the other).
    pub fn check_range(&mut self) -> Option<String> {
        let mut msgs = Vec::new();
        if self.omega_to <= self.omega_from {
            let d = ViewOptions::default();
            msgs.push(format!(
                "The frequency range must start below its end (from Ω {} to Ω {}); it was reset to Ω {} to {}",
                self.omega_from, self.omega_to, d.omega_from, d.omega_to
            ));
            self.omega_from = d.omega_from;
            self.omega_to = d.omega_to;
        }
        if self.map_to <= self.map_from {
            let (lo, hi) = map_default_range(&self.map_key);
            msgs.push(format!(
                "The map's range must start below its end ({} to {} µm); it was reset to {lo} to {hi} µm",
                self.map_from, self.map_to
            ));
            self.map_from = lo;
            self.map_to = hi;
        }
        (!msgs.is_empty()).then(|| msgs.join("; "))
    }
}

/// The whole state a link carries.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Settings {
    /// Model parameters.
    pub params: ModelParams,
    /// View options.
    pub view: ViewOptions,
}

/// The mesh names of a parameter set's model (empty if it cannot be built).
pub fn mesh_names(params: &ModelParams) -> Vec<String> {
    match solver::system::MeshSystem::build(params) {
        Ok(sys) => sys.meshes.iter().map(|m| m.name.clone()).collect(),
        Err(_) => Vec::new(),
    }
}

impl Settings {
    /// The plotted mesh as an index into the model's meshes (`None` = worst).
    /// An unknown name falls back to the first mesh.
    pub fn mesh_index(&self, model: &Model) -> Option<usize> {
        match &self.view.mesh {
            MeshSel::Worst => None,
            MeshSel::Named(n) => Some(model.system.mesh_index(n).unwrap_or(0)),
        }
    }
}

#[cfg(test)]
mod tests;
