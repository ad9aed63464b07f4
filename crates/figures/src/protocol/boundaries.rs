//! A traced boundary of the regime map as the page receives it: what it
//! marks, the mesh whose contact it follows, and its points with the side
//! on which the change it marks has not happened.

use serde::{Deserialize, Serialize};
use solver::boundaries::CurveKind;

/// What a boundary curve marks (`solver::boundaries::CurveKind`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BoundaryKind {
    /// A fold of the periodic branch: the response jumps.
    Fold,
    /// A Floquet multiplier at -1: period doubling begins.
    PeriodDoubling,
    /// The drive flanks start to part (single-sided impact begins).
    DriveFlanksPart,
    /// The back flanks start to touch (double-sided impact begins).
    BackFlanksTouch,
    /// The drive flanks of an unloaded mesh start to touch.
    DriveFlanksTouch,
}

impl BoundaryKind {
    /// Every kind, in the key's order.
    pub const ALL: [BoundaryKind; 5] = [
        BoundaryKind::Fold,
        BoundaryKind::PeriodDoubling,
        BoundaryKind::DriveFlanksPart,
        BoundaryKind::BackFlanksTouch,
        BoundaryKind::DriveFlanksTouch,
    ];

    /// Its name in the key, in plain words.
    pub fn label(self) -> &'static str {
        match self {
            BoundaryKind::Fold => "the jump",
            BoundaryKind::PeriodDoubling => "period doubling begins",
            BoundaryKind::DriveFlanksPart => "the drive flanks start to part",
            BoundaryKind::BackFlanksTouch => "the back flanks start to touch",
            BoundaryKind::DriveFlanksTouch => "the drive flanks start to touch",
        }
    }

    /// Whether the curve follows one mesh's contact.
    pub fn is_contact(self) -> bool {
        !matches!(self, BoundaryKind::Fold | BoundaryKind::PeriodDoubling)
    }

    /// The name the CLI's JSON gives it.
    pub fn solver_name(self) -> &'static str {
        CurveKind::from(self).name()
    }
}

impl From<CurveKind> for BoundaryKind {
    fn from(k: CurveKind) -> Self {
        match k {
            CurveKind::Fold => BoundaryKind::Fold,
            CurveKind::PeriodDoubling => BoundaryKind::PeriodDoubling,
            CurveKind::DriveFlanksPart => BoundaryKind::DriveFlanksPart,
            CurveKind::BackFlanksTouch => BoundaryKind::BackFlanksTouch,
            CurveKind::DriveFlanksTouch => BoundaryKind::DriveFlanksTouch,
        }
    }
}

impl From<BoundaryKind> for CurveKind {
    fn from(k: BoundaryKind) -> Self {
        match k {
            BoundaryKind::Fold => CurveKind::Fold,
            BoundaryKind::PeriodDoubling => CurveKind::PeriodDoubling,
            BoundaryKind::DriveFlanksPart => CurveKind::DriveFlanksPart,
            BoundaryKind::BackFlanksTouch => CurveKind::BackFlanksTouch,
            BoundaryKind::DriveFlanksTouch => CurveKind::DriveFlanksTouch,
        }
    }
}

/// One point of a boundary curve.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BoundaryPoint {
    /// Dimensionless frequency.
    pub omega: f64,
    /// The key's value (its unit: µm for the map's keys).
    pub value: f64,
    /// The unit normal in units of the box (`omega / range`, `value /
    /// range`), pointing to the side where the change has not happened.
    pub normal: (f64, f64),
    /// Period doublings only: whether the orbit's other multipliers are
    /// inside the unit circle (the doubling happens on a stable orbit).
    pub others_stable: Option<bool>,
}

/// A traced boundary curve.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BoundaryCurve {
    /// What it marks.
    pub kind: BoundaryKind,
    /// The mesh whose contact it follows (a contact curve), in the model's
    /// mesh order.
    pub mesh: Option<usize>,
    /// Its points, in order along the curve.
    pub points: Vec<BoundaryPoint>,
}

impl From<&solver::boundaries::Curve> for BoundaryCurve {
    fn from(c: &solver::boundaries::Curve) -> Self {
        BoundaryCurve {
            kind: c.kind.into(),
            mesh: c.mesh,
            points: c
                .points
                .iter()
                .map(|p| BoundaryPoint {
                    omega: p.omega,
                    value: p.value,
                    normal: p.normal,
                    others_stable: p.others_stable,
                })
                .collect(),
        }
    }
}
