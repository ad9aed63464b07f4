//! View 2's plot: the bifurcation diagram (dots returned by colour for a
//! batched fill, the instability bands, the regime legend).

use super::*;
use crate::views::bif::BifView;

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
    let extra = contact_levels(&v.backlash_um, &v.pinned_backlash_um, v.whole_clearance);
    let y = with_headroom(
        padded_range(
            v.points.iter().chain(v.pinned.iter()).map(|p| p.x_um),
            &extra,
            20.0,
        ),
        if v.ab_labels.is_some() { 0.8 } else { 0.55 },
    );
    let caption = format!("Bifurcation diagram, mesh {}{status}", v.mesh_label);
    let axes = Axes::new(OMEGA_AXIS, "Poincaré samples of x = δ − e (µm)");
    let mut chart = linear_chart(root, &caption, (x, y), &axes)?;
    contact_lines(&mut chart, &v.backlash_um, x, true, true)?;
    if pinned_contact_lines(&mut chart, &v.pinned_backlash_um, &v.backlash_um, x)? {
        let style = ShapeStyle::from(&A_MIN).stroke_width(1);
        legend_only(&mut chart, "A's ±b contact lines", style, [6, 10])?;
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
    // One dot per pixel and group: a sweep of 1000 recorded periods has
    // up to 1000 Poincaré samples per point, most on a few pixels.
    for g in &mut groups {
        g.px = decimate::one_per_pixel(g.px.iter().copied(), |(x, y)| {
            (x.round() as i32, y.round() as i32)
        });
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
