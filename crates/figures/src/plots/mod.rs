//! The six plots, drawn with plotters on any backend: a canvas in the
//! browser (`plotters-canvas`), an SVG string in the native tests.
//!
//! Every plot labels its axes with units, draws the ±b contact lines where
//! contact matters, the natural frequencies and the selected-Omega cursor on
//! the Omega axes, and a key under the chart (never over the data). Axis ranges never shrink below a sensible
//! span, so numerical noise is never magnified into structure.
//!
//! Dense point clouds (the bifurcation diagram) are returned as pixel
//! positions grouped by colour, for the caller to draw in a batch: plotters
//! would set a fill style per pixel, which is slow on a canvas.

//!
//! Shared here: colours, the plot frame (pixels to data), ranges, the one
//! chart layout ([`linear_chart`], [`chart_layout`], [`draw_axes`]), the
//! key (in `key`); each view kind's plot in its own module.

mod axis;
mod bif;
pub mod boundaries;
mod boxes;
pub mod campbell;
mod clip;
pub mod css;
pub mod decimate;
pub mod dynamic;
mod fr;
mod key;
pub mod maps;
pub mod multiples;
mod omega;
pub mod orders;
pub mod te_fit;

pub use bif::{draw_bif, draw_groups, failed_label, svg_with, svg_with_dots};
pub use boxes::{text_box, Boxed, TextBox};
pub use fr::{draw_fr, fr_first_mode_peaks, fr_full_key, fr_height, FR_MIN_CHART, KEY_MAX};
pub(crate) use key::*;
pub use omega::{
    draw_phase, draw_phase_with, draw_poincare, draw_poincare_with, draw_spectrum, draw_time,
    draw_time_with, poincare_key,
};

use crate::protocol::Regime;
use crate::speed::SpeedAxis;
use crate::views::fr::{FrCurvePoint, FrMarkerKind};
use crate::views::NaturalFreq;
pub(crate) use axis::{Ticks, XCoord};
use glam::DVec2;
use plotters::coord::ranged1d::{Ranged, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Plot size in pixels (the canvases' width and height attributes).
pub const WIDTH: u32 = 760;
/// Plot height in pixels.
pub const HEIGHT: u32 = 400;

/// A plot that could not be drawn, with the backend's reason.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("drawing failed: {0}")]
pub struct DrawError(pub String);

pub(crate) type Res<T> = Result<T, DrawError>;
pub(crate) type Chart<'a, DB> =
    ChartContext<'a, DB, Cartesian2d<axis::XCoord, plotters::coord::types::RangedCoordf64>>;

/// Any drawing backend's error as a [`DrawError`].
pub fn err<E: std::fmt::Display>(e: E) -> DrawError {
    DrawError(e.to_string())
}

/// Colour of an impact regime.
pub fn regime_color(r: Regime) -> RGBColor {
    match r {
        Regime::NoImpact => RGBColor(31, 119, 180),
        Regime::SingleSided => RGBColor(230, 120, 0),
        Regime::DoubleSided => RGBColor(200, 30, 40),
        Regime::NoContact => RGBColor(40, 150, 60),
        Regime::NoGap => RGBColor(110, 110, 120),
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

/// The colours of a parameter family's members, in order (Okabe–Ito:
/// distinct for colour-blind readers too).
pub const FAMILY_COLORS: [RGBColor; 6] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
];

/// The colour of family member `m`.
pub fn family_color(m: usize) -> RGBColor {
    FAMILY_COLORS[m % FAMILY_COLORS.len()]
}

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

/// The levels a plot of x must show whatever the data: with the whole
/// clearance, ±b of the current state's and A's meshes, and zero; else
/// none (the axes fit the data and the ±b lines show where they fall in it).
pub(crate) fn contact_levels(backlash_um: &[f64], pinned_um: &[f64], whole: bool) -> Vec<f64> {
    if !whole {
        return Vec::new();
    }
    let mut extra: Vec<f64> = backlash_um
        .iter()
        .chain(pinned_um.iter())
        .flat_map(|b| [*b, -*b])
        .collect();
    extra.push(0.0);
    extra
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

/// The canvas width under which a plot is drawn for a phone (smaller
/// caption, shorter lines).
pub const NARROW: u32 = 600;

/// How many characters of 13-pixel text fit on a line across an area
/// `width` pixels wide, less the key's left margin.
pub(crate) fn line_chars(width: u32) -> usize {
    (width.saturating_sub(84) * 10 / 78).max(30) as usize
}

pub(crate) fn small() -> TextStyle<'static> {
    ("sans-serif", 13).into_font().color(&RGBColor(50, 50, 50))
}

/// A chart's axes: their descriptions, the grid, the number of y labels.
pub(crate) struct Axes {
    /// The x axis's description.
    pub(crate) x: String,
    /// The y axis's description.
    pub(crate) y: String,
    /// Grid lines (off where cells fill the plotting area).
    pub(crate) grid: bool,
    /// The number of y labels, if not plotters' default.
    pub(crate) y_labels: Option<usize>,
    /// How the y labels are written, if not plotters' default.
    pub(crate) y_format: Option<fn(&f64) -> String>,
    /// The y label area's least width (pixels); wider if its labels need.
    pub(crate) y_area_min: u32,
    /// How the x ticks are chosen and written (a speed axis in rpm).
    pub(crate) x_ticks: Ticks,
}

/// The y label area's least width of the bifurcation diagram and the
/// Lyapunov exponent drawn under it: their Ω axes line up, pixel for
/// pixel, while their labels fit in it (6 characters and the description).
pub(crate) const STACKED_Y_AREA: u32 = 84;

impl Axes {
    /// Axes with grid lines and default labels.
    pub(crate) fn new(x: impl Into<String>, y: impl Into<String>) -> Self {
        Axes {
            x: x.into(),
            y: y.into(),
            grid: true,
            y_labels: None,
            y_format: None,
            y_area_min: 64,
            x_ticks: Ticks::Data,
        }
    }

    /// Axes over Ω, shown as `speed` says (Ω or the input speed in rpm).
    pub(crate) fn over_omega(speed: &SpeedAxis, y: impl Into<String>) -> Self {
        Axes {
            x_ticks: Ticks::over_omega(speed),
            ..Axes::new(speed.label(), y)
        }
    }
}

/// Where a caption sits across its area.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Align {
    /// Centred (a chart's caption).
    Centre,
    /// From the left edge (a canvas of panels, a message).
    Left,
}

/// The smallest caption font: a caption too long for its area at its own
/// size is drawn at this one before it is wrapped.
const CAPTION_MIN: u32 = 13;

/// Breaks `text` at spaces into lines that each measure at most `avail`
/// pixels in `font` (a single word longer than that stays whole).
fn measured_lines<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    font: &TextStyle<'_>,
    avail: u32,
) -> Vec<String> {
    let width = |t: &str| {
        area.estimate_text_size(t, font)
            .map_or(u32::MAX, |(w, _)| w)
    };
    let mut lines: Vec<String> = Vec::new();
    let mut cur = String::new();
    for word in text.split_whitespace() {
        let joined = if cur.is_empty() {
            word.to_string()
        } else {
            format!("{cur} {word}")
        };
        if cur.is_empty() || width(&joined) <= avail {
            cur = joined;
        } else {
            lines.push(std::mem::replace(&mut cur, word.to_string()));
        }
    }
    if !cur.is_empty() {
        lines.push(cur);
    }
    lines
}

/// Draws `text` as the caption of `area`, measured: on one line in the
/// caption font for the area's width if it fits, else smaller, else
/// wrapped at spaces (never cut mid-word). Returns the pixel row under it.
pub(crate) fn draw_caption<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    align: Align,
    font_px: u32,
) -> Res<i32> {
    caption(area, text, align, font_px, true)
}

/// The height [`draw_caption`] takes on `area`, without drawing it.
pub(crate) fn caption_height<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    font_px: u32,
) -> Res<i32> {
    caption(area, text, Align::Left, font_px, false)
}

/// [`draw_caption`], drawn if `draw`; its height either way.
fn caption<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    align: Align,
    font_px: u32,
    draw: bool,
) -> Res<i32> {
    let (w, _) = area.dim_in_pixel();
    let (left, top) = (10i32, 6i32);
    let avail = w.saturating_sub(2 * left as u32).max(40);
    let font_of = |px: u32| ("sans-serif", px).into_font().color(&BLACK);
    let mut lines = Vec::new();
    let mut px = font_px;
    for size in [font_px, (font_px - 2).max(CAPTION_MIN), CAPTION_MIN] {
        px = size;
        lines = measured_lines(area, text, &font_of(size), avail);
        if lines.len() == 1 {
            break;
        }
    }
    let font = font_of(px);
    let line_h = px as i32 + 5;
    for (k, line) in lines.iter().enumerate().filter(|_| draw) {
        let y = top + line_h * k as i32;
        let t = match align {
            Align::Centre => Text::new(
                line.clone(),
                (w as i32 / 2, y),
                font.pos(Pos::new(HPos::Center, VPos::Top)),
            ),
            Align::Left => Text::new(line.clone(), (left, y), font.clone()),
        };
        area.draw(&t).map_err(err)?;
    }
    Ok(top + line_h * lines.len() as i32)
}

/// The one chart layout every plot uses on `area`: the caption (measured,
/// see [`draw_caption`]), margins and label areas. The right margin holds
/// half of the last x tick label; the top one half of the top y label.
pub(crate) fn chart_layout<'a, 'b, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
) -> Res<ChartBuilder<'a, 'b, DB>> {
    let font_px = if area.dim_in_pixel().0 < NARROW {
        14
    } else {
        17
    };
    let under = draw_caption(area, caption, Align::Centre, font_px)?;
    let mut b = ChartBuilder::on(area);
    b.margin(8)
        .margin_top(under + 10)
        .margin_right(18)
        .x_label_area_size(44)
        .y_label_area_size(64);
    Ok(b)
}

/// Draws a chart's grid, tick labels and axis descriptions.
pub(crate) fn draw_axes<DB: DrawingBackend, X, Y>(
    chart: &mut ChartContext<'_, DB, Cartesian2d<X, Y>>,
    axes: &Axes,
) -> Res<()>
where
    X: Ranged + ValueFormatter<X::ValueType>,
    Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let (plot_w, plot_h) = chart.plotting_area().dim_in_pixel();
    let y_desc = fit_desc(chart.plotting_area(), &axes.y, plot_h);
    let mut mesh = chart.configure_mesh();
    // Tick labels thinned to one per 64 pixels or so: on a phone's plot
    // plotters' default ten would run together ("100.0110.0120.0").
    mesh.x_labels((plot_w as usize / 64).clamp(3, 10));
    if axes.grid {
        mesh.light_line_style(GRID.mix(0.5)).bold_line_style(GRID);
    } else {
        mesh.disable_mesh();
    }
    if let Some(n) = axes.y_labels {
        mesh.y_labels(n);
    }
    if let Some(f) = &axes.y_format {
        mesh.y_label_formatter(f);
    }
    mesh.x_desc(axes.x.as_str())
        .y_desc(y_desc.as_str())
        .label_style(small())
        .axis_desc_style(small())
        .draw()
        .map_err(err)
}

/// An axis description that fits `length` pixels in the small font: whole
/// if it does, else its leading words dropped ("Poincaré samples of x (µm)"
/// becomes "x (µm)"), never a cut word and never a lone "of".
pub(crate) fn fit_desc<DB: DrawingBackend, CT: plotters::coord::CoordTranslate>(
    area: &DrawingArea<DB, CT>,
    desc: &str,
    length: u32,
) -> String {
    let fits = |t: &str| {
        area.estimate_text_size(t, &small())
            .is_ok_and(|(w, _)| w <= length)
    };
    let words: Vec<&str> = desc.split_whitespace().collect();
    (0..words.len())
        .map(|k| words[k..].join(" "))
        .filter(|t| {
            !["of ", "per ", "in ", "at ", "and "]
                .iter()
                .any(|w| t.starts_with(w))
        })
        .find(|t| fits(t))
        .unwrap_or_else(|| words.last().map_or(String::new(), |w| (*w).to_string()))
}

/// A linear chart over `x` and `y` with the shared layout and `axes`,
/// its y label area as wide as its tick labels need ([`y_label_area`]).
pub(crate) fn linear_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    caption: &str,
    (x, y): ((f64, f64), (f64, f64)),
    axes: &Axes,
) -> Res<Chart<'a, DB>> {
    let plotters_own = |v: &f64| plotters::coord::types::RangedCoordf64::format(v);
    let format: &dyn Fn(&f64) -> String = match &axes.y_format {
        Some(f) => f,
        None => &plotters_own,
    };
    let labels = y_tick_labels(y, axes.y_labels.unwrap_or(Y_LABELS), format);
    let mut b = chart_layout(area, caption)?;
    b.y_label_area_size(y_label_area(area, &labels, true).max(axes.y_area_min));
    let mut chart = b
        .build_cartesian_2d(XCoord::new(x, axes.x_ticks), y.0..y.1)
        .map_err(err)?;
    draw_axes(&mut chart, axes)?;
    Ok(chart)
}

/// Plotters' number of y tick labels unless a chart asks for another.
const Y_LABELS: usize = 11;

/// The y tick labels plotters draws over `y` with `n` labels at most,
/// written by `format`.
pub(crate) fn y_tick_labels(
    y: (f64, f64),
    n: usize,
    format: &dyn Fn(&f64) -> String,
) -> Vec<String> {
    let coord: plotters::coord::types::RangedCoordf64 = (y.0..y.1).into();
    coord.key_points(n).iter().map(format).collect()
}

/// The width a y label area needs for `labels` and, if `described`, the
/// rotated axis description at its left edge apart from them: plotters
/// draws the labels right-aligned 10 pixels from the axis (twice its
/// 5-pixel tick) and the description from the area's left edge. A
/// "-100000.0" needs about 100 pixels (in a fixed 64 it was cut to
/// "100000.0", and a "6500.0" ran into the description).
pub(crate) fn y_label_area<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    labels: &[String],
    described: bool,
) -> u32 {
    let size = |t: &str| area.estimate_text_size(t, &small()).unwrap_or((0, 0));
    let widest = labels.iter().map(|l| size(l).0).max().unwrap_or(0);
    let desc = if described {
        size("x (µm)").1.max(13) + 6
    } else {
        0
    };
    widest + 10 + 4 + desc
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
    draw_caption(root, title, Align::Left, 17)?;
    let chars = (w.saturating_sub(48) * 10 / 85).max(30) as usize;
    for (k, line) in wrap(message, chars).iter().enumerate() {
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

/// Draws the Omega-axis decorations: natural frequencies and the cursor
/// (their key items: [`omega_items`]).
pub(crate) fn omega_decorations<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    natural: &[NaturalFreq],
    selected: f64,
    y: (f64, f64),
) -> Res<()> {
    let nat_style = ShapeStyle::from(&NATURAL.mix(0.55)).stroke_width(1);
    chart
        .draw_series(
            natural
                .iter()
                .map(|n| PathElement::new(vec![(n.omega, y.0), (n.omega, y.1)], nat_style)),
        )
        .map_err(err)?;
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(selected, y.0), (selected, y.1)],
            ShapeStyle::from(&CURSOR).stroke_width(2),
        )))
        .map_err(err)?;
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
    let style = contact_style(A_MIN);
    let mut any = false;
    for &b in pinned_um
        .iter()
        .filter(|b| !current_um.iter().any(|c| (*c - **b).abs() < 1e-9))
    {
        let shown = chart.y_range();
        for v in [b, -b].into_iter().filter(|v| shown.contains(v)) {
            chart
                .draw_series(DashedLineSeries::new(vec![(x.0, v), (x.1, v)], 2, 3, style))
                .map_err(err)?;
        }
        any = true;
    }
    Ok(any)
}

/// Draws the ±b contact lines across the x range, those that fall in the
/// axes' range (they fit the data); their key item: [`contact_item`].
fn contact_lines<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    backlash_um: &[f64],
    x: (f64, f64),
    horizontal: bool,
) -> Res<()> {
    let style = contact_style(CONTACT);
    let shown = if horizontal {
        chart.y_range()
    } else {
        chart.x_range()
    };
    for &b in backlash_um {
        for v in [b, -b].into_iter().filter(|v| shown.contains(v)) {
            let pts = if horizontal {
                vec![(x.0, v), (x.1, v)]
            } else {
                vec![(v, x.0), (v, x.1)]
            };
            chart
                .draw_series(DashedLineSeries::new(pts, 2, 3, style))
                .map_err(err)?;
        }
    }
    Ok(())
}

/// The style of a ±b contact line: dotted (2 px on, 3 off) and thin,
/// never to be read as a dashed (unstable) branch.
pub(crate) fn contact_style(color: RGBColor) -> ShapeStyle {
    ShapeStyle::from(&color).stroke_width(1)
}

/// The impact regime along Omega as a thin coloured strip at the bottom of
/// the plot: the branch's own lines keep the max / min colours and the
/// dashes of unstable stretches readable. Only stable (or unknown) stretches
/// are drawn, since only they can be observed.
fn regime_strip<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    points: &[FrCurvePoint],
    filled: &[(Regime, f64, f64)],
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
            .filter(|_| a.stable != Some(false) && b.stable != Some(false) && a.joins(b));
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
            runs.into_iter()
                .chain(filled.iter().copied())
                .map(|(r, from, to)| {
                    Rectangle::new([(from, lo), (to, hi)], regime_color(r).filled())
                }),
        )
        .map_err(err)?;
    Ok(())
}

#[cfg(test)]
mod multiples_tests;
#[cfg(test)]
mod tests;
