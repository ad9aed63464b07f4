//! The six plots, drawn with plotters on any backend: a canvas in the
//! browser (`plotters-canvas`), an SVG string in the native tests.
//!
//! Every plot labels its axes with units, draws the ±b contact lines where
//! contact matters, the natural frequencies and the selected-Omega cursor on
//! the Omega axes, and a legend. Axis ranges never shrink below a sensible
//! span, so numerical noise is never magnified into structure.
//!
//! Dense point clouds (the bifurcation diagram) are returned as pixel
//! positions grouped by colour, for the caller to draw in a batch: plotters
//! would set a fill style per pixel, which is slow on a canvas.

use crate::protocol::{history_start, OmegaResult, Regime, HISTORY_PERIODS};
use crate::views::bif::BifView;
use crate::views::fr::{FrCurvePoint, FrMarkerKind, FrView};
use crate::views::NaturalFreq;
use glam::DVec2;
use plotters::coord::{CoordTranslate, Shift};
use plotters::prelude::*;

/// Plot size in pixels (the canvases' width and height attributes).
pub const WIDTH: u32 = 760;
/// Plot height in pixels.
pub const HEIGHT: u32 = 400;

pub(crate) type Res<T> = Result<T, String>;
pub(crate) type Chart<'a, DB> = ChartContext<
    'a,
    DB,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

pub(crate) fn err<E: std::fmt::Display>(e: E) -> String {
    format!("drawing failed: {e}")
}

/// Colour of an impact regime.
pub fn regime_color(r: Regime) -> RGBColor {
    match r {
        Regime::NoImpact => RGBColor(31, 119, 180),
        Regime::SingleSided => RGBColor(230, 120, 0),
        Regime::DoubleSided => RGBColor(200, 30, 40),
        Regime::NoContact => RGBColor(40, 150, 60),
    }
}

pub(crate) const GRID: RGBColor = RGBColor(225, 229, 235);
const CONTACT: RGBColor = RGBColor(90, 90, 90);
pub(crate) const NATURAL: RGBColor = RGBColor(150, 110, 200);
pub(crate) const CURSOR: RGBColor = RGBColor(220, 20, 60);
const MAX_COLOR: RGBColor = RGBColor(25, 70, 150);
const MIN_COLOR: RGBColor = RGBColor(20, 140, 130);
const ORBIT: RGBColor = RGBColor(70, 110, 170);
const FADED: RGBColor = RGBColor(200, 200, 205);
/// The pinned state A of an A/B comparison: max and min x, and its dots.
const A_MAX: RGBColor = RGBColor(150, 40, 150);
const A_MIN: RGBColor = RGBColor(200, 110, 200);
const A_DOTS: RGBColor = RGBColor(185, 120, 200);

/// Where the data lie on the canvas, to map clicks back to Omega.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlotFrame {
    /// Top-left corner of the plotting area (pixels).
    pub top_left: DVec2,
    /// Bottom-right corner (pixels).
    pub bottom_right: DVec2,
    /// Data x range.
    pub x_range: (f64, f64),
    /// Data y range.
    pub y_range: (f64, f64),
}

impl PlotFrame {
    /// The data x (Omega) under pixel column `px`, clamped to the range;
    /// `None` if the click is well outside the plotting area.
    pub fn x_at(&self, px: f64) -> Option<f64> {
        let (l, r) = (self.top_left.x, self.bottom_right.x);
        if !(px.is_finite() && px >= l - 8.0 && px <= r + 8.0 && r > l) {
            return None;
        }
        let t = ((px - l) / (r - l)).clamp(0.0, 1.0);
        Some(self.x_range.0 + t * (self.x_range.1 - self.x_range.0))
    }

    /// The data point under pixel `(px, py)`, or `None` outside the
    /// plotting area.
    pub fn point_at(&self, px: f64, py: f64) -> Option<DVec2> {
        let (l, r) = (self.top_left.x, self.bottom_right.x);
        let (t, b) = (self.top_left.y, self.bottom_right.y);
        if !(px.is_finite() && py.is_finite() && px >= l && px <= r && py >= t && py <= b)
            || r <= l
            || b <= t
        {
            return None;
        }
        let tx = (px - l) / (r - l);
        let ty = (b - py) / (b - t);
        Some(DVec2::new(
            self.x_range.0 + tx * (self.x_range.1 - self.x_range.0),
            self.y_range.0 + ty * (self.y_range.1 - self.y_range.0),
        ))
    }

    /// The pixel of a data point.
    pub fn to_px(&self, x: f64, y: f64) -> DVec2 {
        let tx = (x - self.x_range.0) / (self.x_range.1 - self.x_range.0);
        let ty = (y - self.y_range.0) / (self.y_range.1 - self.y_range.0);
        DVec2::new(
            self.top_left.x + tx * (self.bottom_right.x - self.top_left.x),
            self.bottom_right.y - ty * (self.bottom_right.y - self.top_left.y),
        )
    }
}

/// Points of one colour and shape, in pixels.
#[derive(Debug, Clone, PartialEq)]
pub struct PointGroup {
    /// Colour.
    pub color: RGBColor,
    /// Filled dot (upward sweep) or open square (downward sweep).
    pub filled: bool,
    /// Pixel positions.
    pub px: Vec<(f32, f32)>,
}

/// Extends a range upwards to leave room for the legend above the data.
pub fn with_headroom(r: (f64, f64), fraction: f64) -> (f64, f64) {
    (r.0, r.1 + fraction * (r.1 - r.0))
}

/// A range that contains `values` and `extra`, padded, at least `min_span` wide.
pub fn padded_range(values: impl Iterator<Item = f64>, extra: &[f64], min_span: f64) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values
        .chain(extra.iter().copied())
        .filter(|v| v.is_finite())
    {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let span = (hi - lo).max(min_span.max(1e-12));
    let mid = 0.5 * (hi + lo);
    let half = 0.5 * span * 1.08;
    (mid - half, mid + half)
}

pub(crate) fn frame_of<DB: DrawingBackend, X, Y>(
    chart: &ChartContext<DB, Cartesian2d<X, Y>>,
    x_range: (f64, f64),
    y_range: (f64, f64),
) -> PlotFrame
where
    X: plotters::coord::ranged1d::Ranged<ValueType = f64>,
    Y: plotters::coord::ranged1d::Ranged<ValueType = f64>,
{
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    PlotFrame {
        top_left: DVec2::new(f64::from(xr.start), f64::from(yr.start)),
        bottom_right: DVec2::new(f64::from(xr.end), f64::from(yr.end)),
        x_range,
        y_range,
    }
}

pub(crate) fn caption_font() -> TextStyle<'static> {
    ("sans-serif", 17).into_font().color(&BLACK)
}

pub(crate) fn small() -> TextStyle<'static> {
    ("sans-serif", 13).into_font().color(&RGBColor(50, 50, 50))
}

/// A plot with nothing to show yet: a frame and a message (never blank).
pub fn draw_message<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    message: &str,
) -> Res<()> {
    root.fill(&WHITE).map_err(err)?;
    let (w, h) = root.dim_in_pixel();
    root.draw(&Rectangle::new(
        [(1, 1), (w as i32 - 2, h as i32 - 2)],
        ShapeStyle::from(&GRID).stroke_width(1),
    ))
    .map_err(err)?;
    root.draw(&Text::new(title.to_string(), (12, 10), caption_font()))
        .map_err(err)?;
    for (k, line) in wrap(message, 80).iter().enumerate() {
        root.draw(&Text::new(
            line.clone(),
            (24, h as i32 / 2 - 10 + 18 * k as i32),
            ("sans-serif", 14).into_font().color(&RGBColor(90, 90, 90)),
        ))
        .map_err(err)?;
    }
    root.present().map_err(err)
}

/// Breaks text into lines of at most `width` characters (at spaces).
pub fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut cur = String::new();
    for word in text.split_whitespace() {
        if !cur.is_empty() && cur.chars().count() + 1 + word.chars().count() > width {
            lines.push(std::mem::take(&mut cur));
        }
        if !cur.is_empty() {
            cur.push(' ');
        }
        cur.push_str(word);
    }
    if !cur.is_empty() {
        lines.push(cur);
    }
    lines.truncate(6);
    lines
}

/// Draws the Omega-axis decorations: natural frequencies and the cursor.
pub(crate) fn omega_decorations<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    natural: &[NaturalFreq],
    selected: f64,
    y: (f64, f64),
    in_legend: bool,
) -> Res<()> {
    let nat_style = ShapeStyle::from(&NATURAL.mix(0.55)).stroke_width(1);
    let mut first = in_legend;
    for n in natural {
        let s = chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(n.omega, y.0), (n.omega, y.1)],
                nat_style,
            )))
            .map_err(err)?;
        if first {
            s.label("natural frequencies (linear, mean k)")
                .legend(move |(x, yy)| PathElement::new(vec![(x, yy), (x + 16, yy)], nat_style));
            first = false;
        }
    }
    let cursor = chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(selected, y.0), (selected, y.1)],
            ShapeStyle::from(&CURSOR).stroke_width(2),
        )))
        .map_err(err)?;
    if !in_legend {
        return Ok(());
    }
    cursor
        .label(format!("selected Omega = {selected:.3}"))
        .legend(|(x, yy)| {
            PathElement::new(
                vec![(x, yy), (x + 16, yy)],
                ShapeStyle::from(&CURSOR).stroke_width(2),
            )
        });
    Ok(())
}

/// Draws the pinned state A's ±b lines (A/B comparison) where they differ
/// from B's, dashed in A's colour; returns whether any were drawn.
fn pinned_contact_lines<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    pinned_um: &[f64],
    current_um: &[f64],
    x: (f64, f64),
) -> Res<bool> {
    let style = ShapeStyle::from(&A_MIN).stroke_width(1);
    let mut any = false;
    for &b in pinned_um
        .iter()
        .filter(|b| !current_um.iter().any(|c| (*c - **b).abs() < 1e-9))
    {
        for v in [b, -b] {
            chart
                .draw_series(DashedLineSeries::new(vec![(x.0, v), (x.1, v)], 6, 4, style))
                .map_err(err)?;
        }
        any = true;
    }
    Ok(any)
}

/// Draws the ±b contact lines across the x range.
fn contact_lines<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    backlash_um: &[f64],
    x: (f64, f64),
    horizontal: bool,
    in_legend: bool,
) -> Res<()> {
    let style = ShapeStyle::from(&CONTACT).stroke_width(1);
    let mut first = in_legend;
    for &b in backlash_um {
        for v in [b, -b] {
            let pts = if horizontal {
                vec![(x.0, v), (x.1, v)]
            } else {
                vec![(v, x.0), (v, x.1)]
            };
            let s = chart
                .draw_series(DashedLineSeries::new(pts, 6, 4, style))
                .map_err(err)?;
            if first {
                s.label(format!("±b contact lines (b = {b} µm)"))
                    .legend(move |(xx, yy)| {
                        PathElement::new(
                            vec![(xx, yy), (xx + 6, yy), (xx + 10, yy), (xx + 16, yy)],
                            style,
                        )
                    });
                first = false;
            }
        }
    }
    Ok(())
}

fn legend<'a, DB: DrawingBackend + 'a, CT: CoordTranslate>(
    chart: &mut ChartContext<'a, DB, CT>,
    pos: SeriesLabelPosition,
) -> Res<()> {
    chart
        .configure_series_labels()
        .position(pos)
        .background_style(WHITE.mix(0.8))
        .border_style(GRID)
        .margin(6)
        .legend_area_size(22)
        .label_font(("sans-serif", 12))
        .draw()
        .map_err(err)
}

/// A symbol of the key row under the frequency response.
#[derive(Debug, Clone, Copy)]
enum KeyIcon {
    Regime(Regime),
    Marker(FrMarkerKind),
    Overlay,
    Line(RGBColor, bool),
}

const MARKER: RGBColor = RGBColor(0, 0, 0);
const OVERLAY: RGBColor = RGBColor(60, 60, 60);
const FAILURE: RGBColor = RGBColor(170, 0, 0);

/// Row height of the key (pixels).
const KEY_ROW: i32 = 17;

/// Where each key item goes, left to right from `x0`, wrapping at the right
/// edge; rows relative to the first (0, 17, ...). Also returns the rows used.
fn key_layout<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    items: &[(KeyIcon, String)],
    x0: i32,
) -> (Vec<(i32, i32)>, i32) {
    let font = small();
    let right = root.dim_in_pixel().0 as i32 - 8;
    let (mut x, mut y) = (x0, 0);
    let mut out = Vec::with_capacity(items.len());
    for (icon, text) in items {
        let w = root
            .estimate_text_size(text, &font)
            .map_or(8 * text.len() as u32, |(w, _)| w) as i32;
        let icon_w = if matches!(icon, KeyIcon::Line(..)) {
            22
        } else {
            14
        };
        if x > x0 && x + icon_w + w > right {
            x = x0;
            y += KEY_ROW;
        }
        out.push((x, y));
        x += icon_w + w + 16;
    }
    let rows = if items.is_empty() { 0 } else { y / KEY_ROW + 1 };
    (out, rows)
}

/// Draws the key (the contact lines, natural frequencies and cursor,
/// regimes present, bifurcation kinds present, the overlay) at the
/// positions of [`key_layout`], offset by `y0`.
fn key_row<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    items: &[(KeyIcon, String)],
    at: &[(i32, i32)],
    y0: i32,
) -> Res<()> {
    let font = small();
    for ((icon, text), &(x, dy)) in items.iter().zip(at) {
        let y = y0 + dy;
        let c = (x + 5, y);
        let text_x = if let KeyIcon::Line(color, dashed) = *icon {
            let style = ShapeStyle::from(&color).stroke_width(2);
            if dashed {
                for k in 0..2 {
                    root.draw(&PathElement::new(
                        vec![(x + 10 * k, y), (x + 10 * k + 6, y)],
                        style,
                    ))
                    .map_err(err)?;
                }
            } else {
                root.draw(&PathElement::new(vec![(x, y), (x + 16, y)], style))
                    .map_err(err)?;
            }
            x + 22
        } else {
            x + 14
        };
        match *icon {
            KeyIcon::Line(..) => {}
            KeyIcon::Regime(r) => root
                .draw(&Circle::new(c, 4, regime_color(r).filled()))
                .map_err(err)?,
            KeyIcon::Marker(k) => draw_marker_px(root, k, c)?,
            KeyIcon::Overlay => root
                .draw(&Circle::new(c, 4, OVERLAY.stroke_width(1)))
                .map_err(err)?,
        }
        root.draw(&Text::new(text.clone(), (text_x, y - 7), font.clone()))
            .map_err(err)?;
    }
    Ok(())
}

/// A bifurcation marker at a pixel position.
fn draw_marker_px<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    kind: FrMarkerKind,
    c: (i32, i32),
) -> Res<()> {
    match kind {
        FrMarkerKind::Fold => root
            .draw(&TriangleMarker::new(c, 6, MARKER.filled()))
            .map_err(err),
        FrMarkerKind::PeriodDoubling => root
            .draw(&Cross::new(c, 5, MARKER.stroke_width(2)))
            .map_err(err),
        FrMarkerKind::NeimarkSacker => root
            .draw(&Circle::new(c, 5, MARKER.stroke_width(2)))
            .map_err(err),
        FrMarkerKind::BranchPoint => root
            .draw(&Rectangle::new(
                [(c.0 - 4, c.1 - 4), (c.0 + 4, c.1 + 4)],
                MARKER.stroke_width(2),
            ))
            .map_err(err),
    }
}

/// The impact regime along Omega as a thin coloured strip at the bottom of
/// the plot: the branch's own lines keep the max / min colours and the
/// dashes of unstable stretches readable. Only stable (or unknown) stretches
/// are drawn, since only they can be observed.
fn regime_strip<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    points: &[FrCurvePoint],
    y: (f64, f64),
) -> Res<()> {
    let (lo, hi) = (y.0, y.0 + 0.025 * (y.1 - y.0));
    // Runs of one regime along the branch become one rectangle each: a
    // branch has about a thousand points but only tens of runs.
    let mut runs: Vec<(Regime, f64, f64)> = Vec::new();
    let mut open = false;
    for w in points.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let regime = b
            .regime
            .filter(|_| a.stable != Some(false) && b.stable != Some(false));
        let Some(r) = regime else {
            open = false;
            continue;
        };
        let (from, to) = (a.omega.min(b.omega), a.omega.max(b.omega));
        match runs.last_mut() {
            Some(run) if open && run.0 == r => {
                run.1 = run.1.min(from);
                run.2 = run.2.max(to);
            }
            _ => runs.push((r, from, to)),
        }
        open = true;
    }
    chart
        .draw_series(
            runs.into_iter().map(|(r, from, to)| {
                Rectangle::new([(from, lo), (to, hi)], regime_color(r).filled())
            }),
        )
        .map_err(err)?;
    Ok(())
}

/// View 1: the frequency response (harmonic-balance branch, stable solid,
/// unstable dashed, bifurcation markers, optional time-integration dots).
pub fn draw_fr<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    v: &FrView,
    status: &str,
) -> Res<PlotFrame> {
    root.fill(&WHITE).map_err(err)?;
    let x = (v.omega_from, v.omega_to);
    let in_range = |o: f64| o >= x.0 && o <= x.1;
    let all = v
        .branches
        .iter()
        .flat_map(|b| b.points.iter())
        .chain(v.overlay.iter())
        .filter(|p| in_range(p.omega))
        .flat_map(|p| [p.max_um, p.min_um]);
    let mut extra: Vec<f64> = v
        .backlash_um
        .iter()
        .chain(v.pinned_backlash_um.iter())
        .flat_map(|b| [*b, -*b])
        .collect();
    extra.push(0.0);
    // Room at the top for the legend (two lines per branch, the faded
    // branch, the unstable dash, the failure line).
    let entries = v.branches.iter().filter(|b| !b.faded).count() * 2
        + usize::from(v.branches.iter().any(|b| b.faded))
        + usize::from(v.branch_error.is_some())
        + 1;
    let y = with_headroom(padded_range(all, &extra, 20.0), 0.25 + 0.1 * entries as f64);
    // The key under the chart: contact lines, natural frequencies, the
    // cursor, regimes, bifurcations, overlay.
    let mut items: Vec<(KeyIcon, String)> = Vec::new();
    if !v.backlash_um.is_empty() {
        let bs: Vec<String> = v.backlash_um.iter().map(|b| format!("{b}")).collect();
        items.push((
            KeyIcon::Line(CONTACT, true),
            format!("±b contact lines (b = {} µm)", bs.join(", ")),
        ));
    }
    let a_only: Vec<String> = v
        .pinned_backlash_um
        .iter()
        .filter(|b| !v.backlash_um.iter().any(|c| (*c - **b).abs() < 1e-9))
        .map(|b| format!("{b}"))
        .collect();
    if !a_only.is_empty() {
        items.push((
            KeyIcon::Line(A_MIN, true),
            format!("A's ±b (b = {} µm)", a_only.join(", ")),
        ));
    }
    if !v.natural.is_empty() {
        items.push((
            KeyIcon::Line(NATURAL, false),
            "natural frequencies (linear, mean k)".into(),
        ));
    }
    items.push((
        KeyIcon::Line(CURSOR, false),
        format!("selected Ω = {:.3}", v.selected_omega),
    ));
    let mut seen = [false; 4];
    for r in v
        .branches
        .iter()
        .filter(|b| !b.faded)
        .flat_map(|b| b.points.iter().filter_map(|p| p.regime))
        .chain(v.overlay.iter().filter_map(|p| p.regime))
    {
        if let Some(i) = Regime::ALL.iter().position(|&x| x == r) {
            seen[i] = true;
        }
    }
    let mut first = true;
    for (i, r) in Regime::ALL.iter().enumerate() {
        if seen[i] {
            let text = if first {
                format!("regime strip (stable): {}", r.label())
            } else {
                r.label().to_string()
            };
            first = false;
            items.push((KeyIcon::Regime(*r), text));
        }
    }
    for k in FrMarkerKind::ALL {
        if v.markers.iter().any(|m| m.kind == k) {
            items.push((KeyIcon::Marker(k), k.label().to_string()));
        }
    }
    if v.overlay_source.is_some() {
        let d = &v.discrepancy;
        let mut text = format!("time integration ({} pts)", v.overlay.len());
        if let Some(m) = d.max_um {
            text.push_str(&format!(
                ": max |Δx| {m:.2} µm at {} on the stable branch",
                d.compared
            ));
        }
        if d.off_branch > 0 {
            text.push_str(&format!("; {} where none is stable", d.off_branch));
        }
        items.push((KeyIcon::Overlay, text));
    }
    let (at, rows) = key_layout(root, &items, 76);
    let key_h = 8 + KEY_ROW * rows;
    let (upper, _) = root.split_vertically(HEIGHT as i32 - key_h);
    let mut chart = ChartBuilder::on(&upper)
        .caption(
            format!(
                "Frequency response, mesh {} ({}){status}",
                v.mesh_label, v.method
            ),
            caption_font(),
        )
        .margin(8)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .light_line_style(GRID.mix(0.5))
        .bold_line_style(GRID)
        .x_desc("Ω = ω / ω_ref (dimensionless mesh frequency)")
        .y_desc("x = δ − e (µm)")
        .label_style(small())
        .axis_desc_style(small())
        .draw()
        .map_err(err)?;
    // These three go in the key under the chart, keeping the legend short.
    contact_lines(&mut chart, &v.backlash_um, x, true, false)?;
    pinned_contact_lines(&mut chart, &v.pinned_backlash_um, &v.backlash_um, x)?;
    omega_decorations(&mut chart, &v.natural, v.selected_omega, y, false)?;
    let mut any_unstable = false;
    for br in &v.branches {
        for (which, color, label) in [(true, MAX_COLOR, "max x"), (false, MIN_COLOR, "min x")] {
            let color = match (br.faded, br.pinned, which) {
                (true, _, _) => FADED,
                (false, true, true) => A_MAX,
                (false, true, false) => A_MIN,
                _ => color,
            };
            let val = |p: &FrCurvePoint| if which { p.max_um } else { p.min_um };
            // Split into runs of equal stability: stable (or unknown) solid,
            // unstable dashed; consecutive runs share their joining point.
            let mut runs: Vec<(bool, Vec<(f64, f64)>)> = Vec::new();
            for p in &br.points {
                let unstable = p.stable == Some(false);
                match runs.last_mut() {
                    Some((u, pts)) if *u == unstable => pts.push((p.omega, val(p))),
                    _ => {
                        let mut pts = Vec::new();
                        if let Some((_, prev)) = runs.last() {
                            if let Some(&last) = prev.last() {
                                pts.push(last);
                            }
                        }
                        pts.push((p.omega, val(p)));
                        runs.push((unstable, pts));
                    }
                }
            }
            let style = ShapeStyle::from(&color).stroke_width(2);
            // The faded branch is labelled once, not per extreme.
            let mut labelled = br.faded && !which;
            for (unstable, pts) in runs {
                let s = if unstable {
                    any_unstable |= !br.faded;
                    chart
                        .draw_series(DashedLineSeries::new(pts, 5, 4, style))
                        .map_err(err)?
                } else {
                    chart
                        .draw_series(LineSeries::new(pts, style))
                        .map_err(err)?
                };
                if !labelled {
                    let text = if br.faded {
                        "previous settings (updating)".to_string()
                    } else {
                        format!("{label} ({})", br.label)
                    };
                    s.label(text).legend(move |(xx, yy)| {
                        PathElement::new(vec![(xx, yy), (xx + 16, yy)], style)
                    });
                    labelled = true;
                }
            }
            if br.faded {
                continue;
            }
        }
        if !br.faded && !br.pinned {
            regime_strip(&mut chart, &br.points, y)?;
        }
    }
    if any_unstable {
        let style = ShapeStyle::from(&CONTACT).stroke_width(2);
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
            .map_err(err)?
            .label("unstable (Floquet): dashed")
            .legend(move |(xx, yy)| {
                PathElement::new(
                    vec![(xx, yy), (xx + 5, yy), (xx + 9, yy), (xx + 16, yy)],
                    style,
                )
            });
    }
    // Time-integration steady states: hollow dots on both extremes.
    chart
        .draw_series(
            v.overlay
                .iter()
                .filter(|p| in_range(p.omega))
                .flat_map(|p| [(p.omega, p.max_um), (p.omega, p.min_um)])
                .map(|c| Circle::new(c, 4, OVERLAY.stroke_width(1))),
        )
        .map_err(err)?;
    for m in v.markers.iter().filter(|m| in_range(m.omega)) {
        let c = chart.backend_coord(&(m.omega, m.value_um));
        draw_marker_px(root, m.kind, c)?;
    }
    if let Some((at, _)) = &v.branch_error {
        chart
            .draw_series(DashedLineSeries::new(
                vec![(*at, y.0), (*at, y.1)],
                3,
                3,
                ShapeStyle::from(&FAILURE).stroke_width(2),
            ))
            .map_err(err)?
            .label("solver failure: branch ends")
            .legend(|(xx, yy)| {
                PathElement::new(
                    vec![(xx, yy), (xx + 16, yy)],
                    ShapeStyle::from(&FAILURE).stroke_width(2),
                )
            });
    }
    legend(&mut chart, SeriesLabelPosition::UpperRight)?;
    let frame = frame_of(&chart, x, y);

    key_row(root, &items, &at, HEIGHT as i32 - key_h + 12)?;
    let mut notes = Vec::new();
    if let Some((at, e)) = &v.branch_error {
        let text = format!(
            "Solver failure after Ω = {at:.4}: {}. The branch ends there (partial).",
            solver::keys::truncate(e, 160)
        );
        notes.extend(wrap(&text, 84));
    }
    // A finished branch that turned back at a fold and left the range at its
    // lower end covers only part of the range: say so rather than let the
    // empty part read as "no response".
    if v.finished && v.branch_error.is_none() {
        for br in v.branches.iter().filter(|b| !b.faded) {
            let reach = br
                .points
                .iter()
                .map(|p| p.omega)
                .fold(f64::NEG_INFINITY, f64::max);
            if reach.is_finite() && reach < x.1 - 0.01 * (x.1 - x.0) {
                let who = if br.pinned {
                    "A's branch"
                } else {
                    "The branch"
                };
                notes.extend(wrap(
                    &format!(
                        "{who} turns back at Ω = {reach:.3} (a fold) and leaves the range below: above it the response lies on another branch (see the bifurcation diagram)."
                    ),
                    84,
                ));
            }
        }
    }
    if !v.failed.is_empty() {
        notes.push(format!(
            "{} time-integration point(s) failed: not plotted",
            v.failed.len()
        ));
    }
    let first_y = frame.bottom_right.y as i32 - 24 - 16 * (notes.len() as i32 - 1);
    for (k, n) in notes.iter().enumerate() {
        root.draw(&Text::new(
            n.clone(),
            (76, first_y + 16 * k as i32),
            ("sans-serif", 13).into_font().color(&FAILURE),
        ))
        .map_err(err)?;
    }
    root.present().map_err(err)?;
    Ok(frame)
}

/// Legend entries for the regimes present.
fn regime_legend<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    present: impl Iterator<Item = Regime>,
) -> Res<()> {
    let mut seen = [false; 4];
    for r in present {
        if let Some(i) = Regime::ALL.iter().position(|&x| x == r) {
            seen[i] = true;
        }
    }
    for (i, r) in Regime::ALL.iter().enumerate() {
        if seen[i] {
            let c = regime_color(*r);
            chart
                .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
                .map_err(err)?
                .label(r.label())
                .legend(move |(x, y)| Circle::new((x + 8, y), 4, c.filled()));
        }
    }
    Ok(())
}

/// The shade of the Omega bands where the engaged system is parametrically
/// unstable.
const UNSTABLE_BAND: RGBColor = RGBColor(90, 90, 90);

/// The legend entry for failed sweep points: how many, and the first one's
/// reason (its message up to the first colon, e.g. "the response grows
/// without bound").
pub fn failed_label(failed: &[(f64, String)]) -> String {
    let reason = failed
        .first()
        .map(|(omega, e)| {
            format!(
                ", first at Ω = {omega:.3}: {}",
                e.split(':').next().unwrap_or(e)
            )
        })
        .unwrap_or_default();
    format!("{} point(s) failed, not plotted{reason}", failed.len())
}

/// View 2: the bifurcation diagram. Returns the frame and the dots (in
/// pixels, grouped by colour and sweep direction) for the caller to draw.
pub fn draw_bif<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    v: &BifView,
    natural: &[NaturalFreq],
    status: &str,
) -> Res<(PlotFrame, Vec<PointGroup>)> {
    root.fill(&WHITE).map_err(err)?;
    let x = (v.omega_from, v.omega_to);
    let mut extra: Vec<f64> = v
        .backlash_um
        .iter()
        .chain(v.pinned_backlash_um.iter())
        .flat_map(|b| [*b, -*b])
        .collect();
    extra.push(0.0);
    let y = with_headroom(
        padded_range(
            v.points.iter().chain(v.pinned.iter()).map(|p| p.x_um),
            &extra,
            20.0,
        ),
        if v.ab_labels.is_some() { 0.8 } else { 0.55 },
    );
    let mut chart = ChartBuilder::on(root)
        .caption(
            format!("Bifurcation diagram, mesh {}{status}", v.mesh_label),
            caption_font(),
        )
        .margin(8)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .light_line_style(GRID.mix(0.5))
        .bold_line_style(GRID)
        .x_desc("Ω = ω / ω_ref (dimensionless mesh frequency)")
        .y_desc("Poincaré samples of x = δ − e (µm)")
        .label_style(small())
        .axis_desc_style(small())
        .draw()
        .map_err(err)?;
    contact_lines(&mut chart, &v.backlash_um, x, true, true)?;
    if pinned_contact_lines(&mut chart, &v.pinned_backlash_um, &v.backlash_um, x)? {
        let style = ShapeStyle::from(&A_MIN).stroke_width(1);
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
            .map_err(err)?
            .label("A's ±b contact lines")
            .legend(move |(xx, yy)| {
                PathElement::new(
                    vec![(xx, yy), (xx + 6, yy), (xx + 10, yy), (xx + 16, yy)],
                    style,
                )
            });
    }
    if !v.unstable_bands.is_empty() {
        // Where motion large against the backlash grows without bound (the
        // engaged system's Floquet spectral radius above 1), under the dots.
        let shade = UNSTABLE_BAND.mix(0.14);
        chart
            .draw_series(v.unstable_bands.iter().map(|&(a, b)| {
                Rectangle::new([(a.max(x.0), y.0), (b.min(x.1), y.1)], shade.filled())
            }))
            .map_err(err)?
            .label("parametrically unstable with all teeth engaged")
            .legend(move |(px, py)| {
                Rectangle::new([(px + 2, py - 4), (px + 14, py + 4)], shade.filled())
            });
    }
    omega_decorations(&mut chart, natural, v.selected_omega, y, true)?;
    let frame = frame_of(&chart, x, y);
    let mut groups: Vec<PointGroup> = Vec::new();
    if !v.pinned.is_empty() {
        // A's dots first, so B's are drawn over them.
        for up in [true, false] {
            let px: Vec<(f32, f32)> = v
                .pinned
                .iter()
                .filter(|p| p.up == up)
                .map(|p| {
                    let q = frame.to_px(p.omega, p.x_um);
                    (q.x as f32, q.y as f32)
                })
                .collect();
            if !px.is_empty() {
                groups.push(PointGroup {
                    color: A_DOTS,
                    filled: up,
                    px,
                });
            }
        }
    }
    for p in &v.points {
        let color = regime_color(p.regime);
        let q = frame.to_px(p.omega, p.x_um);
        let px = (q.x as f32, q.y as f32);
        match groups
            .iter_mut()
            .find(|g| g.color == color && g.filled == p.up)
        {
            Some(g) => g.px.push(px),
            None => groups.push(PointGroup {
                color,
                filled: p.up,
                px: vec![px],
            }),
        }
    }
    if let Some((a, b)) = &v.ab_labels {
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
            .map_err(err)?
            .label(format!("A (pinned): {a}"))
            .legend(move |(x, y)| Circle::new((x + 8, y), 4, A_DOTS.filled()));
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
            .map_err(err)?
            .label(format!("B (current, regime colours): {b}"))
            .legend(move |(x, y)| {
                Circle::new((x + 8, y), 4, regime_color(Regime::SingleSided).filled())
            });
    }
    regime_legend(&mut chart, v.points.iter().map(|p| p.regime))?;
    let dark = RGBColor(60, 60, 60);
    if v.points.iter().any(|p| p.up) {
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
            .map_err(err)?
            .label("upward sweep")
            .legend(move |(x, y)| Circle::new((x + 8, y), 2, dark.filled()));
    }
    if v.points.iter().any(|p| !p.up) {
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
            .map_err(err)?
            .label("downward sweep")
            .legend(move |(x, y)| {
                Rectangle::new([(x + 6, y - 2), (x + 10, y + 2)], dark.stroke_width(1))
            });
    }
    if !v.failed.is_empty() {
        // Where the sweep failed: a grey cross on the Omega axis each, and
        // the first failure's reason (its message up to the first colon).
        let grey = RGBColor(90, 90, 90);
        chart
            .draw_series(
                v.failed
                    .iter()
                    .map(|&(omega, _)| Cross::new((omega, y.0), 5, grey.stroke_width(2))),
            )
            .map_err(err)?
            .label(failed_label(&v.failed))
            .legend(move |(x, y)| Cross::new((x + 8, y), 4, grey.stroke_width(2)));
    }
    legend(&mut chart, SeriesLabelPosition::UpperRight)?;
    root.present().map_err(err)?;
    Ok((frame, groups))
}

/// Draws point groups with plotters (for backends without a fast path).
pub fn draw_groups<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    groups: &[PointGroup],
) -> Res<()> {
    for g in groups {
        for &(x, y) in &g.px {
            let (x, y) = (x.round() as i32, y.round() as i32);
            if g.filled {
                root.draw(&Rectangle::new(
                    [(x - 1, y - 1), (x + 1, y + 1)],
                    g.color.filled(),
                ))
                .map_err(err)?;
            } else {
                root.draw(&Rectangle::new(
                    [(x - 2, y - 2), (x + 2, y + 2)],
                    g.color.stroke_width(1),
                ))
                .map_err(err)?;
            }
        }
    }
    root.present().map_err(err)
}

fn phase_ranges(r: &OmegaResult) -> ((f64, f64), (f64, f64)) {
    let b = r.backlash_um;
    let x = padded_range(r.x_um.iter().copied(), &[b, -b], 20.0);
    let vmax = r.xdot_m_s.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let y = padded_range(r.xdot_m_s.iter().copied(), &[], (vmax * 0.2).max(1e-3));
    (x, with_headroom(y, 0.25))
}

fn omega_caption(what: &str, r: &OmegaResult, status: &str) -> String {
    format!("{what}, mesh {}, Ω = {:.4}{status}", r.mesh_name, r.omega)
}

/// View 3: the phase portrait with its Poincaré points.
pub fn draw_phase<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &OmegaResult,
    status: &str,
) -> Res<()> {
    root.fill(&WHITE).map_err(err)?;
    let (x, y) = phase_ranges(r);
    let mut chart = ChartBuilder::on(root)
        .caption(omega_caption("Phase portrait", r, status), caption_font())
        .margin(8)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .light_line_style(GRID.mix(0.5))
        .bold_line_style(GRID)
        .x_desc("x = δ − e (µm)")
        .y_desc("ẋ (m/s)")
        .label_style(small())
        .axis_desc_style(small())
        .draw()
        .map_err(err)?;
    contact_lines(&mut chart, &[r.backlash_um], y, false, true)?;
    let orbit = ShapeStyle::from(&ORBIT.mix(0.7)).stroke_width(1);
    chart
        .draw_series(LineSeries::new(
            r.x_um.iter().copied().zip(r.xdot_m_s.iter().copied()),
            orbit,
        ))
        .map_err(err)?
        .label(format!("orbit over {} recorded periods", r.record_periods))
        .legend(move |(xx, yy)| PathElement::new(vec![(xx, yy), (xx + 16, yy)], orbit));
    chart
        .draw_series(
            r.poincare_x_um
                .iter()
                .zip(&r.poincare_xdot_m_s)
                .map(|(&a, &b)| Circle::new((a, b), 4, CURSOR.filled())),
        )
        .map_err(err)?
        .label("Poincaré points (once per mesh period)")
        .legend(|(xx, yy)| Circle::new((xx + 8, yy), 4, CURSOR.filled()));
    legend(&mut chart, SeriesLabelPosition::UpperLeft)?;
    root.present().map_err(err)
}

/// View 4: the Poincaré section, on the orbit's axes so that one point reads as one point.
pub fn draw_poincare<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &OmegaResult,
    status: &str,
) -> Res<()> {
    root.fill(&WHITE).map_err(err)?;
    let (x, y) = phase_ranges(r);
    let mut chart = ChartBuilder::on(root)
        .caption(omega_caption("Poincaré section", r, status), caption_font())
        .margin(8)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .light_line_style(GRID.mix(0.5))
        .bold_line_style(GRID)
        .x_desc("x = δ − e (µm), sampled once per mesh period")
        .y_desc("ẋ (m/s)")
        .label_style(small())
        .axis_desc_style(small())
        .draw()
        .map_err(err)?;
    contact_lines(&mut chart, &[r.backlash_um], y, false, true)?;
    let period = match r.period {
        Some(p) => format!("period {p}"),
        None => "not periodic".into(),
    };
    chart
        .draw_series(
            r.poincare_x_um
                .iter()
                .zip(&r.poincare_xdot_m_s)
                .map(|(&a, &b)| Circle::new((a, b), 3, CURSOR.filled())),
        )
        .map_err(err)?
        .label(format!(
            "{} Poincaré points ({period})",
            r.poincare_x_um.len()
        ))
        .legend(|(xx, yy)| Circle::new((xx + 8, yy), 3, CURSOR.filled()));
    legend(&mut chart, SeriesLabelPosition::UpperLeft)?;
    root.present().map_err(err)
}

/// View 5a: the time history of the last recorded periods.
pub fn draw_time<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &OmegaResult,
    status: &str,
) -> Res<PlotFrame> {
    root.fill(&WHITE).map_err(err)?;
    let spp = r.samples_per_period.max(1) as usize;
    let shown = HISTORY_PERIODS.min(r.record_periods) as usize;
    let start = history_start(r.x_um.len(), r.samples_per_period, r.record_periods);
    let t0 = start as f64 / spp as f64;
    let t1 = (r.x_um.len().max(1) - 1) as f64 / spp as f64;
    let x = (t0, t1.max(t0 + 1e-9));
    let b = r.backlash_um;
    let y = with_headroom(
        padded_range(r.x_um[start..].iter().copied(), &[b, -b], 20.0),
        0.2,
    );
    let mut chart = ChartBuilder::on(root)
        .caption(omega_caption("Time history", r, status), caption_font())
        .margin(8)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(err)?;
    chart
        .configure_mesh()
        .light_line_style(GRID.mix(0.5))
        .bold_line_style(GRID)
        .x_desc(format!(
            "time (mesh periods since the recording began; last {shown} of {})",
            r.record_periods
        ))
        .y_desc("x = δ − e (µm)")
        .label_style(small())
        .axis_desc_style(small())
        .draw()
        .map_err(err)?;
    contact_lines(&mut chart, &[b], x, true, true)?;
    let style = ShapeStyle::from(&ORBIT).stroke_width(2);
    chart
        .draw_series(LineSeries::new(
            r.x_um[start..]
                .iter()
                .enumerate()
                .map(|(k, &v)| ((start + k) as f64 / spp as f64, v)),
            style,
        ))
        .map_err(err)?
        .label("x(t)")
        .legend(move |(xx, yy)| PathElement::new(vec![(xx, yy), (xx + 16, yy)], style));
    legend(&mut chart, SeriesLabelPosition::UpperRight)?;
    let frame = frame_of(&chart, x, y);
    root.present().map_err(err)?;
    Ok(frame)
}

/// View 5b: the amplitude spectrum of x (without the mean), log scale.
pub fn draw_spectrum<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &OmegaResult,
    status: &str,
) -> Res<()> {
    root.fill(&WHITE).map_err(err)?;
    let lines: Vec<(f64, f64)> = r
        .spectrum_order
        .iter()
        .zip(&r.spectrum_um)
        .filter(|(o, _)| **o > 0.0)
        .map(|(&o, &a)| (o, a))
        .collect();
    let mean = r
        .spectrum_order
        .first()
        .filter(|o| **o == 0.0)
        .and_then(|_| r.spectrum_um.first().copied());
    let amax = lines.iter().fold(1e-3_f64, |m, l| m.max(l.1));
    let floor = amax * 1e-5;
    let omax = lines.last().map_or(1.0, |l| l.0).max(1.0);
    let mut chart = ChartBuilder::on(root)
        .caption(omega_caption("Spectrum of x", r, status), caption_font())
        .margin(8)
        .x_label_area_size(44)
        .y_label_area_size(64)
        .build_cartesian_2d(0.0..omax * 1.02, (floor..amax * 20.0).log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        .light_line_style(GRID.mix(0.5))
        .bold_line_style(GRID)
        .x_desc("frequency (mesh orders: multiples of the mesh frequency)")
        .y_desc("amplitude of x (µm, log)")
        .label_style(small())
        .axis_desc_style(small())
        .draw()
        .map_err(err)?;
    let style = ShapeStyle::from(&MAX_COLOR).stroke_width(2);
    chart
        .draw_series(
            lines
                .iter()
                .map(|&(o, a)| PathElement::new(vec![(o, floor), (o, a.max(floor))], style)),
        )
        .map_err(err)?
        .label(match mean {
            Some(m) => format!("amplitude (mean x = {m:.2} µm not shown)"),
            None => "amplitude".into(),
        })
        .legend(move |(xx, yy)| PathElement::new(vec![(xx, yy), (xx + 16, yy)], style));
    legend(&mut chart, SeriesLabelPosition::UpperRight)?;
    root.present().map_err(err)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::views::fr::{FrBranch, FrMarker, FrSource};

    fn svg<F: FnOnce(&DrawingArea<SVGBackend, Shift>) -> Res<()>>(f: F) -> String {
        let mut s = String::new();
        {
            let root = SVGBackend::with_string(&mut s, (WIDTH, HEIGHT)).into_drawing_area();
            f(&root).unwrap();
        }
        s
    }

    fn result() -> OmegaResult {
        let n = 64 * 20;
        let x: Vec<f64> = (0..n)
            .map(|k| 110.0 + 30.0 * (k as f64 / 64.0 * std::f64::consts::TAU).sin())
            .collect();
        let v: Vec<f64> = (0..n)
            .map(|k| 0.5 * (k as f64 / 64.0 * std::f64::consts::TAU).cos())
            .collect();
        OmegaResult {
            omega: 0.84,
            mesh: 0,
            mesh_name: "s1a1".into(),
            backlash_um: 100.0,
            regime: Regime::SingleSided,
            period: Some(1),
            dynamic_factor: Some(1.4),
            mesh_freq_hz: 4500.0,
            transient_periods_run: 100,
            settled: true,
            samples_per_period: 64,
            record_periods: 20,
            x_um: x,
            xdot_m_s: v,
            poincare_x_um: vec![110.0; 20],
            poincare_xdot_m_s: vec![0.5; 20],
            spectrum_order: vec![0.0, 1.0, 2.0],
            spectrum_um: vec![110.0, 30.0, 0.1],
            all_meshes: vec![],
            anim: Default::default(),
            steps: 1,
            cli_json: "{}".into(),
            preview: false,
            end_state: vec![],
        }
    }

    #[test]
    fn a_failed_point_is_counted_and_its_reason_named() {
        let failed = vec![
            (
                1.1,
                "the response grows without bound: mesh rb1 deflected 5e-3 m".to_string(),
            ),
            (1.2, "step size fell to 1e-17 s at t = 0.1 s".to_string()),
        ];
        assert_eq!(
            failed_label(&failed),
            "2 point(s) failed, not plotted, first at Ω = 1.100: the response grows without bound"
        );
        assert_eq!(failed_label(&[]), "0 point(s) failed, not plotted");
    }

    #[test]
    fn frame_maps_pixels_to_omega_and_back() {
        let f = PlotFrame {
            top_left: DVec2::new(60.0, 30.0),
            bottom_right: DVec2::new(760.0, 360.0),
            x_range: (0.1, 2.0),
            y_range: (-100.0, 100.0),
        };
        let p = f.to_px(1.05, 0.0);
        assert!((f.x_at(p.x).unwrap() - 1.05).abs() < 1e-12);
        assert_eq!(f.x_at(0.0), None);
        assert_eq!(f.x_at(f64::NAN), None);
        assert_eq!(f.x_at(55.0), Some(0.1));
    }

    #[test]
    fn ranges_never_magnify_noise() {
        let (lo, hi) = padded_range([5.0, 5.0 + 1e-9].into_iter(), &[], 20.0);
        assert!(hi - lo >= 20.0);
        assert_eq!(padded_range(std::iter::empty(), &[], 1.0), (-1.0, 1.0));
    }

    #[test]
    fn every_plot_draws_labels_units_and_legends() {
        let point = |k: u32| FrCurvePoint {
            omega: 0.1 + 0.2 * f64::from(k),
            max_um: 120.0 + f64::from(k),
            min_um: 90.0 - f64::from(k),
            stable: Some(k <= 6),
            regime: Some(Regime::NoImpact),
            period: Some(1),
            bifurcation: (k == 7).then_some(FrMarkerKind::Fold),
        };
        let source = FrSource::Hbm { harmonics: 5 };
        let fr = FrView {
            method: source.label(),
            source,
            mesh_label: "s1a1".into(),
            backlash_um: vec![150.0],
            pinned_backlash_um: vec![100.0],
            branches: vec![
                FrBranch {
                    label: "A: backlash_um=100".into(),
                    points: (0..10).map(point).collect(),
                    faded: false,
                    pinned: true,
                },
                FrBranch {
                    label: "B: backlash_um=150; HBM, H = 5".into(),
                    points: (0..10).map(point).collect(),
                    faded: false,
                    pinned: false,
                },
            ],
            markers: vec![FrMarker {
                omega: 1.5,
                value_um: 127.0,
                kind: FrMarkerKind::Fold,
            }],
            overlay: vec![point(2)],
            overlay_source: Some(FrSource::TimeIntegration {
                transient_periods: 300,
                record_periods: 30,
            }),
            discrepancy: crate::views::fr::Discrepancy {
                max_um: Some(1.5),
                compared: 1,
                off_branch: 2,
            },
            natural: vec![NaturalFreq {
                omega: 0.5,
                frequency_hz: 3000.0,
                kind: "rotational".into(),
                multiplicity: 1,
            }],
            omega_from: 0.1,
            omega_to: 2.0,
            selected_omega: 0.84,
            branch_error: Some((1.9, "no convergence at Omega = 1.9".into())),
            failed: vec![],
            done: 10,
            progress: 0.95,
            finished: true,
        };
        let mut frame = None;
        let s = svg(|root| {
            frame = Some(draw_fr(root, &fr, "")?);
            Ok(())
        });
        assert!(
            s.contains("µm") && s.contains("Ω") && s.contains("±b"),
            "{s}"
        );
        for text in [
            "harmonic balance, H = 5, exact",
            "unstable (Floquet): dashed",
            "fold (jump)",
            "time integration (1 pts): max |Δx| 1.50 µm at 1 on the stable branch; 2 where none is stable",
            "Solver failure after Ω = 1.9000",
            "(partial)",
            "max x (A: backlash_um=100)",
            "max x (B: backlash_um=150; HBM, H = 5)",
            "s ±b (b = 100 µm)",
        ] {
            assert!(s.contains(text), "{text} missing");
        }
        let f = frame.unwrap();
        assert!(f.bottom_right.x > f.top_left.x);
        let r = result();
        for s in [
            svg(|root| draw_phase(root, &r, "")),
            svg(|root| draw_poincare(root, &r, "")),
            svg(|root| draw_time(root, &r, "").map(|_| ())),
            svg(|root| draw_spectrum(root, &r, "")),
        ] {
            assert!(s.contains("µm") && s.contains("s1a1"), "{s}");
        }
        let s = svg(|root| draw_message(root, "Bifurcation diagram", "waiting for the workers"));
        assert!(s.contains("waiting"));
    }

    #[test]
    fn wrap_breaks_at_spaces() {
        assert_eq!(wrap("aa bb cc", 5), vec!["aa bb", "cc"]);
    }
}
