//! The page's claims section: the table of `crate::claims` as rows of
//! text (never markup from data), each with a button that loads the
//! figure preset that shows it.

use super::*;
use crate::claims::{heading, CLAIMS};

pub(super) fn build_claims(page: &Shared) {
    let doc = page.borrow().doc.clone();
    let Some(body) = doc.get_element_by_id("claims-rows") else {
        return;
    };
    for c in CLAIMS {
        let Some(tr) = el(&doc, "tr") else { continue };
        check(tr.set_attribute("id", &format!("claim-{}", c.id)));
        for text in [
            heading(c),
            c.says.to_string(),
            c.verdict.to_string(),
            c.evidence.to_string(),
        ] {
            if let Some(td) = el(&doc, "td") {
                td.set_text_content(Some(&text));
                check(tr.append_child(&td));
            }
        }
        if let Some(td) = el(&doc, "td") {
            if let Some(f) = c.figure.and_then(crate::presets::preset) {
                if let Some(b) = el(&doc, "button") {
                    check(b.set_attribute("type", "button"));
                    check(b.set_attribute("title", &format!("Load the preset: {}", f.title)));
                    let short = f.title.split(':').next().unwrap_or(f.id);
                    b.set_text_content(Some(short));
                    let page2 = page.clone();
                    let id = f.id;
                    listen(&b.clone().into(), "click", move |_e: Event| {
                        let fx = {
                            let mut p = page2.borrow_mut();
                            let t = now(&p.window);
                            p.core.ctl_mut().apply_preset(id, t)
                        };
                        run_effects(&page2, fx);
                        request_frame(&page2);
                    });
                    check(td.append_child(&b));
                }
            }
            check(tr.append_child(&td));
        }
        if let Some(td) = el(&doc, "td") {
            if let Some(code) = el(&doc, "code") {
                code.set_text_content(Some(c.command));
                check(td.append_child(&code));
            }
            if !c.with.is_empty() {
                if let Some(note) = el(&doc, "div") {
                    note.set_text_content(Some(&crate::claims::with_text(c)));
                    check(td.append_child(&note));
                }
            }
            check(tr.append_child(&td));
        }
        check(body.append_child(&tr));
    }
}
