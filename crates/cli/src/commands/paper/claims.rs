//! The claims as the page lists them and the document's verdicts at a
//! glance: what the paper says, the verdict and one sentence of evidence
//! for each, with `{{name}}` where a number of the record goes. The
//! document quotes the same sentences (`{{claim.ID.verdict}}`, ...), so
//! each is written once.

/// One claim's texts before the record's numbers are filled in.
pub struct ClaimText {
    /// The claim's number ("1", "7a") or a section ("scale", "impact").
    pub id: &'static str,
    /// What the paper says.
    pub says: &'static str,
    /// The verdict.
    pub verdict: &'static str,
    /// A sentence of the document with the evidence.
    pub evidence: &'static str,
    /// The figure preset that shows it.
    pub figure: &'static str,
    /// The value name of the command that reproduces the numbers.
    pub command: &'static str,
    /// The value name of its placeholders' values (empty if none).
    pub with: &'static str,
}

/// Every claim in the document's order, then the frequency scale and the
/// impact criterion.
pub const CLAIMS: &[ClaimText] = &[
    ClaimText {
        id: "1",
        says: "TE intensifies the resonances and adds harmonic peaks",
        verdict: "partly reproduced: the peaks grow with the TE, none appears",
        evidence: "The peaks of the tooth deflection x, TE included, grow with the TE (at the first mode, on stable points, from {{c1.first}} µm), but no peak appears: every peak of the 30 µm responses is there at 5 µm already, under each reading, with either method and on every panel.",
        figure: "fig2",
        command: "cmd.fig2",
        with: "with.fig2",
    },
    ClaimText {
        id: "1b",
        says: "to avoid the TE's influence, keep the speed out of the resonance and harmonic response ranges",
        verdict: "partly reproduced: the ranges to avoid are the resonances, but with 5 µm TE on every mesh none is left to run in above Ω {{c1b.top_5}}",
        evidence: "Without backlash and with 5 µm TE on every mesh, the tooth deflection x, TE included, of every mesh stays above 0 on a stable orbit (so a mesh with backlash would keep its drive flanks in contact) only over Ω {{c1b.kept_5}}; with 30 µm only over {{c1b.kept_30}} (the branches start at Ω {{c1b.from}}).",
        figure: "fig2",
        command: "cmd.fig2",
        with: "with.fig2",
    },
    ClaimText {
        id: "2",
        says: "more backlash raises the peak at Ω 1.4, not at 0.4 and 1.2",
        verdict: "partly reproduced: on the literal scale at 0.4 and 1.4, not on the matched one; the paper's one-harmonic branch is unstable there",
        evidence: "Matched on the first mode, the tooth deflection x, TE included, rises from {{c2.first_b}} to {{c2.last_b}} µm backlash as much at the paper's 1.2 (Ω {{c2.w12}}: {{c2.rise12}} µm) as at its 1.4 (Ω {{c2.w14}}: {{c2.rise14}} µm), so the paper's contrast does not hold there.",
        figure: "fig3",
        command: "cmd.fig3",
        with: "with.fig3",
    },
    ClaimText {
        id: "3",
        says: "TE raises the low-frequency amplitude from 2.9 to 26",
        verdict: "depends on a reading: with the TE on the small sun's meshes x grows {{c3.low}} µm at Ω {{read.w_low}}, with the TE on every mesh {{c3.low_all}} µm",
        evidence: "With the TE on the small sun's meshes the tooth deflection x, TE included, grows {{c3.low}} µm at Ω {{read.w_low}} (the grid point nearest the paper's 0.4 matched on the first mode), {{c3.literal}} µm at the literal 0.4 and {{c3.peak}} µm at the first mode's own peak: nowhere near tenfold.",
        figure: "fig4",
        command: "cmd.sweep",
        with: "with.fig4",
    },
    ClaimText {
        id: "3b",
        says: "Fig. 4's resonance at Ω 0.4 is the first natural frequency, as in Fig. 2",
        verdict: "reproduced: the sweeps peak at Fig. 2's first mode, bent slightly lower",
        evidence: "Swept up with 200 µm backlash, the tooth deflection x, TE included, peaks at Ω {{c3b.peaks}} for TE 0, 20 and 30 µm, just below the first mode of Fig. 2's harmonic balance ({{c3b.fig2}}).",
        figure: "fig4",
        command: "cmd.fine",
        with: "with.fine4",
    },
    ClaimText {
        id: "4",
        says: "TE has little effect at Ω 1.2–2",
        verdict: "not reproduced: the amplitude there grows {{c4.first}} → {{c4.last}} µm",
        evidence: "The largest amplitude of the tooth deflection x, TE included, at Ω ≥ 1.2 grows from {{c4.high_0}} µm (no TE) to {{c4.high_20}} (20 µm) and {{c4.high_30}} µm (30 µm), and over the matched range {{c4.matched_range}} from {{c4.matched_0}} to {{c4.matched_30}} µm.",
        figure: "fig4",
        command: "cmd.sweep",
        with: "with.fig4",
    },
    ClaimText {
        id: "4b",
        says: "TE brings random vibration in the mid- and high-frequency sections",
        verdict: "reproduced: with TE the motion is not periodic over most of Ω {{c4b.from}}–2",
        evidence: "Without TE the tooth deflection x, TE included, moves periodically except {{c4b.np_0}}; with 20 µm TE it is not periodic over {{c4b.np_20}}, with 30 µm over {{c4b.np_30}}.",
        figure: "fig4",
        command: "cmd.sweep",
        with: "with.fig4",
    },
    ClaimText {
        id: "5",
        says: "\"negative vibration\", i.e. bilateral impact, comes with TE",
        verdict: "depends on a reading: no back-flank contact with the TE on the small sun's meshes and b half the gap; with 30 µm TE on every mesh, or b the whole gap, back flanks touch",
        evidence: "With 200 µm backlash the lowest tooth deflection x, TE included, over Ω 0.15–2 is {{c5.lowest}} µm for TE 0, 20 and 30 µm ({{c5.lowest_matched}} µm over the paper's range matched): never negative, and the back flanks of no mesh ever touch.",
        figure: "fig4",
        command: "cmd.sweep",
        with: "with.fig4",
    },
    ClaimText {
        id: "6",
        says: "Figs. 5–7: period 1 → period 2 → quasi-periodic as TE grows; the velocity grows",
        verdict: "partly reproduced: period 1 is lost and the penetration velocity grows, but the TE brings no period 2; the paper contradicts itself",
        evidence: "At Ω 0.84 and 1.97 the TE destroys the period-1 motion, and the penetration velocity (the rate of the tooth deflection x, TE included) grows with the TE at all three of the paper's frequencies (at 1.97: {{c6.v197}} m/s), as the paper says.",
        figure: "fig5",
        command: "cmd.te",
        with: "with.te",
    },
    ClaimText {
        id: "7a",
        says: "Figs. 9–10: backlash has little effect at low and medium frequency, and turns period 1 into period 2",
        verdict: "partly reproduced: the backlash cannot act until the back flanks touch, but it turns no period 1 into period 2",
        evidence: "At the matched Ω {{c7a.w05}} and {{c7a.w084}} the three backlashes give the very same motion of the tooth deflection x, TE included ({{c7a.m05}} and {{c7a.m084}}), and at the literal 0.5 and 0.84 it is {{c7a.literal}} for every backlash: no backlash turns period 1 into period 2.",
        figure: "fig9",
        command: "cmd.backlash",
        with: "with.backlash",
    },
    ClaimText {
        id: "7b",
        says: "Fig. 11: backlash turns period 1 into quasi-periodic motion and chaos at high frequency",
        verdict: "not reproduced: the motion is chaotic for every backlash",
        evidence: "At Ω 1.97 the tooth deflection x, TE included, moves chaotically for every backlash, {{c7b.smallest}} µm included, with the same penetration velocity ({{c7b.velocities}} m/s).",
        figure: "fig11",
        command: "cmd.backlash",
        with: "with.backlash",
    },
    ClaimText {
        id: "8",
        says: "more backlash advances chaos from Ω 0.8 to 0.4",
        verdict: "not reproduced under either reading: chaos starts at Ω {{c8.onset}} for every backlash",
        evidence: "A negative tooth deflection x, TE included, first appears at Ω {{c8.negative}} for {{c8.backlashes}} µm: more backlash moves it up, and removes it.",
        figure: "fig8",
        command: "cmd.lyapunov",
        with: "with.fig8",
    },
    ClaimText {
        id: "9",
        says: "more backlash means more intense shock",
        verdict: "not reproduced: the smallest backlash is the one that reaches the back flanks",
        evidence: "The back flanks of some mesh touch only with the smallest backlash, {{c9.smallest}} µm, and the tooth deflection x, TE included, goes negative {{c9.negative}} with it.",
        figure: "fig8",
        command: "cmd.sweep",
        with: "with.fig8",
    },
    ClaimText {
        id: "10",
        says: "keep the speed below Ω 0.8",
        verdict: "partly reproduced: every case has impact-free windows below Ω 0.8 ({{c10.glance}}), but not every speed below 0.8 is free, and more backlash does not move the windows",
        evidence: "With 20 µm TE, no mesh's drive flanks part (the tooth deflection x, TE included, stays above b) on a periodic orbit over Ω {{c10.windows_20}}, for {{c10.backlashes_20}} µm of backlash alike.",
        figure: "fig8",
        command: "cmd.fine",
        with: "with.fine10",
    },
    ClaimText {
        id: "scale",
        says: "resonances of the s1a1 deflection at Ω 0.4, 1.2 and 1.4",
        verdict: "on the literal scale 1.2 and 1.4 lie near modes, weakly; matched on the first mode (factor {{scale.factor}}) the paper's 1.4 is the third mode",
        evidence: "Nothing lies near 0.4: gearshock's response of the tooth deflection x, TE included, peaks at the first mode ({{scale.peak_1}}), the second ({{scale.peak_2}}) and at half of each ({{scale.peak_half_1}} and {{scale.peak_half_2}}: superharmonic resonances of the stiffness variation).",
        figure: "fig2",
        command: "cmd.modes",
        with: "",
    },
    ClaimText {
        id: "impact",
        says: "any negative deflection is bilateral impact",
        verdict: "the readings differ: with {{impact.smallest}} µm backlash x is negative over a wide band, the back flanks of s1a1 touch over a narrower one",
        evidence: "With {{impact.smallest}} µm backlash the tooth deflection x, TE included, is negative over Ω {{impact.negative}}, but the back flanks of s1a1 touch only {{impact.s1a1_back}}.",
        figure: "fig8",
        command: "cmd.sweep",
        with: "with.fig8",
    },
];
