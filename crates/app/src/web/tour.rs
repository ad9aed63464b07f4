//! The "Start here" tour's panel: Start, Back, Next and Skip buttons; each
//! step's settings through the controller ([`Controller::tour_go`]), its
//! words from [`crate::tour::TOUR`], and its target scrolled to and
//! highlighted.

use super::*;
use crate::tour::{counter, TOUR};

/// The step a button leads to from the current one.
type Move = fn(Option<usize>) -> Option<usize>;

/// Wires the tour's buttons and shows the step a link asked for.
pub(super) fn build_tour(page: &Shared) {
    let doc = page.borrow().doc.clone();
    let buttons: [(&str, Move); 4] = [
        ("tour-start", |_| Some(0)),
        ("tour-back", |s| s.map(|s| s.saturating_sub(1))),
        ("tour-next", |s| {
            s.map(|s| s + 1).filter(|&s| s < TOUR.len())
        }),
        ("tour-skip", |_| None),
    ];
    for (id, next) in buttons {
        if let Some(b) = doc.get_element_by_id(id) {
            let page2 = page.clone();
            listen(&b.into(), "click", move |_e: Event| {
                let step = next(page2.borrow().core.ctl().tour());
                go(&page2, step);
            });
        }
    }
    show_tour(&page.borrow());
}

fn go(page: &Shared, step: Option<usize>) {
    let fx = {
        let mut p = page.borrow_mut();
        let t = now(&p.window);
        p.core.ctl_mut().tour_go(step, t)
    };
    run_effects(page, fx);
    show_tour(&page.borrow());
    request_frame(page);
}

/// Shows the current step (or hides the panel), highlights its target and
/// scrolls to it.
fn show_tour(p: &Shell) {
    let doc = &p.doc;
    if let Ok(old) = doc.query_selector_all(".tour-target") {
        for i in 0..old.length() {
            if let Some(e) = old.item(i).and_then(|n| n.dyn_into::<Element>().ok()) {
                check(e.class_list().remove_1("tour-target"));
            }
        }
    }
    let Some(panel) = doc.get_element_by_id("tour") else {
        return;
    };
    let Some(step) = p.core.ctl().tour() else {
        check(panel.set_attribute("hidden", ""));
        return;
    };
    let s = &TOUR[step];
    check(panel.remove_attribute("hidden"));
    check(panel.set_attribute("data-step", &(step + 1).to_string()));
    set_text(doc, "tour-count", &counter(step));
    set_text(doc, "tour-title", s.title);
    set_text(doc, "tour-text", s.text);
    let last = step + 1 == TOUR.len();
    set_text(doc, "tour-next", if last { "Finish" } else { "Next" });
    if let Some(b) = doc.get_element_by_id("tour-back") {
        check(b.toggle_attribute_with_force("disabled", step == 0));
    }
    if let Some(t) = doc.get_element_by_id(s.target) {
        check(t.class_list().add_1("tour-target"));
        t.scroll_into_view();
    }
}
