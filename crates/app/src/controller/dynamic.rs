//! The dynamic factor on the page: its view model from the current model,
//! the frequency response's steady states and the selected state, its
//! text alternative, its note and its exports.

use super::Controller;
use figures::views::dynamic::{dynamic_csv, dynamic_json, DynamicView};
use figures::views::fr::FrStore;
use figures::views::ViewError;

impl Controller {
    /// The selected mesh's dynamic factor beside ISO 6336-1's K_v (the
    /// worst mesh: the one the selected state resolved, else the first);
    /// the model's or the standard's refusal as its reason.
    pub fn dynamic_view(&self) -> Result<DynamicView, ViewError> {
        let model = self.model().map_err(Clone::clone)?;
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
            &v.iso_inputs(),
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
    pub fn dynamic_export(&self, csv: bool) -> Result<String, ViewError> {
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
    use crate::controller::Effect;

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
        let e = c.dynamic_view().unwrap_err().to_string();
        assert!(
            e.contains("mesh pg") && e.contains("tangential load"),
            "{e}"
        );
        assert!(c.dynamic_label().contains("not computed"));
    }

    /// The grade and face width of K_v are page controls: a value out of
    /// range is refused in words naming it and the allowed range (the
    /// state kept), and a link carries them only when set, restoring
    /// them exactly.
    #[test]
    fn the_kv_inputs_are_checked_and_ride_in_the_link_exactly() {
        let (mut c, _) = Controller::new("", 0.0);
        assert!(!c.query().contains("accuracy_grade") && !c.query().contains("face_width"));
        for (key, text, range) in [
            ("accuracy_grade", "12", "a whole number between 1 and 11"),
            ("accuracy_grade", "0", "a whole number between 1 and 11"),
            ("accuracy_grade", "6.5", "a whole number between 1 and 11"),
            ("face_width_mm", "0.5", "between 1 and 2000 mm"),
            ("face_width_mm", "2500", "between 1 and 2000 mm"),
            ("face_width_mm", "NaN", "between 1 and 2000 mm"),
        ] {
            let e = c.set_control(key, text, 0.0).unwrap_err().to_string();
            assert!(
                e.contains(range) && e.contains(&format!("(not {text})")) && !e.contains(key),
                "{e}"
            );
        }
        assert_eq!(c.settings().view, figures::settings::ViewOptions::default());
        let e = c
            .set_control("accuracy_grade", "12", 0.0)
            .unwrap_err()
            .to_string();
        assert_eq!(
            e,
            "Accuracy grade for Kv must be a whole number between 1 and 11 (not 12)."
        );
        // A face width with all of an f64's digits comes back bit for bit.
        let width: f64 = 0.1 + 37.2;
        c.set_control("accuracy_grade", "9", 0.0).unwrap();
        c.set_control("face_width_mm", &format!("{width}"), 0.0)
            .unwrap();
        let q = c.query();
        assert!(
            q.contains("accuracy_grade=9") && q.contains(&format!("face_width_mm={width}")),
            "{q}"
        );
        let (d, _) = Controller::new(&q, 0.0);
        assert_eq!(d.settings(), c.settings());
        // The commands that reproduce the page rate K_v alike.
        let cli = c.cli_commands();
        let flags = format!(" --accuracy-grade 9 --face-width-mm {width}");
        assert_eq!(cli.matches(&flags).count(), 2, "{cli}");
        let (plain, _) = Controller::new("", 0.0);
        assert!(!plain.cli_commands().contains("--accuracy-grade"));
        assert_eq!(d.settings().view.face_width_mm.to_bits(), width.to_bits());
        let (a, b) = (c.dynamic_view().unwrap(), d.dynamic_view().unwrap());
        assert_eq!(a.inputs, b.inputs);
        assert_eq!(a.inputs.accuracy_grade, 9.0);
        assert_eq!(a.kv, b.kv);
    }

    /// The view rates the mesh at the page's inputs. The standard's B_p,
    /// B_f and B_k are c' f / w and c' C_a / w: spreading the same
    /// stiffness and load over another face width changes c' and w alike,
    /// so K_v is the same wherever N_S is (line load w of 100 N/mm or
    /// more: N_S = 0.85); a coarser grade has larger deviations, so a
    /// larger K_v below the resonance.
    #[test]
    fn kv_follows_the_grade_and_not_the_face_width_at_heavy_load() {
        let (mut c, _) = Controller::new("", 0.0);
        let before = c.dynamic_view().unwrap();
        let at = |v: &DynamicView| v.kv_at(0.3);
        assert_eq!(before.range_at(0.3).name(), "subcritical");
        c.set_control("accuracy_grade", "9", 0.0).unwrap();
        let coarse = c.dynamic_view().unwrap();
        assert!(at(&coarse) > at(&before), "{} {}", at(&coarse), at(&before));
        // A narrower face at this load keeps w >= 100 N/mm.
        c.set_control("face_width_mm", "20", 0.0).unwrap();
        let narrow = c.dynamic_view().unwrap();
        assert!(narrow.rating.line_load_n_mm >= 100.0 && coarse.rating.line_load_n_mm >= 100.0);
        assert_eq!(narrow.rating.n_s, 0.85);
        let rel = (at(&narrow) - at(&coarse)).abs() / at(&coarse);
        assert!(rel <= 1e-12, "{} {}", at(&narrow), at(&coarse));
        assert!(
            (narrow.rating.mesh_stiffness_n_mm_um - 2.5 * coarse.rating.mesh_stiffness_n_mm_um)
                .abs()
                <= 1e-9 * narrow.rating.mesh_stiffness_n_mm_um
        );
    }

    /// The selected state's export in the CLI's format carries K_v at
    /// the page's grade and face width: the standard's rating of the
    /// mesh with those inputs (`solver::iso6336`, called here) at the
    /// state's mesh frequency, for the reported mesh and every mesh.
    #[test]
    fn the_simulate_export_rates_kv_at_the_pages_inputs() {
        use figures::protocol::RunOptions;
        use worker::jobs::omega::{omega_result, selected_spec, OmegaJob};
        let (mut c, _) = Controller::new(
            "model=gear-pair&accuracy_grade=8&face_width_mm=30&omega=0.4",
            0.0,
        );
        let model = c.model().unwrap().clone();
        let job = OmegaJob {
            id: 1,
            spec: selected_spec(
                c.settings(),
                &model,
                RunOptions {
                    transient_periods: 40,
                    record_periods: 10,
                },
            ),
            model: model.clone(),
        };
        c.main.omega = Some(omega_result(&job, None).unwrap());
        let fx = c.export_cli(figures::views::ViewId::Time, 1.0).unwrap();
        let [Effect::Download { text, .. }] = &fx[..] else {
            panic!("{fx:?}")
        };
        let v: serde_json::Value = serde_json::from_str(text).unwrap();
        let inputs = solver::iso6336::IsoInputs {
            accuracy_grade: 8.0,
            face_width_mm: 30.0,
            ..Default::default()
        };
        let rated = solver::iso6336::rate_model(&c.settings().params, &model, &inputs).unwrap();
        let hz = v["mesh_freq_hz"].as_f64().unwrap();
        let r = &rated[0].rating;
        let want = r.kv(r.resonance_ratio(hz));
        assert_eq!(v["kv_iso6336"].as_f64(), Some(want));
        assert_eq!(v["all_meshes"]["pg"]["kv_iso6336"].as_f64(), Some(want));
        assert_eq!(v["iso6336"]["inputs"]["accuracy_grade"], 8.0);
        assert_eq!(v["iso6336"]["inputs"]["face_width_mm"], 30.0);
    }
}
