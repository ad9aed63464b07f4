//! A frequency response's y range that a lightly damped first mode cannot
//! flatten: with no backlash the first mode (damping ratio 0.0024 in
//! Table 1) puts a spike of thousands of µm on the response, and an axis
//! fitted to it leaves the rest of the curve a flat line. When the spike
//! reaches more than half a plot height beyond everything else, the axis
//! fits the rest and the clipped peak is marked with its value, so no data
//! are hidden without a word.

use super::*;

/// Half the width in Omega of the first mode's neighbourhood.
const WINDOW: f64 = 0.03;

/// A y range and the peaks it clips.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Clipped {
    /// The axis range (µm).
    pub range: (f64, f64),
    /// The clipped extremes: Omega and value (µm), above or below the range.
    pub peaks: Vec<(f64, f64)>,
}

/// The y range of points `(omega, max, min)` with the contact levels
/// `extra`, clipping the first mode's spike (at the lowest of `natural`)
/// when it overshoots the rest of the data by more than half their span.
pub(crate) fn clipped_range(points: &[(f64, f64, f64)], natural: &[f64], extra: &[f64]) -> Clipped {
    let all = || points.iter().flat_map(|&(_, hi, lo)| [hi, lo]);
    let full = Clipped {
        range: padded_range(all(), extra, 20.0),
        peaks: Vec::new(),
    };
    let Some(first) = natural
        .iter()
        .copied()
        .filter(|w| w.is_finite())
        .min_by(f64::total_cmp)
    else {
        return full;
    };
    let near = |w: f64| (w - first).abs() <= WINDOW;
    let rest: Vec<f64> = points
        .iter()
        .filter(|p| !near(p.0))
        .flat_map(|&(_, hi, lo)| [hi, lo])
        .filter(|v| v.is_finite())
        .collect();
    if rest.is_empty() {
        return full;
    }
    let (lo, hi) = padded_range(rest.iter().copied(), extra, 20.0);
    let span = hi - lo;
    let top = points
        .iter()
        .filter(|p| near(p.0) && p.1.is_finite())
        .max_by(|a, b| a.1.total_cmp(&b.1));
    let bottom = points
        .iter()
        .filter(|p| near(p.0) && p.2.is_finite())
        .min_by(|a, b| a.2.total_cmp(&b.2));
    let mut peaks = Vec::new();
    if let Some(&(w, v, _)) = top.filter(|p| p.1 > hi + 0.5 * span) {
        peaks.push((w, v));
    }
    if let Some(&(w, _, v)) = bottom.filter(|p| p.2 < lo - 0.5 * span) {
        peaks.push((w, v));
    }
    if peaks.is_empty() {
        return full;
    }
    // Headroom for the marks' labels.
    let pad = 0.12 * span;
    Clipped {
        range: (lo - pad, hi + pad),
        peaks,
    }
}

/// Marks each clipped peak at the edge of the axis: a triangle pointing
/// out and its value, "peak 2076 µm (off the axis)".
pub(crate) fn mark_clipped<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    clipped: &Clipped,
) -> Res<()> {
    let (lo, hi) = clipped.range;
    for &(w, v) in &clipped.peaks {
        let up = v > hi;
        let edge = if up { hi } else { lo };
        // In the plotting area's own pixels (its top left is (0, 0)).
        let abs = chart.backend_coord(&(w, edge));
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let at = (abs.0 - xr.start, abs.1 - yr.start);
        let dy = if up { 1 } else { -1 };
        let tip = (at.0, at.1 + dy);
        let base = at.1 + dy * 10;
        chart
            .plotting_area()
            .strip_coord_spec()
            .draw(&Polygon::new(
                vec![tip, (at.0 - 6, base), (at.0 + 6, base)],
                ShapeStyle::from(&BLACK).filled(),
            ))
            .map_err(err)?;
        let label = format!(
            "{} {:.0} µm, off the axis",
            if up { "peak" } else { "low" },
            v
        );
        let text_y = if up { base + 2 } else { base - 14 };
        chart
            .plotting_area()
            .strip_coord_spec()
            .draw(&Text::new(
                label,
                (at.0 + 9, text_y),
                ("sans-serif", 12).into_font().color(&BLACK),
            ))
            .map_err(err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A background of ±100 µm and a first-mode spike of 2000 µm at
    /// Omega 0.23: the axis fits the background, the spike is marked.
    #[test]
    fn a_first_mode_spike_is_clipped_and_named() {
        let pts: Vec<(f64, f64, f64)> = (0..=200)
            .map(|k| {
                let w = 0.1 + 0.01 * f64::from(k);
                if (w - 0.23).abs() < 1e-9 {
                    (w, 2000.0, -1990.0)
                } else {
                    (w, 100.0, -100.0)
                }
            })
            .collect();
        let c = clipped_range(&pts, &[0.232, 0.575], &[]);
        assert!(c.range.1 < 200.0 && c.range.1 > 100.0, "{:?}", c.range);
        assert!(c.range.0 > -200.0 && c.range.0 < -100.0, "{:?}", c.range);
        assert_eq!(c.peaks.len(), 2);
        assert!((c.peaks[0].0 - 0.23).abs() < 1e-9);
        assert_eq!(c.peaks[0].1, 2000.0);
        assert_eq!(c.peaks[1].1, -1990.0);
    }

    /// No spike, or no natural frequency: the whole data, nothing marked.
    #[test]
    fn without_a_spike_the_axis_fits_every_point() {
        let pts = vec![
            (0.2, 150.0, -150.0),
            (0.23, 180.0, -170.0),
            (0.5, 120.0, -120.0),
        ];
        let c = clipped_range(&pts, &[0.232], &[]);
        assert!(c.peaks.is_empty());
        assert!(c.range.1 >= 180.0 && c.range.0 <= -170.0);
        assert!(clipped_range(&pts, &[], &[]).peaks.is_empty());
    }
}
