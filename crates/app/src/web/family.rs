//! The family bar (which parameter to vary and its values) and the small
//! multiples' painting: the bifurcation diagram, phase portrait and
//! Poincaré section of each member side by side. What they show comes from
//! the controller and `plots::multiples`; this file only wires and paints.

use super::*;
use crate::family::FAMILY_KEYS;
use crate::protocol::JobKind;

pub(super) fn build_family_bar(page: &Shared) {
    let doc = page.borrow().doc.clone();
    if let Some(sel) = by_id::<HtmlSelectElement>(&doc, "family-key") {
        for k in FAMILY_KEYS {
            let text = if k.unit.is_empty() {
                k.words.to_string()
            } else {
                format!("{} ({})", k.words, k.unit)
            };
            add_option(&doc, &sel, k.key, &text);
        }
    }
    let apply = {
        let page2 = page.clone();
        move || {
            let fx = {
                let mut p = page2.borrow_mut();
                let key = by_id::<HtmlSelectElement>(&p.doc, "family-key")
                    .map(|s| s.value())
                    .unwrap_or_default();
                let values = by_id::<HtmlInputElement>(&p.doc, "family-values")
                    .map(|s| s.value())
                    .unwrap_or_default();
                let t = now(&p.window);
                match p.ctl.set_family_text(&key, &values, t) {
                    Ok(fx) => {
                        set_text(&p.doc, "family-error", "");
                        fx
                    }
                    Err(e) => {
                        set_text(&p.doc, "family-error", &e);
                        Vec::new()
                    }
                }
            };
            run_effects(&page2, fx);
            request_frame(&page2);
        }
    };
    if let Some(btn) = doc.get_element_by_id("family-apply") {
        let apply = apply.clone();
        listen(&btn.into(), "click", move |_e: Event| apply());
    }
    if let Some(input) = doc.get_element_by_id("family-values") {
        listen(&input.into(), "keydown", move |e: KeyboardEvent| {
            if e.key() == "Enter" {
                apply();
            }
        });
    }
    if let Some(btn) = doc.get_element_by_id("family-clear") {
        let page2 = page.clone();
        listen(&btn.into(), "click", move |_e: Event| {
            let fx = {
                let mut p = page2.borrow_mut();
                set_text(&p.doc, "family-error", "");
                p.ctl.clear_family()
            };
            run_effects(&page2, fx);
            request_frame(&page2);
        });
    }
}

/// The bar's state after a change: the family shown, in words.
pub(super) fn refresh_family_bar(p: &Page) {
    let text = match &p.ctl.family {
        Some(f) => {
            let labels: Vec<String> = (0..f.spec.values.len()).map(|i| f.spec.label(i)).collect();
            if let Some(s) = by_id::<HtmlSelectElement>(&p.doc, "family-key") {
                s.set_value(f.spec.key.key);
            }
            if let Some(i) = by_id::<HtmlInputElement>(&p.doc, "family-values") {
                // Written when the family changed, not while it is typed.
                let code = f.spec.encode();
                if i.get_attribute("data-shown").as_deref() != Some(code.as_str()) {
                    let v: Vec<String> = f
                        .spec
                        .values
                        .iter()
                        .map(|x| crate::settings::fmt_exact(*x))
                        .collect();
                    i.set_value(&v.join(", "));
                    check(i.set_attribute("data-shown", &code));
                }
            }
            format!(
                "Showing {}: one colour each on the frequency response, one panel each on the bifurcation diagram, phase portrait and Poincaré section.",
                labels.join(", ")
            )
        }
        None => String::new(),
    };
    set_text(&p.doc, "family-status", &text);
    if let Some(b) = by_id::<HtmlElement>(&p.doc, "family-clear") {
        b.set_hidden(p.ctl.family.is_none());
    }
}

/// The bifurcation diagrams of the family's members side by side.
pub(super) fn draw_bif_family(p: &mut Page, root: &Area, cv: &HtmlCanvasElement) -> plots::Res<()> {
    let panels = p.ctl.bif_panels();
    let mesh = p.ctl.view_context().mesh_label;
    let running = p.ctl.bif_status.running() || p.ctl.members_running(JobKind::Bif);
    let status = if running { " (computing…)" } else { "" };
    let (frames, groups) = plots::multiples::draw_bif_panels(root, &panels, &mesh, status)?;
    // Clicks pick Omega on the first panel's axis (all share it).
    p.frames[ViewId::Bif.slot()] = frames.into_iter().flatten().next();
    if let Some(ctx) = ctx2d(cv) {
        fill_groups(&ctx, &groups);
    }
    Ok(())
}

/// The frequency responses of the panels' meshes (Figs. 2 and 3, panels
/// a-d), every family member's curve in each.
pub(super) fn draw_fr_panels(p: &mut Page, root: &Area, status: &str) -> plots::Res<()> {
    let panels = p.ctl.fr_panels();
    let frames = plots::multiples::draw_fr_panels(root, &panels, status)?;
    // Clicks pick Omega on the first panel's axis (the column under it
    // shares it).
    p.frames[ViewId::Fr.slot()] = frames.into_iter().flatten().next();
    Ok(())
}

/// The phase portraits (view Phase) or Poincaré sections of the family's
/// members side by side.
pub(super) fn draw_omega_family(p: &mut Page, v: ViewId, root: &Area) -> plots::Res<()> {
    let poincare = v == ViewId::Poincare;
    let n = p.ctl.family.as_ref().map_or(0, |f| f.spec.values.len());
    let panels = p.ctl.omega_panels(if poincare { n } else { 0 });
    let running = p.ctl.omega_status.running() || p.ctl.members_running(JobKind::Omega);
    let status = if running { " (computing…)" } else { "" };
    plots::multiples::draw_phase_panels(root, &panels, poincare, status)
}
