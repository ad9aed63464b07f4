//! The key of every plot over time, Omega or the phase plane: a row (or a
//! few) of symbols and words under the chart, outside the plotting area, so
//! that it never covers the data, the caption or the notes.
//!
//! A plot lists its key items first, [`plan_key`] reserves the rows at the
//! bottom of the canvas (the chart is drawn in the area above them), and
//! [`draw_key`] draws the items there once the chart is done.

use super::*;

/// A symbol of the key.
#[derive(Debug, Clone, Copy)]
pub(crate) enum KeyIcon {
    /// A filled dot in a regime's colour.
    Regime(Regime),
    /// A bifurcation marker of the frequency response.
    Marker(FrMarkerKind),
    /// The hollow dot of a time-integration steady state.
    Overlay,
    /// A line in a colour, solid or dashed.
    Line(RGBColor, bool),
    /// A dotted line in a colour (the ±b contact lines).
    Dotted(RGBColor),
    /// A filled dot of a colour and radius.
    Dot(RGBColor, i32),
    /// A small hollow square (the downward sweep's dots).
    Square(RGBColor),
    /// A hollow circle of a colour and radius.
    Ring(RGBColor, i32),
    /// A shaded band (colour, opacity).
    Shade(RGBColor, f64),
    /// A cross (failed points).
    Cross(RGBColor),
}

/// The key's items: a symbol and its words each.
pub(crate) type KeyItems = Vec<(KeyIcon, String)>;

pub(crate) const MARKER: RGBColor = RGBColor(0, 0, 0);
pub(crate) const OVERLAY: RGBColor = RGBColor(60, 60, 60);
pub(crate) const FAILURE: RGBColor = RGBColor(170, 0, 0);

/// Row height of the key (pixels).
pub(crate) const KEY_ROW: i32 = 17;
/// Where the key's rows start (pixels from the left): under the plotting
/// area's left edge.
const KEY_X: i32 = 76;

/// Where a key goes on the canvas: each item's position, the rows it
/// takes and the top of the band it fills; the chart goes above `top`.
#[derive(Debug, Clone)]
pub(crate) struct KeyPlan {
    at: Vec<KeyPlace>,
    rows: i32,
    /// The first pixel row of the key (the chart's area ends here).
    pub(crate) top: i32,
    /// Lines of words after the items.
    lines: Vec<KeyLine>,
}

/// A line of words under the key's symbols.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum KeyLine {
    /// A sentence about the data, in bold.
    Sentence(String),
    /// A warning (a failure, a partial result), in red.
    Warning(String),
}

/// Lays out `items` (and the `lines` after them) at the bottom of
/// `root`, wrapping at its right edge.
pub(crate) fn plan_key<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    items: &[(KeyIcon, String)],
    lines: Vec<KeyLine>,
) -> KeyPlan {
    let (at, rows) = key_layout(root, items, KEY_X);
    let h = root.dim_in_pixel().1 as i32;
    let n = rows + lines.len() as i32;
    let key_h = if n == 0 { 0 } else { 8 + KEY_ROW * n };
    KeyPlan {
        at,
        rows,
        top: h - key_h,
        lines,
    }
}

/// The area above the key, for the chart.
pub(crate) fn chart_area<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    plan: &KeyPlan,
) -> DrawingArea<DB, Shift> {
    root.split_vertically(plan.top).0
}

/// Draws the key of [`plan_key`].
pub(crate) fn draw_key<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    items: &[(KeyIcon, String)],
    plan: &KeyPlan,
) -> Res<()> {
    key_row(root, items, &plan.at, plan.top + 12)?;
    for (k, line) in plan.lines.iter().enumerate() {
        let y0 = plan.top + 5 + KEY_ROW * (plan.rows + k as i32);
        let (text, font) = match line {
            KeyLine::Sentence(t) => (
                t,
                ("sans-serif", 13)
                    .into_font()
                    .style(FontStyle::Bold)
                    .color(&BLACK),
            ),
            KeyLine::Warning(t) => (t, ("sans-serif", 13).into_font().color(&FAILURE)),
        };
        root.draw(&Text::new(text.clone(), (KEY_X, y0), font))
            .map_err(err)?;
    }
    Ok(())
}

/// The key items of the Omega axes' decorations: the natural frequencies
/// (if any) and the selected-Omega cursor.
pub(crate) fn omega_items(
    natural: &[NaturalFreq],
    selected: f64,
    speed: &crate::speed::SpeedAxis,
) -> KeyItems {
    let mut items = Vec::new();
    if !natural.is_empty() {
        items.push((
            KeyIcon::Line(NATURAL, false),
            "natural frequencies (linear, mean k)".into(),
        ));
    }
    items.push((
        KeyIcon::Line(CURSOR, false),
        format!("selected {}", speed.text(selected)),
    ));
    items
}

/// The key item of the ±b contact lines, if any falls in `shown`.
pub(crate) fn contact_item(backlash_um: &[f64], shown: (f64, f64)) -> Option<(KeyIcon, String)> {
    let r = shown.0.min(shown.1)..=shown.0.max(shown.1);
    let bs: Vec<String> = backlash_um
        .iter()
        .filter(|b| r.contains(*b) || r.contains(&-**b))
        .map(|b| format!("{b}"))
        .collect();
    // Without backlash the two lines are one, at x = 0: no gap to cross.
    let text = if backlash_um.iter().all(|b| !crate::story::has_backlash(*b)) {
        "x = 0: no backlash, the flanks always touch".to_string()
    } else {
        format!("±b contact lines (b = {} µm)", bs.join(", "))
    };
    (!bs.is_empty()).then_some((KeyIcon::Dotted(CONTACT), text))
}

/// The key items of the ±b contact lines shown in `y`: the current
/// state's, then the pinned state A's where they differ (A/B comparison).
pub(crate) fn contact_items(backlash_um: &[f64], pinned_um: &[f64], y: (f64, f64)) -> KeyItems {
    let mut items: KeyItems = contact_item(backlash_um, y).into_iter().collect();
    let a_only: Vec<f64> = pinned_um
        .iter()
        .copied()
        .filter(|b| !backlash_um.iter().any(|c| (*c - *b).abs() < 1e-9))
        .collect();
    if let Some((_, text)) = contact_item(&a_only, y) {
        items.push((
            KeyIcon::Dotted(A_MIN),
            text.replacen("±b contact lines", "A's ±b", 1),
        ));
    }
    items
}

/// The key items of the regimes present, in their fixed order; the first
/// prefixed by `prefix`.
pub(crate) fn regime_items(present: impl Iterator<Item = Regime>, prefix: &str) -> KeyItems {
    let mut seen = [false; Regime::ALL.len()];
    for r in present {
        if let Some(i) = Regime::ALL.iter().position(|&x| x == r) {
            seen[i] = true;
        }
    }
    let mut first = true;
    let mut items = Vec::new();
    for (i, r) in Regime::ALL.iter().enumerate() {
        if seen[i] {
            let text = if first {
                format!("{prefix}{}", r.label())
            } else {
                r.label().to_string()
            };
            first = false;
            items.push((KeyIcon::Regime(*r), text));
        }
    }
    items
}

/// Where each key item goes, left to right from `x0`, wrapping at the right
/// edge; rows relative to the first (0, 17, ...), and the item's words in
/// lines (more than one only for an item wider than a whole row). Also
/// returns the rows used.
fn key_layout<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    items: &[(KeyIcon, String)],
    x0: i32,
) -> (Vec<KeyPlace>, i32) {
    let font = small();
    let right = root.dim_in_pixel().0 as i32 - 8;
    let width = |t: &str| {
        root.estimate_text_size(t, &font)
            .map_or(8 * t.len() as u32, |(w, _)| w) as i32
    };
    layout_rows(items, x0, right, width)
}

/// The height (pixels) of the key of `items` and `lines` lines of words on
/// a canvas `canvas_w` pixels wide, before there is a canvas to measure text
/// on: every character taken as 7 pixels wide (the most a character of the
/// key's font takes), so the estimate is never short.
pub(crate) fn key_height_estimate(items: &[(KeyIcon, String)], lines: usize, canvas_w: u32) -> i32 {
    let right = canvas_w as i32 - 8;
    let (_, rows) = layout_rows(items, KEY_X, right, |t| 7 * t.chars().count() as i32);
    let n = rows + lines as i32;
    if n == 0 {
        0
    } else {
        8 + KEY_ROW * n
    }
}

/// [`key_layout`] with the text's widths from `width`, wrapping at `right`.
fn layout_rows(
    items: &[(KeyIcon, String)],
    x0: i32,
    right: i32,
    width: impl Fn(&str) -> i32,
) -> (Vec<KeyPlace>, i32) {
    let (mut x, mut y) = (x0, 0);
    let mut out = Vec::with_capacity(items.len());
    for (icon, text) in items {
        let w = width(text);
        let icon_w = icon_width(*icon);
        if x > x0 && x + icon_w + w > right {
            x = x0;
            y += KEY_ROW;
        }
        let room = right - x0 - icon_w;
        if w > room || 7 * text.chars().count() as i32 > room {
            // Too wide for a row: its words on rows of their own.
            // (At most 7 pixels a character, whatever the estimate says.)
            let chars = (text.chars().count() as i32 * room / w.max(1))
                .min(room / 7)
                .max(10) as usize;
            let lines = wrap(text, chars);
            let n = lines.len() as i32;
            out.push(KeyPlace { x, y, lines });
            x = x0;
            y += KEY_ROW * n;
            continue;
        }
        out.push(KeyPlace {
            x,
            y,
            lines: vec![text.clone()],
        });
        x += icon_w + w + 16;
    }
    let rows = if items.is_empty() {
        0
    } else if x == x0 {
        y / KEY_ROW
    } else {
        y / KEY_ROW + 1
    };
    (out, rows)
}

/// Where one key item goes: its top-left (relative to the key's first row)
/// and its words in lines.
#[derive(Debug, Clone)]
pub(crate) struct KeyPlace {
    x: i32,
    y: i32,
    lines: Vec<String>,
}

fn icon_width(icon: KeyIcon) -> i32 {
    match icon {
        KeyIcon::Line(..) | KeyIcon::Dotted(..) | KeyIcon::Shade(..) => 22,
        _ => 14,
    }
}

/// Draws the key's items at the positions of [`key_layout`], offset by `y0`.
fn key_row<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    items: &[(KeyIcon, String)],
    at: &[KeyPlace],
    y0: i32,
) -> Res<()> {
    let font = small();
    for ((icon, _), place) in items.iter().zip(at) {
        let (x, y) = (place.x, y0 + place.y);
        draw_icon(root, *icon, x, y)?;
        for (k, line) in place.lines.iter().enumerate() {
            root.draw(&Text::new(
                line.clone(),
                (x + icon_width(*icon), y - 7 + KEY_ROW * k as i32),
                font.clone(),
            ))
            .map_err(err)?;
        }
    }
    Ok(())
}

/// Draws a key symbol with its left end at `x` and its middle at `y`.
fn draw_icon<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    icon: KeyIcon,
    x: i32,
    y: i32,
) -> Res<()> {
    let c = (x + 5, y);
    match icon {
        KeyIcon::Line(color, dashed) => {
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
        }
        KeyIcon::Dotted(color) => {
            let style = ShapeStyle::from(&color).stroke_width(2);
            for k in 0..4 {
                root.draw(&PathElement::new(
                    vec![(x + 5 * k, y), (x + 5 * k + 2, y)],
                    style,
                ))
                .map_err(err)?;
            }
        }
        KeyIcon::Shade(color, alpha) => root
            .draw(&Rectangle::new(
                [(x, y - 5), (x + 16, y + 5)],
                color.mix(alpha).filled(),
            ))
            .map_err(err)?,
        KeyIcon::Regime(r) => root
            .draw(&Circle::new(c, 4, regime_color(r).filled()))
            .map_err(err)?,
        KeyIcon::Dot(color, radius) => root
            .draw(&Circle::new(c, radius, color.filled()))
            .map_err(err)?,
        KeyIcon::Ring(color, radius) => root
            .draw(&Circle::new(c, radius, color.stroke_width(2)))
            .map_err(err)?,
        KeyIcon::Square(color) => root
            .draw(&Rectangle::new(
                [(c.0 - 2, c.1 - 2), (c.0 + 2, c.1 + 2)],
                color.stroke_width(1),
            ))
            .map_err(err)?,
        KeyIcon::Cross(color) => root
            .draw(&Cross::new(c, 4, color.stroke_width(2)))
            .map_err(err)?,
        KeyIcon::Marker(k) => draw_marker_px(root, k, c)?,
        KeyIcon::Overlay => root
            .draw(&Circle::new(c, 4, OVERLAY.stroke_width(1)))
            .map_err(err)?,
    }
    Ok(())
}

/// A bifurcation marker at a pixel position.
pub(crate) fn draw_marker_px<DB: DrawingBackend>(
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
