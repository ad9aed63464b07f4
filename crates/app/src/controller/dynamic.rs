//! The dynamic factor on the page: its view model from the current model,
//! the frequency response's steady states and the selected state, its
//! text alternative, its note and its exports.

use super::Controller;
use figures::views::dynamic::{dynamic_csv, dynamic_json, DynamicView};
use figures::views::fr::FrStore;

impl Controller {
    /// The selected mesh's dynamic factor beside ISO 6336-1's K_v (the
    /// worst mesh: the one the selected state resolved, else the first);
    /// the model's or the standard's refusal as its reason.
    pub fn dynamic_view(&self) -> Result<DynamicView, String> {
        let model = self.model().map_err(ToString::to_string)?;
        let main = &self.main;
        let mesh = self
            .settings
            .mesh_index(model)
            .or(main.omega.as_ref().map(|r| r.mesh))
            .unwrap_or(0);
        // The frequency response's steady states: the overlay job's when it
        // is on, else the bifurcation sweep's (as the frequency response).
        let v = &self.settings.view;
        let swept;
        let states = if v.overlay_on() {
            &main.overlay
        } else {
            swept = FrStore::from_sweep(&main.bif.samples, v.transient_periods, v.record_periods);
            &swept
        };
        DynamicView::new(
            &self.settings.params,
            model,
            &self.view_context(),
            mesh,
            Some(states),
            main.omega.as_ref(),
        )
    }

    /// The plot's text alternative.
    pub fn dynamic_label(&self) -> String {
        match self.dynamic_view() {
            Ok(v) => v.label(),
            Err(e) => format!("Dynamic factor: not computed: {e}"),
        }
    }

    /// The note over the plot: both factors at the selected speed, why they
    /// differ there, and the load sharing.
    pub fn dynamic_note(&self) -> String {
        self.dynamic_view().map(|v| v.note()).unwrap_or_default()
    }

    /// The curves as CSV, or the view as JSON.
    pub fn dynamic_export(&self, csv: bool) -> Result<String, String> {
        let v = self.dynamic_view()?;
        Ok(if csv {
            dynamic_csv(&v)
        } else {
            dynamic_json(&v).to_string()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The default page rates its selected mesh, s1a1, and waits for the
    /// selected state before it names the model's factor at it.
    #[test]
    fn the_default_page_rates_the_selected_mesh() {
        let (c, _) = Controller::new("", 0.0);
        let v = c.dynamic_view().unwrap();
        assert_eq!(v.mesh_name, "s1a1");
        assert!(v.nonlinear.is_empty() && v.selected.is_none());
        assert!(
            c.dynamic_note().contains("computing"),
            "{}",
            c.dynamic_note()
        );
        assert!(c.dynamic_label().starts_with("Dynamic factor of mesh s1a1"));
        assert!(c
            .dynamic_export(true)
            .unwrap()
            .starts_with("omega,input_speed_rpm,"));
        // Without load the standard cannot rate the mesh: the reason shows.
        let (c, _) = Controller::new("model=gear-pair&torque_pinion_nm=0", 0.0);
        let e = c.dynamic_view().unwrap_err();
        assert!(
            e.contains("mesh pg") && e.contains("tangential load"),
            "{e}"
        );
        assert!(c.dynamic_label().contains("not computed"));
    }
}
