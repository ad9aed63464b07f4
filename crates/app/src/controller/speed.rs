//! The speed axes on the page: what they show for the current model
//! (`figures::speed`), the speed fields in the chosen unit (a typed rpm is
//! stored as its exact Ω, so nothing else changes), how a click's speed is
//! rounded (to a step under a pixel, in the axes' unit), the readout of
//! the selected speed in both units and the rpm beside Ω in the exports.

use super::{Controller, Effect, InputError};
use figures::controls::Widget;
use figures::settings::{fmt_exact, view_key, ViewType, SPEED_KEYS};
use figures::speed::{axis_json, csv_with_rpm, SpeedAxis};

impl Controller {
    /// What the speed axes show on the current model.
    pub fn speed_axis(&self) -> SpeedAxis {
        SpeedAxis::new(self.settings.view.axis, self.model.as_ref().ok())
    }

    /// Sets `key` from the text of its control: a speed's text is rpm
    /// while the axes show rpm, converted to its Ω (refused, naming the
    /// value and the allowed rpm, outside the key's range).
    pub fn set_control(
        &mut self,
        key: &str,
        text: &str,
        now_ms: f64,
    ) -> Result<Vec<Effect>, InputError> {
        let typed = super::excitation::typed_text(key, text);
        let text = typed.as_str();
        let axis = self.speed_axis();
        let (Some(s), true) = (axis.rpm_scale(), SPEED_KEYS.contains(&key)) else {
            return self.set_key(key, text, now_ms);
        };
        let Some(ViewType::Float { min, max }) = view_key(key).map(|k| k.ty) else {
            return self.set_key(key, text, now_ms);
        };
        let (lo, hi) = (axis.field_value(min), axis.field_value(max));
        let rpm = text.trim().parse::<f64>().ok().filter(|x| x.is_finite());
        match rpm {
            Some(r) if r >= lo && r <= hi => {
                // The ends of the range are written rounded: their Ω stays in range.
                let omega = s.omega(r).clamp(min, max);
                self.set_key(key, &fmt_exact(omega), now_ms)
            }
            _ => Err(InputError::Rpm {
                what: speed_label(key).to_string(),
                lo: fmt_exact(lo),
                hi: fmt_exact(hi),
                input: s.input().to_string(),
                text: solver::keys::truncate(text.trim(), 40),
            }),
        }
    }

    /// The text of a speed key's field in the axes' unit; `None` for
    /// other keys.
    pub fn speed_field_text(&self, key: &str) -> Option<String> {
        if !SPEED_KEYS.contains(&key) {
            return None;
        }
        let omega: f64 = self.settings.view.get(key)?.parse().ok()?;
        Some(fmt_exact(self.speed_axis().field_value(omega)))
    }

    /// The decimal step a clicked or stepped speed is rounded to, as a
    /// power of ten in the unit the axes show: 1e-4 in Ω, a whole rpm in
    /// rpm, or finer where the frequency range is narrow, so that the step
    /// is never more than a thousandth of the range (under a pixel of any
    /// plot: the widest is 760 pixels). The rounding keeps links short and
    /// the fields' numbers round; the Ω it gives is written exactly, so a
    /// link restores the selected speed bit for bit.
    fn selection_exponent(&self) -> i32 {
        let v = &self.settings.view;
        let axis = self.speed_axis();
        let (span, coarsest) = match axis.rpm_scale() {
            Some(s) => (s.rpm(v.omega_to) - s.rpm(v.omega_from), 0),
            None => (v.omega_to - v.omega_from, -4),
        };
        let fine = (span.abs() / 1000.0).log10().floor();
        if fine.is_finite() {
            (fine.max(-12.0) as i32).min(coarsest)
        } else {
            coarsest
        }
    }

    /// A clicked or stepped speed as it is selected: its value in the
    /// axes' unit rounded to the step of [`Self::selection_exponent`]
    /// (Ω to 1e-4, rpm to a whole rpm on the default range), then as Ω.
    pub(super) fn rounded_selection(&self, omega: f64) -> f64 {
        let per = 10f64.powi(-self.selection_exponent());
        let round = |x: f64| (x * per).round() / per;
        match self.speed_axis().rpm_scale() {
            Some(s) => s.omega(round(s.rpm(omega))),
            None => round(omega),
        }
    }

    /// How far a selected speed can lie from the one clicked
    /// ([`Self::rounded_selection`]), in Ω, with a little room.
    pub(super) fn selection_tolerance(&self) -> f64 {
        let step = 10f64.powi(self.selection_exponent());
        match self.speed_axis().rpm_scale() {
            Some(s) => s.omega(0.5 * step) * 1.001,
            None => step,
        }
    }

    /// The selected speed in both units with the mesh frequency.
    pub fn speed_readout(&self) -> String {
        self.speed_axis().readout(self.settings.view.omega)
    }

    /// An export as the speed axes in rpm write it: a CSV with the input
    /// speed beside Ω, a JSON object with the axis it was read on. With
    /// the axes in Ω it is unchanged.
    pub(super) fn with_speed(&self, text: String, csv: bool) -> String {
        let axis = self.speed_axis();
        let Some(s) = axis.rpm_scale() else {
            return text;
        };
        if csv {
            return csv_with_rpm(&text, s);
        }
        match serde_json::from_str::<serde_json::Value>(&text) {
            Ok(serde_json::Value::Object(mut o)) => {
                o.insert("speed_axis".into(), axis_json(&axis));
                serde_json::Value::Object(o).to_string()
            }
            _ => text,
        }
    }
}

impl Controller {
    /// A speed key's control label with the axes in rpm; `None` for
    /// other keys or with the axes in Ω (the control's own label).
    pub fn speed_label(&self, key: &str) -> Option<String> {
        let axis = self.speed_axis();
        let s = axis.rpm_scale().filter(|_| SPEED_KEYS.contains(&key))?;
        Some(rpm_label(key, s.input()))
    }

    /// A speed key's slider and field ranges in the axes' unit (the
    /// control's own in Ω; whole rpm steps in rpm); `None` for other keys.
    pub fn speed_widget(&self, key: &str, widget: &Widget) -> Option<Widget> {
        if !SPEED_KEYS.contains(&key) {
            return None;
        }
        let Widget::Slider {
            min,
            max,
            field_min,
            field_max,
            ..
        } = *widget
        else {
            return None;
        };
        let axis = self.speed_axis();
        Some(match axis.rpm_scale() {
            Some(_) => Widget::Slider {
                min: axis.field_value(min).floor(),
                max: axis.field_value(max).ceil(),
                step: 1.0,
                field_min: axis.field_value(field_min),
                field_max: axis.field_value(field_max),
            },
            None => widget.clone(),
        })
    }

    /// The speed axes' choices named for the current model: "Ω
    /// (dimensionless)" and "sun s1 speed, rpm" (the pinion's on the pair).
    pub fn axis_options(&self) -> Vec<(String, String)> {
        let input = self.speed_axis().scale.map_or("input", |s| s.input());
        vec![
            ("omega".into(), "Ω (dimensionless)".into()),
            ("rpm".into(), format!("{input} speed, rpm")),
        ]
    }
}

/// A speed field's name in a sentence.
fn speed_label(key: &str) -> &'static str {
    match key {
        "omega_from" => "The start of the speed range",
        "omega_to" => "The end of the speed range",
        _ => "The selected speed",
    }
}

/// The label of a speed key's control with the axes in rpm, naming the
/// input member: "Selected speed, sun s1 (rpm)".
fn rpm_label(key: &str, input: &str) -> String {
    match key {
        "omega_from" => format!("Speed range: from, {input} (rpm)"),
        "omega_to" => format!("Speed range: to, {input} (rpm)"),
        _ => format!("Selected speed, {input} (rpm)"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use figures::speed::AxisUnit;

    /// The ratio of rpm to Ω by hand: Ω ω_ref / 2π is the mesh frequency,
    /// and that over z_in |n_in - n_c| / n_in / 60 is the input's rpm.
    fn rpm_per_omega(c: &Controller) -> f64 {
        let m = c.model().unwrap();
        let sp = m.system.speed;
        m.system.omega_ref_rad_s
            / (2.0 * std::f64::consts::PI)
            / (f64::from(sp.input_teeth) * sp.relative_per_input.abs() / 60.0)
    }

    /// With the axes in rpm, a range typed in rpm is stored as its Ω
    /// (exactly: 1e-12) and its field reads the rpm back; the link carries
    /// the Ω and `axis=rpm`; a speed out of range is refused in rpm.
    #[test]
    fn speeds_typed_in_rpm_are_stored_as_their_omega() {
        let (mut c, _) = Controller::new("axis=rpm", 0.0);
        assert_eq!(c.settings().view.axis, AxisUnit::Rpm);
        let k = rpm_per_omega(&c);
        c.set_control("omega_from", "1000", 0.0).unwrap();
        c.set_control("omega_to", "9000", 0.0).unwrap();
        let v = &c.settings().view;
        assert!((v.omega_from - 1000.0 / k).abs() <= 1e-12 * v.omega_from);
        assert!((v.omega_to - 9000.0 / k).abs() <= 1e-12 * v.omega_to);
        assert_eq!(c.speed_field_text("omega_from").as_deref(), Some("1000"));
        assert_eq!(c.speed_field_text("omega_to").as_deref(), Some("9000"));
        assert!(c.query().contains("&axis=rpm"), "{}", c.query());
        let e = c
            .set_control("omega_to", "1e9", 0.0)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("rpm") && e.contains("(not 1e9)") && e.contains("sun s1"),
            "{e}"
        );
        assert!((c.settings().view.omega_to - 9000.0 / k).abs() <= 1e-12);
        // Other keys are as they were; in Ω the range fields are Ω.
        c.set_control("fr_points", "60", 0.0).unwrap();
        c.set_control("axis", "omega", 0.0).unwrap();
        c.set_control("omega_to", "1.5", 0.0).unwrap();
        assert_eq!(c.settings().view.omega_to, 1.5);
        assert!(!c.query().contains("axis="));
    }

    /// A click selects a whole rpm with the axes in rpm (Ω to 1e-4 in Ω),
    /// and the arrows still step between the critical speeds from there.
    #[test]
    fn a_click_selects_a_whole_rpm_and_the_arrows_step_from_it() {
        let (mut c, _) = Controller::new("axis=rpm", 0.0);
        let k = rpm_per_omega(&c);
        let crossings: Vec<f64> = c
            .campbell_view()
            .unwrap()
            .crossings
            .iter()
            .map(|x| x.omega)
            .collect();
        c.select_omega(crossings[1], 0.0);
        let rpm = c.settings().view.omega * k;
        assert!((rpm - rpm.round()).abs() <= 1e-9 * rpm, "{rpm}");
        assert!((rpm - crossings[1] * k).abs() <= 0.5 + 1e-9);
        let at = c.settings().view.omega;
        assert_eq!(c.campbell_step(at, 1.0), Some(crossings[2]));
        assert_eq!(c.campbell_step(at, -1.0), Some(crossings[0]));
        assert!(c
            .speed_readout()
            .contains(&format!("{} rpm", figures::speed::grouped(rpm))));
    }

    /// On a narrow range a click selects a speed finer than a whole rpm
    /// (the step at most a thousandth of the range: 0.01 rpm over 20
    /// rpm), in Ω a finer step than 1e-4 too; the link restores the
    /// selected Ω bit for bit, and the field and readout say the rpm.
    #[test]
    fn a_click_on_a_narrow_range_selects_the_rpm_it_points_at() {
        let (mut c, _) = Controller::new("axis=rpm", 0.0);
        let k = rpm_per_omega(&c);
        c.set_control("omega_from", "3000", 0.0).unwrap();
        c.set_control("omega_to", "3020", 0.0).unwrap();
        // A pixel's Ω: 3004.3712 rpm, selected as 3004.37.
        c.select_omega(3004.3712 / k, 0.0);
        let rpm = c
            .speed_axis()
            .rpm_scale()
            .unwrap()
            .rpm(c.settings().view.omega);
        assert!((rpm - 3004.37).abs() <= 1e-9, "{rpm}");
        assert_eq!(c.speed_field_text("omega").as_deref(), Some("3004.37"));
        assert!(
            c.speed_readout().contains("sun s1 at 3\u{a0}004.37 rpm"),
            "{}",
            c.speed_readout()
        );
        let (d, _) = Controller::new(&c.query(), 0.0);
        assert_eq!(
            d.settings().view.omega.to_bits(),
            c.settings().view.omega.to_bits()
        );
        assert_eq!(d.speed_field_text("omega").as_deref(), Some("3004.37"));
        // In Ω over a range of 0.004: steps of 1e-6.
        let (mut c, _) = Controller::new("omega_from=0.5&omega_to=0.504", 0.0);
        c.select_omega(0.501_234_567, 0.0);
        assert_eq!(c.settings().view.omega, 0.501235);
        // The default range keeps Ω to 1e-4.
        let (mut c, _) = Controller::new("", 0.0);
        c.select_omega(0.501_234_567, 0.0);
        assert_eq!(c.settings().view.omega, 0.5012);
    }

    /// A preset keeps the speed axes the reader chose (its figure's
    /// settings are its own).
    #[test]
    fn a_preset_keeps_the_speed_axes() {
        let (mut c, _) = Controller::new("axis=rpm", 0.0);
        let id = figures::presets::PRESETS[1].id;
        c.apply_preset(id, 0.0);
        assert_eq!(c.settings().view.axis, AxisUnit::Rpm);
        assert!(c.query().contains("axis=rpm"), "{}", c.query());
    }

    /// The exports say the axis: the CSV with the input speed beside Ω,
    /// the JSON with the axis it was read on; in Ω they are unchanged.
    #[test]
    fn exports_carry_the_rpm_beside_omega() {
        let (mut c, _) = Controller::new("", 0.0);
        let csv = "branch,omega,x\nhbm,0.5,1\n".to_string();
        assert_eq!(c.with_speed(csv.clone(), true), csv);
        c.set_control("axis", "rpm", 0.0).unwrap();
        let k = rpm_per_omega(&c);
        let out = c.with_speed(csv, true);
        let row: Vec<&str> = out.lines().nth(1).unwrap().split(',').collect();
        assert_eq!(out.lines().next(), Some("branch,omega,s1_rpm,x"));
        let rpm: f64 = row[2].parse().unwrap();
        assert!((rpm - 0.5 * k).abs() <= 1e-12 * rpm);
        let json: serde_json::Value =
            serde_json::from_str(&c.with_speed("{\"a\":1}".into(), false)).unwrap();
        assert_eq!(json["speed_axis"]["unit"], "rpm");
        assert_eq!(json["speed_axis"]["input"], "sun s1");
        let per = json["speed_axis"]["rpm_per_omega"].as_f64().unwrap();
        assert!((per - k).abs() <= 1e-12 * k);
    }
}
