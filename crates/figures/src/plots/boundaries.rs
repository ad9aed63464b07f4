//! The traced boundaries over the impact-regime map: each kind's line
//! style (colour, halo, width, dashes), the curves and the marks of the
//! cells that disagree with them as pixel paths (the canvas and the SVG
//! export stroke them after the cells), and their entries in the key.

use super::{err, PlotFrame, Res};
use crate::protocol::{BoundaryCurve, BoundaryKind};
use crate::views::map::MapGrid;
use plotters::coord::Shift;
use plotters::prelude::*;

/// How a kind of boundary is drawn: a line over a wider halo of the
/// contrasting colour, so it reads on every regime's colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveStyle {
    /// The line's colour.
    pub color: RGBColor,
    /// The halo's colour.
    pub halo: RGBColor,
    /// The line's width (pixels); the halo is 2 px wider.
    pub width: f64,
    /// Dash and gap lengths (pixels), `None` for a solid line.
    pub dash: Option<(f64, f64)>,
}

const DARK: RGBColor = RGBColor(0, 0, 0);
const LIGHT: RGBColor = RGBColor(255, 255, 255);
/// The outline of a cell that disagrees with the curves.
pub const MARK: RGBColor = RGBColor(255, 225, 0);
/// What the mark means, in the key.
pub const MARK_LABEL: &str = "the periodic branch is not what the gears do here";
/// The glow under a clicked curve and the ring at its picked point (the
/// sentence beside the map starts with the same ring).
pub const PICKED: RGBColor = RGBColor(230, 0, 170);

/// A clicked curve's glow (a wide line under its own) and the ring at its
/// picked point, in pixels.
pub fn picked_glow(
    frame: &PlotFrame,
    curve: &BoundaryCurve,
    (omega, value): (f64, f64),
) -> (OverlayLine, [f64; 2]) {
    let path = curve
        .points
        .iter()
        .map(|p| {
            let q = frame.to_px(p.omega, p.value);
            [q.x, q.y]
        })
        .collect();
    let at = frame.to_px(omega, value);
    (
        OverlayLine {
            color: PICKED,
            width: style(curve.kind).width + 8.0,
            paths: vec![path],
        },
        [at.x, at.y],
    )
}

/// Each kind's style: the jump solid black, period doubling dashed black,
/// the contact changes white (solid, dashed, dotted).
pub fn style(kind: BoundaryKind) -> CurveStyle {
    let (color, halo, width, dash) = match kind {
        BoundaryKind::Fold => (DARK, LIGHT, 3.0, None),
        BoundaryKind::PeriodDoubling => (DARK, LIGHT, 2.0, Some((7.0, 4.0))),
        BoundaryKind::DriveFlanksPart => (LIGHT, DARK, 2.5, None),
        BoundaryKind::BackFlanksTouch => (LIGHT, DARK, 2.5, Some((7.0, 4.0))),
        BoundaryKind::DriveFlanksTouch => (LIGHT, DARK, 2.5, Some((2.0, 3.0))),
    };
    CurveStyle {
        color,
        halo,
        width,
        dash,
    }
}

/// Polylines of one colour and width, in pixels.
#[derive(Debug, Clone, PartialEq)]
pub struct OverlayLine {
    /// Stroke colour.
    pub color: RGBColor,
    /// Stroke width (pixels).
    pub width: f64,
    /// The polylines.
    pub paths: Vec<Vec<[f64; 2]>>,
}

/// The curves as pixel polylines in drawing order: every halo first, then
/// every line, one entry per kind and layer.
pub fn curve_lines(frame: &PlotFrame, curves: &[&BoundaryCurve]) -> Vec<OverlayLine> {
    let mut halos = Vec::new();
    let mut lines = Vec::new();
    for kind in BoundaryKind::ALL {
        let s = style(kind);
        let mut paths = Vec::new();
        for c in curves.iter().filter(|c| c.kind == kind) {
            let px: Vec<[f64; 2]> = c
                .points
                .iter()
                .map(|p| {
                    let q = frame.to_px(p.omega, p.value);
                    [q.x, q.y]
                })
                .collect();
            match s.dash {
                Some((on, off)) => paths.extend(dashed(&px, on, off)),
                None => paths.push(px),
            }
        }
        if paths.is_empty() {
            continue;
        }
        halos.push(OverlayLine {
            color: s.halo,
            width: s.width + 2.0,
            paths: paths.clone(),
        });
        lines.push(OverlayLine {
            color: s.color,
            width: s.width,
            paths,
        });
    }
    halos.extend(lines);
    halos
}

/// A polyline cut into dashes of `on` pixels with gaps of `off`.
pub fn dashed(path: &[[f64; 2]], on: f64, off: f64) -> Vec<Vec<[f64; 2]>> {
    let mut out = Vec::new();
    let mut current: Vec<[f64; 2]> = Vec::new();
    // Where in the on/off cycle the walk is.
    let mut phase = 0.0;
    let period = on + off;
    for seg in path.windows(2) {
        let (a, b) = (seg[0], seg[1]);
        let len = (b[0] - a[0]).hypot(b[1] - a[1]);
        let mut t = 0.0;
        while t < len {
            let in_dash = phase < on;
            let left = if in_dash { on - phase } else { period - phase };
            let step = left.min(len - t);
            let at = |u: f64| {
                [
                    a[0] + (b[0] - a[0]) * u / len,
                    a[1] + (b[1] - a[1]) * u / len,
                ]
            };
            if in_dash {
                if current.is_empty() {
                    current.push(at(t));
                }
                current.push(at(t + step));
            }
            t += step;
            phase += step;
            if phase >= on && in_dash && !current.is_empty() {
                out.push(std::mem::take(&mut current));
            }
            if phase >= period {
                phase -= period;
            }
        }
    }
    if current.len() >= 2 {
        out.push(current);
    }
    out
}

/// The outlines of the cells `(row, column)` that disagree, in pixels
/// (`[x, y, width, height]`, inset by a pixel).
pub fn mark_rects(frame: &PlotFrame, grid: &MapGrid, cells: &[(u32, u32)]) -> Vec<[f64; 4]> {
    let (dx, dy) = (0.5 * grid.omega_step(), 0.5 * grid.value_step());
    cells
        .iter()
        .map(|&(r, c)| {
            let (x, y) = (grid.omega(c), grid.value(r));
            let a = frame.to_px(x - dx, y + dy);
            let b = frame.to_px(x + dx, y - dy);
            [a.x + 1.0, a.y + 1.0, b.x - a.x - 2.0, b.y - a.y - 2.0]
        })
        .collect()
}

/// Draws a key's sample of a kind's line, 14 px long, from `(x, y)`.
pub fn draw_line_sample<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    (x, y): (i32, i32),
    kind: BoundaryKind,
) -> Res<()> {
    let s = style(kind);
    let pieces: Vec<Vec<(i32, i32)>> = match s.dash {
        Some((on, _)) if on < 4.0 => vec![
            vec![(x, y), (x + 2, y)],
            vec![(x + 6, y), (x + 8, y)],
            vec![(x + 12, y), (x + 14, y)],
        ],
        Some(_) => vec![vec![(x, y), (x + 5, y)], vec![(x + 9, y), (x + 14, y)]],
        None => vec![vec![(x, y), (x + 14, y)]],
    };
    for (color, width) in [(s.halo, s.width + 2.0), (s.color, s.width)] {
        for p in &pieces {
            area.draw(&PathElement::new(
                p.clone(),
                ShapeStyle::from(&color).stroke_width(width.round() as u32),
            ))
            .map_err(err)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dashes_cover_the_on_share_of_the_path_and_keep_its_ends_inside() {
        // 100 px straight: 7 on, 4 off -> dashes start at 0, 11, 22, ...
        let path = [[0.0, 0.0], [60.0, 0.0], [100.0, 0.0]];
        let d = dashed(&path, 7.0, 4.0);
        assert_eq!(d.len(), 10, "{d:?}");
        let on: f64 = d
            .iter()
            .map(|p| p.windows(2).map(|s| (s[1][0] - s[0][0]).abs()).sum::<f64>())
            .sum();
        // 9 whole dashes (ending at 95) and a last one from 99 to 100.
        assert!((on - (9.0 * 7.0 + 1.0)).abs() < 1e-9, "{on}");
        assert!((d[1][0][0] - 11.0).abs() < 1e-9);
        // A dash across the corner at 60 keeps the corner.
        assert!(d.iter().any(|p| p.len() == 3 && p[1] == [60.0, 0.0]));
        assert!(d.iter().flatten().all(|q| q[0] >= 0.0 && q[0] <= 100.0));
    }

    #[test]
    fn every_kind_has_its_own_style() {
        for a in BoundaryKind::ALL {
            for b in BoundaryKind::ALL {
                assert_eq!(a == b, style(a) == style(b), "{a:?} {b:?}");
            }
        }
    }
}
