//! The animated gear set on the page: its own animation-frame loop (the
//! page core decides what each tick draws: [`Page::anim_tick`]), the
//! visibility observer of its canvases, the rasterizer of its [`Scene`]
//! and the time history's cursor.
//!
//! [`Page::anim_tick`]: crate::page::Page::anim_tick

use super::*;
use crate::page::anim::ANIM_CANVASES;
use crate::page::AnimDraw;
use crate::scene::{key_items, Item, SubPath};
use web_sys::{IntersectionObserver, IntersectionObserverEntry};

/// Tells the core whether the animation's two canvases are on screen.
pub(super) fn observe_anim_visibility(page: &Shared) {
    let page2 = page.clone();
    let cb = Closure::<dyn FnMut(js_sys::Array)>::new(move |entries: js_sys::Array| {
        let mut p = page2.borrow_mut();
        for e in entries.iter() {
            if let Ok(entry) = e.dyn_into::<IntersectionObserverEntry>() {
                let id = entry.target().id();
                p.core.anim_visible(&id, entry.is_intersecting());
            }
        }
    });
    let Ok(observer) = IntersectionObserver::new(cb.as_ref().unchecked_ref()) else {
        return;
    };
    let doc = page.borrow().doc.clone();
    for el in ANIM_CANVASES
        .iter()
        .filter_map(|id| doc.get_element_by_id(id))
    {
        observer.observe(&el);
    }
    cb.forget();
    // The observer lives as long as the page.
    std::mem::forget(observer);
}

/// The animation's own requestAnimationFrame loop: a few hundred polygon
/// vertices and a cursor line per frame, well under a millisecond to draw,
/// but two canvas updates for the browser to commit.
pub(super) fn start_anim_loop(page: &Shared) {
    let page2 = page.clone();
    let cb = Closure::once_into_js(move |ts: f64| {
        anim_tick(&page2, ts);
        start_anim_loop(&page2);
    });
    let window = page.borrow().window.clone();
    check(window.request_animation_frame(cb.unchecked_ref()));
}

fn anim_tick(page: &Shared, ts: f64) {
    let mut p = page.borrow_mut();
    match p.core.anim_tick(ts) {
        AnimDraw::Nothing => {}
        AnimDraw::Placeholder => {
            let cv = by_id::<HtmlCanvasElement>(&p.doc, "canvas-anim");
            if let Some(b) = cv.as_ref().and_then(canvas::Canvas::new) {
                p.core.draw_anim_placeholder(&b.into_drawing_area());
            }
        }
        AnimDraw::Scene => {
            draw_anim(&mut p);
            draw_time_cursor(&p);
        }
    }
}

fn trace(ctx: &CanvasRenderingContext2d, part: &SubPath) {
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
        SubPath::Rect { at, size } => ctx.rect(at.x, at.y, size.x, size.y),
    }
}

/// Rasterizes scene items on a canvas of `size` pixels.
pub(super) fn paint_items(ctx: &CanvasRenderingContext2d, items: &[Item], size: (f64, f64)) {
    ctx.set_font("12px sans-serif");
    for item in items {
        match item {
            Item::Clear(color) => {
                ctx.set_fill_style_str(color);
                ctx.fill_rect(0.0, 0.0, size.0, size.1);
            }
            Item::Erase => ctx.clear_rect(0.0, 0.0, size.0, size.1),
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
                let width = |t: &str| ctx.measure_text(t).map_or(150.0, |m| m.width());
                paint_items(ctx, &key_items(*at, entries, width), size);
            }
        }
    }
}

fn draw_anim(p: &mut Shell) {
    if super::present::draw_anim(p) {
        return;
    }
    let Some(cv) = by_id::<HtmlCanvasElement>(&p.doc, "canvas-anim") else {
        return;
    };
    let Some(ctx) = ctx2d(&cv) else { return };
    let size = (f64::from(cv.width()), f64::from(cv.height()));
    if let Some((scene, writes)) = p.core.anim_scene(size) {
        paint_items(&ctx, &scene.items, size);
        paint(p, writes);
    }
}

fn draw_time_cursor(p: &Shell) {
    let Some(cv) = by_id::<HtmlCanvasElement>(&p.doc, "canvas-time-cursor") else {
        return;
    };
    if let Some(ctx) = ctx2d(&cv) {
        let size = (f64::from(cv.width()), f64::from(cv.height()));
        paint_items(&ctx, &p.core.time_cursor(), size);
    }
}
