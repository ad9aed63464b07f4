//! The Campbell diagram on the page: its view model from the current
//! model and Omega range, its text alternative, its exports, and the
//! critical speed a click or an arrow key selects.

use super::Controller;
use figures::views::campbell::{campbell_csv, CampbellCrossing, CampbellView};
use figures::views::ViewError;

impl Controller {
    /// The Campbell diagram of the current model, from standstill to the
    /// speed of the top of the Omega range, the selected Omega marked; the
    /// model's refusal as its reason.
    pub fn campbell_view(&self) -> Result<CampbellView, ViewError> {
        let model = self.model().map_err(Clone::clone)?;
        let v = &self.settings.view;
        let mut c = CampbellView::new(model, v.omega_to, v.omega)?
            .with_planet_pass(model, &self.settings.params)?;
        c.speed = self.speed_axis();
        Ok(c)
    }

    /// The diagram's text alternative: the first critical speeds in words.
    pub fn campbell_label(&self) -> String {
        match self.campbell_view() {
            Ok(v) => v.label(),
            Err(e) => format!("Campbell diagram: not computed: {e}"),
        }
    }

    /// The note over the diagram: its first critical speeds in words.
    pub fn campbell_note(&self) -> String {
        self.campbell_view().map(|v| v.note()).unwrap_or_default()
    }

    /// The diagram's critical speeds as CSV, or as JSON.
    pub fn campbell_export(&self, csv: bool) -> Result<String, ViewError> {
        let v = self.campbell_view()?;
        if csv {
            return Ok(campbell_csv(&v));
        }
        let crossings: Vec<serde_json::Value> = v.crossings.iter().map(crossing_json).collect();
        Ok(serde_json::json!({
            "rpm_max": v.rpm_max,
            "mesh_hz_per_rpm": v.mesh_hz_per_rpm,
            "natural_frequencies_hz": v.modes.iter().map(|m| m.frequency_hz).collect::<Vec<f64>>(),
            "crossings": crossings,
            "planet_pass": v.planet_pass.as_ref().map(|p| serde_json::json!({
                "planets": p.planets,
                "hz_per_rpm": p.hz_per_rpm,
                "crossings": p.crossings.iter().map(|c| serde_json::json!({
                    "order": c.order,
                    "mode": c.rank + 1,
                    "natural_frequency_hz": c.frequency_hz,
                    "rpm": c.rpm,
                    "omega": c.omega,
                })).collect::<Vec<_>>(),
            })),
        })
        .to_string())
    }

    /// The Omega of the critical speed after (`dir` > 0) or before the
    /// selected Omega `from`, if there is one.
    pub fn campbell_step(&self, from: f64, dir: f64) -> Option<f64> {
        let v = self.campbell_view().ok()?;
        // The selected Omega is rounded (`select_omega`): a crossing
        // within that of it is the one selected.
        let tol = self.selection_tolerance();
        let next = |c: &&CampbellCrossing| {
            if dir > 0.0 {
                c.omega > from + tol
            } else {
                c.omega < from - tol
            }
        };
        let mut it = v.crossings.iter().filter(next);
        if dir > 0.0 {
            it.next().map(|c| c.omega)
        } else {
            it.next_back().map(|c| c.omega)
        }
    }
}

/// One critical speed as JSON (the page's status and the export).
pub(crate) fn crossing_json(c: &CampbellCrossing) -> serde_json::Value {
    serde_json::json!({
        "order": c.order,
        "mode": c.rank + 1,
        "natural_frequency_hz": c.frequency_hz,
        "rpm": c.rpm,
        "omega": c.omega,
        "excited": c.excited,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The arrows step from a selected critical speed (its Omega rounded
    /// as the page rounds it) to the next and the previous one.
    #[test]
    fn the_arrows_step_between_critical_speeds() {
        let (c, _) = Controller::new("", 0.0);
        let v = c.campbell_view().unwrap();
        let omegas: Vec<f64> = v.crossings.iter().map(|x| x.omega).collect();
        let at = (omegas[1] * 1e4).round() / 1e4;
        assert_eq!(c.campbell_step(at, 1.0), Some(omegas[2]));
        assert_eq!(c.campbell_step(at, -1.0), Some(omegas[0]));
        assert_eq!(c.campbell_step(omegas[0], -1.0), None);
        assert!(c.campbell_export(true).unwrap().starts_with("order,mode,"));
        assert!(c.campbell_label().contains("order 1 meets the first mode"));
    }
}
