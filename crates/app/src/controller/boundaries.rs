//! The map's traced boundaries in the controller: a click that picks a
//! curve (what it is, in a sentence, and its point selected), the note
//! under the map, and the tests' status.

use super::*;
use figures::views::boundaries::{describe, pick};

/// How near a click must be to a curve to pick it (pixels).
pub(super) const PICK_PX: f64 = 6.0;

/// A clicked boundary: what it marks, in a sentence shown beside the map,
/// and where, marked on it.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct PickedMark {
    /// What the curve marks, in a sentence.
    pub(super) sentence: String,
    /// The curve's place among the boundaries shown.
    pub(super) curve: usize,
    /// The picked point `(omega, value)`.
    pub(super) at: (f64, f64),
}

impl Controller {
    /// A click at `(omega, value)` of the map, `px` pixels per unit of
    /// Omega and of the value: if it is within [`PICK_PX`] of a shown
    /// boundary, says what the boundary is and selects its nearest point
    /// (the key's value and Omega); `None` if no curve is near.
    pub fn pick_map_boundary(
        &mut self,
        (omega, value): (f64, f64),
        px: (f64, f64),
        now_ms: f64,
    ) -> Option<Result<Vec<Effect>, InputError>> {
        let (shown, _, _) = self.map_boundaries();
        let picked = pick(&shown, (omega, value), px, PICK_PX)?;
        let names = self.mesh_names();
        let mesh = picked.mesh.and_then(|m| names.get(m)).map(String::as_str);
        let key = self.settings.view.map_key.clone();
        let sentence = describe(&picked, &key, mesh);
        // The value as the slider holds it (three decimals), Omega exact.
        let v = (picked.value * 1e3).round() / 1e3;
        let r = self
            .set_key(&key, &figures::settings::fmt_exact(v), now_ms)
            .map(|mut fx| {
                self.dirty.controls = true;
                fx.extend(self.select_omega(picked.omega, now_ms));
                fx
            });
        self.picked_boundary = r.is_ok().then_some(PickedMark {
            sentence,
            curve: picked.curve,
            at: (picked.omega, v),
        });
        self.dirty.data(figures::views::ViewId::Map.spec().shows);
        Some(r)
    }

    /// Forgets the picked boundary (a click on a cell).
    pub fn clear_picked_boundary(&mut self) {
        if self.picked_boundary.take().is_some() {
            self.dirty.data(figures::views::ViewId::Map.spec().shows);
        }
    }

    /// The note over the map: its cells, then the boundaries (how many,
    /// what the outlined cells mean, how to learn what a curve marks).
    pub fn map_note_text(&self) -> String {
        let st = self.main.map_status();
        let mut note = figures::views::map::map_note(&self.main.map, st.total);
        let b = &self.main.boundaries;
        if !self.settings.view.boundaries {
            return note;
        }
        let (shown, disagree, _) = self.map_boundaries();
        let bst = self.main.boundaries_status();
        note.push_str(&format!(" Boundaries: {} curves traced", shown.len()));
        if let Some(e) = &bst.error {
            note.push_str(&format!(" (stopped: {e})"));
        } else if !b.finished {
            note.push_str(&format!(" (tracing, {}%)", bst.done / 10));
        }
        note.push('.');
        if !disagree.is_empty() {
            note.push_str(&format!(
                " {} cells outlined in yellow lie on the wrong side of a curve: {}.",
                disagree.len(),
                figures::plots::boundaries::MARK_LABEL
            ));
        }
        if !shown.is_empty() {
            note.push_str(" Click a curve to see what it marks.");
        }
        note
    }

    /// What the clicked boundary marks, for beside the map (a ring marks
    /// its point on the map), if one is clicked.
    pub fn picked_boundary_text(&self) -> Option<String> {
        self.picked_boundary
            .as_ref()
            .map(|p| format!("◯ {}", p.sentence))
    }

    /// The boundaries for the tests: the job, the curves shown by kind,
    /// the cusps, the cells judged and those that disagree, the picked
    /// sentence.
    pub(super) fn boundaries_status(&self) -> serde_json::Value {
        let b = &self.main.boundaries;
        let (shown, disagree, judged) = self.map_boundaries();
        let kinds: std::collections::BTreeMap<&str, usize> = figures::protocol::BoundaryKind::ALL
            .iter()
            .map(|k| {
                (
                    k.solver_name(),
                    shown.iter().filter(|c| c.kind == *k).count(),
                )
            })
            .filter(|(_, n)| *n > 0)
            .collect();
        // The middle point of the longest curve shown, for a click.
        let sample = shown.iter().max_by_key(|c| c.points.len()).and_then(|c| {
            let p = c.points.get(c.points.len() / 2)?;
            Some(serde_json::json!({
                "kind": c.kind.solver_name(), "omega": p.omega, "value": p.value,
            }))
        });
        serde_json::json!({
            "sample": sample,
            "curves": b.curves.len(),
            "shown": shown.len(),
            "kinds": kinds,
            "cusps": b.cusps.len(),
            "notes": b.notes,
            "finished": b.finished,
            "judged": judged,
            "disagree": disagree.len(),
            "picked": self.picked_boundary.as_ref().map(|p| &p.sentence),
        })
    }
}
