//! Where the frequency response's branch is unstable: the Omega ranges no
//! stable stretch covers, the plain sentence the plot shows there ("no
//! stable periodic motion between Ω 0.45 and 1.7: the dots are the actual
//! response") and the regime strip filled from the time-integration dots.

use super::fr::{FrCurvePoint, FrView};
use crate::protocol::Regime;
use crate::speed::SpeedAxis;
use crate::story::BranchAt;

/// What the branch `points` says at `omega`: stable if a stable stretch
/// (both ends stable, or of unknown stability) covers it, unstable if only
/// unstable stretches do, not covered otherwise.
pub fn branch_at(points: &[FrCurvePoint], omega: f64) -> BranchAt {
    let ok = |p: &FrCurvePoint| p.stable != Some(false);
    let mut covered = false;
    for w in points.windows(2).filter(|w| w[0].joins(&w[1])) {
        let (a, b) = (w[0].omega.min(w[1].omega), w[0].omega.max(w[1].omega));
        if omega < a || omega > b {
            continue;
        }
        if ok(&w[0]) && ok(&w[1]) {
            return BranchAt::Stable;
        }
        covered = true;
    }
    if covered {
        BranchAt::Unstable
    } else {
        BranchAt::NotCovered
    }
}

/// The branch whose stability the frequency response's sentence reads: the
/// current settings' (a family's first member, whose steady state the
/// summary describes), never the faded previous one or the pinned A.
pub fn current_branch(v: &FrView) -> Option<&super::fr::FrBranch> {
    v.branches.iter().find(|b| !b.faded && !b.pinned)
}

/// The Omega ranges, within the branch's reach, where no stretch of the
/// branch is stable (stretches of unknown stability count as stable): there
/// the gears do not follow any periodic solution the branch holds. Ranges
/// narrower than 0.5 % of the branch's reach are left out, and stable
/// islands that narrow do not split a range (a stretch of a point or two
/// between bifurcations); a wider stable island always does, so that the
/// sentence never covers an Ω where the branch holds a stable orbit.
pub fn unstable_ranges(points: &[FrCurvePoint]) -> Vec<(f64, f64)> {
    let lo = points.iter().map(|p| p.omega).fold(f64::INFINITY, f64::min);
    let hi = points
        .iter()
        .map(|p| p.omega)
        .fold(f64::NEG_INFINITY, f64::max);
    if points.len() < 2 || hi <= lo {
        return Vec::new();
    }
    let ok = |p: &FrCurvePoint| p.stable != Some(false);
    let mut stable: Vec<(f64, f64)> = points
        .windows(2)
        .filter(|w| ok(&w[0]) && ok(&w[1]))
        .map(|w| (w[0].omega.min(w[1].omega), w[0].omega.max(w[1].omega)))
        .collect();
    stable.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut gaps = Vec::new();
    let mut reach = lo;
    for (a, b) in stable {
        if a > reach {
            gaps.push((reach, a));
        }
        reach = reach.max(b);
    }
    if hi > reach {
        gaps.push((reach, hi));
    }
    let narrow = MERGE_FRACTION * (hi - lo);
    let mut merged: Vec<(f64, f64)> = Vec::new();
    for g in gaps {
        match merged.last_mut() {
            Some(last) if g.0 - last.1 < narrow => last.1 = g.1,
            _ => merged.push(g),
        }
    }
    merged.retain(|&(a, b)| b - a >= narrow);
    merged
}

/// The width, as a fraction of the branch's reach, below which an unstable
/// range is left out and a stable island does not split one.
const MERGE_FRACTION: f64 = 0.005;

pub use crate::words::short;

/// A speed in a sentence as the speed axes show it: "Ω 0.35", or
/// "3 012 rpm".
pub(crate) fn speed_at(speed: &SpeedAxis, omega: f64) -> String {
    match speed.rpm_scale() {
        Some(s) => format!("{} rpm", crate::speed::grouped(s.rpm(omega))),
        None => format!("Ω {}", short(omega)),
    }
}

/// A span of speeds in a sentence: "from Ω 0.45 to 2" ("from 0.45 to 2"
/// unless `named`), or "from 2 400 to 10 600 rpm".
pub(crate) fn speed_span(speed: &SpeedAxis, a: f64, b: f64, named: bool) -> String {
    match speed.rpm_scale() {
        Some(s) => format!(
            "from {} to {} rpm",
            crate::speed::grouped(s.rpm(a)),
            crate::speed::grouped(s.rpm(b))
        ),
        None if named => format!("from Ω {} to {}", short(a), short(b)),
        None => format!("from {} to {}", short(a), short(b)),
    }
}

/// What the speeds are called in a count: "values of Ω" or "speeds".
pub(crate) fn speed_values(speed: &SpeedAxis) -> &'static str {
    if speed.rpm_scale().is_some() {
        "speeds"
    } else {
        "values of Ω"
    }
}

/// Ranges in words: "between Ω 0.45 and 1.7" (joined by "and" when
/// several), or with the speed axes in rpm "between 2 400 and 9 000 rpm".
fn ranges_text(ranges: &[(f64, f64)], speed: &crate::speed::SpeedAxis) -> String {
    let parts: Vec<String> = ranges
        .iter()
        .enumerate()
        .map(|(i, &(a, b))| match speed.rpm_scale() {
            Some(s) => format!(
                "between {} and {} rpm",
                crate::speed::grouped(s.rpm(a)),
                crate::speed::grouped(s.rpm(b))
            ),
            None => {
                let omega = if i == 0 { "Ω " } else { "" };
                format!("between {omega}{} and {}", short(a), short(b))
            }
        })
        .collect();
    parts.join(" and ")
}

/// The plain sentence the plot shows when the current branch is unstable
/// over a range: no orbit the branch holds is stable there, and the dots
/// are what the gears actually do; where the selected Ω lies in such a
/// range, what its steady state is ([`crate::story::branch_agreement`]).
pub fn unstable_sentence(v: &FrView) -> Option<String> {
    let br = current_branch(v)?;
    let ranges = unstable_ranges(&br.points);
    if ranges.is_empty() {
        return None;
    }
    let tail = if v.overlay.is_empty() {
        "the actual response (time integration) is being computed"
    } else {
        "the dots are the actual response"
    };
    let on = match br.member {
        Some(_) => format!(" on the {} curve", br.label),
        None => String::new(),
    };
    let mut s = format!(
        "No stable orbit on the branch{on} {}: {tail}.",
        ranges_text(&ranges, &v.speed)
    );
    if let Some(m) = v.selected_motion {
        let inside = ranges
            .iter()
            .any(|&(a, b)| v.selected_omega >= a && v.selected_omega <= b);
        if inside {
            if let Some(more) = crate::story::branch_agreement(m, BranchAt::Unstable) {
                s.push_str(&format!(
                    " At the selected {}: {}",
                    speed_at(&v.speed, v.selected_omega),
                    lower_first(&more)
                ));
            }
        }
    }
    Some(s)
}

/// `s` with its first letter in lower case.
fn lower_first(s: &str) -> String {
    let mut c = s.chars();
    match c.next() {
        Some(f) => f.to_lowercase().chain(c).collect(),
        None => String::new(),
    }
}

/// The regime strip where the branch is unstable, from the time-integration
/// points inside those ranges: each point's regime over the Omegas nearer
/// to it than to its neighbours, clipped to the range. Returns (regime,
/// from, to) runs.
pub fn strip_from_overlay(
    ranges: &[(f64, f64)],
    overlay: &[FrCurvePoint],
) -> Vec<(Regime, f64, f64)> {
    let mut pts: Vec<&FrCurvePoint> = overlay.iter().filter(|p| p.regime.is_some()).collect();
    pts.sort_by(|a, b| a.omega.total_cmp(&b.omega));
    let mut out = Vec::new();
    for (i, p) in pts.iter().enumerate() {
        let Some(&(a, b)) = ranges.iter().find(|r| p.omega >= r.0 && p.omega <= r.1) else {
            continue;
        };
        // Half-way to each neighbour; at either end of the dots as far as
        // the spacing on the other side, so that a sweep still running
        // does not colour Omegas it has not reached.
        let prev = i.checked_sub(1).map(|j| pts[j].omega);
        let next = pts.get(i + 1).map(|q| q.omega);
        let (left, right) = match (prev, next) {
            (Some(l), Some(r)) => (0.5 * (l + p.omega), 0.5 * (r + p.omega)),
            (None, Some(r)) => (p.omega - 0.5 * (r - p.omega), 0.5 * (r + p.omega)),
            (Some(l), None) => (0.5 * (l + p.omega), p.omega + 0.5 * (p.omega - l)),
            (None, None) => (a, b),
        };
        let (from, to) = (left.max(a), right.min(b));
        if let (Some(r), true) = (p.regime, to > from) {
            out.push((r, from, to));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::FrSample;
    use crate::views::fr::{fr_view, FrStore, HbmStore};
    use crate::views::test_support::{ctx, ext, hbm_point};

    fn pt(omega: f64, stable: Option<bool>, regime: Regime) -> FrCurvePoint {
        FrCurvePoint {
            omega,
            max_um: 1.0,
            min_um: 0.0,
            stable,
            regime: Some(regime),
            period: None,
            bifurcation: None,
            piece: 0,
        }
    }

    /// The unstable ranges are the Omegas no stable stretch covers: a fold
    /// whose upper stretch is stable covers its Omegas even though the
    /// middle stretch there is unstable; tiny gaps are left out.
    #[test]
    fn unstable_ranges_are_where_no_stretch_is_stable() {
        let s = Some(true);
        let u = Some(false);
        let r = Regime::NoImpact;
        let curve = |pts: &[(f64, Option<bool>)]| -> Vec<FrCurvePoint> {
            pts.iter().map(|&(o, st)| pt(o, st, r)).collect()
        };
        // Stable 0.1..0.4, unstable 0.4..1.0 then 1.0..1.7, stable again to 2.
        let branch = curve(&[(0.1, s), (0.4, s), (0.7, u), (1.0, u), (1.7, s), (2.0, s)]);
        assert_eq!(unstable_ranges(&branch), vec![(0.4, 1.7)]);
        // A fold: up 0.1..0.8 stable, back 0.8..0.5 unstable, up 0.5..2 stable.
        let fold = curve(&[(0.1, s), (0.8, s), (0.5, u), (0.5, s), (2.0, s)]);
        assert!(unstable_ranges(&fold).is_empty());
        // Unknown stability counts as stable; a gap under 0.5 % is dropped.
        assert!(unstable_ranges(&curve(&[(0.1, None), (2.0, None)])).is_empty());
        let tiny = curve(&[(0.0, s), (1.0, s), (1.004, u), (2.0, s)]);
        assert_eq!(unstable_ranges(&tiny), vec![(1.0, 2.0)]);
        let tiny2 = curve(&[(0.0, s), (1.0, s), (1.004, u), (1.008, s), (2.0, s)]);
        assert!(unstable_ranges(&tiny2).is_empty());
        // A stable island under 0.5 % of the reach does not split a range.
        let island = [0.0, 0.5, 0.8, 0.803, 0.806, 1.5, 1.6, 2.0];
        let stable = [s, s, u, s, s, u, s, s];
        let island: Vec<(f64, Option<bool>)> = island.into_iter().zip(stable).collect();
        assert_eq!(unstable_ranges(&curve(&island)), vec![(0.5, 1.6)]);
        // A wider one does: the default set's stable period-1 stretch over
        // Ω 0.242-0.281 between two unstable ones is 2 % of the reach, and
        // the sentence must not cover Ω 0.27, where the orbit is stable.
        let island = [0.1, 0.239, 0.24, 0.242, 0.281, 0.285, 0.3, 2.0];
        let stable = [s, s, u, u, u, u, s, s];
        let split: Vec<(f64, Option<bool>)> = island.into_iter().zip(stable).collect();
        let stable = [s, s, u, s, s, u, s, s];
        let kept: Vec<(f64, Option<bool>)> = island.into_iter().zip(stable).collect();
        assert_eq!(unstable_ranges(&curve(&split)), vec![(0.239, 0.3)]);
        assert_eq!(unstable_ranges(&curve(&kept)), vec![(0.281, 0.3)]);
        assert_eq!(
            branch_at(&curve(&kept), 0.27),
            crate::story::BranchAt::Stable
        );
        assert_eq!(
            branch_at(&curve(&kept), 0.29),
            crate::story::BranchAt::Unstable
        );
        assert_eq!(
            branch_at(&curve(&kept), 2.5),
            crate::story::BranchAt::NotCovered
        );
        assert_eq!(short(0.45), "0.45");
        assert_eq!(short(1.7), "1.7");
        assert_eq!(short(2.0), "2");
    }

    /// Inside an unstable range the strip takes each dot's regime over the
    /// Omegas nearest to it, clipped to the range; dots outside are unused.
    #[test]
    fn the_strip_is_filled_from_the_dots_where_the_branch_is_unstable() {
        let dots = vec![
            pt(0.2, None, Regime::NoImpact),
            pt(0.6, None, Regime::SingleSided),
            pt(1.0, None, Regime::DoubleSided),
            pt(1.4, None, Regime::SingleSided),
        ];
        let runs = strip_from_overlay(&[(0.5, 1.1)], &dots);
        assert_eq!(runs.len(), 2);
        assert_eq!(runs[0].0, Regime::SingleSided);
        assert!((runs[0].1 - 0.5).abs() < 1e-12 && (runs[0].2 - 0.8).abs() < 1e-12);
        assert_eq!(runs[1].0, Regime::DoubleSided);
        assert!((runs[1].1 - 0.8).abs() < 1e-12 && (runs[1].2 - 1.1).abs() < 1e-12);
        assert!(strip_from_overlay(&[], &dots).is_empty());
        // The last dot of a sweep still running colours half a spacing
        // beyond it, not the rest of the range.
        let partial = strip_from_overlay(&[(0.5, 1.9)], &dots[..3]);
        let last = partial.last().unwrap();
        assert!(
            (last.1 - 0.8).abs() < 1e-12 && (last.2 - 1.2).abs() < 1e-12,
            "{last:?}"
        );
    }

    /// The sentence names the range and says what the dots are, or that
    /// they are coming; a branch stable everywhere gets none.
    #[test]
    fn the_plot_says_where_no_periodic_motion_is_stable() {
        let mut st = HbmStore::new(5);
        st.add(
            vec![
                hbm_point(0.1, &[(80.0, 120.0)], true),
                hbm_point(0.45, &[(80.0, 120.0)], true),
                hbm_point(1.0, &[(60.0, 140.0)], false),
                hbm_point(1.7, &[(80.0, 120.0)], true),
                hbm_point(2.0, &[(80.0, 120.0)], true),
            ],
            1.0,
            true,
            None,
        );
        let v = fr_view(&st, None, None, Some(0), &[100.0], &ctx());
        assert_eq!(
            unstable_sentence(&v).as_deref(),
            Some("No stable orbit on the branch between Ω 0.45 and 1.7: the actual response (time integration) is being computed.")
        );
        let mut ti = FrStore::new(1, 300, 30);
        ti.add(vec![FrSample {
            index: 0,
            omega: 1.2,
            meshes: vec![ext(0.0, 10.0, None)],
            period: None,
            error: None,
        }]);
        let v = fr_view(&st, None, Some(&ti), Some(0), &[100.0], &ctx());
        assert_eq!(
            unstable_sentence(&v).as_deref(),
            Some("No stable orbit on the branch between Ω 0.45 and 1.7: the dots are the actual response.")
        );
        // With the speed axes in rpm, the range is the input's rpm, each
        // end Ω times rpm per Ω (the scale's, checked against the solver
        // in crate::speed).
        let m = solver::model::Model::new(&solver::params::ModelParams::default()).unwrap();
        let mut rpm = v.clone();
        rpm.speed = crate::speed::SpeedAxis::new(crate::speed::AxisUnit::Rpm, Some(&m));
        let k = crate::speed::SpeedScale::of(&m).rpm(1.0);
        let g = |o: f64| crate::speed::grouped(o * k);
        assert_eq!(
            unstable_sentence(&rpm),
            Some(format!("No stable orbit on the branch between {} and {} rpm: the dots are the actual response.", g(0.45), g(1.7)))
        );
        let mut ok = HbmStore::new(5);
        ok.add(
            vec![
                hbm_point(0.1, &[(1.0, 2.0)], true),
                hbm_point(2.0, &[(1.0, 2.0)], true),
            ],
            1.0,
            true,
            None,
        );
        assert_eq!(
            unstable_sentence(&fr_view(&ok, None, None, Some(0), &[100.0], &ctx())),
            None
        );
    }
}
