//! The excitation's controls beyond a key's value: a TE table fitted to a
//! mesh kind (`solver::te_file`, as `gearshock --te-file` does), and the
//! contact ratio of the rectangular and trapezoid stiffness, empty for
//! the value the teeth give (its placeholder says which).

use super::{Controller, Effect, InputError};
use figures::protocol::KindSet;
use solver::keys;
use solver::model::Model;
use solver::te_file::{self, TeFit, TeTable};
use solver::waveform::Wave;

/// The mesh kind a contact-ratio or waveform key names (`pair` for the
/// gear pair's own keys), if it is one.
fn ratio_kind(key: &str) -> Option<&str> {
    match key {
        "contact_ratio" => Some("pair"),
        _ => key
            .strip_prefix("contact_ratio_")
            .filter(|k| ["s1a", "s2b", "ab", "rb"].contains(k)),
    }
}

impl Controller {
    /// Fits `harmonics` harmonics of `table` to mesh kind `kind` and makes
    /// them the kind's TE (every view restarts, the link carries them).
    /// Refused, nothing changed: what the fit or the model refuses, in
    /// the solver's words (the line and the reason).
    pub fn apply_te_table(
        &mut self,
        kind: &str,
        table: &TeTable,
        harmonics: usize,
        now_ms: f64,
    ) -> Result<(TeFit, Vec<Effect>), InputError> {
        let mut params = self.settings.params.clone();
        let fit = te_file::fit_into(&mut params, kind, table, harmonics)?;
        let model = Model::new(&params)?;
        self.settings.params = params;
        self.model = Ok(model);
        self.preset_note = None;
        self.dirty.controls = true;
        self.dirty.url = true;
        Ok((fit, self.restart(KindSet::ALL, now_ms)))
    }

    /// The mesh kinds a TE table can be fitted to in this model, with
    /// their words: (kind, words).
    pub fn te_kinds(&self) -> Vec<(String, String)> {
        te_file::kinds(&self.settings.params)
            .iter()
            .map(|k| {
                let words = match *k {
                    "pair" => "the gear pair".to_string(),
                    k => format!("{k} meshes"),
                };
                (k.to_string(), words)
            })
            .collect()
    }

    /// A contact-ratio field's placeholder while it is empty: the value
    /// the teeth give; `None` for other keys or a given value.
    pub fn contact_ratio_hint(&self, key: &str) -> Option<String> {
        let kind = ratio_kind(key)?;
        let params = &self.settings.params;
        if !matches!(keys::get(params, key), Some(keys::Value::Text(_))) {
            return None;
        }
        let e = params.auto_contact_ratio(kind)?;
        Some(format!("{e:.3}"))
    }

    /// What a contact ratio means, in words under its field: the value
    /// used, where it comes from, and the share of each mesh period with
    /// one more pair of teeth in contact; `None` for other keys.
    pub fn contact_ratio_words(&self, key: &str) -> Option<String> {
        let kind = ratio_kind(key)?;
        let params = &self.settings.params;
        let teeth = params.auto_contact_ratio(kind);
        let (e, said) = match (keys::get(params, key), teeth) {
            (Some(keys::Value::Num(e)), Some(t)) => {
                (e, format!("{e} as typed (the teeth give {t:.3})"))
            }
            (Some(keys::Value::Num(e)), None) => (e, format!("{e} as typed")),
            (_, Some(t)) => (
                t,
                format!(
                    "Left empty: {t:.3}, computed from the tooth counts, module and pressure \
                     angle of standard teeth"
                ),
            ),
            (_, None) => return None,
        };
        let pairs = e.floor();
        let share = 100.0 * (e - pairs);
        Some(format!(
            "{said}; {} pairs of teeth in contact for {share:.0} % of each mesh period, \
             {pairs} for the rest.",
            pairs + 1.0
        ))
    }

    /// Whether a control is out of use: a contact ratio while its mesh
    /// kind's stiffness is the cosine, which does not read it.
    pub fn control_unused(&self, key: &str) -> bool {
        let Some(kind) = ratio_kind(key) else {
            return false;
        };
        let wave_key = match kind {
            "pair" => "stiffness_wave".to_string(),
            k => format!("stiffness_wave_{k}"),
        };
        match keys::get(&self.settings.params, &wave_key) {
            Some(keys::Value::Text(w)) => Wave::from_name(&w) == Wave::Cosine,
            _ => false,
        }
    }
}

/// A field's text as its key takes it: an emptied contact ratio (or any
/// key that may be automatic) is the automatic value.
pub(super) fn typed_text(key: &str, text: &str) -> String {
    let auto = matches!(
        keys::spec(key).map(|s| s.ty),
        Some(keys::KeyType::FloatOrAuto { .. })
    );
    if auto && text.trim().is_empty() {
        "auto".into()
    } else {
        text.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_empty_contact_ratio_is_the_teeth_value_and_is_said_so() {
        let (mut c, _) = Controller::new("model=gear-pair", 0.0);
        // The cosine does not read the contact ratio.
        assert!(c.control_unused("contact_ratio"));
        c.set_key("stiffness_wave", "rectangular", 0.0).unwrap();
        assert!(!c.control_unused("contact_ratio"));
        // Hand calculation in solver::waveform's test: 1.695 for 30 and 45 teeth.
        assert_eq!(
            c.contact_ratio_hint("contact_ratio").as_deref(),
            Some("1.695")
        );
        let words = c.contact_ratio_words("contact_ratio").unwrap();
        assert!(words.starts_with("Left empty: 1.695, computed"), "{words}");
        // 1.6945 (the hand calculation to four digits): 0.6945 of each period in double contact.
        assert!(
            words.contains("for 69 % of each mesh period, 1 for the rest"),
            "{words}"
        );
        c.set_key("contact_ratio", "1.6", 0.0).unwrap();
        assert_eq!(c.contact_ratio_hint("contact_ratio"), None);
        let words = c.contact_ratio_words("contact_ratio").unwrap();
        assert!(
            words.starts_with("1.6 as typed (the teeth give 1.695); 2 pairs"),
            "{words}"
        );
        assert!(c.query().contains("contact_ratio=1.6"), "{}", c.query());
        let e = c
            .set_key("contact_ratio", "3.5", 0.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains("between 1 and 2.95") && e.contains("3.5"), "{e}");
        assert!(!e.contains('_'), "{e}");
        let auto = typed_text("contact_ratio", " ");
        c.set_key("contact_ratio", &auto, 0.0).unwrap();
        assert!(!c.query().contains("contact_ratio"), "{}", c.query());
        assert_eq!(typed_text("backlash_um", ""), "");
    }

    #[test]
    fn a_te_table_sets_the_kinds_harmonics_and_a_bad_one_changes_nothing() {
        let (mut c, _) = Controller::new("model=gear-pair", 0.0);
        // 2 + 1.5 cos(theta) at four points of one mesh period.
        let table = te_file::parse("fraction,te_um\n0,3.5\n0.25,2\n0.5,0.5\n0.75,2\n").unwrap();
        let before = c.query();
        assert!(c.apply_te_table("pair", &table, 2, 0.0).is_err());
        assert_eq!(c.query(), before);
        let (fit, _) = c.apply_te_table("pair", &table, 1, 0.0).unwrap();
        assert_eq!(fit.mean_um, 2.0);
        let q = c.query();
        assert!(
            q.contains("te_mean_um=2") && q.contains("te_cos_um=1.5"),
            "{q}"
        );
        assert_eq!(c.te_kinds(), vec![("pair".into(), "the gear pair".into())]);
    }
}
