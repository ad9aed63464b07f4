//! The paper's claims with gearshock's verdicts, as the page lists them.
//!
//! The rows are not typed here: `gearshock paper` computes one record of
//! the claims' numbers and renders from it both `docs/paper.md` and
//! `claims.json` beside this file, which the page includes. The CLI's
//! paper test renders both again and fails if either differs from what is
//! committed, so the page, the document and the code cannot drift apart.

use serde::{Deserialize, Serialize};
use std::sync::OnceLock;

/// One claim of the paper and what gearshock finds.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Claim {
    /// The claim's number in `docs/paper.md` ("1" to "10", parts such as
    /// "4b" or "7a"), or the name of a section ("scale", "impact").
    pub id: String,
    /// What the paper says.
    pub says: String,
    /// The verdict, as in the document's "verdicts at a glance".
    pub verdict: String,
    /// The evidence: gearshock's numbers, a sentence of the document.
    pub evidence: String,
    /// The figure preset that shows it.
    pub figure: Option<String>,
    /// The command that reproduces the numbers (the document's).
    pub command: String,
    /// The values of the command's placeholders in plain text ("b = 200
    /// and te = 0, 20, 30"; empty if none).
    pub with: String,
}

/// The claims as `gearshock paper` rendered them.
pub const CLAIMS_JSON: &str = include_str!("claims.json");

/// Every claim, in the document's order, then the frequency scale and the
/// impact criterion. Empty only if `claims.json` is broken, which the
/// tests below catch.
pub fn claims() -> &'static [Claim] {
    static CLAIMS: OnceLock<Vec<Claim>> = OnceLock::new();
    CLAIMS.get_or_init(|| serde_json::from_str(CLAIMS_JSON).unwrap_or_default())
}

/// A claim's heading on the page: "Claim 3", "The frequency scale", ...
pub fn heading(c: &Claim) -> String {
    match c.id.as_str() {
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
        let text = std::fs::read_to_string(path).unwrap_or_default();
        text.split_whitespace().collect::<Vec<_>>().join(" ")
    }

    #[test]
    fn the_claims_parse_and_load_their_figures() {
        let parsed: Result<Vec<Claim>, _> = serde_json::from_str(CLAIMS_JSON);
        assert!(parsed.is_ok(), "claims.json: {parsed:?}");
        let all = claims();
        assert!(all.len() >= 12);
        for c in all {
            for text in [&c.says, &c.verdict, &c.evidence, &c.command] {
                assert!(!text.is_empty(), "claim {}", c.id);
            }
            if let Some(f) = &c.figure {
                assert!(figures::presets::preset(f).is_some(), "{f}");
                // The page names the plotted quantity in plain words.
                assert!(
                    c.evidence.contains(figures::presets::X_WORDS),
                    "claim {}'s evidence does not name x in plain words",
                    c.id
                );
            }
        }
        assert_eq!(heading(&all[2]), format!("Claim {}", all[2].id));
    }

    /// The page and the document say the same: each numbered claim's row
    /// of the verdicts at a glance and its evidence are the document's.
    #[test]
    fn every_claim_is_the_documents_word_for_word() {
        let d = doc();
        for c in claims() {
            if c.id.starts_with(|ch: char| ch.is_ascii_digit()) {
                let row = format!("| {} | {} | {} |", c.id, c.says, c.verdict);
                assert!(d.contains(&row), "claim {}: {row}", c.id);
            }
            assert!(d.contains(&c.evidence), "claim {}'s evidence", c.id);
            assert!(d.contains(&c.command), "claim {}'s command", c.id);
        }
    }
}
