//! Presets: the Table 1 defaults, the seed paper's figures panel for panel
//! (`docs/model.md`, "The seed's figures, as settings") and two teaching
//! cases.
//!
//! A preset is data: the settings every panel shares (flat link keys, the
//! same as the CLI's `--set` and the page's URL), the family (one key and the
//! values it takes across a figure's curves or panels), the meshes of a
//! figure whose panels are one mesh kind each, and a note in plain words of
//! what the paper shows and what gearshock had to assume.
//!
//! The paper is ambiguous in two places and each figure preset names its
//! reading through a parameter key: `te_meshes` (Fig. 2's "Ec_all": TE on
//! every mesh; the other figures: on the small-sun meshes, as Table 1's sun
//! s1 eccentricity) and `ring_support_radius_mm` (left at `auto`, the ring's
//! base circle, 157.9 mm; the paper prints 15.79 mm).
//!
//! Loading a preset loads its whole family (the page's controller adds the
//! family to [`Preset::query`], the first member on the first panel's
//! mesh); every member's link alone is [`Preset::member_query`].

/// One parameter taking several values across a figure's curves or panels.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Family {
    /// The link key that varies, e.g. `te_um`.
    pub key: &'static str,
    /// Its values, in the order of the paper's curves or panels a, b, c.
    pub values: &'static [f64],
}

/// One preset.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Preset {
    /// Stable id (used by tests, the CLI and the select's values), e.g. `fig5`.
    pub id: &'static str,
    /// Menu label.
    pub title: &'static str,
    /// The settings every panel and member shares, as link key/value pairs
    /// (neither the family's key nor, when `meshes` is given, `mesh`).
    pub settings: &'static [(&'static str, &'static str)],
    /// The varied parameter, if the preset is a family.
    pub family: Option<Family>,
    /// The meshes of a figure whose panels show one mesh each (Figs. 2, 3).
    pub meshes: Option<&'static [&'static str]>,
    /// One or two plain sentences: what the paper shows, what was assumed.
    pub note: &'static str,
    /// An A/B comparison's pinned state A, as a link query (teaching cases).
    pub pinned: Option<&'static str>,
}

impl Preset {
    /// The link of one member: family value `member` on panel mesh `panel`
    /// (indices past the end fall back to the first).
    pub fn member_query(&self, member: usize, panel: usize) -> String {
        let mut parts: Vec<String> = self
            .settings
            .iter()
            .map(|(k, v)| format!("{k}={v}"))
            .collect();
        if let Some(f) = &self.family {
            if let Some(x) = f.values.get(member).or(f.values.first()) {
                parts.push(format!("{}={}", f.key, crate::settings::fmt_exact(*x)));
            }
        }
        if let Some(m) = self.meshes {
            if let Some(name) = m.get(panel).or(m.first()) {
                parts.push(format!("mesh={name}"));
            }
        }
        if let Some(a) = self.pinned {
            parts.push(format!(
                "{}={}",
                crate::link::PINNED_KEY,
                crate::link::percent_encode(a)
            ));
        }
        parts.join("&")
    }

    /// The link the page loads: the first member on the first panel's mesh.
    pub fn query(&self) -> String {
        self.member_query(0, 0)
    }
}

const MODEL: (&str, &str) = ("model", "ravigneaux");
const RANGE: [(&str, &str); 2] = [("omega_from", "0.1"), ("omega_to", "2")];
const FOUR_MESHES: &[&str] = &["s1a1", "s2b1", "a1b1", "rb1"];
const TE_0_20_30: Family = Family {
    key: "te_um",
    values: &[0.0, 20.0, 30.0],
};
const B_50_100_200: Family = Family {
    key: "backlash_um",
    values: &[50.0, 100.0, 200.0],
};

/// Settings of the bifurcation figures (4 and 8) besides the family.
macro_rules! bifurcation {
    ($($k:literal = $v:literal),*) => {
        &[
            MODEL, $(($k, $v),)* ("te_meshes", "s1a"), ("mesh", "s1a1"), RANGE[0], RANGE[1],
            ("bif_dir", "both"), ("record_periods", "100"),
        ]
    };
}

/// Settings of the orbit figures (5-7 and 9-11) besides the family.
macro_rules! orbit {
    ($omega:literal, $($k:literal = $v:literal),*) => {
        &[MODEL, $(($k, $v),)* ("te_meshes", "s1a"), ("mesh", "s1a1"), ("omega", $omega)]
    };
}

/// Every preset, in menu order.
pub const PRESETS: &[Preset] = &[
    Preset {
        id: "table1",
        title: "Table 1 defaults",
        settings: &[MODEL],
        family: None,
        meshes: None,
        note: "The paper's Table 1: three planet pairs, module 4 mm, teeth 36/48/21/84, mesh stiffness 10⁹ N/m, 100 µm backlash, a 20 µm eccentricity of sun s1 and 2000 N m on s1. gearshock derives the radii from the tooth counts (the printed base radii do not follow from them) and puts the 20 µm as a sine on the small-sun meshes.",
        pinned: None,
    },
    Preset {
        id: "fig2",
        title: "Fig. 2: frequency response, TE 5-30 µm, no backlash (several harmonics, converged)",
        settings: &[MODEL, ("backlash_um", "0"), ("te_meshes", "all"), RANGE[0], RANGE[1]],
        family: Some(Family {
            key: "te_um",
            values: &[5.0, 10.0, 15.0, 20.0, 25.0, 30.0],
        }),
        meshes: Some(FOUR_MESHES),
        note: "The paper shows the harmonic-balance response of the tooth deflection x, TE included, of each kind of mesh (panels a-d) with no backlash as the TE's sine amplitude on all meshes rises from 5 to 30 µm. This is gearshock's converged branch with several harmonics (the harmonics setting; \"Fig. 2, one harmonic\" is the paper's own method), with the same sine on every mesh (switch to the small-sun meshes only to compare; the paper's superscript c may also mean a cosine) in steps of 5 µm over Ω 0.1 to 2, none of which the paper states.",
        pinned: None,
    },
    Preset {
        id: "fig2h1",
        title: "Fig. 2, one harmonic: frequency response as the paper computed it, TE 5-30 µm, no backlash",
        settings: &[MODEL, ("backlash_um", "0"), ("te_meshes", "all"), RANGE[0], RANGE[1], ("harmonics", "1")],
        family: Some(Family {
            key: "te_um",
            values: &[5.0, 10.0, 15.0, 20.0, 25.0, 30.0],
        }),
        meshes: Some(FOUR_MESHES),
        note: "Fig. 2 as the paper computed it: the tooth deflection x, TE included, of each kind of mesh from one harmonic (H = 1, the describing function of its equations 9 to 13) with no backlash, as the TE's sine amplitude on every mesh rises from 5 to 30 µm. One harmonic overstates the first-mode peak by about a quarter and misses the superharmonic peak near Ω 0.12; the preset \"Fig. 2\" is the converged branch.",
        pinned: None,
    },
    Preset {
        id: "fig3",
        title: "Fig. 3: frequency response, backlash 50-200 µm, TE 60 µm (several harmonics, converged)",
        settings: &[MODEL, ("te_um", "60"), ("te_meshes", "s1a"), RANGE[0], RANGE[1]],
        family: Some(Family {
            key: "backlash_um",
            values: &[50.0, 100.0, 150.0, 200.0],
        }),
        meshes: Some(FOUR_MESHES),
        note: "The paper shows the harmonic-balance response of the tooth deflection x, TE included, of each kind of mesh (panels a-d) with a 60 µm TE fundamental as the backlash of every mesh rises from 50 to 200 µm. This is gearshock's converged branch with several harmonics (the harmonics setting), unstable over most of the range (\"Fig. 3, one harmonic\" is the paper's own method), with the 60 µm as a sine on the small-sun meshes (read as a mean it would have no dynamic effect) and 50, 100, 150 and 200 µm; the paper gives only the range.",
        pinned: None,
    },
    Preset {
        id: "fig3h1",
        title: "Fig. 3, one harmonic: frequency response as the paper computed it, backlash 50-200 µm, TE 60 µm",
        settings: &[MODEL, ("te_um", "60"), ("te_meshes", "s1a"), RANGE[0], RANGE[1], ("harmonics", "1")],
        family: Some(Family {
            key: "backlash_um",
            values: &[50.0, 100.0, 150.0, 200.0],
        }),
        meshes: Some(FOUR_MESHES),
        note: "Fig. 3 as the paper computed it: the tooth deflection x, TE included, of each kind of mesh from one harmonic (H = 1, the describing function of its equations 9 to 13), with a 60 µm TE sine on the small-sun meshes, as the backlash of every mesh rises from 50 to 200 µm. The preset \"Fig. 3\" is the converged branch with several harmonics.",
        pinned: None,
    },
    Preset {
        id: "fig4",
        title: "Fig. 4: bifurcation, TE 0 / 20 / 30 µm, backlash 200 µm",
        settings: bifurcation!("backlash_um" = "200"),
        family: Some(TE_0_20_30),
        meshes: None,
        note: "The paper shows bifurcation diagrams of the tooth deflection x, TE included, of mesh s1a1 over Ω 0 to 2, one hundred samples per Ω, with 200 µm backlash and TE 0, 20 and 30 µm in panels a-c. gearshock puts the TE as a sine on the small-sun meshes, starts at Ω 0.1 and sweeps up and down; the paper states neither its sweep nor its frequency scale.",
        pinned: None,
    },
    Preset {
        id: "fig5",
        title: "Fig. 5: orbits at Ω 0.5, TE 0 / 20 / 30 µm",
        settings: orbit!("0.5", "backlash_um" = "200"),
        family: Some(TE_0_20_30),
        meshes: None,
        note: "The paper shows the tooth deflection x, TE included, and its rate: phase portraits (panels a-c) and Poincaré sections (d-f) at Ω 0.5 as the TE increases: a period-1 motion doubles. It states neither the TE values nor the backlash or the mesh here; gearshock takes Fig. 4's 200 µm and TE 0, 20 and 30 µm (a sine on the small-sun meshes) on mesh s1a1.",
        pinned: None,
    },
    Preset {
        id: "fig6",
        title: "Fig. 6: orbits at Ω 0.84, TE 0 / 20 / 30 µm",
        settings: orbit!("0.84", "backlash_um" = "200"),
        family: Some(TE_0_20_30),
        meshes: None,
        note: "The paper shows the tooth deflection x, TE included, and its rate: phase portraits (panels a-c) and Poincaré sections (d-f) at Ω 0.84 as the TE increases: a period-1 motion turns quasi-periodic. It states neither the TE values nor the backlash or the mesh here; gearshock takes Fig. 4's 200 µm and TE 0, 20 and 30 µm (a sine on the small-sun meshes) on mesh s1a1.",
        pinned: None,
    },
    Preset {
        id: "fig7",
        title: "Fig. 7: orbits at Ω 1.97, TE 0 / 20 / 30 µm",
        settings: orbit!("1.97", "backlash_um" = "200"),
        family: Some(TE_0_20_30),
        meshes: None,
        note: "The paper shows the tooth deflection x, TE included, of mesh s1a1 and its rate at Ω 1.97 with 200 µm backlash as the TE increases: phase portraits in panels a-c, Poincaré sections in d-f (its caption says \"different backlashes\" for d-f, its text says TE). gearshock takes TE 0, 20 and 30 µm as in Fig. 4, a sine on the small-sun meshes; the paper does not state the values here.",
        pinned: None,
    },
    Preset {
        id: "fig8",
        title: "Fig. 8: bifurcation, backlash 50 / 100 / 200 µm, TE 20 µm",
        settings: bifurcation!("te_um" = "20"),
        family: Some(B_50_100_200),
        meshes: None,
        note: "The paper shows bifurcation diagrams of the tooth deflection x, TE included, of mesh s1a1 with 20 µm TE and backlash 50, 100 and 200 µm in panels a-c. gearshock assumes Fig. 4's Ω range and one hundred samples per Ω (the paper does not restate them), the TE as a sine on the small-sun meshes, and sweeps up and down.",
        pinned: None,
    },
    Preset {
        id: "fig9",
        title: "Fig. 9: orbits at Ω 0.5, backlash 50 / 100 / 200 µm",
        settings: orbit!("0.5", "te_um" = "20"),
        family: Some(B_50_100_200),
        meshes: None,
        note: "The paper shows the tooth deflection x, TE included, and its rate: phase portraits (panels a-c) and Poincaré sections (d-f) at Ω 0.5 as the backlash increases. It states neither the backlash values nor the TE or the mesh here; gearshock takes Fig. 8's 50, 100 and 200 µm and 20 µm TE (a sine on the small-sun meshes) on mesh s1a1.",
        pinned: None,
    },
    Preset {
        id: "fig10",
        title: "Fig. 10: orbits at Ω 0.84, backlash 50 / 100 / 200 µm",
        settings: orbit!("0.84", "te_um" = "20"),
        family: Some(B_50_100_200),
        meshes: None,
        note: "The paper shows the tooth deflection x, TE included, and its rate: phase portraits (panels a-c) and Poincaré sections (d-f) at Ω 0.84 as the backlash increases. It states neither the backlash values nor the TE or the mesh here; gearshock takes Fig. 8's 50, 100 and 200 µm and 20 µm TE (a sine on the small-sun meshes) on mesh s1a1.",
        pinned: None,
    },
    Preset {
        id: "fig11",
        title: "Fig. 11: orbits at Ω 1.97, backlash 50 / 100 / 200 µm",
        settings: orbit!("1.97", "te_um" = "20"),
        family: Some(B_50_100_200),
        meshes: None,
        note: "The paper shows the tooth deflection x, TE included, and its rate: phase portraits (panels a-c) and Poincaré sections (d-f) at Ω 1.97 as the backlash increases. It states neither the backlash values nor the TE or the mesh here; gearshock takes Fig. 8's 50, 100 and 200 µm and 20 µm TE (a sine on the small-sun meshes) on mesh s1a1.",
        pinned: None,
    },
    Preset {
        id: "phasing5",
        title: "Planet phasing: in-phase (A) vs sequential (B), N = 5",
        settings: &[MODEL, ("planets", "5"), ("phasing", "sequential"), ("mesh", "s1a1"), ("omega", "0.84")],
        family: None,
        meshes: None,
        note: "Not in the paper: planet phasing after Parker & Lin (2004), in phase (A) against in sequence (B); with five planets and these tooth counts only every fifth mesh order reaches the suns. Five equally spaced pairs of this set could not be assembled, so this is a teaching case.",
        pinned: Some("model=ravigneaux&planets=5&phasing=in-phase&mesh=s1a1&omega=0.84"),
    },
    Preset {
        id: "pair",
        title: "Classic single gear pair",
        settings: &[("model", "gear-pair"), ("mesh", "pg"), ("omega_from", "0.3"), ("omega_to", "2.5"), ("omega", "1")],
        family: None,
        meshes: None,
        note: "Not in the paper: the single spur pair with backlash of Kahraman & Singh (1990), the textbook case of single- and double-sided impacts, with gearshock's own pair (module 4 mm, 30/45 teeth, 100 µm backlash, 20 µm TE).",
        pinned: None,
    },
];

/// The plotted quantity in plain words, as every figure preset's note and
/// the claims name it: x = delta - e, the paper's relative meshing
/// displacement.
pub const X_WORDS: &str = "tooth deflection x, TE included";

/// Finds a preset by id.
pub fn preset(id: &str) -> Option<&'static Preset> {
    PRESETS.iter().find(|p| p.id == id)
}

/// The note shown when a preset is loaded.
pub fn note(p: &Preset) -> String {
    let shown = match p.meshes {
        Some(m) if m.len() > 1 => format!(
            " The frequency response shows panels a-{} side by side (meshes {}); the other views show mesh {}, and choosing a mesh in the settings shows that mesh alone.",
            char::from(b'a' + (m.len() - 1).min(25) as u8),
            m.join(", "),
            m[0]
        ),
        _ => String::new(),
    };
    format!("{}. {}{shown}", p.title, p.note)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::link::decode;
    use solver::keys::{get, Value};

    #[test]
    fn every_member_of_every_preset_decodes_without_issues_and_builds() {
        for p in PRESETS {
            let members = p.family.map_or(1, |f| f.values.len());
            let panels = p.meshes.map_or(1, <[_]>::len);
            for m in 0..members {
                for panel in 0..panels {
                    let d = decode(&p.member_query(m, panel));
                    assert!(d.issues.is_empty(), "{} {m} {panel}: {:?}", p.id, d.issues);
                    assert!(solver::model::Model::new(&d.settings.params).is_ok());
                }
            }
            assert_eq!(p.query(), p.member_query(0, 0));
            assert_eq!(preset(p.id), Some(p));
            // Plain words: no key names or file names in what a user reads.
            for word in [
                "_um",
                "model.md",
                "backlash_um",
                "te_um",
                " um",
                "..=",
                "the seed",
            ] {
                assert!(!p.note.contains(word), "{}: {word}", p.id);
            }
            // No key name of any kind (every key with an underscore, and
            // no word with one), nor a choice's code word.
            for k in solver::keys::KEYS.iter().filter(|k| k.name.contains('_')) {
                assert!(!p.note.contains(k.name), "{}: {}", p.id, k.name);
            }
            assert!(!p.note.contains('_'), "{}: an underscore", p.id);
            for word in ["te_meshes", "s1a\"", "gear-pair", "in-phase"] {
                assert!(!p.note.contains(word), "{}: {word}", p.id);
            }
            let sentences = sentence_count(p.note);
            assert!(sentences <= 2, "{}: {sentences} sentences", p.id);
            // The shared settings hold neither the family's key nor the panels' mesh.
            if let Some(f) = p.family {
                assert!(p.settings.iter().all(|(k, _)| *k != f.key), "{}", p.id);
            }
            if p.meshes.is_some() {
                assert!(p.settings.iter().all(|(k, _)| *k != "mesh"), "{}", p.id);
            }
        }
    }

    /// Sentences: full stops followed by a space, except after "Fig"/"Figs".
    fn sentence_count(text: &str) -> usize {
        let parts: Vec<&str> = text.split(". ").collect();
        1 + parts[..parts.len() - 1]
            .iter()
            .filter(|s| !(s.ends_with("Fig") || s.ends_with("Figs")))
            .count()
    }

    #[test]
    fn the_phasing_preset_is_an_ab_comparison() {
        let d = decode(&preset("phasing5").unwrap().query());
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
