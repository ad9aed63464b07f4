//! The selected-Omega plots: phase portrait, Poincaré section, time
//! history and spectrum.

use super::*;
use crate::protocol::{history_start, OmegaResult, HISTORY_PERIODS};

/// The ±b levels an axis of x must include: both with the whole clearance,
/// none when the axes fit the data.
fn levels(r: &OmegaResult, whole: bool) -> Vec<f64> {
    if whole {
        vec![r.backlash_um, -r.backlash_um]
    } else {
        Vec::new()
    }
}

fn phase_ranges(r: &OmegaResult, whole: bool) -> ((f64, f64), (f64, f64)) {
    let x = padded_range(r.x_um.iter().copied(), &levels(r, whole), 20.0);
    let vmax = r.xdot_m_s.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let y = padded_range(r.xdot_m_s.iter().copied(), &[], (vmax * 0.2).max(1e-3));
    (x, y)
}

fn omega_caption(what: &str, r: &OmegaResult, status: &str) -> String {
    format!("{what}, mesh {}, Ω = {:.4}{status}", r.mesh_name, r.omega)
}

/// The phase plane (x, ẋ) of the phase portrait and the Poincaré section:
/// the same axes, so one point reads as one point, and the ±b lines; the
/// chart goes on `area`, above the key.
fn phase_plane<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    r: &OmegaResult,
    (what, x_desc): (&str, &str),
    status: &str,
    (x, y): ((f64, f64), (f64, f64)),
) -> Res<Chart<'a, DB>> {
    let caption = omega_caption(what, r, status);
    let mut chart = linear_chart(area, &caption, (x, y), &Axes::new(x_desc, "ẋ (m/s)"))?;
    contact_lines(&mut chart, &[r.backlash_um], y, false)?;
    Ok(chart)
}

/// The orbit's line: the colour a 70 % translucent line has on white,
/// drawn opaque. A translucent path that crosses itself thousands of times
/// (a record of 1000 periods) costs the canvas a coverage mask per stroke,
/// an opaque one plain hairlines; and where two runs of
/// [`decimate::polyline_runs`] cross, an opaque line does not darken.
fn orbit_style(color: RGBColor) -> ShapeStyle {
    let mix = |c: u8| (0.7 * f64::from(c) + 0.3 * 255.0).round() as u8;
    ShapeStyle::from(&RGBColor(mix(color.0), mix(color.1), mix(color.2))).stroke_width(1)
}

/// Draws the orbit of `r` in `color`, each pixel segment once (a steady
/// orbit retraces its pixels every period, 1000 times at the most).
pub(super) fn draw_orbit<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    r: &OmegaResult,
    from_sample: usize,
    color: RGBColor,
) -> Res<()> {
    let runs = decimate::polyline_runs(
        r.x_um
            .iter()
            .copied()
            .zip(r.xdot_m_s.iter().copied())
            .skip(from_sample),
        |p| chart.backend_coord(&p),
    );
    let style = orbit_style(color);
    for run in &runs {
        chart
            .draw_series(LineSeries::new(run.iter().copied(), style))
            .map_err(err)?;
    }
    Ok(())
}

/// The Poincaré points, one per pixel of `px` (equal dots on one pixel
/// look like one).
pub(super) fn poincare_dots(
    r: &OmegaResult,
    px: impl Fn((f64, f64)) -> decimate::Px,
) -> Vec<(f64, f64)> {
    decimate::one_per_pixel(
        r.poincare_x_um
            .iter()
            .copied()
            .zip(r.poincare_xdot_m_s.iter().copied()),
        px,
    )
}

/// `ViewId::Phase`: the phase portrait with its Poincaré points.
pub fn draw_phase<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &OmegaResult,
    status: &str,
) -> Res<()> {
    draw_phase_with(root, r, status, true)
}

/// The phase portrait, its x axis fitting the data unless `whole` (the whole clearance ±b).
pub fn draw_phase_with<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &OmegaResult,
    status: &str,
    whole: bool,
) -> Res<()> {
    draw_plane(root, r, status, whole, false)
}

/// `ViewId::Poincare`: the Poincaré section, on the orbit's axes so that one point reads as one point.
pub fn draw_poincare<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &OmegaResult,
    status: &str,
) -> Res<()> {
    draw_poincare_with(root, r, status, true)
}

/// The Poincaré section, its x axis fitting the data unless `whole`.
pub fn draw_poincare_with<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &OmegaResult,
    status: &str,
    whole: bool,
) -> Res<()> {
    draw_plane(root, r, status, whole, true)
}

/// The phase plane: the orbit with its Poincaré points, or (`poincare`)
/// the points alone, larger.
fn draw_plane<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &OmegaResult,
    status: &str,
    whole: bool,
    poincare: bool,
) -> Res<()> {
    root.fill(&WHITE).map_err(err)?;
    let (x, y) = phase_ranges(r, whole);
    let (mut items, what, radius): (KeyItems, _, i32) = if poincare {
        let points = poincare_key(r);
        let what = (
            "Poincaré section",
            "x = δ − e (µm), sampled once per mesh period",
        );
        (vec![(KeyIcon::Dot(CURSOR, 3), points)], what, 3)
    } else {
        let orbit = format!("orbit over {} recorded periods", r.record_periods);
        let points = "Poincaré points (once per mesh period)".to_string();
        let items = vec![
            (KeyIcon::Line(ORBIT, false), orbit),
            (KeyIcon::Dot(CURSOR, 4), points),
        ];
        (items, ("Phase portrait", "x = δ − e (µm)"), 4)
    };
    items.extend(contact_item(&[r.backlash_um], x));
    let plan = plan_key(root, &items, Vec::new());
    let area = chart_area(root, &plan);
    let mut chart = phase_plane(&area, r, what, status, (x, y))?;
    if !poincare {
        draw_orbit(&mut chart, r, 0, ORBIT)?;
    }
    let dots = poincare_dots(r, |p| chart.backend_coord(&p));
    chart
        .draw_series(
            dots.into_iter()
                .map(|p| Circle::new(p, radius, CURSOR.filled())),
        )
        .map_err(err)?;
    draw_key(root, &items, &plan)?;
    root.present().map_err(err)
}

/// The Poincaré section's key entry: how many points, and the motion's
/// classification ("100 Poincaré points: period 1 (exact)").
pub fn poincare_key(r: &OmegaResult) -> String {
    format!(
        "{} Poincaré points: {}",
        r.poincare_x_um.len(),
        crate::story::motion_tag(r.motion)
    )
}

/// `ViewId::Time`: the time history of the last recorded periods.
pub fn draw_time<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &OmegaResult,
    status: &str,
) -> Res<PlotFrame> {
    draw_time_with(root, r, status, true)
}

/// The time history, its x axis fitting the data unless `whole`.
pub fn draw_time_with<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    r: &OmegaResult,
    status: &str,
    whole: bool,
) -> Res<PlotFrame> {
    root.fill(&WHITE).map_err(err)?;
    let spp = r.samples_per_period.max(1) as usize;
    let shown = HISTORY_PERIODS.min(r.record_periods) as usize;
    let start = history_start(r.x_um.len(), r.samples_per_period, r.record_periods);
    let t0 = start as f64 / spp as f64;
    let t1 = (r.x_um.len().max(1) - 1) as f64 / spp as f64;
    let x = (t0, t1.max(t0 + 1e-9));
    let b = r.backlash_um;
    let y = padded_range(r.x_um[start..].iter().copied(), &levels(r, whole), 20.0);
    let style = ShapeStyle::from(&ORBIT).stroke_width(2);
    let mut items: KeyItems = vec![(KeyIcon::Line(ORBIT, false), "x(t)".into())];
    items.extend(contact_item(&[b], y));
    let plan = plan_key(root, &items, Vec::new());
    let area = chart_area(root, &plan);
    let caption = omega_caption("Time history", r, status);
    let axes = Axes::new(
        format!(
            "time (mesh periods since the recording began; last {shown} of {})",
            r.record_periods
        ),
        "x = δ − e (µm)",
    );
    let mut chart = linear_chart(&area, &caption, (x, y), &axes)?;
    contact_lines(&mut chart, &[b], x, true)?;
    chart
        .draw_series(LineSeries::new(
            r.x_um[start..]
                .iter()
                .enumerate()
                .map(|(k, &v)| ((start + k) as f64 / spp as f64, v)),
            style,
        ))
        .map_err(err)?;
    let frame = frame_of(&chart, x, y);
    draw_key(root, &items, &plan)?;
    root.present().map_err(err)?;
    Ok(frame)
}

/// `ViewId::Spectrum`: the amplitude spectrum of x (without the mean), log scale.
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
    let style = ShapeStyle::from(&MAX_COLOR).stroke_width(2);
    let items: KeyItems = vec![(
        KeyIcon::Line(MAX_COLOR, false),
        match mean {
            Some(m) => format!("amplitude (mean x = {m:.2} µm not shown)"),
            None => "amplitude".into(),
        },
    )];
    let plan = plan_key(root, &items, Vec::new());
    let area = chart_area(root, &plan);
    let mut chart = chart_layout(&area, &omega_caption("Spectrum of x", r, status))?
        .build_cartesian_2d(0.0..omax * 1.02, (floor..amax * 2.0).log_scale())
        .map_err(err)?;
    let axes = Axes::new(
        "frequency (mesh orders: multiples of the mesh frequency)",
        "amplitude of x (µm, log)",
    );
    draw_axes(&mut chart, &axes)?;
    // A line per pixel column (8000 lines over 1000 recorded periods).
    let lines = decimate::tallest_per_column(&lines, |o| chart.backend_coord(&(o, floor)).0);
    chart
        .draw_series(
            lines
                .iter()
                .map(|&(o, a)| PathElement::new(vec![(o, floor), (o, a.max(floor))], style)),
        )
        .map_err(err)?;
    draw_key(root, &items, &plan)?;
    root.present().map_err(err)
}
