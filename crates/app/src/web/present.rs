//! Present mode in the browser: the keys anywhere on the page, the
//! stage's size read from its box (CSS pixels and the device's pixel
//! ratio) for the page core to fit the drawing to
//! ([`crate::page::present`]), the presented view drawn on the stage's
//! canvas, and the stage canvas's pointer: a tap or a drag picks Ω on the
//! frequency response, the bifurcation diagram and the Lyapunov exponent,
//! a click a map cell or an instant of the time history, as on the page.

use super::*;
use crate::page::present::PresentSize;

/// The stage's canvas.
const STAGE_CANVAS: &str = "canvas-present";

/// Listens to the keys (on the whole document, while presenting), the
/// window's size and the stage canvas's pointer.
pub(super) fn build(page: &Shared) {
    let (doc, window) = {
        let p = page.borrow();
        (p.doc.clone(), p.window.clone())
    };
    let p2 = page.clone();
    listen(&doc.clone().into(), "keydown", move |e: KeyboardEvent| {
        if e.ctrl_key() || e.meta_key() || e.alt_key() {
            return;
        }
        // A key on a button or a drop-down of the stage is the control's.
        let on_control = e
            .target()
            .and_then(|t| t.dyn_into::<Element>().ok())
            .is_some_and(|t| {
                matches!(t.tag_name().as_str(), "BUTTON" | "SELECT") && e.key() == " "
            });
        if on_control {
            return;
        }
        let writes = p2
            .borrow_mut()
            .core
            .present_keydown(&e.key(), e.shift_key());
        if let Some(writes) = writes {
            e.prevent_default();
            paint(&p2.borrow(), writes);
            request_frame(&p2);
        }
    });
    let p2 = page.clone();
    listen(&window.into(), "resize", move |_e: Event| {
        if p2.borrow().core.presenting() {
            request_frame(&p2);
        }
    });
    let Some(cv) = by_id::<HtmlCanvasElement>(&doc, STAGE_CANVAS) else {
        return;
    };
    for (kind, phase) in POINTER_EVENTS {
        let (p2, cv2) = (page.clone(), cv.clone());
        listen(&cv.clone().into(), kind, move |e: PointerEvent| {
            let Some((view, size)) = presented(&p2.borrow().core) else {
                return;
            };
            if !matches!(view, ViewId::Fr | ViewId::Bif | ViewId::Lyap) {
                return;
            }
            if phase == Phase::Down {
                check(cv2.set_pointer_capture(e.pointer_id()));
            }
            let at = (f64::from(e.client_x()), f64::from(e.client_y()));
            let x = stage_xy(&cv2, &e, size).0;
            let ev = PointerIn::new(phase, x, at, &e.pointer_type());
            if p2.borrow_mut().core.pointer(view, ev) {
                request_frame(&p2);
            }
        });
    }
    let (p2, cv2) = (page.clone(), cv.clone());
    listen(&cv.into(), "click", move |e: MouseEvent| {
        let fx = {
            let mut p = p2.borrow_mut();
            let Some((view, size)) = presented(&p.core) else {
                return;
            };
            let (x, y) = stage_xy(&cv2, &e, size);
            let t = now(&p.window);
            p.core.click(view, x, y, t)
        };
        run_effects(&p2, fx);
        request_frame(&p2);
    });
}

/// The presented view and the stage's sizes, while a view is presented.
fn presented(core: &Page) -> Option<(ViewId, PresentSize)> {
    Some((core.presented_view()?, core.present_size()?))
}

/// A mouse event's position in the presented drawing's pixels.
fn stage_xy(cv: &HtmlCanvasElement, e: &MouseEvent, size: PresentSize) -> (f64, f64) {
    let offset = (f64::from(e.offset_x()), f64::from(e.offset_y()));
    let css = (f64::from(cv.client_width()), f64::from(cv.client_height()));
    drawing_px(offset, css, size.drawing)
}

/// Measures the stage while presenting: the core fits the drawing to it,
/// and the canvas takes its device pixels.
pub(super) fn fit(p: &mut Shell) {
    if !p.core.presenting() {
        return;
    }
    let Some(stage) = p.doc.get_element_by_id("present-stage") else {
        return;
    };
    let css = (
        f64::from(stage.client_width()),
        f64::from(stage.client_height()),
    );
    p.core.present_fit(css, p.window.device_pixel_ratio());
    let (Some(size), Some(cv)) = (
        p.core.present_size(),
        by_id::<HtmlCanvasElement>(&p.doc, STAGE_CANVAS),
    ) else {
        return;
    };
    if (cv.width(), cv.height()) != size.canvas {
        cv.set_width(size.canvas.0);
        cv.set_height(size.canvas.1);
    }
}

/// Draws the presented view `v` on the stage; returns its writes.
pub(super) fn draw(core: &mut Page, doc: &Document, v: ViewId) -> Vec<Write> {
    let (Some(size), Some(cv)) = (
        core.present_size(),
        by_id::<HtmlCanvasElement>(doc, STAGE_CANVAS),
    ) else {
        return Vec::new();
    };
    let (fr, _) = core.prepare(v);
    let Some(b) = canvas::Canvas::scaled(&cv, Some(size.drawing), size.scale) else {
        return Vec::new();
    };
    let (mut writes, overlay) = core.draw_on(v, b, fr.as_ref());
    if let Some(ctx) = ctx2d(&cv) {
        let (w, h) = size.drawing;
        anim::paint_items(&ctx, &overlay, (f64::from(w), f64::from(h)));
    }
    core.present_drew();
    writes.push(Write::Attr {
        id: STAGE_CANVAS.into(),
        name: "aria-label",
        value: core.ctl().canvas_label(v),
    });
    writes
}

/// The gear set on the stage, when it is presented: the scene at the
/// drawing's size, through the stage's scale. Whether it drew there.
pub(super) fn draw_anim(p: &mut Shell) -> bool {
    if !p.core.presenting_anim() {
        return false;
    }
    let (Some(size), Some(cv)) = (
        p.core.present_size(),
        by_id::<HtmlCanvasElement>(&p.doc, STAGE_CANVAS),
    ) else {
        return true;
    };
    let Some(ctx) = ctx2d(&cv) else { return true };
    check(ctx.set_transform(size.scale, 0.0, 0.0, size.scale, 0.0, 0.0));
    let drawing = (f64::from(size.drawing.0), f64::from(size.drawing.1));
    if let Some((scene, writes)) = p.core.anim_scene(drawing) {
        anim::paint_items(&ctx, &scene.items, drawing);
        paint(p, writes);
        p.core.present_drew();
    }
    true
}
