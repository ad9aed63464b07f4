//! The one table of views: every part of the page (canvases, export bars,
//! progress bars, file names, draw order, the tests' status arrays) names a
//! view by its [`ViewId`] and reads the rest from [`VIEWS`].

use crate::protocol::{JobKind, KindSet};

/// A view drawn from the controller's state. The discriminant is the view's
/// slot in the page's per-view arrays (the tests' status: `draws`,
/// `last_draw_ms`, ...).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ViewId {
    /// Frequency response (harmonic balance, with the time-integration dots).
    Fr,
    /// Bifurcation diagram.
    Bif,
    /// Phase portrait at the selected Omega.
    Phase,
    /// Poincaré section at the selected Omega.
    Poincare,
    /// Time history at the selected Omega.
    Time,
    /// Spectrum at the selected Omega.
    Spectrum,
    /// Impact-regime map.
    Map,
    /// Largest Lyapunov exponent over Omega (under the bifurcation diagram).
    Lyap,
    /// Campbell diagram: natural frequencies against input speed, with the
    /// mesh orders' crossings (drawn from the model, with the selected
    /// Omega's speed, so it follows the selected-Omega job).
    Campbell,
    /// The selected mesh's dynamic factor over Omega beside K_v by ISO
    /// 6336-1 method B, and the selected state's load sharing (drawn from
    /// the sweep's or the overlay's steady states and the selected Omega's).
    Dynamic,
    /// The plotted mesh's force at the selected Omega by order of the mesh
    /// frequency, with the planets' sum.
    Orders,
}

/// What the page needs to know about a view.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ViewSpec {
    /// The view.
    pub id: ViewId,
    /// Its key in element ids (`canvas-KEY`, `exports-KEY`, `progress-KEY`)
    /// and file names (`gearshock-KEY-MESH.csv`).
    pub key: &'static str,
    /// Its title (the heading starts with it; the plot's title when it has no data).
    pub title: &'static str,
    /// The job whose data it shows and exports (its status is the view's).
    pub data: JobKind,
    /// Every job whose data it draws (a change of one redraws it).
    pub shows: KindSet,
    /// Whether its job streams points (redraws are then throttled while it runs).
    pub progressive: bool,
}

/// Every view, in [`ViewId`] order.
pub const VIEWS: [ViewSpec; 11] = [
    ViewSpec {
        id: ViewId::Fr,
        key: "fr",
        title: "Frequency response",
        data: JobKind::HarmonicBalance,
        shows: KindSet::of(&[JobKind::HarmonicBalance, JobKind::Overlay]),
        progressive: true,
    },
    ViewSpec {
        id: ViewId::Bif,
        key: "bif",
        title: "Bifurcation diagram",
        data: JobKind::Bif,
        shows: KindSet::of(&[JobKind::Bif, JobKind::Orbits]),
        progressive: true,
    },
    ViewSpec {
        id: ViewId::Phase,
        key: "phase",
        title: "Phase portrait",
        data: JobKind::Omega,
        shows: JobKind::Omega.set(),
        progressive: false,
    },
    ViewSpec {
        id: ViewId::Poincare,
        key: "poincare",
        title: "Poincaré section",
        data: JobKind::Omega,
        shows: JobKind::Omega.set(),
        progressive: false,
    },
    ViewSpec {
        id: ViewId::Time,
        key: "time",
        title: "Time history",
        data: JobKind::Omega,
        shows: JobKind::Omega.set(),
        progressive: false,
    },
    ViewSpec {
        id: ViewId::Spectrum,
        key: "spectrum",
        title: "Spectrum",
        data: JobKind::Omega,
        shows: JobKind::Omega.set(),
        progressive: false,
    },
    ViewSpec {
        id: ViewId::Map,
        key: "map",
        title: "Impact-regime map",
        data: JobKind::Map,
        shows: KindSet::of(&[JobKind::Map, JobKind::Boundaries]),
        progressive: true,
    },
    ViewSpec {
        id: ViewId::Lyap,
        key: "lyap",
        title: "Largest Lyapunov exponent",
        data: JobKind::Lyap,
        shows: JobKind::Lyap.set(),
        progressive: true,
    },
    ViewSpec {
        id: ViewId::Campbell,
        key: "campbell",
        title: "Campbell diagram",
        data: JobKind::Omega,
        shows: JobKind::Omega.set(),
        progressive: false,
    },
    ViewSpec {
        id: ViewId::Dynamic,
        key: "dynamic",
        title: "Dynamic factor",
        data: JobKind::Bif,
        shows: KindSet::of(&[JobKind::Bif, JobKind::Overlay, JobKind::Omega]),
        progressive: true,
    },
    ViewSpec {
        id: ViewId::Orders,
        key: "orders",
        title: "Mesh force by order",
        data: JobKind::Omega,
        shows: JobKind::Omega.set(),
        progressive: false,
    },
];

/// One numbered part of the page, in page order: the views of [`VIEWS`]
/// and the gear set's animation (drawn by `web::anim`, not a [`ViewId`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PagePart {
    /// The key of the part's element (`view-KEY`).
    pub key: &'static str,
    /// Its title, as in the heading.
    pub title: &'static str,
}

/// The page's numbered parts in page order: the question-answering views
/// first (what the response is, when impact becomes double-sided, when the
/// motion stops repeating), then the views of the motion at the selected
/// Omega. A part's number is its place here; `index.html` is checked
/// against it (order, headings and every "view N" in the help texts).
pub const PAGE: [PagePart; 12] = [
    PagePart {
        key: "fr",
        title: "Frequency response",
    },
    PagePart {
        key: "map",
        title: "Impact-regime map",
    },
    PagePart {
        key: "bif",
        title: "Bifurcation diagram",
    },
    PagePart {
        key: "lyap",
        title: "Largest Lyapunov exponent",
    },
    PagePart {
        key: "phase",
        title: "Phase portrait",
    },
    PagePart {
        key: "poincare",
        title: "Poincaré section",
    },
    PagePart {
        key: "time",
        title: "Time history",
    },
    PagePart {
        key: "anim",
        title: "The gear set in motion",
    },
    PagePart {
        key: "spectrum",
        title: "Spectrum",
    },
    PagePart {
        key: "campbell",
        title: "Campbell diagram",
    },
    PagePart {
        key: "dynamic",
        title: "Dynamic factor",
    },
    PagePart {
        key: "orders",
        title: "Mesh force by order",
    },
];

/// The number of the page part with key `key` (1-based), if there is one.
pub fn part_number(key: &str) -> Option<usize> {
    PAGE.iter().position(|p| p.key == key).map(|i| i + 1)
}

/// The order in which dirty views are drawn: the views a slider drag
/// watches first (the frequency response, then the phase portrait).
pub const DRAW_ORDER: [ViewId; 11] = [
    ViewId::Fr,
    ViewId::Phase,
    ViewId::Bif,
    ViewId::Poincare,
    ViewId::Time,
    ViewId::Spectrum,
    ViewId::Lyap,
    ViewId::Map,
    ViewId::Campbell,
    ViewId::Dynamic,
    ViewId::Orders,
];

impl ViewId {
    /// Every view, in slot order.
    pub const ALL: [ViewId; 11] = [
        ViewId::Fr,
        ViewId::Bif,
        ViewId::Phase,
        ViewId::Poincare,
        ViewId::Time,
        ViewId::Spectrum,
        ViewId::Map,
        ViewId::Lyap,
        ViewId::Campbell,
        ViewId::Dynamic,
        ViewId::Orders,
    ];

    /// The view's slot in per-view arrays.
    pub fn slot(self) -> usize {
        self as usize
    }

    /// Whether the view shows the selected Omega's steady state (or is
    /// drawn at it).
    pub fn at_selected_omega(self) -> bool {
        self.spec().data == JobKind::Omega
    }

    /// The view's entry in [`VIEWS`].
    pub fn spec(self) -> &'static ViewSpec {
        &VIEWS[self.slot()]
    }

    /// The view's key (element ids, file names).
    pub fn key(self) -> &'static str {
        self.spec().key
    }

    /// The view's number on the page (its place in [`PAGE`]).
    pub fn number(self) -> usize {
        part_number(self.key()).unwrap_or(0)
    }

    /// The heading: number and title.
    pub fn heading(self) -> String {
        format!("{}. {}", self.number(), self.spec().title)
    }

    /// The progress bar's label at `done` of `total`.
    pub fn progress_label(self, done: usize, total: usize) -> String {
        if self == ViewId::Dynamic {
            return format!("computing {done}/{total} steady states");
        }
        match self.spec().data {
            JobKind::HarmonicBalance | JobKind::Overlay => {
                format!("harmonic balance: {done}% of the Ω range")
            }
            JobKind::Bif | JobKind::Lyap | JobKind::Orbits => {
                format!("computing {done}/{total} points")
            }
            JobKind::Map | JobKind::Boundaries => format!("computing {done}/{total} cells"),
            JobKind::Omega => "computing…".into(),
        }
    }

    /// An export button's name, by what it exports: "Export the frequency
    /// response as CSV" (`what` is "CSV", "JSON", "a PNG image", ...).
    pub fn export_name(self, what: &str) -> String {
        let t = self.spec().title;
        let mut c = t.chars();
        // Names stay capitalized (Poincaré); other titles read in lower case.
        let lower: String = match c.next() {
            Some(f) if !t.starts_with("Poincaré") => f.to_lowercase().chain(c).collect(),
            _ => t.to_string(),
        };
        format!("Export the {lower} as {what}")
    }

    /// The CLI-format export's button title, for the views that have one.
    pub fn cli_export_title(self) -> Option<&'static str> {
        if matches!(self, ViewId::Campbell | ViewId::Dynamic) {
            return None;
        }
        match self.spec().data {
            JobKind::Bif => Some("The sweep as `gearshock bifurcation` JSON (the CLI's format)"),
            JobKind::Omega => Some("This run as `gearshock simulate` JSON (the CLI's format)"),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table is in slot order, keys are unique, and the
    /// draw order names every view once.
    #[test]
    fn the_table_is_consistent() {
        for (i, v) in VIEWS.iter().enumerate() {
            assert_eq!(v.id.slot(), i);
            assert_eq!(ViewId::ALL[i], v.id);
        }
        let mut keys: Vec<&str> = VIEWS.iter().map(|v| v.key).collect();
        keys.sort_unstable();
        keys.dedup();
        assert_eq!(keys.len(), VIEWS.len());
        let mut order: Vec<usize> = DRAW_ORDER.iter().map(|v| v.slot()).collect();
        order.sort_unstable();
        assert_eq!(order, (0..VIEWS.len()).collect::<Vec<_>>());
    }

    /// The page's parts appear in [`PAGE`] order with their numbered
    /// headings, and every "view N" of the help texts names an existing
    /// part, right after its title ("the phase portrait (view 5)").
    #[test]
    fn the_page_order_numbering_and_references_follow_the_table() {
        let html = include_str!("../../../../index.html");
        let mut last = 0;
        for (i, part) in PAGE.iter().enumerate() {
            let at = html
                .find(&format!("id=\"view-{}\"", part.key))
                .unwrap_or_else(|| panic!("index.html lacks view-{}", part.key));
            assert!(at > last, "view-{} is out of order", part.key);
            last = at;
            let heading = format!(">{}. {}", i + 1, part.title);
            assert!(html[at..].contains(&heading), "no heading {heading}");
        }
        for v in VIEWS {
            assert!(v.id.number() >= 1, "{} is not on the page", v.key);
        }
        let lower = html.to_lowercase();
        let mut refs = 0;
        for (at, _) in lower.match_indices("(view ") {
            let digits: String = lower[at + 6..]
                .chars()
                .take_while(|c| c.is_ascii_digit())
                .collect();
            let n: usize = digits.parse().expect("a number after (view");
            assert!(n >= 1 && n <= PAGE.len(), "view {n} does not exist");
            let title = PAGE[n - 1].title.to_lowercase();
            let before = &lower[at.saturating_sub(60)..at];
            assert!(
                before.contains(&title),
                "(view {n}) does not follow \"{title}\": {before}"
            );
            refs += 1;
        }
        assert!(refs >= 3, "the help texts refer to other views by number");
        assert!(!lower.contains("views 3") && !lower.contains("view 6)") && !lower.contains("5a"));
    }

    #[test]
    fn export_buttons_say_what_they_export() {
        assert_eq!(
            ViewId::Fr.export_name("CSV"),
            "Export the frequency response as CSV"
        );
        assert_eq!(
            ViewId::Poincare.export_name("a PNG image"),
            "Export the Poincaré section as a PNG image"
        );
    }

    /// The page's HTML has every view's canvas, export bar, progress bar and
    /// heading, as the table names them.
    #[test]
    fn the_page_has_every_view_of_the_table() {
        let html = include_str!("../../../../index.html");
        for v in VIEWS {
            for id in ["canvas", "exports", "progress"] {
                let needle = format!("id=\"{id}-{}\"", v.key);
                assert!(html.contains(&needle), "index.html lacks {needle}");
            }
            let heading = v.id.heading();
            assert!(
                html.contains(&format!(">{heading}")),
                "index.html lacks the heading {heading}"
            );
        }
    }
}
