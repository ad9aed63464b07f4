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

/// The least gap (pixels) between two peak labels.
const LABEL_GAP_PX: i32 = 6;

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
    // A stem per pixel column, the tallest (8 000 lines over 1 000
    // recorded periods would otherwise be drawn one on another).
    let column = |o: f64| chart.backend_coord(&(o, 0.0)).0;
    let own = decimate::tallest_per_column(&view.lines, column);
    let sum = view
        .sum
        .as_ref()
        .map(|s| decimate::tallest_per_column(&s.lines, column));
    // Labels from the largest peak down, each centred on its line and
    // clear of a larger one's by the two labels' half widths as drawn (a
    // motion that does not repeat has many close lines, and "2.43×" is
    // wider than "2×").
    let font = small();
    let mut by_size: Vec<&crate::protocol::OrderPeak> = view.peaks.iter().collect();
    by_size.sort_by(|a, b| b.amplitude_n.total_cmp(&a.amplitude_n));
    let mut kept: Vec<(i32, i32, &crate::protocol::OrderPeak)> = Vec::new();
    for p in by_size {
        let x = column(p.order);
        let (w, _) = root.estimate_text_size(&p.label, &font).map_err(err)?;
        let half = i32::try_from(w / 2).unwrap_or(i32::MAX / 4);
        if kept
            .iter()
            .all(|(k, kh, _)| (k - x).abs() >= kh + half + LABEL_GAP_PX)
        {
            kept.push((x, half, p));
        }
    }
    chart.draw_series(stems(&own, MESH_COLOR, 5)).map_err(err)?;
    if let Some(sum) = &sum {
        chart.draw_series(stems(sum, SUM_COLOR, 2)).map_err(err)?;
    }
    chart
        .draw_series(kept.iter().map(|(_, _, p)| {
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

    /// Of two peaks closer than a label's width, only the larger is named.
    #[test]
    fn close_peaks_keep_the_larger_label() {
        let mut r = crate::views::test_support::omega_result();
        let peak = |order: f64, label: &str, amplitude_n: f64| OrderPeak {
            order,
            label: label.into(),
            whole: false,
            amplitude_n,
        };
        r.force_orders = Some(ForceByOrder {
            record_periods: 20,
            order: (0..=40).map(|k| f64::from(k) / 20.0).collect(),
            amplitude_n: (0..=40)
                .map(|k| match k {
                    20 => 3000.0,
                    21 => 900.0,
                    _ => 0.0,
                })
                .collect(),
            peaks: vec![peak(1.0, "1×", 3000.0), peak(1.05, "1.05×", 900.0)],
            sum: None,
        });
        let p = crate::link::decode("").settings.params;
        let v = OrdersView::new(&r, &p, 5000.0).unwrap();
        let mut s = String::new();
        {
            let root = SVGBackend::with_string(&mut s, (WIDTH, HEIGHT)).into_drawing_area();
            draw_orders(&root, &v, "").unwrap();
        }
        assert!(
            s.lines().any(|l| l.trim() == "1×") && !s.contains("1.05×"),
            "{s}"
        );
    }
}
