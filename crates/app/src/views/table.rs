//! The one table of views: every part of the page (canvases, export bars,
//! progress bars, file names, draw order, the tests' status arrays) names a
//! view by its [`ViewId`] and reads the rest from [`VIEWS`].

/// A view drawn from the controller's state. The discriminant is the view's
/// slot in the page's per-view arrays (the tests' status: `draws`,
/// `last_draw_ms`, ...).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum ViewId {
    /// 1. Frequency response (harmonic balance, with the time-integration overlay).
    Fr,
    /// 2. Bifurcation diagram.
    Bif,
    /// 3. Phase portrait at the selected Omega.
    Phase,
    /// 4. Poincaré section at the selected Omega.
    Poincare,
    /// 5a. Time history at the selected Omega.
    Time,
    /// 5b. Spectrum at the selected Omega.
    Spectrum,
    /// 7. Impact-regime map.
    Map,
    /// 2b. Largest Lyapunov exponent over Omega (under the bifurcation diagram).
    Lyap,
}

/// Which job's data a view shows, and so which exports it offers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ExportKind {
    /// The harmonic-balance branch and the overlay.
    Fr,
    /// The bifurcation sweep (also as `gearshock bifurcation` JSON).
    Bif,
    /// The selected-Omega steady state (also as `gearshock simulate` JSON).
    Omega,
    /// The impact-regime map.
    Map,
    /// The Lyapunov curve.
    Lyap,
}

/// What the page needs to know about a view.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ViewSpec {
    /// The view.
    pub id: ViewId,
    /// Its key in element ids (`canvas-KEY`, `exports-KEY`, `progress-KEY`)
    /// and file names (`gearshock-KEY-MESH.csv`).
    pub key: &'static str,
    /// Its number on the page.
    pub number: &'static str,
    /// Its title (the heading starts with it; the plot's title when it has no data).
    pub title: &'static str,
    /// Whose data it shows.
    pub data: ExportKind,
    /// Whether its job streams points (redraws are then throttled while it runs).
    pub progressive: bool,
}

/// Every view, in [`ViewId`] order.
pub const VIEWS: [ViewSpec; 8] = [
    ViewSpec {
        id: ViewId::Fr,
        key: "fr",
        number: "1",
        title: "Frequency response",
        data: ExportKind::Fr,
        progressive: true,
    },
    ViewSpec {
        id: ViewId::Bif,
        key: "bif",
        number: "2",
        title: "Bifurcation diagram",
        data: ExportKind::Bif,
        progressive: true,
    },
    ViewSpec {
        id: ViewId::Phase,
        key: "phase",
        number: "3",
        title: "Phase portrait",
        data: ExportKind::Omega,
        progressive: false,
    },
    ViewSpec {
        id: ViewId::Poincare,
        key: "poincare",
        number: "4",
        title: "Poincaré section",
        data: ExportKind::Omega,
        progressive: false,
    },
    ViewSpec {
        id: ViewId::Time,
        key: "time",
        number: "5a",
        title: "Time history",
        data: ExportKind::Omega,
        progressive: false,
    },
    ViewSpec {
        id: ViewId::Spectrum,
        key: "spectrum",
        number: "5b",
        title: "Spectrum",
        data: ExportKind::Omega,
        progressive: false,
    },
    ViewSpec {
        id: ViewId::Map,
        key: "map",
        number: "7",
        title: "Impact-regime map",
        data: ExportKind::Map,
        progressive: true,
    },
    ViewSpec {
        id: ViewId::Lyap,
        key: "lyap",
        number: "2b",
        title: "Largest Lyapunov exponent",
        data: ExportKind::Lyap,
        progressive: true,
    },
];

/// The order in which dirty views are drawn: the views a slider drag
/// watches first (the frequency response, then the phase portrait).
pub const DRAW_ORDER: [ViewId; 8] = [
    ViewId::Fr,
    ViewId::Phase,
    ViewId::Bif,
    ViewId::Poincare,
    ViewId::Time,
    ViewId::Spectrum,
    ViewId::Lyap,
    ViewId::Map,
];

impl ViewId {
    /// Every view, in slot order.
    pub const ALL: [ViewId; 8] = [
        ViewId::Fr,
        ViewId::Bif,
        ViewId::Phase,
        ViewId::Poincare,
        ViewId::Time,
        ViewId::Spectrum,
        ViewId::Map,
        ViewId::Lyap,
    ];

    /// The view's slot in per-view arrays.
    pub fn slot(self) -> usize {
        self as usize
    }

    /// The view's entry in [`VIEWS`].
    pub fn spec(self) -> &'static ViewSpec {
        &VIEWS[self.slot()]
    }

    /// The view's key (element ids, file names).
    pub fn key(self) -> &'static str {
        self.spec().key
    }

    /// The heading: number and title.
    pub fn heading(self) -> String {
        format!("{}. {}", self.spec().number, self.spec().title)
    }

    /// The progress bar's label at `done` of `total`.
    pub fn progress_label(self, done: usize, total: usize) -> String {
        match self.spec().data {
            ExportKind::Fr => format!("harmonic balance: {done}% of the Ω range"),
            ExportKind::Bif | ExportKind::Lyap => format!("computing {done}/{total} points"),
            ExportKind::Map => format!("computing {done}/{total} cells"),
            ExportKind::Omega => "computing…".into(),
        }
    }

    /// The CLI-format export's button title, for the views that have one.
    pub fn cli_export_title(self) -> Option<&'static str> {
        match self.spec().data {
            ExportKind::Bif => Some("The sweep as `gearshock bifurcation` JSON (the CLI's format)"),
            ExportKind::Omega => Some("This run as `gearshock simulate` JSON (the CLI's format)"),
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
