//! `ViewId::Fr`'s plot: the frequency response (branches, stability, markers,
//! the regime strip, the overlay and the key row).

use super::*;
use crate::views::fr::{FrBranch, FrCurvePoint, FrMarkerKind, FrView};
use crate::views::unstable::{strip_from_overlay, unstable_ranges, unstable_sentence};

/// The least height (pixels) of the frequency response's chart above its
/// key, by [`key_height_estimate`]: what the ordinary 400-pixel canvas
/// leaves above the key of one branch with its markers, the time-
/// integration dots and the sentence on unstable ranges (a plot about 190
/// pixels high). A comparison's key (two branches, two sets of contact
/// lines) takes three or four rows more, which left its plot 155 pixels
/// high; the canvas grows instead.
pub const FR_MIN_CHART: u32 = 270;

/// The frequency response's canvas height for `size` (width, ordinary
/// height): taller where its key would leave the chart less than
/// [`FR_MIN_CHART`] pixels.
pub fn fr_height(v: &FrView, (w, h): (u32, u32)) -> u32 {
    let items = compact_key(fr_key(v, fr_y_range(v)));
    let lines = fr_lines(v, line_chars(w)).len();
    let key = key_height_estimate(&items, lines, w).max(0) as u32;
    h.max(FR_MIN_CHART + key)
}

/// A curve's points: Omega, max x and min x (µm).
type Points = Vec<(f64, f64, f64)>;

/// The key's words for a dashed branch: unstable, said plainly (the
/// Floquet test is named in the note).
pub(crate) const UNSTABLE_KEY: &str = "dashed: unstable (a small disturbance grows)";

/// The frequency response's y range: the data in the Ω range (the
/// time-integration overlay too, `with_overlay`) and the contact lines
/// asked for (the key is under the chart, so the axes fit the data alone),
/// the first mode's spike clipped and marked when it would flatten the
/// rest ([`super::clip`]). The single plot and each panel of several
/// meshes share it.
pub(super) fn fr_clipped(v: &FrView, with_overlay: bool) -> super::clip::Clipped {
    let lists = fr_lists(v, with_overlay);
    let extra = contact_levels(&v.backlash_um, &v.pinned_backlash_um, v.whole_clearance);
    super::clip::clipped_range(&curves(&lists), &natural_in_range(v), &extra)
}

/// Each current curve's first-mode peak, `(name, Omega, x µm)`, as the
/// plot locates it (see [`super::clip`]).
pub fn fr_first_mode_peaks(v: &FrView) -> Vec<(String, f64, f64)> {
    // The lists follow the branches one for one (no overlay asked for).
    let lists: Vec<_> = fr_lists(v, false)
        .into_iter()
        .zip(&v.branches)
        .filter(|(_, b)| !b.faded)
        .map(|(l, _)| l)
        .collect();
    super::clip::first_mode_peaks(&curves(&lists), &natural_in_range(v))
}

/// One curve for the clipping: its points in the Omega range, its max and
/// min colours, and its name where there are several current curves.
type CurveList = (Points, (RGBColor, RGBColor), Option<String>);

/// Every branch's curve (faded ones too), then the overlay's dots
/// (`with_overlay`).
fn fr_lists(v: &FrView, with_overlay: bool) -> Vec<CurveList> {
    let in_range = |o: f64| o >= v.omega_from && o <= v.omega_to;
    let pts = |ps: &[FrCurvePoint]| -> Points {
        ps.iter()
            .filter(|p| in_range(p.omega))
            .map(|p| (p.omega, p.max_um, p.min_um))
            .collect()
    };
    let several = v.branches.iter().filter(|b| !b.faded).count() > 1;
    let mut lists: Vec<CurveList> = v
        .branches
        .iter()
        .map(|b| {
            let label = (several && !b.faded).then(|| b.label.clone());
            (
                pts(&b.points),
                (branch_color(b, true), branch_color(b, false)),
                label,
            )
        })
        .collect();
    if with_overlay && !v.overlay.is_empty() {
        lists.push((
            pts(&v.overlay),
            (OVERLAY, OVERLAY),
            several.then(|| "dots".to_string()),
        ));
    }
    lists
}

/// The clipping's view of `lists`.
fn curves(lists: &[CurveList]) -> Vec<super::clip::Curve<'_>> {
    lists
        .iter()
        .map(|(points, colors, label)| super::clip::Curve {
            points,
            colors: *colors,
            label: label.clone(),
        })
        .collect()
}

/// The natural frequencies in the Omega range.
fn natural_in_range(v: &FrView) -> Vec<f64> {
    v.natural
        .iter()
        .map(|n| n.omega)
        .filter(|&w| w >= v.omega_from && w <= v.omega_to)
        .collect()
}

fn fr_y_range(v: &FrView) -> (f64, f64) {
    fr_clipped(v, true).range
}

/// `ViewId::Fr`: the frequency response (harmonic-balance branch, stable solid,
/// unstable dashed, bifurcation markers, optional time-integration dots).
pub fn draw_fr<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    v: &FrView,
    status: &str,
) -> Res<PlotFrame> {
    root.fill(&WHITE).map_err(err)?;
    let x = (v.omega_from, v.omega_to);
    let in_range = |o: f64| o >= x.0 && o <= x.1;
    let clipped = fr_clipped(v, true);
    let y = clipped.range;
    let items = compact_key(fr_key(v, y));
    let plan = plan_key(root, &items, fr_lines(v, line_chars(root.dim_in_pixel().0)));
    let upper = chart_area(root, &plan);
    let caption = if v.branches.iter().any(|b| b.member.is_some()) {
        format!(
            "Frequency response, mesh {}: max and min x per value{status}",
            v.mesh_label
        )
    } else {
        // The method is in the note under the plot, not the title.
        format!("Frequency response, mesh {}{status}", v.mesh_label)
    };
    let axes = Axes::over_omega(&v.speed, "x = δ − e (µm)");
    let mut chart = linear_chart(&upper, &caption, (x, y), &axes)?;
    contact_lines(&mut chart, &v.backlash_um, x, true)?;
    pinned_contact_lines(&mut chart, &v.pinned_backlash_um, &v.backlash_um, x)?;
    omega_decorations(&mut chart, &v.natural, v.selected_omega, y)?;
    for br in &v.branches {
        draw_branch(&mut chart, br)?;
        if !br.faded && !br.pinned && br.member.is_none() {
            // Where no stretch is stable, the strip shows the dots' regimes.
            let filled = strip_from_overlay(&unstable_ranges(&br.points), &v.overlay);
            regime_strip(&mut chart, &br.points, &filled, y)?;
        }
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
    for m in v
        .markers
        .iter()
        .filter(|m| in_range(m.omega) && (y.0..=y.1).contains(&m.value_um))
    {
        let c = chart.backend_coord(&(m.omega, m.value_um));
        draw_marker_px(root, m.kind, c)?;
    }
    super::clip::mark_clipped(&mut chart, &clipped)?;
    if let Some((at, _)) = &v.branch_error {
        chart
            .draw_series(DashedLineSeries::new(
                vec![(*at, y.0), (*at, y.1)],
                3,
                3,
                ShapeStyle::from(&FAILURE).stroke_width(2),
            ))
            .map_err(err)?;
    }
    let frame = frame_of(&chart, x, y);
    draw_key(root, &items, &plan)?;
    root.present().map_err(err)?;
    Ok(frame)
}

/// The most entries the key drawn under the frequency response has; the
/// full key, every entry explained, is the text under the plot
/// ([`fr_full_key`]).
pub const KEY_MAX: usize = 8;

/// The key drawn under the plot: `items` while they are at most
/// [`KEY_MAX`]; else the regimes' colours become one entry and the
/// bifurcation symbols another, and then the entries a reader needs least
/// to read the curves (natural frequencies, the selected Ω, the symbols,
/// the regime strip, the contact lines, in that order) give way to one
/// last entry that counts them and points at the full key.
pub(crate) fn compact_key(items: KeyItems) -> KeyItems {
    let collapse = |items: KeyItems, is: fn(&KeyIcon) -> bool, text: &str| -> KeyItems {
        if items.len() <= KEY_MAX || items.iter().filter(|i| is(&i.0)).count() < 2 {
            return items;
        }
        let mut out: KeyItems = Vec::new();
        for (icon, t) in items {
            if !is(&icon) {
                out.push((icon, t));
            } else if !out.iter().any(|i| is(&i.0)) {
                out.push((icon, text.to_string()));
            }
        }
        out
    };
    let items = collapse(
        items,
        |i| matches!(i, KeyIcon::Regime(_)),
        "regime strip: coloured by what the teeth do",
    );
    let items = collapse(
        items,
        |i| matches!(i, KeyIcon::Marker(_)),
        "black symbols: bifurcations",
    );
    if items.len() <= KEY_MAX {
        return items;
    }
    // Which entry gives way first (lowest first).
    let rank = |(icon, text): &(KeyIcon, String)| match icon {
        KeyIcon::Line(..) if text.starts_with("natural") => 0,
        KeyIcon::Line(..) if text.starts_with("selected") => 1,
        KeyIcon::Marker(_) => 2,
        KeyIcon::Regime(_) => 3,
        KeyIcon::Dotted(..) => 4,
        _ => 9,
    };
    let drop = items.len() - (KEY_MAX - 1);
    let mut order: Vec<usize> = (0..items.len()).collect();
    order.sort_by_key(|&i| rank(&items[i]));
    let dropped: Vec<usize> = order
        .into_iter()
        .take(drop)
        .filter(|&i| rank(&items[i]) < 9)
        .collect();
    let more = dropped.len();
    let mut out: KeyItems = items
        .into_iter()
        .enumerate()
        .filter(|(i, _)| !dropped.contains(i))
        .map(|(_, item)| item)
        .collect();
    if more > 0 {
        out.push((
            KeyIcon::Dot(WHITE, 0),
            format!("{more} more in the full key under the plot"),
        ));
    }
    out
}

/// The full key of the frequency response, one line per entry, each
/// regime and bifurcation kind with its plain explanation: the text in
/// "details" under the plot.
pub fn fr_full_key(v: &FrView) -> Vec<String> {
    fr_key(v, fr_y_range(v))
        .into_iter()
        .map(|(icon, text)| match icon {
            KeyIcon::Marker(k) => {
                let symbol = match k {
                    FrMarkerKind::Fold => "▲",
                    FrMarkerKind::PeriodDoubling => "✕",
                    FrMarkerKind::NeimarkSacker => "○",
                    FrMarkerKind::BranchPoint => "□",
                };
                format!("{symbol} {}", k.explain())
            }
            KeyIcon::Regime(r) => format!(
                "regime strip: {}",
                crate::story::contact_sentence(r, v.backlash_um.first().copied().unwrap_or(0.0))
            ),
            _ => text,
        })
        .collect()
}

/// The frequency response's key: the branches (a family's member and the
/// faded previous branch once each, else max and min), the contact lines,
/// natural frequencies and cursor, the unstable dash, the regimes present,
/// the bifurcation kinds present, the overlay and a failure's line.
pub(crate) fn fr_key(v: &FrView, y: (f64, f64)) -> KeyItems {
    let mut items: KeyItems = Vec::new();
    items.extend(branch_items(&v.branches));
    if v.branches.iter().any(|b| b.faded) {
        items.push((
            KeyIcon::Line(FADED, false),
            "previous settings (updating)".into(),
        ));
    }
    items.extend(contact_items(&v.backlash_um, &v.pinned_backlash_um, y));
    items.extend(omega_items(&v.natural, v.selected_omega, &v.speed));
    let any_unstable = v
        .branches
        .iter()
        .filter(|b| !b.faded)
        .any(|b| b.points.iter().any(|p| p.stable == Some(false)));
    if any_unstable {
        items.push((KeyIcon::Line(CONTACT, true), UNSTABLE_KEY.into()));
    }
    // The regime strip is drawn under the current state's branch only (not
    // a family's members): its key only then.
    let strip = v
        .branches
        .iter()
        .any(|b| !b.faded && !b.pinned && b.member.is_none());
    items.extend(regime_items(
        v.branches
            .iter()
            .filter(|b| !b.faded && b.member.is_none())
            .flat_map(|b| b.points.iter().filter_map(|p| p.regime))
            .chain(v.overlay.iter().filter_map(|p| p.regime))
            .filter(|_| strip),
        "regime strip: ",
    ));
    for k in FrMarkerKind::ALL {
        if v.markers.iter().any(|m| m.kind == k) {
            items.push((KeyIcon::Marker(k), k.label().to_string()));
        }
    }
    if v.overlay_source.is_some() {
        let d = &v.discrepancy;
        // Short enough for one row of the key: the points off the stable
        // branch are what the sentence under the key is about.
        let mut text = format!(
            "time integration: the actual response ({} points",
            v.overlay.len()
        );
        if let Some(m) = d.max_um {
            // Where the curve is stable the dots should lie on it: how far
            // the farthest of them is.
            text.push_str(&format!("; within {m:.1} µm of the stable curve"));
        }
        text.push(')');
        items.push((KeyIcon::Overlay, text));
    }
    if v.branch_error.is_some() {
        items.push((
            KeyIcon::Line(FAILURE, true),
            "solver failure: branch ends".into(),
        ));
    }
    items
}

/// The lines under the frequency response's key: the plain sentence when
/// the branch is unstable over a range, then the warnings (a solver
/// failure, a branch that turns back, failed time-integration points).
fn fr_lines(v: &FrView, chars: usize) -> Vec<KeyLine> {
    let x = (v.omega_from, v.omega_to);
    let mut lines: Vec<KeyLine> = unstable_sentence(v)
        .map_or(Vec::new(), |t| wrap(&t, chars))
        .into_iter()
        .map(KeyLine::Sentence)
        .collect();
    let mut notes = Vec::new();
    if let Some((at, e)) = &v.branch_error {
        let text = format!(
            "Solver failure after Ω = {at:.4}: {}. The branch ends there (partial).",
            solver::keys::truncate(e, 160)
        );
        notes.extend(wrap(&text, chars));
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
                    chars,
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
    lines.extend(notes.into_iter().map(KeyLine::Warning));
    lines
}

/// The colour of a branch's max x (`which`) or min x curve: faded, A's, a
/// family member's or the current state's own.
pub(super) fn branch_color(br: &FrBranch, which: bool) -> RGBColor {
    match (br.faded, br.pinned, which, br.member) {
        (true, _, _, _) => FADED,
        (false, true, true, _) => A_MAX,
        (false, true, false, _) => A_MIN,
        (false, false, _, Some(m)) => family_color(m),
        (false, false, true, None) => MAX_COLOR,
        (false, false, false, None) => MIN_COLOR,
    }
}

/// A branch's max x (`which`) or min x split into runs of equal
/// stability, `(unstable, points)`: stable (or unknown) drawn solid,
/// unstable dashed; consecutive runs of one piece share their joining
/// point, and no line joins two pieces of the branch.
pub(super) fn stability_runs(points: &[FrCurvePoint], which: bool) -> Vec<(bool, Vec<(f64, f64)>)> {
    let val = |p: &FrCurvePoint| if which { p.max_um } else { p.min_um };
    let mut runs: Vec<(bool, Vec<(f64, f64)>)> = Vec::new();
    let mut prev: Option<&FrCurvePoint> = None;
    for p in points {
        let unstable = p.stable == Some(false);
        let joined = prev.is_none_or(|q| q.joins(p));
        prev = Some(p);
        match runs.last_mut() {
            Some((u, pts)) if *u == unstable && joined => pts.push((p.omega, val(p))),
            _ => {
                let mut pts = Vec::new();
                if let Some((_, prev)) = runs.last().filter(|_| joined) {
                    if let Some(&last) = prev.last() {
                        pts.push(last);
                    }
                }
                pts.push((p.omega, val(p)));
                runs.push((unstable, pts));
            }
        }
    }
    runs
}

/// The points of a polyline at least `min_px` pixels (Chebyshev distance)
/// from the last point kept, with both ends kept.
pub(super) fn thin(
    pts: Vec<(f64, f64)>,
    to_px: impl Fn(&(f64, f64)) -> (i32, i32),
    min_px: i32,
) -> Vec<(f64, f64)> {
    let n = pts.len();
    let mut out: Vec<(f64, f64)> = Vec::with_capacity(n);
    let mut last: Option<(i32, i32)> = None;
    for (i, p) in pts.into_iter().enumerate() {
        let px = to_px(&p);
        let far = last.is_none_or(|l| (px.0 - l.0).abs().max((px.1 - l.1).abs()) >= min_px);
        if far || i + 1 == n {
            out.push(p);
            last = Some(px);
        }
    }
    out
}

/// The key's lines of the branches not faded: a family member once (its
/// max and min share its colour), any other branch's max and min.
pub(super) fn branch_items(branches: &[FrBranch]) -> KeyItems {
    let mut items: KeyItems = Vec::new();
    for br in branches.iter().filter(|b| !b.faded) {
        if br.member.is_some() {
            items.push((
                KeyIcon::Line(branch_color(br, true), false),
                br.label.clone(),
            ));
        } else {
            for (which, what) in [(true, "max x"), (false, "min x")] {
                items.push((
                    KeyIcon::Line(branch_color(br, which), false),
                    format!("{what} ({})", br.label),
                ));
            }
        }
    }
    items
}

/// Draws a branch's max and min x, stable runs solid and unstable ones
/// dashed. A branch has about a thousand points, most less than a pixel
/// apart: drawing each (every dash a stroke) made a redraw take 100 ms, so
/// points closer than 2 px to the last one kept are left out (the ends
/// always stay).
pub(super) fn draw_branch<DB: DrawingBackend>(chart: &mut Chart<'_, DB>, br: &FrBranch) -> Res<()> {
    for which in [true, false] {
        let style = ShapeStyle::from(&branch_color(br, which)).stroke_width(2);
        for (unstable, pts) in stability_runs(&br.points, which) {
            let pts = thin(pts, |p| chart.backend_coord(p), 2);
            if unstable {
                chart
                    .draw_series(DashedLineSeries::new(pts, 5, 4, style))
                    .map_err(err)?;
            } else {
                chart
                    .draw_series(LineSeries::new(pts, style))
                    .map_err(err)?;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    /// Thinning keeps both ends and drops points under the pixel distance.
    #[test]
    fn thin_keeps_the_ends_and_drops_near_points() {
        let pts: Vec<(f64, f64)> = (0..=10).map(|k| (f64::from(k), 0.0)).collect();
        let out = super::thin(pts, |p| (p.0 as i32, p.1 as i32), 3);
        assert_eq!(
            out.iter().map(|p| p.0).collect::<Vec<_>>(),
            vec![0.0, 3.0, 6.0, 9.0, 10.0]
        );
    }
}
