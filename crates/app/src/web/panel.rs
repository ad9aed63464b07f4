//! The element builder: creates the elements the page core describes
//! ([`crate::page::dom::built`]) and wires every listener to
//! [`Page::act`](crate::page::Page::act); and what only a browser can do
//! for an action: copy the link, offer a file, rasterize a PNG.

use super::*;
use crate::page::boot::Png;
use crate::page::dom::{built, Action, Node, WIRING};
use crate::page::{EventIn, PngFailure};
use web_sys::{Blob, BlobPropertyBag, HtmlAnchorElement, HtmlImageElement, Url};

/// Creates every built element and wires every listener.
pub(super) fn build(page: &Shared) {
    let doc = page.borrow().doc.clone();
    for (id, nodes) in built() {
        let Some(parent) = doc.get_element_by_id(&id) else {
            continue;
        };
        for n in &nodes {
            if let Some(e) = make(page, &doc, n) {
                check(parent.append_child(&e));
            }
        }
    }
    for (id, kind, action) in WIRING {
        if let Some(e) = doc.get_element_by_id(id) {
            on(page, &e, kind, action);
        }
    }
}

/// One node and its children as elements, with their listeners.
fn make(page: &Shared, doc: &Document, n: &Node) -> Option<Element> {
    let e = doc.create_element(n.tag).ok()?;
    for (name, value) in &n.attrs {
        check(e.set_attribute(name, value));
    }
    if let Some(t) = &n.text {
        e.set_text_content(Some(t));
    }
    for c in &n.children {
        if let Some(c) = make(page, doc, c) {
            check(e.append_child(&c));
        }
    }
    for (kind, action) in &n.on {
        on(page, &e, kind, *action);
    }
    Some(e)
}

/// `action` on each `kind` event of `e`, with the element's value and the key.
fn on(page: &Shared, e: &Element, kind: &str, action: Action) {
    let (p2, e2) = (page.clone(), e.clone());
    listen(e, kind, move |ev: Event| {
        let value = js_sys::Reflect::get(&e2, &JsValue::from_str("value"))
            .ok()
            .and_then(|v| v.as_string())
            .unwrap_or_default();
        let key = ev.dyn_ref::<KeyboardEvent>().map(KeyboardEvent::key);
        act(&p2, action, &EventIn { value, key });
    });
}

fn act(page: &Shared, action: Action, ev: &EventIn) {
    if let Action::Png(v) = action {
        return png_2x(page, v);
    }
    if let Action::AnimGif = action {
        return super::gif::export(page);
    }
    // The core hears of every action, the copy of the link too (the
    // tour's last step is done by it); the clipboard is this layer's.
    let out = {
        let mut p = page.borrow_mut();
        let t = now(&p.window);
        p.core.act(action, ev, t)
    };
    paint(&page.borrow(), out.writes);
    run_effects(page, out.effects);
    if out.frame {
        request_frame(page);
    }
    if matches!(action, Action::CopyLink) {
        copy_link(page);
    }
}

/// A drop-down's options, replaced.
pub(super) fn set_options(doc: &Document, sel: &Element, options: &[(String, String)]) {
    sel.set_text_content(None);
    for (value, text) in options {
        if let Ok(o) = doc.create_element("option") {
            check(o.set_attribute("value", value));
            o.set_text_content(Some(text));
            check(sel.append_child(&o));
        }
    }
}

fn copy_link(page: &Shared) {
    let (window, doc) = {
        let p = page.borrow();
        (p.window.clone(), p.doc.clone())
    };
    let href = window.location().href().unwrap_or_default();
    let said = |copied: bool| {
        let page = page.clone();
        Closure::<dyn FnMut(JsValue)>::new(move |_v: JsValue| {
            let mut p = page.borrow_mut();
            let t = now(&p.window);
            let w = p.core.link_copied(copied, t, js_sys::Date::now());
            paint(&p, w);
        })
    };
    let (ok, fail) = (said(true), said(false));
    // The promise settles into `ok` or `fail`, which say so; nothing else
    // waits for it. One pair per click, small: leaked rather than tracked.
    let clipboard = window.navigator().clipboard();
    drop(clipboard.write_text(&href).then2(&ok, &fail));
    ok.forget();
    fail.forget();
    if let Some(b) = doc.get_element_by_id("copy-link") {
        check(b.set_attribute("data-link", &href));
    }
}

pub(super) fn download_text(doc: &Document, name: &str, mime: &str, text: &str) {
    if let Ok(blob) = blob(text, mime) {
        download_blob(doc, name, &blob);
    }
}

fn blob(text: &str, mime: &str) -> Result<Blob, JsValue> {
    let parts = js_sys::Array::of1(&JsValue::from_str(text));
    let opts = BlobPropertyBag::new();
    opts.set_type(mime);
    Blob::new_with_str_sequence_and_options(&parts, &opts)
}

/// Offers `blob` as the file `name` through an object URL (a data URL
/// over 2 MB is refused by the browser without a word).
pub(super) fn download_blob(doc: &Document, name: &str, blob: &Blob) {
    let Ok(url) = Url::create_object_url_with_blob(blob) else {
        return;
    };
    let Some(a) = doc
        .create_element("a")
        .ok()
        .and_then(|a| a.dyn_into::<HtmlAnchorElement>().ok())
    else {
        return;
    };
    a.set_href(&url);
    a.set_download(name);
    a.click();
}

/// Saves a view as a PNG at twice its size: its SVG picture (the same
/// drawing) rasterized onto an offscreen canvas of twice the canvas's
/// size, encoded with `toBlob`. A picture that cannot be made or loaded
/// is said in the messages.
fn png_2x(page: &Shared, v: ViewId) {
    let (doc, png) = (page.borrow().doc.clone(), page.borrow().core.png(v));
    let Png { svg, name, size } = match png {
        Ok(png) => png,
        Err(e) => return failed(page, e),
    };
    let Ok(img) = HtmlImageElement::new() else {
        return failed(page, PngFailure::NoImage);
    };
    let (img2, p2) = (img.clone(), page.clone());
    let onload = Closure::<dyn FnMut()>::new(move || {
        let Some(cv) = doc
            .create_element("canvas")
            .ok()
            .and_then(|e| e.dyn_into::<HtmlCanvasElement>().ok())
        else {
            return;
        };
        cv.set_width(size.0);
        cv.set_height(size.1);
        if let Some(ctx) = ctx2d(&cv) {
            let (dw, dh) = (f64::from(size.0), f64::from(size.1));
            check(ctx.draw_image_with_html_image_element_and_dw_and_dh(&img2, 0.0, 0.0, dw, dh));
        }
        let (doc, name, p3) = (doc.clone(), name.clone(), p2.clone());
        let done = Closure::once_into_js(move |blob: JsValue| match blob.dyn_into::<Blob>() {
            Ok(blob) => download_blob(&doc, &name, &blob),
            Err(_) => failed(&p3, PngFailure::NotEncoded),
        });
        if cv.to_blob(done.unchecked_ref()).is_err() {
            failed(&p2, PngFailure::NotEncoded);
        }
    });
    let p2 = page.clone();
    let onerror = Closure::<dyn FnMut()>::new(move || failed(&p2, PngFailure::NotLoaded));
    img.set_onload(Some(onload.as_ref().unchecked_ref()));
    img.set_onerror(Some(onerror.as_ref().unchecked_ref()));
    // One pair per click, small: leaked rather than tracked.
    onload.forget();
    onerror.forget();
    match blob(&svg, "image/svg+xml").and_then(|b| Url::create_object_url_with_blob(&b)) {
        Ok(url) => img.set_src(&url),
        Err(_) => failed(page, PngFailure::NotStored),
    }
}

fn failed(page: &Shared, why: PngFailure) {
    page.borrow_mut().core.png_failed(why);
    request_frame(page);
}
