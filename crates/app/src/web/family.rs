//! The family bar (which parameter to vary and its values) and the small
//! multiples' painting: the bifurcation diagram, phase portrait and
//! Poincaré section of each member side by side. What they show comes from
//! the controller and `plots::multiples`; this file only wires and paints.

use super::*;
use crate::family::FAMILY_KEYS;

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
                match p.core.ctl_mut().set_family_text(&key, &values, t) {
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
                p.core.ctl_mut().clear_family()
            };
            run_effects(&page2, fx);
            request_frame(&page2);
        });
    }
}

/// The bar's fields after a change: the family shown (its line and its
/// "Clear" button are the core's writes).
pub(super) fn refresh_family_bar(p: &Shell) {
    let Some(f) = p.core.ctl().family() else {
        return;
    };
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
}

/// The bifurcation diagrams of the family's members side by side.
pub(super) fn draw_bif_family(
    p: &mut Shell,
    root: &Area,
    cv: &HtmlCanvasElement,
) -> plots::Res<()> {
    let panels = p.core.ctl().bif_panels();
    let mesh = p.core.ctl().view_context().mesh_label;
    let status = p.core.caption_suffix(ViewId::Bif, None);
    let (frames, groups) = plots::multiples::draw_bif_panels(root, &panels, &mesh, &status)?;
    // Clicks pick Omega on the first panel's axis (all share it).
    p.core
        .set_frame(ViewId::Bif, frames.into_iter().flatten().next());
    if let Some(ctx) = ctx2d(cv) {
        fill_groups(&ctx, &groups);
    }
    Ok(())
}

/// The frequency responses of the panels' meshes (Figs. 2 and 3, panels
/// a-d), every family member's curve in each.
pub(super) fn draw_fr_panels(p: &mut Shell, root: &Area, status: &str) -> plots::Res<()> {
    let panels = p.core.ctl().fr_panels();
    let frames = plots::multiples::draw_fr_panels(root, &panels, status)?;
    // Clicks pick Omega on the first panel's axis (the column under it
    // shares it).
    p.core
        .set_frame(ViewId::Fr, frames.into_iter().flatten().next());
    Ok(())
}

/// The phase portraits (view Phase) or Poincaré sections of the family's
/// members side by side.
pub(super) fn draw_omega_family(p: &mut Shell, v: ViewId, root: &Area) -> plots::Res<()> {
    let poincare = v == ViewId::Poincare;
    let n = p.core.ctl().family().map_or(0, |f| f.spec.values.len());
    let panels = p.core.ctl().omega_panels(if poincare { n } else { 0 });
    let status = p.core.caption_suffix(v, None);
    plots::multiples::draw_phase_panels(root, &panels, poincare, &status)
}
