//! Where the model stops describing real gears, said beside the results:
//! its tooth contact is a linear spring for small deflections (gear teeth
//! deflect micrometres to tens of micrometres under load), so a state whose
//! teeth deflect by a millimetre or more (a torque of 900 000 N m, a
//! resonance with little damping) is computed, but is not physics. The
//! page warns from the static deflection at once and from the steady
//! state's peak once it is computed.

use figures::protocol::AnimHistory;
use figures::words::short;
use solver::model::Model;

/// The tooth deflection (µm) from which the small-deflection model is
/// warned about: a millimetre.
pub const LIMIT_UM: f64 = 1000.0;

/// The largest static tooth deflection (µm) of any mesh: its static
/// contact force over its mean stiffness (the deflection beyond the
/// backlash; zero for a mesh whose teeth are apart).
pub fn static_deflection_um(model: &Model) -> f64 {
    model
        .system
        .meshes
        .iter()
        .zip(&model.statics.mesh_force_n)
        .map(|(m, f)| 1e6 * f.abs() / m.stiffness_mean_n_m)
        .filter(|d| d.is_finite())
        .fold(0.0, f64::max)
}

/// The largest tooth deflection (µm) of any mesh over a steady state's
/// window: how far x goes beyond a flank contact, |x| − b (TE included).
pub fn peak_deflection_um(h: &AnimHistory) -> f64 {
    h.x_um
        .iter()
        .zip(&h.backlash_um)
        .flat_map(|(xs, b)| xs.iter().map(move |x| x.abs() - b))
        .filter(|d| d.is_finite())
        .fold(0.0, f64::max)
}

/// The warning for a state whose teeth deflect `static_um` under the load
/// alone and `peak_um` at most in the steady state at `omega` (if
/// computed), or `None` within the model's validity.
pub fn warning(static_um: f64, peak: Option<(f64, f64)>) -> Option<String> {
    let peak_um = peak.map_or(0.0, |(_, p)| p);
    let worst = static_um.max(peak_um);
    if worst < LIMIT_UM {
        return None;
    }
    let (how, what) = if static_um >= LIMIT_UM {
        (
            format!(
                "under the load alone the teeth deflect {}",
                amount(static_um)
            ),
            "Lower the input torque",
        )
    } else {
        let omega = peak.map_or(String::new(), |(o, _)| format!(" at Ω {}", short(o)));
        (
            format!("the teeth deflect up to {}{omega}", amount(peak_um)),
            "Lower the input torque, or add damping",
        )
    };
    Some(format!(
        "Outside the model: {how}. The model treats the teeth as linear springs for small deflections (real teeth deflect micrometres to tens of micrometres; at a millimetre they would break), so these results are not physical. {what}."
    ))
}

/// A deflection in µm with its size in mm: "114 940 µm (115 mm)".
fn amount(um: f64) -> String {
    format!("{} µm ({} mm)", grouped(um.round()), short_mm(um / 1000.0))
}

fn short_mm(mm: f64) -> String {
    if mm >= 10.0 {
        format!("{mm:.0}")
    } else {
        short(mm)
    }
}

/// An integer with thin spaces between groups of three digits.
fn grouped(x: f64) -> String {
    let digits = format!("{:.0}", x.abs());
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push('\u{202f}');
        }
        out.push(c);
    }
    if x < 0.0 {
        format!("−{out}")
    } else {
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use solver::params::ModelParams;

    fn model(assignments: &[&str]) -> Model {
        let mut p = ModelParams::default();
        for kv in assignments {
            if let Err(e) = solver::keys::set_assignment(&mut p, kv) {
                panic!("{kv}: {e}");
            }
        }
        match Model::new(&p) {
            Ok(m) => m,
            Err(e) => panic!("{e}"),
        }
    }

    #[test]
    fn millimetres_of_tooth_deflection_are_warned_micrometres_are_not() {
        // The default load deflects the teeth by micrometres: no warning.
        let d = static_deflection_um(&model(&[]));
        assert!(d > 0.1 && d < 100.0, "{d}");
        assert_eq!(warning(d, Some((0.35, 2.0 * d))), None);
        // 900 000 N m deflects them by millimetres: warned at once.
        let d = static_deflection_um(&model(&["torque_s1_nm=900000"]));
        assert!(d > 4000.0, "{d}");
        let w = warning(d, None).unwrap_or_default();
        assert!(
            w.starts_with("Outside the model: under the load alone"),
            "{w}"
        );
        assert!(
            w.contains("not physical") && w.contains("Lower the input torque"),
            "{w}"
        );
        // A steady state's peak past a millimetre, under a small load.
        let w = warning(20.0, Some((1.2, 1500.4))).unwrap_or_default();
        assert!(w.contains("up to 1\u{202f}500 µm (1.5 mm) at Ω 1.2"), "{w}");
        assert_eq!(amount(114_940.0), "114\u{202f}940 µm (115 mm)");
        // No load: no deflection.
        assert!(static_deflection_um(&model(&["torque_s1_nm=0"])) < 1e-9);
    }

    #[test]
    fn the_peak_is_how_far_x_goes_beyond_a_flank() {
        let h = AnimHistory {
            start_sample: 0,
            x_um: vec![vec![90.0, 130.0, -40.0], vec![-260.0, 0.0]],
            backlash_um: vec![100.0, 50.0],
        };
        assert_eq!(peak_deflection_um(&h), 210.0);
        assert_eq!(peak_deflection_um(&AnimHistory::default()), 0.0);
    }
}
