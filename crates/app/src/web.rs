//! The browser boundary (`wasm_bindgen`, `web_sys`), and this file its
//! page's glue: it hands DOM events, worker messages and animation frames
//! to the page core ([`crate::page::Page`]) and paints what the core
//! lists: its [`Write`]s, and the views it says to draw. Its submodules
//! are the rest of the boundary: `panel` creates the elements the core
//! describes ([`crate::page::dom`]) and does what only a browser can (the
//! clipboard, a download, a PNG); `anim` rasterizes the gear set's
//! [`crate::scene::Scene`]; `canvas` is the plotters backend; `worker` is
//! the Web Worker's shell.
//!
//! Text from links and workers reaches the page only through
//! `textContent` and attribute setters, never `innerHTML`. A DOM call whose
//! failure leaves the page usable is passed to [`check`], which logs it.
use crate::controller::Effect;
use crate::page::boot::{drawing_px, Browser, POINTER_EVENTS};
use crate::page::{Page, Phase, PointerIn, Write};
use figures::views::ViewId;
use plotters::prelude::IntoDrawingArea;
use std::cell::RefCell;
use std::rc::Rc;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{
    CanvasRenderingContext2d, Document, Element, Event, HtmlCanvasElement, KeyboardEvent,
    MessageEvent, MouseEvent, PointerEvent, Window, Worker,
};

mod anim;
mod canvas;
mod gif;
mod panel;
mod present;
mod tefile;
mod worker;

pub use worker::start_worker;

/// Handles a DOM call's failure that leaves the page usable (an attribute
/// not set, a text not drawn, a message not posted to a closed worker): it
/// is logged to the console, here and nowhere else.
fn check<T>(r: Result<T, JsValue>) {
    if let Err(e) = r {
        web_sys::console::warn_1(&e);
    }
}

/// The page core and what only the browser has: the window, the
/// document, the workers.
struct Shell {
    core: Page,
    window: Window,
    doc: Document,
    workers: Vec<Worker>,
}

type Shared = Rc<RefCell<Shell>>;

fn now(window: &Window) -> f64 {
    window.performance().map_or(0.0, |p| p.now())
}

fn by_id<T: JsCast>(doc: &Document, id: &str) -> Option<T> {
    doc.get_element_by_id(id)?.dyn_into::<T>().ok()
}

/// Sets an element's text, leaving the DOM (and so the next layout) alone
/// when it already reads `text`.
fn set_text_of(e: &Element, text: &str) {
    if e.text_content().as_deref() != Some(text) {
        e.set_text_content(Some(text));
    }
}

fn listen<E: JsCast + 'static>(
    target: &web_sys::EventTarget,
    kind: &str,
    mut f: impl FnMut(E) + 'static,
) {
    let cb = Closure::<dyn FnMut(Event)>::new(move |e: Event| {
        if let Ok(e) = e.dyn_into::<E>() {
            f(e);
        }
    });
    check(target.add_event_listener_with_callback(kind, cb.as_ref().unchecked_ref()));
    cb.forget();
}

/// Whether the browser's media query `q` matches.
fn media(window: &Window, q: &str) -> bool {
    window
        .match_media(q)
        .ok()
        .flatten()
        .is_some_and(|m| m.matches())
}

/// Starts the page: workers, elements, events, first frame.
pub fn start_app() {
    let Some(window) = web_sys::window() else {
        return;
    };
    let Some(doc) = window.document() else {
        return;
    };
    let number = |v: JsValue| v.as_f64();
    // The workers index.html started: their count is the pool's.
    let early = early_workers(&window);
    let browser = Browser {
        query: window.location().search().unwrap_or_default(),
        now_ms: now(&window),
        early_workers: early.len(),
        cores: Some(window.navigator().hardware_concurrency()),
        forced_workers: js_sys::Reflect::get(&window, &"gearshockWorkers".into())
            .ok()
            .and_then(number),
        width: window.inner_width().ok().and_then(number),
        reduced_motion: media(&window, "(prefers-reduced-motion: reduce)"),
    };
    let (core, effects) = Page::boot(&browser);
    let page = Rc::new(RefCell::new(Shell {
        core,
        window: window.clone(),
        doc: doc.clone(),
        workers: Vec::new(),
    }));
    // The workers first: the jobs on screen are posted as soon as a worker
    // is ready, while the page builds its elements.
    start_workers(&page, early);
    run_effects(&page, effects);
    panel::build(&page);
    paint(&page.borrow(), page.borrow().core.first_writes());
    let w = page.borrow_mut().core.first_present_writes();
    paint(&page.borrow(), w);
    present::build(&page);
    tefile::build(&page);
    build_canvas_events(&page);
    expose_status(&page);
    anim::observe_anim_visibility(&page);
    anim::start_anim_loop(&page);
    // Progress indicators are time-based: refresh them ten times a second.
    let tick = {
        let page = page.clone();
        Closure::<dyn FnMut()>::new(move || {
            let mut p = page.borrow_mut();
            let t = now(&p.window);
            let w = p.core.progress(t);
            paint(&p, w);
        })
    };
    check(
        window.set_interval_with_callback_and_timeout_and_arguments_0(
            tick.as_ref().unchecked_ref(),
            100,
        ),
    );
    tick.forget();
    request_frame(&page);
}

/// A worker `index.html` started before the page's WebAssembly loaded,
/// with the messages it sent meanwhile and whether it failed.
struct Early {
    worker: Worker,
    messages: Vec<String>,
    failed: bool,
}

/// Takes the workers `index.html` started (`window.gearshockEarlyWorkers`):
/// their queueing handlers are removed, so every later message reaches
/// the page's listener ([`start_workers`]); [`start_app`] does both in
/// one task, so none is lost between.
fn early_workers(window: &Window) -> Vec<Early> {
    let key = JsValue::from_str("gearshockEarlyWorkers");
    let list = js_sys::Reflect::get(window, &key).unwrap_or(JsValue::UNDEFINED);
    check(js_sys::Reflect::delete_property(window, &key).map(drop));
    let Ok(list) = list.dyn_into::<js_sys::Array>() else {
        return Vec::new();
    };
    let field = |e: &JsValue, name: &str| js_sys::Reflect::get(e, &JsValue::from_str(name)).ok();
    list.iter()
        .filter_map(|e| {
            let worker = field(&e, "worker")?.dyn_into::<Worker>().ok()?;
            worker.set_onmessage(None);
            worker.set_onerror(None);
            let messages = field(&e, "messages")
                .and_then(|m| m.dyn_into::<js_sys::Array>().ok())
                .map(|m| m.iter().filter_map(|t| t.as_string()).collect())
                .unwrap_or_default();
            let failed = field(&e, "failed").is_some_and(|f| f.is_truthy());
            Some(Early {
                worker,
                messages,
                failed,
            })
        })
        .collect()
}

/// Starts the pool: the workers `index.html` started (`early`), adopted
/// with the messages they sent meanwhile; where it started none, new ones.
/// The pool's size is theirs ([`crate::page::boot::pool_size_of`]), so
/// none is missing and none extra, unless it exceeds the pool's bounds.
fn start_workers(page: &Shared, early: Vec<Early>) {
    let workers = page.borrow().core.ctl().workers();
    let mut early = early.into_iter();
    for w in 0..workers {
        let (worker, messages, failed) = match early.next() {
            Some(e) => (e.worker, e.messages, e.failed),
            None => {
                let Ok(worker) = Worker::new("./worker_loader.js") else {
                    page.borrow_mut().core.worker_missing();
                    continue;
                };
                (worker, Vec::new(), false)
            }
        };
        let said = {
            let page = page.clone();
            move |text: &str| {
                let fx = {
                    let p = &mut *page.borrow_mut();
                    p.core.worker_said(w, text, || now(&p.window))
                };
                run_effects(&page, fx);
                request_frame(&page);
            }
        };
        listen(&worker, "message", {
            let said = said.clone();
            move |e: MessageEvent| said(&e.data().as_string().unwrap_or_default())
        });
        let p2 = page.clone();
        listen(&worker, "error", move |_e: Event| {
            let fx = {
                let p = &mut *p2.borrow_mut();
                let t = now(&p.window);
                p.core.worker_failed(w, t)
            };
            run_effects(&p2, fx);
            request_frame(&p2);
        });
        page.borrow_mut().workers.push(worker);
        for text in &messages {
            said(text);
        }
        if failed {
            let fx = {
                let p = &mut *page.borrow_mut();
                let t = now(&p.window);
                p.core.worker_failed(w, t)
            };
            run_effects(page, fx);
        }
    }
    for extra in early {
        extra.worker.terminate();
    }
}

fn run_effects(page: &Shared, effects: Vec<Effect>) {
    for e in effects {
        match e {
            Effect::Post { worker, text } => {
                if let Some(w) = page.borrow().workers.get(worker) {
                    check(w.post_message(&JsValue::from_str(&text)));
                }
            }
            Effect::Download { name, mime, text } => {
                let doc = page.borrow().doc.clone();
                panel::download_text(&doc, &name, &mime, &text);
            }
        }
    }
}

fn request_frame(page: &Shared) {
    let window = {
        let mut p = page.borrow_mut();
        if !p.core.request_frame() {
            return;
        }
        p.window.clone()
    };
    let page2 = page.clone();
    let cb = Closure::once_into_js(move |ts: f64| frame(&page2, ts));
    check(window.request_animation_frame(cb.unchecked_ref()));
}

/// Once per animation frame (`ts`: its time stamp): the core applies the
/// queued input, then the views it picks are drawn and its writes made.
fn frame(page: &Shared, ts: f64) {
    let t_frame = now(&page.borrow().window);
    let (effects, marks) = {
        let mut p = page.borrow_mut();
        let t = now(&p.window);
        p.core.apply_pending(t)
    };
    run_effects(page, effects);
    let mut p = page.borrow_mut();
    paint(&p, marks);
    present::fit(&mut p);
    let Shell {
        core, doc, window, ..
    } = &mut *p;
    let writes = core.draw_frame(ts, || now(window), |core, v| paint_canvas(core, doc, v));
    paint(&p, writes);
    if p.core.next_frame() {
        let page2 = page.clone();
        let cb = Closure::once_into_js(move |ts: f64| frame(&page2, ts));
        check(p.window.request_animation_frame(cb.unchecked_ref()));
    }
    let took = now(&p.window) - t_frame;
    p.core.frame_took(took);
}

/// Makes the core's writes in the document (each only if it changes it).
fn paint(p: &Shell, writes: Vec<Write>) {
    for w in writes {
        let Some(e) = w.id().and_then(|id| p.doc.get_element_by_id(id)) else {
            if let Write::Url(q) = &w {
                write_url(&p.window, q);
            }
            continue;
        };
        match w {
            Write::Text { text, .. } => set_text_of(&e, &text),
            Write::Attr { name, value, .. } => {
                if e.get_attribute(name).as_deref() != Some(value.as_str()) {
                    check(e.set_attribute(name, &value));
                }
            }
            Write::Hidden { hidden: on, .. } => {
                if e.has_attribute("hidden") != on {
                    check(e.toggle_attribute_with_force("hidden", on));
                }
            }
            Write::Flag { name, on, .. } => check(e.toggle_attribute_with_force(name, on)),
            Write::Class { class, on, .. } => check(e.class_list().toggle_with_force(class, on)),
            Write::Value { value, .. } => {
                let v = JsValue::from_str(&value);
                check(js_sys::Reflect::set(&e, &JsValue::from_str("value"), &v));
            }
            Write::Options { options, .. } => panel::set_options(&p.doc, &e, &options),
            Write::Scroll(_) => e.scroll_into_view(),
            Write::Focus(_) => {
                if let Some(h) = e.dyn_ref::<web_sys::HtmlElement>() {
                    check(h.focus());
                }
            }
            Write::PlaceCard {
                keep_clear,
                prefer_clear,
                docked,
                new_step,
                ..
            } => place_card(p, &e, (&keep_clear, &prefer_clear), docked, new_step),
            Write::Url(_) => {}
        }
    }
}

/// Writes `query` into the address bar, in a task of its own after this
/// one: the browser's history call takes 15-70 ms of the main thread on a
/// busy machine (measured), which would otherwise lengthen the frame that
/// drew the views.
fn write_url(window: &Window, query: &str) {
    let url = format!("?{query}");
    let w = window.clone();
    let cb = Closure::once_into_js(move || {
        if let Ok(h) = w.history() {
            check(h.replace_state_with_url(&JsValue::NULL, "", Some(&url)));
        }
    });
    check(window.set_timeout_with_callback(cb.unchecked_ref()));
}

/// Places `card` clear of the elements `keep_clear` (its target first)
/// and, where it can, of `prefer_clear`, as [`crate::tour::placement`]
/// says from the window's geometry, and scrolls on if it says so.
/// Elements without a box (in a closed drawer) are left out; without its
/// target the card stays.
fn place_card(
    p: &Shell,
    card: &Element,
    (keep_clear, prefer_clear): (&[String], &[String]),
    docked: bool,
    new_step: bool,
) {
    let Some(card) = card.dyn_ref::<web_sys::HtmlElement>() else {
        return;
    };
    // The reader went to a control: the page stays where it was scrolled.
    if docked && !new_step && card.has_attribute("data-at-control") {
        return;
    }
    let rect = |e: &Element| {
        let r = e.get_bounding_client_rect();
        [r.left(), r.top(), r.right(), r.bottom()]
    };
    let boxes = |ids: &[String]| -> Vec<Option<[f64; 4]>> {
        ids.iter()
            .map(|id| {
                p.doc
                    .get_element_by_id(id)
                    .map(|e| rect(&e))
                    .filter(|r| r[2] > r[0] && r[3] > r[1])
            })
            .collect()
    };
    let keep = boxes(keep_clear);
    if keep.first().is_none_or(Option::is_none) {
        return;
    }
    let view = p.doc.document_element().map_or((0.0, 0.0), |e| {
        (f64::from(e.client_width()), f64::from(e.client_height()))
    });
    let shown = !card.hidden() && card.offset_width() > 0;
    // Where the target was when the card was last placed ("x y").
    let anchor = card.get_attribute("data-anchor").and_then(|a| {
        let mut v = a.split(' ').map(str::parse::<f64>);
        Some((v.next()?.ok()?, v.next()?.ok()?, v.next()?.ok()?))
    });
    let g = crate::tour::Geometry {
        keep_clear: keep.into_iter().flatten().collect(),
        prefer_clear: boxes(prefer_clear).into_iter().flatten().collect(),
        card_now: shown.then(|| rect(card)),
        anchor,
        scroll: (
            p.window.scroll_x().unwrap_or(0.0),
            p.window.scroll_y().unwrap_or(0.0),
        ),
        view,
        card: (
            f64::from(card.offset_width()),
            f64::from(card.offset_height()),
        ),
    };
    let placed = crate::tour::placement(&g, new_step, docked);
    if let Some((x, y)) = placed.at {
        let style = card.style();
        check(style.set_property("left", &format!("{x:.0}px")));
        check(style.set_property("top", &format!("{y:.0}px")));
    }
    if let Some(by) = placed.scroll_by {
        p.window.scroll_by_with_x_and_y(0.0, by);
    }
    if let Some((x, y, top)) = placed.anchor {
        // The target's place on the page (a scroll does not move it) and
        // on the screen.
        check(card.set_attribute("data-anchor", &format!("{x:.1} {y:.1} {top:.1}")));
    }
}

fn canvas(doc: &Document, view: ViewId) -> Option<HtmlCanvasElement> {
    by_id(doc, &format!("canvas-{}", view.key()))
}

/// Draws one view on its canvas (the core draws, this fills the dots and
/// the map's cells); returns its writes, to make after the frame's drawing.
fn paint_canvas(core: &mut Page, doc: &Document, v: ViewId) -> Vec<Write> {
    if core.presented_view() == Some(v) {
        return present::draw(core, doc, v);
    }
    let Some(cv) = canvas(doc, v) else {
        return Vec::new();
    };
    let (fr, (w, h)) = core.prepare(v);
    if (cv.width(), cv.height()) != (w, h) {
        cv.set_width(w);
        cv.set_height(h);
    }
    let Some(b) = canvas::Canvas::new(&cv) else {
        return Vec::new();
    };
    let (writes, overlay) = core.draw_on(v, b, fr.as_ref());
    if let Some(ctx) = ctx2d(&cv) {
        anim::paint_items(&ctx, &overlay, (f64::from(w), f64::from(h)));
    }
    writes
}

/// A mouse event's position in the canvas's drawing pixels.
fn canvas_xy(cv: &HtmlCanvasElement, e: &MouseEvent) -> (f64, f64) {
    let offset = (f64::from(e.offset_x()), f64::from(e.offset_y()));
    let css = (f64::from(cv.client_width()), f64::from(cv.client_height()));
    drawing_px(offset, css, (cv.width(), cv.height()))
}

/// The canvases' events: a click on the map picks a cell, on the time
/// history an instant of the animation; on an Omega axis a tap, a drag or
/// the arrows pick Omega (the core tells a tap and a drag from a swipe).
fn build_canvas_events(page: &Shared) {
    let doc = page.borrow().doc.clone();
    for view in [ViewId::Map, ViewId::Time, ViewId::Campbell] {
        let Some(cv) = canvas(&doc, view) else {
            continue;
        };
        let (p2, cv2) = (page.clone(), cv.clone());
        listen(&cv.into(), "click", move |e: MouseEvent| {
            let (x, y) = canvas_xy(&cv2, &e);
            let fx = {
                let mut p = p2.borrow_mut();
                let t = now(&p.window);
                p.core.click(view, x, y, t)
            };
            run_effects(&p2, fx);
            request_frame(&p2);
        });
    }
    if let Some(cv) = canvas(&doc, ViewId::Campbell) {
        let p2 = page.clone();
        listen(&cv.into(), "keydown", move |e: KeyboardEvent| {
            if p2.borrow_mut().core.campbell_key(&e.key()) {
                e.prevent_default();
                request_frame(&p2);
            }
        });
    }
    for view in [ViewId::Fr, ViewId::Bif, ViewId::Lyap, ViewId::Dynamic] {
        let Some(cv) = canvas(&doc, view) else {
            continue;
        };
        for (kind, phase) in POINTER_EVENTS {
            let (p2, cv2) = (page.clone(), cv.clone());
            listen(&cv.clone().into(), kind, move |e: PointerEvent| {
                if phase == Phase::Down {
                    // Keeps the drag's events when the pointer leaves the canvas.
                    check(cv2.set_pointer_capture(e.pointer_id()));
                }
                let at = (f64::from(e.client_x()), f64::from(e.client_y()));
                let ev = PointerIn::new(phase, canvas_xy(&cv2, &e).0, at, &e.pointer_type());
                if p2.borrow_mut().core.pointer(view, ev) {
                    request_frame(&p2);
                }
            });
        }
        let p2 = page.clone();
        listen(&cv.into(), "keydown", move |e: KeyboardEvent| {
            if p2.borrow_mut().core.key(&e.key(), e.shift_key()) {
                e.prevent_default();
                request_frame(&p2);
            }
        });
    }
}

/// `window.gearshockStatus()` returns the page core's status as JSON (job
/// progress and timings, the link, messages, draw counts, the gear set's
/// last frame): the browser tests and the benchmark read it instead of
/// guessing from pixels.
fn expose_status(page: &Shared) {
    let window = page.borrow().window.clone();
    let page2 = page.clone();
    let f = Closure::<dyn FnMut() -> String>::new(move || {
        let p = page2.borrow();
        p.core.status(now(&p.window)).to_string()
    });
    check(js_sys::Reflect::set(
        &window,
        &JsValue::from_str("gearshockStatus"),
        f.as_ref(),
    ));
    f.forget();
}

fn ctx2d(cv: &HtmlCanvasElement) -> Option<CanvasRenderingContext2d> {
    cv.get_context("2d")
        .ok()
        .flatten()
        .and_then(|c| c.dyn_into::<CanvasRenderingContext2d>().ok())
}
