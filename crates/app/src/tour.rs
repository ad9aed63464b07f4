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
    /// What the card must leave in view, by element id: the target's
    /// picture first (a plot's canvas, the gear set's drawing, a button),
    /// then what the step asks the student to use or read.
    pub keep_clear: &'static [&'static str],
    /// The control the action uses (its key), if any: on a phone, whose
    /// settings drawer starts closed, the tour opens the drawer and its
    /// card offers a jump to the control and back.
    pub control: Option<&'static str>,
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
        keep_clear: &["schematic-svg", "control-mesh"],
        control: Some("mesh"),
        set: &[("mesh", "s1a1"), ("omega", "0.35")],
        action: "Now choose another mesh in “Mesh to plot” and see the highlight and the plots follow it.",
        goal: Goal::Changed { key: "mesh", from: "s1a1" },
        done: "the plots now show another mesh.",
    },
    TourStep {
        title: "Backlash and the frequency response",
        text: "The tour has moved the backlash from 100 to 150 µm: the grey ±b lines, where the teeth meet, moved with it, and the curve was computed again. For each speed (mesh frequency) the curve gives the largest and smallest tooth deflection x (TE included); below +b the teeth have separated. Where the curve is dashed no periodic motion is stable: the dots are what the gears actually do.",
        target: "view-fr",
        keep_clear: &["canvas-fr", "control-backlash_um"],
        control: Some("backlash_um"),
        set: &[("backlash_um", "150")],
        action: "Now drag the backlash slider to 50 µm and watch the ±b lines and the curve follow.",
        goal: Goal::Near { key: "backlash_um", to: 50.0, tol: 5.0 },
        done: "the backlash is 50 µm.",
    },
    TourStep {
        title: "When impact becomes double-sided",
        text: "The tour has chosen backlash 20 µm and Ω 1.4. The regime map colours every frequency and backlash by what the teeth do: no impact, single-sided impact (the driving flanks part and strike again) or double-sided impact (the teeth cross the whole backlash and hit the back flanks). At 20 µm and Ω 1.4 the teeth of s1a1 hit both flanks: see the time history (view 7).",
        target: "view-map",
        keep_clear: &["canvas-map"],
        control: None,
        set: &[("backlash_um", "20"), ("omega", "1.4")],
        action: "Now click a cell of another colour on the map and see the time history change.",
        goal: Goal::Moved,
        done: "you moved to another cell of the map.",
    },
    TourStep {
        title: "From periodic to chaotic motion",
        text: "The tour has set the backlash back to 100 µm and selected Ω 1.2: the red line. The bifurcation diagram samples x once per mesh period after the transient: one dot per speed means the motion repeats every period, a cloud means it never repeats. At Ω 1.2 it is a cloud, and the Lyapunov exponent under it is positive: the motion is chaotic.",
        target: "view-bif",
        keep_clear: &["canvas-bif"],
        control: None,
        set: &[("backlash_um", "100"), ("omega", "1.2")],
        action: "Now click the diagram at a speed below Ω 0.5, where one dot per speed shows a motion that repeats.",
        goal: Goal::Below { key: "omega", to: 0.5 },
        done: "the selected speed is below Ω 0.5, where the motion repeats.",
    },
    TourStep {
        title: "Share what you found",
        text: "Copy link makes a link that restores every setting, the selected speed and this tour step. Every plot exports its data (CSV, JSON) and its picture (PNG, SVG).",
        target: "copy-link",
        keep_clear: &["copy-link", "summary"],
        control: None,
        set: &[],
        action: "Now press Copy link.",
        goal: Goal::LinkCopied,
        done: "the link is copied; paste it anywhere to come back here.",
    },
];

/// A step's words as the speed axes read them: with the axes in rpm each
/// speed "Ω 1.4" becomes "7 228 rpm (Ω 1.4)", the input member's speed
/// first; in Ω the words are as written. The steps' settings stay in Ω.
pub fn in_speed(text: &str, axis: &figures::speed::SpeedAxis) -> String {
    let Some(scale) = axis.rpm_scale() else {
        return text.to_string();
    };
    let mut out = String::new();
    let mut rest = text;
    while let Some(at) = rest.find("Ω ") {
        out.push_str(&rest[..at]);
        let after = &rest[at + "Ω ".len()..];
        let len = after
            .char_indices()
            .take_while(|(_, c)| c.is_ascii_digit() || *c == '.')
            .map(|(i, c)| i + c.len_utf8())
            .last()
            .unwrap_or(0);
        // A sentence's full stop is not the number's.
        let number = after[..len].trim_end_matches('.');
        match number.parse::<f64>() {
            Ok(omega) => {
                let rpm = figures::speed::grouped(scale.rpm(omega));
                out.push_str(&format!("{rpm} rpm (Ω {number})"));
                rest = &after[number.len()..];
            }
            Err(_) => {
                out.push_str("Ω ");
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

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

/// The gap between the tour's card and what it must leave in view (CSS px).
const GAP: f64 = 12.0;

/// A box on the screen: left, top, right, bottom (CSS px).
pub type Rect = [f64; 4];

fn overlaps(a: Rect, b: Rect) -> bool {
    a[0].max(b[0]) < a[2].min(b[2]) && a[1].max(b[1]) < a[3].min(b[3])
}

/// How far apart two boxes are (0 if they touch or overlap).
fn distance(a: Rect, b: Rect) -> f64 {
    let dx = (b[0] - a[2]).max(a[0] - b[2]).max(0.0);
    let dy = (b[1] - a[3]).max(a[1] - b[3]).max(0.0);
    dx.hypot(dy)
}

/// What the window says when the card is placed (CSS px, boxes in the
/// viewport's coordinates).
#[derive(Debug, Clone, PartialEq)]
pub struct Geometry {
    /// What the card must leave in view: the step's target first (a
    /// plot's canvas, the gear set's picture, a button), then the controls
    /// it names (those shown: a closed drawer's have no box).
    pub keep_clear: Vec<Rect>,
    /// What the card had better leave in view too, where the screen has
    /// room: the highlighted target whole (its caption and key), the plots.
    pub prefer_clear: Vec<Rect>,
    /// The card's box now, if it shows.
    pub card_now: Option<Rect>,
    /// Where the target was when the card was last placed: its left and
    /// top on the page, and its top on the screen after that placement's
    /// scroll. The card keeps its place beside the target as the page's
    /// layout shifts (a plot above grows).
    pub anchor: Option<(f64, f64, f64)>,
    /// The page's scroll (x, y).
    pub scroll: (f64, f64),
    /// The viewport's width and height.
    pub view: (f64, f64),
    /// The card's size (width, height).
    pub card: (f64, f64),
}

/// Where the card goes and how far the page scrolls on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Placement {
    /// The card's left and top in page pixels; `None`: it stays where it
    /// is (docked at the screen's foot, or already clear of everything).
    pub at: Option<(f64, f64)>,
    /// How far to scroll the page down (negative: up), if at all.
    pub scroll_by: Option<f64>,
    /// Where the target is on the page now, and on the screen after this
    /// placement's scroll ([`Geometry::anchor`] for the next placement).
    pub anchor: Option<(f64, f64, f64)>,
}

/// The card's spot in the viewport: within the screen, over none of the
/// boxes to keep clear, and as near the first (the target) as can be.
/// Tried at every edge of every box and of the screen; `None` if no spot
/// is free.
pub fn free_spot(keep_clear: &[Rect], card: (f64, f64), view: (f64, f64)) -> Option<(f64, f64)> {
    let (w, h) = card;
    let (vw, vh) = view;
    let edge = GAP / 2.0;
    let target = *keep_clear.first()?;
    let mut xs = vec![edge, vw - w - edge];
    let mut ys = vec![edge, vh - h - edge];
    for r in keep_clear {
        xs.extend([r[0] - GAP - w, r[2] + GAP, r[0], r[2] - w]);
        ys.extend([r[1], r[3] + GAP, r[1] - GAP - h, r[3] - h]);
    }
    let grown = |r: &Rect| [r[0] - 4.0, r[1] - 4.0, r[2] + 4.0, r[3] + 4.0];
    let mut best: Option<(f64, (f64, f64))> = None;
    for &x in &xs {
        for &y in &ys {
            let c = [x, y, x + w, y + h];
            let inside = x >= edge - 0.5
                && y >= edge - 0.5
                && c[2] <= vw - edge + 0.5
                && c[3] <= vh - edge + 0.5;
            if !inside || keep_clear.iter().any(|r| overlaps(c, grown(r))) {
                continue;
            }
            // Near the target, and level with its top where it can be.
            let score = distance(c, target) + 0.1 * (y - target[1].max(edge)).abs();
            if best.is_none_or(|(s, _)| score < s - 1e-9) {
                best = Some((score, (x, y)));
            }
        }
    }
    best.map(|(_, at)| at)
}

/// Where the card goes ([`Placement`]). `docked`: the card sits at the
/// foot of the screen (a phone's), so a new step scrolls its target to the
/// top, above the card. Else the card goes on a free spot of the screen
/// beside the target ([`free_spot`]), clear of what it had better leave
/// in view too where there is one such spot. A later frame moves it with
/// its target as the layout shifts, and looks for a new spot only if it
/// then covers something (the plot grew). With no free spot it goes under
/// the target, and a new step scrolls on until the card shows, never past
/// the target's top.
pub fn placement(g: &Geometry, new_step: bool, docked: bool) -> Placement {
    let (sx, sy) = g.scroll;
    let Some(&target) = g.keep_clear.first() else {
        return Placement {
            at: None,
            scroll_by: None,
            anchor: None,
        };
    };
    let page = (target[0] + sx, target[1] + sy);
    let anchor = Some((page.0, page.1, target[1]));
    if docked {
        // A new step: its target to the top. Later: when the layout above
        // the target shifts (a note grows), the target goes back to its
        // place on the screen, above the card. The browser's own scroll
        // anchoring may have done so already: then nothing is left to
        // scroll. A reader's own scroll moves nothing on the page and is
        // left alone.
        let by = match (new_step, g.anchor) {
            (true, _) => target[1] - GAP,
            (false, Some(then)) if (page.1 - then.1).abs() > 1.0 => target[1] - then.2,
            (false, _) => 0.0,
        };
        let scroll_by = (by.abs() > 1.0).then_some(by);
        return Placement {
            at: None,
            scroll_by,
            anchor: Some((page.0, page.1, target[1] - scroll_by.unwrap_or(0.0))),
        };
    }
    let clear = |c: Rect| !g.keep_clear.iter().any(|r| overlaps(c, *r));
    if let (false, Some(now)) = (new_step, g.card_now) {
        // The target moved on the page by (dx, dy): the card with it.
        let (dx, dy) = match g.anchor {
            Some(then) => (page.0 - then.0, page.1 - then.1),
            None => (0.0, 0.0),
        };
        let moved = [now[0] + dx, now[1] + dy, now[2] + dx, now[3] + dy];
        if clear(moved) {
            let shifted = dx.abs() >= 0.5 || dy.abs() >= 0.5;
            return Placement {
                at: shifted.then_some((moved[0] + sx, moved[1] + sy)),
                scroll_by: None,
                anchor,
            };
        }
    }
    let both: Vec<Rect> = g
        .keep_clear
        .iter()
        .chain(&g.prefer_clear)
        .copied()
        .collect();
    let spot =
        free_spot(&both, g.card, g.view).or_else(|| free_spot(&g.keep_clear, g.card, g.view));
    if let Some((x, y)) = spot {
        return Placement {
            at: Some((x + sx, y + sy)),
            scroll_by: None,
            anchor,
        };
    }
    let (w, h) = g.card;
    let x = target[0].min(g.view.0 - w - GAP / 2.0).max(GAP / 2.0);
    let y = target[3] + GAP;
    let by = (y + h + 8.0 - g.view.1).min(target[1] - 8.0);
    Placement {
        at: Some((x + sx, y + sy)),
        scroll_by: (new_step && by > 0.0).then_some(by),
        anchor,
    }
}

/// The step's counter: "Step 2 of 5".
pub fn counter(step: usize) -> String {
    format!("Step {} of {}", step + 1, TOUR.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A laptop's step 2: the frequency response's canvas fills the main
    /// column and the backlash slider sits in the settings on its left.
    /// The card goes in the settings' column, under the slider.
    #[test]
    fn the_card_leaves_the_plot_and_the_control_it_names_in_view() {
        let canvas = [341.0, 90.0, 1341.0, 630.0];
        let slider = [29.0, 240.0, 303.0, 290.0];
        let g = Geometry {
            keep_clear: vec![canvas, slider],
            prefer_clear: vec![[333.0, 16.0, 1350.0, 700.0]],
            card_now: None,
            anchor: None,
            scroll: (0.0, 1200.0),
            view: (1366.0, 768.0),
            card: (304.0, 420.0),
        };
        let p = placement(&g, true, false);
        let Some((x, y)) = p.at else {
            panic!("{p:?}");
        };
        let card = [x, y - 1200.0, x + 304.0, y - 1200.0 + 420.0];
        assert!(
            !overlaps(card, canvas) && !overlaps(card, slider),
            "{card:?}"
        );
        assert!(card[1] >= slider[3] && card[3] <= 768.0, "{card:?}");
        assert_eq!(p.scroll_by, None);
        // A later frame leaves a card that covers nothing where it is...
        let later = Geometry {
            card_now: Some(card),
            anchor: p.anchor,
            ..g.clone()
        };
        assert_eq!(placement(&later, false, false).at, None);
        // ...moves it with its target when a plot above grew by 40 px...
        let shifted = Geometry {
            keep_clear: vec![[341.0, 130.0, 1341.0, 670.0], slider],
            ..later.clone()
        };
        assert_eq!(placement(&shifted, false, false).at, Some((x, y + 40.0)));
        // ...and moves one that the grown plot now runs under.
        let grown = Geometry {
            card_now: Some([500.0, 100.0, 804.0, 520.0]),
            ..g.clone()
        };
        assert!(placement(&grown, false, false).at.is_some());
    }

    /// A phone's card is docked at the screen's foot: a new step scrolls
    /// its target's top just under the screen's top; later frames scroll
    /// only with a shift of the layout.
    #[test]
    fn a_docked_card_scrolls_its_target_to_the_top() {
        let g = Geometry {
            keep_clear: vec![[8.0, 300.0, 382.0, 800.0]],
            prefer_clear: Vec::new(),
            card_now: None,
            anchor: None,
            scroll: (0.0, 1000.0),
            view: (390.0, 844.0),
            card: (374.0, 320.0),
        };
        let p = placement(&g, true, true);
        assert_eq!((p.at, p.scroll_by), (None, Some(288.0)));
        assert_eq!(placement(&g, false, true).scroll_by, None);
        // The target at the top (page y 1300): a note above it grows by
        // 105 px, and the page scrolls on with it.
        assert_eq!(p.anchor, Some((8.0, 1300.0, 12.0)));
        let placed = Geometry {
            keep_clear: vec![[8.0, 12.0, 382.0, 512.0]],
            scroll: (0.0, 1288.0),
            anchor: p.anchor,
            ..g.clone()
        };
        assert_eq!(placement(&placed, false, true).scroll_by, None);
        let shifted = Geometry {
            keep_clear: vec![[8.0, 117.0, 382.0, 617.0]],
            ..placed.clone()
        };
        assert_eq!(placement(&shifted, false, true).scroll_by, Some(105.0));
        // The browser's scroll anchoring kept the target in place on the
        // screen by scrolling the 105 px itself: nothing more to scroll
        // (scrolling again put the gear set's picture off the phone's
        // screen once view 12 made the page longer).
        let anchored = Geometry {
            scroll: (0.0, 1393.0),
            ..placed.clone()
        };
        assert_eq!(placement(&anchored, false, true).scroll_by, None);
        // A reader's scroll moves nothing on the page: left alone.
        let read = Geometry {
            keep_clear: vec![[8.0, 212.0, 382.0, 712.0]],
            scroll: (0.0, 1088.0),
            ..placed.clone()
        };
        assert_eq!(placement(&read, false, true).scroll_by, None);
    }

    /// With no free spot on the screen the card goes under its target and
    /// a new step scrolls on until it shows, never past the target's top.
    #[test]
    fn with_no_free_spot_the_card_goes_under_its_target() {
        let g = Geometry {
            keep_clear: vec![[20.0, 100.0, 370.0, 400.0]],
            prefer_clear: Vec::new(),
            card_now: None,
            anchor: None,
            scroll: (0.0, 1000.0),
            view: (390.0, 500.0),
            card: (300.0, 200.0),
        };
        let p = placement(&g, true, false);
        assert_eq!(p.at.map(|(_, y)| y), Some(1412.0));
        assert_eq!(p.scroll_by, Some(92.0));
        assert_eq!(placement(&g, false, false).scroll_by, None);
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

    /// A free spot is on the screen and over nothing to keep clear, at a
    /// laptop's and a wide screen's sizes, wherever the target lies.
    #[test]
    fn a_free_spot_never_covers_what_it_must_leave_in_view() {
        for (vw, vh) in [(1366.0_f64, 768.0_f64), (1920.0, 1080.0)] {
            for left in [8.0_f64, 120.0, 341.0, 900.0] {
                let target = [left, 60.0, (left + 1000.0).min(vw - 8.0), 640.0];
                let control = [20.0, 500.0, 300.0, 540.0];
                let card = (304.0, 420.0);
                let Some((x, y)) = free_spot(&[target, control], card, (vw, vh)) else {
                    continue;
                };
                let c = [x, y, x + card.0, y + card.1];
                assert!(
                    !overlaps(c, target) && !overlaps(c, control),
                    "{vw} {left}: {c:?}"
                );
                assert!(
                    c[0] >= 0.0 && c[2] <= vw && c[1] >= 0.0 && c[3] <= vh,
                    "{c:?}"
                );
            }
        }
        // Nothing to keep clear: no spot to look for.
        assert_eq!(free_spot(&[], (10.0, 10.0), (100.0, 100.0)), None);
    }

    /// Every step sets real keys to values they accept, and points at a
    /// part of the page that exists.
    #[test]
    fn every_step_sets_real_settings_and_points_at_the_page() {
        let html = include_str!("../../../index.html");
        assert!((4..=6).contains(&TOUR.len()));
        let controls: Vec<String> = figures::controls::controls()
            .iter()
            .map(|c| format!("control-{}", c.key))
            .collect();
        for s in TOUR {
            assert!(
                html.contains(&format!("id=\"{}\"", s.target)),
                "{}",
                s.target
            );
            // What the card leaves in view: parts of the page or controls.
            for id in s.keep_clear {
                let there =
                    html.contains(&format!("id=\"{id}\"")) || controls.contains(&id.to_string());
                assert!(there, "{id}");
            }
            if let Some(c) = s.control {
                assert!(
                    s.keep_clear.contains(&format!("control-{c}").as_str()),
                    "{c}"
                );
            }
            for (k, v) in s.set {
                let mut settings = figures::settings::Settings::default();
                let ok = if figures::settings::view_key(k).is_some() {
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

    /// The page opens on a periodic state, and the tour's first step, which
    /// sets it, says what it is: at the default Ω the plotted mesh's motion is
    /// period 1, found exactly, without impact, as the step's text claims.
    #[test]
    fn the_page_opens_on_the_periodic_state_the_first_tour_step_explains() {
        use figures::protocol::{Motion, Regime, RunOptions};
        use worker::jobs::omega::{omega_result, selected_spec, OmegaJob};
        let step = &crate::tour::TOUR[0];
        let omega = figures::settings::DEFAULT_OMEGA.to_string();
        assert!(
            step.set.contains(&("omega", omega.as_str())),
            "{:?}",
            step.set
        );
        assert!(step.text.contains(&format!("Ω {omega}")), "{}", step.text);
        let s = figures::settings::Settings::default();
        let model = solver::model::Model::new(&s.params).expect("model");
        let run = RunOptions {
            transient_periods: s.view.transient_periods,
            record_periods: s.view.record_periods,
        };
        let job = OmegaJob {
            id: 1,
            spec: selected_spec(&s, &model, run),
            model,
        };
        let r = omega_result(&job, None).expect("the steady state");
        assert!(
            matches!(r.motion, Motion::PeriodicExact { period: 1, .. }),
            "{:?}",
            r.motion
        );
        assert_eq!(r.regime, Regime::NoImpact);
        // What the step claims, in the summary's words too.
        assert!(
            step.text.contains("stay in contact")
                && step.text.contains("repeats exactly every mesh period")
        );
        let summary = figures::views::omega::student_summary(&r);
        assert!(
            summary.contains("stay in contact")
                && summary.contains("repeats exactly every mesh period"),
            "{summary}"
        );
    }

    /// Every step keeps the speed axes the reader chose, and with the
    /// axes in rpm its words give each speed in rpm first, the input's
    /// rpm at that Ω (Ω times the model's rpm per Ω), the Ω beside it.
    #[test]
    fn the_steps_keep_the_rpm_axes_and_say_their_speeds_in_rpm() {
        use crate::controller::Controller;
        let (mut c, _) = Controller::new("axis=rpm", 0.0);
        for step in 0..TOUR.len() {
            c.tour_go(Some(step), 0.0);
            assert_eq!(c.settings().view.axis, figures::speed::AxisUnit::Rpm);
            assert!(c.query().contains("axis=rpm"), "{}", c.query());
        }
        let axis = c.speed_axis();
        let per_omega = axis.rpm_scale().expect("rpm").rpm(1.0);
        let text = in_speed(TOUR[2].text, &axis);
        let rpm = figures::speed::grouped(1.4 * per_omega);
        assert!(
            text.contains(&format!("backlash 20 µm and {rpm} rpm (Ω 1.4)."))
                && !text.contains("and Ω"),
            "{text}"
        );
        let done = in_speed(TOUR[3].done, &axis);
        let rpm = figures::speed::grouped(0.5 * per_omega);
        assert_eq!(
            done,
            format!("the selected speed is below {rpm} rpm (Ω 0.5), where the motion repeats.")
        );
        // In Ω the words are as written.
        let omega = figures::speed::SpeedAxis::default();
        for s in &TOUR {
            assert_eq!(in_speed(s.text, &omega), s.text);
        }
        // A Ω without a number is left as it is.
        assert_eq!(in_speed("one dot per Ω here", &axis), "one dot per Ω here");
    }
}
