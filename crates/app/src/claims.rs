//! The paper's claims with gearshock's verdicts, as the page lists them:
//! one table, kept word for word in step with `docs/paper.md` (whose
//! numbers `cargo test -p cli --test paper` recomputes) by this module's
//! test, so the page cannot drift from the document or the code.

/// One claim of the paper and what gearshock finds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Claim {
    /// The claim's number in `docs/paper.md` ("1" to "10", parts "4b",
    /// "7a", "7b"), or the name of a section ("scale", "impact").
    pub id: &'static str,
    /// What the paper says.
    pub says: &'static str,
    /// The verdict, as in the document's "verdicts at a glance".
    pub verdict: &'static str,
    /// The evidence: gearshock's numbers, a sentence of the document.
    pub evidence: &'static str,
    /// The figure preset that shows it.
    pub figure: Option<&'static str>,
    /// The command that reproduces the numbers (the document's).
    pub command: &'static str,
    /// The values of the command's placeholders, as the document gives
    /// them (with its backticks; empty if none).
    pub with: &'static str,
}

const SIMULATE_TE: &str =
    "gearshock simulate --set backlash_um=200 --set te_um=$x --mesh s1a1 --omega $w";
const SIMULATE_B: &str =
    "gearshock simulate --set te_um=20 --set backlash_um=$x --mesh s1a1 --omega $w";
const SWEEP: &str = "gearshock bifurcation --set backlash_um=$b --set te_um=$te --mesh s1a1 --omega-from 0.15 --omega-to 2 --points 38 --direction up";
const FINE: &str = "gearshock bifurcation --set backlash_um=$b --set te_um=$te --mesh s1a1 --omega-from $from --omega-to $to --points $n --direction up";
const LYAPUNOV: &str = "gearshock lyapunov --set backlash_um=$b --set te_um=20 --omega-from 0.3 --omega-to 1 --points 15";

/// Every claim, in the document's order, then the frequency scale and the
/// impact criterion. The deflection is x, the tooth deflection with the TE
/// included: the quantity the paper plots.
pub const CLAIMS: &[Claim] = &[
    Claim {
        id: "1",
        says: "TE intensifies the resonances and adds harmonic peaks",
        verdict: "partly reproduced: peaks grow with TE, none appears",
        evidence: "The peaks of the tooth deflection x, TE included, grow with the TE. But no peak appears: the small peak near Ω 0.12 (half the first natural frequency, a superharmonic resonance of the stiffness variation) is there at 5 µm already, and the one-harmonic method, the paper's own, cannot show it at all.",
        figure: Some("fig2"),
        command: "gearshock frf --set backlash_um=0 --set te_meshes=$reading --set te_um=$te --mesh all --omega-from 0.1 --omega-to 2",
        with: "`reading` = all or s1a, `te` = 5 or 30",
    },
    Claim {
        id: "2",
        says: "more backlash raises the peak at Ω 1.4, not at 0.4 and 1.2",
        verdict: "partly reproduced: on the literal scale, but not on the matched one nor with one harmonic",
        evidence: "Matched on the first mode, the tooth deflection x, TE included, rises at the paper's 1.2 (0.695: 125.3 → 182.8 µm) more than at its 1.4 (0.811: 156.0 → 196.2 µm), so the paper's contrast, no change at 1.2 and a sharp rise at 1.4, does not hold. The paper's own one-harmonic branch shows no rise at 1.4 on either scale.",
        figure: Some("fig3"),
        command: "gearshock simulate --set backlash_um=$b --set te_um=60 --mesh s1a1 --omega $w",
        with: "`b` = 50, 100, 150, 200; `w` = 0.4, 1.2, 1.4, 0.232, 0.695, 0.811",
    },
    Claim {
        id: "3",
        says: "TE raises the low-frequency amplitude from 2.9 to 26",
        verdict: "not reproduced: x grows 2.9 → 3.0 → 3.5 µm at Ω 0.25",
        evidence: "The tooth deflection x, TE included, grows 2.9 → 3.0 → 3.5 µm at Ω 0.25 (the paper's 0.4 matched on the first mode), 4.9 → 6.5 → 8.5 µm at the literal 0.4, and 8.9 → 10.3 µm at the first mode's own peak: nowhere near tenfold.",
        figure: Some("fig4"),
        command: SWEEP,
        with: "with `b` = 200 and `te` = 0, 20, 30",
    },
    Claim {
        id: "4",
        says: "TE has little effect at Ω 1.2–2",
        verdict: "not reproduced: the amplitude there grows 4.1 → 125.8 µm",
        evidence: "the largest amplitude of the tooth deflection x, TE included, at Ω ≥ 1.2 grows from 4.1 µm (no TE) to 86.2 (20 µm) and 125.8 µm (30 µm), and over the matched range 0.70–1.15 from 7.9 to 119.4 µm",
        figure: Some("fig4"),
        command: SWEEP,
        with: "with `b` = 200 and `te` = 0, 20, 30",
    },
    Claim {
        id: "4b",
        says: "TE brings random vibration in the mid- and high-frequency sections",
        verdict: "reproduced: with TE the motion is not periodic over most of Ω 0.45–2",
        evidence: "without TE the tooth deflection x, TE included, moves periodically except over Ω 0.50–0.55, 1.05–1.15 and at 1.80; with 20 µm TE it is not periodic over 0.50–1.70 and 1.95–2.00, with 30 µm over 0.50–1.80 and 1.90–2.00.",
        figure: Some("fig4"),
        command: SWEEP,
        with: "with `b` = 200 and `te` = 0, 20, 30",
    },
    Claim {
        id: "5",
        says: "\"negative vibration\", i.e. bilateral impact, comes with TE",
        verdict: "not reproduced: x never goes negative at 200 µm backlash; read as the penetration depth, the drive flanks part with TE from Ω 0.45–0.50 up",
        evidence: "the lowest tooth deflection x, TE included, over Ω 0.15–2 is 195.2, 101.9 and 33.5 µm for TE 0, 20 and 30 µm: never negative, and the back flanks of no mesh ever touch.",
        figure: Some("fig4"),
        command: SWEEP,
        with: "with `b` = 200 and `te` = 0, 20, 30",
    },
    Claim {
        id: "6",
        says: "Figs. 5–7: period 1 → period 2 → quasi-periodic as TE grows; the velocity grows",
        verdict: "partly reproduced: period 1 is lost and the penetration velocity grows, but no period 2 appears; the paper contradicts itself",
        evidence: "At Ω 0.84 and 1.97 the TE destroys the period-1 motion, and the penetration velocity (the rate of the tooth deflection x, TE included) grows with the TE at all three of the paper's frequencies (at 1.97: 0.02 → 2.41 → 3.13 m/s), as the paper says.",
        figure: Some("fig5"),
        command: SIMULATE_TE,
        with: "`x` = 0, 20, 30; `w` = 0.5, 0.84, 1.97 and matched 0.290, 0.487, 1.142",
    },
    Claim {
        id: "7a",
        says: "Figs. 9–10: backlash has little effect at low and medium frequency",
        verdict: "reproduced: the backlash cannot act until the back flanks touch",
        evidence: "At the matched Ω 0.290 and 0.487 the three backlashes give the very same motion of the tooth deflection x, TE included.",
        figure: Some("fig9"),
        command: SIMULATE_B,
        with: "`x` = 50, 100, 200; `w` = 0.5, 0.84, 1.97 and matched 0.290, 0.487, 1.142",
    },
    Claim {
        id: "7b",
        says: "Fig. 11: backlash turns period 1 into quasi-periodic motion and chaos at high frequency",
        verdict: "not reproduced: the motion is chaotic for every backlash",
        evidence: "At Ω 1.97 the tooth deflection x, TE included, moves chaotically for every backlash, 50 µm included, with the same penetration velocity (2.41–2.45 m/s)",
        figure: Some("fig11"),
        command: SIMULATE_B,
        with: "`x` = 50, 100, 200; `w` = 0.5, 0.84, 1.97 and matched 0.290, 0.487, 1.142",
    },
    Claim {
        id: "8",
        says: "more backlash advances chaos from Ω 0.8 to 0.4",
        verdict: "not reproduced under either reading: chaos starts at Ω 0.50 for every backlash",
        evidence: "a negative tooth deflection x, TE included, first appears at Ω 0.85, 1.20 and none for 50, 100 and 200 µm: more backlash moves it up, and removes it.",
        figure: Some("fig8"),
        command: LYAPUNOV,
        with: "with `b` = 50, 100, 200 and `te` = 20",
    },
    Claim {
        id: "9",
        says: "more backlash means more intense shock",
        verdict: "not reproduced: the smallest backlash is the one that reaches the back flanks",
        evidence: "the back flanks of some mesh touch only with the smallest backlash, 50 µm, and the tooth deflection x, TE included, goes negative over Ω 0.90–1.70 with 50 µm",
        figure: Some("fig8"),
        command: SWEEP,
        with: "with `b` = 50, 100, 200 and `te` = 20",
    },
    Claim {
        id: "10",
        says: "keep the speed below Ω 0.8",
        verdict: "not reproduced: no speed below Ω 0.8 is free of impacts on every mesh",
        evidence: "In every case, even without TE, some mesh's drive flanks part from Ω 0.115 up (its tooth deflection x, TE included, falls below b)",
        figure: Some("fig8"),
        command: FINE,
        with: "`from`, `to`, `n` = 0.1, 0.8, 71; 0.105, 0.125, 21; 0.22, 0.245, 26; 0.565, 0.585, 21",
    },
    Claim {
        id: "scale",
        says: "resonances of the s1a1 deflection at Ω 0.4, 1.2 and 1.4",
        verdict: "on the literal scale 1.2 and 1.4 lie near modes, weakly; matched on the first mode (factor 0.58) the paper's 1.4 is the third mode",
        evidence: "Nothing lies near 0.4. gearshock's response of the tooth deflection x, TE included, peaks at the first mode (0.231), the second (0.575), and at the first mode's superharmonics (0.115 and 0.289 for the stiffness variation).",
        figure: Some("fig2"),
        command: "gearshock modes",
        with: "",
    },
    Claim {
        id: "impact",
        says: "any negative deflection is bilateral impact",
        verdict: "the readings differ: with 50 µm backlash x is negative over a wide band, the back flanks of s1a1 touch at one Ω",
        evidence: "with 50 µm, the tooth deflection x, TE included, is negative over Ω 0.90–1.70 but the back flanks of s1a1 touch only over 1.15–1.25 and at 1.35.",
        figure: Some("fig8"),
        command: SWEEP,
        with: "with `b` = 50, 100, 200 and `te` = 20",
    },
];

/// The placeholders' values in plain text: "with b = 200 and te = 0, 20, 30".
pub fn with_text(c: &Claim) -> String {
    c.with.replace('`', "")
}

/// A claim's heading on the page: "Claim 3", "The frequency scale", ...
pub fn heading(c: &Claim) -> String {
    match c.id {
        "scale" => "The frequency scale".into(),
        "impact" => "The impact criterion".into(),
        n => format!("Claim {n}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The document with its line breaks and runs of spaces as single spaces.
    fn doc() -> String {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/paper.md");
        let text = std::fs::read_to_string(path).unwrap();
        text.split_whitespace().collect::<Vec<_>>().join(" ")
    }

    /// A numbered claim ("3", "7a"), not a section.
    fn numbered(c: &Claim) -> bool {
        c.id.starts_with(|ch: char| ch.is_ascii_digit())
    }

    #[test]
    fn every_claim_is_the_documents_word_for_word() {
        let d = doc();
        for c in CLAIMS {
            if numbered(c) {
                // The row of the verdicts at a glance.
                let row = format!("| {} | {} | {} |", c.id, c.says, c.verdict);
                assert!(
                    d.contains(&row),
                    "claim {} differs from paper.md: {row}",
                    c.id
                );
            }
            assert!(
                d.contains(c.evidence),
                "claim {}'s evidence is not in paper.md",
                c.id
            );
            assert!(
                d.contains(c.command),
                "claim {}'s command is not in paper.md",
                c.id
            );
            if let Some(f) = c.figure {
                assert!(crate::presets::preset(f).is_some(), "{f}");
                // The page names the plotted quantity in plain words.
                assert!(
                    c.evidence.contains(crate::presets::X_WORDS),
                    "claim {}'s evidence does not name x in plain words",
                    c.id
                );
            }
        }
        // Every numbered claim of the document's verdicts at a glance is on
        // the page.
        let glance = d
            .split("## The verdicts at a glance")
            .nth(1)
            .and_then(|rest| rest.split(" ## ").next())
            .unwrap();
        let on_page = CLAIMS.iter().filter(|c| numbered(c)).count();
        let rows = (1..=30)
            .flat_map(|n| ["", "a", "b", "c"].map(|part| format!("| {n}{part} | ")))
            .filter(|row| glance.contains(row.as_str()))
            .count();
        assert_eq!(on_page, rows);
        assert_eq!(heading(&CLAIMS[2]), "Claim 3");
        assert!(d.contains("## The frequency scale") && d.contains("## The impact criterion"));
    }
}
