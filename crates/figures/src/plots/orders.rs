//! The mesh force by order's plot: the plotted mesh's force amplitude (N,
//! a linear axis) at each order of the mesh frequency as a stem, the
//! planets' sum divided by their number as a narrower stem over it, and
//! the mesh's labelled peaks ("1×", "1/2×") over their stems; the mean
//! force is said in the key, not drawn.

use super::*;
use crate::views::orders::OrdersView;

/// The plotted mesh's stems.
pub const MESH_COLOR: RGBColor = RGBColor(31, 119, 180);
/// The planets' sum per planet.
pub const SUM_COLOR: RGBColor = RGBColor(230, 120, 0);

/// Draws `view` on `root` with `status` after the caption.
pub fn draw_orders<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    view: &OrdersView,
    status: &str,
) -> Res<()> {
    root.fill(&WHITE).map_err(err)?;
    let top = view.top_n().max(1e-9) * 1.18;
    let omax = view.lines.last().map_or(1.0, |l| l.0).max(1.0);
    let mut items: KeyItems = vec![(
        KeyIcon::Line(MESH_COLOR, false),
        format!(
            "mesh {} (mean force {} N, not drawn)",
            view.mesh_name,
            crate::speed::grouped(view.mean_n)
        ),
    )];
    if let (Some(s), Some(phasing)) = (&view.sum, view.phasing) {
        items.push((
            KeyIcon::Line(SUM_COLOR, false),
            format!(
                "sum over the {} planets' meshes of this kind ÷ {} ({phasing} phasing)",
                s.planets, s.planets
            ),
        ));
    }
    let plan = plan_key(root, &items, Vec::new());
    let area = chart_area(root, &plan);
    let caption = format!(
        "Mesh force by order, mesh {} at Ω {:.3} ({} rpm){status}",
        view.mesh_name,
        view.omega,
        crate::speed::grouped(view.rpm)
    );
    // Linear in N, the ticks grouped like the other force figures
    // ("3 500"), the label area as wide as they need.
    let axes = Axes {
        y_format: Some(|v: &f64| crate::speed::grouped(*v)),
        ..Axes::new(
            "order of the mesh frequency (1× = mesh frequency)",
            "force amplitude (N)",
        )
    };
    let mut chart = linear_chart(&area, &caption, ((0.0, omax * 1.02), (0.0, top)), &axes)?;
    let stems = |lines: &[(f64, f64)], color: RGBColor, width: u32| {
        let style = ShapeStyle::from(&color).stroke_width(width);
        lines
            .iter()
            .filter(|l| l.1 > 0.0)
            .map(move |&(o, a)| PathElement::new(vec![(o, 0.0), (o, a)], style))
            .collect::<Vec<_>>()
    };
    chart
        .draw_series(stems(&view.lines, MESH_COLOR, 5))
        .map_err(err)?;
    if let Some(s) = &view.sum {
        chart
            .draw_series(stems(&s.lines, SUM_COLOR, 2))
            .map_err(err)?;
    }
    let font = small();
    chart
        .draw_series(view.peaks.iter().map(|p| {
            Text::new(
                p.label.clone(),
                (p.order, p.amplitude_n + top * 0.02),
                font.pos(Pos::new(HPos::Center, VPos::Bottom)),
            )
        }))
        .map_err(err)?;
    draw_key(root, &items, &plan)?;
    root.present().map_err(err)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::{ForceByOrder, OrderPeak};

    /// The plot says its axes, its key and its peaks' labels.
    #[test]
    fn the_plot_labels_its_peaks_and_says_its_axes() {
        let mut r = crate::views::test_support::omega_result();
        r.force_orders = Some(ForceByOrder {
            record_periods: 2,
            order: vec![0.0, 0.5, 1.0, 1.5, 2.0],
            amplitude_n: vec![9000.0, 400.0, 3000.0, 0.0, 1000.0],
            peaks: vec![
                OrderPeak {
                    order: 0.5,
                    label: "1/2×".into(),
                    whole: false,
                    amplitude_n: 400.0,
                },
                OrderPeak {
                    order: 1.0,
                    label: "1×".into(),
                    whole: true,
                    amplitude_n: 3000.0,
                },
                OrderPeak {
                    order: 2.0,
                    label: "2×".into(),
                    whole: true,
                    amplitude_n: 1000.0,
                },
            ],
            sum: None,
        });
        let p = crate::link::decode("").settings.params;
        let v = OrdersView::new(&r, &p, 5000.0).unwrap();
        let mut s = String::new();
        {
            let root = SVGBackend::with_string(&mut s, (WIDTH, HEIGHT)).into_drawing_area();
            draw_orders(&root, &v, "").unwrap();
        }
        for words in [
            "1/2×",
            "1×",
            "2×",
            "force amplitude (N)",
            "order of the mesh frequency",
            "not drawn",
        ] {
            assert!(s.contains(words), "no {words}");
        }
    }
}
