//! What the page says about the controller's state in words: each view's
//! status and text alternative, the student summary and the expert details,
//! what a view without data shows, the messages box and the highlighted mesh.

use super::*;
use figures::views::ViewId;

impl Controller {
    /// The method of `ViewId::Fr` in words.
    pub fn fr_method(&self) -> String {
        FrSource::Hbm {
            harmonics: self.main.hbm.harmonics,
        }
        .label()
    }

    /// The status of the job whose data `view` shows.
    pub fn view_status(&self, view: figures::views::ViewId) -> &JobStatus {
        self.main.status(view.spec().data)
    }

    /// The status that paces `view`'s redraws: its data's job while that
    /// runs, else the first running job among the others it draws (the
    /// shooting branches over a finished bifurcation diagram, the
    /// boundaries over a finished map), so that their points, which
    /// arrive every few tens of milliseconds, redraw it at most every
    /// [`crate::page::redraw::RUNNING_REDRAW_MS`] as the data's own points do.
    pub fn redraw_status(&self, view: figures::views::ViewId) -> &JobStatus {
        let data = self.view_status(view);
        if data.running() {
            return data;
        }
        view.spec()
            .shows
            .iter()
            .map(|k| self.main.status(k))
            .find(|s| s.running())
            .unwrap_or(data)
    }

    /// The text alternative of a view's canvas (its `aria-label`), from
    /// the data it draws.
    pub fn canvas_label(&self, view: figures::views::ViewId) -> String {
        use figures::views::labels;
        let title = view.spec().title;
        if view == ViewId::Campbell {
            return self.campbell_label();
        }
        match view {
            ViewId::Dynamic => self.dynamic_label(),
            ViewId::Orders => self.orders_label(),
            ViewId::Fr if self.panels.is_some() => labels::fr_panels_label(&self.fr_panels()),
            ViewId::Fr => labels::fr_label(&self.fr_view()),
            ViewId::Bif => labels::bif_label(&self.bif_view()),
            ViewId::Map => labels::map_label(&self.main.map, &self.speed_axis()),
            ViewId::Lyap => labels::lyap_label(
                &self.main.lyap.curve(),
                self.main.lyap.linear,
                &self.speed_axis(),
            ),
            ViewId::Phase
            | ViewId::Poincare
            | ViewId::Time
            | ViewId::Spectrum
            | ViewId::Campbell => match (&self.main.omega, &self.main.omega_status().error) {
                (_, Some(e)) => format!("{title}: not computed: {e}"),
                (Some(r), None) => labels::omega_label(title, r),
                (None, None) => format!("{title}: computing."),
            },
        }
    }

    /// The text alternative of the gear-set animation.
    pub fn anim_label(&self) -> String {
        match &self.main.omega {
            Some(r) => format!(
                "The gear set in slow motion at Ω {}, each mesh coloured by its contact state; mesh {}: {}.",
                figures::views::unstable::short(r.omega),
                r.mesh_name,
                figures::story::contact_tag(r.regime, r.backlash_um)
            ),
            None => "The gear set in slow motion: computing the motion.".into(),
        }
    }

    /// The two-sentence summary for students at the selected Omega (the
    /// regime, whether the motion repeats, the dynamic factor explained);
    /// the expert figures are [`Controller::summary_text`].
    pub fn student_summary(&self) -> String {
        let text = match (&self.main.omega, &self.main.omega_status().error) {
            (_, Some(e)) => format!("Not computed: {e}"),
            (Some(r), None) => {
                let mut s = figures::views::omega::student_summary_at(r, &self.speed_axis());
                if let Some(more) = self.branch_agreement() {
                    s.push(' ');
                    s.push_str(&more);
                }
                s
            }
            (None, None) => "Computing the motion at the selected speed…".into(),
        };
        match &self.family {
            Some(f) => format!(
                "{}: {text} The other curves' motions are in the panels' titles.",
                figures::words::capitalize(&f.spec.label(0))
            ),
            None => text,
        }
    }

    /// What the frequency response's branch says at the selected Ω, where
    /// it tells another story than the steady state found there (see
    /// [`figures::story::branch_agreement`]); `None` while either computes.
    pub fn branch_agreement(&self) -> Option<String> {
        let r = self.main.omega.as_ref().filter(|r| !r.preview)?;
        if !self.main.hbm.finished {
            return None;
        }
        let v = self.fr_view();
        let br = figures::views::unstable::current_branch(&v)?;
        let at = figures::views::unstable::branch_at(&br.points, r.omega);
        figures::story::branch_agreement(r.motion, at)
    }

    /// The summary line at the selected Omega: the result's figures and the
    /// planet phasing clause, or why there is none yet; the model's warnings.
    pub fn summary_text(&self) -> String {
        let natural = self.view_context().natural;
        let text = match (&self.main.omega, &self.main.omega_status().error) {
            (_, Some(e)) => format!("Not computed: {e}"),
            (Some(r), None) => {
                let mut s = figures::views::omega::summary_line(r, &natural);
                if let Ok(m) = &self.model {
                    let line =
                        figures::views::omega::phasing_line(m, &self.settings.params, Some(r));
                    if let Some(line) = line {
                        s.push(' ');
                        s.push_str(&line);
                    }
                }
                if self.main.omega_status().running() && !r.preview {
                    s.push_str(" Updating…");
                }
                s
            }
            (None, None) => "Computing the steady state at the selected speed…".into(),
        };
        match &self.model {
            Ok(m) if !m.system.warnings.is_empty() => {
                format!("{text} Model warnings: {}", m.system.warnings.join("; "))
            }
            _ => text,
        }
    }

    /// What `view` shows instead of a plot, if it has nothing to plot: why
    /// (its job failed before any data, it waits for the workers, it is
    /// switched off, its first result is computing).
    pub fn placeholder(&self, view: figures::views::ViewId) -> Option<String> {
        let st = self.view_status(view);
        let not_computed = |e: &String| format!("Not computed: {e}");
        match view {
            ViewId::Campbell => self
                .campbell_view()
                .err()
                .map(|e| not_computed(&e.to_string())),
            ViewId::Dynamic => self
                .dynamic_view()
                .err()
                .map(|e| not_computed(&e.to_string())),
            ViewId::Fr => {
                let e = st.error.as_ref()?;
                let v = self.fr_view();
                let has_data =
                    v.branches.iter().any(|b| !b.points.is_empty()) || !v.overlay.is_empty();
                (!has_data).then(|| not_computed(e))
            }
            ViewId::Bif => st
                .error
                .as_ref()
                .filter(|_| self.main.bif.samples.is_empty())
                .map(not_computed),
            ViewId::Map => (self.main.map.done == 0
                && (st.error.is_some() || self.main.map.grid.is_none()))
            .then(|| {
                st.error
                    .as_ref()
                    .map_or_else(|| "Waiting for the Web Workers…".to_string(), not_computed)
            }),
            ViewId::Lyap if !self.settings.view.lyap_on() => Some(
                "Off: set Lyapunov speed points above 0 (Regime map and Lyapunov exponent).".into(),
            ),
            ViewId::Lyap => st
                .error
                .as_ref()
                .filter(|_| self.main.lyap.points.is_empty())
                .map(not_computed),
            ViewId::Phase | ViewId::Poincare | ViewId::Time | ViewId::Spectrum | ViewId::Orders => {
                match (&self.main.omega, &st.error) {
                    (_, Some(e)) => Some(not_computed(e)),
                    (None, None) => Some(figures::views::omega::computing_message(
                        self.settings.view.omega,
                    )),
                    (Some(_), None) => None,
                }
            }
        }
    }

    /// The messages box's text: the first eight messages, how many more,
    /// and how to dismiss them; empty when there is none.
    pub fn messages_text(&self) -> String {
        let issues = &self.issues;
        if issues.is_empty() {
            return String::new();
        }
        let shown: Vec<&str> = issues.iter().take(8).map(String::as_str).collect();
        let mut text = shown.join("\n");
        if issues.len() > 8 {
            text.push_str(&format!("\n… and {} more", issues.len() - 8));
        }
        text.push_str("\n(click to dismiss)");
        text
    }

    /// The mesh the schematic highlights: the chosen one, or the worst of
    /// the last result.
    pub fn highlighted_mesh(&self) -> String {
        match (&self.settings.view.mesh, &self.main.omega) {
            (MeshSel::Named(n), _) => n.clone(),
            (MeshSel::Worst, Some(r)) => r.mesh_name.clone(),
            _ => String::new(),
        }
    }
}
