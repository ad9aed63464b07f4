//! The Campbell diagram's plot: natural frequencies as horizontal lines,
//! the mesh orders as lines through the origin, the critical speeds where
//! they cross (filled where the meshes excite them, hollow and grey where
//! the planets' phasing cancels them), and the selected speed as a vertical
//! line. Its frequency axis is the view model's, so every order line ends
//! inside the plot; the key is under the chart.

use super::*;
use crate::views::campbell::{grouped, CampbellView, ORDERS};

/// The colour of the hollow, cancelled crossings.
const CANCELLED: RGBColor = RGBColor(120, 120, 120);

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
            grouped(view.selected_rpm),
            view.selected_omega
        ),
    ));
    let plan = plan_key(root, &items, Vec::new());
    let area = chart_area(root, &plan);
    let caption = format!("Campbell diagram: natural frequencies against input speed{status}");
    let axes = Axes {
        y_format: Some(|v: &f64| grouped(*v)),
        ..Axes::new("input member's speed (rpm)", "frequency (Hz)")
    };
    let mut chart = linear_chart(&area, &caption, (x, y), &axes)?;
    chart
        .draw_series(view.modes.iter().map(|m| {
            PathElement::new(
                vec![(x.0, m.frequency_hz), (x.1, m.frequency_hz)],
                ShapeStyle::from(&NATURAL).stroke_width(1),
            )
        }))
        .map_err(err)?;
    for k in 1..=ORDERS {
        let top = f64::from(k) * view.mesh_hz_per_rpm * x.1;
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(0.0, 0.0), (x.1, top.min(y.1))],
                ShapeStyle::from(&order_color(k)).stroke_width(2),
            )))
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
            "input member",
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
    }
}
