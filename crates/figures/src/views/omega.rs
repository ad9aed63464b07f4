//! the selected-Omega views (`ViewId::Phase`, `Poincare`, `Time`, `Spectrum`), the selected Omega: the summary line (with the planet
//! phasing clause), and the phase portrait's, Poincaré section's, time
//! history's and spectrum's CSV and JSON exports.

use super::{csv_num, NaturalFreq};
use crate::protocol::{Motion, OmegaResult};
use solver::model::Model;
use solver::params::MeshKind;

/// The one-line summary at the selected Omega (under the selected-Omega views).
pub fn summary_line(r: &OmegaResult, natural: &[NaturalFreq]) -> String {
    let period = crate::story::motion_tag(r.motion);
    let df = r.dynamic_factor.map_or("n/a".into(), |d| format!("{d:.3}"));
    let nat = if natural.is_empty() {
        "none in range".to_string()
    } else {
        natural
            .iter()
            .map(|n| format!("{:.3}", n.omega))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let preview = if r.preview {
        format!(
            "Preview ({} + {} periods continued from the previous state; the full run is computing): ",
            r.transient_periods_run, r.record_periods
        )
    } else {
        String::new()
    };
    let multiplier = match r.motion {
        Motion::PeriodicExact {
            max_multiplier_modulus,
            ..
        } => format!(", largest Floquet multiplier {max_multiplier_modulus:.3}"),
        _ => String::new(),
    };
    format!(
        "{preview}Ω = {:.4} ({:.0} Hz mesh frequency), mesh {}: {}, {period}{multiplier}, dynamic factor {}. Natural frequencies in range (Ω): {}.",
        r.omega,
        r.mesh_freq_hz,
        r.mesh_name,
        crate::story::contact_tag(r.regime, r.backlash_um),
        df,
        nat
    )
}

/// The summary for students at the selected Omega, plain first: what the
/// teeth do (the regime in words, read against the backlash) and whether
/// the motion repeats (its classification), then the dynamic factor
/// explained, then the mesh and the speed's figures.
pub fn student_summary(r: &OmegaResult) -> String {
    student_summary_at(r, &crate::speed::SpeedAxis::default())
}

/// [`student_summary`] stating the speed as `speed` shows it: with the
/// speed axes in rpm, the input member's speed in rpm before Ω.
pub fn student_summary_at(r: &OmegaResult, speed: &crate::speed::SpeedAxis) -> String {
    let what = crate::story::contact_sentence(r.regime, r.backlash_um);
    let repeats = crate::story::motion_sentence(r.motion, r.transient_periods_run);
    let preview = if r.preview { "Preview: " } else { "" };
    // Plain first: what the teeth do, in words; the speed's figures and
    // the dynamic factor's name after it.
    let first = format!("{preview}At this speed {what}; {repeats}.");
    let second = match r.dynamic_factor {
        Some(d) => format!(
            " The largest tooth force is {d:.2} times the force of the steady load alone (dynamic factor {d:.2})."
        ),
        None => String::new(),
    };
    let at = match speed.rpm_scale() {
        Some(s) => format!(
            "{} at {} rpm (Ω {})",
            s.input(),
            crate::speed::grouped_fine(s.rpm(r.omega)),
            crate::views::unstable::short(r.omega)
        ),
        None => format!("Ω {}", crate::views::unstable::short(r.omega)),
    };
    let third = format!(
        " Mesh {}, {at}: a mesh frequency of {:.0} Hz.",
        r.mesh_name, r.mesh_freq_hz
    );
    format!("{first}{second}{third}")
}

/// Highest mesh order of the phasing numbers.
pub const PHASING_ORDERS: u32 = 6;

/// The phasing clause of the summary: per mesh kind, the surviving fraction
/// of the in-phase excitation at mesh orders 1.., the orders that cancel,
/// and the response's spectrum at those orders. `None` for the gear pair.
pub fn phasing_line(
    model: &Model,
    params: &solver::params::ModelParams,
    r: Option<&OmegaResult>,
) -> Option<String> {
    let solver::params::ModelParams::Ravigneaux(p) = params else {
        return None;
    };
    let mut parts = Vec::new();
    let mut cancelled_all: Option<Vec<u32>> = None;
    for (kind, name) in [
        (MeshKind::S1A, "s1a"),
        (MeshKind::S2B, "s2b"),
        (MeshKind::AB, "ab"),
        (MeshKind::RB, "rb"),
    ] {
        let f = model.system.phasing_factors(kind, PHASING_ORDERS);
        let cancelled: Vec<u32> = f
            .iter()
            .enumerate()
            .filter(|(_, v)| **v < 1e-3)
            .map(|(k, _)| k as u32 + 1)
            .collect();
        cancelled_all = Some(match cancelled_all {
            None => cancelled.clone(),
            Some(c) => c.into_iter().filter(|k| cancelled.contains(k)).collect(),
        });
        let nums: Vec<String> = f.iter().map(|v| format!("{v:.2}")).collect();
        parts.push(format!("{name} {}", nums.join("/")));
    }
    let cancelled = cancelled_all.unwrap_or_default();
    let cancel_text = if cancelled.is_empty() {
        "no order cancels".to_string()
    } else {
        let ks: Vec<String> = cancelled.iter().map(|k| k.to_string()).collect();
        format!("orders {} cancel in every kind", ks.join(", "))
    };
    let mut line = format!(
        "Planet phasing ({}, N = {}): fraction of the in-phase excitation left in the sum over the planets at mesh orders 1–{PHASING_ORDERS}: {}; {cancel_text}.",
        p.phasing.name(),
        p.planets,
        parts.join("; ")
    );
    if let Some(r) = r {
        let amp = |k: u32| {
            r.spectrum_order
                .iter()
                .zip(&r.spectrum_um)
                .filter(|(o, _)| (**o - f64::from(k)).abs() < 1e-6)
                .map(|(_, a)| *a)
                .next()
        };
        let spec: Vec<String> = (1..=PHASING_ORDERS.min(4))
            .map(|k| amp(k).map_or("-".into(), |a| format!("{a:.2}")))
            .collect();
        line.push_str(&format!(
            " Response of {} at orders 1–4: {} µm.",
            r.mesh_name,
            spec.join(", ")
        ));
    }
    Some(line)
}

/// Which of the selected-Omega views.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OmegaView {
    /// Phase portrait.
    Phase,
    /// Poincaré section.
    Poincare,
    /// Time history.
    Time,
    /// Spectrum.
    Spectrum,
}

impl OmegaView {
    /// The selected-Omega view `view` is, if it is one.
    pub fn of(view: super::ViewId) -> Option<OmegaView> {
        use super::ViewId;
        match view {
            ViewId::Phase => Some(OmegaView::Phase),
            ViewId::Poincare => Some(OmegaView::Poincare),
            ViewId::Time => Some(OmegaView::Time),
            ViewId::Spectrum => Some(OmegaView::Spectrum),
            _ => None,
        }
    }
}

/// A selected-Omega view as CSV.
pub fn omega_csv(r: &OmegaResult, which: OmegaView) -> String {
    let spp = f64::from(r.samples_per_period.max(1));
    match which {
        OmegaView::Phase | OmegaView::Time => {
            let mut s = String::from("t_periods,x_um,xdot_m_s\n");
            for (k, (x, v)) in r.x_um.iter().zip(&r.xdot_m_s).enumerate() {
                s.push_str(&format!(
                    "{},{},{}\n",
                    k as f64 / spp,
                    csv_num(*x),
                    csv_num(*v)
                ));
            }
            s
        }
        OmegaView::Poincare => {
            let mut s = String::from("n,x_um,xdot_m_s\n");
            for (k, (x, v)) in r.poincare_x_um.iter().zip(&r.poincare_xdot_m_s).enumerate() {
                s.push_str(&format!("{k},{},{}\n", csv_num(*x), csv_num(*v)));
            }
            s
        }
        OmegaView::Spectrum => {
            let mut s = String::from("order,amplitude_um\n");
            for (o, a) in r.spectrum_order.iter().zip(&r.spectrum_um) {
                s.push_str(&format!("{},{}\n", csv_num(*o), csv_num(*a)));
            }
            s
        }
    }
}

/// A selected-Omega view's data as JSON (the plotted series plus context).
pub fn omega_json(r: &OmegaResult, which: OmegaView) -> serde_json::Value {
    use serde_json::json;
    let head = json!({
        "omega": r.omega,
        "mesh": r.mesh_name,
        "backlash_um": r.backlash_um,
        "impact": r.regime.solver_name(),
        "period": r.period,
        "motion": r.motion.name(),
        "exact": r.motion.is_exact(),
        "max_multiplier_modulus": match r.motion {
            Motion::PeriodicExact { max_multiplier_modulus, .. } => Some(max_multiplier_modulus),
            _ => None,
        },
        "dynamic_factor": r.dynamic_factor,
        "samples_per_period": r.samples_per_period,
        "record_periods": r.record_periods,
    });
    let body = match which {
        OmegaView::Phase | OmegaView::Time => json!({
            "x_um": r.x_um, "xdot_m_s": r.xdot_m_s,
            "poincare_x_um": r.poincare_x_um, "poincare_xdot_m_s": r.poincare_xdot_m_s,
        }),
        OmegaView::Poincare => json!({
            "poincare_x_um": r.poincare_x_um, "poincare_xdot_m_s": r.poincare_xdot_m_s,
        }),
        OmegaView::Spectrum => json!({
            "order": r.spectrum_order, "amplitude_um": r.spectrum_um,
        }),
    };
    json!({ "view": head, "data": body })
}

/// The caption's status of a selected-Omega view.
pub fn caption_suffix(preview: bool, running: bool) -> &'static str {
    match (preview, running) {
        (true, _) => " (preview; full run computing…)",
        (false, true) => " (updating…)",
        (false, false) => "",
    }
}

/// What a selected-Omega view shows while its first result computes.
pub fn computing_message(omega: f64) -> String {
    format!("Computing the steady state at Ω = {omega} in a Web Worker…")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sequential_phasing_of_five_planets_cancels_orders_one_to_four() {
        let model = |q: &str| {
            let d = crate::link::decode(q);
            (Model::new(&d.settings.params).unwrap(), d.settings.params)
        };
        // z_s1 = 36, z_s2 = 48, z_r = 84: k z / 5 is whole only for k = 5.
        let (m, p) = model("planets=5&phasing=sequential");
        for kind in [MeshKind::S1A, MeshKind::S2B, MeshKind::AB, MeshKind::RB] {
            assert_eq!(
                m.system.phasing_factors(kind, 6),
                vec![0.0, 0.0, 0.0, 0.0, 1.0, 0.0],
                "{kind:?}"
            );
        }
        let line = phasing_line(&m, &p, None).unwrap();
        assert!(line.contains("orders 1, 2, 3, 4, 6 cancel"), "{line}");
        // In phase, nothing cancels; with N = 3 sequential equals in-phase.
        for q in ["planets=5&phasing=in-phase", "planets=3&phasing=sequential"] {
            let (m, p) = model(q);
            assert_eq!(
                m.system.phasing_factors(MeshKind::S1A, 6),
                vec![1.0; 6],
                "{q}"
            );
            assert!(phasing_line(&m, &p, None)
                .unwrap()
                .contains("no order cancels"));
        }
        let (m, p) = model("model=gear-pair");
        assert!(phasing_line(&m, &p, None).is_none());
    }
}
