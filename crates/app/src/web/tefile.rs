//! The TE file's browser side: the file field's choice and a file dropped
//! on the Advanced group's drop zone are read as text (after the core
//! agreed to their size) and handed to the page core
//! ([`crate::page::tefile`]), which fits and applies them; the fit it
//! keeps is drawn here on its canvas.

use super::*;
use crate::page::tefile::{DROP, HARMONICS, INPUT, KIND, PLOT};
use web_sys::{DragEvent, File, HtmlInputElement};

/// Wires the file field and the drop zone.
pub(super) fn build(page: &Shared) {
    let doc = page.borrow().doc.clone();
    if let Some(input) = by_id::<HtmlInputElement>(&doc, INPUT) {
        let (p2, i2) = (page.clone(), input.clone());
        listen(&input, "change", move |_e: Event| {
            if let Some(f) = i2.files().and_then(|l| l.get(0)) {
                read(&p2, &f);
            }
            // The same file chosen again is read again.
            i2.set_value("");
        });
    }
    // A file dropped beside the box is ignored, not opened in the tab in
    // place of the page (the browser's own default).
    for kind in ["dragover", "drop"] {
        listen(&doc, kind, |e: DragEvent| e.prevent_default());
    }
    if let Some(zone) = doc.get_element_by_id(DROP) {
        let z2 = zone.clone();
        listen(&zone, "dragover", move |e: DragEvent| {
            e.prevent_default();
            check(z2.class_list().add_1("dragging"));
        });
        let z2 = zone.clone();
        listen(&zone, "dragleave", move |_e: DragEvent| {
            check(z2.class_list().remove_1("dragging"));
        });
        let (p2, z2) = (page.clone(), zone.clone());
        listen(&zone, "drop", move |e: DragEvent| {
            e.prevent_default();
            check(z2.class_list().remove_1("dragging"));
            if let Some(f) = e
                .data_transfer()
                .and_then(|d| d.files())
                .and_then(|l| l.get(0))
            {
                read(&p2, &f);
            }
        });
    }
}

/// A drop-down's value.
fn value_of(doc: &Document, id: &str) -> String {
    doc.get_element_by_id(id)
        .and_then(|e| js_sys::Reflect::get(&e, &JsValue::from_str("value")).ok())
        .and_then(|v| v.as_string())
        .unwrap_or_default()
}

/// Reads `file` as text and hands it to the core; a file too large is
/// not read (the core says so).
fn read(page: &Shared, file: &File) {
    let name = file.name();
    let ok = page.borrow_mut().core.te_file_size(&name, file.size());
    if !ok {
        request_frame(page);
        return;
    }
    let p2 = page.clone();
    let done = Closure::<dyn FnMut(JsValue)>::new(move |text: JsValue| {
        let text = text.as_string().unwrap_or_default();
        let out = {
            let p = &mut *p2.borrow_mut();
            let (kind, harmonics) = (value_of(&p.doc, KIND), value_of(&p.doc, HARMONICS));
            let t = now(&p.window);
            p.core.te_file(&kind, &harmonics, &name, &text, t)
        };
        paint(&p2.borrow(), out.writes);
        run_effects(&p2, out.effects);
        draw(&p2);
        request_frame(&p2);
    });
    let p2 = page.clone();
    let failed = Closure::<dyn FnMut(JsValue)>::new(move |_e: JsValue| {
        let mut p = p2.borrow_mut();
        p.core
            .issue("The TE file could not be read by the browser.".into());
        drop(p);
        request_frame(&p2);
    });
    // The promise settles into one of the two; one pair per file, small:
    // leaked rather than tracked.
    drop(file.text().then2(&done, &failed));
    done.forget();
    failed.forget();
}

/// Draws the last fit on its canvas.
fn draw(page: &Shared) {
    let p = page.borrow();
    let (Some(view), Some(cv)) = (p.core.te_view(), by_id::<HtmlCanvasElement>(&p.doc, PLOT))
    else {
        return;
    };
    let Some(b) = canvas::Canvas::new(&cv) else {
        return;
    };
    let root = b.into_drawing_area();
    if let Err(e) = figures::plots::te_fit::draw_te_fit(&root, view) {
        web_sys::console::warn_1(&JsValue::from_str(&e.to_string()));
    }
}
