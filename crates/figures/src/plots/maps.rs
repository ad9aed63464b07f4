//! The impact-regime map (`ViewId::Map`) and the Lyapunov curve (under `ViewId::Bif`),
//! drawn with plotters like the other plots.
//!
//! The map's cells are filled rectangles in the regime colours of the other
//! views; a black dot marks a cell whose response is not period 1 (period
//! 2 or more, or no period found: quasi-periodic or chaotic). Cells not yet
//! computed are light grey, failed cells dark grey. The Lyapunov curve
//! shares the bifurcation diagram's Omega axis, margins and label widths, so
//! its Omega ticks line up with the diagram above it.

use super::boundaries::{curve_lines, draw_line_sample, mark_rects, OverlayLine, MARK, MARK_LABEL};
use super::{
    chart_area, draw_key, err, frame_of, linear_chart, omega_decorations, omega_items,
    padded_range, plan_key, regime_color, small, Axes, DrawError, KeyIcon, KeyItems, PlotFrame,
    Res, GRID,
};
use crate::protocol::{BoundaryKind, Regime};
use crate::views::lyap::{lyap_kind, LyapKind, LyapStore, LYAP_ZERO_BAND};
use crate::views::map::MapView;
use crate::views::NaturalFreq;
use plotters::coord::Shift;
use plotters::prelude::*;

const PENDING: RGBColor = RGBColor(236, 238, 242);
const FAILED: RGBColor = RGBColor(110, 110, 110);

/// The map's cells, period marks and cursor in pixels, for the caller to
/// fill in a batch (one path per colour: a 200 x 100 map is 20000 cells,
/// too many for one plotters call each).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MapOverlay {
    /// Cells by colour: `(colour, [x, y, width, height] in pixels)`.
    pub cells: Vec<(RGBColor, Vec<[f64; 4]>)>,
    /// Centres of the cells that are not period 1.
    pub dots: Vec<[f64; 2]>,
    /// Radius of the dots (pixels).
    pub dot_radius: f64,
    /// The cursor: the selected Omega's column and the key's value's row (pixels).
    pub cursor: (Option<f64>, Option<f64>),
    /// The traced boundaries, halos first ([`super::boundaries`]).
    pub curves: Vec<OverlayLine>,
    /// The cusps' centres (pixels).
    pub cusps: Vec<[f64; 2]>,
    /// Outlines of the cells that disagree with the curves (pixels).
    pub marks: Vec<[f64; 4]>,
    /// The clicked curve's glow, drawn under the curves, and the ring at
    /// its picked point, drawn over everything.
    pub picked: Option<(OverlayLine, [f64; 2])>,
}

/// Draws the map's axes and key; returns where its cells lie (to map
/// clicks back to cells) and the cells themselves, in pixels.
pub fn draw_map<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    v: &MapView,
    status: &str,
) -> Res<(PlotFrame, MapOverlay)> {
    root.fill(&WHITE).map_err(err)?;
    let Some(g) = v.store.grid.as_ref() else {
        return Err(DrawError("no map grid".into()));
    };
    let x = g.x_range();
    let y = g.y_range();
    let (w, h) = root.dim_in_pixel();
    // The key: every regime (so the colours read the same in every map),
    // the period mark, pending and failed cells; each kind of boundary
    // shown and the disagreement mark. Laid out first: its area under the
    // x axis description is as tall as its lines (a phone's takes three).
    let mut items: Vec<(Entry, String)> = Regime::ALL
        .iter()
        .map(|&r| (Entry::Swatch(regime_color(r)), r.label().to_string()))
        .collect();
    items.push((Entry::Text, "• not period 1".into()));
    items.push((Entry::Swatch(PENDING), "not computed yet".into()));
    if v.store.counts().2 > 0 {
        items.push((Entry::Swatch(FAILED), "failed".into()));
    }
    for kind in BoundaryKind::ALL {
        if v.boundaries.iter().any(|c| c.kind == kind) {
            items.push((Entry::Line(kind), kind.label().into()));
        }
    }
    if !v.cusps.is_empty() {
        items.push((Entry::Text, "○ a cusp: the jump disappears".into()));
    }
    if !v.disagree.is_empty() {
        items.push((Entry::Mark, MARK_LABEL.into()));
    }
    let key = lay_out_key(root, items, w);
    let key_h = key.last().map_or(0, |(_, _, (_, ky), _)| *ky) + 17 + 6;
    let (plot_area, key_area) = root.split_vertically(h as i32 - key_h.max(40));
    let caption = format!("Impact-regime map, {}{status}", v.mesh_label);
    let axes = Axes {
        grid: false,
        ..Axes::over_omega(&v.speed, g.key_label())
    };
    let chart = linear_chart(&plot_area, &caption, (x, y), &axes)?;
    let frame = frame_of(&chart, x, y);
    let (dx, dy) = (0.5 * g.omega_step(), 0.5 * g.value_step());
    let mut overlay = MapOverlay::default();
    let mut push =
        |color: RGBColor, r: [f64; 4]| match overlay.cells.iter_mut().find(|(c, _)| *c == color) {
            Some((_, v)) => v.push(r),
            None => overlay.cells.push((color, vec![r])),
        };
    let mut dots = Vec::new();
    for r in 0..g.value_points {
        for c in 0..g.omega_points {
            let (xo, yv) = (g.omega(c), g.value(r));
            let color = match v.store.cell(r, c) {
                None => PENDING,
                Some(cell) if cell.error.is_some() => FAILED,
                Some(cell) => {
                    if cell.period != Some(1) {
                        dots.push((xo, yv));
                    }
                    regime_color(cell.regime)
                }
            };
            let a = frame.to_px(xo - dx, yv + dy);
            let b = frame.to_px(xo + dx, yv - dy);
            // Cells overlap by a fraction of a pixel so no seams show.
            push(color, [a.x, a.y, b.x - a.x + 0.5, b.y - a.y + 0.5]);
        }
    }
    let cell_px = {
        let a = frame.to_px(g.omega(0) - dx, g.value(0) - dy);
        let b = frame.to_px(g.omega(0) + dx, g.value(0) + dy);
        (b.x - a.x).abs().min((b.y - a.y).abs())
    };
    overlay.dot_radius = (cell_px * 0.18).clamp(1.0, 4.0);
    overlay.dots = dots
        .iter()
        .map(|&(xo, yv)| {
            let q = frame.to_px(xo, yv);
            [q.x, q.y]
        })
        .collect();
    // The cursor: the selected Omega and the current value of the key.
    let (om, val) = v.selected;
    overlay.cursor = (
        Some(om)
            .filter(|om| *om >= x.0 && *om <= x.1)
            .map(|om| frame.to_px(om, y.0).x),
        val.filter(|val| *val >= y.0.min(y.1) && *val <= y.0.max(y.1))
            .map(|val| frame.to_px(x.0, val).y),
    );
    // The boundaries, their cusps and the cells that disagree with them.
    overlay.curves = curve_lines(&frame, &v.boundaries);
    overlay.picked = v.picked.and_then(|(i, at)| {
        let c = v.boundaries.get(i)?;
        Some(super::boundaries::picked_glow(&frame, c, at))
    });
    overlay.cusps = v
        .cusps
        .iter()
        .map(|&(om, val)| {
            let q = frame.to_px(om, val);
            [q.x, q.y]
        })
        .collect();
    overlay.marks = mark_rects(&frame, g, &v.disagree);
    let font = small();
    for (entry, text, (kx, ky), _) in key {
        let swatch = |style: ShapeStyle| Rectangle::new([(kx, ky + 1), (kx + 12, ky + 12)], style);
        match entry {
            Entry::Text => {
                key_area
                    .draw(&Text::new(text, (kx, ky), font.clone()))
                    .map_err(err)?;
                continue;
            }
            Entry::Line(kind) => draw_line_sample(&key_area, (kx - 1, ky + 7), kind)?,
            Entry::Mark => key_area
                .draw(&swatch(ShapeStyle::from(&MARK).stroke_width(2)))
                .map_err(err)?,
            Entry::Swatch(color) => {
                key_area
                    .draw(&swatch(ShapeStyle::from(&color).filled()))
                    .map_err(err)?;
                key_area
                    .draw(&swatch(ShapeStyle::from(&GRID).stroke_width(1)))
                    .map_err(err)?;
            }
        }
        key_area
            .draw(&Text::new(text, (kx + 17, ky), font.clone()))
            .map_err(err)?;
    }
    root.present().map_err(err)?;
    Ok((frame, overlay))
}

/// The map's cells, period dots and cursor lines drawn with plotters (the
/// canvas fills them itself).
pub fn draw_map_overlay<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    f: &PlotFrame,
    o: &MapOverlay,
) -> Res<()> {
    for (c, rects) in &o.cells {
        for r in rects {
            let (x, y) = (r[0].round() as i32, r[1].round() as i32);
            let (w, h) = (r[2].round() as i32, r[3].round() as i32);
            root.draw(&Rectangle::new([(x, y), (x + w, y + h)], c.filled()))
                .map_err(err)?;
        }
    }
    for d in &o.dots {
        let c = (d[0].round() as i32, d[1].round() as i32);
        root.draw(&Circle::new(c, o.dot_radius.round() as i32, BLACK.filled()))
            .map_err(err)?;
    }
    let line = BLACK.mix(0.7).stroke_width(1);
    let (t, b) = (f.top_left, f.bottom_right);
    let mut lines = Vec::new();
    if let Some(x) = o.cursor.0 {
        lines.push([
            (x.round() as i32, t.y as i32),
            (x.round() as i32, b.y as i32),
        ]);
    }
    if let Some(y) = o.cursor.1 {
        lines.push([
            (t.x as i32, y.round() as i32),
            (b.x as i32, y.round() as i32),
        ]);
    }
    for l in lines {
        root.draw(&PathElement::new(l.to_vec(), line))
            .map_err(err)?;
    }
    // The traced boundaries (a clicked one's glow under them), the cells
    // that disagree with them, the cusps, the clicked point's ring.
    let px = |q: &[f64; 2]| (q[0].round() as i32, q[1].round() as i32);
    for l in o.picked.iter().map(|(l, _)| l).chain(&o.curves) {
        let style = l.color.stroke_width(l.width.round() as u32);
        for p in &l.paths {
            root.draw(&PathElement::new(
                p.iter().map(px).collect::<Vec<_>>(),
                style,
            ))
            .map_err(err)?;
        }
    }
    for r in &o.marks {
        let (x, y) = (r[0].round() as i32, r[1].round() as i32);
        let (w, h) = (r[2].round() as i32, r[3].round() as i32);
        let style = MARK.stroke_width(2);
        root.draw(&Rectangle::new([(x, y), (x + w, y + h)], style))
            .map_err(err)?;
    }
    for c in &o.cusps {
        root.draw(&Circle::new(px(c), 5, WHITE.filled()))
            .map_err(err)?;
        root.draw(&Circle::new(px(c), 5, BLACK.stroke_width(2)))
            .map_err(err)?;
    }
    if let Some((_, at)) = &o.picked {
        let ring = super::boundaries::PICKED.stroke_width(3);
        root.draw(&Circle::new(px(at), 8, ring)).map_err(err)?;
    }
    Ok(())
}

/// The map drawn as SVG text of `size` pixels, its cells, boundaries and
/// marks inside the chart (the CLI's map figure).
pub fn map_svg(v: &MapView, size: (u32, u32)) -> Res<String> {
    let mut s = String::new();
    let (frame, overlay) = {
        let root = SVGBackend::with_string(&mut s, size).into_drawing_area();
        let r = draw_map(&root, v, "")?;
        root.present().map_err(err)?;
        r
    };
    super::svg_with(&s, size, |root| draw_map_overlay(root, &frame, &overlay))
}

/// The map's key entries placed in lines across a canvas `w` pixels wide:
/// each entry with its position in the key's area and its text's width.
fn lay_out_key<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    items: Vec<(Entry, String)>,
    w: u32,
) -> Vec<(Entry, String, (i32, i32), i32)> {
    let font = small();
    let (mut kx, mut ky) = (12, 4);
    items
        .into_iter()
        .map(|(entry, text)| {
            let tw = root
                .estimate_text_size(&text, &font)
                .map_or(8 * text.len() as u32, |(w, _)| w) as i32;
            // A swatch, a line or a mark goes before its words.
            let icon = if matches!(entry, Entry::Text) { 0 } else { 17 };
            if kx + icon + tw > w as i32 - 8 && kx > 12 {
                kx = 12;
                ky += 17;
            }
            let at = (kx, ky);
            kx += icon + tw + 16;
            (entry, text, at, tw)
        })
        .collect()
}

/// An entry of the map's key.
#[derive(Debug, Clone, Copy)]
enum Entry {
    /// A filled square.
    Swatch(RGBColor),
    /// Text alone.
    Text,
    /// A boundary's line.
    Line(BoundaryKind),
    /// The disagreement outline.
    Mark,
}

/// Colour of an exponent's reading.
pub fn lyap_color(k: LyapKind) -> RGBColor {
    match k {
        LyapKind::Periodic => RGBColor(31, 119, 180),
        LyapKind::Neutral => RGBColor(230, 120, 0),
        LyapKind::Chaotic => RGBColor(200, 30, 40),
        LyapKind::Growth => RGBColor(120, 40, 140),
    }
}

/// Draws the largest Lyapunov exponent of the Poincaré map over Omega.
pub fn draw_lyap<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    store: &LyapStore,
    omega_range: (f64, f64),
    natural: &[NaturalFreq],
    selected: f64,
    speed: &crate::speed::SpeedAxis,
    status: &str,
) -> Res<PlotFrame> {
    root.fill(&WHITE).map_err(err)?;
    let curve = store.curve();
    let x = omega_range;
    // The key is under the chart, so the axes fit the curve alone.
    let y = padded_range(curve.iter().map(|p| p.1), &[0.0], 0.2);
    // The readings this model can have: chaos on a nonlinear one, growth
    // on a linear one.
    let kinds: Vec<LyapKind> = LyapKind::ALL
        .into_iter()
        .filter(|k| match k {
            LyapKind::Chaotic => !store.linear,
            LyapKind::Growth => store.linear,
            _ => true,
        })
        .collect();
    let zero_color = BLACK;
    let mut items: KeyItems = vec![(KeyIcon::Line(zero_color, false), "λ = 0".into())];
    for &kind in &kinds {
        items.push((KeyIcon::Dot(lyap_color(kind), 3), kind.label().into()));
    }
    items.extend(omega_items(natural, selected, speed));
    let failed = store.failed();
    let grey = RGBColor(90, 90, 90);
    if !failed.is_empty() {
        items.push((KeyIcon::Cross(grey), super::failed_label(&failed)));
    }
    let plan = plan_key(root, &items, Vec::new());
    let area = chart_area(root, &plan);
    let caption = format!(
        "Largest Lyapunov exponent of the Poincaré map ({} periods each){status}",
        store.periods
    );
    let axes = Axes {
        y_labels: Some(5),
        // Two decimals, and zero without a sign (plotters wrote "-0.0").
        y_format: Some(|v: &f64| format!("{:.2}", if v.abs() < 1e-9 { 0.0 } else { *v })),
        y_area_min: super::STACKED_Y_AREA,
        ..Axes::over_omega(speed, "λ per mesh period (−)")
    };
    let mut chart = linear_chart(&area, &caption, (x, y), &axes)?;
    omega_decorations(&mut chart, natural, selected, y)?;
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(x.0, 0.0), (x.1, 0.0)],
            ShapeStyle::from(&zero_color).stroke_width(1),
        )))
        .map_err(err)?;
    let band = RGBColor(230, 120, 0).mix(0.12);
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(x.0, -LYAP_ZERO_BAND), (x.1, LYAP_ZERO_BAND)],
            band.filled(),
        )))
        .map_err(err)?;
    chart
        .draw_series(LineSeries::new(
            curve.iter().copied(),
            ShapeStyle::from(&RGBColor(120, 120, 130)).stroke_width(1),
        ))
        .map_err(err)?;
    for &kind in &kinds {
        let c = lyap_color(kind);
        chart
            .draw_series(
                curve
                    .iter()
                    .copied()
                    .filter(|p| lyap_kind(p.1, store.linear) == kind)
                    .map(|p| Circle::new(p, 3, c.filled())),
            )
            .map_err(err)?;
    }
    if !failed.is_empty() {
        chart
            .draw_series(
                failed
                    .iter()
                    .map(|&(omega, _)| Cross::new((omega, y.0), 5, grey.stroke_width(2))),
            )
            .map_err(err)?;
    }
    let frame = frame_of(&chart, x, y);
    draw_key(root, &items, &plan)?;
    root.present().map_err(err)?;
    Ok(frame)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::plots::WIDTH;
    use crate::protocol::{LyapSample, MapSample};
    use crate::views::map::{MapGrid, MapStore};

    /// The map canvas's height (pixels).
    const MAP_HEIGHT: u32 = 460;
    /// The Lyapunov canvas's height (pixels).
    const LYAP_HEIGHT: u32 = 300;

    #[test]
    fn the_map_and_the_lyapunov_curve_draw_with_labelled_axes() {
        let grid = MapGrid {
            key: "te_um".into(),
            omega_from: 0.1,
            omega_to: 2.0,
            omega_points: 5,
            value_from: 0.0,
            value_to: 60.0,
            value_points: 3,
        };
        let mut store = MapStore::new(grid, String::new());
        store.add(vec![MapSample {
            row: 1,
            column: 2,
            omega: 1.05,
            value: 30.0,
            regime: Regime::DoubleSided,
            period: None,
            error: None,
        }]);
        let view = MapView {
            store: &store,
            mesh_label: "mesh s1a1".into(),
            selected: (1.05, Some(30.0)),
            boundaries: Vec::new(),
            cusps: Vec::new(),
            disagree: Vec::new(),
            picked: None,
            speed: Default::default(),
        };
        let mut s = String::new();
        let frame = {
            let root = SVGBackend::with_string(&mut s, (WIDTH, MAP_HEIGHT)).into_drawing_area();
            let (frame, overlay) = draw_map(&root, &view, "").unwrap();
            // 15 cells in two colours (one computed, 14 pending), one dot, both cursor lines.
            assert_eq!(overlay.cells.iter().map(|c| c.1.len()).sum::<usize>(), 15);
            assert_eq!(overlay.cells.len(), 2);
            assert_eq!(overlay.dots.len(), 1);
            assert!(overlay.cursor.0.is_some() && overlay.cursor.1.is_some());
            draw_map_overlay(&root, &frame, &overlay).unwrap();
            frame
        };
        assert!(s.contains("TE sine amplitude"), "axis label");
        assert!(s.contains("not period 1") && s.contains("double-sided impact"));
        // The frame maps the centre of the computed cell back to it.
        let px = frame.to_px(1.05, 30.0);
        let t = (px.x - frame.top_left.x) / (frame.bottom_right.x - frame.top_left.x);
        let om = frame.x_range.0 + t * (frame.x_range.1 - frame.x_range.0);
        assert!((om - 1.05).abs() < 1e-9);

        let lyap = LyapStore {
            linear: false,
            points: vec![
                LyapSample {
                    index: 0,
                    omega: 0.5,
                    per_period: Some(-0.4),
                    per_s: Some(-100.0),
                    error: None,
                },
                LyapSample {
                    index: 1,
                    omega: 1.0,
                    per_period: Some(0.1),
                    per_s: Some(40.0),
                    error: None,
                },
            ],
            total: 2,
            periods: 100,
        };
        let mut s = String::new();
        {
            let root = SVGBackend::with_string(&mut s, (WIDTH, LYAP_HEIGHT)).into_drawing_area();
            draw_lyap(&root, &lyap, (0.1, 2.0), &[], 0.84, &Default::default(), "").unwrap();
        }
        assert!(s.contains("λ per mesh period") && s.contains("chaotic") && s.contains("λ = 0"));
    }
}
