//! The Campbell diagram's plot: natural frequencies as horizontal lines,
//! the mesh orders as lines through the origin, the critical speeds where
//! they cross (filled where the meshes excite them, hollow and grey where
//! the planets' phasing cancels them), and the selected speed as a vertical
//! line; with sequential phasing the planet-pass orders as thin brown
//! lines, their crossings as triangles. Its frequency axis is the view model's, so every
//! order line ends inside the plot; the key is under the chart.

use super::*;
use crate::speed::{capital, grouped};
use crate::views::campbell::{CampbellCrossing, CampbellView, ORDERS};

/// How close (pixels) a click must come to a crossing to pick it.
pub const PICK_PX: f64 = 12.0;

/// The crossing of `view` nearest the pixel `(px, py)` of its plot drawn
/// with `frame`, if one is within [`PICK_PX`].
pub fn pick<'a>(
    view: &'a CampbellView,
    frame: &PlotFrame,
    px: f64,
    py: f64,
) -> Option<&'a CampbellCrossing> {
    view.crossings
        .iter()
        .map(|c| {
            (
                c,
                frame
                    .to_px(c.rpm, c.frequency_hz)
                    .distance(DVec2::new(px, py)),
            )
        })
        .filter(|(_, d)| *d <= PICK_PX)
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(c, _)| c)
}

/// The colour of the hollow, cancelled crossings.
const CANCELLED: RGBColor = RGBColor(120, 120, 120);
/// The planet-pass orders' dashed lines and triangles.
const PASS: RGBColor = RGBColor(140, 86, 75);

/// Colour of mesh order `k` (1-based).
pub fn order_color(k: u32) -> RGBColor {
    family_color(k.saturating_sub(1) as usize)
}

/// Draws `view` on `root` with `status` after the caption; returns the
/// frame its clicks map through (rpm across, Hz up).
pub fn draw_campbell<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    view: &CampbellView,
    status: &str,
) -> Res<PlotFrame> {
    root.fill(&WHITE).map_err(err)?;
    let x = (0.0, view.rpm_max.max(1e-9));
    let y = (0.0, view.hz_max.max(1e-9));
    let mut items: KeyItems = (1..=ORDERS)
        .map(|k| {
            (
                KeyIcon::Line(order_color(k), false),
                if k == 1 {
                    "order 1 (mesh frequency)".to_string()
                } else {
                    format!("order {k}")
                },
            )
        })
        .collect();
    if let Some(pp) = &view.planet_pass {
        items.push((
            KeyIcon::Line(PASS, false),
            format!(
                "planet-pass orders 1 to {ORDERS} ({} planets × carrier speed; not excited by the model)",
                pp.planets
            ),
        ));
    }
    items.push((KeyIcon::Line(NATURAL, false), "natural frequency".into()));
    items.push((
        KeyIcon::Dot(BLACK, 4),
        "critical speed the meshes excite".into(),
    ));
    if view.crossings.iter().any(|c| !c.excited) {
        items.push((
            KeyIcon::Ring(CANCELLED, 4),
            "critical speed the planets' phasing cancels".into(),
        ));
    }
    items.push((
        KeyIcon::Line(CURSOR, false),
        format!(
            "selected speed {} rpm (Ω {:.3})",
            crate::speed::grouped_fine(view.selected_rpm),
            view.selected_omega
        ),
    ));
    let plan = plan_key(root, &items, Vec::new());
    let area = chart_area(root, &plan);
    let caption = format!("Campbell diagram: natural frequencies against input speed{status}");
    let mut b = chart_layout(&area, &caption)?;
    b.y_label_area_size(72);
    // The data are rpm; the ticks are the speed axes' unit.
    let ticks = Ticks::over_rpm(&view.speed);
    let x_desc = match view.speed.scale {
        Some(s) if ticks == Ticks::Data => format!("{} speed (rpm)", capital(s.input())),
        Some(_) => view.speed.label(),
        None => "input member's speed (rpm)".into(),
    };
    let mut chart = b
        .build_cartesian_2d(XCoord::new(x, ticks), y.0..y.1)
        .map_err(err)?;
    let plot_w = chart.plotting_area().dim_in_pixel().0;
    let mut mesh = chart.configure_mesh();
    if ticks == Ticks::Data {
        mesh.x_label_formatter(&|v: &f64| grouped(*v));
    }
    mesh.x_labels((plot_w as usize / 80).clamp(3, 10))
        .y_labels(8)
        .light_line_style(GRID.mix(0.5))
        .bold_line_style(GRID)
        .y_label_formatter(&|v: &f64| grouped(*v))
        .x_desc(x_desc.as_str())
        .y_desc("frequency (Hz)")
        .label_style(small())
        .axis_desc_style(small())
        .draw()
        .map_err(err)?;
    chart
        .draw_series(view.modes.iter().map(|m| {
            PathElement::new(
                vec![(x.0, m.frequency_hz), (x.1, m.frequency_hz)],
                ShapeStyle::from(&NATURAL).stroke_width(1),
            )
        }))
        .map_err(err)?;
    for k in 1..=ORDERS {
        // Cut where the line leaves the plot, at its right or its top.
        let slope = f64::from(k) * view.mesh_hz_per_rpm;
        let end = if slope * x.1 <= y.1 {
            (x.1, slope * x.1)
        } else {
            (y.1 / slope, y.1)
        };
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(0.0, 0.0), end],
                ShapeStyle::from(&order_color(k)).stroke_width(2),
            )))
            .map_err(err)?;
    }
    if let Some(pp) = &view.planet_pass {
        for k in 1..=ORDERS {
            let slope = f64::from(k) * pp.hz_per_rpm;
            let end = if slope * x.1 <= y.1 {
                (x.1, slope * x.1)
            } else {
                (y.1 / slope, y.1)
            };
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(0.0, 0.0), end],
                    ShapeStyle::from(&PASS.mix(0.8)).stroke_width(1),
                )))
                .map_err(err)?;
        }
        chart
            .draw_series(
                pp.crossings
                    .iter()
                    .map(|c| TriangleMarker::new((c.rpm, c.frequency_hz), 5, PASS.stroke_width(2))),
            )
            .map_err(err)?;
    }
    if view.selected_rpm >= x.0 && view.selected_rpm <= x.1 {
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(view.selected_rpm, y.0), (view.selected_rpm, y.1)],
                ShapeStyle::from(&CURSOR).stroke_width(2),
            )))
            .map_err(err)?;
    }
    chart
        .draw_series(view.crossings.iter().map(|c| {
            let style = if c.excited {
                order_color(c.order).filled()
            } else {
                CANCELLED.stroke_width(2)
            };
            Circle::new((c.rpm, c.frequency_hz), 5, style)
        }))
        .map_err(err)?;
    // An outline makes the filled markers stand out on their own line.
    chart
        .draw_series(
            view.crossings
                .iter()
                .filter(|c| c.excited)
                .map(|c| Circle::new((c.rpm, c.frequency_hz), 5, BLACK.stroke_width(1))),
        )
        .map_err(err)?;
    let frame = frame_of(&chart, x, y);
    draw_key(root, &items, &plan)?;
    root.present().map_err(err)?;
    Ok(frame)
}

#[cfg(test)]
mod tests {
    use super::*;
    use solver::model::Model;

    #[test]
    fn the_diagram_draws_its_lines_crossings_and_key_inside_the_canvas() {
        let q = crate::link::decode("planets=5&phasing=sequential");
        let model = Model::new(&q.settings.params).unwrap();
        let view = CampbellView::new(&model, 2.0, 0.5).unwrap();
        let mut s = String::new();
        let frame = {
            let root = SVGBackend::with_string(&mut s, (WIDTH, HEIGHT)).into_drawing_area();
            draw_campbell(&root, &view, "").unwrap()
        };
        for words in [
            // The speed axes show Ω by default, the data staying rpm.
            "Ω = ω / ω_ref",
            "frequency (Hz)",
            "order 1 (mesh frequency)",
            "order 4",
            "critical speed the meshes excite",
            "phasing cancels",
            "selected speed",
        ] {
            assert!(s.contains(words), "no {words}");
        }
        // Every crossing maps inside the plotting area.
        for c in &view.crossings {
            let p = frame.to_px(c.rpm, c.frequency_hz);
            assert!(p.x >= frame.top_left.x - 1e-6 && p.x <= frame.bottom_right.x + 1e-6);
            assert!(p.y >= frame.top_left.y - 1e-6 && p.y <= frame.bottom_right.y + 1e-6);
        }
        assert!(frame.bottom_right.y < f64::from(HEIGHT));
        // In rpm, the axis names the input member and its unit; the frame
        // is the same rpm.
        let mut rpm = view.clone();
        rpm.speed.unit = crate::speed::AxisUnit::Rpm;
        let mut s = String::new();
        let again = {
            let root = SVGBackend::with_string(&mut s, (WIDTH, HEIGHT)).into_drawing_area();
            draw_campbell(&root, &rpm, "").unwrap()
        };
        assert!(
            s.contains("Sun s1 speed (rpm)") && !s.contains("ω_ref"),
            "{s}"
        );
        assert_eq!(again, frame);
    }

    #[test]
    fn a_click_near_a_crossing_picks_it() {
        let q = crate::link::decode("");
        let v = CampbellView::new(&Model::new(&q.settings.params).unwrap(), 2.0, 0.5).unwrap();
        let frame = PlotFrame {
            top_left: DVec2::new(80.0, 40.0),
            bottom_right: DVec2::new(740.0, 300.0),
            x_range: (0.0, v.rpm_max),
            y_range: (0.0, v.hz_max),
        };
        let c = &v.crossings[0];
        let p = frame.to_px(c.rpm, c.frequency_hz);
        assert_eq!(pick(&v, &frame, p.x + 3.0, p.y - 2.0), Some(c));
        // At standstill, the top of the axis: no crossing is near.
        assert_eq!(pick(&v, &frame, 80.0, 40.0), None);
    }
}
