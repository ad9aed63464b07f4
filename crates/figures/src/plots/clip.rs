//! A frequency response's y range that a lightly damped first mode cannot
//! flatten, and the first mode's peak located on every curve: with no
//! backlash the first mode (damping ratio 0.0024 in Table 1) puts a spike
//! of thousands of µm on the response, and an axis fitted to it leaves the
//! rest of the curve a flat line. When the spike reaches more than half a
//! plot height beyond everything else, the axis fits the rest and every
//! curve's clipped peak is marked with its value in the curve's colour, so
//! no data are hidden without a word. A family's curves share one Ω for
//! that peak (a linear response scales with the TE), so one needle would
//! hide the others: each curve's peak is marked with a dot of its colour.

use super::*;

/// Half the width in Omega of the first mode's neighbourhood.
const WINDOW: f64 = 0.03;

/// One curve's extreme near the first mode.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Peak {
    /// Where (Omega).
    pub omega: f64,
    /// The value (µm): a maximum of x, or a minimum when `up` is false.
    pub value: f64,
    /// A maximum (true) or a minimum.
    pub up: bool,
    /// The curve's colour.
    pub color: RGBColor,
    /// The curve's name in a family or comparison ("TE 5 µm"), if several.
    pub label: Option<String>,
}

/// A y range, the peaks it clips and each curve's first-mode peak.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Clipped {
    /// The axis range (µm).
    pub range: (f64, f64),
    /// The clipped extremes, above or below the range.
    pub peaks: Vec<Peak>,
    /// Each family member's first-mode maximum inside the range, to be
    /// marked with a dot (empty without a family).
    pub inside: Vec<Peak>,
}

/// The first mode: the lowest finite natural frequency (Omega).
fn first_mode(natural: &[f64]) -> Option<f64> {
    natural
        .iter()
        .copied()
        .filter(|w| w.is_finite())
        .min_by(f64::total_cmp)
}

/// One curve's points `(omega, max, min)`, its colour and its name.
pub(crate) struct Curve<'a> {
    pub points: &'a [(f64, f64, f64)],
    /// The colours of its max and min lines.
    pub colors: (RGBColor, RGBColor),
    pub label: Option<String>,
}

/// The y range of `curves` with the contact levels `extra`, clipping the
/// first mode's spike (at the lowest of `natural`) when it overshoots the
/// rest of the data by more than half their span; every curve's spike
/// beyond the range is listed.
pub(crate) fn clipped_range(curves: &[Curve<'_>], natural: &[f64], extra: &[f64]) -> Clipped {
    let all = || {
        curves
            .iter()
            .flat_map(|c| c.points.iter())
            .flat_map(|&(_, hi, lo)| [hi, lo])
    };
    let full = Clipped {
        range: padded_range(all(), extra, 20.0),
        peaks: Vec::new(),
        inside: Vec::new(),
    };
    let Some(first) = first_mode(natural) else {
        return full;
    };
    let near = |w: f64| (w - first).abs() <= WINDOW;
    let rest: Vec<f64> = curves
        .iter()
        .flat_map(|c| c.points.iter())
        .filter(|p| !near(p.0))
        .flat_map(|&(_, hi, lo)| [hi, lo])
        .filter(|v| v.is_finite())
        .collect();
    if rest.is_empty() {
        return full;
    }
    // Each curve's top and bottom near the first mode.
    let extremes: Vec<(Peak, Peak)> = curves
        .iter()
        .filter_map(|c| {
            let near_pts = || c.points.iter().filter(|p| near(p.0));
            let top = near_pts()
                .filter(|p| p.1.is_finite())
                .max_by(|a, b| a.1.total_cmp(&b.1))?;
            let bottom = near_pts()
                .filter(|p| p.2.is_finite())
                .min_by(|a, b| a.2.total_cmp(&b.2))?;
            let peak = |omega, value, up: bool| Peak {
                omega,
                value,
                up,
                color: if up { c.colors.0 } else { c.colors.1 },
                label: c.label.clone(),
            };
            Some((peak(top.0, top.1, true), peak(bottom.0, bottom.2, false)))
        })
        .collect();
    let (lo, hi) = padded_range(rest.iter().copied(), extra, 20.0);
    let span = hi - lo;
    let clips = extremes
        .iter()
        .any(|(t, b)| t.value > hi + 0.5 * span || b.value < lo - 0.5 * span);
    if !clips {
        // Nothing clipped: each family member's peak gets a dot, so that
        // a taller curve's needle at the same Omega hides none.
        let family = curves.len() > 1 && curves.iter().all(|c| c.label.is_some());
        let inside = extremes
            .into_iter()
            .map(|(t, _)| t)
            .filter(|_| family)
            .collect();
        return Clipped { inside, ..full };
    }
    // Headroom for the marks' labels.
    let pad = 0.12 * span;
    let range = (lo - pad, hi + pad);
    let mut peaks = Vec::new();
    let mut inside = Vec::new();
    for (t, b) in extremes {
        if t.value > range.1 {
            peaks.push(t);
        } else if curves.len() > 1 {
            inside.push(t);
        }
        if b.value < range.0 {
            peaks.push(b);
        }
    }
    Clipped {
        range,
        peaks,
        inside,
    }
}

/// Each curve's first-mode peak as `(name, Omega, x µm)`: its largest x
/// within the first mode's neighbourhood, from [`clipped_range`]'s own
/// search, for the page's status (a test reads where every member's
/// resonance lies).
pub(crate) fn first_mode_peaks(curves: &[Curve<'_>], natural: &[f64]) -> Vec<(String, f64, f64)> {
    let Some(first) = first_mode(natural) else {
        return Vec::new();
    };
    curves
        .iter()
        .filter_map(|c| {
            let top = c
                .points
                .iter()
                .filter(|p| (p.0 - first).abs() <= WINDOW && p.1.is_finite())
                .max_by(|a, b| a.1.total_cmp(&b.1))?;
            Some((c.label.clone().unwrap_or_default(), top.0, top.1))
        })
        .collect()
}

/// Marks each clipped peak at the edge of the axis: a triangle pointing
/// out in its curve's colour, and one line of words on a white ground:
/// "peak 2076 µm, off the axis", or, with several curves, three lines
/// "peaks off the axis: / 598 µm (TE 5 µm) to / 2672 µm (TE 30 µm)".
/// Each family member's
/// peak inside the axis gets a dot of its colour.
pub(crate) fn mark_clipped<'a, DB: DrawingBackend + 'a>(
    chart: &mut Chart<'a, DB>,
    clipped: &Clipped,
) -> Res<()> {
    let (lo, hi) = clipped.range;
    for p in &clipped.inside {
        chart
            .draw_series(std::iter::once(Circle::new(
                (p.omega, p.value),
                3,
                p.color.filled(),
            )))
            .map_err(err)?;
    }
    for up in [true, false] {
        let mut these: Vec<&Peak> = clipped.peaks.iter().filter(|p| p.up == up).collect();
        if these.is_empty() {
            continue;
        }
        these.sort_by(|a, b| a.value.abs().total_cmp(&b.value.abs()));
        let edge = if up { hi } else { lo };
        let dy = if up { 1 } else { -1 };
        let mut at = (0, 0);
        // A triangle per curve at its own Omega, pointing out, in its
        // colour (the largest drawn last, on top).
        for p in &these {
            // In the plotting area's own pixels (its top left is (0, 0)).
            let abs = chart.backend_coord(&(p.omega, edge));
            let (xr, yr) = chart.plotting_area().get_pixel_range();
            at = (abs.0 - xr.start, abs.1 - yr.start);
            let base = at.1 + dy * 10;
            chart
                .plotting_area()
                .strip_coord_spec()
                .draw(&Polygon::new(
                    vec![(at.0, at.1 + dy), (at.0 - 6, base), (at.0 + 6, base)],
                    ShapeStyle::from(&p.color).filled(),
                ))
                .map_err(err)?;
        }
        let word = if up { "peak" } else { "low" };
        let value = |p: &Peak| match &p.label {
            Some(name) => format!("{:.0} µm ({name})", p.value),
            None => format!("{:.0} µm", p.value),
        };
        let lines: Vec<String> = match (these.first(), these.last()) {
            (Some(a), Some(b)) if these.len() > 1 => vec![
                format!("{word}s off the axis:"),
                format!("{} to", value(a)),
                value(b),
            ],
            (Some(a), _) => vec![format!("{word} {}, off the axis", value(a))],
            _ => continue,
        };
        // On a white ground, so that no curve crosses the words; right of
        // the needle, or as far right as the words fit.
        let chars = lines.iter().map(|l| l.chars().count()).max().unwrap_or(0);
        let (w, h) = ((chars as f64 * 7.0) as i32, 14 * lines.len() as i32 + 2);
        let top = if up { at.1 + 12 } else { at.1 - 12 - h };
        let width = chart.plotting_area().dim_in_pixel().0 as i32;
        let left = (at.0 + 9).min(width - w - 2).max(2);
        let area = chart.plotting_area().strip_coord_spec();
        area.draw(&Rectangle::new(
            [(left - 2, top), (left + w, top + h)],
            WHITE.mix(0.85).filled(),
        ))
        .map_err(err)?;
        for (k, line) in lines.into_iter().enumerate() {
            area.draw(&Text::new(
                line,
                (left, top + 2 + 14 * k as i32),
                ("sans-serif", 12).into_font().color(&BLACK),
            ))
            .map_err(err)?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curve<'a>(points: &'a [(f64, f64, f64)], label: Option<&str>) -> Curve<'a> {
        Curve {
            points,
            colors: (BLACK, BLACK),
            label: label.map(str::to_string),
        }
    }

    /// A background of ±100 µm and a first-mode spike of `spike` µm at
    /// Omega 0.23.
    fn spiked(spike: f64) -> Vec<(f64, f64, f64)> {
        (0..=200)
            .map(|k| {
                let w = 0.1 + 0.01 * f64::from(k);
                if (w - 0.23).abs() < 1e-9 {
                    (w, spike, -spike + 10.0)
                } else {
                    (w, 100.0, -100.0)
                }
            })
            .collect()
    }

    /// The axis fits the background, the spike is marked.
    #[test]
    fn a_first_mode_spike_is_clipped_and_named() {
        let pts = spiked(2000.0);
        let c = clipped_range(&[curve(&pts, None)], &[0.232, 0.575], &[]);
        assert!(c.range.1 < 200.0 && c.range.1 > 100.0, "{:?}", c.range);
        assert!(c.range.0 > -200.0 && c.range.0 < -100.0, "{:?}", c.range);
        assert_eq!(c.peaks.len(), 2);
        assert!((c.peaks[0].omega - 0.23).abs() < 1e-9);
        assert_eq!(c.peaks[0].value, 2000.0);
        assert_eq!(c.peaks[1].value, -1990.0);
    }

    /// A family of a linear response: the spike scales with the member's
    /// TE, so every member's peak lies beyond the axis fitted to the rest
    /// and each is listed with its name, not only the tallest.
    #[test]
    fn every_members_clipped_peak_is_listed() {
        let a = spiked(1000.0);
        let b = spiked(2000.0);
        let c = spiked(3000.0);
        let curves = [
            curve(&a, Some("TE 5 µm")),
            curve(&b, Some("TE 10 µm")),
            curve(&c, Some("TE 15 µm")),
        ];
        let clip = clipped_range(&curves, &[0.232], &[]);
        let tops: Vec<(f64, Option<&str>)> = clip
            .peaks
            .iter()
            .filter(|p| p.up)
            .map(|p| (p.value, p.label.as_deref()))
            .collect();
        assert_eq!(
            tops,
            vec![
                (1000.0, Some("TE 5 µm")),
                (2000.0, Some("TE 10 µm")),
                (3000.0, Some("TE 15 µm"))
            ]
        );
        // Not clipped (a spike below half a plot height beyond the rest):
        // each member's top above the rest gets a dot.
        let low = spiked(130.0);
        let high = spiked(140.0);
        let clip = clipped_range(
            &[curve(&low, Some("TE 5 µm")), curve(&high, Some("TE 10 µm"))],
            &[0.232],
            &[],
        );
        assert!(clip.peaks.is_empty());
        assert_eq!(clip.inside.len(), 2);
        assert!(clip.range.1 >= 140.0);
    }

    /// No spike, or no natural frequency: the whole data, nothing marked.
    #[test]
    fn without_a_spike_the_axis_fits_every_point() {
        let pts = vec![
            (0.2, 150.0, -150.0),
            (0.23, 180.0, -170.0),
            (0.5, 120.0, -120.0),
        ];
        let c = clipped_range(&[curve(&pts, None)], &[0.232], &[]);
        assert!(c.peaks.is_empty() && c.inside.is_empty());
        assert!(c.range.1 >= 180.0 && c.range.0 <= -170.0);
        assert!(clipped_range(&[curve(&pts, None)], &[], &[])
            .peaks
            .is_empty());
    }
}
