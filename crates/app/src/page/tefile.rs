//! A TE table from a file, in the page core: the ids of the Advanced
//! group's file field and drop zone (`dom::te_file_panel`), the file's text fitted to the
//! chosen mesh kind (`solver::te_file`, the command line's `--te-file`)
//! and applied through the controller, and what the page then shows: the
//! fit in plain words and, for the web layer to draw, its points beside
//! the fitted curve. A refused file is said in the messages with its line
//! and reason, and nothing changes. The web layer only reads the file.

use super::{Acted, Page, Write};
use crate::controller::{Effect, InputError};
use figures::te_fit::TeFitView;
use solver::params::TE_HARMONICS;
use solver::te_file::{self, MAX_TE_FILE_BYTES};

/// The file field's id.
pub const INPUT: &str = "te-file-input";
/// The drop zone's id.
pub const DROP: &str = "te-file-drop";
/// The mesh kind's drop-down.
pub const KIND: &str = "te-file-kind";
/// The harmonics' drop-down.
pub const HARMONICS: &str = "te-file-harmonics";
/// The plot's canvas.
pub const PLOT: &str = "te-file-plot";
/// The sentence under it.
pub const NOTE: &str = "te-file-note";

/// The solver's message with its code quotes (`abc`) as quotation
/// marks (“abc”).
fn quoted(message: &str) -> String {
    let mut open = false;
    message
        .chars()
        .map(|c| match c {
            '`' => {
                open = !open;
                if open {
                    '“'
                } else {
                    '”'
                }
            }
            c => c,
        })
        .collect()
}

impl Page {
    /// Whether a file of `bytes` bytes may be read; if not, the messages
    /// say why (its size and the limit) and the web layer reads nothing.
    pub fn te_file_size(&mut self, name: &str, bytes: f64) -> bool {
        let limit = MAX_TE_FILE_BYTES as f64;
        if bytes <= limit {
            return true;
        }
        self.ctl.issue(format!(
            "The TE file {} was not used: it has {:.1} MB; at most {:.0} MB are allowed. \
             Nothing was changed.",
            solver::keys::truncate(name, 60),
            bytes / 1e6,
            limit / (1 << 20) as f64
        ));
        false
    }

    /// A TE file's text read: parsed, `harmonics` (the drop-down's text)
    /// harmonics fitted to mesh kind `kind` and made its TE. Refused,
    /// nothing changed and the last fit still shown: a file the fit cannot
    /// take, said in the messages with its line and reason.
    pub fn te_file(
        &mut self,
        kind: &str,
        harmonics: &str,
        name: &str,
        text: &str,
        now_ms: f64,
    ) -> Acted {
        let mut out = Acted {
            frame: true,
            ..Acted::default()
        };
        match self.fit_te_file(kind, harmonics, name, text, now_ms) {
            Ok((view, fx)) => {
                out.writes.push(Write::text(NOTE, view.sentence()));
                out.writes.push(Write::Hidden {
                    id: PLOT.into(),
                    hidden: false,
                });
                self.te = Some(view);
                out.effects = fx;
            }
            Err(why) => self.ctl.issue(format!(
                "The TE file {} was not used: {}. Nothing was changed.",
                solver::keys::truncate(name, 60),
                quoted(&why.to_string())
            )),
        }
        out
    }

    fn fit_te_file(
        &mut self,
        kind: &str,
        harmonics: &str,
        name: &str,
        text: &str,
        now_ms: f64,
    ) -> Result<(TeFitView, Vec<Effect>), InputError> {
        let h = harmonics
            .trim()
            .parse::<usize>()
            .ok()
            .filter(|h| (1..=TE_HARMONICS).contains(h))
            .ok_or_else(|| InputError::TeHarmonics {
                most: TE_HARMONICS,
                given: harmonics.to_string(),
            })?;
        let table = te_file::parse(text)?;
        let period = te_file::mesh_period(&self.ctl.settings().params, kind, &table);
        let (fit, fx) = self.ctl.apply_te_table(kind, &table, h, now_ms)?;
        Ok((TeFitView::new(kind, name, &table, period, fit), fx))
    }

    /// The last TE file fitted, for the web layer to draw.
    pub fn te_view(&self) -> Option<&TeFitView> {
        self.te.as_ref()
    }

    /// The mesh kinds' drop-down for the current model.
    pub(super) fn te_kind_writes(&self) -> Write {
        Write::Options {
            id: KIND.into(),
            options: self.ctl.te_kinds(),
        }
    }

    /// The TE file's state for the status: the last fit, if any.
    pub(super) fn te_status(&self) -> serde_json::Value {
        match &self.te {
            None => serde_json::Value::Null,
            Some(v) => serde_json::json!({
                "kind": v.kind,
                "file": v.file,
                "points": v.fit.points,
                "harmonics": v.fit.harmonics_um.len(),
                "mean_um": v.fit.mean_um,
                "harmonics_um": v.fit.harmonics_um,
                "rms_residual_um": v.fit.rms_residual_um,
                "sentence": v.sentence(),
            }),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::controller::Controller;

    const FILE: &str = include_str!("../../../../tests/data/te_three_harmonics.csv");

    fn page() -> Page {
        Page::new(Controller::new("model=gear-pair", 0.0).0, false)
    }

    #[test]
    fn a_file_sets_its_harmonics_and_a_bad_one_keeps_the_last_good_state() {
        let mut p = page();
        // The page's own words for the columns are headings the file may have.
        let plain = FILE.replace("fraction,te_um", "Fraction,TE (µm)");
        p.te_file("pair", "6", "te.csv", &plain, 0.0);
        // The harmonics the file's comment names (the curve it was made from).
        let q = p.ctl().query();
        for k in [
            "te_mean_um=2",
            "te_um=12",
            "te_cos_um=-3",
            "te_cos2_um=2.5",
            "te_sin2_um=1.25",
            "te_sin3_um=-0.8",
        ] {
            assert!(q.contains(k), "{k}: {q}");
        }
        let good = p.te_view().cloned();
        assert_eq!(good.as_ref().map(|v| v.fit.points), Some(360));
        let said = good.as_ref().map(TeFitView::sentence).unwrap_or_default();
        assert!(
            said.starts_with("te.csv: 360 points over 1 mesh period, fitted with 6 harmonics"),
            "{said}"
        );
        let bad = [
            ("", "empty"),
            (
                "fraction,te_um\n0,1\n0.5,abc\n",
                "line 3: the TE “abc” is not a number",
            ),
            ("fraction,te_um\n0,1\n0.5,NaN\n", "line 3: the TE is NaN"),
            (
                "roll_deg,te_um\n-1,1\n0,2\n",
                "line 2: the abscissa -1 is negative; allowed 0 and above",
            ),
            (
                "fraction,te_um\n0,1\n0.5,2\n0.4,3\n",
                "line 4: the abscissa 0.4 does not increase",
            ),
            (
                "fraction,te_um\n0,1\n0.25,2\n0.5,3\n0.75,4\n",
                "4 points cannot fit 6 harmonics: at least 14 are needed",
            ),
        ];
        for (text, why) in bad {
            p.te_file("pair", "6", "bad.csv", text, 0.0);
            let said = p.ctl().status(0.0)["issues"].to_string();
            assert!(
                said.contains(why) && said.contains("bad.csv"),
                "{why}: {said}"
            );
            assert_eq!(p.ctl().query(), q);
            assert_eq!(p.te_view(), good.as_ref());
        }
        p.te_file("pair", "9", "te.csv", FILE, 0.0);
        let said = p.ctl().status(0.0)["issues"].to_string();
        assert!(said.contains("must be 1 to 6 (not 9)"), "{said}");
        assert!(!p.te_file_size("big.csv", 11e6));
        let said = p.ctl().status(0.0)["issues"].to_string();
        assert!(said.contains("11.0 MB; at most 10 MB"), "{said}");
        assert!(p.te_file_size("ok.csv", 1e6));
    }
}
