//! The canvases' text alternatives (their `aria-label`, with `role="img"`):
//! one sentence per view built from the data it draws, so a screen reader
//! hears what the plot shows ("Frequency response of s1a1: peak 140 µm at
//! Ω 0.23; single-sided impact from Ω 0.45 to 2"), and the text changes
//! whenever the data does.

use super::bif::BifView;
use super::fr::FrView;
use super::map::MapStore;
use super::multiples::Panel;
use super::unstable::{
    short, speed_at, speed_span, speed_values, strip_from_overlay, unstable_ranges,
    unstable_sentence,
};
use crate::protocol::{OmegaResult, Regime};
use crate::speed::SpeedAxis;

/// Runs of one regime along Omega as "single-sided impact from Ω 0.45 to
/// 2", joined by "; " (runs shorter than 2 % of the range are left out).
fn regime_runs(mut runs: Vec<(Regime, f64, f64)>, span: f64, speed: &SpeedAxis) -> String {
    runs.sort_by(|a, b| a.1.total_cmp(&b.1));
    let mut merged: Vec<(Regime, f64, f64)> = Vec::new();
    for (r, a, b) in runs {
        match merged.last_mut() {
            Some(last) if last.0 == r && a <= last.2 + 1e-9 => last.2 = last.2.max(b),
            _ => merged.push((r, a, b)),
        }
    }
    merged
        .into_iter()
        .filter(|(_, a, b)| b - a >= 0.02 * span)
        .map(|(r, a, b)| format!("{} {}", r.label(), speed_span(speed, a, b, true)))
        .collect::<Vec<_>>()
        .join("; ")
}

/// The frequency response's mesh panels: each panel's mesh in words and
/// its highest peak, naming the curve (the family's value) it is on.
pub fn fr_panels_label(panels: &[Panel<FrView>]) -> String {
    let parts: Vec<String> = panels
        .iter()
        .map(|p| match &p.data {
            Err(e) => format!("{}: {e}", p.title),
            Ok(v) => {
                let peak = v
                    .branches
                    .iter()
                    .filter(|b| !b.faded)
                    .flat_map(|b| b.points.iter().map(move |q| (b, q)))
                    .max_by(|a, b| a.1.max_um.total_cmp(&b.1.max_um));
                match peak {
                    Some((b, q)) => format!(
                        "{}: highest peak {:.0} µm at {} ({})",
                        p.title,
                        q.max_um,
                        speed_at(&v.speed, q.omega),
                        b.label
                    ),
                    None => format!("{}: computing", p.title),
                }
            }
        })
        .collect();
    format!(
        "Frequency response of {} meshes side by side. {}.",
        panels.len(),
        parts.join("; ")
    )
}

/// The frequency response: the peak of the current branch, the regimes
/// along Omega (stable stretches, and the dots where none is stable), and
/// the unstable ranges.
pub fn fr_label(v: &FrView) -> String {
    let Some(br) = v.branches.iter().rfind(|b| !b.faded && !b.pinned) else {
        return format!("Frequency response of {}: computing.", v.mesh_label);
    };
    let Some(peak) = br
        .points
        .iter()
        .chain(v.overlay.iter())
        .max_by(|a, b| a.max_um.total_cmp(&b.max_um))
    else {
        return format!("Frequency response of {}: computing.", v.mesh_label);
    };
    let mut runs: Vec<(Regime, f64, f64)> = br
        .points
        .windows(2)
        .filter(|w| w[0].stable != Some(false) && w[1].stable != Some(false))
        .filter_map(|w| {
            let (a, b) = (w[0].omega.min(w[1].omega), w[0].omega.max(w[1].omega));
            w[1].regime.map(|r| (r, a, b))
        })
        .collect();
    runs.extend(strip_from_overlay(&unstable_ranges(&br.points), &v.overlay));
    let regimes = regime_runs(runs, v.omega_to - v.omega_from, &v.speed);
    let mut s = format!(
        "Frequency response of {}: peak {:.0} µm at {}",
        v.mesh_label,
        peak.max_um,
        speed_at(&v.speed, peak.omega)
    );
    if !regimes.is_empty() {
        s.push_str("; ");
        s.push_str(&regimes);
    }
    s.push('.');
    if let Some(u) = unstable_sentence(v) {
        s.push(' ');
        s.push_str(&u);
    }
    s
}

/// The bifurcation diagram: how many Omegas, the spread of the Poincaré
/// samples, and where the motion is not period 1 (many distinct samples).
pub fn bif_label(v: &BifView) -> String {
    if v.points.is_empty() {
        return format!("Bifurcation diagram of {}: computing.", v.mesh_label);
    }
    let lo = v
        .points
        .iter()
        .map(|p| p.x_um)
        .fold(f64::INFINITY, f64::min);
    let hi = v
        .points
        .iter()
        .map(|p| p.x_um)
        .fold(f64::NEG_INFINITY, f64::max);
    let mut omegas: Vec<f64> = v.points.iter().map(|p| p.omega).collect();
    omegas.sort_by(f64::total_cmp);
    omegas.dedup();
    let regimes = {
        let mut by: Vec<(Regime, f64, f64)> = Vec::new();
        let mut pts: Vec<_> = v.points.iter().filter(|p| p.up).collect();
        pts.sort_by(|a, b| a.omega.total_cmp(&b.omega));
        // The grid's spacing: each point stands for the Ω up to half way to
        // its neighbours, so neighbours of one regime join into one run.
        let step = (v.omega_to - v.omega_from) / (omegas.len().max(2) - 1) as f64;
        for p in pts {
            by.push((p.regime, p.omega - 0.5 * step, p.omega + 0.5 * step));
        }
        regime_runs(by, v.omega_to - v.omega_from, &v.speed)
    };
    let mut s = format!(
        "Bifurcation diagram of {}: Poincaré samples at {} {} {}, x from {:.0} to {:.0} µm",
        v.mesh_label,
        omegas.len(),
        speed_values(&v.speed),
        speed_span(&v.speed, v.omega_from, v.omega_to, false),
        lo,
        hi
    );
    if !regimes.is_empty() {
        s.push_str("; upward sweep: ");
        s.push_str(&regimes);
    }
    if !v.branches.is_empty() {
        let stable = v.branches.iter().filter(|l| l.stable).count();
        s.push_str(&format!(
            "; branches of periodic motion found by shooting: {stable} stable and {} unstable stretches",
            v.branches.len() - stable
        ));
        let marks: Vec<String> = v
            .branch_markers
            .iter()
            .take(6)
            .map(|m| format!("{} at {}", m.kind.label(), speed_at(&v.speed, m.omega)))
            .collect();
        if !marks.is_empty() {
            s.push_str(&format!(" ({})", marks.join(", ")));
        }
    }
    let motions = motion_runs(&v.motions, &v.speed);
    if !motions.is_empty() {
        s.push_str("; motion on the upward sweep: ");
        s.push_str(&motions);
    }
    s.push_str(&format!(" ({} of {} points computed).", v.done, v.total));
    s
}

/// Runs of one classification along the upward sweep, in the words of
/// [`crate::story::motion_tag`]: "period 1 (exact) from Ω 0.1 to 0.9; not
/// periodic at Ω 1".
fn motion_runs(motions: &[(f64, bool, crate::protocol::Motion)], speed: &SpeedAxis) -> String {
    let mut up: Vec<(f64, String)> = motions
        .iter()
        .filter(|m| m.1)
        .map(|&(o, _, m)| (o, crate::story::motion_tag(m)))
        .collect();
    up.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut runs: Vec<(String, f64, f64)> = Vec::new();
    let n = up.len();
    let mut counts: Vec<(String, usize)> = Vec::new();
    for (o, tag) in up {
        match counts.iter_mut().find(|c| c.0 == tag) {
            Some(c) => c.1 += 1,
            None => counts.push((tag.clone(), 1)),
        }
        match runs.last_mut() {
            Some(last) if last.0 == tag => last.2 = o,
            _ => runs.push((tag, o, o)),
        }
    }
    // Many short runs read better as counts.
    if runs.len() > 6 {
        counts.sort_by_key(|c| std::cmp::Reverse(c.1));
        return counts
            .into_iter()
            .map(|(tag, k)| format!("{tag} at {k} of {n} {}", speed_values(speed)))
            .collect::<Vec<_>>()
            .join(", ");
    }
    runs.into_iter()
        .map(|(tag, a, b)| {
            if a == b {
                format!("{tag} at {}", speed_at(speed, a))
            } else {
                format!("{tag} {}", speed_span(speed, a, b, true))
            }
        })
        .collect::<Vec<_>>()
        .join("; ")
}

/// The impact-regime map: its axes, how many cells of each regime, and
/// how many are not period 1.
pub fn map_label(map: &MapStore, speed: &SpeedAxis) -> String {
    let Some(g) = &map.grid else {
        return "Impact-regime map: waiting for the workers.".into();
    };
    let (by, not_p1, failed) = map.counts();
    let axis = if g.key == "te_um" {
        "TE amplitude"
    } else {
        "backlash"
    };
    let parts = crate::views::map::regime_counts(&by);
    let mut s = format!(
        "Impact-regime map over {} and {axis} {} to {} µm, {} of {} cells",
        match speed.rpm_scale() {
            Some(_) => speed_span(speed, g.omega_from, g.omega_to, false)
                .trim_start_matches("from ")
                .to_string(),
            None => format!("Ω {} to {}", short(g.omega_from), short(g.omega_to)),
        },
        short(g.value_from),
        short(g.value_to),
        map.done,
        g.omega_points * g.value_points
    );
    if !parts.is_empty() {
        s.push_str(": ");
        s.push_str(&parts.join(", "));
    }
    if not_p1 > 0 {
        s.push_str(&format!("; {not_p1} not period 1"));
    }
    if failed > 0 {
        s.push_str(&format!("; {failed} failed"));
    }
    s.push('.');
    s
}

/// The Lyapunov curve: its largest exponent and where the motion is
/// chaotic (or, on a linear model, grows: a parametric instability).
pub fn lyap_label(curve: &[(f64, f64)], linear: bool, speed: &SpeedAxis) -> String {
    use super::lyap::{lyap_kind, LyapKind};
    let Some(&(om, top)) = curve.iter().max_by(|a, b| a.1.total_cmp(&b.1)) else {
        return "Largest Lyapunov exponent: computing or off.".into();
    };
    let count = |k: LyapKind| {
        curve
            .iter()
            .filter(|(_, l)| lyap_kind(*l, linear) == k)
            .count()
    };
    let (chaotic, growth) = (count(LyapKind::Chaotic), count(LyapKind::Growth));
    let reading = if growth > 0 {
        format!("positive at {growth} of them: the motion grows without bound there (parametric instability; a linear system is not chaotic)")
    } else if chaotic > 0 {
        format!("positive (chaos) at {chaotic} of them")
    } else {
        "no chaos (no clearly positive exponent)".to_string()
    };
    format!(
        "Largest Lyapunov exponent at {} {}: highest {top:.3} per mesh period at {}; {reading}.",
        curve.len(),
        speed_values(speed),
        speed_at(speed, om),
    )
}

/// A view of the motion at the selected Omega (`title` names it): the
/// range of x, the regime and the period.
pub fn omega_label(title: &str, r: &OmegaResult) -> String {
    let lo = r.x_um.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = r.x_um.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let period = crate::story::motion_tag(r.motion);
    let range = if lo.is_finite() && hi.is_finite() {
        format!(
            ", x from {lo:.0} to {hi:.0} µm (backlash {:.0} µm)",
            r.backlash_um
        )
    } else {
        String::new()
    };
    let preview = if r.preview { " (preview)" } else { "" };
    format!(
        "{title} of {} at Ω {}{preview}: {}, {period}{range}.",
        r.mesh_name,
        short(r.omega),
        crate::story::contact_tag(r.regime, r.backlash_um)
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::views::fr::{fr_view, HbmStore};
    use crate::views::test_support::{ctx, hbm_peak as point};

    /// The label names the peak and the regimes along Omega, and changes
    /// when the data does.
    #[test]
    fn the_frequency_response_label_says_what_the_plot_shows() {
        let mut st = HbmStore::new(5);
        st.add(
            vec![
                point(0.1, 100.0, Regime::NoImpact, true),
                point(0.23, 140.0, Regime::NoImpact, true),
                point(0.45, 120.0, Regime::SingleSided, true),
                point(2.0, 110.0, Regime::SingleSided, true),
            ],
            1.0,
            true,
            None,
        );
        let v = fr_view(&st, None, None, Some(0), &[100.0], &ctx());
        let text = fr_label(&v);
        assert_eq!(
            text,
            "Frequency response of s1a1: peak 140 µm at Ω 0.23; no impact from Ω 0.1 to 0.23; single-sided impact from Ω 0.23 to 2."
        );
        let mut more = st.clone();
        more.add(
            vec![point(2.0, 300.0, Regime::DoubleSided, true)],
            1.0,
            true,
            None,
        );
        let v2 = fr_view(&more, None, None, Some(0), &[100.0], &ctx());
        assert_ne!(fr_label(&v2), text);
        assert!(fr_label(&v2).contains("peak 300 µm at Ω 2"));
        let empty = fr_view(&HbmStore::new(5), None, None, Some(0), &[], &ctx());
        assert_eq!(fr_label(&empty), "Frequency response of s1a1: computing.");
        // With the speed axes in rpm the same sentence says rpm: each
        // speed Ω times the scale's rpm per Ω.
        let m = solver::model::Model::new(&solver::params::ModelParams::default()).unwrap();
        let mut rpm = v.clone();
        rpm.speed = SpeedAxis::new(crate::speed::AxisUnit::Rpm, Some(&m));
        let g = |o: f64| crate::speed::grouped(crate::speed::SpeedScale::of(&m).rpm(o));
        assert_eq!(
            fr_label(&rpm),
            format!(
                "Frequency response of s1a1: peak 140 µm at {} rpm; no impact from {} to {} rpm; single-sided impact from {} to {} rpm.",
                g(0.23), g(0.1), g(0.23), g(0.23), g(2.0)
            )
        );
    }

    #[test]
    fn the_lyapunov_label_counts_chaos() {
        let omega = SpeedAxis::default();
        assert!(lyap_label(&[], false, &omega).contains("computing"));
        let t = lyap_label(&[(0.5, -0.2), (1.0, 0.3), (1.5, 0.05)], false, &omega);
        assert_eq!(
            t,
            "Largest Lyapunov exponent at 3 values of Ω: highest 0.300 per mesh period at Ω 1; positive (chaos) at 2 of them."
        );
    }
}
