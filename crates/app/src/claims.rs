//! The paper's claims with gearshock's verdicts, as the page lists them:
//! one table, kept word for word in step with `docs/paper.md` (whose
//! numbers `cargo test -p cli --test paper` recomputes) by this module's
//! test, so the page cannot drift from the document or the code.

/// One claim of the paper and what gearshock finds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Claim {
    /// The claim's number in `docs/paper.md` ("1" to "10"), or the name of
    /// a section ("scale", "impact").
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

const SIMULATE_TE: &str = "gearshock simulate --set backlash_um=200 --set te_um=$x --mesh s1a1 --omega $w --transient-periods 3000";
const SWEEP: &str = "gearshock bifurcation --set backlash_um=$b --set te_um=$te --mesh s1a1 --omega-from 0.15 --omega-to 2 --points 38 --direction up --transient-periods 3000";
const LYAPUNOV: &str = "gearshock lyapunov --set backlash_um=$b --set te_um=20 --omega-from 0.3 --omega-to 1 --points 15";

/// Every claim, in the document's order, then the frequency scale and the
/// impact criterion.
pub const CLAIMS: &[Claim] = &[
    Claim {
        id: "1",
        says: "TE intensifies the resonances and adds harmonic peaks",
        verdict: "partly reproduced: peaks grow with TE, none appears",
        evidence: "The peaks grow with the TE. But no peak appears: the small peak near Ω 0.12 (half the first natural frequency, a superharmonic resonance of the stiffness variation) is there at 5 µm already.",
        figure: Some("fig2"),
        command: "gearshock frf --set backlash_um=0 --set te_meshes=$reading --set te_um=$te --mesh s1a1 --omega-from 0.1 --omega-to 2",
        with: "`reading` = all or s1a, `te` = 5 or 30",
    },
    Claim {
        id: "2",
        says: "more backlash raises the peak at Ω 1.4, not at 0.4 and 1.2",
        verdict: "reproduced at 0.4 and 1.4 by time integration; not at 1.2",
        evidence: "At Ω 1.4 the amplitude rises from 90.9 to 154.4 µm, and gearshock shows why: with 50 and 100 µm the teeth strike their back flanks, which stops the swing; with more backlash they have room to swing further.",
        figure: Some("fig3"),
        command: "gearshock simulate --set backlash_um=$b --set te_um=60 --mesh s1a1 --omega $w --transient-periods 3000",
        with: "`b` = 50, 100, 150, 200; `w` = 0.4, 1.2, 1.4",
    },
    Claim {
        id: "3",
        says: "TE raises the low-frequency amplitude from 2.9 to 26",
        verdict: "reproduced in size (2.9 to 30.4), but it is the TE itself, not a resonance",
        evidence: "gearshock's amplitude grows from 2.9 to 30.4 µm at Ω 0.25, close to the paper's 2.9 to 26. But it grows as much at Ω 0.15, below the first natural frequency (0.232), where the amplitude nearly equals the TE",
        figure: Some("fig4"),
        command: SWEEP,
        with: "with `b` = 200 and `te` = 0, 20, 30",
    },
    Claim {
        id: "4",
        says: "TE has little effect at Ω 1.2–2",
        verdict: "not reproduced: the amplitude there grows 8.8 → 109.4 µm",
        evidence: "the largest amplitude at Ω ≥ 1.2 grows from 8.8 µm (no TE) to 76.2 (20 µm) and 109.4 µm (30 µm)",
        figure: Some("fig4"),
        command: SWEEP,
        with: "with `b` = 200 and `te` = 0, 20, 30",
    },
    Claim {
        id: "5",
        says: "\"negative vibration\", i.e. bilateral impact, comes with TE",
        verdict: "not reproduced as bilateral impact; if \"negative\" is counted from the start of contact, the drive flanks part with TE at high frequency only",
        evidence: "the lowest deflection over Ω 0.15–2 is 195.3, 99.2 and 40.4 µm for TE 0, 20 and 30 µm: never negative, and the back flanks never touch.",
        figure: Some("fig4"),
        command: SWEEP,
        with: "with `b` = 200 and `te` = 0, 20, 30",
    },
    Claim {
        id: "6",
        says: "Figs. 5–7: period 1 → period 2 → quasi-periodic as TE grows",
        verdict: "partly reproduced: period 1 is lost at Ω 0.84 and 1.97, no period 2",
        evidence: "At Ω 0.84 and 1.97 the TE destroys the period-1 motion, and the velocity grows with the TE at all three frequencies, as the paper says.",
        figure: Some("fig5"),
        command: SIMULATE_TE,
        with: "`x` = 0, 20, 30; `w` = 0.5, 0.84, 1.97",
    },
    Claim {
        id: "7",
        says: "Figs. 9–11: backlash turns period 1 into period 2, quasi-periodic, chaos",
        verdict: "not reproduced: the motion does not depend on the backlash until the back flanks touch",
        evidence: "At Ω 0.5 the three amplitudes are identical (43.4 µm)",
        figure: Some("fig9"),
        command: "gearshock simulate --set te_um=20 --set backlash_um=$x --mesh s1a1 --omega $w --transient-periods 3000",
        with: "`x` = 50, 100, 200; `w` = 0.5, 0.84, 1.97",
    },
    Claim {
        id: "8",
        says: "more backlash advances chaos from Ω 0.8 to 0.4",
        verdict: "not reproduced: chaos starts at Ω 0.50 for every backlash",
        evidence: "period-1 motion ends at Ω 0.50 for 50, 100 and 200 µm alike, and the Lyapunov exponent turns positive at Ω 0.50, 0.50 and 0.55.",
        figure: Some("fig8"),
        command: LYAPUNOV,
        with: "with `b` = 50, 100, 200 and `te` = 20",
    },
    Claim {
        id: "9",
        says: "more backlash means more intense shock",
        verdict: "not reproduced: the smallest backlash is the one that reaches the back flanks",
        evidence: "the back flanks touch only with the smallest backlash, 50 µm",
        figure: Some("fig8"),
        command: SWEEP,
        with: "with `b` = 50, 100, 200 and `te` = 20",
    },
    Claim {
        id: "10",
        says: "keep the speed below Ω 0.8",
        verdict: "depends on the frequency scale: in gearshock's, the motion is chaotic from Ω 0.50",
        evidence: "the first band of parametric instability lies at 0.460–0.465; so below Ω 0.8 is not a safe range there, below about 0.45 is.",
        figure: Some("fig8"),
        command: LYAPUNOV,
        with: "with `b` = 50, 100, 200 and `te` = 20",
    },
    Claim {
        id: "scale",
        says: "resonances of the s1a1 deflection at Ω 0.4, 1.2 and 1.4",
        verdict: "1.2 and 1.4 agree with natural frequencies; nothing lies near 0.4",
        evidence: "the paper's 1.2 and 1.4 fall within 0.01 of gearshock's modes at 1.199 (all planets alike) and 1.394 (a planet mode). What does not: nothing lies near 0.4",
        figure: Some("fig2"),
        command: "gearshock modes",
        with: "",
    },
    Claim {
        id: "impact",
        says: "any negative deflection is bilateral impact",
        verdict: "the readings differ: with 50 µm backlash the deflection is negative over a wide band, the back flanks touch at one Ω",
        evidence: "with 50 µm, the deflection is negative over Ω 0.85–1.60 but the back flanks touch only at 1.30.",
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

    #[test]
    fn every_claim_is_the_documents_word_for_word() {
        let d = doc();
        for c in CLAIMS {
            if c.id.parse::<u32>().is_ok() {
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
            }
        }
        // Every numbered claim of the document is on the page.
        let numbered = CLAIMS
            .iter()
            .filter(|c| c.id.parse::<u32>().is_ok())
            .count();
        let rows = (1..=30)
            .filter(|n| d.contains(&format!("| {n} | ")))
            .count();
        assert_eq!(numbered, rows);
        assert_eq!(heading(&CLAIMS[2]), "Claim 3");
        assert!(d.contains("## The frequency scale") && d.contains("## The impact criterion"));
    }
}
