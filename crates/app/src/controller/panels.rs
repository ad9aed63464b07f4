//! The frequency response's mesh panels on the page (the paper's Figs. 2
//! and 3, panels a-d): each panel is the same branches — the current
//! state's and every family member's — projected on one mesh. Every
//! harmonic-balance branch already holds every mesh's response, so the
//! panels compute nothing new.

use super::*;
use figures::panels::mesh_words;
use figures::views::multiples::{panel_titles, Panel};

impl Controller {
    /// Each frequency-response panel's (or the single plot's, `fr`)
    /// curves' first-mode peaks: name, Omega, x (µm), as the plots locate
    /// them; the tests' status reads them.
    pub(super) fn first_mode_peaks(&self, fr: &FrView) -> Vec<Vec<(String, f64, f64)>> {
        match &self.panels {
            Some(_) => self
                .fr_panels()
                .iter()
                .map(|p| {
                    p.data
                        .as_ref()
                        .map(figures::plots::fr_first_mode_peaks)
                        .unwrap_or_default()
                })
                .collect(),
            None => vec![figures::plots::fr_first_mode_peaks(fr)],
        }
    }

    /// The frequency response of each panel's mesh, titled with the mesh
    /// in words ("(a) s1a1 (small sun – short planet a1)"); empty without
    /// panels.
    pub fn fr_panels(&self) -> Vec<Panel<FrView>> {
        let Some(names) = &self.panels else {
            return Vec::new();
        };
        let words: Vec<String> = names.iter().map(|n| mesh_words(n)).collect();
        let titles = panel_titles(&words, 0);
        names
            .iter()
            .zip(titles)
            .map(|(name, title)| {
                let data = match &self.model {
                    Ok(m) => match m.system.mesh_index(name) {
                        Some(j) => Ok(self.fr_view_on(Some(j), Some(name))),
                        None => Err(format!("There is no mesh {name} in this model.")),
                    },
                    Err(e) => Err(e.to_string()),
                };
                Panel { title, data }
            })
            .collect()
    }
}
