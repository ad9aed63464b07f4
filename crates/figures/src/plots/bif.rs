//! `ViewId::Bif`'s plot: the bifurcation diagram (dots returned by colour for a
//! batched fill, the instability bands, the key).

use super::*;
use crate::views::bif::{BifPoint, BifView};

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

/// The colour of a failed sweep point's cross.
const FAILED_CROSS: RGBColor = RGBColor(90, 90, 90);

/// Where a sweep failed: a grey cross of `size` pixels on the Ω axis (at
/// `y0`, the axis's bottom) per failed point; the series, to label.
pub(super) fn failed_crosses<'a, 'c, DB: DrawingBackend + 'a>(
    chart: &'c mut Chart<'a, DB>,
    failed: &[(f64, String)],
    y0: f64,
    size: i32,
) -> Res<&'c mut plotters::chart::SeriesAnno<'a, DB>> {
    chart
        .draw_series(
            failed
                .iter()
                .map(|&(omega, _)| Cross::new((omega, y0), size, FAILED_CROSS.stroke_width(2))),
        )
        .map_err(err)
}

/// Adds a bifurcation diagram's dots to `groups`, in pixels of `frame`:
/// one group per regime colour and sweep direction (filled: upward), for
/// one batched fill each.
pub(super) fn group_dots(groups: &mut Vec<PointGroup>, points: &[BifPoint], frame: &PlotFrame) {
    for p in points {
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
}

/// `ViewId::Bif`: the bifurcation diagram. Returns the frame and the dots (in
/// pixels, grouped by colour and sweep direction) for the caller to draw.
pub fn draw_bif<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    v: &BifView,
    natural: &[NaturalFreq],
    status: &str,
) -> Res<(PlotFrame, Vec<PointGroup>)> {
    root.fill(&WHITE).map_err(err)?;
    let x = (v.omega_from, v.omega_to);
    let extra = contact_levels(&v.backlash_um, &v.pinned_backlash_um, v.whole_clearance);
    // The key is under the chart, so the axes fit the data alone.
    let in_range = |o: f64| o >= x.0 && o <= x.1;
    let branch_x = v
        .branches
        .iter()
        .flat_map(|l| l.points.iter())
        .filter(|p| in_range(p.0))
        .map(|p| p.1);
    let y = padded_range(
        v.points
            .iter()
            .chain(v.pinned.iter())
            .map(|p| p.x_um)
            .chain(branch_x),
        &extra,
        20.0,
    );
    let items = bif_key(v, natural, y);
    let plan = plan_key(root, &items, Vec::new());
    let upper = chart_area(root, &plan);
    let caption = format!("Bifurcation diagram, mesh {}{status}", v.mesh_label);
    let axes = Axes {
        y_area_min: super::STACKED_Y_AREA,
        ..Axes::over_omega(&v.speed, "Poincaré samples of x = δ − e (µm)")
    };
    let mut chart = linear_chart(&upper, &caption, (x, y), &axes)?;
    contact_lines(&mut chart, &v.backlash_um, x, true)?;
    pinned_contact_lines(&mut chart, &v.pinned_backlash_um, &v.backlash_um, x)?;
    if !v.unstable_bands.is_empty() {
        // Where motion large against the backlash grows without bound (the
        // engaged system's Floquet spectral radius above 1), under the dots.
        let shade = UNSTABLE_BAND.mix(BAND_ALPHA);
        chart
            .draw_series(v.unstable_bands.iter().map(|&(a, b)| {
                Rectangle::new([(a.max(x.0), y.0), (b.min(x.1), y.1)], shade.filled())
            }))
            .map_err(err)?;
    }
    omega_decorations(&mut chart, natural, v.selected_omega, y)?;
    draw_branches(&mut chart, v)?;
    let frame = frame_of(&chart, x, y);
    for m in v.branch_markers.iter().filter(|m| in_range(m.omega)) {
        let q = frame.to_px(m.omega, m.x_um);
        draw_marker_px(root, m.kind, (q.x.round() as i32, q.y.round() as i32))?;
    }
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
    group_dots(&mut groups, &v.points, &frame);
    // One dot per pixel and group: a sweep of 1000 recorded periods has
    // up to 1000 Poincaré samples per point, most on a few pixels.
    for g in &mut groups {
        g.px = decimate::one_per_pixel(g.px.iter().copied(), |(x, y)| {
            (x.round() as i32, y.round() as i32)
        });
    }
    if !v.failed.is_empty() {
        // Where the sweep failed: a grey cross on the Omega axis each.
        failed_crosses(&mut chart, &v.failed, y.0, 5)?;
    }
    draw_key(root, &items, &plan)?;
    root.present().map_err(err)?;
    Ok((frame, groups))
}

/// The colour of the shooting branches.
const BRANCH: RGBColor = RGBColor(20, 20, 20);

/// The shooting branches: stable stretches solid (2 px), unstable ones
/// thin and dashed, as continuation tools draw their diagrams.
fn draw_branches<DB: DrawingBackend>(chart: &mut Chart<'_, DB>, v: &BifView) -> Res<()> {
    for line in &v.branches {
        let pts = line.points.iter().copied();
        if line.stable {
            let style = ShapeStyle::from(&BRANCH).stroke_width(2);
            chart
                .draw_series(LineSeries::new(pts, style))
                .map_err(err)?;
        } else {
            let style = ShapeStyle::from(&BRANCH).stroke_width(1);
            chart
                .draw_series(DashedLineSeries::new(pts, 4, 3, style))
                .map_err(err)?;
        }
    }
    Ok(())
}

/// A bifurcation chart's SVG text with its dots ([`svg_with`]).
pub fn svg_with_dots(chart: &str, size: (u32, u32), groups: &[PointGroup]) -> Res<String> {
    svg_with(chart, size, |root| draw_groups(root, groups))
}

/// A chart's SVG text with more drawn over it: plotters closes an SVG when
/// the chart is presented (anything drawn after lands behind its end and
/// no viewer shows the file), so `draw` draws into a second SVG of the
/// same `size` whose body goes inside the first, before its end.
pub fn svg_with(
    chart: &str,
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<plotters::prelude::SVGBackend<'_>, Shift>) -> Res<()>,
) -> Res<String> {
    let mut over = String::new();
    {
        let root = plotters::prelude::SVGBackend::with_string(&mut over, size).into_drawing_area();
        draw(&root)?;
    }
    let head = chart
        .trim_end()
        .strip_suffix("</svg>")
        .ok_or_else(|| DrawError("the chart is not a complete SVG".into()))?;
    let body = over
        .split_once('>')
        .map(|(_, rest)| rest.trim_end())
        .and_then(|rest| rest.strip_suffix("</svg>"))
        .ok_or_else(|| DrawError("the overlay is not a complete SVG".into()))?;
    Ok(format!("{head}{body}</svg>\n"))
}

/// The shade's opacity of the unstable bands.
const BAND_ALPHA: f64 = 0.14;

/// The bifurcation diagram's key: A and B when comparing, the regimes
/// present, the sweep directions, the contact lines, the unstable bands,
/// natural frequencies and cursor, and the failed points with the first
/// one's reason.
fn bif_key(v: &BifView, natural: &[NaturalFreq], y: (f64, f64)) -> KeyItems {
    let mut items: KeyItems = Vec::new();
    if let Some((a, b)) = &v.ab_labels {
        items.push((KeyIcon::Dot(A_DOTS, 4), format!("A (pinned): {a}")));
        items.push((
            KeyIcon::Regime(Regime::SingleSided),
            format!("B (current, regime colours): {b}"),
        ));
    }
    items.extend(regime_items(v.points.iter().map(|p| p.regime), ""));
    let dark = RGBColor(60, 60, 60);
    if v.points.iter().any(|p| p.up) {
        items.push((KeyIcon::Dot(dark, 2), "upward sweep".into()));
    }
    if v.points.iter().any(|p| !p.up) {
        items.push((KeyIcon::Square(dark), "downward sweep".into()));
    }
    items.extend(contact_items(&v.backlash_um, &v.pinned_backlash_um, y));
    if !v.unstable_bands.is_empty() {
        items.push((
            KeyIcon::Shade(UNSTABLE_BAND, BAND_ALPHA),
            "parametrically unstable with all teeth engaged".into(),
        ));
    }
    items.extend(omega_items(natural, v.selected_omega, &v.speed));
    if v.branches.iter().any(|l| l.stable) {
        items.push((
            KeyIcon::Line(BRANCH, false),
            "periodic motion found by shooting, stable: solid".into(),
        ));
    }
    if v.branches.iter().any(|l| !l.stable) {
        items.push((
            KeyIcon::Line(BRANCH, true),
            "unstable (never seen in a sweep): thin dashed".into(),
        ));
    }
    // Each bifurcation kind drawn, with its one plain line.
    for k in crate::views::fr::FrMarkerKind::ALL {
        if v.branch_markers.iter().any(|m| m.kind == k) {
            items.push((KeyIcon::Marker(k), k.explain().to_string()));
        }
    }
    if !v.failed.is_empty() {
        items.push((KeyIcon::Cross(FAILED_CROSS), failed_label(&v.failed)));
    }
    items
}

/// Draws the dots of [`draw_bif`] with plotters (the page fills them on the
/// canvas directly, in a fast pass; the command line's SVG figures use this).
pub fn draw_groups<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    groups: &[PointGroup],
) -> Res<()> {
    for g in groups {
        for &(x, y) in &g.px {
            let (x, y) = (x.round() as i32, y.round() as i32);
            let shape = if g.filled {
                Rectangle::new([(x - 1, y - 1), (x + 1, y + 1)], g.color.filled())
            } else {
                Rectangle::new([(x - 2, y - 2), (x + 2, y + 2)], g.color.stroke_width(1))
            };
            root.draw(&shape).map_err(err)?;
        }
    }
    root.present().map_err(err)
}
