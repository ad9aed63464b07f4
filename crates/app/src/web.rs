//! The browser boundary (`wasm_bindgen`, `web_sys`), and this file its
//! page's glue: it hands DOM events, worker messages and animation frames
//! to the page core ([`crate::page::Page`]) and paints what the core
//! lists: its [`Write`]s, and the views it says to draw, with
//! `plotters-canvas`. Its submodules are the rest of the boundary: `panel`
//! builds the controls, toolbar and export bars; `anim` runs and
//! rasterizes the gear set's [`crate::scene::Scene`]; `worker` is the Web
//! Worker's shell.
//!
//! Text from links and workers reaches the page only through
//! `textContent` and attribute setters, never `innerHTML`. A DOM call whose
//! failure leaves the page usable is passed to [`check`], which logs the
//! failure.
use crate::controller::{pool_size, Controller, Effect, ExportError, Format};
use crate::controls::{controls, field_text, shown_for, Group, Target, Widget};
use crate::gearset::{AnimClock, GearSet};
use crate::page::redraw::Decision;
use crate::page::{screen_size, Page, Write};
use crate::plots::{self, PlotFrame, PointGroup};
use crate::presets::PRESETS;
use crate::protocol::JobKind;
use crate::views::ViewId;
use plotters::coord::Shift;
use plotters::prelude::{DrawingArea, IntoDrawingArea};
use std::cell::RefCell;
use std::rc::Rc;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{
    Blob, BlobPropertyBag, CanvasRenderingContext2d, Document, Element, Event, HtmlAnchorElement,
    HtmlCanvasElement, HtmlElement, HtmlInputElement, HtmlSelectElement, IntersectionObserver,
    IntersectionObserverEntry, KeyboardEvent, MessageEvent, MouseEvent, PointerEvent, Url, Window,
    Worker,
};

mod anim;
mod canvas;
mod claims;
mod family;
mod panel;
mod tour;
mod worker;

use anim::{build_anim_controls, observe_anim_visibility, start_anim_loop};
use panel::{
    add_option, build_controls, build_exports, build_toolbar, download_text, refresh_controls,
};
pub use worker::start_worker;

/// Handles a DOM call's failure that leaves the page usable (an attribute
/// not set, a text not drawn, a message not posted to a closed worker): it
/// is logged to the console, here and nowhere else.
fn check<T>(r: Result<T, JsValue>) {
    if let Err(e) = r {
        web_sys::console::warn_1(&e);
    }
}

// ---------------------------------------------------------------- page

/// The page core and what only the browser has: the window, the
/// document, the workers, the gear set's animation.
struct Shell {
    core: Page,
    window: Window,
    doc: Document,
    workers: Vec<Worker>,
    anim: AnimState,
    frame_requested: bool,
}

type Shared = Rc<RefCell<Shell>>;
type Area = DrawingArea<canvas::Canvas, Shift>;

/// The animated gear set's state on the page.
#[derive(Default)]
struct AnimState {
    clock: AnimClock,
    last_ts: Option<f64>,
    frames: u32,
    dirty: bool,
    /// Whether the canvas holds the "no motion yet" frame.
    placeholder: bool,
    /// Whether the gear set's canvas and the time history's cursor canvas
    /// are both scrolled out of view (an `IntersectionObserver` says so):
    /// then the clock runs on but nothing is drawn, which spares the main
    /// thread two canvas updates per frame while workers load the cores.
    offscreen: [bool; 2],
    /// The drawing model and the parameters it was built from.
    set: Option<(solver::params::ModelParams, GearSet)>,
    /// What the last frame showed (for the tests' status).
    info: serde_json::Value,
}

fn now(window: &Window) -> f64 {
    window.performance().map_or(0.0, |p| p.now())
}

fn by_id<T: JsCast>(doc: &Document, id: &str) -> Option<T> {
    doc.get_element_by_id(id)?.dyn_into::<T>().ok()
}

/// Sets an element's text, leaving the DOM (and so the next layout) alone
/// when it already reads `text`.
fn set_text(doc: &Document, id: &str, text: &str) {
    if let Some(e) = doc.get_element_by_id(id) {
        set_text_of(&e, text);
    }
}

fn set_text_of(e: &Element, text: &str) {
    if e.text_content().as_deref() != Some(text) {
        e.set_text_content(Some(text));
    }
}

fn el(doc: &Document, tag: &str) -> Option<Element> {
    doc.create_element(tag).ok()
}

fn listen<E: JsCast + 'static>(
    target: &web_sys::EventTarget,
    kind: &str,
    f: impl FnMut(E) + 'static,
) {
    let mut f = f;
    let cb = Closure::<dyn FnMut(Event)>::new(move |e: Event| {
        if let Ok(e) = e.dyn_into::<E>() {
            f(e);
        }
    });
    check(target.add_event_listener_with_callback(kind, cb.as_ref().unchecked_ref()));
    cb.forget();
}

/// Starts the page: controls, workers, events, first frame.
pub fn start_app() {
    let Some(window) = web_sys::window() else {
        return;
    };
    let Some(doc) = window.document() else {
        return;
    };
    let query = window.location().search().unwrap_or_default();
    let t = now(&window);
    // A worker per logical core but one (the page's), within the pool's
    // bounds; `window.gearshockWorkers` (set by the benchmark) overrides it.
    let cores = window.navigator().hardware_concurrency();
    let cores = (cores.is_finite() && cores >= 1.0).then_some(cores as u32);
    let forced = js_sys::Reflect::get(&window, &JsValue::from_str("gearshockWorkers"))
        .ok()
        .and_then(|v| v.as_f64())
        .filter(|n| n.is_finite() && *n >= 1.0)
        .map(|n| n as usize);
    let workers = forced.unwrap_or_else(|| pool_size(cores));
    let (ctl, effects) = Controller::with_workers(&query, t, workers);
    let page = Rc::new(RefCell::new(Shell {
        core: Page::new(ctl, is_narrow(&window)),
        window: window.clone(),
        doc: doc.clone(),
        workers: Vec::new(),
        anim: AnimState::default(),
        frame_requested: false,
    }));
    build_controls(&page);
    build_toolbar(&page);
    family::build_family_bar(&page);
    claims::build_claims(&page);
    build_exports(&page);
    tour::build_tour(&page);
    fit_canvases(&window, &doc);
    build_canvas_events(&page);
    start_workers(&page);
    run_effects(&page, effects);
    expose_status(&page);
    build_anim_controls(&page);
    observe_anim_visibility(&page);
    start_anim_loop(&page);
    // Progress indicators are time-based: refresh them ten times a second.
    let tick = {
        let page = page.clone();
        Closure::<dyn FnMut()>::new(move || update_progress(&page))
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
fn start_workers(page: &Shared) {
    let workers = page.borrow().core.ctl().workers();
    for w in 0..workers {
        let worker = match Worker::new("./worker_loader.js") {
            Ok(worker) => worker,
            Err(_) => {
                let msg = "could not start a Web Worker; the views cannot be computed";
                page.borrow_mut().core.issue(msg.into());
                continue;
            }
        };
        let onmessage = {
            let page = page.clone();
            Closure::<dyn FnMut(MessageEvent)>::new(move |e: MessageEvent| {
                let text = e.data().as_string().unwrap_or_default();
                let fx = {
                    let mut p = page.borrow_mut();
                    let t = now(&p.window);
                    let fx = p.core.worker_message(w, &text, t);
                    let took = now(&p.window) - t;
                    p.core.message_took(took);
                    fx
                };
                run_effects(&page, fx);
                request_frame(&page);
            })
        };
        worker.set_onmessage(Some(onmessage.as_ref().unchecked_ref()));
        onmessage.forget();
        let onerror = {
            let page = page.clone();
            Closure::<dyn FnMut(Event)>::new(move |_e: Event| {
                let msg = format!("Web Worker {w} failed to load or crashed");
                page.borrow_mut().core.issue(msg);
                request_frame(&page);
            })
        };
        worker.set_onerror(Some(onerror.as_ref().unchecked_ref()));
        onerror.forget();
        page.borrow_mut().workers.push(worker);
    }
}

fn run_effects(page: &Shared, effects: Vec<Effect>) {
    for e in effects {
        match e {
            Effect::Post { worker, text } => {
                let p = page.borrow();
                if let Some(w) = p.workers.get(worker) {
                    check(w.post_message(&JsValue::from_str(&text)));
                }
            }
            Effect::Download { name, mime, text } => {
                let doc = page.borrow().doc.clone();
                download_text(&doc, &name, &mime, &text);
            }
        }
    }
}

fn request_frame(page: &Shared) {
    let window = {
        let mut p = page.borrow_mut();
        if p.frame_requested {
            return;
        }
        p.frame_requested = true;
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
        p.frame_requested = false;
        let t = now(&p.window);
        p.core.apply_pending(t)
    };
    run_effects(page, effects);
    let mut p = page.borrow_mut();
    paint(&p, marks);
    // The frame's drawing budget starts now, after the input (and a
    // selected-Omega preview) was applied.
    let t0 = now(&p.window);
    let (d, order) = p.core.begin_frame(ts);
    // The canvases first, the page's text after: plotters measures legend
    // text in the page (a span it adds and removes), which lays out the
    // whole page again whenever text changed since the last measure.
    let mut writes = Vec::new();
    for &v in order {
        let start = now(&p.window);
        match p.core.decide(v, t0, start) {
            Decision::Stop => break,
            Decision::Skip => continue,
            Decision::Draw => writes.extend(draw_view(&mut p, v)),
        }
        let end = now(&p.window);
        p.core.drawn(v, (start, end), ts);
    }
    paint(&p, writes);
    if d.controls {
        refresh_controls(&p);
    }
    let writes = p.core.end_frame(&d);
    paint(&p, writes);
    if d.url || d.controls {
        family::refresh_family_bar(&p);
    }
    highlight_mesh(&p);
    if p.core.wants_frame() {
        let page2 = page.clone();
        let cb = Closure::once_into_js(move |ts: f64| frame(&page2, ts));
        p.frame_requested = p.window.request_animation_frame(cb.unchecked_ref()).is_ok();
    }
    let took = now(&p.window) - t_frame;
    p.core.frame_took(took);
}

/// Makes the core's writes in the document.
fn paint(p: &Shell, writes: Vec<Write>) {
    let doc = &p.doc;
    for w in writes {
        match w {
            Write::Text { id, text } => set_text(doc, &id, &text),
            Write::Attr { id, name, value } => {
                if let Some(e) = doc.get_element_by_id(&id) {
                    if e.get_attribute(name).as_deref() != Some(value.as_str()) {
                        check(e.set_attribute(name, &value));
                    }
                }
            }
            Write::Hidden { id, hidden } => {
                if let Some(e) = by_id::<HtmlElement>(doc, &id) {
                    if e.hidden() != hidden {
                        e.set_hidden(hidden);
                    }
                }
            }
            Write::Class { id, class, on } => {
                if let Some(e) = doc.get_element_by_id(&id) {
                    check(e.class_list().toggle_with_force(class, on));
                }
            }
            Write::Progress { view, shown } => paint_progress(doc, view, shown),
            Write::Url(q) => {
                if let Ok(h) = p.window.history() {
                    check(h.replace_state_with_url(&JsValue::NULL, "", Some(&format!("?{q}"))));
                }
            }
        }
    }
}

fn paint_progress(doc: &Document, view: ViewId, shown: Option<(f64, String)>) {
    let Some(el) = by_id::<HtmlElement>(doc, &format!("progress-{}", view.key())) else {
        return;
    };
    let Some((frac, label)) = shown else {
        if !el.hidden() {
            el.set_hidden(true);
        }
        return;
    };
    if el.hidden() {
        el.set_hidden(false);
    }
    if let Ok(Some(bar)) = el.query_selector(".bar") {
        let style = format!("width:{:.1}%", 100.0 * frac);
        if bar.get_attribute("style").as_deref() != Some(style.as_str()) {
            check(bar.set_attribute("style", &style));
        }
    }
    if let Ok(Some(l)) = el.query_selector(".label") {
        set_text_of(&l, &label);
    }
}

fn canvas(doc: &Document, view: ViewId) -> Option<HtmlCanvasElement> {
    by_id(doc, &format!("canvas-{}", view.key()))
}

/// Draws one view on its canvas (or why it has nothing to draw); a
/// plotting failure joins the messages. Returns its note and label, for
/// the caller to write after the frame's drawing.
fn draw_view(p: &mut Shell, v: ViewId) -> Vec<Write> {
    let Some(cv) = canvas(&p.doc, v) else {
        return Vec::new();
    };
    // The frequency response's view model, built once for its size, note
    // and plot.
    let fr = (v == ViewId::Fr).then(|| p.core.ctl().fr_view());
    let (w, h) = p.core.canvas_size(v, fr.as_ref());
    if (cv.width(), cv.height()) != (w, h) {
        cv.set_width(w);
        cv.set_height(h);
    }
    let Some(b) = canvas::Canvas::new(&cv) else {
        return Vec::new();
    };
    let root = b.into_drawing_area();
    let mut writes: Vec<Write> = p.core.note(v, fr.as_ref()).into_iter().collect();
    let suffix = p.core.caption_suffix(v, fr.as_ref());
    let r = match p.core.ctl().placeholder(v) {
        Some(message) => {
            // No plot, no frame to map clicks with (the Lyapunov curve
            // drops its frame only when switched off).
            if v == ViewId::Time || (v == ViewId::Lyap && p.core.ctl().main().lyap.id == 0) {
                p.core.set_frame(v, None);
            }
            plots::draw_message(&root, v.spec().title, &message)
        }
        None => match v.spec().data {
            JobKind::HarmonicBalance | JobKind::Overlay => {
                fr.map_or(Ok(()), |fr| draw_fr(p, &root, &fr, &suffix))
            }
            JobKind::Bif | JobKind::Orbits => draw_bif(p, &root, &cv, &suffix),
            JobKind::Omega => draw_omega_view(p, v, &root, &suffix),
            JobKind::Map => draw_map(p, &root, &cv, &suffix),
            JobKind::Lyap => draw_lyap(p, &root, &suffix),
        },
    };
    if v == ViewId::Time {
        p.anim.dirty = true;
    }
    writes.push(Write::Attr {
        id: cv.id(),
        name: "aria-label",
        value: p.core.ctl().canvas_label(v),
    });
    if let Err(e) = r {
        p.core.plot_failed(e.to_string());
    }
    writes
}

fn draw_fr(
    p: &mut Shell,
    root: &Area,
    v: &crate::views::fr::FrView,
    suffix: &str,
) -> plots::Res<()> {
    if p.core.ctl().panels().is_some() {
        return family::draw_fr_panels(p, root, suffix);
    }
    let f = plots::draw_fr(root, v, suffix)?;
    p.core.set_frame(ViewId::Fr, Some(f));
    Ok(())
}

fn fill_groups(ctx: &CanvasRenderingContext2d, groups: &[PointGroup]) {
    for g in groups {
        let c = format!("rgb({},{},{})", g.color.0, g.color.1, g.color.2);
        ctx.begin_path();
        for &(x, y) in &g.px {
            if g.filled {
                ctx.rect(f64::from(x) - 1.25, f64::from(y) - 1.25, 2.5, 2.5);
            } else {
                ctx.rect(f64::from(x) - 2.5, f64::from(y) - 2.5, 5.0, 5.0);
            }
        }
        if g.filled {
            ctx.set_fill_style_str(&c);
            ctx.fill();
        } else {
            ctx.set_stroke_style_str(&c);
            ctx.set_line_width(1.0);
            ctx.stroke();
        }
    }
}

fn draw_bif(p: &mut Shell, root: &Area, cv: &HtmlCanvasElement, suffix: &str) -> plots::Res<()> {
    if p.core.ctl().family().is_some() {
        return family::draw_bif_family(p, root, cv);
    }
    let v = p.core.ctl().bif_view();
    let natural = p.core.ctl().view_context().natural;
    let (frame, groups) = plots::draw_bif(root, &v, &natural, suffix)?;
    p.core.set_frame(ViewId::Bif, Some(frame));
    if let Some(ctx) = ctx2d(cv) {
        fill_groups(&ctx, &groups);
    }
    Ok(())
}

fn draw_map(p: &mut Shell, root: &Area, cv: &HtmlCanvasElement, suffix: &str) -> plots::Res<()> {
    let (f, o) = crate::plots::maps::draw_map(root, &p.core.ctl().map_view(), suffix)?;
    p.core.set_frame(ViewId::Map, Some(f));
    if let Some(ctx) = ctx2d(cv) {
        fill_map(&ctx, &f, &o);
    }
    Ok(())
}

/// The map's cells, one path per colour, then the period dots and the cursor.
fn fill_map(ctx: &CanvasRenderingContext2d, f: &PlotFrame, o: &crate::plots::maps::MapOverlay) {
    for (c, rects) in &o.cells {
        ctx.begin_path();
        for r in rects {
            ctx.rect(r[0], r[1], r[2], r[3]);
        }
        ctx.set_fill_style_str(&format!("rgb({},{},{})", c.0, c.1, c.2));
        ctx.fill();
    }
    ctx.begin_path();
    for d in &o.dots {
        ctx.move_to(d[0] + o.dot_radius, d[1]);
        check(ctx.arc(d[0], d[1], o.dot_radius, 0.0, std::f64::consts::TAU));
    }
    ctx.set_fill_style_str("#000");
    ctx.fill();
    ctx.set_stroke_style_str("rgba(0,0,0,0.7)");
    ctx.set_line_width(1.0);
    ctx.begin_path();
    if let Some(x) = o.cursor.0 {
        ctx.move_to(x, f.top_left.y);
        ctx.line_to(x, f.bottom_right.y);
    }
    if let Some(y) = o.cursor.1 {
        ctx.move_to(f.top_left.x, y);
        ctx.line_to(f.bottom_right.x, y);
    }
    ctx.stroke();
}

fn draw_lyap(p: &mut Shell, root: &Area, suffix: &str) -> plots::Res<()> {
    let ctl = p.core.ctl();
    let v = &ctl.settings().view;
    let natural = ctl.view_context().natural;
    let range = (v.omega_from, v.omega_to);
    let f =
        crate::plots::maps::draw_lyap(root, &ctl.main().lyap, range, &natural, v.omega, suffix)?;
    p.core.set_frame(ViewId::Lyap, Some(f));
    Ok(())
}

fn draw_omega_view(p: &mut Shell, v: ViewId, root: &Area, stale: &str) -> plots::Res<()> {
    if p.core.ctl().family().is_some() && matches!(v, ViewId::Phase | ViewId::Poincare) {
        return family::draw_omega_family(p, v, root);
    }
    let Some(res) = &p.core.ctl().main().omega else {
        return Ok(());
    };
    let whole = p.core.ctl().settings().view.whole_clearance;
    let time = match v {
        ViewId::Phase => return plots::draw_phase_with(root, res, stale, whole),
        ViewId::Poincare => return plots::draw_poincare_with(root, res, stale, whole),
        ViewId::Time => plots::draw_time_with(root, res, stale, whole),
        _ => return plots::draw_spectrum(root, res, stale),
    };
    p.core.set_frame(v, time.as_ref().ok().copied());
    time.map(|_| ())
}

/// The schematic's plotted mesh, and the schematic of the model shown.
fn highlight_mesh(p: &Shell) {
    let selected = format!("mesh-{}", p.core.ctl().highlighted_mesh());
    if let Ok(list) = p.doc.query_selector_all("#schematic .mesh") {
        for i in 0..list.length() {
            if let Some(e) = list.get(i).and_then(|n| n.dyn_into::<Element>().ok()) {
                check(
                    e.class_list()
                        .toggle_with_force("selected", e.id() == selected),
                );
            }
        }
    }
    let pair = p.core.ctl().settings().params.kind() == solver::ModelKind::GearPair;
    for (id, show) in [("schem-ravigneaux", !pair), ("schem-pair", pair)] {
        if let Some(e) = p.doc.get_element_by_id(id) {
            check(e.set_attribute("style", if show { "" } else { "display:none" }));
        }
    }
}

fn update_progress(page: &Shared) {
    let p = page.borrow();
    let writes = p.core.progress(now(&p.window));
    paint(&p, writes);
}

// ---------------------------------------------------------------- canvases

/// A mouse event's position in the canvas's drawing pixels.
fn canvas_xy(cv: &HtmlCanvasElement, e: &MouseEvent) -> (f64, f64) {
    let css_w = f64::from(cv.client_width().max(1));
    let css_h = f64::from(cv.client_height().max(1));
    (
        f64::from(e.offset_x()) * f64::from(cv.width()) / css_w,
        f64::from(e.offset_y()) * f64::from(cv.height()) / css_h,
    )
}

fn canvas_px(cv: &HtmlCanvasElement, e: &MouseEvent) -> f64 {
    canvas_xy(cv, e).0
}

/// On a narrow screen (under [`plots::NARROW`] CSS pixels) every plot's
/// canvas draws on fewer, larger pixels and is taller for its width (its
/// key takes more rows), so that the plotting area keeps a readable height:
/// the plots adapt to their canvas's size. The gear set keeps its drawing.
fn fit_canvases(window: &Window, doc: &Document) {
    if !is_narrow(window) {
        return;
    }
    let Ok(all) = doc.query_selector_all("canvas") else {
        return;
    };
    for k in 0..all.length() {
        let Some(cv) = all
            .item(k)
            .and_then(|n| n.dyn_into::<HtmlCanvasElement>().ok())
        else {
            continue;
        };
        if cv.id() == "canvas-anim" {
            continue;
        }
        let (w, h) = screen_size((cv.width(), cv.height()), cv.id() == "canvas-fr", true);
        cv.set_width(w);
        cv.set_height(h);
    }
}

/// Whether the window is narrower than [`plots::NARROW`] CSS pixels.
fn is_narrow(window: &Window) -> bool {
    window
        .inner_width()
        .ok()
        .and_then(|w| w.as_f64())
        .is_some_and(|w| w < f64::from(plots::NARROW))
}

fn build_canvas_events(page: &Shared) {
    let doc = page.borrow().doc.clone();
    if let Some(cv) = canvas(&doc, ViewId::Map) {
        let page2 = page.clone();
        let cv2 = cv.clone();
        listen(&cv.into(), "click", move |e: MouseEvent| {
            let (px, py) = canvas_xy(&cv2, &e);
            let fx = {
                let mut p = page2.borrow_mut();
                let t = now(&p.window);
                p.core.map_click(px, py, t)
            };
            run_effects(&page2, fx);
            request_frame(&page2);
        });
    }
    // The views with an Omega axis: a click or drag selects that Omega
    // (pointer events: a mouse and a finger take one path; the canvas's
    // `touch-action: pan-y` leaves vertical swipes to scroll the page),
    // and the arrows step it.
    for view in [ViewId::Fr, ViewId::Bif, ViewId::Lyap] {
        let Some(cv) = canvas(&doc, view) else {
            continue;
        };
        for (kind, press) in [
            ("pointerdown", Some(true)),
            ("pointermove", None),
            ("pointerup", Some(false)),
            ("pointercancel", Some(false)),
        ] {
            let (p2, cv2) = (page.clone(), cv.clone());
            listen(&cv.clone().into(), kind, move |e: PointerEvent| {
                if press == Some(true) {
                    // Keeps the drag's events when the pointer leaves the canvas.
                    let _ = cv2.set_pointer_capture(e.pointer_id());
                }
                let x = canvas_px(&cv2, &e);
                let held = e.buttons() & 1 == 1;
                if p2.borrow_mut().core.pointer(view, x, press, held) {
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

// ---------------------------------------------------------------- tests' hook

/// `window.gearshockStatus()` returns the page core's status as JSON (job
/// progress and timings, the link, messages, draw counts): the browser
/// tests and the benchmark read it instead of guessing from pixels.
fn expose_status(page: &Shared) {
    let window = page.borrow().window.clone();
    let page2 = page.clone();
    let f = Closure::<dyn FnMut() -> String>::new(move || {
        let p = page2.borrow();
        let t = now(&p.window);
        p.core.status(t, p.anim.info.clone()).to_string()
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
