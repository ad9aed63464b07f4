//! Small multiples of a parameter family: the bifurcation diagram, the
//! phase portrait and the Poincaré section of each member side by side
//! (the paper's panels a-c, d-f), on shared axes so that the panels
//! compare at a glance, with one key under them.

use super::*;
use crate::protocol::OmegaResult;
use crate::views::bif::BifView;
use crate::views::family::Panel;

/// Room for the title above the panels and the key under them (pixels).
const TOP: u32 = 28;
const BOTTOM: u32 = 40;

/// The shared axes of bifurcation panels: the Omega range of the first
/// panel with data, and one x range holding every panel's dots and ±b.
pub fn bif_ranges(panels: &[Panel<BifView>]) -> ((f64, f64), (f64, f64)) {
    let ok = || panels.iter().filter_map(|p| p.data.as_ref().ok());
    let x = ok()
        .next()
        .map_or((0.0, 1.0), |v| (v.omega_from, v.omega_to));
    let levels: Vec<f64> = ok()
        .flat_map(|v| contact_levels(&v.backlash_um, &[], false))
        .collect();
    let y = padded_range(
        ok().flat_map(|v| v.points.iter().map(|p| p.x_um)),
        &levels,
        20.0,
    );
    (x, y)
}

/// The shared axes of phase-plane panels: one x range holding every
/// orbit, one velocity range holding every orbit.
pub fn phase_ranges(panels: &[Panel<OmegaResult>]) -> ((f64, f64), (f64, f64)) {
    let ok = || panels.iter().filter_map(|p| p.data.as_ref().ok());
    // The axes fit the orbits, as every plot's do (the ±b lines are drawn
    // where they fall in range): at b = 200 µm an orbit near +b would
    // otherwise fill a sliver of a panel that spans the whole clearance.
    let levels: Vec<f64> = ok()
        .flat_map(|r| contact_levels(&[r.backlash_um], &[], false))
        .collect();
    let x = padded_range(ok().flat_map(|r| r.x_um.iter().copied()), &levels, 20.0);
    let vmax = ok()
        .flat_map(|r| r.xdot_m_s.iter())
        .fold(0.0_f64, |m, v| m.max(v.abs()));
    let y = padded_range(
        ok().flat_map(|r| r.xdot_m_s.iter().copied()),
        &[],
        (vmax * 0.2).max(1e-3),
    );
    (x, y)
}

/// The panel areas of `n` panels side by side under a title and over a key.
fn layout<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    key: &str,
    n: usize,
) -> Res<Vec<DrawingArea<DB, Shift>>> {
    root.fill(&WHITE).map_err(err)?;
    let (_, h) = root.dim_in_pixel();
    root.draw(&Text::new(title.to_string(), (10, 6), caption_font()))
        .map_err(err)?;
    // The key in at most two lines under the panels.
    for (k, line) in wrap(key, 110).iter().take(2).enumerate() {
        root.draw(&Text::new(
            line.clone(),
            (10, h as i32 - BOTTOM as i32 + 4 + 16 * k as i32),
            small(),
        ))
        .map_err(err)?;
    }
    let (_, rest) = root.split_vertically(TOP);
    let (middle, _) = rest.split_vertically(h.saturating_sub(TOP + BOTTOM));
    Ok(middle.split_evenly((1, n.max(1))))
}

/// One panel's chart on shared ranges: its title, compact tick labels, the
/// axis descriptions (the y description on the first panel only).
fn panel_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    title: &str,
    (x, y): ((f64, f64), (f64, f64)),
    (x_desc, y_desc): (&str, &str),
    first: bool,
) -> Res<Chart<'a, DB>> {
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 15).into_font().color(&BLACK))
        .margin(6)
        .margin_right(16)
        .x_label_area_size(36)
        .y_label_area_size(if first { 58 } else { 44 })
        .build_cartesian_2d(x.0..x.1, y.0..y.1)
        .map_err(err)?;
    let fmt = |span: f64| {
        move |v: &f64| -> String {
            if span >= 20.0 {
                format!("{v:.0}")
            } else if span >= 2.0 {
                format!("{v:.1}")
            } else {
                format!("{v:.2}")
            }
        }
    };
    let (fx, fy) = (fmt(x.1 - x.0), fmt(y.1 - y.0));
    chart
        .configure_mesh()
        .light_line_style(GRID.mix(0.5))
        .bold_line_style(GRID)
        .x_labels(4)
        .y_labels(6)
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .x_desc(x_desc)
        .y_desc(if first { y_desc } else { "" })
        .label_style(("sans-serif", 11).into_font().color(&RGBColor(50, 50, 50)))
        .axis_desc_style(small())
        .draw()
        .map_err(err)?;
    Ok(chart)
}

/// A panel without data: its frame and why.
fn panel_message<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    message: &str,
) -> Res<()> {
    area.draw(&Text::new(
        title.to_string(),
        (8, 4),
        ("sans-serif", 15).into_font().color(&BLACK),
    ))
    .map_err(err)?;
    for (k, line) in wrap(message, 30).iter().take(6).enumerate() {
        area.draw(&Text::new(line.clone(), (8, 40 + 16 * k as i32), small()))
            .map_err(err)?;
    }
    Ok(())
}

fn dashed<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    pts: Vec<(f64, f64)>,
    color: RGBColor,
) -> Res<()> {
    let style = ShapeStyle::from(&color).stroke_width(1);
    chart
        .draw_series(DashedLineSeries::new(pts, 6, 4, style))
        .map_err(err)?;
    Ok(())
}

/// The bifurcation diagrams of a family side by side. Returns each
/// panel's frame (`None` without data) and the dots in pixels for the
/// caller to draw, as [`draw_bif`] does.
pub fn draw_bif_panels<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    panels: &[Panel<BifView>],
    mesh_label: &str,
    status: &str,
) -> Res<(Vec<Option<PlotFrame>>, Vec<PointGroup>)> {
    let (x, y) = bif_ranges(panels);
    let title = format!("Bifurcation diagrams, mesh {mesh_label}, shared axes{status}");
    let regimes: Vec<&str> = Regime::ALL
        .iter()
        .filter(|r| {
            panels
                .iter()
                .filter_map(|p| p.data.as_ref().ok())
                .any(|v| v.points.iter().any(|p| p.regime == **r))
        })
        .map(|r| r.label())
        .collect();
    let key = format!(
        "Dots: Poincaré samples coloured by regime ({}); filled: upward sweep, open: downward. Dashed grey: ±b; dashed red: selected Ω.",
        if regimes.is_empty() { "none yet".to_string() } else { regimes.join(", ") }
    );
    let areas = layout(root, &title, &key, panels.len())?;
    let mut frames = Vec::new();
    let mut groups: Vec<PointGroup> = Vec::new();
    for (k, (area, p)) in areas.iter().zip(panels).enumerate() {
        let v = match &p.data {
            Ok(v) => v,
            Err(e) => {
                panel_message(area, &p.title, e)?;
                frames.push(None);
                continue;
            }
        };
        let mut t = p.title.clone();
        if v.done < v.total {
            t.push_str(&format!(" ({}/{})", v.done, v.total));
        }
        let mut chart = panel_chart(
            area,
            &t,
            (x, y),
            ("Ω", "Poincaré samples of x (µm)"),
            k == 0,
        )?;
        for &b in &v.backlash_um {
            for level in [b, -b].into_iter().filter(|l| (y.0..=y.1).contains(l)) {
                dashed(
                    &mut chart,
                    vec![(x.0, level), (x.1, level)],
                    RGBColor(90, 90, 90),
                )?;
            }
        }
        let s = v.selected_omega;
        if s >= x.0 && s <= x.1 {
            dashed(&mut chart, vec![(s, y.0), (s, y.1)], CURSOR)?;
        }
        if !v.failed.is_empty() {
            let grey = RGBColor(90, 90, 90);
            chart
                .draw_series(
                    v.failed
                        .iter()
                        .map(|&(omega, _)| Cross::new((omega, y.0), 4, grey.stroke_width(2))),
                )
                .map_err(err)?;
        }
        let frame = frame_of(&chart, x, y);
        for pt in &v.points {
            let color = regime_color(pt.regime);
            let q = frame.to_px(pt.omega, pt.x_um);
            let px = (q.x as f32, q.y as f32);
            match groups
                .iter_mut()
                .find(|g| g.color == color && g.filled == pt.up)
            {
                Some(g) => g.px.push(px),
                None => groups.push(PointGroup {
                    color,
                    filled: pt.up,
                    px: vec![px],
                }),
            }
        }
        frames.push(Some(frame));
    }
    // One dot per pixel and group (see `draw_bif`).
    for g in &mut groups {
        g.px = super::decimate::one_per_pixel(g.px.iter().copied(), |(x, y)| {
            (x.round() as i32, y.round() as i32)
        });
    }
    root.present().map_err(err)?;
    Ok((frames, groups))
}

/// The phase portraits (`poincare` false) or Poincaré sections of a
/// family side by side, on shared axes.
pub fn draw_phase_panels<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    panels: &[Panel<OmegaResult>],
    poincare: bool,
    status: &str,
) -> Res<()> {
    let (x, y) = phase_ranges(panels);
    let first = panels.iter().find_map(|p| p.data.as_ref().ok());
    let (what, key) = if poincare {
        (
            "Poincaré sections",
            "Dots: the state once per mesh period after the transient; dashed: ±b",
        )
    } else {
        (
            "Phase portraits",
            "Line: the recorded orbit; red dots: its Poincaré points; dashed: ±b",
        )
    };
    let title = match first {
        Some(r) => format!(
            "{what}, mesh {}, Ω = {:.4}, shared axes{status}",
            r.mesh_name, r.omega
        ),
        None => format!("{what}{status}"),
    };
    let areas = layout(root, &title, key, panels.len())?;
    for (k, (area, p)) in areas.iter().zip(panels).enumerate() {
        let r = match &p.data {
            Ok(r) => r,
            Err(e) => {
                panel_message(area, &p.title, e)?;
                continue;
            }
        };
        let period = match r.period {
            Some(n) => format!("period {n}"),
            None => "not periodic".into(),
        };
        let t = format!("{}: {period}", p.title);
        let mut chart = panel_chart(area, &t, (x, y), ("x (µm)", "ẋ (m/s)"), k == 0)?;
        let b = r.backlash_um;
        // The contact lines where they fall in range (the axes fit the data).
        for level in [b, -b].into_iter().filter(|l| (x.0..=x.1).contains(l)) {
            dashed(
                &mut chart,
                vec![(level, y.0), (level, y.1)],
                RGBColor(90, 90, 90),
            )?;
        }
        let color = family_color(k);
        if !poincare {
            super::omega::draw_orbit(&mut chart, r, color, None)?;
        }
        let (dot, size) = if poincare { (color, 3) } else { (CURSOR, 3) };
        let dots = super::omega::poincare_dots(r, |p| chart.backend_coord(&p));
        chart
            .draw_series(dots.into_iter().map(|p| Circle::new(p, size, dot.filled())))
            .map_err(err)?;
    }
    root.present().map_err(err)
}
