//! The regime map's traced boundaries (the boundaries job): the store
//! that collects the worker's curves, the curves the map shows, the check
//! of the sampled cells against the side of the curves they lie on, the
//! curve point a click picks and the sentence that says what it is.
//!
//! The check. A contact curve separates a side where its contact has not
//! begun (the point's normal points there) from one where it has: on the
//! side where "the back flanks start to touch" has not happened a cell of
//! the curve's mesh must not be double-sided, beyond it it must be. A
//! period doubling on a stable orbit separates period 1 from longer
//! periods. A cell that contradicts its side is where the periodic branch
//! the curves follow is not what the gears do (a coexisting motion, chaos,
//! a branch beyond a jump). Only the cells next to a curve are judged:
//! within [`BAND`] cells of it, not on it ([`MARGIN`]), not beyond its
//! ends, and with no other shown curve between the cell and its nearest
//! point on the curve: beyond a second period doubling, a jump or another
//! contact change the first curve's side no longer says what the branch
//! does (on the default compound map the narrow instability windows at
//! Omega 0.28-0.30 and 0.43-0.47, two period doublings a cell or less
//! apart, had each doubling judge the cells beyond the other: 89 of the
//! 152 cells marked).
//! Folds make no claim: between the two folds of a jump both branches
//! exist. Nor do cells without backlash on the back flanks (they always
//! touch) or on the drive flanks parting.

use super::map::{MapGrid, MapStore};
use crate::protocol::{BoundaryCurve, BoundaryKind, MapSample, Regime};

/// Values of the map's key whose frequency responses seed its boundaries.
pub const BOUNDARY_LEVELS: u32 = 5;
/// The boundaries' resolution: a curve's step moves at most 1/50 of the
/// map (on the gear pair the whole trace takes about 4 s natively).
pub const BOUNDARY_POINTS: u32 = 50;

/// How far from a curve (in cells) a cell's centre may lie to be judged
/// by its side: the cells next to the curve, where it is locally a line
/// and no other boundary (a jump beyond which its branch does not exist)
/// lies between.
pub const BAND: f64 = 1.5;
/// How near (in cells) a cell's centre may not lie: the curve crosses the
/// cell (its centre is what was integrated, the curve is harmonic balance).
pub const MARGIN: f64 = 0.5;

/// The traced boundaries as they arrive, for one job.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BoundaryStore {
    /// The curves, in the order they were finished.
    pub curves: Vec<BoundaryCurve>,
    /// The cusps: `(omega, value)`.
    pub cusps: Vec<(f64, f64)>,
    /// What the trace could not do, in plain sentences.
    pub notes: Vec<String>,
    /// Every curve is traced.
    pub finished: bool,
    /// What the job depends on: a new trace is only started when this changes.
    pub signature: String,
}

impl BoundaryStore {
    /// An empty store for a new job.
    pub fn new(signature: String) -> Self {
        BoundaryStore {
            signature,
            ..BoundaryStore::default()
        }
    }

    /// The curves the map of `mesh` shows: every fold and period doubling,
    /// and the contact curves of that mesh (of every mesh for the most
    /// severe mesh, `None`).
    pub fn shown(&self, mesh: Option<usize>) -> Vec<&BoundaryCurve> {
        self.curves
            .iter()
            .filter(|c| !c.kind.is_contact() || mesh.is_none() || c.mesh == mesh)
            .collect()
    }
}

/// Whether a cell of regime `cell` agrees with lying on the side
/// `unchanged` (the change has not happened) of a curve of `kind`
/// (`others_stable`: a period doubling's other multipliers inside the unit
/// circle); `None` where the curve makes no claim.
pub fn agrees(
    kind: BoundaryKind,
    others_stable: Option<bool>,
    unchanged: bool,
    cell: &MapSample,
) -> Option<bool> {
    if cell.error.is_some() {
        return None;
    }
    let r = cell.regime;
    match kind {
        BoundaryKind::Fold => None,
        BoundaryKind::PeriodDoubling => {
            (others_stable == Some(true)).then_some((cell.period == Some(1)) == unchanged)
        }
        BoundaryKind::DriveFlanksPart => match r {
            Regime::NoContact | Regime::NoGap => None,
            Regime::NoImpact => Some(unchanged),
            Regime::SingleSided | Regime::DoubleSided => Some(!unchanged),
        },
        BoundaryKind::BackFlanksTouch => match r {
            Regime::NoGap => None,
            _ => Some((r == Regime::DoubleSided) != unchanged),
        },
        BoundaryKind::DriveFlanksTouch => match r {
            Regime::NoContact => Some(unchanged),
            Regime::NoImpact | Regime::SingleSided => Some(!unchanged),
            Regime::DoubleSided | Regime::NoGap => None,
        },
    }
}

/// A segment between two points in cell coordinates.
type Segment = ((f64, f64), (f64, f64));

/// The nearest point of a curve to a cell, in units of the box.
#[derive(Debug, Clone, Copy)]
struct Nearest {
    distance: f64,
    /// The cell lies on the side the normal points to.
    unchanged: bool,
    /// The projection falls beyond the curve's first or last point.
    beyond_end: bool,
    others_stable: Option<bool>,
    /// The nearest point of the curve (cell coordinates).
    foot: (f64, f64),
}

/// The cells `(row, column)` whose regime disagrees with the side of a
/// shown curve they lie on, and how many cells were judged in all.
/// Distances are measured in cells (a column's width, a row's height), so
/// only the cells next to a curve are judged, on maps of any shape.
pub fn disagreements(
    grid: &MapGrid,
    map: &MapStore,
    curves: &[&BoundaryCurve],
) -> (Vec<(u32, u32)>, usize) {
    let (cols, rows) = (grid.omega_points as usize, grid.value_points as usize);
    if cols == 0 || rows == 0 {
        return (Vec::new(), 0);
    }
    let om = (grid.omega_to - grid.omega_from).abs().max(1e-12);
    let vr = (grid.value_to - grid.value_from).abs().max(1e-12);
    // A cell's size in Omega and in the value.
    let cw = grid.omega_step().abs().max(1e-12);
    let ch = if rows > 1 {
        grid.value_step().abs().max(1e-12)
    } else {
        vr
    };
    // Cell coordinates of a point: fractional column and row.
    let at = |omega: f64, value: f64| {
        (
            (omega - grid.omega_from) / cw,
            (value - grid.value_from) / ch,
        )
    };
    let mut bad = vec![false; cols * rows];
    let mut judged = vec![false; cols * rows];
    // Every curve's segments in cell coordinates, with the curve's place.
    let segments: Vec<(usize, Segment)> = curves
        .iter()
        .enumerate()
        .flat_map(|(i, c)| {
            c.points
                .windows(2)
                .map(move |w| (i, (at(w[0].omega, w[0].value), at(w[1].omega, w[1].value))))
        })
        .collect();
    for (index, curve) in curves.iter().enumerate() {
        let mut best: Vec<Option<Nearest>> = vec![None; cols * rows];
        let pts: Vec<(f64, f64)> = curve.points.iter().map(|p| at(p.omega, p.value)).collect();
        let last = pts.len().saturating_sub(2);
        for (i, seg) in curve.points.windows(2).enumerate() {
            let (a, b) = (pts[i], pts[i + 1]);
            // The cells within the band of the segment.
            let clamp = |x: f64, n: usize| (x.max(0.0) as usize).min(n - 1);
            let (c0, c1) = (
                clamp((a.0.min(b.0) - BAND).floor(), cols),
                clamp((a.0.max(b.0) + BAND).ceil(), cols),
            );
            let (r0, r1) = (
                clamp((a.1.min(b.1) - BAND).floor(), rows),
                clamp((a.1.max(b.1) + BAND).ceil(), rows),
            );
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len2 = dx * dx + dy * dy;
            for r in r0..=r1 {
                for c in c0..=c1 {
                    let p = (c as f64, r as f64);
                    let s = if len2 > 0.0 {
                        ((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2
                    } else {
                        0.0
                    };
                    let beyond_end = (i == 0 && s < 0.0) || (i == last && s > 1.0);
                    let t = s.clamp(0.0, 1.0);
                    let q = (a.0 + t * dx, a.1 + t * dy);
                    let distance = (p.0 - q.0).hypot(p.1 - q.1);
                    let k = r * cols + c;
                    if best[k].is_some_and(|n| n.distance <= distance) {
                        continue;
                    }
                    // The normal is given in units of the box; in cells it
                    // scales by the cell's size in the box (a gradient).
                    let (na, nb) = (seg[0].normal, seg[1].normal);
                    let n = (
                        (na.0 + t * (nb.0 - na.0)) * cw / om,
                        (na.1 + t * (nb.1 - na.1)) * ch / vr,
                    );
                    best[k] = Some(Nearest {
                        foot: q,
                        distance,
                        unchanged: (p.0 - q.0) * n.0 + (p.1 - q.1) * n.1 > 0.0,
                        beyond_end,
                        others_stable: if t < 0.5 {
                            seg[0].others_stable
                        } else {
                            seg[1].others_stable
                        },
                    });
                }
            }
        }
        for (k, near) in best.iter().enumerate() {
            let Some(n) = near else { continue };
            if n.beyond_end || n.distance < MARGIN || n.distance > BAND {
                continue;
            }
            let centre = ((k % cols) as f64, (k / cols) as f64);
            if segments
                .iter()
                .any(|&(i, seg)| i != index && crosses((centre, n.foot), seg))
            {
                continue;
            }
            let Some(cell) = map.cell((k / cols) as u32, (k % cols) as u32) else {
                continue;
            };
            if let Some(ok) = agrees(curve.kind, n.others_stable, n.unchanged, cell) {
                judged[k] = true;
                bad[k] |= !ok;
            }
        }
    }
    let marks = bad
        .iter()
        .enumerate()
        .filter(|(_, b)| **b)
        .map(|(k, _)| ((k / cols) as u32, (k % cols) as u32))
        .collect();
    (marks, judged.iter().filter(|j| **j).count())
}

/// Whether the segment `p` (a cell's centre to its nearest point on a
/// curve) crosses the segment `q` of another curve: its ends lie strictly
/// on either side of `q`'s line, and `q` meets `p`'s line (a vertex of the
/// other curve on `p` counts).
fn crosses((p0, p1): Segment, (q0, q1): Segment) -> bool {
    let apart = |a: f64, b: f64, c: f64, d: f64| a.max(b) < c.min(d) || c.max(d) < a.min(b);
    if apart(p0.0, p1.0, q0.0, q1.0) || apart(p0.1, p1.1, q0.1, q1.1) {
        return false;
    }
    let side = |a: (f64, f64), b: (f64, f64), c: (f64, f64)| {
        (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
    };
    side(q0, q1, p0) * side(q0, q1, p1) < 0.0 && side(p0, p1, q0) * side(p0, p1, q1) <= 0.0
}

/// A point of a curve picked by a click.
#[derive(Debug, Clone, PartialEq)]
pub struct Picked {
    /// The picked curve's place in the list picked from.
    pub curve: usize,
    /// What the curve marks.
    pub kind: BoundaryKind,
    /// The mesh whose contact it follows.
    pub mesh: Option<usize>,
    /// The picked point on the curve.
    pub omega: f64,
    /// The key's value there.
    pub value: f64,
}

/// The point of `curves` nearest to `(omega, value)`, if it is within
/// `tolerance_px` pixels; `px` gives pixels per unit of Omega and of the
/// value.
pub fn pick(
    curves: &[&BoundaryCurve],
    (omega, value): (f64, f64),
    px: (f64, f64),
    tolerance_px: f64,
) -> Option<Picked> {
    let mut best: Option<(f64, Picked)> = None;
    for (i, c) in curves.iter().enumerate() {
        for seg in c.points.windows(2) {
            let a = (seg[0].omega * px.0, seg[0].value * px.1);
            let b = (seg[1].omega * px.0, seg[1].value * px.1);
            let p = (omega * px.0, value * px.1);
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len2 = dx * dx + dy * dy;
            let t = if len2 > 0.0 {
                (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let d = (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy);
            if d <= tolerance_px && best.as_ref().is_none_or(|(bd, _)| d < *bd) {
                let picked = Picked {
                    curve: i,
                    kind: c.kind,
                    mesh: c.mesh,
                    omega: seg[0].omega + t * (seg[1].omega - seg[0].omega),
                    value: seg[0].value + t * (seg[1].value - seg[0].value),
                };
                best = Some((d, picked));
            }
        }
    }
    best.map(|(_, p)| p)
}

/// What a picked point is, in a plain sentence: "Here the back flanks of
/// mesh s1a1 start to touch (double-sided impact begins): Ω 0.812,
/// backlash 42.5 µm."
pub fn describe(p: &Picked, key: &str, mesh_name: Option<&str>) -> String {
    let what = match p.kind {
        BoundaryKind::Fold => "the response jumps (a fold of the periodic branch)".to_string(),
        BoundaryKind::PeriodDoubling => {
            "period doubling begins (the motion starts repeating every two mesh periods)"
                .to_string()
        }
        kind => {
            let flanks = match kind {
                BoundaryKind::DriveFlanksPart => {
                    "drive flanks start to part (single-sided impact begins)"
                }
                BoundaryKind::BackFlanksTouch => {
                    "back flanks start to touch (double-sided impact begins)"
                }
                _ => "drive flanks start to touch",
            };
            match mesh_name {
                Some(m) => format!("on mesh {m} the {flanks}"),
                None => format!("the {flanks}"),
            }
        }
    };
    let what_value = match key {
        "te_um" => format!("TE {:.1} µm", p.value),
        "backlash_um" => format!("backlash {:.1} µm", p.value),
        other => format!("{other} {:.4}", p.value),
    };
    format!("Here {what}: Ω {:.3}, {what_value}.", p.omega)
}

/// The traced boundaries as JSON (field names as in `gearshock
/// boundaries`); `mesh_names` names the meshes in model order.
pub fn boundaries_json(store: &BoundaryStore, mesh_names: &[String]) -> serde_json::Value {
    let curves: Vec<serde_json::Value> = store
        .curves
        .iter()
        .map(|c| {
            let points: Vec<serde_json::Value> = c
                .points
                .iter()
                .map(|p| serde_json::json!({ "omega": p.omega, "value": p.value }))
                .collect();
            serde_json::json!({
                "kind": c.kind.solver_name(),
                "mesh": c.mesh.and_then(|m| mesh_names.get(m)),
                "points": points,
            })
        })
        .collect();
    let cusps: Vec<serde_json::Value> = store
        .cusps
        .iter()
        .map(|(omega, value)| serde_json::json!({ "omega": omega, "value": value }))
        .collect();
    serde_json::json!({
        "complete": store.finished,
        "curves": curves,
        "cusps": cusps,
        "notes": store.notes,
    })
}

#[cfg(test)]
mod tests;
