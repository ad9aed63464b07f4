//! The browser boundary (`wasm_bindgen`, `web_sys`), and this file its
//! page: it turns DOM events into [`Controller`] calls, runs the page's
//! animation-frame loop and paints the views with `plotters-canvas`. What to
//! draw and when ([`Redraw`]), every text it shows and every export come
//! from the natively tested modules; this file only reads events and
//! paints. Its submodules are the rest of the boundary: `panel` builds the
//! controls, toolbar and export bars; `anim` runs and rasterizes the gear
//! set's [`crate::scene::Scene`]; `worker` is the Web Worker's shell.
//!
//! Main-thread rules: input events only queue work; the queued slider
//! values, Omega selections and redraws are applied once per animation
//! frame, so a fast drag costs one job restart and one redraw per frame.
//! Text from links and workers reaches the page only through `textContent`
//! and attribute setters, never `innerHTML`. A DOM call whose failure
//! leaves the page usable is passed to [`check`], which logs the failure.
use crate::controller::{pool_size, Controller, Effect, ExportError, Format};
use crate::controls::{controls, field_text, shown_for, Group, Target, Widget};
use crate::gearset::{AnimClock, GearSet};
use crate::plots::{self, PlotFrame, PointGroup};
use crate::presets::PRESETS;
use crate::views::redraw::{Decision, FrameTurn, Redraw};
use crate::views::{ExportKind, ViewId, DRAW_ORDER, VIEWS};
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

struct Page {
    ctl: Controller,
    window: Window,
    doc: Document,
    workers: Vec<Worker>,
    /// Each view's plot frame as last drawn (views with pixel-to-data
    /// mappings), by [`ViewId::slot`].
    frames: [Option<PlotFrame>; VIEWS.len()],
    anim: AnimState,
    pending: Vec<(String, String)>,
    pending_omega: Option<f64>,
    frame_requested: bool,
    last_query: String,
    redraw: Redraw,
    /// The longest handling of one worker message (ms), for the tests.
    max_message_ms: f64,
    /// The longest animation frame's work (ms), for the tests.
    max_frame_ms: f64,
    /// Whether the views or the gear set draw in an animation frame.
    turn: FrameTurn,
    last_input_ms: f64,
    dragging: bool,
    /// Whether the screen is narrow (a phone): plots draw on fewer, larger
    /// pixels, see [`fit_canvases`].
    narrow: bool,
}

type Shared = Rc<RefCell<Page>>;
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
    let page = Rc::new(RefCell::new(Page {
        ctl,
        window: window.clone(),
        doc: doc.clone(),
        workers: Vec::new(),
        frames: [None; VIEWS.len()],
        anim: AnimState::default(),
        pending: Vec::new(),
        pending_omega: None,
        frame_requested: false,
        last_query: String::new(),
        redraw: Redraw::default(),
        max_message_ms: 0.0,
        max_frame_ms: 0.0,
        turn: FrameTurn::default(),
        last_input_ms: 0.0,
        dragging: false,
        narrow: is_narrow(&window),
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
    let workers = page.borrow().ctl.workers();
    for w in 0..workers {
        let worker = match Worker::new("./worker_loader.js") {
            Ok(worker) => worker,
            Err(_) => {
                let mut p = page.borrow_mut();
                p.ctl
                    .issues
                    .push("could not start a Web Worker; the views cannot be computed".into());
                p.ctl.dirty.messages = true;
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
                    let fx = p.ctl.worker_message(w, &text, t);
                    let took = now(&p.window) - t;
                    p.max_message_ms = p.max_message_ms.max(took);
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
                let mut p = page.borrow_mut();
                p.ctl
                    .issues
                    .push(format!("Web Worker {w} failed to load or crashed"));
                p.ctl.dirty.messages = true;
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

/// Once per animation frame (`ts`: its time stamp): apply queued input,
/// then redraw what changed.
fn frame(page: &Shared, ts: f64) {
    let t_frame = now(&page.borrow().window);
    let effects = {
        let mut p = page.borrow_mut();
        p.frame_requested = false;
        let t = now(&p.window);
        let mut fx = Vec::new();
        let pending = std::mem::take(&mut p.pending);
        for (key, value) in pending {
            match p.ctl.set_key(&key, &value, t) {
                Ok(more) => {
                    fx.extend(more);
                    mark_invalid(&p.doc, &key, false);
                }
                Err(msg) => {
                    p.ctl.issues.retain(|i| !i.starts_with(&key));
                    p.ctl.issues.push(msg);
                    p.ctl.dirty.messages = true;
                    p.ctl.dirty.controls = true;
                    mark_invalid(&p.doc, &key, true);
                }
            }
        }
        if let Some(o) = p.pending_omega.take() {
            fx.extend(p.ctl.select_omega(o, t));
        }
        fx
    };
    run_effects(page, effects);
    let mut p = page.borrow_mut();
    draw_dirty(page, &mut p, ts);
    let took = now(&p.window) - t_frame;
    p.max_frame_ms = p.max_frame_ms.max(took);
}

fn mark_invalid(doc: &Document, key: &str, invalid: bool) {
    if let Some(e) = doc.get_element_by_id(&format!("control-{key}")) {
        check(e.class_list().toggle_with_force("invalid", invalid));
    }
}

fn draw_dirty(page: &Shared, p: &mut Page, ts: f64) {
    let t0 = now(&p.window);
    let d = std::mem::take(&mut p.ctl.dirty);
    p.redraw.mark(&d);
    // The canvases first, the page's text after: plotters measures legend
    // text in the page (a span it adds and removes), which lays out the
    // whole page again whenever text changed since the last measure.
    let mut writes = Vec::new();
    let order = if p.turn.views_draw(ts) {
        DRAW_ORDER.as_slice()
    } else {
        &[]
    };
    for &v in order {
        let start = now(&p.window);
        match p.redraw.decide(v, t0, start, Some(p.ctl.view_status(v))) {
            Decision::Stop => break,
            Decision::Skip => continue,
            Decision::Draw => writes.extend(draw_view(p, v)),
        }
        let end = now(&p.window);
        p.redraw.drawn(v, start, end);
        p.turn.views_drew(ts);
    }
    for (id, attr, value) in writes {
        match attr {
            None => set_text(&p.doc, &id, &value),
            Some(name) => {
                if let Some(e) = p.doc.get_element_by_id(&id) {
                    check(e.set_attribute(name, &value));
                }
            }
        }
    }
    if d.controls {
        refresh_controls(p);
    }
    // (A plotting failure in this frame joined the messages.)
    if d.messages || std::mem::take(&mut p.ctl.dirty.messages) {
        refresh_messages(p);
    }
    if d.omega {
        set_text(&p.doc, "summary", &p.ctl.student_summary());
        set_text(&p.doc, "summary-expert", &p.ctl.summary_text());
        if let Some(e) = p.doc.get_element_by_id("canvas-anim") {
            check(e.set_attribute("aria-label", &p.ctl.anim_label()));
        }
    }
    if d.url || d.controls {
        let q = p.ctl.query();
        if q != p.last_query {
            if let Ok(h) = p.window.history() {
                check(h.replace_state_with_url(&JsValue::NULL, "", Some(&format!("?{q}"))));
            }
            p.last_query = q;
        }
        set_text(&p.doc, "cli-command", &p.ctl.cli_commands());
        refresh_ab(p);
        family::refresh_family_bar(p);
    }
    highlight_mesh(p);
    if p.redraw.pending() {
        p.frame_requested = false;
        let page2 = page.clone();
        let cb = Closure::once_into_js(move |ts: f64| frame(&page2, ts));
        p.frame_requested = p.window.request_animation_frame(cb.unchecked_ref()).is_ok();
    }
}

fn canvas(doc: &Document, view: ViewId) -> Option<HtmlCanvasElement> {
    by_id(doc, &format!("canvas-{}", view.key()))
}

/// A text (`None`) or attribute of the element with an id, to set once
/// the frame's canvases are drawn.
type DomWrite = (String, Option<&'static str>, String);

/// Draws one view on its canvas (or why it has nothing to draw); a
/// plotting failure joins the messages. Returns its note and label, for
/// the caller to set after the frame's drawing.
fn draw_view(p: &mut Page, v: ViewId) -> Vec<DomWrite> {
    let Some(cv) = canvas(&p.doc, v) else {
        return Vec::new();
    };
    // The frequency response's view model, built once for its size, note
    // and plot.
    let fr = (v == ViewId::Fr).then(|| p.ctl.fr_view());
    // The frequency response's mesh panels take a taller canvas, and so
    // does a long key under one frequency response.
    let (w, h) = screen_size(p.ctl.base_canvas_size(v), v == ViewId::Fr, p.narrow);
    let h = match (&fr, &p.ctl.panels) {
        (Some(fr), None) => plots::fr_height(fr, (w, h)),
        _ => h,
    };
    if (cv.width(), cv.height()) != (w, h) {
        cv.set_width(w);
        cv.set_height(h);
    }
    let Some(b) = canvas::Canvas::new(&cv) else {
        return Vec::new();
    };
    let root = b.into_drawing_area();
    let mut writes = Vec::new();
    let note = |text: String| (format!("note-{}", v.key()), None, text);
    if let Some(fr) = &fr {
        writes.push(note(match p.ctl.panels {
            Some(_) => crate::views::fr::fr_panels_note(fr),
            None => crate::views::fr::fr_note(fr),
        }));
    }
    if v == ViewId::Map {
        writes.push(note(crate::views::map::map_note(
            &p.ctl.map,
            p.ctl.map_status.total,
        )));
    }
    let r = match p.ctl.placeholder(v) {
        Some(message) => {
            // No plot, no frame to map clicks with (the Lyapunov curve
            // drops its frame only when switched off).
            if v == ViewId::Time || (v == ViewId::Lyap && p.ctl.lyap.id == 0) {
                p.frames[v.slot()] = None;
            }
            plots::draw_message(&root, v.spec().title, &message)
        }
        None => match v.spec().data {
            ExportKind::Fr => fr.map_or(Ok(()), |fr| draw_fr(p, &root, &fr)),
            ExportKind::Bif => draw_bif(p, &root, &cv),
            ExportKind::Omega => draw_omega_view(p, v, &root),
            ExportKind::Map => draw_map(p, &root, &cv),
            ExportKind::Lyap => draw_lyap(p, &root),
        },
    };
    if v == ViewId::Time {
        p.anim.dirty = true;
    }
    writes.push((cv.id(), Some("aria-label"), p.ctl.canvas_label(v)));
    if let Err(e) = r.map_err(|e| e.to_string()) {
        if !p.ctl.issues.contains(&e) {
            p.ctl.issues.push(e);
            p.ctl.dirty.messages = true;
        }
    }
    writes
}

fn draw_fr(p: &mut Page, root: &Area, v: &crate::views::fr::FrView) -> plots::Res<()> {
    let running = p.ctl.fr_status.running() || p.ctl.members_running(crate::protocol::JobKind::Hbm);
    let suffix = crate::views::fr::fr_caption_suffix(running, v);
    if p.ctl.panels.is_some() {
        return family::draw_fr_panels(p, root, &suffix);
    }
    p.frames[ViewId::Fr.slot()] = Some(plots::draw_fr(root, v, &suffix)?);
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

fn draw_bif(p: &mut Page, root: &Area, cv: &HtmlCanvasElement) -> plots::Res<()> {
    if p.ctl.family.is_some() {
        return family::draw_bif_family(p, root, cv);
    }
    let v = p.ctl.bif_view();
    let natural = p.ctl.view_context().natural;
    let suffix = p.ctl.bif_status.caption_suffix();
    let (frame, groups) = plots::draw_bif(root, &v, &natural, &suffix)?;
    p.frames[ViewId::Bif.slot()] = Some(frame);
    if let Some(ctx) = ctx2d(cv) {
        fill_groups(&ctx, &groups);
    }
    Ok(())
}

fn draw_map(p: &mut Page, root: &Area, cv: &HtmlCanvasElement) -> plots::Res<()> {
    let suffix = crate::views::map::map_caption_suffix(&p.ctl.map_status);
    let (f, o) = crate::plots::maps::draw_map(root, &p.ctl.map_view(), &suffix)?;
    p.frames[ViewId::Map.slot()] = Some(f);
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

fn draw_lyap(p: &mut Page, root: &Area) -> plots::Res<()> {
    let v = &p.ctl.settings.view;
    let natural = p.ctl.view_context().natural;
    let f = crate::plots::maps::draw_lyap(
        root,
        &p.ctl.lyap,
        (v.omega_from, v.omega_to),
        &natural,
        v.omega,
        &p.ctl.lyap_status.caption_suffix(),
    )?;
    p.frames[ViewId::Lyap.slot()] = Some(f);
    Ok(())
}

fn draw_omega_view(p: &mut Page, v: ViewId, root: &Area) -> plots::Res<()> {
    if p.ctl.family.is_some() && matches!(v, ViewId::Phase | ViewId::Poincare) {
        return family::draw_omega_family(p, v, root);
    }
    let Some(res) = &p.ctl.omega else {
        return Ok(());
    };
    let whole = p.ctl.settings.view.whole_clearance;
    let stale = crate::views::omega::caption_suffix(res.preview, p.ctl.omega_status.running());
    match v {
        ViewId::Phase => plots::draw_phase_with(root, res, stale, whole),
        ViewId::Poincare => plots::draw_poincare_with(root, res, stale, whole),
        ViewId::Time => {
            let f = plots::draw_time_with(root, res, stale, whole);
            p.frames[v.slot()] = f.as_ref().ok().copied();
            f.map(|_| ())
        }
        _ => plots::draw_spectrum(root, res, stale),
    }
}

fn refresh_messages(p: &Page) {
    let Some(box_) = by_id::<HtmlElement>(&p.doc, "messages") else {
        return;
    };
    let text = p.ctl.messages_text();
    box_.set_hidden(text.is_empty());
    box_.set_text_content(Some(&text));
    if let Some(note) = by_id::<HtmlElement>(&p.doc, "preset-note") {
        note.set_hidden(p.ctl.preset_note.is_none());
        note.set_text_content(p.ctl.preset_note.as_deref());
    }
}

fn refresh_ab(p: &Page) {
    let text = match p.ctl.ab_labels() {
        Some((a, b)) => format!("Comparing A ({a}) with B ({b})"),
        None => String::new(),
    };
    set_text(&p.doc, "ab-status", &text);
    if let Some(b) = by_id::<HtmlElement>(&p.doc, "clear-a") {
        b.set_hidden(p.ctl.pinned.is_none());
    }
}

fn highlight_mesh(p: &Page) {
    let selected = format!("mesh-{}", p.ctl.highlighted_mesh());
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
    let pair = p.ctl.settings.params.kind() == solver::ModelKind::GearPair;
    for (id, show) in [("schem-ravigneaux", !pair), ("schem-pair", pair)] {
        if let Some(e) = p.doc.get_element_by_id(id) {
            check(e.set_attribute("style", if show { "" } else { "display:none" }));
        }
    }
}

fn update_progress(page: &Shared) {
    let p = page.borrow();
    let t = now(&p.window);
    let mut busy = false;
    for v in ViewId::ALL {
        let prog = p.ctl.view_status(v).progress(t);
        busy |= prog.is_some();
        let Some(el) = by_id::<HtmlElement>(&p.doc, &format!("progress-{}", v.key())) else {
            continue;
        };
        match prog {
            Some((done, total)) => {
                if el.hidden() {
                    el.set_hidden(false);
                }
                let frac = if total > 0 {
                    done as f64 / total as f64
                } else {
                    0.0
                };
                if let Ok(Some(bar)) = el.query_selector(".bar") {
                    let style = format!("width:{:.1}%", 100.0 * frac);
                    if bar.get_attribute("style").as_deref() != Some(style.as_str()) {
                        check(bar.set_attribute("style", &style));
                    }
                }
                if let Ok(Some(label)) = el.query_selector(".label") {
                    set_text_of(&label, &v.progress_label(done, total));
                }
            }
            None if !el.hidden() => el.set_hidden(true),
            None => {}
        }
    }
    let status = if busy {
        "Computing in Web Workers…"
    } else {
        ""
    };
    set_text(&p.doc, "status", status);
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

/// The plots' drawing width on a phone: with the canvas at the screen's
/// width (about 360 CSS pixels), the axes' and the key's 13-pixel words
/// read at about 10 pixels rather than the 6 of the 760-pixel drawing.
const PHONE_PLOT_WIDTH: u32 = 480;

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

/// A plot canvas's size on the screen for its drawing size `(w, h)`: as
/// drawn, or on a narrow screen [`PHONE_PLOT_WIDTH`] wide and taller for
/// its width (the frequency response of one mesh 640 pixels high).
fn screen_size((w, h): (u32, u32), fr: bool, narrow: bool) -> (u32, u32) {
    match (narrow, fr && h == plots::HEIGHT) {
        (false, _) => (w, h),
        (true, true) => (PHONE_PLOT_WIDTH, 640),
        (true, false) => (PHONE_PLOT_WIDTH, h * 13 / 10),
    }
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
                let at = p.frames[ViewId::Map.slot()].and_then(|f| f.point_at(px, py));
                match at.map(|q| p.ctl.pick_map_point(q.x, q.y, t)) {
                    Some(Ok(fx)) => fx,
                    Some(Err(msg)) => {
                        set_text(&p.doc, "status", &msg);
                        Vec::new()
                    }
                    None => Vec::new(),
                }
            };
            run_effects(&page2, fx);
            request_frame(&page2);
        });
    }
    // The views with an Omega axis: a click or drag selects that Omega.
    for view in [ViewId::Fr, ViewId::Bif, ViewId::Lyap] {
        let Some(cv) = canvas(&doc, view) else {
            continue;
        };
        let pick = {
            let page = page.clone();
            let cv = cv.clone();
            move |e: &MouseEvent| {
                let x = canvas_px(&cv, e);
                let omega = {
                    let p = page.borrow();
                    p.frames[view.slot()].and_then(|f| f.x_at(x))
                };
                if let Some(o) = omega {
                    page.borrow_mut().pending_omega = Some(o);
                    request_frame(&page);
                }
            }
        };
        // Pointer events: a mouse click or drag and a finger's tap or
        // sideways drag take one path (the canvas's `touch-action: pan-y`
        // leaves vertical swipes to scroll the page).
        let down = pick.clone();
        let p2 = page.clone();
        let cv2 = cv.clone();
        listen(&cv.clone().into(), "pointerdown", move |e: PointerEvent| {
            p2.borrow_mut().dragging = true;
            // Keeps the drag's events when the finger or mouse leaves the canvas.
            let _ = cv2.set_pointer_capture(e.pointer_id());
            down(&e);
        });
        let mv = pick.clone();
        let p2 = page.clone();
        listen(&cv.clone().into(), "pointermove", move |e: PointerEvent| {
            if p2.borrow().dragging && e.buttons() & 1 == 1 {
                mv(&e);
            }
        });
        for end in ["pointerup", "pointercancel"] {
            let p2 = page.clone();
            listen(&cv.clone().into(), end, move |_e: PointerEvent| {
                p2.borrow_mut().dragging = false;
            });
        }
        // Keyboard: arrows move the selected Omega by 1 % of the range (10 % with Shift).
        let p2 = page.clone();
        listen(&cv.into(), "keydown", move |e: KeyboardEvent| {
            let dir = match e.key().as_str() {
                "ArrowLeft" | "ArrowDown" => -1.0,
                "ArrowRight" | "ArrowUp" => 1.0,
                _ => return,
            };
            e.prevent_default();
            {
                let mut p = p2.borrow_mut();
                let v = &p.ctl.settings.view;
                let step = (v.omega_to - v.omega_from) * if e.shift_key() { 0.1 } else { 0.01 };
                let o = (v.omega + dir * step).clamp(v.omega_from, v.omega_to);
                p.pending_omega = Some(o);
            }
            request_frame(&p2);
        });
    }
}

// ---------------------------------------------------------------- tests' hook

fn frame_json(f: Option<PlotFrame>) -> serde_json::Value {
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
}

/// `window.gearshockStatus()` returns the controller's status as JSON (job
/// progress and timings, the link, messages, draw counts): the browser tests
/// and the benchmark read it instead of guessing from pixels.
fn expose_status(page: &Shared) {
    let window = page.borrow().window.clone();
    let page2 = page.clone();
    let f = Closure::<dyn FnMut() -> String>::new(move || {
        let p = page2.borrow();
        let t = now(&p.window);
        let mut v = p.ctl.status(t);
        if let Some(o) = v.as_object_mut() {
            let r = &p.redraw;
            o.insert("draws".into(), serde_json::json!(r.draws));
            o.insert("last_draw_ms".into(), serde_json::json!(r.last_draw_ms));
            o.insert("max_draw_ms".into(), serde_json::json!(r.max_draw_ms));
            o.insert("max_message_ms".into(), serde_json::json!(p.max_message_ms));
            o.insert("max_frame_ms".into(), serde_json::json!(p.max_frame_ms));
            o.insert("first_draw_ms".into(), serde_json::json!(r.first_draw_ms));
            o.insert("last_input_ms".into(), serde_json::json!(p.last_input_ms));
            o.insert("now_ms".into(), serde_json::json!(t));
            for v in [ViewId::Map, ViewId::Lyap, ViewId::Bif, ViewId::Time] {
                let key = format!("{}_frame", v.key());
                o.insert(key, frame_json(p.frames[v.slot()]));
            }
            o.insert("anim".into(), p.anim.info.clone());
            let fr = p.frames[ViewId::Fr.slot()];
            let corners = fr.map(|f| {
                [
                    f.top_left.x,
                    f.top_left.y,
                    f.bottom_right.x,
                    f.bottom_right.y,
                ]
            });
            o.insert("fr_frame".into(), serde_json::json!(corners));
        }
        v.to_string()
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
