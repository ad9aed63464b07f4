//! The views: one table ([`VIEWS`]) names every view the page draws from
//! the controller's state, and one module per view kind holds its data
//! store, its view model (what the plot draws) and its CSV/JSON export.
//!
//! Architecture invariant: a view is a [`ViewId`]; its key (canvas, export
//! bar, progress bar, file names), heading number, title, draw priority and
//! export formats come from [`VIEWS`] and nowhere else.

pub mod bif;
pub mod boundaries;
pub mod campbell;
pub mod dynamic;
pub mod fr;
pub mod labels;
pub mod lyap;
pub mod map;
pub mod multiples;
pub mod omega;
pub mod orbits;
pub mod orders;
mod table;
#[cfg(any(test, feature = "test-support"))]
pub mod test_support;
pub mod unstable;

pub use table::{part_number, PagePart, ViewId, ViewSpec, DRAW_ORDER, PAGE, VIEWS};

use serde::Serialize;
use solver::modal::ModeKind;
use solver::model::Model;

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
    /// What the speed axes show (Ω or the input speed in rpm).
    pub speed: crate::speed::SpeedAxis,
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

/// The distinct ±b values of the plotted mesh (all meshes' for "worst").
pub fn distinct(backlash_um: &[f64], mesh: Option<usize>) -> Vec<f64> {
    let mut out: Vec<f64> = match mesh {
        Some(j) => backlash_um.get(j).copied().into_iter().collect(),
        None => backlash_um.to_vec(),
    };
    out.sort_by(f64::total_cmp);
    out.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    out
}

/// Why a view computed on the page's side (the Campbell diagram, the
/// dynamic factor) cannot be drawn: the page writes it after "not
/// computed:".
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ViewError {
    /// The model cannot be built, or its modal analysis failed.
    #[error(transparent)]
    Solver(#[from] solver::SolverError),
    /// A mesh index past the model's meshes.
    #[error("the model has no mesh {0}")]
    NoMesh(usize),
    /// The selected speed's steady state has not arrived.
    #[error("the steady state at the selected speed is computing")]
    Computing,
    /// The run kept no history of the mesh's force.
    #[error("the run kept no history of the mesh's force")]
    NoForceHistory,
    /// A mesh the standard has no geometry for.
    #[error("mesh {0} has no geometry for ISO 6336-1")]
    NoIsoGeometry(String),
    /// The standard refuses to rate the mesh (a mesh without load).
    #[error("mesh {mesh}: {source}")]
    Rating {
        /// The mesh's name.
        mesh: String,
        /// The standard's reason.
        source: solver::SolverError,
    },
}
