//! Every figure preset against what the paper states, figure by figure and
//! panel by panel. The table below is written from the paper (Shen, Liu,
//! Yang and Zhang: its figure captions and sections 3.1-3.2) and from
//! `docs/model.md`'s "The seed's figures, as settings", not from
//! `presets.rs`; every member of every preset is decoded as the page decodes a link and
//! compared with the Table 1 defaults plus the figure's stated values.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use figures::link::decode;
use figures::presets::{preset, PRESETS};
use figures::settings::MeshSel;
use solver::keys::{self, Value};
use solver::params::ModelParams;

/// A value the paper states for a figure.
#[derive(Debug, Clone, Copy)]
enum Stated {
    /// The same on every panel and curve.
    Fixed(f64),
    /// One value per panel a, b, c (or per curve), in order.
    PerPanel(&'static [f64]),
    /// Only a range "from lo to hi": the curves' values are gearshock's.
    Range(f64, f64),
}

/// One figure as the paper states it.
struct Figure {
    id: &'static str,
    /// The meshes of panels a-d, or the one mesh every panel shows.
    meshes: &'static [&'static str],
    backlash_um: Stated,
    te_um: Stated,
    /// The one Omega of an orbit figure.
    omega: Option<f64>,
    /// A bifurcation diagram over Omega up to 2 with 100 samples per Omega.
    bifurcation: bool,
    /// gearshock's reading of where the TE acts (the paper's "Ec_all" for
    /// Fig. 2; Table 1's sun-s1 eccentricity elsewhere).
    te_meshes: &'static str,
    /// The harmonics of a frequency response: the paper's own method has
    /// one (its describing function), gearshock's converged branch the
    /// page's default.
    harmonics: u32,
}

/// The page's default harmonics of a frequency response.
const CONVERGED: u32 = 5;

const FOUR: &[&str] = &["s1a1", "s2b1", "a1b1", "rb1"];
const S1A1: &[&str] = &["s1a1"];

/// A frequency response of the four meshes (Figs. 2 and 3).
const fn frf(
    id: &'static str,
    backlash_um: Stated,
    te_um: Stated,
    te_meshes: &'static str,
    harmonics: u32,
) -> Figure {
    Figure {
        id,
        meshes: FOUR,
        backlash_um,
        te_um,
        omega: None,
        bifurcation: false,
        te_meshes,
        harmonics,
    }
}

/// A figure of the sun-planet mesh s1a1 with the TE on the sun meshes: a
/// bifurcation diagram (`omega` `None`) or the orbits at one Omega.
const fn s1a1(id: &'static str, backlash_um: Stated, te_um: Stated, omega: Option<f64>) -> Figure {
    Figure {
        id,
        meshes: S1A1,
        backlash_um,
        te_um,
        omega,
        bifurcation: omega.is_none(),
        te_meshes: "s1a",
        harmonics: CONVERGED,
    }
}

/// Figs. 4-7: backlash 200 um, TE 0 / 20 / 30 um.
const TE_PANELS: Stated = Stated::PerPanel(&[0.0, 20.0, 30.0]);
/// Figs. 8-11: TE 20 um, backlash 50 / 100 / 200 um.
const BACKLASH_PANELS: Stated = Stated::PerPanel(&[50.0, 100.0, 200.0]);

const PAPER: &[Figure] = &[
    // 3.1.1: b = 0, the TE sine amplitude "increased from 5 um to 30 um";
    // fig2h1 as the paper computed it, one harmonic.
    frf(
        "fig2",
        Stated::Fixed(0.0),
        Stated::Range(5.0, 30.0),
        "all",
        CONVERGED,
    ),
    frf(
        "fig2h1",
        Stated::Fixed(0.0),
        Stated::Range(5.0, 30.0),
        "all",
        1,
    ),
    // 3.1.2: TE fundamental 60 um, backlash "increasing from 50 um to 200
    // um"; fig3h1 as the paper computed it, one harmonic.
    frf(
        "fig3",
        Stated::Range(50.0, 200.0),
        Stated::Fixed(60.0),
        "s1a",
        CONVERGED,
    ),
    frf(
        "fig3h1",
        Stated::Range(50.0, 200.0),
        Stated::Fixed(60.0),
        "s1a",
        1,
    ),
    // Fig. 4 caption: backlash 200 um, TE 0 / 20 / 30 um; Figs. 5-7: one
    // Omega each, b = 200 um, TE varied across panels.
    s1a1("fig4", Stated::Fixed(200.0), TE_PANELS, None),
    s1a1("fig5", Stated::Fixed(200.0), TE_PANELS, Some(0.5)),
    s1a1("fig6", Stated::Fixed(200.0), TE_PANELS, Some(0.84)),
    s1a1("fig7", Stated::Fixed(200.0), TE_PANELS, Some(1.97)),
    // Fig. 8 caption: TE 20 um, backlash 50 / 100 / 200 um; Figs. 9-11:
    // "the backlash increases" (Fig. 8's values, docs/model.md).
    s1a1("fig8", BACKLASH_PANELS, Stated::Fixed(20.0), None),
    s1a1("fig9", BACKLASH_PANELS, Stated::Fixed(20.0), Some(0.5)),
    s1a1("fig10", BACKLASH_PANELS, Stated::Fixed(20.0), Some(0.84)),
    s1a1("fig11", BACKLASH_PANELS, Stated::Fixed(20.0), Some(1.97)),
];

/// The values a stated quantity takes across the preset's members.
fn expected_values(stated: Stated, family_values: Option<&[f64]>, id: &str) -> Vec<f64> {
    match stated {
        Stated::Fixed(x) => vec![x],
        Stated::PerPanel(v) => {
            assert_eq!(family_values, Some(v), "{id}: the panels' values");
            v.to_vec()
        }
        Stated::Range(lo, hi) => {
            let v = family_values.unwrap_or_else(|| panic!("{id}: a family over {lo}..{hi}"));
            assert_eq!(v.first(), Some(&lo), "{id}");
            assert_eq!(v.last(), Some(&hi), "{id}");
            assert!(v.windows(2).all(|w| w[0] < w[1]), "{id}: {v:?}");
            v.to_vec()
        }
    }
}

#[test]
fn every_figure_preset_holds_the_papers_family_and_panels() {
    for fig in PAPER {
        let p = preset(fig.id).unwrap_or_else(|| panic!("no preset {}", fig.id));
        let varied: Vec<(&str, Stated)> = [("backlash_um", fig.backlash_um), ("te_um", fig.te_um)]
            .into_iter()
            .filter(|(_, s)| !matches!(s, Stated::Fixed(_)))
            .collect();
        assert_eq!(varied.len(), 1, "{}: one family per figure", fig.id);
        let family = p
            .family
            .unwrap_or_else(|| panic!("{} has no family", fig.id));
        assert_eq!(family.key, varied[0].0, "{}", fig.id);
        let backlash = expected_values(
            fig.backlash_um,
            (family.key == "backlash_um").then_some(family.values),
            fig.id,
        );
        let te = expected_values(
            fig.te_um,
            (family.key == "te_um").then_some(family.values),
            fig.id,
        );
        // The note says in words where the TE acts.
        let words = match fig.te_meshes {
            "all" => "every mesh",
            _ => "small-sun meshes",
        };
        assert!(p.note.contains(words), "{}: {words}", fig.id);
        // Panels by mesh (Figs. 2, 3) or one mesh for every panel.
        if fig.meshes.len() > 1 {
            assert_eq!(p.meshes, Some(fig.meshes), "{}", fig.id);
        } else {
            assert_eq!(p.meshes, None, "{}", fig.id);
        }
        for (m, _) in family.values.iter().enumerate() {
            for (panel, mesh) in fig.meshes.iter().enumerate() {
                let d = decode(&p.member_query(m, panel));
                assert!(d.issues.is_empty(), "{}: {:?}", fig.id, d.issues);
                let pick = |v: &[f64]| if v.len() == 1 { v[0] } else { v[m] };
                // Table 1 (docs/model.md's defaults), the figure's values on top.
                let mut want = ModelParams::default();
                keys::set(&mut want, "te_meshes", Value::Text(fig.te_meshes.into())).unwrap();
                keys::set(&mut want, "backlash_um", Value::Num(pick(&backlash))).unwrap();
                keys::set(&mut want, "te_um", Value::Num(pick(&te))).unwrap();
                assert_eq!(
                    d.settings.params, want,
                    "{} member {m} panel {panel}",
                    fig.id
                );
                assert_eq!(
                    d.settings.view.mesh,
                    MeshSel::Named((*mesh).into()),
                    "{}",
                    fig.id
                );
                if fig.meshes.len() > 1 {
                    assert_eq!(d.settings.view.harmonics, fig.harmonics, "{}", fig.id);
                }
                // The note names the plotted quantity in plain words.
                assert!(p.note.contains(figures::presets::X_WORDS), "{}", fig.id);
                if let Some(omega) = fig.omega {
                    assert_eq!(d.settings.view.omega, omega, "{}", fig.id);
                    assert!(p.settings.contains(&("omega", &omega.to_string()[..])));
                }
                // The page's link of this member restores it exactly.
                let again = decode(&figures::link::encode(&d.settings));
                assert!(again.issues.is_empty(), "{:?}", again.issues);
                assert_eq!(again.settings, d.settings, "{}", fig.id);
                if fig.bifurcation {
                    assert_eq!(d.settings.view.omega_to, 2.0, "{}", fig.id);
                    assert_eq!(d.settings.view.record_periods, 100, "{}", fig.id);
                }
            }
        }
    }
}

#[test]
fn the_paper_figures_are_all_there_and_nothing_else_claims_to_be_one() {
    let ids: Vec<&str> = PRESETS
        .iter()
        .map(|p| p.id)
        .filter(|id| id.starts_with("fig"))
        .collect();
    let want: Vec<&str> = PAPER.iter().map(|f| f.id).collect();
    assert_eq!(ids, want);
    // The paper's own load case: Table 1's torques balance over the mechanism.
    let d = decode(&preset("table1").unwrap().query());
    assert_eq!(d.settings.params, ModelParams::default());
    assert_eq!(
        keys::get(&d.settings.params, "ring_support_radius_mm"),
        Some(Value::Text("auto".into()))
    );
}
