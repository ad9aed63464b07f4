//! Exports, in one room: each view's data as CSV or JSON, the CLI-format
//! JSON (the bifurcation sweep assembled from the workers' shards), the
//! parameters file and the CLI commands; a family's exports, one entry per
//! member (`family.rs`); every view as SVG, also rasterized for the PNG
//! export (`svg.rs`).

use super::*;
use figures::views::{omega::OmegaView, ViewId};
use worker::jobs::omega::with_iso6336;

/// A data export's format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// Comma-separated values.
    Csv,
    /// JSON.
    Json,
}

impl Format {
    /// Both formats, in the export bar's order.
    pub const ALL: [Format; 2] = [Format::Csv, Format::Json];

    /// The button's label.
    pub fn label(self) -> &'static str {
        match self {
            Format::Csv => "CSV",
            Format::Json => "JSON",
        }
    }

    fn file(self) -> (&'static str, &'static str) {
        match self {
            Format::Csv => ("csv", "text/csv"),
            Format::Json => ("json", "application/json"),
        }
    }
}

/// Why an export cannot be offered now (the page says so in its status line).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ExportError {
    /// The selected-Omega views show the page's preview, not a result.
    #[error(
        "The views at the selected speed show a preview; export once the full steady state has arrived."
    )]
    Preview,
    /// The selected-Omega steady state has not arrived yet.
    #[error(
        "The steady state at the selected speed is still computing; export once it has arrived."
    )]
    NotComputed,
    /// The bifurcation sweep is still running.
    #[error("the bifurcation sweep has not finished yet")]
    SweepRunning,
    /// The view has no CLI-format export.
    #[error("this view has no CLI-format export")]
    NoCliFormat,
    /// The model's natural frequencies cannot be computed.
    #[error("the natural frequencies cannot be computed: {0}")]
    Modes(figures::views::ViewError),
    /// The standard cannot rate the mesh (or the model cannot be built).
    #[error("the dynamic factor cannot be computed: {0}")]
    Rating(figures::views::ViewError),
    /// The data could not be written as JSON.
    #[error("cannot write the JSON: {0}")]
    Json(String),
}

pub(super) fn json_text(r: Result<String, serde_json::Error>) -> Result<String, ExportError> {
    r.map_err(|e| ExportError::Json(e.to_string()))
}

impl Controller {
    /// The selected-Omega result, if it is exportable (not a preview).
    pub(super) fn exportable_omega(&self) -> Result<&OmegaResult, ExportError> {
        match &self.main.omega {
            Some(r) if r.preview => Err(ExportError::Preview),
            Some(r) => Ok(r),
            None => Err(ExportError::NotComputed),
        }
    }

    /// The data behind `view` as a file in `format`.
    pub fn export(&self, view: ViewId, format: Format) -> Result<Effect, ExportError> {
        let csv = format == Format::Csv;
        let text = match view {
            ViewId::Campbell => self.campbell_export(csv).map_err(ExportError::Modes)?,
            ViewId::Dynamic => self.dynamic_export(csv).map_err(ExportError::Rating)?,
            ViewId::Orders => {
                self.exportable_omega()?;
                self.orders_export(csv)
                    .map_err(|_| ExportError::NotComputed)?
            }
            ViewId::Fr if self.panels.is_some() => self.fr_panels_export(csv)?,
            ViewId::Fr => {
                let v = self.fr_view();
                if csv {
                    figures::views::fr::fr_csv(&v)
                } else {
                    json_text(serde_json::to_string_pretty(&v))?
                }
            }
            // A family: every member, named.
            ViewId::Bif if self.family.is_some() => self.family_bif_export(csv)?,
            ViewId::Bif => {
                let v = self.bif_view();
                if csv {
                    figures::views::bif::bif_csv(&v)
                } else {
                    json_text(serde_json::to_string(&v))?
                }
            }
            ViewId::Map if csv => figures::views::map::map_csv(&self.main.map),
            ViewId::Map => {
                let mut j = figures::views::map::map_json(&self.main.map);
                // The traced boundaries, when they are on.
                if self.settings.view.boundaries {
                    let names = self.mesh_names();
                    if let Some(o) = j.as_object_mut() {
                        o.insert(
                            "boundaries".into(),
                            figures::views::boundaries::boundaries_json(
                                &self.main.boundaries,
                                &names,
                            ),
                        );
                    }
                }
                j.to_string()
            }
            ViewId::Lyap if csv => figures::views::lyap::lyap_csv(&self.main.lyap),
            ViewId::Lyap => figures::views::lyap::lyap_json(&self.main.lyap).to_string(),
            ViewId::Phase | ViewId::Poincare | ViewId::Time | ViewId::Spectrum
                if self.family.is_some() =>
            {
                let which = OmegaView::of(view).ok_or(ExportError::NoCliFormat)?;
                self.family_omega_export(which, csv)?
            }
            ViewId::Phase | ViewId::Poincare | ViewId::Time | ViewId::Spectrum => {
                let r = self.exportable_omega()?;
                let which = OmegaView::of(view).ok_or(ExportError::NoCliFormat)?;
                if csv {
                    figures::views::omega::omega_csv(r, which)
                } else {
                    figures::views::omega::omega_json(r, which).to_string()
                }
            }
        };
        let (ext, mime) = format.file();
        Ok(Effect::Download {
            name: self.file_name(view, None, ext),
            mime: mime.into(),
            text: self.with_speed(text, csv),
        })
    }

    /// The frequency response's mesh panels: CSV with a `mesh` column
    /// before each panel's rows, or JSON with one entry per panel.
    fn fr_panels_export(&self, csv: bool) -> Result<String, ExportError> {
        let names = self.panels.clone().unwrap_or_default();
        let panels = self.fr_panels();
        if csv {
            let mut out = String::new();
            for (name, p) in names.iter().zip(&panels) {
                let Ok(v) = &p.data else { continue };
                let text = figures::views::fr::fr_csv(v);
                let mut lines = text.lines();
                if out.is_empty() {
                    out = format!("mesh,{}\n", lines.next().unwrap_or_default());
                } else {
                    lines.next();
                }
                for l in lines {
                    out.push_str(&format!("{name},{l}\n"));
                }
            }
            return Ok(out);
        }
        let entries: Vec<serde_json::Value> = names
            .iter()
            .zip(&panels)
            .map(|(name, p)| match &p.data {
                Ok(v) => serde_json::json!({ "mesh": name, "title": p.title, "view": v }),
                Err(e) => serde_json::json!({ "mesh": name, "title": p.title, "error": e }),
            })
            .collect();
        json_text(serde_json::to_string_pretty(
            &serde_json::json!({ "panels": entries }),
        ))
    }

    /// The data behind `view` in the CLI's JSON format: the selected-Omega
    /// run as `gearshock simulate` writes it (a download at once), or the
    /// bifurcation sweep, assembled from the workers' shards (messages to
    /// post at `now_ms`; the download follows their replies).
    pub fn export_cli(&mut self, view: ViewId, now_ms: f64) -> Result<Vec<Effect>, ExportError> {
        match view {
            ViewId::Bif => self.request_bif_export(now_ms),
            _ if view.at_selected_omega() => {
                let mut r = self.exportable_omega()?.clone();
                // K_v at the page's grade and face width, as `gearshock
                // simulate --accuracy-grade .. --face-width-mm ..` writes it.
                if let Ok(model) = self.model() {
                    let inputs = self.settings.view.iso_inputs();
                    with_iso6336(&mut r, &self.settings.params, model, &inputs);
                }
                Ok(vec![Effect::Download {
                    name: self.file_name(view, Some("simulate"), "json"),
                    mime: "application/json".into(),
                    text: r.cli_json,
                }])
            }
            _ => Err(ExportError::NoCliFormat),
        }
    }

    /// The parameters as the CLI's `--params` file.
    pub fn export_params(&self) -> Effect {
        Effect::Download {
            name: "gearshock-params.json".into(),
            mime: "application/json".into(),
            text: self.params_json(),
        }
    }

    /// Starts assembling the bifurcation JSON in the CLI's format: every
    /// worker but the first sends its shards, then worker 0 (which holds
    /// chain 0) merges them with its own.
    fn request_bif_export(&mut self, now_ms: f64) -> Result<Vec<Effect>, ExportError> {
        if self.main.bif_status().finished_ms.is_none() {
            return Err(ExportError::SweepRunning);
        }
        let (mesh, _) = self.mesh_and_backlash();
        let id = self.main.bif_status().id;
        let chains = chain_count(self.settings.view.bif_points);
        let holders: Vec<usize> = (1..self.workers())
            .filter(|&w| self.chains_on(w, chains) > 0)
            .collect();
        self.export = Some(PendingExport {
            id,
            mesh,
            collected: Vec::new(),
            expected: chains as usize - self.chains_on(0, chains),
        });
        let msg = ToWorker::ExportBif {
            id,
            mesh,
            other: Vec::new(),
        };
        if holders.is_empty() {
            return Ok(self.post(0, &msg, now_ms));
        }
        Ok(holders
            .into_iter()
            .flat_map(|w| self.post(w, &msg, now_ms))
            .collect())
    }

    pub(super) fn export_reply(
        &mut self,
        worker: usize,
        id: JobId,
        text: String,
        now_ms: f64,
    ) -> Vec<Effect> {
        let Some(pending) = self.export.as_mut().filter(|e| e.id == id) else {
            return Vec::new();
        };
        if worker == 0 {
            self.export = None;
            return vec![Effect::Download {
                name: self.file_name(ViewId::Bif, Some("bifurcation"), "json"),
                mime: "application/json".into(),
                text,
            }];
        }
        // A worker with several shards sends them as a JSON array.
        match serde_json::from_str::<serde_json::Value>(&text) {
            Ok(serde_json::Value::Array(shards)) => pending
                .collected
                .extend(shards.iter().map(serde_json::Value::to_string)),
            _ => pending.collected.push(text),
        }
        if pending.collected.len() < pending.expected {
            return Vec::new();
        }
        let msg = ToWorker::ExportBif {
            id,
            mesh: pending.mesh,
            other: std::mem::take(&mut pending.collected),
        };
        self.post(0, &msg, now_ms)
    }

    /// An export's file name: the view, what the file holds if the view
    /// has two formats of it (`simulate`, `bifurcation`: the CLI's), the
    /// plotted mesh, Ω for the views of the selected Ω, and the family's
    /// key and values if one is shown, so that no two files of different
    /// states share a name: `gearshock-phase-simulate-s1a1-omega0.84.json`,
    /// `gearshock-fr-s1a1-te_um-0_20_30.png`.
    pub fn file_name(&self, view: ViewId, what: Option<&str>, ext: &str) -> String {
        let mut name = format!("gearshock-{}", view.key());
        if let Some(w) = what {
            name.push('-');
            name.push_str(w);
        }
        name.push('-');
        name.push_str(self.settings.view.mesh.text());
        if view.at_selected_omega() {
            let omega = self
                .main
                .omega
                .as_ref()
                .map_or(self.settings.view.omega, |r| r.omega);
            name.push_str(&format!("-omega{}", figures::settings::fmt_exact(omega)));
        }
        if let Some(f) = &self.family {
            let values: Vec<String> = f
                .spec
                .values
                .iter()
                .map(|x| figures::settings::fmt_exact(*x))
                .collect();
            name.push_str(&format!("-{}-{}", f.spec.key.key, values.join("_")));
        }
        format!("{name}.{ext}")
    }

    /// The CLI commands that reproduce the current views natively.
    pub fn cli_commands(&self) -> String {
        let v = &self.settings.view;
        let mesh = match (&self.model, &v.mesh) {
            (_, MeshSel::Named(n)) => n.clone(),
            (Ok(m), MeshSel::Worst) => self
                .main
                .omega
                .as_ref()
                .map_or_else(|| m.system.meshes[0].name.clone(), |r| r.mesh_name.clone()),
            (Err(_), MeshSel::Worst) => "s1a1".into(),
        };
        let chains = chain_count(v.bif_points);
        let frf_mesh = match &v.mesh {
            MeshSel::Named(n) => n.as_str(),
            MeshSel::Worst => "all",
        };
        // K_v's inputs where the page's differ from the defaults (which
        // are the command line's).
        let d = figures::settings::ViewOptions::default();
        let mut iso = String::new();
        if v.accuracy_grade != d.accuracy_grade {
            iso.push_str(&format!(" --accuracy-grade {}", v.accuracy_grade));
        }
        if v.face_width_mm != d.face_width_mm {
            iso.push_str(&format!(" --face-width-mm {}", v.face_width_mm));
        }
        format!(
            "gearshock frf --params gearshock-params.json --omega-from {} --omega-to {} --points {} --harmonics {} --mesh {frf_mesh}{iso}\n\
             gearshock simulate --params gearshock-params.json --omega {} --mesh {mesh} --transient-periods {} --record-periods {}{iso}\n\
             gearshock bifurcation --params gearshock-params.json --omega-from {} --omega-to {} --points {} --direction {} --transient-periods {} --record-periods {} --mesh {} --chains {chains}",
            v.omega_from,
            v.omega_to,
            v.fr_points,
            v.harmonics,
            v.omega,
            v.transient_periods,
            v.record_periods,
            v.omega_from,
            v.omega_to,
            v.bif_points,
            v.bif_dir.name(),
            v.transient_periods,
            v.record_periods,
            match &v.mesh {
                MeshSel::Named(n) => n.as_str(),
                MeshSel::Worst => "all",
            }
        )
    }

    /// The parameters as the CLI's `--params` JSON.
    pub fn params_json(&self) -> String {
        // `{:#}` is serde_json's pretty printer, which cannot fail on a Value.
        format!(
            "{:#}",
            serde_json::Value::Object(keys::to_json(&self.settings.params))
        )
    }
}

mod members;
mod svg;
pub use svg::{view_size, Drawn, SvgError};

#[cfg(test)]
mod tests {
    use crate::controller::Controller;

    /// Every export's file name says which view, mesh, Ω and family it
    /// holds: files of different states never overwrite each other, and the
    /// four views of the selected Ω save their command-line JSON apart.
    #[test]
    fn export_names_carry_the_view_the_mesh_omega_and_the_family() {
        use figures::views::ViewId;
        let (c, _) = Controller::new("omega=0.84&mesh=s2b1", 0.0);
        assert_eq!(
            c.file_name(ViewId::Fr, None, "csv"),
            "gearshock-fr-s2b1.csv"
        );
        assert_eq!(
            c.file_name(ViewId::Phase, None, "png"),
            "gearshock-phase-s2b1-omega0.84.png"
        );
        let cli: Vec<String> = [
            ViewId::Phase,
            ViewId::Poincare,
            ViewId::Time,
            ViewId::Spectrum,
        ]
        .iter()
        .map(|&v| c.file_name(v, Some("simulate"), "json"))
        .collect();
        assert_eq!(cli[0], "gearshock-phase-simulate-s2b1-omega0.84.json");
        let mut distinct = cli.clone();
        distinct.dedup();
        assert_eq!(distinct.len(), 4, "{cli:?}");
        let (f, _) = Controller::new("family=te_um:0,20,30", 0.0);
        assert_eq!(
            f.file_name(ViewId::Bif, Some("bifurcation"), "json"),
            "gearshock-bif-bifurcation-s1a1-te_um-0_20_30.json"
        );
    }
}
