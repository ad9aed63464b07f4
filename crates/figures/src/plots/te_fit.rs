//! The TE file's plot: the table's points beside the fitted curve, over
//! mesh periods, the key under the chart.

use super::*;
use crate::te_fit::{kind_words, TeFitView};

/// The plot's size (pixels): small, in the Advanced group.
pub const SIZE: (u32, u32) = (380, 280);
/// The table's points.
pub const POINTS: RGBColor = RGBColor(0, 114, 178);
/// The fitted curve.
pub const CURVE: RGBColor = RGBColor(213, 94, 0);

/// Draws `view` on `root`.
pub fn draw_te_fit<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, view: &TeFitView) -> Res<()> {
    root.fill(&WHITE).map_err(err)?;
    let points = view.drawn_points();
    let curve = view.curve(400);
    let x = (
        view.x_periods.first().copied().unwrap_or(0.0),
        view.x_periods.last().copied().unwrap_or(1.0),
    );
    let x = (x.0, x.1.max(x.0 + 1e-9));
    let y = padded_range(points.iter().chain(&curve).map(|p| p.1), &[], 1e-3);
    let h = view.fit.harmonics_um.len();
    let items: KeyItems = vec![
        (KeyIcon::Ring(POINTS, 3), "the file's points".into()),
        (
            KeyIcon::Line(CURVE, false),
            format!("the fit: {h} harmonic{}", if h == 1 { "" } else { "s" }),
        ),
    ];
    let plan = plan_key(root, &items, Vec::new());
    let area = chart_area(root, &plan);
    let caption = format!("TE from a file, {}", kind_words(&view.kind));
    let axes = Axes::new("mesh periods", "TE (µm)");
    let mut chart = linear_chart(&area, &caption, (x, y), &axes)?;
    // The curve first, the points over it as rings: where the fit is
    // exact each ring sits on the line.
    chart
        .draw_series(LineSeries::new(
            curve,
            ShapeStyle::from(&CURVE).stroke_width(2),
        ))
        .map_err(err)?;
    chart
        .draw_series(
            points
                .iter()
                .map(|&p| Circle::new(p, 3, POINTS.stroke_width(1))),
        )
        .map_err(err)?;
    draw_key(root, &items, &plan)?;
    root.present().map_err(err)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use solver::te_file::{fit, parse};

    #[test]
    fn the_plot_draws_the_points_and_the_curve_as_svg() {
        let text = "fraction,te_um\n0,1\n0.25,3\n0.5,1\n0.75,-1\n";
        let table = parse(text).unwrap();
        let v = TeFitView::new("pair", "a.csv", &table, 1.0, fit(&table, 1.0, 1).unwrap());
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, SIZE).into_drawing_area();
            draw_te_fit(&root, &v).unwrap();
        }
        // Four points, their circles; the key's words.
        assert!(svg.matches("<circle").count() >= 4, "{svg}");
        assert!(svg.contains("the file&apos;s points") || svg.contains("the file's points"));
        assert!(svg.contains("TE (µm)"));
    }
}
