//! Small multiples of a parameter family: the bifurcation diagram, the
//! phase portrait and the Poincaré section of each member side by side
//! (the paper's panels a-c, d-f), on shared axes so that the panels
//! compare at a glance, with one key under them; and the frequency
//! responses of several meshes (the paper's Figs. 2 and 3, panels a-d),
//! every family member's curve in each.

use super::bif::{failed_crosses, group_dots};
use super::fr::{branch_items, draw_branch, fr_clipped};
use super::*;
use crate::protocol::OmegaResult;
use crate::views::bif::BifView;
use crate::views::fr::FrView;
use crate::views::multiples::Panel;

/// Room for the title above the panels and the key under them (pixels).
const TOP: u32 = 28;
const BOTTOM: u32 = 40;
/// A family's panels a row on a wide canvas: six panels of a 760-pixel
/// canvas in one row were too narrow for their titles and tick labels.
pub const FAMILY_COLS: usize = 3;

/// The canvas size of a family of `n` small multiples (pixels): one row is
/// the ordinary plot's height, two rows are taller so each panel reads.
pub fn family_panels_size(n: usize) -> (u32, u32) {
    (WIDTH, if n > FAMILY_COLS { 680 } else { HEIGHT })
}

/// The most orbit samples a family's phase portraits draw in all: about
/// 250 periods of each of six members at 64 samples a period. Six chaotic
/// orbits of 1000 periods (64 000 samples each, hardly any two on the same
/// pixel segment of a small panel) took 130 ms of main-thread CPU time to
/// decimate and stroke in one frame; at panel size the last 250 periods
/// already fill the attractor's picture, and the Poincaré dots of every
/// recorded period are drawn.
pub const PANEL_ORBIT_SAMPLES: usize = 96_000;

/// The first sample of the orbit a phase panel draws, and the periods
/// from there to the end, when `n` panels share [`PANEL_ORBIT_SAMPLES`]:
/// the last whole periods that fit (at least one), or the whole record.
pub fn panel_orbit_tail(r: &OmegaResult, n: usize) -> (usize, usize) {
    let len = r.x_um.len().min(r.xdot_m_s.len());
    let spp = (r.samples_per_period as usize).max(1);
    let budget = PANEL_ORBIT_SAMPLES / n.max(1);
    if len <= budget {
        return (0, len / spp);
    }
    let periods = (budget / spp).max(1).min(len / spp);
    (len - periods * spp, periods)
}

/// The ±b lines of a panel over Ω.
const GUIDE: RGBColor = RGBColor(90, 90, 90);

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
pub fn phase_ranges(panels: &[Panel<&OmegaResult>]) -> ((f64, f64), (f64, f64)) {
    let ok = || panels.iter().filter_map(|p| p.data.as_ref().ok().copied());
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

/// The panel areas of `n` panels side by side under a title and over a key
/// (two a row on a phone's narrow canvas, else up to [`FAMILY_COLS`]), and
/// the panels a row. With `chrome` the canvas is cleared and the title and
/// key drawn; without, the same areas are only measured (a drawing in
/// parts adds its later panels to the first's).
fn layout<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    title: &str,
    key: &str,
    n: usize,
    chrome: bool,
) -> Res<(Vec<DrawingArea<DB, Shift>>, usize)> {
    if chrome {
        root.fill(&WHITE).map_err(err)?;
    }
    let (w, h) = root.dim_in_pixel();
    let cols = if w < super::NARROW {
        n.clamp(1, 2)
    } else {
        n.clamp(1, FAMILY_COLS)
    };
    let rows = n.max(1).div_ceil(cols);
    let caption = if chrome {
        super::draw_caption(root, title, super::Align::Left, 17)?
    } else {
        super::caption_height(root, title, 17)?
    };
    let top = TOP.max(caption as u32 + 4);
    // The key in lines under the panels (two on a wide canvas).
    let lines = wrap(key, super::line_chars(w + 64));
    let bottom = BOTTOM.max(8 + 16 * lines.len() as u32);
    for (k, line) in lines.iter().enumerate().filter(|_| chrome) {
        root.draw(&Text::new(
            line.clone(),
            (10, h as i32 - bottom as i32 + 4 + 16 * k as i32),
            small(),
        ))
        .map_err(err)?;
    }
    let (_, rest) = root.split_vertically(top);
    let (middle, _) = rest.split_vertically(h.saturating_sub(top + bottom));
    let mut areas = middle.split_evenly((rows, cols));
    areas.truncate(n.max(1));
    Ok((areas, cols))
}

/// One panel's chart on shared ranges: its title, compact tick labels, the
/// axis descriptions (the y description on the first panel only).
fn panel_chart<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    title: &str,
    (x, y): ((f64, f64), (f64, f64)),
    (x_desc, y_desc): (&str, &str),
    first: bool,
    ticks: Ticks,
) -> Res<Chart<'a, DB>> {
    let under = super::draw_caption(area, title, super::Align::Centre, 15)?;
    let fmt = |span: f64| {
        move |v: &f64| -> String {
            let s = if span >= 20.0 {
                format!("{v:.0}")
            } else if span >= 2.0 {
                format!("{v:.1}")
            } else {
                format!("{v:.2}")
            };
            // Zero without a sign (a tick at -1e-17 read "-0.00").
            match s.strip_prefix('-') {
                Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
                _ => s,
            }
        }
    };
    let (fx, fy) = (fmt(x.1 - x.0), fmt(y.1 - y.0));
    // The labels' own width; the first panel's holds the description too.
    let labels = super::y_tick_labels(y, 6, &fy);
    let y_area = if first {
        super::y_label_area(area, &labels, true).max(58)
    } else {
        super::y_label_area(area, &labels, false).max(44)
    };
    let mut chart = ChartBuilder::on(area)
        .margin(6)
        .margin_top(under as u32 + 8)
        .margin_right(16)
        .x_label_area_size(42)
        .y_label_area_size(y_area)
        .build_cartesian_2d(XCoord::new(x, ticks), y.0..y.1)
        .map_err(err)?;
    let y_desc = super::fit_desc(
        chart.plotting_area(),
        y_desc,
        chart.plotting_area().dim_in_pixel().1,
    );
    let mut mesh = chart.configure_mesh();
    if ticks == Ticks::Data {
        mesh.x_label_formatter(&fx);
    }
    mesh.light_line_style(GRID.mix(0.5))
        .bold_line_style(GRID)
        .x_labels(4)
        .y_labels(6)
        .y_label_formatter(&fy)
        .x_desc(x_desc)
        .y_desc(if first { y_desc.as_str() } else { "" })
        .label_style(("sans-serif", 11).into_font().color(&RGBColor(50, 50, 50)))
        .axis_desc_style(small())
        .draw()
        .map_err(err)?;
    Ok(chart)
}

/// A panel's data, or `None` once its frame and why there is none are
/// drawn.
fn panel_data<'a, DB: DrawingBackend, T>(
    area: &DrawingArea<DB, Shift>,
    p: &'a Panel<T>,
) -> Res<Option<&'a T>> {
    match &p.data {
        Ok(v) => Ok(Some(v)),
        Err(e) => panel_message(area, &p.title, e).map(|()| None),
    }
}

/// A panel without data: its frame and why.
fn panel_message<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    message: &str,
) -> Res<()> {
    let under = super::draw_caption(area, title, super::Align::Left, 15)?;
    for (k, line) in wrap(message, 30).iter().take(6).enumerate() {
        area.draw(&Text::new(
            line.clone(),
            (8, under + 12 + 16 * k as i32),
            small(),
        ))
        .map_err(err)?;
    }
    Ok(())
}

/// A ±b contact line: dotted, thin, so that it never reads as a dashed
/// (unstable) branch of the same colour.
fn dotted<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    pts: Vec<(f64, f64)>,
    color: RGBColor,
) -> Res<()> {
    chart
        .draw_series(DashedLineSeries::new(
            pts,
            2,
            3,
            super::contact_style(color),
        ))
        .map_err(err)?;
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

/// A panel over Ω: the ±b lines of `backlash_um` where they fall in the
/// y range, in the member's colour `color` (every view of one member says
/// which), and the selected Ω where it falls in the x range (dashed).
fn omega_guides<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    backlash_um: &[f64],
    selected: f64,
    (x, y): ((f64, f64), (f64, f64)),
    color: RGBColor,
) -> Res<()> {
    for &b in backlash_um {
        for level in [b, -b].into_iter().filter(|l| (y.0..=y.1).contains(l)) {
            dotted(chart, vec![(x.0, level), (x.1, level)], color)?;
        }
    }
    if (x.0..=x.1).contains(&selected) {
        dashed(chart, vec![(selected, y.0), (selected, y.1)], CURSOR)?;
    }
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
        "Dots: Poincaré samples coloured by regime ({}); filled: upward sweep, open: downward. Dotted: ±b, in the panel's colour; dashed red: selected speed.",
        if regimes.is_empty() { "none yet".to_string() } else { regimes.join(", ") }
    );
    let (areas, cols) = layout(root, &title, &key, panels.len(), true)?;
    let mut frames = Vec::new();
    let mut groups: Vec<PointGroup> = Vec::new();
    for (k, (area, p)) in areas.iter().zip(panels).enumerate() {
        let Some(v) = panel_data(area, p)? else {
            frames.push(None);
            continue;
        };
        let mut t = p.title.clone();
        if v.done < v.total {
            t.push_str(&format!(" ({}/{})", v.done, v.total));
        }
        let mut chart = panel_chart(
            area,
            &t,
            (x, y),
            (&v.speed.short_label(), "Poincaré samples of x (µm)"),
            k % cols == 0,
            Ticks::over_omega(&v.speed),
        )?;
        omega_guides(
            &mut chart,
            &v.backlash_um,
            v.selected_omega,
            (x, y),
            family_color(k),
        )?;
        failed_crosses(&mut chart, &v.failed, y.0, 4)?;
        let frame = frame_of(&chart, x, y);
        group_dots(&mut groups, &v.points, &frame);
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

/// A family member's phase portrait or Poincaré section title: the
/// member and its motion's classification ("(a) TE 5 µm: period 1 (exact)").
pub fn phase_panel_title(title: &str, r: &OmegaResult) -> String {
    format!("{title}: {}", crate::story::motion_tag_short(r.motion))
}

/// The phase portraits (`poincare` false) or Poincaré sections of a
/// family side by side: each panel's x axis fits its own orbit and its ±b
/// (a shared one squeezed each orbit into a sliver: Fig. 9's backlashes
/// 50 to 200 µm), the velocity axis is shared; each panel's ±b lines are
/// in its member's colour. With `part` `Some(k)` only panel k is drawn,
/// and the canvas cleared, the title and key drawn, only with the first:
/// the page draws six panels of long orbits over six frames.
pub fn draw_phase_panels<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    panels: &[Panel<&OmegaResult>],
    poincare: bool,
    status: &str,
    part: Option<usize>,
) -> Res<()> {
    let (_, y) = phase_ranges(panels);
    let first = panels.iter().find_map(|p| p.data.as_ref().ok());
    let (what, key) = if poincare {
        (
            "Poincaré sections",
            "Dots: the state once per mesh period after the transient; dotted: ±b, in the panel's colour",
        )
    } else {
        (
            "Phase portraits",
            "Line: the recorded orbit; red dots: its Poincaré points; dotted: ±b, in the panel's colour",
        )
    };
    // Without backlash the dotted line is x = 0, not ±b.
    let no_backlash = panels
        .iter()
        .filter_map(|p| p.data.as_ref().ok())
        .all(|r| !crate::story::has_backlash(r.backlash_um));
    let key = if no_backlash {
        key.replace(
            "dotted: ±b, in the panel's colour",
            "dotted: x = 0 (no backlash)",
        )
    } else {
        key.to_string()
    };
    let title = match first {
        Some(r) => format!(
            "{what}, mesh {}, Ω = {:.4}, x axis per panel, velocity shared{status}",
            r.mesh_name, r.omega
        ),
        None => format!("{what}{status}"),
    };
    // A motion still settling is starred in the panel's title (the title
    // has no room for the words) and said in the key.
    let unsettled =
        |r: &OmegaResult| matches!(r.motion, crate::protocol::Motion::StillSettling { .. });
    let mut key = key;
    // The orbits cut to the panels' budget, in words: "the last 250 of 1000
    // recorded periods" (the largest of the panels' cuts).
    let n = panels.len();
    let cut = panels
        .iter()
        .filter_map(|p| p.data.as_ref().ok())
        .filter_map(|r| match panel_orbit_tail(r, n) {
            (0, _) => None,
            (_, shown) => Some((shown, r.record_periods)),
        })
        .max_by_key(|&(shown, _)| shown);
    if let (false, Some((shown, recorded))) = (poincare, cut) {
        key = format!(
            "Line: the orbit's last {shown} of {recorded} recorded periods; red dots: the Poincaré points of all of them; dotted: {}",
            if no_backlash { "x = 0 (no backlash)" } else { "±b, in the panel's colour" }
        );
    }
    if panels
        .iter()
        .any(|p| p.data.as_ref().is_ok_and(|r| unsettled(r)))
    {
        key.push_str("; ");
        key.push_str(crate::story::STILL_SETTLING_KEY);
    }
    let chrome = part.is_none_or(|k| k == 0);
    let (areas, cols) = layout(root, &title, &key, panels.len(), chrome)?;
    let drawn = |k: usize| part.is_none_or(|only| only == k);
    for (k, (area, p)) in areas
        .iter()
        .zip(panels)
        .enumerate()
        .filter(|(k, _)| drawn(*k))
    {
        let Some(r) = panel_data(area, p)? else {
            continue;
        };
        let t = phase_panel_title(&p.title, r);
        let (x, _) = phase_ranges(std::slice::from_ref(p));
        let mut chart = panel_chart(
            area,
            &t,
            (x, y),
            ("x (µm)", "ẋ (m/s)"),
            k % cols == 0,
            Ticks::Data,
        )?;
        let b = r.backlash_um;
        let color = family_color(k);
        // The contact lines where they fall in range (the axes fit the
        // data), in the member's colour.
        for level in [b, -b].into_iter().filter(|l| (x.0..=x.1).contains(l)) {
            dotted(&mut chart, vec![(level, y.0), (level, y.1)], color)?;
        }
        if !poincare {
            let (from, _) = panel_orbit_tail(r, n);
            super::omega::draw_orbit(&mut chart, r, from, color)?;
        }
        let (dot, size) = if poincare { (color, 3) } else { (CURSOR, 3) };
        let dots = super::omega::poincare_dots(r, |p| chart.backend_coord(&p));
        chart
            .draw_series(dots.into_iter().map(|p| Circle::new(p, size, dot.filled())))
            .map_err(err)?;
    }
    root.present().map_err(err)
}

/// Rows and columns of `n` frequency-response panels: two columns up to
/// four panels (the paper's a-d as a 2 × 2 grid), three beyond.
pub fn fr_grid(n: usize) -> (usize, usize) {
    let cols = match n {
        0 | 1 => 1,
        2..=4 => 2,
        _ => 3,
    };
    (n.div_ceil(cols).max(1), cols)
}

/// The canvas size of `n` frequency-response panels (pixels): one row is
/// the ordinary plot's height, two rows are taller so each panel reads.
pub fn fr_panels_size(n: usize) -> (u32, u32) {
    let (rows, _) = fr_grid(n);
    (WIDTH, if rows > 1 { 680 } else { HEIGHT })
}

/// The frequency responses of several meshes (the paper's Figs. 2 and 3,
/// panels a-d), each panel on its own x scale and all on one Ω axis, with
/// one key in words under them naming each curve's value. Returns each
/// panel's frame (`None` without data).
pub fn draw_fr_panels<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    panels: &[Panel<FrView>],
    status: &str,
) -> Res<Vec<Option<PlotFrame>>> {
    root.fill(&WHITE).map_err(err)?;
    let title = format!(
        "Frequency response of {} meshes: max and min x, Ω axis shared{status}",
        panels.len()
    );
    let top = TOP.max(super::draw_caption(root, &title, super::Align::Left, 17)? as u32 + 4);
    // The key under the panels: one coloured line per curve, in words,
    // from the first panel with data (every panel holds the same curves),
    // then the line styles; as tall as it needs on a narrow canvas.
    let mut items: KeyItems = panels
        .iter()
        .find_map(|p| p.data.as_ref().ok())
        .map_or_else(Vec::new, |v| branch_items(&v.branches));
    items.extend([
        (
            KeyIcon::Dotted(GUIDE),
            "±b (contact), grey, where in range".into(),
        ),
        (KeyIcon::Line(CURSOR, true), "selected speed".into()),
    ]);
    let lines = vec![KeyLine::Sentence(format!(
        "Solid: stable; {}.",
        super::fr::UNSTABLE_KEY
    ))];
    let plan = plan_key(root, &items, lines);
    draw_key(root, &items, &plan)?;
    let (_, rest) = root.split_vertically(top);
    let (middle, _) = rest.split_vertically((plan.top.max(top as i32 + 40) as u32) - top);
    let (rows, cols) = fr_grid(panels.len());
    let areas = middle.split_evenly((rows, cols));
    let mut frames = Vec::new();
    for (k, (area, p)) in areas.iter().zip(panels).enumerate() {
        let Some(v) = panel_data(area, p)? else {
            frames.push(None);
            continue;
        };
        let x = (v.omega_from, v.omega_to);
        // A lightly damped first mode's spike would flatten the rest: the
        // axis fits the rest and the clipped peak is marked with its value.
        let clipped = fr_clipped(v, false);
        let y = clipped.range;
        let mut chart = panel_chart(
            area,
            &p.title,
            (x, y),
            (&v.speed.short_label(), "x = δ − e (µm)"),
            k % cols == 0,
            Ticks::over_omega(&v.speed),
        )?;
        let levels: Vec<f64> = v
            .backlash_um
            .iter()
            .chain(&v.pinned_backlash_um)
            .copied()
            .collect();
        // Grey: a mesh panel holds every member's curve, so no member's
        // colour is the panel's.
        omega_guides(&mut chart, &levels, v.selected_omega, (x, y), GUIDE)?;
        for br in v.branches.iter() {
            draw_branch(&mut chart, br)?;
        }
        super::clip::mark_clipped(&mut chart, &clipped)?;
        frames.push(Some(frame_of(&chart, x, y)));
    }
    root.present().map_err(err)?;
    Ok(frames)
}
