//! A view as an SVG picture: the same plotters drawing functions as the
//! canvases, on plotters' SVG backend (for slides and papers; the page
//! also rasterizes it at twice the size for its PNG export).

use super::super::*;
use super::ExportError;
use figures::plots::maps::{self, MapOverlay};
use figures::plots::{self, DrawError, PlotFrame, PointGroup};
use figures::views::fr::FrView;
use figures::views::ViewId;
use plotters::coord::Shift;
use plotters::prelude::*;

/// A view's drawing size in pixels (its canvas's size on the page).
pub fn view_size(view: ViewId) -> (u32, u32) {
    match view {
        ViewId::Map => (plots::WIDTH, 460),
        ViewId::Lyap => (plots::WIDTH, 300),
        _ => (plots::WIDTH, plots::HEIGHT),
    }
}

/// Why a view cannot be drawn as SVG now.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SvgError {
    /// The view's data is not there yet (the selected-Ω motion computing).
    #[error(transparent)]
    NotReady(#[from] ExportError),
    /// The drawing itself failed.
    #[error(transparent)]
    Draw(#[from] DrawError),
}

/// What [`Controller::plot`] leaves to its caller: the plot frame
/// that maps pixels to data (the views one clicks on), and what a canvas
/// fills faster itself than plotters does: the bifurcation dots and the
/// map's cells.
#[derive(Debug, Clone, Default)]
pub struct Drawn {
    /// The plot's frame (the first panel's, for small multiples).
    pub frame: Option<PlotFrame>,
    /// The bifurcation diagram's dots, by colour and shape.
    pub dots: Vec<PointGroup>,
    /// The map's cells, period dots and cursor.
    pub map: Option<MapOverlay>,
}

impl Controller {
    /// A view's drawing size now: [`Self::base_canvas_size`], the frequency
    /// response taller where its key is long ([`plots::fr_height`]).
    pub fn canvas_size(&self, view: ViewId) -> (u32, u32) {
        let size = self.base_canvas_size(view);
        if view == ViewId::Fr && self.panels.is_none() {
            (size.0, plots::fr_height(&self.fr_view(), size))
        } else {
            size
        }
    }

    /// A view's drawing size before its key is laid out: [`view_size`],
    /// except the frequency response's mesh panels and a large family's
    /// small multiples, which take a taller canvas.
    pub fn base_canvas_size(&self, view: ViewId) -> (u32, u32) {
        let family = self.family.as_ref().map(|f| f.members.len() + 1);
        match (&self.panels, family, view) {
            (Some(p), _, ViewId::Fr) => plots::multiples::fr_panels_size(p.len()),
            (_, Some(n), ViewId::Bif | ViewId::Phase | ViewId::Poincare) => {
                plots::multiples::family_panels_size(n)
            }
            _ => view_size(view),
        }
    }

    /// The parts the page draws `view` in, one an animation frame: a
    /// family's phase portraits and Poincaré sections a panel each (six
    /// long orbits drawn at once were the page's longest main-thread
    /// task), every other view whole (1).
    pub fn parts(&self, view: ViewId) -> usize {
        match (view, &self.family) {
            (ViewId::Phase | ViewId::Poincare, Some(f)) => f.spec.values.len().max(1),
            _ => 1,
        }
    }

    /// Draws `view` on any plotters backend, as the page and the SVG
    /// export both do, with `status` after its title (the page's progress
    /// caption; empty for a file) and, for the frequency response, its
    /// view model `fr` if the caller built it already. What the backend
    /// draws faster itself is returned, not drawn: the bifurcation dots and
    /// the map's cells ([`Drawn`]). `part` draws one of a view's parts
    /// ([`Self::parts`]); `None` draws it whole.
    pub fn plot<DB: DrawingBackend>(
        &self,
        view: ViewId,
        root: &DrawingArea<DB, Shift>,
        status: &str,
        fr: Option<&FrView>,
        part: Option<usize>,
    ) -> Result<Drawn, SvgError> {
        let natural = self.view_context().natural;
        let v = &self.settings.view;
        let whole = v.whole_clearance;
        let first = |frames: Vec<Option<PlotFrame>>| frames.into_iter().flatten().next();
        let mut d = Drawn::default();
        match view {
            ViewId::Campbell => {
                let c = self.campbell_view().map_err(plots::err)?;
                d.frame = Some(plots::campbell::draw_campbell(root, &c, status)?);
            }
            ViewId::Orders => {
                let v = self.orders_view().map_err(plots::err)?;
                plots::orders::draw_orders(root, &v, status)?;
            }
            ViewId::Dynamic => {
                let v = self.dynamic_view().map_err(plots::err)?;
                d.frame = Some(plots::dynamic::draw_dynamic(
                    root,
                    &v,
                    status,
                    &self.speed_axis(),
                )?);
            }
            // Clicks pick Omega on the first panel's axis (all share it).
            ViewId::Fr if self.panels.is_some() => {
                d.frame = first(plots::multiples::draw_fr_panels(
                    root,
                    &self.fr_panels(),
                    status,
                )?);
            }
            ViewId::Fr => {
                let own;
                let fr = match fr {
                    Some(fr) => fr,
                    None => {
                        own = self.fr_view();
                        &own
                    }
                };
                d.frame = Some(plots::draw_fr(root, fr, status)?);
            }
            // A family: its small multiples.
            ViewId::Bif if self.family.is_some() => {
                let mesh = self.view_context().mesh_label;
                let (frames, dots) =
                    plots::multiples::draw_bif_panels(root, &self.bif_panels(), &mesh, status)?;
                (d.frame, d.dots) = (first(frames), dots);
            }
            ViewId::Bif => {
                let (frame, dots) = plots::draw_bif(root, &self.bif_view(), &natural, status)?;
                (d.frame, d.dots) = (Some(frame), dots);
            }
            ViewId::Map => {
                let (f, o) = maps::draw_map(root, &self.map_view(), status)?;
                (d.frame, d.map) = (Some(f), Some(o));
            }
            ViewId::Lyap => {
                let range = (v.omega_from, v.omega_to);
                d.frame = Some(maps::draw_lyap(
                    root,
                    &self.main.lyap,
                    range,
                    &natural,
                    v.omega,
                    &self.speed_axis(),
                    status,
                )?);
            }
            ViewId::Phase | ViewId::Poincare if self.family.is_some() => {
                let poincare = view == ViewId::Poincare;
                let n = self.family.as_ref().map_or(0, |f| f.spec.values.len());
                let panels = self.omega_panels(if poincare { n } else { 0 });
                plots::multiples::draw_phase_panels(root, &panels, poincare, status, part)?;
            }
            ViewId::Phase | ViewId::Poincare | ViewId::Time | ViewId::Spectrum => {
                let r = self.main.omega.as_ref().ok_or(ExportError::NotComputed)?;
                match view {
                    ViewId::Phase => plots::draw_phase_with(root, r, status, whole)?,
                    ViewId::Poincare => plots::draw_poincare_with(root, r, status, whole)?,
                    ViewId::Time => d.frame = Some(plots::draw_time_with(root, r, status, whole)?),
                    _ => plots::draw_spectrum(root, r, status)?,
                }
            }
        }
        Ok(d)
    }

    /// The view drawn as SVG text, as the page shows it (without the
    /// progress captions).
    pub fn plot_svg(&self, view: ViewId) -> Result<String, SvgError> {
        let size = self.canvas_size(view);
        let mut s = String::new();
        let d = {
            let root = SVGBackend::with_string(&mut s, size).into_drawing_area();
            let d = self.plot(view, &root, "", None, None)?;
            root.present().map_err(plots::err)?;
            d
        };
        // What the canvas fills itself goes inside the closed chart.
        Ok(match (d.frame, &d.map) {
            (Some(f), Some(o)) => {
                plots::svg_with(&s, size, |root| maps::draw_map_overlay(root, &f, o))?
            }
            _ if !d.dots.is_empty() => plots::svg_with_dots(&s, size, &d.dots)?,
            _ => s,
        })
    }

    /// The view as an SVG file to download.
    pub fn export_svg(&self, view: ViewId) -> Result<Effect, SvgError> {
        Ok(Effect::Download {
            name: self.file_name(view, None, "svg"),
            mime: "image/svg+xml".into(),
            text: self.plot_svg(view)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every view draws as SVG of its canvas's size with its title's words,
    /// even before any data (the message plot) — and with data, its data.
    #[test]
    fn every_view_exports_as_svg() {
        let (c, _) = Controller::new("", 0.0);
        for v in ViewId::ALL {
            match c.plot_svg(v) {
                Ok(s) => {
                    let (w, h) = view_size(v);
                    assert!(
                        s.starts_with("<svg")
                            && s.contains(&format!("width=\"{w}\""))
                            && s.contains(&format!("height=\"{h}\"")),
                        "{}",
                        v.key()
                    );
                }
                Err(e) => assert!(v.at_selected_omega(), "{}: {e}", v.key()),
            }
        }
        let (mut c, _) = Controller::new("", 0.0);
        c.worker_message(0, r#"{"type":"ready"}"#, 1.0);
        let s = c.plot_svg(ViewId::Fr).unwrap();
        assert!(s.contains("Frequency response"), "{s}");
    }
}
