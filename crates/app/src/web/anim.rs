//! The animated gear set on the page: its controls, its own animation-frame
//! loop (animating only while on screen, but drawing every new state at
//! once, so the canvas is never blank), the rasterizer of its
//! [`Scene`] and the time history's cursor.

use super::*;
use crate::scene::{anim_note, gear_scene, Item, Marker, Scene, SubPath};

const ANIM_SPEEDS: [(f64, &str); 5] = [
    (0.1, "0.1 mesh periods/s"),
    (0.25, "0.25 mesh periods/s"),
    (0.5, "0.5 mesh periods/s"),
    (1.0, "1 mesh period/s"),
    (2.0, "2 mesh periods/s"),
];

pub(super) fn build_anim_controls(page: &Shared) {
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
    if let Some(cv) = canvas(&doc, ViewId::Time) {
        let page2 = page.clone();
        let cv2 = cv.clone();
        listen(&cv.into(), "click", move |e: MouseEvent| {
            let (px, py) = canvas_xy(&cv2, &e);
            let mut p = page2.borrow_mut();
            let len = anim_len(&p);
            let (Some(f), Some(r)) = (
                p.core.frame(ViewId::Time),
                p.core.ctl().main().omega.as_ref(),
            ) else {
                return;
            };
            let Some(q) = f.point_at(px, py) else { return };
            let window = (r.anim.start_sample, r.samples_per_period);
            p.anim.clock.seek(q.x, window, len);
            p.anim.dirty = true;
        });
    }
}

pub(super) fn anim_len(p: &Shell) -> usize {
    p.core
        .ctl()
        .main()
        .omega
        .as_ref()
        .and_then(|r| r.anim.x_um.first())
        .map_or(0, Vec::len)
}

/// Tracks whether the animation's two canvases are on screen.
pub(super) fn observe_anim_visibility(page: &Shared) {
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
pub(super) fn start_anim_loop(page: &Shared) {
    type Cb = Closure<dyn FnMut(f64)>;
    let slot: Rc<RefCell<Option<Cb>>> = Rc::new(RefCell::new(None));
    let slot2 = slot.clone();
    let page2 = page.clone();
    *slot.borrow_mut() = Some(Closure::new(move |ts: f64| {
        anim_tick(&page2, ts);
        let window = page2.borrow().window.clone();
        if let Some(cb) = slot2.borrow().as_ref() {
            check(window.request_animation_frame(cb.as_ref().unchecked_ref()));
        }
    }));
    let window = page.borrow().window.clone();
    let first = slot.borrow();
    if let Some(cb) = first.as_ref() {
        check(window.request_animation_frame(cb.as_ref().unchecked_ref()));
    }
}

pub(super) fn anim_tick(page: &Shared, ts: f64) {
    let mut p = page.borrow_mut();
    let dt = p.anim.last_ts.map_or(0.0, |t| (ts - t) / 1000.0);
    p.anim.last_ts = Some(ts);
    let len = anim_len(&p);
    let spp = p
        .core
        .ctl()
        .main()
        .omega
        .as_ref()
        .map(|r| r.samples_per_period);
    let (Some(spp), true) = (spp, len > 0) else {
        // No motion yet: a drawn frame that says so, never a blank canvas.
        if !p.anim.placeholder {
            p.anim.placeholder = draw_anim_placeholder(&p);
        }
        return;
    };
    if p.anim.clock.pos >= len as f64 {
        p.anim.clock.pos = 0.0;
    }
    p.anim.clock.advance(dt, spp, len);
    // A new state (or a seek, a speed, the view scrolled in) is drawn at
    // once, in view or not, so the canvas always holds the current state (a
    // full-page screenshot shows it); the running animation only in view.
    let in_view = !p.anim.offscreen.iter().all(|&o| o);
    if !(p.anim.dirty || (p.anim.clock.playing && in_view)) {
        return;
    }
    let views_waiting = p.frame_requested && p.core.wants_frame();
    if !p.core.anim_draws(ts, views_waiting) {
        return;
    }
    p.anim.dirty = false;
    draw_anim(&mut p);
    draw_time_cursor(&p);
}

/// Fills the gear set's canvas with a frame and a line saying the motion is
/// on its way; returns whether it was drawn.
fn draw_anim_placeholder(p: &Shell) -> bool {
    let Some(cv) = by_id::<HtmlCanvasElement>(&p.doc, "canvas-anim") else {
        return false;
    };
    let Some(b) = canvas::Canvas::new(&cv) else {
        return false;
    };
    let root: Area = b.into_drawing_area();
    plots::draw_message(
        &root,
        "The gear set",
        "The gear set and its meshes appear here once the motion at the selected Ω is computed.",
    )
    .is_ok()
}

pub(super) fn trace(ctx: &CanvasRenderingContext2d, part: &SubPath) {
    match part {
        SubPath::Polygon(pts) | SubPath::Polyline(pts) => {
            for (i, q) in pts.iter().enumerate() {
                if i == 0 {
                    ctx.move_to(q.x, q.y);
                } else {
                    ctx.line_to(q.x, q.y);
                }
            }
            if matches!(part, SubPath::Polygon(_)) {
                ctx.close_path();
            }
        }
        SubPath::Circle { c, r } => {
            ctx.move_to(c.x + r, c.y);
            check(ctx.arc(c.x, c.y, *r, 0.0, std::f64::consts::TAU));
        }
    }
}

/// Rasterizes a scene on a canvas of `size` pixels.
pub(super) fn paint_scene(ctx: &CanvasRenderingContext2d, scene: &Scene, size: (f64, f64)) {
    ctx.set_font("12px sans-serif");
    for item in &scene.items {
        match item {
            Item::Clear(color) => {
                ctx.set_fill_style_str(color);
                ctx.fill_rect(0.0, 0.0, size.0, size.1);
            }
            Item::Shape {
                parts,
                fill,
                even_odd,
                stroke,
            } => {
                ctx.begin_path();
                parts.iter().for_each(|part| trace(ctx, part));
                if let Some(fill) = fill {
                    ctx.set_fill_style_str(fill);
                    if *even_odd {
                        ctx.fill_with_canvas_winding_rule(web_sys::CanvasWindingRule::Evenodd);
                    } else {
                        ctx.fill();
                    }
                }
                if let Some((color, width)) = stroke {
                    ctx.set_stroke_style_str(color);
                    ctx.set_line_width(*width);
                    ctx.stroke();
                }
            }
            Item::Text { at, text, color } => {
                ctx.set_fill_style_str(color);
                check(ctx.fill_text(text, at.x, at.y));
            }
            Item::Key { at, entries } => {
                let mut kx = at.x;
                for (color, label) in entries {
                    ctx.begin_path();
                    check(ctx.arc(kx + 6.0, at.y - 4.0, 6.0, 0.0, std::f64::consts::TAU));
                    ctx.set_fill_style_str(color);
                    ctx.fill();
                    ctx.set_fill_style_str("#1d232b");
                    check(ctx.fill_text(label, kx + 16.0, at.y));
                    let tw = ctx.measure_text(label).map_or(150.0, |m| m.width());
                    kx += 16.0 + tw + 18.0;
                }
            }
        }
    }
}

pub(super) fn draw_anim(p: &mut Shell) {
    let Some(cv) = by_id::<HtmlCanvasElement>(&p.doc, "canvas-anim") else {
        return;
    };
    let Some(ctx) = ctx2d(&cv) else { return };
    let params = p.core.ctl().settings().params.clone();
    if p.anim.set.as_ref().is_none_or(|(q, _)| *q != params) {
        let meshes: Vec<(solver::params::MeshKind, usize)> = match p.core.ctl().model() {
            Ok(m) => m.system.meshes.iter().map(|x| (x.kind, x.planet)).collect(),
            Err(_) => Vec::new(),
        };
        p.anim.set = GearSet::new(&params, &meshes).map(|g| (params.clone(), g));
    }
    let (Some((_, set)), Some(r)) = (p.anim.set.as_ref(), p.core.ctl().main().omega.as_ref())
    else {
        return;
    };
    let size = (f64::from(cv.width()), f64::from(cv.height()));
    let clock = p.anim.clock;
    let scene = gear_scene(set, r, &clock, size);
    paint_scene(&ctx, &scene, size);
    let k = r.anim.start_sample as usize + scene.sample;
    let markers: &[Marker] = &scene.markers;
    let info = serde_json::json!({
        "frames": p.anim.frames + 1,
        "playing": clock.playing,
        "periods_per_s": clock.periods_per_s,
        "sample": scene.sample,
        "window_len": r.anim.x_um.first().map_or(0, Vec::len),
        "history_sample": k,
        "t_periods": scene.t_periods,
        "factor": scene.factor,
        "omega": r.omega,
        "plotted_mesh": r.mesh,
        "plotted_x_um": r.x_um.get(k),
        "markers": markers,
    });
    let note = anim_note(r, &clock);
    p.anim.frames += 1;
    p.anim.info = info;
    set_text(&p.doc, "note-anim", &note);
    set_text(
        &p.doc,
        "anim-play",
        if clock.playing { "Pause" } else { "Play" },
    );
}

pub(super) fn draw_time_cursor(p: &Shell) {
    let Some(cv) = by_id::<HtmlCanvasElement>(&p.doc, "canvas-time-cursor") else {
        return;
    };
    let Some(ctx) = ctx2d(&cv) else { return };
    ctx.clear_rect(0.0, 0.0, f64::from(cv.width()), f64::from(cv.height()));
    let (Some(f), Some(r)) = (
        p.core.frame(ViewId::Time),
        p.core.ctl().main().omega.as_ref(),
    ) else {
        return;
    };
    let t = p
        .anim
        .clock
        .time_periods((r.anim.start_sample, r.samples_per_period));
    let x = f.to_px(t, f.y_range.0).x;
    ctx.set_stroke_style_str("rgba(220,20,60,0.9)");
    ctx.set_line_width(2.0);
    ctx.begin_path();
    ctx.move_to(x, f.top_left.y);
    ctx.line_to(x, f.bottom_right.y);
    ctx.stroke();
}
