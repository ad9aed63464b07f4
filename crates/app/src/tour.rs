//! The "Start here" tour: five steps from the gear set to sharing a link,
//! each setting a state and pointing at the part of the page that shows
//! it. Its step rides in the link as `tour=N` (1-based), so a lecturer can
//! send a class straight to a step; `tour` is not a setting and never
//! changes a computation by itself.

/// One step of the tour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TourStep {
    /// The step's heading.
    pub title: &'static str,
    /// What to look at, in two or three sentences.
    pub text: &'static str,
    /// The id of the element it points at (scrolled to and highlighted).
    pub target: &'static str,
    /// The settings it makes (key, value), as the controls would.
    pub set: &'static [(&'static str, &'static str)],
    /// The one thing the student does to end the step, said plainly.
    pub action: &'static str,
    /// When the action is done, read off the page's state ([`done`]).
    pub goal: Goal,
    /// What the card says once it is done (after "Done: ").
    pub done: &'static str,
}

/// When a step's action is done: a fact about the page's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Goal {
    /// The setting `key` is another than `from`.
    Changed {
        /// The setting's key.
        key: &'static str,
        /// The value the step set.
        from: &'static str,
    },
    /// The setting `key` is within `tol` of `to`.
    Near {
        /// The setting's key.
        key: &'static str,
        /// The value asked for.
        to: f64,
        /// How close counts (a slider's step).
        tol: f64,
    },
    /// The setting `key` is below `to`.
    Below {
        /// The setting's key.
        key: &'static str,
        /// The bound.
        to: f64,
    },
    /// Either setting moved from what the step set (a cell clicked).
    Moved,
    /// The link was copied.
    LinkCopied,
}

/// Whether step `step`'s action is done: `get` reads a setting as the link
/// writes it, `copied` says whether the link was copied during the step.
pub fn done(step: &TourStep, get: impl Fn(&str) -> Option<String>, copied: bool) -> bool {
    let num = |k: &str| get(k).and_then(|v| v.parse::<f64>().ok());
    match step.goal {
        Goal::Changed { key, from } => get(key).is_some_and(|v| v != from),
        Goal::Near { key, to, tol } => num(key).is_some_and(|x| (x - to).abs() <= tol),
        Goal::Below { key, to } => num(key).is_some_and(|x| x < to),
        Goal::Moved => step.set.iter().any(|(k, v)| {
            let (now, set) = (num(k), v.parse::<f64>().ok());
            now.zip(set).is_some_and(|(a, b)| (a - b).abs() > 1e-9)
        }),
        Goal::LinkCopied => copied,
    }
}

/// The tour, in order.
pub const TOUR: [TourStep; 5] = [
    TourStep {
        title: "The gear set and its meshes",
        text: "The small sun s1 drives three short planets, each meshing with a long planet, which meshes with the large sun s2 and the ring: twelve tooth meshes. The highlighted one, s1a1, is the mesh the plots show; the animation (view 8) shows all of them. The page opens at Ω 0.35, a calm motion: the teeth of s1a1 stay in contact and the motion repeats exactly every mesh period, one closed loop in the phase portrait (view 5) and one dot in the Poincaré section (view 6).",
        target: "schematic",
        set: &[("mesh", "s1a1"), ("omega", "0.35")],
        action: "Now choose another mesh in “Mesh to plot” and see the highlight and the plots follow it.",
        goal: Goal::Changed { key: "mesh", from: "s1a1" },
        done: "the plots now show another mesh.",
    },
    TourStep {
        title: "Backlash and the frequency response",
        text: "The tour has moved the backlash from 100 to 150 µm: the grey ±b lines, where the teeth meet, moved with it, and the curve was computed again. For each Ω (mesh frequency) the curve gives the largest and smallest tooth deflection x (TE included); below +b the teeth have separated. Where the curve is dashed no periodic motion is stable: the dots are what the gears actually do.",
        target: "view-fr",
        set: &[("backlash_um", "150")],
        action: "Now drag the backlash slider to 50 µm and watch the ±b lines and the curve follow.",
        goal: Goal::Near { key: "backlash_um", to: 50.0, tol: 5.0 },
        done: "the backlash is 50 µm.",
    },
    TourStep {
        title: "When impact becomes double-sided",
        text: "The tour has chosen backlash 20 µm and Ω 1.4. The regime map colours every frequency and backlash by what the teeth do: no impact, single-sided impact (the driving flanks part and strike again) or double-sided impact (the teeth cross the whole backlash and hit the back flanks). At 20 µm and Ω 1.4 the teeth of s1a1 hit both flanks: see the time history (view 7).",
        target: "view-map",
        set: &[("backlash_um", "20"), ("omega", "1.4")],
        action: "Now click a cell of another colour on the map and see the time history change.",
        goal: Goal::Moved,
        done: "you moved to another cell of the map.",
    },
    TourStep {
        title: "From periodic to chaotic motion",
        text: "The tour has set the backlash back to 100 µm and selected Ω 1.2 (the red line). The bifurcation diagram samples x once per mesh period after the transient: one dot per Ω means the motion repeats every period, a cloud means it never repeats. At Ω 1.2 it is a cloud, and the Lyapunov exponent under it is positive: the motion is chaotic.",
        target: "view-bif",
        set: &[("backlash_um", "100"), ("omega", "1.2")],
        action: "Now click the diagram at an Ω below 0.5, where one dot per Ω shows a motion that repeats.",
        goal: Goal::Below { key: "omega", to: 0.5 },
        done: "Ω is below 0.5, where the motion repeats.",
    },
    TourStep {
        title: "Share what you found",
        text: "Copy link makes a link that restores every setting, the selected Ω and this tour step. Every plot exports its data (CSV, JSON) and its picture (PNG, SVG).",
        target: "copy-link",
        set: &[],
        action: "Now press Copy link.",
        goal: Goal::LinkCopied,
        done: "the link is copied; paste it anywhere to come back here.",
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

/// The gap between the tour's card and the data it points at (CSS px).
const GAP: f64 = 12.0;

/// Where the tour's card goes (its left and top, in page pixels): beside
/// the data it describes, never over it. `data` is the pointed plot's data
/// area (left, top, right, bottom), `card` the card's size, `page_w` the
/// page's width. To the left of the data if the card fits there (over the
/// settings, beside a plot in the first column), else to its right, else
/// under it.
pub fn place_card(data: [f64; 4], card: (f64, f64), page_w: f64) -> (f64, f64) {
    let [l, t, r, b] = data;
    let (w, _) = card;
    if l >= w + 2.0 * GAP {
        (l - GAP - w, t)
    } else if page_w - r >= w + 2.0 * GAP {
        (r + GAP, t)
    } else {
        let x = l.min(page_w - w - GAP / 2.0).max(GAP / 2.0);
        (x, b + GAP)
    }
}

/// What the window says when the card is placed (CSS px).
pub struct Geometry {
    /// The pointed data's box in viewport pixels (left, top, right, bottom).
    pub data: [f64; 4],
    /// The page's scroll (x, y).
    pub scroll: (f64, f64),
    /// The page's width.
    pub page_w: f64,
    /// The viewport's height.
    pub view_h: f64,
    /// The card's size (width, height).
    pub card: (f64, f64),
}

/// Where the card goes, in page pixels ([`place_card`]), and, for a new
/// step (its target just scrolled to the top), how far the page scrolls on
/// so that the card's bottom shows: never past the data's top.
pub fn placement(g: &Geometry, new_step: bool) -> ((f64, f64), Option<f64>) {
    let (sx, sy) = g.scroll;
    let [l, t, r, b] = g.data;
    let (x, y) = place_card([l + sx, t + sy, r + sx, b + sy], g.card, g.page_w);
    let by = (y - sy + g.card.1 + 8.0 - g.view_h).min(t - 8.0);
    ((x, y), (new_step && by > 0.0).then_some(by))
}

/// The step's counter: "Step 2 of 5".
pub fn counter(step: usize) -> String {
    format!("Step {} of {}", step + 1, TOUR.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_new_steps_card_under_its_data_is_scrolled_into_view_but_never_past_the_datas_top() {
        // A phone: 390 px wide, the plot (data 20..370 x 100..400 in the
        // viewport, scrolled by 1000) leaves no room beside it, so the card
        // (300 x 200) goes under it, at page y 1412, whose bottom is 1612 -
        // 1000 = 612 + 8 past a 500 px viewport: scroll on by 120, as the
        // data's top (100 - 8 = 92) allows only 92.
        let g = Geometry {
            data: [20.0, 100.0, 370.0, 400.0],
            scroll: (0.0, 1000.0),
            page_w: 390.0,
            view_h: 500.0,
            card: (300.0, 200.0),
        };
        let ((x, y), by) = placement(&g, true);
        assert_eq!(y, 1412.0);
        assert!(x >= 0.0 && x + 300.0 <= 390.0);
        assert_eq!(by, Some(92.0));
        // Not a new step: the card follows its data without scrolling.
        assert_eq!(placement(&g, false).1, None);
        // A tall viewport: the card shows, no scroll.
        let tall = Geometry { view_h: 900.0, ..g };
        assert_eq!(placement(&tall, true).1, None);
    }

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

    fn overlaps(a: [f64; 4], b: [f64; 4]) -> bool {
        a[0].max(b[0]) < a[2].min(b[2]) && a[1].max(b[1]) < a[3].min(b[3])
    }

    /// The card sits beside the data at a phone's, a laptop's and a wide
    /// screen's widths, wherever the data lie across the page.
    #[test]
    fn the_card_never_covers_the_data() {
        for page_w in [390.0_f64, 1366.0, 1920.0] {
            for left in [8.0_f64, 120.0, 420.0, 900.0]
                .into_iter()
                .filter(|l| l + 200.0 < page_w)
            {
                let data = [left, 300.0, (left + 700.0).min(page_w - 8.0), 800.0];
                let card = ((page_w - 16.0).min(352.0), 320.0);
                let (x, y) = place_card(data, card, page_w);
                let cb = [x, y, x + card.0, y + card.1];
                assert!(!overlaps(cb, data), "{page_w} {left}: {cb:?} over {data:?}");
                assert!(x >= 0.0 && x + card.0 <= page_w, "{page_w} {left}: {cb:?}");
            }
        }
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
            assert!(s.action.starts_with("Now "), "{}", s.action);
        }
    }

    /// Each step's action is not done in the state the step sets, and is
    /// done once the student has done what the action says.
    #[test]
    fn each_steps_action_is_done_only_once_the_student_did_it() {
        // The state right after the step: its own settings.
        for s in TOUR {
            let set = |k: &str| {
                s.set
                    .iter()
                    .find(|(key, _)| *key == k)
                    .map(|(_, v)| v.to_string())
            };
            assert!(!done(&s, set, false), "{}", s.title);
        }
        let with = |pairs: &'static [(&'static str, &'static str)]| {
            move |k: &str| {
                pairs
                    .iter()
                    .find(|(key, _)| *key == k)
                    .map(|(_, v)| v.to_string())
            }
        };
        // Step 1: another mesh.
        assert!(done(&TOUR[0], with(&[("mesh", "s2a1")]), false));
        // Step 2: the slider at 50 µm (its 5 µm step either side), not at 100.
        assert!(done(&TOUR[1], with(&[("backlash_um", "50")]), false));
        assert!(done(&TOUR[1], with(&[("backlash_um", "55")]), false));
        assert!(!done(&TOUR[1], with(&[("backlash_um", "100")]), false));
        // Step 3: a click on the map moves Omega, the backlash or both.
        assert!(done(
            &TOUR[2],
            with(&[("backlash_um", "20"), ("omega", "0.9")]),
            false
        ));
        assert!(done(
            &TOUR[2],
            with(&[("backlash_um", "60"), ("omega", "1.4")]),
            false
        ));
        // Step 4: Omega below 0.5.
        assert!(done(&TOUR[3], with(&[("omega", "0.45")]), false));
        assert!(!done(&TOUR[3], with(&[("omega", "0.5")]), false));
        // Step 5: only the copy counts.
        assert!(done(&TOUR[4], with(&[]), true));
        assert!(!done(&TOUR[4], with(&[]), false));
    }
}
