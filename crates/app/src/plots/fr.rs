//! View 1's plot: the frequency response (branches, stability, markers,
//! the regime strip, the overlay and the key row).

use super::*;
use crate::views::fr::{FrBranch, FrCurvePoint, FrMarkerKind, FrView};
use crate::views::unstable::{strip_from_overlay, unstable_ranges, unstable_sentence};

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
    let extra = contact_levels(&v.backlash_um, &v.pinned_backlash_um, v.whole_clearance);
    // Room at the top for the legend (two lines per branch, the faded
    // branch, the unstable dash, the failure line).
    // (A family's member has one line: its max and min share a colour.)
    let entries = v
        .branches
        .iter()
        .filter(|b| !b.faded)
        .map(|b| if b.member.is_some() { 1 } else { 2 })
        .sum::<usize>()
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
    // The regime strip is drawn under the current state's branch only (not
    // a family's members): its key only then.
    for r in v
        .branches
        .iter()
        .filter(|b| !b.faded && b.member.is_none())
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
                format!("regime strip: {}", r.label())
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
        // Short enough for one row of the key: the points off the stable
        // branch are what the sentence under the key is about.
        let mut text = format!(
            "time integration: the actual response ({} points",
            v.overlay.len()
        );
        if let Some(m) = d.max_um {
            text.push_str(&format!(
                "; within {m:.1} µm of the stable branch at {}",
                d.compared
            ));
        }
        text.push(')');
        items.push((KeyIcon::Overlay, text));
    }
    let (at, rows) = key_layout(root, &items, 76);
    // The plain sentence under the key when the branch is unstable over a range.
    let sentence: Vec<String> = unstable_sentence(v).map_or(Vec::new(), |t| wrap(&t, 86));
    let key_h = 8 + KEY_ROW * (rows + sentence.len() as i32);
    let (upper, _) = root.split_vertically(HEIGHT as i32 - key_h);
    let caption = if v.branches.iter().any(|b| b.member.is_some()) {
        format!(
            "Frequency response, mesh {}: max and min x per value{status}",
            v.mesh_label
        )
    } else {
        format!(
            "Frequency response, mesh {} ({}){status}",
            v.mesh_label, v.method
        )
    };
    let axes = Axes::new(OMEGA_AXIS, "x = δ − e (µm)");
    let mut chart = linear_chart(&upper, &caption, (x, y), &axes)?;
    // These three go in the key under the chart, keeping the legend short.
    contact_lines(&mut chart, &v.backlash_um, x, true, false)?;
    pinned_contact_lines(&mut chart, &v.pinned_backlash_um, &v.backlash_um, x)?;
    omega_decorations(&mut chart, &v.natural, v.selected_omega, y, false)?;
    let mut any_unstable = false;
    for br in &v.branches {
        for (which, color, label) in [(true, MAX_COLOR, "max x"), (false, MIN_COLOR, "min x")] {
            let color = branch_color(br, which).unwrap_or(color);
            let runs = stability_runs(&br.points, which);
            let style = ShapeStyle::from(&color).stroke_width(2);
            // The faded branch and a family member are labelled once, not
            // per extreme (a member's max and min share its colour).
            let mut labelled = (br.faded || br.member.is_some()) && !which;
            for (unstable, pts) in runs {
                // A branch has about a thousand points, most less than a
                // pixel apart: drawing each (every dash a stroke) made a
                // redraw take 100 ms. Points closer than 2 px to the last
                // one kept are left out; the ends always stay.
                let pts = thin(pts, |p| chart.backend_coord(p), 2);
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
                    } else if br.member.is_some() {
                        br.label.clone()
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
        if !br.faded && !br.pinned && br.member.is_none() {
            // Where no stretch is stable, the strip shows the dots' regimes.
            let filled = strip_from_overlay(&unstable_ranges(&br.points), &v.overlay);
            regime_strip(&mut chart, &br.points, &filled, y)?;
        }
    }
    if any_unstable {
        let style = ShapeStyle::from(&CONTACT).stroke_width(2);
        legend_only(&mut chart, "unstable (Floquet): dashed", style, [5, 9])?;
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
    for (k, line) in sentence.iter().enumerate() {
        let y0 = HEIGHT as i32 - key_h + 5 + KEY_ROW * (rows + k as i32);
        root.draw(&Text::new(
            line.clone(),
            (76, y0),
            ("sans-serif", 13).into_font().style(FontStyle::Bold),
        ))
        .map_err(err)?;
    }
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

/// The colour of a branch's max x (`which`) or min x curve, if not the
/// current state's own (faded, A's, or a family member's).
pub(super) fn branch_color(br: &FrBranch, which: bool) -> Option<RGBColor> {
    match (br.faded, br.pinned, which, br.member) {
        (true, _, _, _) => Some(FADED),
        (false, true, true, _) => Some(A_MAX),
        (false, true, false, _) => Some(A_MIN),
        (false, false, _, Some(m)) => Some(family_color(m)),
        _ => None,
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
