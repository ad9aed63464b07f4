//! Presets: the Table 1 defaults, the seed paper's figures as settings
//! (`MODEL.md`, "The seed's figures, as settings") and a classic single gear
//! pair. Each preset is a link query, so it goes through the same decoder as
//! a shared link, plus a note of what the seed states and what was assumed.

/// One preset.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Preset {
    /// Stable id (used by tests and the select's values).
    pub id: &'static str,
    /// Menu label.
    pub title: &'static str,
    /// The settings, as a link query.
    pub query: &'static str,
    /// What the seed states.
    pub seed: &'static str,
    /// What had to be assumed.
    pub assumed: &'static str,
}

const SCALE_NOTE: &str = "The seed's dimensionless scales are not stated, so its Omega values do not map one to one onto ours (Omega = omega / omega_ref, omega_ref from mesh s1a1; MODEL.md).";

/// Every preset, in menu order.
pub const PRESETS: &[Preset] = &[
    Preset {
        id: "table1",
        title: "Table 1 defaults",
        query: "model=ravigneaux",
        seed: "Table 1: N = 3 planet pairs, module 4 mm, teeth 36/48/21/84, k = 1e9 N/m, T_s1 = 2000 N m.",
        assumed: "MODEL.md's clean reading: geometry from the tooth counts, b = 100 um on every mesh, v = 0.3, xi = 0.06, 20 um TE sine on the s1a meshes, T_s2 balancing (969.7 N m).",
    },
    Preset {
        id: "fig2",
        title: "Fig. 2: frequency response, b = 0",
        query: "model=ravigneaux&backlash_um=0&te_um=20&mesh=s1a1&omega_from=0.1&omega_to=2",
        seed: "HBM frequency response of one mesh of each kind, with no backlash and TE sine amplitudes of 5 to 30 um on the s1a meshes.",
        assumed: "One TE amplitude of 20 um (the middle of the seed's range); pick other meshes with the mesh control. The curve is the harmonic-balance branch (H = 5 by default, forces integrated exactly between the contact switches).",
    },
    Preset {
        id: "fig3",
        title: "Fig. 3: frequency response, TE 60 um",
        query: "model=ravigneaux&backlash_um=100&te_um=60&mesh=s1a1&omega_from=0.1&omega_to=2",
        seed: "HBM frequency response with a TE fundamental component of 60 um and backlash of 50 to 200 um.",
        assumed: "The fundamental is taken as the sine amplitude on the s1a meshes; b = 100 um of the seed's 50..200 (move the backlash slider to see the others).",
    },
    Preset {
        id: "fig4a",
        title: "Fig. 4a: bifurcation, TE 0",
        query: "model=ravigneaux&backlash_um=200&te_um=0&mesh=s1a1&omega_from=0.1&omega_to=2&bif_dir=both",
        seed: "Bifurcation diagram of delta_s1a1 over Omega in [0, 2], b = 200 um, no TE.",
        assumed: "The sweep starts at Omega = 0.1 (below that one mesh period spans many natural periods and the response is quasi-static); up and down sweeps, 300 + 100 periods per point.",
    },
    Preset {
        id: "fig4b",
        title: "Fig. 4b: bifurcation, TE 20 um",
        query: "model=ravigneaux&backlash_um=200&te_um=20&mesh=s1a1&omega_from=0.1&omega_to=2&bif_dir=both",
        seed: "Bifurcation diagram of delta_s1a1 over Omega in [0, 2], b = 200 um, TE 20 um.",
        assumed: "As Fig. 4a; the TE is a sine on the s1a meshes; x = delta - e is plotted (equal to delta at the Poincaré phase for a sine TE).",
    },
    Preset {
        id: "fig4c",
        title: "Fig. 4c: bifurcation, TE 30 um",
        query: "model=ravigneaux&backlash_um=200&te_um=30&mesh=s1a1&omega_from=0.1&omega_to=2&bif_dir=both",
        seed: "Bifurcation diagram of delta_s1a1 over Omega in [0, 2], b = 200 um, TE 30 um.",
        assumed: "As Fig. 4a.",
    },
    Preset {
        id: "fig5",
        title: "Fig. 5: phase portraits, TE 0",
        query: "model=ravigneaux&backlash_um=200&te_um=0&mesh=s1a1&omega=0.5",
        seed: "Phase portraits and Poincaré sections at Omega = 0.5, 0.84 and 1.97, b = 200 um, no TE.",
        assumed: "Figs. 5-7 are read as one TE level each; Omega = 0.5 is selected, click the frequency response or bifurcation diagram to move to 0.84 or 1.97.",
    },
    Preset {
        id: "fig6",
        title: "Fig. 6: phase portraits, TE 20 um",
        query: "model=ravigneaux&backlash_um=200&te_um=20&mesh=s1a1&omega=0.84",
        seed: "Phase portraits and Poincaré sections at Omega = 0.5, 0.84 and 1.97, b = 200 um, TE 20 um.",
        assumed: "Omega = 0.84 is selected; the others are a click away.",
    },
    Preset {
        id: "fig7",
        title: "Fig. 7: phase portraits, TE 30 um",
        query: "model=ravigneaux&backlash_um=200&te_um=30&mesh=s1a1&omega=1.97",
        seed: "Phase portraits and Poincaré sections at Omega = 0.5, 0.84 and 1.97, b = 200 um, TE 30 um.",
        assumed: "Omega = 1.97 is selected; the others are a click away.",
    },
    Preset {
        id: "fig8a",
        title: "Fig. 8a: bifurcation, b = 50 um",
        query: "model=ravigneaux&backlash_um=50&te_um=20&mesh=s1a1&omega_from=0.1&omega_to=2&bif_dir=both",
        seed: "Bifurcation diagram with TE 20 um and b = 50 um.",
        assumed: "Omega range 0.1..2 as in Fig. 4; mesh s1a1.",
    },
    Preset {
        id: "fig8b",
        title: "Fig. 8b: bifurcation, b = 100 um",
        query: "model=ravigneaux&backlash_um=100&te_um=20&mesh=s1a1&omega_from=0.1&omega_to=2&bif_dir=both",
        seed: "Bifurcation diagram with TE 20 um and b = 100 um.",
        assumed: "Omega range 0.1..2 as in Fig. 4; mesh s1a1.",
    },
    Preset {
        id: "fig8c",
        title: "Fig. 8c: bifurcation, b = 200 um",
        query: "model=ravigneaux&backlash_um=200&te_um=20&mesh=s1a1&omega_from=0.1&omega_to=2&bif_dir=both",
        seed: "Bifurcation diagram with TE 20 um and b = 200 um.",
        assumed: "Omega range 0.1..2 as in Fig. 4; mesh s1a1.",
    },
    Preset {
        id: "fig9",
        title: "Fig. 9: phase portraits, b = 50 um",
        query: "model=ravigneaux&backlash_um=50&te_um=20&mesh=s1a1&omega=0.5",
        seed: "Phase portraits and Poincaré sections at Omega = 0.5, 0.84 and 1.97 with TE 20 um and b = 50 um.",
        assumed: "Figs. 9-11 are read as one backlash each; Omega = 0.5 is selected.",
    },
    Preset {
        id: "fig10",
        title: "Fig. 10: phase portraits, b = 100 um",
        query: "model=ravigneaux&backlash_um=100&te_um=20&mesh=s1a1&omega=0.84",
        seed: "Phase portraits and Poincaré sections at Omega = 0.5, 0.84 and 1.97 with TE 20 um and b = 100 um.",
        assumed: "Omega = 0.84 is selected.",
    },
    Preset {
        id: "fig11",
        title: "Fig. 11: phase portraits, b = 200 um",
        query: "model=ravigneaux&backlash_um=200&te_um=20&mesh=s1a1&omega=1.97",
        seed: "Phase portraits and Poincaré sections at Omega = 0.5, 0.84 and 1.97 with TE 20 um and b = 200 um.",
        assumed: "Omega = 1.97 is selected.",
    },
    Preset {
        id: "phasing5",
        title: "Planet phasing: in-phase (A) vs sequential (B), N = 5",
        query: "model=ravigneaux&planets=5&phasing=sequential&mesh=s1a1&omega=0.84&a=model%3Dravigneaux%26planets%3D5%26phasing%3Din-phase%26mesh%3Ds1a1%26omega%3D0.84",
        seed: "Not in the seed: planet phasing after Parker & Lin (2004). In phase, the N meshes of a kind engage together and their excitations add; in sequence, planet n is shifted by z psi_n (z the central member's teeth, psi_n = 2 pi (n - 1) / N), so in the net torque on a central member the mesh order k cancels unless k z / N is a whole number. With the default tooth counts (36, 48, 84) sequential equals in-phase for N = 3, 4 and 6; with N = 5 orders 1 to 4 (and 6) cancel and only order 5 acts. This preset loads the comparison: A in phase, B in sequence; the summary line gives the surviving fraction of each order and the response at orders 1 to 4 (switch the phasing control to see A's numbers).",
        assumed: "N = 5 with the default tooth counts is a teaching case: five equally spaced pairs would clash (a long planet and the next short planet overlap) and (teeth_r + teeth_s2) = 132 is not a multiple of 5, so such a set cannot be assembled; the torsional model still runs and the phases are those of equal spacing.",
    },
    Preset {
        id: "pair",
        title: "Classic single gear pair",
        query: "model=gear-pair&mesh=pg&omega_from=0.3&omega_to=2.5&omega=1",
        seed: "Not in the seed: the single spur pair with backlash of Kahraman & Singh (1990), the textbook case of single- and double-sided impacts.",
        assumed: "Module 4 mm, 30/45 teeth, steel discs of 30 mm face width, k = 1e9 N/m, v = 0.2, xi = 0.06, b = 100 um, 20 um TE, 500 N m on the pinion (solver defaults).",
    },
];

/// Finds a preset by id.
pub fn preset(id: &str) -> Option<&'static Preset> {
    PRESETS.iter().find(|p| p.id == id)
}

/// The note shown when a preset is loaded.
pub fn note(p: &Preset) -> String {
    format!(
        "{}. The seed states: {} Assumed: {} {SCALE_NOTE}",
        p.title, p.seed, p.assumed
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::link::decode;

    #[test]
    fn every_preset_decodes_without_issues_and_builds() {
        assert!(PRESETS.len() >= 16);
        for p in PRESETS {
            let d = decode(p.query);
            assert!(d.issues.is_empty(), "{}: {:?}", p.id, d.issues);
            assert!(
                solver::steady::Model::new(&d.settings.params).is_ok(),
                "{}",
                p.id
            );
            assert!(!p.seed.is_empty() && !p.assumed.is_empty());
            assert_eq!(preset(p.id), Some(p));
        }
    }

    #[test]
    fn seed_figure_presets_carry_the_stated_values() {
        use solver::keys::{get, Value};
        let b = |id: &str| {
            get(
                &decode(preset(id).unwrap().query).settings.params,
                "backlash_um",
            )
        };
        assert_eq!(b("fig4a"), Some(Value::Num(200.0)));
        assert_eq!(b("fig8a"), Some(Value::Num(50.0)));
        assert_eq!(b("fig2"), Some(Value::Num(0.0)));
        let d = decode(preset("fig7").unwrap().query);
        assert_eq!(d.settings.view.omega, 1.97);
        // The phasing preset is an A/B comparison: A in phase, B in sequence, N = 5.
        let d = decode(preset("phasing5").unwrap().query);
        assert_eq!(
            get(&d.settings.params, "phasing"),
            Some(Value::Text("sequential".into()))
        );
        let a = d.pinned.unwrap();
        assert_eq!(
            get(&a.params, "phasing"),
            Some(Value::Text("in-phase".into()))
        );
        assert_eq!(get(&a.params, "planets"), Some(Value::Num(5.0)));
    }
}
