//! A family's exports: the bifurcation diagram and the selected-Ω views of
//! every member, not the current state's alone. CSV gets a leading
//! `member` column naming the value in words ("TE 20 µm"); JSON holds the
//! family and one entry per member naming it.

use super::super::*;
use super::ExportError;
use figures::views::omega::{omega_csv, omega_json, OmegaView};

/// CSV texts of one shape, one per member, as one CSV with a leading
/// `member` column (the header once; commas in a label become `;`).
pub(super) fn member_csv(parts: &[(String, String)]) -> String {
    let mut out = String::new();
    for (label, text) in parts {
        let mut lines = text.lines();
        let head = lines.next().unwrap_or_default();
        if out.is_empty() {
            out = format!("member,{head}\n");
        }
        let label = label.replace(',', ";");
        for l in lines {
            out.push_str(&format!("{label},{l}\n"));
        }
    }
    out
}

impl Controller {
    /// The family's key and values, as the JSON exports name them.
    fn family_json(&self) -> serde_json::Value {
        self.family.as_ref().map_or(
            serde_json::Value::Null,
            |f| serde_json::json!({ "key": f.spec.key.key, "values": f.spec.values }),
        )
    }

    /// Member `i`'s value in words and number.
    fn member_names(&self) -> Vec<(String, f64)> {
        self.family.as_ref().map_or(Vec::new(), |f| {
            (0..f.spec.values.len())
                .map(|i| (f.spec.label(i), f.spec.values[i]))
                .collect()
        })
    }

    /// Every member's bifurcation points (what has arrived; a member whose
    /// sweep failed is named with its reason in the JSON and has no rows).
    pub(super) fn family_bif_export(&self, csv: bool) -> Result<String, ExportError> {
        let panels = self.bif_panels();
        let names = self.member_names();
        if csv {
            let parts: Vec<(String, String)> = names
                .iter()
                .zip(&panels)
                .filter_map(|((label, _), p)| {
                    let v = p.data.as_ref().ok()?;
                    Some((label.clone(), figures::views::bif::bif_csv(v)))
                })
                .collect();
            return Ok(member_csv(&parts));
        }
        let members: Vec<serde_json::Value> = names
            .iter()
            .zip(&panels)
            .map(|((label, value), p)| match &p.data {
                Ok(v) => serde_json::json!({ "member": label, "value": value, "view": v }),
                Err(e) => serde_json::json!({ "member": label, "value": value, "error": e }),
            })
            .collect();
        super::export::json_text(serde_json::to_string(
            &serde_json::json!({ "family": self.family_json(), "members": members }),
        ))
    }

    /// Every member's selected-Ω view `which`; refused until every member's
    /// full steady state has arrived (a partial family is not the figure).
    pub(super) fn family_omega_export(
        &self,
        which: OmegaView,
        csv: bool,
    ) -> Result<String, ExportError> {
        let mut results: Vec<&OmegaResult> = vec![self.exportable_omega()?];
        if let Some(f) = &self.family {
            for m in &f.members {
                match &m.comp.omega {
                    Some(r) if !r.preview && m.comp.omega_status().error.is_none() => {
                        results.push(r)
                    }
                    _ => return Err(ExportError::NotComputed),
                }
            }
        }
        let names = self.member_names();
        if csv {
            let parts: Vec<(String, String)> = names
                .iter()
                .zip(&results)
                .map(|((label, _), r)| (label.clone(), omega_csv(r, which)))
                .collect();
            return Ok(member_csv(&parts));
        }
        let members: Vec<serde_json::Value> = names
            .iter()
            .zip(&results)
            .map(|((label, value), r)| {
                let mut j = omega_json(r, which);
                j["member"] = serde_json::json!(label);
                j["value"] = serde_json::json!(value);
                j
            })
            .collect();
        Ok(serde_json::json!({ "family": self.family_json(), "members": members }).to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn member_csv_puts_each_members_rows_under_one_header() {
        let parts = vec![
            ("TE 0 µm".to_string(), "a,b\n1,2\n3,4\n".to_string()),
            ("damping ratio 0,05".to_string(), "a,b\n5,6\n".to_string()),
        ];
        assert_eq!(
            member_csv(&parts),
            "member,a,b\nTE 0 µm,1,2\nTE 0 µm,3,4\ndamping ratio 0;05,5,6\n"
        );
    }
}
