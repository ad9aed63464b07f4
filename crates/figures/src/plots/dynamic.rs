//! The dynamic factor's plot: the model's factor over Omega (a dot per
//! steady state, joined), K_v by ISO 6336-1 method B over the same axis
//! (solid, broken where it jumps at N_S), the standard's main resonance
//! band shaded, with the natural frequencies and the selected Omega as on
//! the other Omega axes; the key under the chart.

use super::*;
use crate::views::dynamic::DynamicView;

/// The model's factor.
pub const MODEL_COLOR: RGBColor = RGBColor(230, 120, 0);
/// The standard's K_v.
pub const ISO_COLOR: RGBColor = RGBColor(31, 119, 180);
/// The planets' load-sharing factor.
pub const SHARING_COLOR: RGBColor = RGBColor(44, 160, 44);

/// Draws `view` on `root` with `status` after the caption, its speed
/// axis as `speed` says (Omega or the input's rpm); returns the frame its
/// clicks map through (Omega across).
pub fn draw_dynamic<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    view: &DynamicView,
    status: &str,
    speed: &crate::speed::SpeedAxis,
) -> Res<PlotFrame> {
    root.fill(&WHITE).map_err(err)?;
    let x = (view.omega_from, view.omega_to.max(view.omega_from + 1e-9));
    let sharing: Vec<(f64, f64)> = view
        .sharing_over_speed
        .iter()
        .filter_map(|s| Some((s.omega, s.worst()?)))
        .collect();
    let values = view
        .nonlinear
        .iter()
        .map(|p| p.1)
        .chain(view.kv.iter().flatten().map(|p| p.1))
        .chain(sharing.iter().map(|p| p.1));
    let y = padded_range(values, &[1.0], 0.5);
    let y = (y.0.min(1.0), y.1);
    let (start, _, end) = view.main_band();
    let band = (start.max(x.0), end.min(x.1));
    let i = &view.inputs;
    let mut items: KeyItems = vec![
        (
            KeyIcon::Dot(MODEL_COLOR, 3),
            "the model's dynamic factor (largest mesh force / static), one dot per steady state"
                .into(),
        ),
        (
            KeyIcon::Line(ISO_COLOR, false),
            format!(
                "dynamic factor Kv (ISO 6336-1, method B): grade {}, face width {} mm",
                i.accuracy_grade, i.face_width_mm
            ),
        ),
    ];
    if let (false, Some(phasing)) = (sharing.is_empty(), view.phasing) {
        items.push((
            KeyIcon::Line(SHARING_COLOR, true),
            format!(
                "load-sharing factor of the {} planets (largest planet force / mean, worst mesh kind; {phasing} phasing)",
                view.planets
            ),
        ));
    }
    if band.0 < band.1 {
        items.push((
            KeyIcon::Shade(ISO_COLOR, 0.12),
            "the standard's main resonance range".into(),
        ));
    }
    items.extend(omega_items(&view.natural, view.selected_omega, speed));
    let plan = plan_key(root, &items, Vec::new());
    let area = chart_area(root, &plan);
    let caption = format!(
        "Dynamic factor of mesh {}: the model beside ISO 6336-1{status}",
        view.mesh_name
    );
    let axes = Axes {
        y_labels: Some(6),
        y_format: Some(|v: &f64| format!("{v:.2}")),
        ..Axes::over_omega(speed, "dynamic factor (−)")
    };
    let mut chart = linear_chart(&area, &caption, (x, y), &axes)?;
    if band.0 < band.1 {
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(band.0, y.0), (band.1, y.1)],
                ISO_COLOR.mix(0.12).filled(),
            )))
            .map_err(err)?;
    }
    omega_decorations(&mut chart, &view.natural, view.selected_omega, y)?;
    for line in &view.kv {
        chart
            .draw_series(LineSeries::new(
                line.iter().copied(),
                ShapeStyle::from(&ISO_COLOR).stroke_width(2),
            ))
            .map_err(err)?;
    }
    chart
        .draw_series(DashedLineSeries::new(
            sharing.iter().copied(),
            6,
            4,
            ShapeStyle::from(&SHARING_COLOR).stroke_width(2),
        ))
        .map_err(err)?;
    chart
        .draw_series(LineSeries::new(
            view.nonlinear.iter().copied(),
            ShapeStyle::from(&MODEL_COLOR.mix(0.6)).stroke_width(1),
        ))
        .map_err(err)?;
    chart
        .draw_series(
            view.nonlinear
                .iter()
                .map(|&p| Circle::new(p, 3, MODEL_COLOR.filled())),
        )
        .map_err(err)?;
    if let Some(f) = view.selected.as_ref().and_then(|s| s.factor) {
        chart
            .draw_series(std::iter::once(Circle::new(
                (view.selected_omega, f.min(y.1)),
                5,
                CURSOR.stroke_width(2),
            )))
            .map_err(err)?;
    }
    let frame = frame_of(&chart, x, y);
    draw_key(root, &items, &plan)?;
    root.present().map_err(err)?;
    Ok(frame)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::views::ViewContext;
    use solver::iso6336::IsoInputs;
    use solver::model::Model;

    #[test]
    fn the_plot_draws_both_factors_and_its_key_inside_the_canvas() {
        let q = crate::link::decode("model=gear-pair");
        let p = &q.settings.params;
        let model = Model::new(p).unwrap();
        let ctx = ViewContext {
            omega_from: 0.1,
            omega_to: 2.0,
            selected_omega: 0.5,
            ..ViewContext::default()
        };
        let view = DynamicView::new(p, &model, &ctx, 0, None, None, &IsoInputs::default()).unwrap();
        let mut s = String::new();
        let frame = {
            let root = SVGBackend::with_string(&mut s, (WIDTH, HEIGHT)).into_drawing_area();
            draw_dynamic(&root, &view, "", &crate::speed::SpeedAxis::default()).unwrap()
        };
        for words in [
            "Dynamic factor of mesh pg",
            "dynamic factor (−)",
            "dynamic factor (largest mesh force / static)",
            "dynamic factor Kv (ISO 6336-1, method B): grade 6, face width 50 mm",
            "main resonance range",
            "selected Ω = 0.500",
        ] {
            assert!(s.contains(words), "no {words}");
        }
        // K_v's curve lies inside the plotting area.
        for &(o, k) in view.kv.iter().flatten() {
            let px = frame.to_px(o, k);
            assert!(px.x >= frame.top_left.x - 1e-6 && px.x <= frame.bottom_right.x + 1e-6);
            assert!(px.y >= frame.top_left.y - 1e-6 && px.y <= frame.bottom_right.y + 1e-6);
        }
        assert!(frame.bottom_right.y < f64::from(HEIGHT));
        // A click on the axis maps back to Omega.
        let at = frame.to_px(1.0, 1.0).x;
        assert!((frame.x_at(at).unwrap() - 1.0).abs() < 1e-9);
    }
}
