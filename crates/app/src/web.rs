//! The one module that touches the browser (`wasm_bindgen`, `web_sys`): it
//! builds the control panel, runs the two Web Workers, turns DOM events into
//! [`Controller`] calls, and draws the views with `plotters-canvas`.
//!
//! Main-thread rules: input events only queue work; the queued slider
//! values, Omega selections and redraws are applied once per animation
//! frame, so a fast drag costs one job restart and one redraw per frame.
//! Text from links and workers reaches the page only through `textContent`
//! and attribute setters, never `innerHTML`.

use crate::controller::{Controller, Effect, WORKERS};
use crate::controls::{controls, field_text, shown_for, Group, Target, Widget};
use crate::gearset::{
    gauge_factor, sample_at, tooth_outline, view_transform, AnimClock, BodyKind, Contact, GearSet,
};
use crate::plots::{self, PlotFrame, PointGroup};
use crate::presets::PRESETS;
use crate::views::{self, OmegaView};
use crate::worker_core::{ready_message, WorkerCore};
use glam::DVec2;
use plotters::prelude::IntoDrawingArea;
use plotters_canvas::CanvasBackend;
use std::cell::{Cell, RefCell};
use std::rc::Rc;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{
    Blob, BlobPropertyBag, CanvasRenderingContext2d, DedicatedWorkerGlobalScope, Document, Element,
    Event, HtmlAnchorElement, HtmlCanvasElement, HtmlElement, HtmlInputElement, HtmlSelectElement,
    IntersectionObserver, IntersectionObserverEntry, KeyboardEvent, MessageChannel, MessageEvent,
    MouseEvent, Url, Window, Worker,
};

// ---------------------------------------------------------------- worker

/// A worker's time slice (ms) before it yields to its event loop.
const SLICE_MS: f64 = 25.0;
/// The pause (ms) after `PAUSE_EVERY_MS` of work: see `start_worker`.
const SLICE_PAUSE_MS: i32 = 3;
/// Work (ms) between two pauses.
const PAUSE_EVERY_MS: f64 = 100.0;

/// Runs a Web Worker: posts "ready", then serves jobs in bounded chunks,
/// yielding to the event loop so that newer jobs and cancels arrive:
/// through a `MessageChannel` (which, unlike `setTimeout`, is not clamped)
/// after a slice, through a `SLICE_PAUSE_MS` timer once `PAUSE_EVERY_MS`
/// of work have passed since the last pause, to leave the page's main thread
/// room on two cores.
pub fn start_worker() {
    let scope: DedicatedWorkerGlobalScope = js_sys::global().unchecked_into();
    let core = Rc::new(RefCell::new(WorkerCore::new()));
    let scheduled = Rc::new(Cell::new(false));
    let Ok(channel) = MessageChannel::new() else {
        return;
    };
    let port = channel.port2();

    let post = {
        let scope = scope.clone();
        move |msgs: Vec<crate::protocol::FromWorker>| {
            for m in msgs {
                let _ = scope.post_message(&JsValue::from_str(&crate::protocol::encode(&m)));
            }
        }
    };

    let schedule = {
        let scheduled = scheduled.clone();
        let port = port.clone();
        move || {
            if !scheduled.get() {
                scheduled.set(true);
                let _ = port.post_message(&JsValue::NULL);
            }
        }
    };

    // Every PAUSE_EVERY_MS of work the worker pauses briefly (a timer, not the
    // unclamped channel): on the 2-core target two busy workers otherwise
    // leave the page's main thread too little CPU to draw within 100 ms.
    let resume = {
        let port = port.clone();
        Closure::<dyn FnMut()>::new(move || {
            let _ = port.post_message(&JsValue::NULL);
        })
    };
    let pause = {
        let scheduled = scheduled.clone();
        let scope = scope.clone();
        move || {
            if !scheduled.get() {
                scheduled.set(true);
                let _ = scope.set_timeout_with_callback_and_timeout_and_arguments_0(
                    resume.as_ref().unchecked_ref(),
                    SLICE_PAUSE_MS,
                );
            }
        }
    };
    let busy_ms = Rc::new(Cell::new(0.0));
    let tick = {
        let core = core.clone();
        let scheduled = scheduled.clone();
        let busy_ms = busy_ms.clone();
        let post = post.clone();
        let schedule = schedule.clone();
        Closure::<dyn FnMut(MessageEvent)>::new(move |_e: MessageEvent| {
            scheduled.set(false);
            let start = js_sys::Date::now();
            // A time slice of about 25 ms, then yield; one step is one steady state.
            loop {
                let msgs = core.borrow_mut().step();
                post(msgs);
                if !core.borrow().has_work() || js_sys::Date::now() - start > SLICE_MS {
                    break;
                }
            }
            if core.borrow().has_work() {
                busy_ms.set(busy_ms.get() + js_sys::Date::now() - start);
                if busy_ms.get() > PAUSE_EVERY_MS {
                    busy_ms.set(0.0);
                    pause();
                } else {
                    schedule();
                }
            } else {
                busy_ms.set(0.0);
            }
        })
    };
    channel
        .port1()
        .set_onmessage(Some(tick.as_ref().unchecked_ref()));
    tick.forget();

    let onmessage = {
        let core = core.clone();
        Closure::<dyn FnMut(MessageEvent)>::new(move |e: MessageEvent| {
            let text = e.data().as_string().unwrap_or_default();
            let replies = core.borrow_mut().handle(&text);
            post(replies);
            if core.borrow().has_work() {
                schedule();
            }
        })
    };
    scope.set_onmessage(Some(onmessage.as_ref().unchecked_ref()));
    onmessage.forget();
    let _ = scope.post_message(&JsValue::from_str(&ready_message()));
}

// ---------------------------------------------------------------- page

/// Every view with an export bar (PNG, CSV, JSON).
const EXPORT_VIEWS: [&str; 8] = [
    "fr", "bif", "phase", "poincare", "time", "spectrum", "map", "lyap",
];
/// Canvases drawn from the controller's state: the six views, the map (6)
/// and the Lyapunov curve (7).
const DRAWN: usize = 8;

struct Page {
    ctl: Controller,
    window: Window,
    doc: Document,
    workers: Vec<Worker>,
    fr_frame: Option<PlotFrame>,
    bif_frame: Option<PlotFrame>,
    map_frame: Option<PlotFrame>,
    lyap_frame: Option<PlotFrame>,
    time_frame: Option<PlotFrame>,
    anim: AnimState,
    pending: Vec<(String, String)>,
    pending_omega: Option<f64>,
    frame_requested: bool,
    last_query: String,
    draws: [u32; DRAWN],
    last_draw_ms: [f64; DRAWN],
    max_draw_ms: [f64; DRAWN],
    /// The longest handling of one worker message (ms), for the tests.
    max_message_ms: f64,
    /// The longest animation frame's work (ms), for the tests.
    max_frame_ms: f64,
    first_draw_ms: [f64; DRAWN],
    need: [bool; DRAWN],
    last_input_ms: f64,
    dragging: bool,
}

type Shared = Rc<RefCell<Page>>;

/// The animated gear set's state on the page.
#[derive(Default)]
struct AnimState {
    clock: AnimClock,
    last_ts: Option<f64>,
    frames: u32,
    dirty: bool,
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
    let _ = target.add_event_listener_with_callback(kind, cb.as_ref().unchecked_ref());
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
    let (ctl, effects) = Controller::new(&query, t);
    let page = Rc::new(RefCell::new(Page {
        ctl,
        window: window.clone(),
        doc: doc.clone(),
        workers: Vec::new(),
        fr_frame: None,
        bif_frame: None,
        map_frame: None,
        lyap_frame: None,
        time_frame: None,
        anim: AnimState::default(),
        pending: Vec::new(),
        pending_omega: None,
        frame_requested: false,
        last_query: String::new(),
        draws: [0; DRAWN],
        last_draw_ms: [0.0; DRAWN],
        max_draw_ms: [0.0; DRAWN],
        max_message_ms: 0.0,
        max_frame_ms: 0.0,
        first_draw_ms: [0.0; DRAWN],
        need: [false; DRAWN],
        last_input_ms: 0.0,
        dragging: false,
    }));
    build_controls(&page);
    build_toolbar(&page);
    build_exports(&page);
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
    let _ = window
        .set_interval_with_callback_and_timeout_and_arguments_0(tick.as_ref().unchecked_ref(), 100);
    tick.forget();
    request_frame(&page);
}

fn start_workers(page: &Shared) {
    for w in 0..WORKERS {
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
                    let _ = w.post_message(&JsValue::from_str(&text));
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
    let cb = Closure::once_into_js(move |_t: f64| frame(&page2));
    let _ = window.request_animation_frame(cb.unchecked_ref());
}

/// Once per animation frame: apply queued input, then redraw what changed.
fn frame(page: &Shared) {
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
    draw_dirty(page, &mut p);
    let took = now(&p.window) - t_frame;
    p.max_frame_ms = p.max_frame_ms.max(took);
}

fn mark_invalid(doc: &Document, key: &str, invalid: bool) {
    if let Some(e) = doc.get_element_by_id(&format!("control-{key}")) {
        let _ = e.class_list().toggle_with_force("invalid", invalid);
    }
}

fn status_suffix(st: &crate::controller::JobStatus) -> String {
    if let Some(e) = &st.error {
        let _ = e;
        " (failed)".into()
    } else if st.running() {
        format!(" (computing {}/{})", st.done, st.total)
    } else {
        String::new()
    }
}

/// Main-thread time after which a frame starts no further view (ms): a
/// full refresh spreads over a few frames instead of blocking one. (Drawing
/// the frequency response and the phase portrait in one frame regardless
/// was tried: with both workers busy such frames reached 100 ms.)
const FRAME_BUDGET_MS: f64 = 8.0;
/// While a sweep is still running its view is redrawn at most this often (ms).
const RUNNING_REDRAW_MS: f64 = 250.0;
/// The order in which dirty views are drawn: the views a slider drag
/// watches first.
const DRAW_ORDER: [usize; DRAWN] = [0, 2, 1, 3, 4, 5, 7, 6];

fn draw_dirty(page: &Shared, p: &mut Page) {
    let t0 = now(&p.window);
    let d = p.ctl.dirty;
    p.ctl.dirty = Default::default();
    if d.controls {
        refresh_controls(p);
    }
    if d.messages {
        refresh_messages(p);
    }
    if d.fr {
        p.need[0] = true;
    }
    if d.bif {
        p.need[1] = true;
    }
    if d.omega {
        for k in 2..6 {
            p.need[k] = true;
        }
        refresh_summary(p);
    }
    if d.map {
        p.need[6] = true;
    }
    if d.lyap {
        p.need[7] = true;
    }
    for k in DRAW_ORDER {
        if !p.need[k] {
            continue;
        }
        let start = now(&p.window);
        if start - t0 > FRAME_BUDGET_MS {
            break;
        }
        let status = match k {
            0 => Some(&p.ctl.fr_status),
            1 => Some(&p.ctl.bif_status),
            6 => Some(&p.ctl.map_status),
            7 => Some(&p.ctl.lyap_status),
            _ => None,
        };
        let running = status.is_some_and(|s| s.running());
        // Progressive views: throttle redraws while points stream in, but
        // show a new job's start (the new settings) and its first points
        // at once.
        let last = p.last_draw_ms[k];
        let fresh = status
            .is_some_and(|s| s.started_ms > last || s.first_data_ms.is_some_and(|t| t > last));
        if running && !fresh && p.draws[k] > 0 && start - last < RUNNING_REDRAW_MS {
            continue;
        }
        p.need[k] = false;
        match k {
            0 => draw_fr(p),
            1 => draw_bif(p),
            6 => draw_map(p),
            7 => draw_lyap(p),
            _ => draw_omega_view(p, k - 2),
        }
        let end = now(&p.window);
        p.draws[k] += 1;
        p.last_draw_ms[k] = end;
        p.max_draw_ms[k] = p.max_draw_ms[k].max(end - start);
        if p.first_draw_ms[k] == 0.0 {
            p.first_draw_ms[k] = end;
        }
    }
    if d.url || d.controls {
        let q = p.ctl.query();
        if q != p.last_query {
            if let Ok(h) = p.window.history() {
                let _ = h.replace_state_with_url(&JsValue::NULL, "", Some(&format!("?{q}")));
            }
            p.last_query = q;
        }
        set_text(&p.doc, "cli-command", &p.ctl.cli_commands());
        refresh_ab(p);
    }
    highlight_mesh(p);
    if p.need.iter().any(|&n| n) {
        p.frame_requested = false;
        let page2 = page.clone();
        let cb = Closure::once_into_js(move |_t: f64| frame(&page2));
        p.frame_requested = p.window.request_animation_frame(cb.unchecked_ref()).is_ok();
    }
}

fn canvas(doc: &Document, view: &str) -> Option<HtmlCanvasElement> {
    by_id(doc, &format!("canvas-{view}"))
}

fn backend(doc: &Document, view: &str) -> Option<CanvasBackend> {
    CanvasBackend::with_canvas_object(canvas(doc, view)?)
}

fn report_draw_error(p: &mut Page, r: Result<(), String>) {
    if let Err(e) = r {
        if !p.ctl.issues.contains(&e) {
            p.ctl.issues.push(e);
            refresh_messages(p);
        }
    }
}

fn draw_fr(p: &mut Page) {
    let Some(b) = backend(&p.doc, "fr") else {
        return;
    };
    let root = b.into_drawing_area();
    let st = p.ctl.fr_status.clone();
    let v = p.ctl.fr_view();
    let has_data = v.branches.iter().any(|b| !b.points.is_empty()) || !v.overlay.is_empty();
    let r = match (&st.error, has_data) {
        (Some(e), false) => {
            plots::draw_message(&root, "Frequency response", &format!("Not computed: {e}"))
        }
        _ => plots::draw_fr(&root, &v, &fr_status_suffix(&st, &v)).map(|f| {
            p.fr_frame = Some(f);
        }),
    };
    let overlay = if v.overlay_source.is_some() {
        " Hollow dots: time-integration steady states (upward sweep) for comparison."
    } else {
        " A time-integration overlay can be switched on under Analysis (fr_ti_points)."
    };
    set_text(
        &p.doc,
        "note-fr",
        &format!(
            "Method: {} (mesh forces integrated in closed form between the contact switches), pseudo-arclength continuation upward in Ω with Floquet stability.{overlay}",
            v.method
        ),
    );
    report_draw_error(p, r);
}

/// The caption's status of view 1: progress over the Omega range while the
/// branch computes, and a partial branch said as such.
fn fr_status_suffix(st: &crate::controller::JobStatus, v: &views::FrView) -> String {
    if v.branch_error.is_some() {
        " (partial: solver failed)".into()
    } else if st.running() {
        format!(" (computing, {:.0}% of Ω range)", 100.0 * v.progress)
    } else {
        String::new()
    }
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

fn draw_bif(p: &mut Page) {
    let Some(cv) = canvas(&p.doc, "bif") else {
        return;
    };
    let Some(b) = CanvasBackend::with_canvas_object(cv.clone()) else {
        return;
    };
    let root = b.into_drawing_area();
    let st = p.ctl.bif_status.clone();
    let r = if let (Some(e), true) = (&st.error, p.ctl.bif.samples.is_empty()) {
        plots::draw_message(&root, "Bifurcation diagram", &format!("Not computed: {e}"))
    } else {
        let v = p.ctl.bif_view();
        let natural = p.ctl.view_context().natural;
        match plots::draw_bif(&root, &v, &natural, &status_suffix(&st)) {
            Ok((frame, groups)) => {
                p.bif_frame = Some(frame);
                if let Some(ctx) = cv
                    .get_context("2d")
                    .ok()
                    .flatten()
                    .and_then(|c| c.dyn_into::<CanvasRenderingContext2d>().ok())
                {
                    fill_groups(&ctx, &groups);
                }
                Ok(())
            }
            Err(e) => Err(e),
        }
    };
    report_draw_error(p, r);
}

fn draw_map(p: &mut Page) {
    let Some(b) = backend(&p.doc, "map") else {
        return;
    };
    let root = b.into_drawing_area();
    let st = p.ctl.map_status.clone();
    let r = if p.ctl.map.done == 0 && (st.error.is_some() || p.ctl.map.grid.is_none()) {
        let msg = st.error.as_ref().map_or_else(
            || "Waiting for the Web Workers…".to_string(),
            |e| format!("Not computed: {e}"),
        );
        plots::draw_message(&root, "Impact-regime map", &msg)
    } else {
        let suffix = if st.running() {
            format!(" (computing {}/{} cells)", st.done, st.total)
        } else {
            String::new()
        };
        crate::plots_maps::draw_map(&root, &p.ctl.map_view(), &suffix).map(|(f, o)| {
            p.map_frame = Some(f);
            if let Some(ctx) = canvas(&p.doc, "map").as_ref().and_then(ctx2d) {
                fill_map(&ctx, &f, &o);
            }
        })
    };
    let (by, not_p1, failed) = p.ctl.map.counts();
    let mut note = format!(
        "{} of {} cells: {} no impact, {} single-sided, {} double-sided, {} no contact; {} not period 1",
        p.ctl.map.done, st.total, by[0], by[1], by[2], by[3], not_p1
    );
    if failed > 0 {
        note.push_str(&format!("; {failed} failed (dark grey)"));
        if let Some(c) = p.ctl.map.first_failure() {
            let key = p.ctl.map.grid.as_ref().map_or("", |g| g.key.as_str());
            note.push_str(&format!(
                ", e.g. Omega {:.4}, {key} {:.4}: {}",
                c.omega,
                c.value,
                c.error.as_deref().unwrap_or("")
            ));
        }
    }
    note.push_str(". Click a cell to set both parameters.");
    set_text(&p.doc, "note-map", &note);
    report_draw_error(p, r);
}

/// The map's cells, one path per colour, then the period dots and the cursor.
fn fill_map(ctx: &CanvasRenderingContext2d, f: &PlotFrame, o: &crate::plots_maps::MapOverlay) {
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
        let _ = ctx.arc(d[0], d[1], o.dot_radius, 0.0, std::f64::consts::TAU);
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

fn draw_lyap(p: &mut Page) {
    let Some(b) = backend(&p.doc, "lyap") else {
        return;
    };
    let root = b.into_drawing_area();
    let st = p.ctl.lyap_status.clone();
    let v = &p.ctl.settings.view;
    let r = if p.ctl.lyap.id == 0 {
        p.lyap_frame = None;
        plots::draw_message(
            &root,
            "Largest Lyapunov exponent",
            "Off: set Lyapunov Ω points above 0 (Regime map and Lyapunov exponent).",
        )
    } else if let (Some(e), true) = (&st.error, p.ctl.lyap.points.is_empty()) {
        plots::draw_message(
            &root,
            "Largest Lyapunov exponent",
            &format!("Not computed: {e}"),
        )
    } else {
        let natural = p.ctl.view_context().natural;
        crate::plots_maps::draw_lyap(
            &root,
            &p.ctl.lyap,
            (v.omega_from, v.omega_to),
            &natural,
            v.omega,
            &status_suffix(&st),
        )
        .map(|f| {
            p.lyap_frame = Some(f);
        })
    };
    report_draw_error(p, r);
}

fn draw_omega_view(p: &mut Page, only: usize) {
    let st = p.ctl.omega_status.clone();
    let mut time_frame = None;
    let titles = [
        "Phase portrait",
        "Poincaré section",
        "Time history",
        "Spectrum",
    ];
    for (k, view) in ["phase", "poincare", "time", "spectrum"].iter().enumerate() {
        if k != only {
            continue;
        }
        let Some(b) = backend(&p.doc, view) else {
            continue;
        };
        let root = b.into_drawing_area();
        let r = match (&p.ctl.omega, &st.error) {
            (_, Some(e)) => plots::draw_message(&root, titles[k], &format!("Not computed: {e}")),
            (Some(res), None) => {
                let stale = match (res.preview, st.running()) {
                    (true, _) => " (preview; full run computing…)",
                    (false, true) => " (updating…)",
                    (false, false) => "",
                };
                match k {
                    0 => plots::draw_phase(&root, res, stale),
                    1 => plots::draw_poincare(&root, res, stale),
                    2 => plots::draw_time(&root, res, stale).map(|f| {
                        time_frame = Some(f);
                    }),
                    _ => plots::draw_spectrum(&root, res, stale),
                }
            }
            (None, None) => plots::draw_message(
                &root,
                titles[k],
                &format!(
                    "Computing the steady state at Ω = {} in a Web Worker…",
                    p.ctl.settings.view.omega
                ),
            ),
        };
        report_draw_error(p, r);
    }
    if only == 2 {
        p.time_frame = time_frame;
        p.anim.dirty = true;
    }
}

fn refresh_summary(p: &Page) {
    let natural = p.ctl.view_context().natural;
    let text = match (&p.ctl.omega, &p.ctl.omega_status.error) {
        (_, Some(e)) => format!("Not computed: {e}"),
        (Some(r), None) => {
            let mut s = views::summary_line(r, &natural);
            if let Ok(m) = &p.ctl.model {
                if let Some(line) = views::phasing_line(m, &p.ctl.settings.params, Some(r)) {
                    s.push(' ');
                    s.push_str(&line);
                }
            }
            if p.ctl.omega_status.running() && !r.preview {
                s.push_str(" Updating…");
            }
            s
        }
        (None, None) => "Computing the steady state at the selected Omega…".into(),
    };
    let text = match &p.ctl.model {
        Ok(m) if !m.system.warnings.is_empty() => {
            format!("{text} Model warnings: {}", m.system.warnings.join("; "))
        }
        _ => text,
    };
    set_text(&p.doc, "summary", &text);
}

fn refresh_messages(p: &Page) {
    let Some(box_) = by_id::<HtmlElement>(&p.doc, "messages") else {
        return;
    };
    let issues = &p.ctl.issues;
    box_.set_hidden(issues.is_empty());
    let shown: Vec<&str> = issues.iter().take(8).map(String::as_str).collect();
    let mut text = shown.join("\n");
    if issues.len() > 8 {
        text.push_str(&format!("\n… and {} more", issues.len() - 8));
    }
    if !issues.is_empty() {
        text.push_str("\n(click to dismiss)");
    }
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
    let name = match (&p.ctl.settings.view.mesh, &p.ctl.omega) {
        (crate::settings::MeshSel::Named(n), _) => n.clone(),
        (crate::settings::MeshSel::Worst, Some(r)) => r.mesh_name.clone(),
        _ => String::new(),
    };
    if let Ok(list) = p.doc.query_selector_all("#schematic .mesh") {
        for i in 0..list.length() {
            if let Some(e) = list.get(i).and_then(|n| n.dyn_into::<Element>().ok()) {
                let on = e.id() == format!("mesh-{name}");
                let _ = e.class_list().toggle_with_force("selected", on);
            }
        }
    }
    let pair = p.ctl.settings.params.kind() == solver::ModelKind::GearPair;
    for (id, show) in [("schem-ravigneaux", !pair), ("schem-pair", pair)] {
        if let Some(e) = p.doc.get_element_by_id(id) {
            let _ = e.set_attribute("style", if show { "" } else { "display:none" });
        }
    }
}

fn update_progress(page: &Shared) {
    let p = page.borrow();
    let t = now(&p.window);
    let fr = p.ctl.fr_status.progress(t);
    let bif = p.ctl.bif_status.progress(t);
    let om = p.ctl.omega_status.progress(t);
    let map = p.ctl.map_status.progress(t);
    let lyap = p.ctl.lyap_status.progress(t);
    for (view, prog) in [
        ("fr", fr),
        ("bif", bif),
        ("map", map),
        ("lyap", lyap),
        ("phase", om),
        ("poincare", om),
        ("time", om),
        ("spectrum", om),
    ] {
        let Some(el) = by_id::<HtmlElement>(&p.doc, &format!("progress-{view}")) else {
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
                        let _ = bar.set_attribute("style", &style);
                    }
                }
                if let Ok(Some(label)) = el.query_selector(".label") {
                    let text = if view == "fr" {
                        format!("harmonic balance: {done}% of the Ω range")
                    } else if view == "bif" || view == "lyap" {
                        format!("computing {done}/{total} points")
                    } else if view == "map" {
                        format!("computing {done}/{total} cells")
                    } else {
                        "computing…".into()
                    };
                    set_text_of(&label, &text);
                }
            }
            None if !el.hidden() => el.set_hidden(true),
            None => {}
        }
    }
    let busy = [fr, bif, om, map, lyap].iter().any(Option::is_some);
    set_text(
        &p.doc,
        "status",
        if busy {
            "Computing in Web Workers…"
        } else {
            ""
        },
    );
}

// ---------------------------------------------------------------- controls

fn build_controls(page: &Shared) {
    let doc = page.borrow().doc.clone();
    let Some(panel) = doc.get_element_by_id("controls") else {
        return;
    };
    let mut advanced: Option<Element> = None;
    for group in Group::ALL {
        let Some(fs) = el(&doc, "fieldset") else {
            continue;
        };
        let container: Element = if group == Group::Advanced {
            let Some(det) = el(&doc, "details") else {
                continue;
            };
            det.set_class_name("advanced");
            if let Some(sum) = el(&doc, "summary") {
                sum.set_text_content(Some(group.title()));
                let _ = det.append_child(&sum);
            }
            let _ = det.append_child(&fs);
            let _ = panel.append_child(&det);
            advanced = Some(det);
            fs
        } else {
            if let Some(lg) = el(&doc, "legend") {
                lg.set_text_content(Some(group.title()));
                let _ = fs.append_child(&lg);
            }
            let _ = panel.append_child(&fs);
            fs
        };
        for c in controls().into_iter().filter(|c| c.group == group) {
            let Some(div) = el(&doc, "div") else { continue };
            div.set_class_name("control");
            div.set_id(&format!("control-{}", c.key));
            let _ = div.set_attribute("title", &c.tooltip);
            let _ = div.set_attribute(
                "data-applies",
                match c.applies {
                    solver::keys::Applies::Both => "both",
                    solver::keys::Applies::Ravigneaux => "ravigneaux",
                    solver::keys::Applies::GearPair => "gear-pair",
                },
            );
            let Some(label) = el(&doc, "label") else {
                continue;
            };
            label.set_text_content(Some(&c.label));
            let _ = div.append_child(&label);
            match &c.widget {
                Widget::Slider {
                    min,
                    max,
                    step,
                    field_min,
                    field_max,
                } => {
                    let _ = label.set_attribute("for", &format!("num-{}", c.key));
                    let (Some(range), Some(num), Some(unit)) =
                        (el(&doc, "input"), el(&doc, "input"), el(&doc, "span"))
                    else {
                        continue;
                    };
                    let (Ok(range), Ok(num)) = (
                        range.dyn_into::<HtmlInputElement>(),
                        num.dyn_into::<HtmlInputElement>(),
                    ) else {
                        continue;
                    };
                    range.set_type("range");
                    range.set_id(&format!("slider-{}", c.key));
                    range.set_min(&min.to_string());
                    range.set_max(&max.to_string());
                    range.set_step(&step.to_string());
                    let _ = range.set_attribute("aria-label", &format!("{} slider", c.label));
                    num.set_type("number");
                    num.set_id(&format!("num-{}", c.key));
                    num.set_min(&field_min.to_string());
                    num.set_max(&field_max.to_string());
                    num.set_step("any");
                    unit.set_class_name("unit");
                    unit.set_text_content(Some(&c.unit));
                    let _ = div.append_child(&range);
                    let _ = div.append_child(&num);
                    let _ = div.append_child(&unit);
                    let key = c.key.to_string();
                    let p2 = page.clone();
                    let num2 = num.clone();
                    listen(&range.clone().into(), "input", move |_e: Event| {
                        let v = range.value();
                        num2.set_value(&v);
                        queue_input(&p2, &key, &v);
                    });
                    let key = c.key.to_string();
                    let p2 = page.clone();
                    let num3 = num.clone();
                    listen(&num.into(), "change", move |_e: Event| {
                        queue_input(&p2, &key, &num3.value());
                    });
                }
                Widget::Select(options) => {
                    let _ = label.set_attribute("for", &format!("sel-{}", c.key));
                    let Some(sel) =
                        el(&doc, "select").and_then(|s| s.dyn_into::<HtmlSelectElement>().ok())
                    else {
                        continue;
                    };
                    sel.set_id(&format!("sel-{}", c.key));
                    for (value, text) in options {
                        add_option(&doc, &sel, value, text);
                    }
                    let _ = div.append_child(&sel);
                    let key = c.key.to_string();
                    let p2 = page.clone();
                    let sel2 = sel.clone();
                    listen(&sel.into(), "change", move |_e: Event| {
                        queue_input(&p2, &key, &sel2.value());
                    });
                }
            }
            let _ = container.append_child(&div);
        }
    }
    let _ = advanced;
}

fn add_option(doc: &Document, sel: &HtmlSelectElement, value: &str, text: &str) {
    if let Some(o) = el(doc, "option") {
        let _ = o.set_attribute("value", value);
        o.set_text_content(Some(text));
        let _ = sel.append_child(&o);
    }
}

fn queue_input(page: &Shared, key: &str, value: &str) {
    {
        let mut p = page.borrow_mut();
        p.last_input_ms = now(&p.window);
        // Coalesce: only the latest value of a key per frame.
        p.pending.retain(|(k, _)| k != key);
        p.pending.push((key.to_string(), value.to_string()));
    }
    request_frame(page);
}

fn refresh_controls(p: &Page) {
    let params = &p.ctl.settings.params;
    let model = params.kind();
    // The mesh list depends on the model.
    if let Some(sel) = by_id::<HtmlSelectElement>(&p.doc, "sel-mesh") {
        let names = p.ctl.mesh_names();
        let wanted: Vec<String> = names.iter().cloned().chain(["worst".to_string()]).collect();
        let current: Vec<String> = (0..sel.length())
            .filter_map(|i| sel.item(i))
            .filter_map(|o| o.get_attribute("value"))
            .collect();
        if current != wanted {
            sel.set_text_content(None);
            for n in &names {
                add_option(&p.doc, &sel, n, n);
            }
            add_option(&p.doc, &sel, "worst", "worst (largest dynamic factor)");
        }
    }
    for c in controls() {
        if let Some(div) = by_id::<HtmlElement>(&p.doc, &format!("control-{}", c.key)) {
            div.set_hidden(!shown_for(&c, model));
        }
        let text = match c.target {
            Target::Param => match solver::keys::get(params, c.key) {
                Some(solver::keys::Value::Num(x)) => field_text(x),
                Some(solver::keys::Value::Text(t)) => t,
                None => continue,
            },
            Target::View => match p.ctl.settings.view.get(c.key) {
                Some(t) => t,
                None => continue,
            },
        };
        match c.widget {
            Widget::Slider { .. } => {
                if let Some(n) = by_id::<HtmlInputElement>(&p.doc, &format!("num-{}", c.key)) {
                    n.set_value(&text);
                    n.set_placeholder(if text.is_empty() { "mixed" } else { "" });
                }
                if let Some(s) = by_id::<HtmlInputElement>(&p.doc, &format!("slider-{}", c.key)) {
                    if !text.is_empty() {
                        s.set_value(&text);
                    }
                }
            }
            Widget::Select(_) => {
                if let Some(s) = by_id::<HtmlSelectElement>(&p.doc, &format!("sel-{}", c.key)) {
                    s.set_value(&text);
                }
            }
        }
    }
}

fn build_toolbar(page: &Shared) {
    let doc = page.borrow().doc.clone();
    if let Some(sel) = by_id::<HtmlSelectElement>(&doc, "preset") {
        add_option(&doc, &sel, "", "Choose a preset…");
        for p in PRESETS {
            add_option(&doc, &sel, p.id, p.title);
        }
        let page2 = page.clone();
        let sel2 = sel.clone();
        listen(&sel.into(), "change", move |_e: Event| {
            let id = sel2.value();
            if id.is_empty() {
                return;
            }
            let fx = {
                let mut p = page2.borrow_mut();
                let t = now(&p.window);
                p.ctl.apply_preset(&id, t)
            };
            run_effects(&page2, fx);
            request_frame(&page2);
        });
    }
    if let Some(btn) = doc.get_element_by_id("reset") {
        let page2 = page.clone();
        listen(&btn.into(), "click", move |_e: Event| {
            let fx = {
                let mut p = page2.borrow_mut();
                let t = now(&p.window);
                p.ctl.load_query("", t)
            };
            run_effects(&page2, fx);
            request_frame(&page2);
        });
    }
    for (id, pin) in [("pin-a", true), ("clear-a", false)] {
        if let Some(btn) = doc.get_element_by_id(id) {
            let page2 = page.clone();
            listen(&btn.into(), "click", move |_e: Event| {
                let fx = {
                    let mut p = page2.borrow_mut();
                    let t = now(&p.window);
                    if pin {
                        p.ctl.pin_a(t)
                    } else {
                        p.ctl.clear_a()
                    }
                };
                run_effects(&page2, fx);
                request_frame(&page2);
            });
        }
    }
    if let Some(btn) = doc.get_element_by_id("copy-link") {
        let page2 = page.clone();
        listen(&btn.into(), "click", move |_e: Event| copy_link(&page2));
    }
    if let Some(m) = doc.get_element_by_id("messages") {
        let page2 = page.clone();
        listen(&m.into(), "click", move |_e: Event| {
            let mut p = page2.borrow_mut();
            p.ctl.clear_issues();
            refresh_messages(&p);
        });
    }
}

fn copy_link(page: &Shared) {
    let (window, doc) = {
        let p = page.borrow();
        (p.window.clone(), p.doc.clone())
    };
    let href = window.location().href().unwrap_or_default();
    let clipboard = window.navigator().clipboard();
    let ok_doc = doc.clone();
    let ok = Closure::<dyn FnMut(JsValue)>::new(move |_v: JsValue| {
        set_text(&ok_doc, "status", "Link copied to the clipboard.");
    });
    let fail_doc = doc.clone();
    let fail = Closure::<dyn FnMut(JsValue)>::new(move |_v: JsValue| {
        set_text(
            &fail_doc,
            "status",
            "Could not copy; the link is in the address bar.",
        );
    });
    let _ = clipboard.write_text(&href).then2(&ok, &fail);
    // One pair per click; small and rare, so they are leaked rather than tracked.
    ok.forget();
    fail.forget();
    if let Some(b) = doc.get_element_by_id("copy-link") {
        let _ = b.set_attribute("data-link", &href);
    }
}

// ---------------------------------------------------------------- exports

fn download_text(doc: &Document, name: &str, mime: &str, text: &str) {
    let parts = js_sys::Array::of1(&JsValue::from_str(text));
    let opts = BlobPropertyBag::new();
    opts.set_type(mime);
    let Ok(blob) = Blob::new_with_str_sequence_and_options(&parts, &opts) else {
        return;
    };
    let Ok(url) = Url::create_object_url_with_blob(&blob) else {
        return;
    };
    download_url(doc, name, &url);
}

fn download_url(doc: &Document, name: &str, url: &str) {
    let Some(a) = el(doc, "a").and_then(|a| a.dyn_into::<HtmlAnchorElement>().ok()) else {
        return;
    };
    a.set_href(url);
    a.set_download(name);
    a.click();
}

fn add_button(doc: &Document, parent: &Element, text: &str, title: &str) -> Option<Element> {
    let b = el(doc, "button")?;
    let _ = b.set_attribute("type", "button");
    let _ = b.set_attribute("title", title);
    b.set_text_content(Some(text));
    let _ = parent.append_child(&b);
    Some(b)
}

fn build_exports(page: &Shared) {
    let doc = page.borrow().doc.clone();
    for view in EXPORT_VIEWS {
        let Some(bar) = doc.get_element_by_id(&format!("exports-{view}")) else {
            continue;
        };
        if let Some(b) = add_button(&doc, &bar, "PNG", "Save this plot as a PNG image") {
            let page2 = page.clone();
            listen(&b.into(), "click", move |_e: Event| {
                let doc = page2.borrow().doc.clone();
                if let Some(cv) = canvas(&doc, view) {
                    if let Ok(url) = cv.to_data_url() {
                        download_url(&doc, &format!("gearshock-{view}.png"), &url);
                    }
                }
            });
        }
        for fmt in ["CSV", "JSON"] {
            if let Some(b) = add_button(
                &doc,
                &bar,
                fmt,
                &format!("Download the data behind this plot as {fmt}"),
            ) {
                let page2 = page.clone();
                listen(&b.into(), "click", move |_e: Event| {
                    export_view(&page2, view, fmt)
                });
            }
        }
        let cli_title = match view {
            "bif" => Some("The sweep as `gearshock bifurcation` JSON (the CLI's format)"),
            "phase" | "poincare" | "time" | "spectrum" => {
                Some("This run as `gearshock simulate` JSON (the CLI's format)")
            }
            _ => None,
        };
        if let Some(title) = cli_title {
            if let Some(b) = add_button(&doc, &bar, "CLI JSON", title) {
                let page2 = page.clone();
                listen(&b.into(), "click", move |_e: Event| {
                    export_cli(&page2, view)
                });
            }
        }
    }
    if let Some(sec) = doc.get_element_by_id("export-cli") {
        if let Some(b) = add_button(
            &doc,
            &sec,
            "Download gearshock-params.json",
            "The parameters as the CLI's --params file",
        ) {
            let page2 = page.clone();
            listen(&b.into(), "click", move |_e: Event| {
                let p = page2.borrow();
                download_text(
                    &p.doc,
                    "gearshock-params.json",
                    "application/json",
                    &p.ctl.params_json(),
                );
            });
        }
    }
}

fn export_view(page: &Shared, view: &str, fmt: &str) {
    let p = page.borrow();
    let mesh = p.ctl.mesh_file_label();
    let (text, ok) = match view {
        "fr" => {
            let v = p.ctl.fr_view();
            if fmt == "CSV" {
                (views::fr_csv(&v), true)
            } else {
                (serde_json::to_string_pretty(&v).unwrap_or_default(), true)
            }
        }
        "bif" => {
            let v = p.ctl.bif_view();
            if fmt == "CSV" {
                (views::bif_csv(&v), true)
            } else {
                (serde_json::to_string(&v).unwrap_or_default(), true)
            }
        }
        "map" if fmt == "CSV" => (crate::views::map::map_csv(&p.ctl.map), true),
        "map" => (crate::views::map::map_json(&p.ctl.map).to_string(), true),
        "lyap" if fmt == "CSV" => (crate::views::map::lyap_csv(&p.ctl.lyap), true),
        "lyap" => (crate::views::map::lyap_json(&p.ctl.lyap).to_string(), true),
        _ => {
            let which = match view {
                "phase" => OmegaView::Phase,
                "poincare" => OmegaView::Poincare,
                "time" => OmegaView::Time,
                _ => OmegaView::Spectrum,
            };
            match &p.ctl.omega {
                Some(r) if r.preview => {
                    set_text(&p.doc, "status", PREVIEW_EXPORT);
                    (String::new(), false)
                }
                Some(r) if fmt == "CSV" => (views::omega_csv(r, which), true),
                Some(r) => (views::omega_json(r, which).to_string(), true),
                None => (String::new(), false),
            }
        }
    };
    if ok {
        let (ext, mime) = if fmt == "CSV" {
            ("csv", "text/csv")
        } else {
            ("json", "application/json")
        };
        download_text(
            &p.doc,
            &format!("gearshock-{view}-{mesh}.{ext}"),
            mime,
            &text,
        );
    }
}

/// Why the selected-Omega views do not export while they show a preview.
const PREVIEW_EXPORT: &str =
    "The selected-Omega views show a preview; export once the full steady state has arrived.";

fn export_cli(page: &Shared, view: &str) {
    if view == "bif" {
        let fx = {
            let mut p = page.borrow_mut();
            match p.ctl.request_bif_export() {
                Ok(fx) => fx,
                Err(e) => {
                    set_text(&p.doc, "status", &e);
                    Vec::new()
                }
            }
        };
        run_effects(page, fx);
        return;
    }
    let p = page.borrow();
    if p.ctl.omega.as_ref().is_some_and(|r| r.preview) {
        set_text(&p.doc, "status", PREVIEW_EXPORT);
        return;
    }
    if let Some(r) = &p.ctl.omega {
        download_text(
            &p.doc,
            &format!("gearshock-simulate-{}-{}.json", r.mesh_name, r.omega),
            "application/json",
            &r.cli_json,
        );
    }
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

fn build_canvas_events(page: &Shared) {
    let doc = page.borrow().doc.clone();
    if let Some(cv) = canvas(&doc, "map") {
        let page2 = page.clone();
        let cv2 = cv.clone();
        listen(&cv.into(), "click", move |e: MouseEvent| {
            let (px, py) = canvas_xy(&cv2, &e);
            let fx = {
                let mut p = page2.borrow_mut();
                let t = now(&p.window);
                let at = p.map_frame.and_then(|f| f.point_at(px, py));
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
    for view in ["fr", "bif", "lyap"] {
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
                    let frame = match view {
                        "fr" => p.fr_frame,
                        "bif" => p.bif_frame,
                        _ => p.lyap_frame,
                    };
                    frame.and_then(|f| f.x_at(x))
                };
                if let Some(o) = omega {
                    page.borrow_mut().pending_omega = Some(o);
                    request_frame(&page);
                }
            }
        };
        let down = pick.clone();
        let p2 = page.clone();
        listen(&cv.clone().into(), "pointerdown", move |e: MouseEvent| {
            p2.borrow_mut().dragging = true;
            down(&e);
        });
        let mv = pick.clone();
        let p2 = page.clone();
        listen(&cv.clone().into(), "pointermove", move |e: MouseEvent| {
            if p2.borrow().dragging && e.buttons() & 1 == 1 {
                mv(&e);
            }
        });
        let p2 = page.clone();
        listen(&cv.clone().into(), "pointerup", move |_e: MouseEvent| {
            p2.borrow_mut().dragging = false;
        });
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

/// `window.gearshockStatus()` returns the controller's status as JSON (job
/// progress and timings, the link, messages, draw counts): the browser tests
/// and the benchmark read it instead of guessing from pixels.
fn expose_status(page: &Shared) {
    let window = page.borrow().window.clone();
    let page2 = page.clone();
    let f = Closure::<dyn FnMut() -> String>::new(move || {
        let p = page2.borrow();
        let t = now(&p.window);
        let mut v: serde_json::Value =
            serde_json::from_str(&p.ctl.status_json(t)).unwrap_or(serde_json::Value::Null);
        if let Some(o) = v.as_object_mut() {
            o.insert("draws".into(), serde_json::json!(p.draws));
            o.insert("last_draw_ms".into(), serde_json::json!(p.last_draw_ms));
            o.insert("max_draw_ms".into(), serde_json::json!(p.max_draw_ms));
            o.insert("max_message_ms".into(), serde_json::json!(p.max_message_ms));
            o.insert("max_frame_ms".into(), serde_json::json!(p.max_frame_ms));
            o.insert("first_draw_ms".into(), serde_json::json!(p.first_draw_ms));
            o.insert("last_input_ms".into(), serde_json::json!(p.last_input_ms));
            o.insert("now_ms".into(), serde_json::json!(t));
            let frame_json = |f: Option<PlotFrame>| {
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
            o.insert("map_frame".into(), frame_json(p.map_frame));
            o.insert("lyap_frame".into(), frame_json(p.lyap_frame));
            o.insert("bif_frame".into(), frame_json(p.bif_frame));
            o.insert("time_frame".into(), frame_json(p.time_frame));
            o.insert("anim".into(), p.anim.info.clone());
            o.insert(
                "fr_frame".into(),
                serde_json::json!(p.fr_frame.map(|f| [
                    f.top_left.x,
                    f.top_left.y,
                    f.bottom_right.x,
                    f.bottom_right.y
                ])),
            );
        }
        v.to_string()
    });
    let _ = js_sys::Reflect::set(&window, &JsValue::from_str("gearshockStatus"), f.as_ref());
    f.forget();
}

// ---------------------------------------------------------------- animated gear set

const ANIM_SPEEDS: [(f64, &str); 5] = [
    (0.1, "0.1 mesh periods/s"),
    (0.25, "0.25 mesh periods/s"),
    (0.5, "0.5 mesh periods/s"),
    (1.0, "1 mesh period/s"),
    (2.0, "2 mesh periods/s"),
];

fn build_anim_controls(page: &Shared) {
    let doc = page.borrow().doc.clone();
    if let Some(b) = doc.get_element_by_id("anim-play") {
        let page2 = page.clone();
        listen(&b.into(), "click", move |_e: Event| {
            let mut p = page2.borrow_mut();
            p.anim.clock.playing = !p.anim.clock.playing;
            p.anim.dirty = true;
        });
    }
    for (id, samples) in [("anim-back", -1_i64), ("anim-fwd", 1)] {
        if let Some(b) = doc.get_element_by_id(id) {
            let page2 = page.clone();
            listen(&b.into(), "click", move |_e: Event| {
                let mut p = page2.borrow_mut();
                let len = anim_len(&p);
                p.anim.clock.step(samples, len);
                p.anim.dirty = true;
            });
        }
    }
    if let Some(sel) = by_id::<HtmlSelectElement>(&doc, "anim-speed") {
        for (v, text) in ANIM_SPEEDS {
            add_option(&doc, &sel, &v.to_string(), text);
        }
        sel.set_value("0.5");
        let page2 = page.clone();
        let sel2 = sel.clone();
        listen(&sel.into(), "change", move |_e: Event| {
            if let Ok(v) = sel2.value().parse::<f64>() {
                let mut p = page2.borrow_mut();
                p.anim.clock.periods_per_s = v;
                p.anim.dirty = true;
            }
        });
    }
    // A click on the time history moves the animation to that instant.
    if let Some(cv) = canvas(&doc, "time") {
        let page2 = page.clone();
        let cv2 = cv.clone();
        listen(&cv.into(), "click", move |e: MouseEvent| {
            let (px, py) = canvas_xy(&cv2, &e);
            let mut p = page2.borrow_mut();
            let len = anim_len(&p);
            let (Some(f), Some(r)) = (p.time_frame, p.ctl.omega.as_ref()) else {
                return;
            };
            let Some(q) = f.point_at(px, py) else { return };
            let spp = f64::from(r.samples_per_period.max(1));
            let pos = (q.x * spp).round() - f64::from(r.anim.start_sample);
            p.anim.clock.playing = false;
            p.anim.clock.pos = pos.clamp(0.0, len.saturating_sub(1) as f64);
            p.anim.dirty = true;
        });
    }
}

fn anim_len(p: &Page) -> usize {
    p.ctl
        .omega
        .as_ref()
        .and_then(|r| r.anim.x_um.first())
        .map_or(0, Vec::len)
}

/// Tracks whether the animation's two canvases are on screen.
fn observe_anim_visibility(page: &Shared) {
    let page2 = page.clone();
    let cb = Closure::<dyn FnMut(js_sys::Array)>::new(move |entries: js_sys::Array| {
        let mut p = page2.borrow_mut();
        for e in entries.iter() {
            let Ok(entry) = e.dyn_into::<IntersectionObserverEntry>() else {
                continue;
            };
            let slot = match entry.target().id().as_str() {
                "canvas-anim" => 0,
                "canvas-time-cursor" => 1,
                _ => continue,
            };
            p.anim.offscreen[slot] = !entry.is_intersecting();
        }
        p.anim.dirty = true;
    });
    let Ok(observer) = IntersectionObserver::new(cb.as_ref().unchecked_ref()) else {
        return;
    };
    let doc = page.borrow().doc.clone();
    for id in ["canvas-anim", "canvas-time-cursor"] {
        if let Some(el) = doc.get_element_by_id(id) {
            observer.observe(&el);
        }
    }
    cb.forget();
    // The observer lives as long as the page.
    std::mem::forget(observer);
}

/// The animation's own requestAnimationFrame loop: a few hundred polygon
/// vertices and a cursor line per frame, well under a millisecond to draw,
/// but two canvas updates for the browser to commit; it draws only while
/// one of its canvases is in view.
fn start_anim_loop(page: &Shared) {
    type Cb = Closure<dyn FnMut(f64)>;
    let slot: Rc<RefCell<Option<Cb>>> = Rc::new(RefCell::new(None));
    let slot2 = slot.clone();
    let page2 = page.clone();
    *slot.borrow_mut() = Some(Closure::new(move |ts: f64| {
        anim_tick(&page2, ts);
        let window = page2.borrow().window.clone();
        if let Some(cb) = slot2.borrow().as_ref() {
            let _ = window.request_animation_frame(cb.as_ref().unchecked_ref());
        }
    }));
    let window = page.borrow().window.clone();
    let first = slot.borrow();
    if let Some(cb) = first.as_ref() {
        let _ = window.request_animation_frame(cb.as_ref().unchecked_ref());
    }
}

fn anim_tick(page: &Shared, ts: f64) {
    let mut p = page.borrow_mut();
    let dt = p.anim.last_ts.map_or(0.0, |t| (ts - t) / 1000.0);
    p.anim.last_ts = Some(ts);
    let len = anim_len(&p);
    let Some(spp) = p.ctl.omega.as_ref().map(|r| r.samples_per_period) else {
        return;
    };
    if len == 0 {
        return;
    }
    if p.anim.clock.pos >= len as f64 {
        p.anim.clock.pos = 0.0;
    }
    p.anim.clock.advance(dt, spp, len);
    if !(p.anim.clock.playing || p.anim.dirty) {
        return;
    }
    if p.anim.offscreen.iter().all(|&o| o) {
        // Drawn once it scrolls into view (the observer sets `dirty`).
        return;
    }
    p.anim.dirty = false;
    draw_anim(&mut p);
    draw_time_cursor(&p);
}

fn ctx2d(cv: &HtmlCanvasElement) -> Option<CanvasRenderingContext2d> {
    cv.get_context("2d")
        .ok()
        .flatten()
        .and_then(|c| c.dyn_into::<CanvasRenderingContext2d>().ok())
}

fn rgb((r, g, b): (u8, u8, u8)) -> String {
    format!("rgb({r},{g},{b})")
}

fn draw_anim(p: &mut Page) {
    let Some(cv) = canvas(&p.doc, "anim") else {
        return;
    };
    let Some(ctx) = ctx2d(&cv) else { return };
    let params = p.ctl.settings.params.clone();
    let rebuild = p.anim.set.as_ref().is_none_or(|(q, _)| *q != params);
    if rebuild {
        let meshes: Vec<(solver::params::MeshKind, usize)> = match &p.ctl.model {
            Ok(m) => m.system.meshes.iter().map(|x| (x.kind, x.planet)).collect(),
            Err(_) => Vec::new(),
        };
        p.anim.set = GearSet::new(&params, &meshes).map(|g| (params.clone(), g));
    }
    let Some((_, set)) = p.anim.set.as_ref() else {
        return;
    };
    let Some(r) = p.ctl.omega.as_ref() else {
        return;
    };
    let (w, h) = (f64::from(cv.width()), f64::from(cv.height()));
    let len = r.anim.x_um.first().map_or(0, Vec::len);
    let k = p.anim.clock.sample(len);
    let spp = f64::from(r.samples_per_period.max(1));
    // Time in mesh periods since the recording began (the time view's axis).
    let t_periods = (f64::from(r.anim.start_sample) + p.anim.clock.pos) / spp;
    let tau = t_periods;
    ctx.set_fill_style_str("#ffffff");
    ctx.fill_rect(0.0, 0.0, w, h);
    let key_h = 62.0;
    let view = view_transform(set.extent_m, (w, h - key_h));
    let scale = view.matrix2.x_axis.x;
    // Bodies: the ring, the large sun, the small sun, then the planets.
    for body in &set.bodies {
        let t = view * set.body_transform(body, tau);
        let pts = tooth_outline(body, set.module_m);
        ctx.begin_path();
        for (i, q) in pts.iter().enumerate() {
            let v = t.transform_point2(*q);
            if i == 0 {
                ctx.move_to(v.x, v.y);
            } else {
                ctx.line_to(v.x, v.y);
            }
        }
        ctx.close_path();
        let (fill, stroke) = match (body.kind, body.name.as_str()) {
            (BodyKind::Ring, _) => ("rgba(200,205,212,0.55)", "#6b7480"),
            (_, "s1") | (_, "pinion") => ("rgba(190,210,240,0.75)", "#3d5f8f"),
            (_, "s2") | (_, "gear") => ("rgba(215,200,235,0.55)", "#6a4f8f"),
            _ if body.name.starts_with('a') => ("rgba(234,241,251,0.85)", "#4b6fa5"),
            _ => ("rgba(243,238,250,0.85)", "#7d62a3"),
        };
        ctx.set_fill_style_str(fill);
        if body.kind == BodyKind::Ring {
            // The ring's body: the annulus between its teeth and its rim.
            let c = t.transform_point2(DVec2::ZERO);
            let rim = (body.pitch_radius_m + 2.2 * set.module_m) * scale;
            ctx.move_to(c.x + rim, c.y);
            let _ = ctx.arc(c.x, c.y, rim, 0.0, std::f64::consts::TAU);
            ctx.fill_with_canvas_winding_rule(web_sys::CanvasWindingRule::Evenodd);
        } else {
            ctx.fill();
        }
        ctx.set_stroke_style_str(stroke);
        ctx.set_line_width(1.0);
        ctx.stroke();
        // A radial mark so the turning shows at any tooth count.
        let c = t.transform_point2(DVec2::ZERO);
        let m = t.transform_point2(DVec2::new(body.pitch_radius_m * 0.8, 0.0));
        ctx.begin_path();
        ctx.move_to(c.x, c.y);
        ctx.line_to(m.x, m.y);
        ctx.stroke();
    }
    // The carrier: pins, arms and its circle, turning with it.
    if set.carrier_radius_m > 0.0 {
        ctx.set_stroke_style_str("rgba(90,100,115,0.9)");
        ctx.set_line_width(2.0);
        let planets: Vec<&crate::gearset::Body> = set
            .bodies
            .iter()
            .filter(|b| b.kind == BodyKind::Planet)
            .collect();
        for pair in planets.chunks(2) {
            ctx.begin_path();
            for (i, b) in pair.iter().enumerate() {
                let c = (view * set.body_transform(b, tau)).transform_point2(DVec2::ZERO);
                if i == 0 {
                    ctx.move_to(c.x, c.y);
                } else {
                    ctx.line_to(c.x, c.y);
                }
            }
            ctx.stroke();
        }
        for b in &planets {
            let c = (view * set.body_transform(b, tau)).transform_point2(DVec2::ZERO);
            ctx.begin_path();
            let _ = ctx.arc(c.x, c.y, 4.0, 0.0, std::f64::consts::TAU);
            ctx.set_fill_style_str("#5a6573");
            ctx.fill();
        }
    }
    // Body labels.
    ctx.set_font("12px sans-serif");
    ctx.set_fill_style_str("#1d232b");
    for body in &set.bodies {
        let t = view * set.body_transform(body, tau);
        let c = match body.kind {
            BodyKind::Planet => t.transform_point2(DVec2::ZERO),
            BodyKind::Ring => {
                view.transform_point2(DVec2::new(0.72 * set.extent_m, -0.72 * set.extent_m))
            }
            BodyKind::Sun => {
                let off = match body.name.as_str() {
                    "s1" => 0.0,
                    "s2" => -0.86 * body.pitch_radius_m,
                    _ => 0.0,
                };
                let base = view.transform_point2(body.centre_m);
                DVec2::new(base.x, base.y - off * scale)
            }
        };
        let _ = ctx.fill_text(&body.name, c.x - 6.0, c.y + 4.0);
    }
    // Mesh gauges and contact markers.
    let x_now = sample_at(&r.anim.x_um, k);
    let x_max = r
        .anim
        .x_um
        .iter()
        .flatten()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    let factor = gauge_factor(set.module_m, &r.anim.backlash_um, x_max);
    let mut markers = Vec::new();
    for site in &set.sites {
        let (pt, tan) = set.site_at(site, tau);
        let c = view.transform_point2(pt);
        let d = view.transform_vector2(tan).normalize_or_zero();
        let (Some(&x), Some(&b)) = (x_now.get(site.mesh), r.anim.backlash_um.get(site.mesh)) else {
            continue;
        };
        if !x.is_finite() {
            continue;
        }
        let state = Contact::of(x, b);
        let to_px = |um: f64| um * 1e-6 * factor * scale;
        // Ticks at +-b.
        ctx.set_stroke_style_str("#222");
        ctx.set_line_width(1.5);
        let n = d.perp();
        for sb in [b, -b] {
            let q = c + d * to_px(sb);
            ctx.begin_path();
            ctx.move_to(q.x - n.x * 5.0, q.y - n.y * 5.0);
            ctx.line_to(q.x + n.x * 5.0, q.y + n.y * 5.0);
            ctx.stroke();
        }
        ctx.set_stroke_style_str(&rgb(state.rgb()));
        ctx.set_line_width(3.0);
        ctx.begin_path();
        ctx.move_to(c.x, c.y);
        let e = c + d * to_px(x);
        ctx.line_to(e.x, e.y);
        ctx.stroke();
        markers.push((site, c, x, b, state));
    }
    for (_, c, _, _, state) in &markers {
        ctx.begin_path();
        let _ = ctx.arc(c.x, c.y, 6.0, 0.0, std::f64::consts::TAU);
        ctx.set_fill_style_str(&rgb(state.rgb()));
        ctx.fill();
    }
    // The key and the clock.
    let mut kx = 10.0;
    let ky = h - key_h + 14.0;
    ctx.set_font("12px sans-serif");
    for state in [Contact::Drive, Contact::Apart, Contact::Back] {
        ctx.begin_path();
        let _ = ctx.arc(kx + 6.0, ky - 4.0, 6.0, 0.0, std::f64::consts::TAU);
        ctx.set_fill_style_str(&rgb(state.rgb()));
        ctx.fill();
        ctx.set_fill_style_str("#1d232b");
        let _ = ctx.fill_text(state.label(), kx + 16.0, ky);
        let tw = ctx.measure_text(state.label()).map_or(150.0, |m| m.width());
        kx += 16.0 + tw + 18.0;
    }
    ctx.set_fill_style_str("#1d232b");
    let _ = ctx.fill_text(
        &format!(
            "t = {t_periods:.3} mesh periods (sample {} of the time history), Ω = {:.4}{}",
            r.anim.start_sample as usize + k,
            r.omega,
            if p.anim.clock.playing { "" } else { "; paused" }
        ),
        10.0,
        ky + 18.0,
    );
    let _ = ctx.fill_text(
        &format!("gauges: x = δ − e along each mesh's pitch tangent, exaggerated × {factor}; black ticks at ±b"),
        10.0,
        ky + 34.0,
    );
    p.anim.frames += 1;
    let plotted = r.mesh;
    p.anim.info = serde_json::json!({
        "frames": p.anim.frames,
        "playing": p.anim.clock.playing,
        "periods_per_s": p.anim.clock.periods_per_s,
        "sample": k,
        "history_sample": r.anim.start_sample as usize + k,
        "t_periods": t_periods,
        "factor": factor,
        "omega": r.omega,
        "plotted_mesh": plotted,
        "plotted_x_um": r.x_um.get(r.anim.start_sample as usize + k),
        "markers": markers.iter().map(|(site, c, x, b, state)| serde_json::json!({
            "mesh": site.mesh, "name": site.name, "px": [c.x, c.y], "x_um": x, "b_um": b, "state": state,
        })).collect::<Vec<_>>(),
    });
    let slow = r.mesh_freq_hz / p.anim.clock.periods_per_s;
    set_text(
        &p.doc,
        "note-anim",
        &format!(
            "Slow motion: {} mesh periods per second of {:.0} Hz, {:.0}× slower than real time. Drawn to scale from the module and tooth counts; bodies turn with the rigid-body motion (ring held), the vibration shows in the mesh gauges.",
            p.anim.clock.periods_per_s, r.mesh_freq_hz, slow
        ),
    );
    set_text(
        &p.doc,
        "anim-play",
        if p.anim.clock.playing {
            "Pause"
        } else {
            "Play"
        },
    );
}

fn draw_time_cursor(p: &Page) {
    let Some(cv) = by_id::<HtmlCanvasElement>(&p.doc, "canvas-time-cursor") else {
        return;
    };
    let Some(ctx) = ctx2d(&cv) else { return };
    ctx.clear_rect(0.0, 0.0, f64::from(cv.width()), f64::from(cv.height()));
    let (Some(f), Some(r)) = (p.time_frame, p.ctl.omega.as_ref()) else {
        return;
    };
    let spp = f64::from(r.samples_per_period.max(1));
    let t = (f64::from(r.anim.start_sample) + p.anim.clock.pos.floor()) / spp;
    let x = f.to_px(t, f.y_range.0).x;
    ctx.set_stroke_style_str("rgba(220,20,60,0.9)");
    ctx.set_line_width(2.0);
    ctx.begin_path();
    ctx.move_to(x, f.top_left.y);
    ctx.line_to(x, f.bottom_right.y);
    ctx.stroke();
}
