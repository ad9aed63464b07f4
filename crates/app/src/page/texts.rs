//! The page core's texts: the messages box, the comparison line, the
//! family bar's line, the progress bars and the status line, each view's
//! caption status and note, and the status the tests read.

use super::{Page, Write};
use figures::views::fr::FrView;
use figures::views::{ViewId, VIEWS};

/// The most lines of the mesh force by order the status lists (the
/// browser tests' runs of 40 recorded periods have 320).
const STATUS_ORDER_LINES: usize = 4096;

/// How long the Copy link's confirmation shows (ms).
pub(crate) const TOAST_MS: f64 = 2000.0;

/// The status line while any job shows progress.
pub(crate) const COMPUTING: &str = "Computing in Web Workers…";

impl Page {
    /// The messages box and the preset's note.
    pub(super) fn messages(&self) -> Vec<Write> {
        let text = self.ctl.messages_text();
        let note = self.ctl.preset_note();
        vec![
            Write::Hidden {
                id: "messages".into(),
                hidden: text.is_empty(),
            },
            Write::text("messages", text),
            Write::Hidden {
                id: "preset-note".into(),
                hidden: note.is_none(),
            },
            Write::text("preset-note", note.unwrap_or_default()),
        ]
    }

    /// The A/B comparison line and its "Clear A" button; the family bar's line.
    pub(super) fn comparison(&self) -> Vec<Write> {
        let ab = match self.ctl.ab_labels() {
            Some((a, b)) => format!("Comparing A ({a}) with B ({b})"),
            None => String::new(),
        };
        let family = match self.ctl.family() {
            Some(f) => {
                let labels: Vec<String> =
                    (0..f.spec.values.len()).map(|i| f.spec.label(i)).collect();
                format!(
                    "Showing {}: one colour each on the frequency response, one panel each on the bifurcation diagram, phase portrait and Poincaré section.",
                    labels.join(", ")
                )
            }
            None => String::new(),
        };
        vec![
            Write::text("ab-status", ab),
            Write::Hidden {
                id: "clear-a".into(),
                hidden: self.ctl.pinned().is_none(),
            },
            Write::text("family-status", family),
            Write::Hidden {
                id: "family-clear".into(),
                hidden: self.ctl.family().is_none(),
            },
        ]
    }

    /// Every view's progress bar at `now_ms` and the status line (progress
    /// is time-based: the page asks ten times a second).
    pub fn progress(&mut self, now_ms: f64) -> Vec<Write> {
        let mut busy = false;
        let mut w = Vec::new();
        for view in ViewId::ALL {
            let (prog, label) = self.view_progress(view, now_ms);
            busy |= prog.is_some();
            let id = format!("progress-{}", view.key());
            w.push(Write::Hidden {
                id: id.clone(),
                hidden: prog.is_none(),
            });
            let Some((done, total)) = prog else {
                continue;
            };
            let frac = if total > 0 {
                done as f64 / total as f64
            } else {
                0.0
            };
            w.push(Write::Attr {
                id: format!("{id}-bar"),
                name: "style",
                value: format!("width:{:.1}%", 100.0 * frac),
            });
            w.push(Write::text(&format!("{id}-label"), label));
        }
        w.push(Write::text("status", if busy { COMPUTING } else { "" }));
        // The Copy link's confirmation goes after its two seconds.
        if self.notices.toast_until.is_some_and(|t| now_ms >= t) {
            self.notices.toast_until = None;
            w.push(Write::Hidden {
                id: "copy-done".into(),
                hidden: true,
            });
        }
        w
    }

    /// A view's progress at `now_ms` (done, total) and its label, if it
    /// shows one. The map's runs on while its boundaries are traced, long
    /// after its cells (a minute on the compound set): the bar stays
    /// until the trace ends.
    fn view_progress(&self, view: ViewId, now_ms: f64) -> (Option<(usize, usize)>, String) {
        let main = self.ctl.main();
        let prog = self.ctl.view_status(view).progress(now_ms);
        let trace = main.boundaries_status().progress(now_ms);
        match (view, prog, trace) {
            (ViewId::Map, None, Some((done, total))) => (
                Some((done, total)),
                format!(
                    "tracing the regime boundaries: {}%",
                    100 * done / total.max(1)
                ),
            ),
            // Drawn from the model at once: nothing to wait for.
            (ViewId::Campbell, _, _) => (None, String::new()),
            (_, Some((done, total)), _) => (Some((done, total)), view.progress_label(done, total)),
            _ => (None, String::new()),
        }
    }

    /// The Copy link's confirmation `text`, shown from `now_ms` for
    /// [`TOAST_MS`]; `stamp` (the wall clock's ms) marks it for the tests.
    pub fn confirm(&mut self, text: &str, now_ms: f64, stamp: f64) -> Vec<Write> {
        self.notices.toast_until = Some(now_ms + TOAST_MS);
        vec![
            Write::text("copy-done", text),
            Write::Attr {
                id: "copy-done".into(),
                name: "data-shown",
                value: format!("{stamp}"),
            },
            Write::Hidden {
                id: "copy-done".into(),
                hidden: false,
            },
        ]
    }

    /// Whether the job whose data `view` shows runs, the current state's
    /// or a member's.
    fn running(&self, view: ViewId) -> bool {
        let kind = view.spec().data;
        self.ctl.main().status(kind).running() || self.ctl.members_running(kind)
    }

    /// The status a view's caption ends with: computing, a preview, partial.
    pub fn caption_suffix(&self, view: ViewId, fr: Option<&FrView>) -> String {
        let main = self.ctl.main();
        let family = self.ctl.family().is_some();
        match view {
            ViewId::Fr => fr.map_or_else(String::new, |v| {
                figures::views::fr::fr_caption_suffix(self.running(view), v)
            }),
            ViewId::Bif if family => computing(self.running(view)),
            ViewId::Bif => main.bif_status().caption_suffix(),
            ViewId::Map if main.boundaries_status().running() && !main.map_status().running() => {
                " (tracing the boundaries…)".into()
            }
            ViewId::Map => main.map_status().map_caption_suffix(),
            ViewId::Lyap => main.lyap_status().caption_suffix(),
            ViewId::Campbell => String::new(),
            ViewId::Dynamic => main.bif_status().caption_suffix(),
            ViewId::Phase | ViewId::Poincare if family => computing(self.running(view)),
            ViewId::Phase | ViewId::Poincare | ViewId::Time | ViewId::Spectrum | ViewId::Orders => {
                let preview = main.omega.as_ref().is_some_and(|r| r.preview);
                let running = main.omega_status().running();
                figures::views::omega::caption_suffix(preview, running).to_string()
            }
        }
    }

    /// The note under a view (the frequency response's, the map's), if it
    /// has one, and the frequency response's full key (one line per entry,
    /// behind "details"; empty for the mesh panels, whose key is complete).
    pub fn note(&self, view: ViewId, fr: Option<&FrView>) -> Vec<Write> {
        match (view, fr) {
            (ViewId::Campbell, _) => vec![Write::text("note-campbell", self.ctl.campbell_note())],
            (ViewId::Dynamic, _) => vec![Write::text("note-dynamic", self.ctl.dynamic_note())],
            (ViewId::Orders, _) => vec![Write::text("note-orders", self.ctl.orders_note())],
            (ViewId::Fr, Some(fr)) if self.ctl.panels().is_some() => {
                let note = figures::views::fr::fr_panels_note(fr);
                vec![
                    Write::text("note-fr", note),
                    Write::text("key-fr", String::new()),
                ]
            }
            (ViewId::Fr, Some(fr)) => {
                let key = figures::plots::fr_full_key(fr).join("\n");
                vec![
                    Write::text("note-fr", figures::views::fr::fr_note(fr)),
                    Write::text("key-fr", key),
                ]
            }
            // The map's note over it; what a clicked boundary marks under it.
            (ViewId::Map, _) => {
                let picked = self.ctl.picked_boundary_text();
                vec![
                    Write::text("note-map", self.ctl.map_note_text()),
                    Write::Hidden {
                        id: "map-picked".into(),
                        hidden: picked.is_none(),
                    },
                    Write::text("map-picked", picked.unwrap_or_default()),
                ]
            }
            _ => Vec::new(),
        }
    }

    /// The dynamic factor at the selected Omega as the page shows it: the
    /// model's, K_v by ISO 6336-1 and its range, the load sharing, and how
    /// many steady states the model's curve has.
    fn dynamic_status(&self) -> serde_json::Value {
        let Ok(v) = self.ctl.dynamic_view() else {
            return serde_json::Value::Null;
        };
        let o = v.selected_omega;
        let selected = v.selected.as_ref();
        serde_json::json!({
            "mesh": v.mesh_name,
            "omega": o,
            "dynamic_factor": selected.and_then(|s| s.factor),
            "preview": selected.is_some_and(|s| s.preview),
            "kv": v.kv_at(o),
            "accuracy_grade": v.inputs.accuracy_grade,
            "face_width_mm": v.inputs.face_width_mm,
            "iso_range": v.range_at(o).name(),
            "resonance_ratio": v.n_at(o),
            "phasing": v.phasing,
            "planets": v.planets,
            "load_sharing": v.sharing.iter().map(|k| serde_json::json!({
                "kind": k.kind,
                "factor": k.factor,
                "peak_force_n": k.peak_force_n,
            })).collect::<Vec<_>>(),
            "sharing_over_speed": v.sharing_over_speed.iter().map(|s| serde_json::json!({
                "omega": s.omega,
                "worst": s.worst(),
            })).collect::<Vec<_>>(),
            "points": v.nonlinear.len(),
            "note": v.note(),
        })
    }

    /// The Campbell diagram's critical speeds, each with its pixel on the
    /// canvas (where a click selects it) once the diagram is drawn.
    fn campbell_status(&self) -> serde_json::Value {
        let Ok(v) = self.ctl.campbell_view() else {
            return serde_json::Value::Null;
        };
        let frame = self.frame(ViewId::Campbell);
        let crossings: Vec<serde_json::Value> = v
            .crossings
            .iter()
            .map(|c| {
                let mut j = crate::controller::campbell::crossing_json(c);
                if let (Some(f), Some(o)) = (frame, j.as_object_mut()) {
                    let p = f.to_px(c.rpm, c.frequency_hz);
                    o.insert("px".into(), serde_json::json!([p.x, p.y]));
                }
                j
            })
            .collect();
        serde_json::json!({"label": v.label(), "crossings": crossings})
    }

    /// The readout of the selected speed and the views' captions of their
    /// speed axes, in the axes' unit.
    pub(super) fn speed_writes(&self) -> Vec<Write> {
        let axis = self.ctl.speed_axis();
        let (omega, campbell) = match axis.rpm_scale() {
            Some(s) => {
                let rpm = format!("{} speed (rpm)", s.input());
                (rpm.clone(), rpm)
            }
            None => ("Ω (dimensionless)".into(), "input speed, read as Ω".into()),
        };
        let mut w = vec![Write::text("speed-readout", self.ctl.speed_readout())];
        for key in ["fr", "map", "bif", "dynamic"] {
            w.push(Write::text(&format!("axes-speed-{key}"), omega.clone()));
        }
        w.push(Write::text("axes-speed-campbell", campbell));
        w
    }

    /// The speed axes: their unit, the selected speed in Ω and in rpm of
    /// the input member, the readout, and the factor between them.
    fn speed_status(&self) -> serde_json::Value {
        let axis = self.ctl.speed_axis();
        let omega = self.ctl.settings().view.omega;
        serde_json::json!({
            "axis": axis.unit.name(),
            "input": axis.scale.map(|s| s.input()),
            "omega": omega,
            "rpm": axis.scale.map(|s| s.rpm(omega)),
            "mesh_hz": axis.scale.map(|s| s.mesh_hz(omega)),
            "readout": self.ctl.speed_readout(),
        })
    }

    /// Everything the tests and the benchmark read: the controller's
    /// status, the draw counters, the frames, the timings, the preview
    /// marker, and the gear set's last frame under `anim`.
    pub fn status(&self, now_ms: f64) -> serde_json::Value {
        let mut v = self.ctl.status(now_ms);
        let frame_json = |f: Option<figures::plots::PlotFrame>| {
            serde_json::json!(f.map(|f| [
                f.top_left.x,
                f.top_left.y,
                f.bottom_right.x,
                f.bottom_right.y,
                f.x_range.0,
                f.x_range.1,
                f.y_range.0,
                f.y_range.1
            ]))
        };
        if let Some(o) = v.as_object_mut() {
            let r = &self.redraw;
            o.insert("draws".into(), serde_json::json!(r.draws));
            o.insert("partial_draws".into(), serde_json::json!(r.partial_draws));
            o.insert("te_file".into(), self.te_status());
            o.insert("last_draw_ms".into(), serde_json::json!(r.last_draw_ms));
            o.insert("max_draw_ms".into(), serde_json::json!(r.max_draw_ms));
            o.insert("first_draw_ms".into(), serde_json::json!(r.first_draw_ms));
            o.insert(
                "max_message_ms".into(),
                serde_json::json!(self.telemetry.max_message_ms),
            );
            o.insert(
                "max_frame_ms".into(),
                serde_json::json!(self.telemetry.max_frame_ms),
            );
            o.insert(
                "last_input_ms".into(),
                serde_json::json!(self.telemetry.last_input_ms),
            );
            o.insert("now_ms".into(), serde_json::json!(now_ms));
            for view in [
                ViewId::Map,
                ViewId::Lyap,
                ViewId::Bif,
                ViewId::Time,
                ViewId::Campbell,
                ViewId::Dynamic,
            ] {
                o.insert(
                    format!("{}_frame", view.key()),
                    frame_json(self.frame(view)),
                );
            }
            let corners = self.frame(ViewId::Fr).map(|f| {
                [
                    f.top_left.x,
                    f.top_left.y,
                    f.bottom_right.x,
                    f.bottom_right.y,
                ]
            });
            o.insert("fr_frame".into(), serde_json::json!(corners));
            o.insert(
                "preview_drawn".into(),
                serde_json::json!(self
                    .telemetry
                    .preview_drawn
                    .as_ref()
                    .map(|(ms, summary)| serde_json::json!({"ms": ms, "summary": summary}))),
            );
            o.insert("anim".into(), self.anim.info.clone());
            o.insert("gif".into(), self.anim.gif.clone());
            let (n, last) = (self.telemetry.gestures_ended, self.telemetry.last_gesture);
            o.insert("gesture".into(), serde_json::json!({"n": n, "last": last}));
            o.insert(
                "see_orbit".into(),
                serde_json::json!(self.notices.see_orbit),
            );
            o.insert(
                "tour".into(),
                serde_json::json!({"step": self.ctl.tour(), "done": self.tour_done()}),
            );
            o.insert("map_drawn".into(), self.telemetry.map_drawn.clone());
            o.insert("present".into(), self.present_status());
            o.insert("campbell".into(), self.campbell_status());
            // The mesh force by order as its export says it, with its text.
            // Its lines only while they are few: the status is read at
            // every animation frame while a test waits, and 1000 recorded
            // periods give 8 000 lines (400 kB of JSON a frame).
            let orders = self.ctl.orders_view().ok().map(|v| {
                let mut j = figures::views::orders::orders_json(&v);
                j["label"] = serde_json::json!(v.label());
                j["preview"] = serde_json::json!(v.preview);
                j["lines"] = serde_json::json!(v.lines.len());
                if v.lines.len() > STATUS_ORDER_LINES {
                    if let Some(o) = j.as_object_mut() {
                        o.remove("order");
                        o.remove("amplitude_n");
                    }
                    if let Some(sum) = j["planet_sum"].as_object_mut() {
                        sum.remove("per_planet_n");
                    }
                }
                j
            });
            o.insert("orders".into(), serde_json::json!(orders));
            o.insert("speed".into(), self.speed_status());
            o.insert("dynamic".into(), self.dynamic_status());
            let boxes: serde_json::Map<String, serde_json::Value> = VIEWS
                .iter()
                .zip(&self.telemetry.text_boxes)
                .map(|(spec, (size, b))| {
                    (
                        spec.key.to_string(),
                        serde_json::json!({"size": size, "boxes": b}),
                    )
                })
                .collect();
            o.insert("text_boxes".into(), serde_json::Value::Object(boxes));
        }
        v
    }
}

fn computing(running: bool) -> String {
    if running { " (computing…)" } else { "" }.to_string()
}
