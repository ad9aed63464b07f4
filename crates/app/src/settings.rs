//! Everything a link restores: the model parameters (the solver's flat keys,
//! as on the CLI) and the page's own view options (frequency range, grid
//! sizes, periods, harmonics, plotted mesh, selected Omega).
//!
//! View options have their own small key table, [`VIEW_KEYS`], with ranges
//! that cap every job: no link can start an unbounded computation.

use solver::params::ModelParams;
use solver::steady::Model;
use solver::sweep::Directions;

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

/// One view option key.
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
        unit: "-",
        ty: OMEGA,
        description: "selected dimensionless mesh frequency Omega for the phase portrait, Poincaré section, history and spectrum",
    },
    ViewKey {
        name: "mesh",
        unit: "-",
        ty: ViewType::Mesh,
        description: "which mesh to plot, or the worst (largest dynamic factor)",
    },
    ViewKey {
        name: "omega_from",
        unit: "-",
        ty: OMEGA,
        description: "lowest Omega of the frequency response and bifurcation diagram",
    },
    ViewKey {
        name: "omega_to",
        unit: "-",
        ty: OMEGA,
        description: "highest Omega of the frequency response and bifurcation diagram",
    },
    ViewKey {
        name: "fr_points",
        unit: "-",
        ty: ViewType::Int {
            min: 2,
            max: MAX_FR_POINTS,
        },
        description: "nominal points of the harmonic-balance frequency response (largest continuation step = range / points; resonances get more)",
    },
    ViewKey {
        name: "fr_ti_points",
        unit: "-",
        ty: ViewType::Int {
            min: 0,
            max: MAX_FR_TI_POINTS,
        },
        description: "Omega points of a time-integration run of its own for the frequency response's dots (0: the dots are the bifurcation sweep's steady states)",
    },
    ViewKey {
        name: "fr_record_periods",
        unit: "periods",
        ty: ViewType::Int { min: 1, max: 200 },
        description: "recorded mesh periods per time-integration overlay point of the frequency response",
    },
    ViewKey {
        name: "bif_points",
        unit: "-",
        ty: ViewType::Int {
            min: 2,
            max: MAX_BIF_POINTS,
        },
        description: "Omega points of the bifurcation diagram",
    },
    ViewKey {
        name: "bif_dir",
        unit: "-",
        ty: ViewType::Choice(&["up", "down", "both"]),
        description: "bifurcation sweep direction: up, down, or up then down",
    },
    ViewKey {
        name: "transient_periods",
        unit: "periods",
        ty: ViewType::Int {
            min: 0,
            max: MAX_TRANSIENT,
        },
        description: "maximum transient mesh periods per steady state (ends early once settled)",
    },
    ViewKey {
        name: "record_periods",
        unit: "periods",
        ty: ViewType::Int {
            min: 1,
            max: MAX_RECORD,
        },
        description: "recorded mesh periods per steady state (Poincaré samples, history)",
    },
    ViewKey {
        name: "harmonics",
        unit: "-",
        ty: ViewType::Int {
            min: 1,
            max: MAX_HARMONICS,
        },
        description: "harmonics H of the harmonic-balance frequency response",
    },
    ViewKey {
        name: "map_key",
        unit: "-",
        ty: ViewType::Choice(MAP_KEYS),
        description: "the parameter on the vertical axis of the impact-regime map: backlash b or TE amplitude",
    },
    ViewKey {
        name: "map_from",
        unit: "um",
        ty: ViewType::Float {
            min: 0.0,
            max: 1000.0,
        },
        description: "lowest value of the map's parameter (bottom row)",
    },
    ViewKey {
        name: "map_to",
        unit: "um",
        ty: ViewType::Float {
            min: 0.0,
            max: 1000.0,
        },
        description: "highest value of the map's parameter (top row)",
    },
    ViewKey {
        name: "map_omega_points",
        unit: "-",
        ty: ViewType::Int {
            min: 2,
            max: MAX_MAP_OMEGA_POINTS,
        },
        description: "Omega columns of the impact-regime map (over the frequency range)",
    },
    ViewKey {
        name: "map_value_points",
        unit: "-",
        ty: ViewType::Int {
            min: 1,
            max: MAX_MAP_VALUE_POINTS,
        },
        description: "rows of the impact-regime map (values of its parameter)",
    },
    ViewKey {
        name: "map_transient_periods",
        unit: "periods",
        ty: ViewType::Int {
            min: 0,
            max: MAX_TRANSIENT,
        },
        description: "maximum transient mesh periods per map cell (ends early once settled)",
    },
    ViewKey {
        name: "map_record_periods",
        unit: "periods",
        ty: ViewType::Int {
            min: 1,
            max: MAX_RECORD,
        },
        description: "recorded mesh periods per map cell (regime and period detection)",
    },
    ViewKey {
        name: "lyap_points",
        unit: "-",
        ty: ViewType::Int {
            min: 0,
            max: MAX_LYAP_POINTS,
        },
        description: "Omega points of the largest Lyapunov exponent under the bifurcation diagram (0 = off)",
    },
    ViewKey {
        name: "lyap_transient_periods",
        unit: "periods",
        ty: ViewType::Int {
            min: 0,
            max: MAX_TRANSIENT,
        },
        description: "transient mesh periods before the Lyapunov exponent is measured (ends early once settled)",
    },
    ViewKey {
        name: "lyap_periods",
        unit: "periods",
        ty: ViewType::Int {
            min: 10,
            max: MAX_RECORD,
        },
        description: "mesh periods over which the Lyapunov exponent is averaged",
    },
    ViewKey {
        name: "clearance",
        unit: "-",
        ty: ViewType::Choice(&["fit", "whole"]),
        description: "the axes of x: fit the data (the ±b lines drawn where they fall in range) or show the whole clearance from −b to +b",
    },
];

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
}

impl Default for ViewOptions {
    fn default() -> Self {
        ViewOptions {
            omega: 0.84,
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
        }
    }
}

/// Formats a number so that parsing it gives the same `f64` back (Rust's
/// shortest round-trip form).
pub fn fmt_exact(x: f64) -> String {
    format!("{x}")
}

impl ViewOptions {
    /// The value of a view key as link text.
    pub fn get(&self, name: &str) -> Option<String> {
        Some(match name {
            "omega" => fmt_exact(self.omega),
            "mesh" => self.mesh.text().to_string(),
            "omega_from" => fmt_exact(self.omega_from),
            "omega_to" => fmt_exact(self.omega_to),
            "fr_points" => self.fr_points.to_string(),
            "fr_ti_points" => self.fr_ti_points.to_string(),
            "fr_record_periods" => self.fr_record_periods.to_string(),
            "bif_points" => self.bif_points.to_string(),
            "bif_dir" => self.bif_dir.name().to_string(),
            "clearance" => if self.whole_clearance { "whole" } else { "fit" }.to_string(),
            "transient_periods" => self.transient_periods.to_string(),
            "record_periods" => self.record_periods.to_string(),
            "harmonics" => self.harmonics.to_string(),
            "map_key" => self.map_key.clone(),
            "map_from" => fmt_exact(self.map_from),
            "map_to" => fmt_exact(self.map_to),
            "map_omega_points" => self.map_omega_points.to_string(),
            "map_value_points" => self.map_value_points.to_string(),
            "map_transient_periods" => self.map_transient_periods.to_string(),
            "map_record_periods" => self.map_record_periods.to_string(),
            "lyap_points" => self.lyap_points.to_string(),
            "lyap_transient_periods" => self.lyap_transient_periods.to_string(),
            "lyap_periods" => self.lyap_periods.to_string(),
            _ => return None,
        })
    }

    /// Sets a view key from text, checking its type and range. `meshes`
    /// lists the mesh names of the current model. The error names the key,
    /// the value and the allowed range.
    pub fn set(&mut self, name: &str, text: &str, meshes: &[String]) -> Result<(), String> {
        let key = view_key(name)
            .ok_or_else(|| format!("unknown key `{}`", solver::keys::truncate(name, 40)))?;
        let text = text.trim();
        let shown = solver::keys::truncate(text, 40);
        let bad = || {
            format!(
                "{name} = {shown} is out of range: allowed {}",
                key.ty.allowed()
            )
        };
        match key.ty {
            ViewType::Float { min, max } => {
                let x: f64 = text.parse().map_err(|_| bad())?;
                if !(x.is_finite() && x >= min && x <= max) {
                    return Err(bad());
                }
                // A typed -0 is kept (and written back in links) as 0.
                let x = x + 0.0;
                match name {
                    "omega" => self.omega = x,
                    "omega_from" => self.omega_from = x,
                    "omega_to" => self.omega_to = x,
                    "map_from" => self.map_from = x,
                    "map_to" => self.map_to = x,
                    _ => return Err(bad()),
                }
            }
            ViewType::Int { min, max } => {
                let x: f64 = text.parse().map_err(|_| bad())?;
                if !(x.is_finite()
                    && x.fract() == 0.0
                    && x >= f64::from(min)
                    && x <= f64::from(max))
                {
                    return Err(bad());
                }
                let n = x as u32;
                match name {
                    "fr_points" => self.fr_points = n,
                    "fr_ti_points" => self.fr_ti_points = n,
                    "fr_record_periods" => self.fr_record_periods = n,
                    "bif_points" => self.bif_points = n,
                    "transient_periods" => self.transient_periods = n,
                    "record_periods" => self.record_periods = n,
                    "harmonics" => self.harmonics = n,
                    "map_omega_points" => self.map_omega_points = n,
                    "map_value_points" => self.map_value_points = n,
                    "map_transient_periods" => self.map_transient_periods = n,
                    "map_record_periods" => self.map_record_periods = n,
                    "lyap_points" => self.lyap_points = n,
                    "lyap_transient_periods" => self.lyap_transient_periods = n,
                    "lyap_periods" => self.lyap_periods = n,
                    _ => return Err(bad()),
                }
            }
            ViewType::Choice(words) => match name {
                "bif_dir" => self.bif_dir = Directions::from_name(text).ok_or_else(bad)?,
                "clearance" => {
                    let w = words.iter().find(|w| **w == text).ok_or_else(bad)?;
                    self.whole_clearance = *w == "whole";
                }
                _ => {
                    let w = words.iter().find(|w| **w == text).ok_or_else(bad)?;
                    self.map_key = (*w).to_string();
                }
            },
            ViewType::Mesh => {
                if text == "worst" {
                    self.mesh = MeshSel::Worst;
                } else if meshes.iter().any(|m| m == text) {
                    self.mesh = MeshSel::Named(text.to_string());
                } else {
                    return Err(format!(
                        "mesh = {shown} is not a mesh of this model: allowed {}, worst",
                        meshes.join(", ")
                    ));
                }
            }
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
mod tests {
    use super::*;

    #[test]
    fn every_view_key_reads_back_what_it_sets() {
        let meshes = vec!["s1a1".to_string(), "rb3".to_string()];
        let mut v = ViewOptions::default();
        for (k, t) in [
            ("omega", "1.25"),
            ("mesh", "rb3"),
            ("omega_from", "0.3"),
            ("omega_to", "1.7"),
            ("fr_points", "80"),
            ("fr_ti_points", "24"),
            ("fr_record_periods", "12"),
            ("bif_points", "150"),
            ("bif_dir", "down"),
            ("transient_periods", "500"),
            ("record_periods", "64"),
            ("harmonics", "7"),
            ("map_key", "te_um"),
            ("map_from", "5.5"),
            ("map_to", "80"),
            ("map_omega_points", "200"),
            ("map_value_points", "100"),
            ("map_transient_periods", "300"),
            ("map_record_periods", "100"),
            ("lyap_points", "0"),
            ("lyap_transient_periods", "250"),
            ("lyap_periods", "200"),
            ("clearance", "whole"),
        ] {
            v.set(k, t, &meshes).unwrap();
            assert_eq!(v.get(k).unwrap(), t, "{k}");
        }
        assert!(VIEW_KEYS.iter().all(|k| v.get(k.name).is_some()));
    }

    #[test]
    fn out_of_range_values_name_key_and_range() {
        let mut v = ViewOptions::default();
        let e = v.set("bif_points", "1e9", &[]).unwrap_err();
        assert!(e.contains("bif_points") && e.contains("1000"), "{e}");
        let e = v.set("omega", "NaN", &[]).unwrap_err();
        assert!(e.contains("omega") && e.contains("0.01 ..= 20"), "{e}");
        assert!(v.set("fr_points", "2.5", &[]).is_err());
        assert!(v.set("mesh", "rb9", &["s1a1".into()]).is_err());
        assert_eq!(v, ViewOptions::default());
        v.omega_from = 1.5;
        v.omega_to = 1.0;
        assert!(v.check_range().is_some());
        assert!(v.omega_from < v.omega_to);
        // The map's caps and its own range rule.
        assert!(v.set("map_omega_points", "201", &[]).is_err());
        assert!(v.set("map_value_points", "101", &[]).is_err());
        assert!(v.set("map_key", "damping_ratio", &[]).is_err());
        v.map_from = 50.0;
        v.map_to = 10.0;
        let e = v.check_range().unwrap();
        assert!(
            e.contains("map's range") && e.contains("0 to 200 µm"),
            "{e}"
        );
        assert_eq!((v.map_from, v.map_to), (0.0, 200.0));
    }

    #[test]
    fn both_inverted_ranges_are_named_and_reset() {
        // Once the Omega range was reset the map's was kept inverted.
        let mut v = ViewOptions {
            omega_from: 1.5,
            omega_to: 1.0,
            map_from: 50.0,
            map_to: 10.0,
            ..ViewOptions::default()
        };
        let e = v.check_range().unwrap();
        assert!(
            e.contains("frequency range") && e.contains("map's range"),
            "{e}"
        );
        let d = ViewOptions::default();
        assert_eq!((v.omega_from, v.omega_to), (d.omega_from, d.omega_to));
        assert_eq!((v.map_from, v.map_to), (d.map_from, d.map_to));
        assert_eq!(v.check_range(), None);
    }

    #[test]
    fn minus_zero_is_kept_as_zero() {
        let mut v = ViewOptions::default();
        v.set("map_from", "-0", &[]).unwrap();
        assert_eq!(v.get("map_from").unwrap(), "0");
        assert!(v.map_from.is_sign_positive());
    }
}
