//! The "Start here" tour: five steps from the gear set to sharing a link,
//! each setting a state and pointing at the part of the page that shows
//! it. Its step rides in the link as `tour=N` (1-based), so a lecturer can
//! send a class straight to a step; `tour` is not a setting and never
//! changes a computation by itself.

/// One step of the tour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TourStep {
    /// The step's heading.
    pub title: &'static str,
    /// What to look at, in two or three sentences.
    pub text: &'static str,
    /// The id of the element it points at (scrolled to and highlighted).
    pub target: &'static str,
    /// The settings it makes (key, value), as the controls would.
    pub set: &'static [(&'static str, &'static str)],
}

/// The tour, in order.
pub const TOUR: [TourStep; 5] = [
    TourStep {
        title: "The gear set and its meshes",
        text: "The small sun s1 drives three short planets, each meshing with a long planet, which meshes with the large sun s2 and the ring: twelve tooth meshes. The highlighted one, s1a1, is the mesh the plots show; the animation (view 8) shows all of them. The page opens at Ω 0.35, a calm motion: the teeth of s1a1 stay in contact and the motion repeats exactly every mesh period, one closed loop in the phase portrait (view 5) and one dot in the Poincaré section (view 6).",
        target: "schematic",
        set: &[("mesh", "s1a1"), ("omega", "0.35")],
    },
    TourStep {
        title: "Backlash and the frequency response",
        text: "With 100 µm of backlash, each Ω (mesh frequency) gives the largest and smallest tooth deflection x (TE included). Below +b the teeth have separated. Where the curve is dashed no periodic motion is stable: the dots are what the gears actually do. Try the backlash slider.",
        target: "view-fr",
        set: &[("backlash_um", "100")],
    },
    TourStep {
        title: "When impact becomes double-sided",
        text: "The regime map colours every frequency and backlash by what the teeth do: no impact, single-sided impact (the driving flanks part and strike again) or double-sided impact (the teeth cross the backlash and hit the back flanks). Click a cell to go there.",
        target: "view-map",
        set: &[],
    },
    TourStep {
        title: "From periodic to chaotic motion",
        text: "The bifurcation diagram samples x once per mesh period after the transient: one dot per Ω means the motion repeats every period, a cloud means it never repeats. Where the Lyapunov exponent under it is positive the motion is chaotic. The views below show the motion at Ω 1.2.",
        target: "view-bif",
        set: &[("omega", "1.2")],
    },
    TourStep {
        title: "Share what you found",
        text: "Copy link makes a link that restores every setting, the selected Ω and this tour step. Every plot exports its data (CSV, JSON) and its picture (PNG, SVG).",
        target: "copy-link",
        set: &[],
    },
];

/// Splits `tour=N` off a link's query: the step (0-based, if valid) and the
/// rest of the query for the link decoder.
pub fn split_tour(query: &str) -> (Option<usize>, String) {
    let q = query.strip_prefix('?').unwrap_or(query);
    let mut step = None;
    let rest: Vec<&str> = q
        .split('&')
        .filter(|part| match part.strip_prefix("tour=") {
            Some(n) => {
                step = n
                    .parse::<usize>()
                    .ok()
                    .filter(|n| (1..=TOUR.len()).contains(n))
                    .map(|n| n - 1);
                false
            }
            None => true,
        })
        .collect();
    (step, rest.join("&"))
}

/// What is wrong with a link's `tour=` value, if anything: named, with the
/// steps the tour has (a bad step otherwise hid the tour without a word).
pub fn tour_issue(query: &str) -> Option<String> {
    let q = query.strip_prefix('?').unwrap_or(query);
    let n = q
        .split('&')
        .filter_map(|p| p.strip_prefix("tour="))
        .next_back()?;
    let fine = n
        .parse::<usize>()
        .is_ok_and(|n| (1..=TOUR.len()).contains(&n));
    (!fine).then(|| {
        format!(
            "tour = {} is not a step of the tour: allowed 1 to {}; the tour was not opened",
            solver::keys::truncate(n, 40),
            TOUR.len()
        )
    })
}

/// The step's counter: "Step 2 of 5".
pub fn counter(step: usize) -> String {
    format!("Step {} of {}", step + 1, TOUR.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tour_step_rides_in_the_link_and_bad_steps_are_dropped() {
        assert_eq!(split_tour("tour=3&omega=1"), (Some(2), "omega=1".into()));
        assert_eq!(split_tour("?omega=1&tour=5"), (Some(4), "omega=1".into()));
        assert_eq!(split_tour("omega=1&tour=9"), (None, "omega=1".into()));
        assert_eq!(split_tour("omega=1&tour=x"), (None, "omega=1".into()));
        assert_eq!(split_tour("omega=1"), (None, "omega=1".into()));
        // A bad step is named, with the steps there are.
        assert_eq!(tour_issue("tour=3&omega=1"), None);
        assert_eq!(tour_issue("omega=1"), None);
        for bad in ["999", "0", "%3Cscript%3E", "<script>", "x"] {
            let issue = tour_issue(&format!("omega=1&tour={bad}")).unwrap_or_default();
            assert!(issue.contains(bad), "{issue}");
            assert!(issue.contains(&format!("1 to {}", TOUR.len())), "{issue}");
        }
        assert_eq!(counter(1), "Step 2 of 5");
    }

    /// Every step sets real keys to values they accept, and points at a
    /// part of the page that exists.
    #[test]
    fn every_step_sets_real_settings_and_points_at_the_page() {
        let html = include_str!("../../../index.html");
        assert!((4..=6).contains(&TOUR.len()));
        for s in TOUR {
            assert!(
                html.contains(&format!("id=\"{}\"", s.target)),
                "{}",
                s.target
            );
            for (k, v) in s.set {
                let mut settings = crate::settings::Settings::default();
                let ok = if crate::settings::view_key(k).is_some() {
                    settings.view.set(k, v, &["s1a1".to_string()]).is_ok()
                } else {
                    solver::keys::set_assignment(&mut settings.params, &format!("{k}={v}")).is_ok()
                };
                assert!(ok, "{k}={v}");
            }
            assert!(!s.text.contains('_'), "{}", s.text);
        }
    }
}
