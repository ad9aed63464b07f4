//! The gear set in motion offered as an animated GIF: each instant the
//! page core plans ([`Page::gif_plan`]) drawn on a canvas of its own with
//! the page's drawing calls, its pixels read back and handed to the
//! native encoder ([`GifWriter`]), the file offered like the other
//! exports. The instants are stepped, not timed, so the file is the same
//! whatever the machine's speed; the frames are spread over animation
//! frames, a few milliseconds' work each, so the page stays responsive
//! while the GIF is made (the button is disabled meanwhile).
//!
//! [`Page::gif_plan`]: crate::page::Page::gif_plan

use super::*;
use crate::page::gif::{GifPlan, GifWriter, GIF_SIZE};
use web_sys::{Blob, BlobPropertyBag};

/// Main-thread time after which a tick starts no further frame (ms).
const TICK_MS: f64 = 30.0;

/// The button that makes the GIF.
const BUTTON: &str = "anim-gif";

/// A GIF being made.
struct Job {
    plan: GifPlan,
    name: String,
    writer: GifWriter,
    ctx: CanvasRenderingContext2d,
    next: usize,
}

/// Starts making the GIF, or says in the messages why it cannot.
pub(super) fn export(page: &Shared) {
    let job = {
        let mut p = page.borrow_mut();
        match start(&mut p) {
            Ok(job) => Some(job),
            Err(why) => {
                p.core.issue(why);
                None
            }
        }
    };
    match job {
        Some(job) => {
            button_busy(page, true);
            schedule(page, job);
        }
        None => request_frame(page),
    }
}

fn start(p: &mut Shell) -> Result<Job, String> {
    let Some((plan, name)) = p.core.gif_plan() else {
        return Err(
            "The GIF is made from the motion at the selected speed, which is still being computed; try again once it shows."
                .into(),
        );
    };
    let no_canvas = || "the browser gave no canvas to draw the GIF's frames on".to_string();
    let cv = p
        .doc
        .create_element("canvas")
        .ok()
        .and_then(|c| c.dyn_into::<HtmlCanvasElement>().ok())
        .ok_or_else(no_canvas)?;
    cv.set_width(GIF_SIZE.0);
    cv.set_height(GIF_SIZE.1);
    let ctx = ctx2d(&cv).ok_or_else(no_canvas)?;
    let writer = GifWriter::new(GIF_SIZE, plan.delay_cs).map_err(|e| e.to_string())?;
    Ok(Job {
        plan,
        name,
        writer,
        ctx,
        next: 0,
    })
}

fn button_busy(page: &Shared, busy: bool) {
    if let Some(b) = page.borrow().doc.get_element_by_id(BUTTON) {
        check(b.toggle_attribute_with_force("disabled", busy));
    }
}

fn schedule(page: &Shared, job: Job) {
    let page2 = page.clone();
    let cb = Closure::once_into_js(move |_ts: f64| tick(&page2, job));
    let window = page.borrow().window.clone();
    check(window.request_animation_frame(cb.unchecked_ref()));
}

/// Draws and encodes frames for up to [`TICK_MS`], then the next tick;
/// after the last frame, offers the file.
fn tick(page: &Shared, mut job: Job) {
    let outcome = {
        let mut p = page.borrow_mut();
        let t0 = now(&p.window);
        let mut outcome = Ok(false);
        while outcome == Ok(false) && now(&p.window) - t0 < TICK_MS {
            outcome = step(&mut p, &mut job);
        }
        outcome
    };
    match outcome {
        Ok(false) => schedule(page, job),
        Ok(true) => {
            let r = offer(&mut page.borrow_mut(), job);
            if let Err(why) = r {
                page.borrow_mut().core.issue(why);
            }
            button_busy(page, false);
            request_frame(page);
        }
        Err(why) => {
            page.borrow_mut().core.issue(why);
            button_busy(page, false);
            request_frame(page);
        }
    }
}

/// Draws and encodes the next frame; whether it was the last.
fn step(p: &mut Shell, job: &mut Job) -> Result<bool, String> {
    let Some(&pos) = job.plan.positions.get(job.next) else {
        return Ok(true);
    };
    let size = (f64::from(GIF_SIZE.0), f64::from(GIF_SIZE.1));
    let scene = p
        .core
        .gif_scene(pos, size)
        .ok_or("the gear set of this model cannot be drawn")?;
    anim::paint_items(&job.ctx, &scene.items, size);
    let pixels = job
        .ctx
        .get_image_data(0.0, 0.0, size.0, size.1)
        .map_err(|_| "the browser did not give the frame's pixels".to_string())?;
    job.writer
        .push(&pixels.data().0)
        .map_err(|e| e.to_string())?;
    job.next += 1;
    Ok(job.next == job.plan.positions.len())
}

/// The finished GIF offered as a file.
fn offer(p: &mut Shell, job: Job) -> Result<(), String> {
    let bytes = job.writer.finish().map_err(|e| e.to_string())?;
    let parts = js_sys::Array::of1(&js_sys::Uint8Array::from(bytes.as_slice()));
    let opts = BlobPropertyBag::new();
    opts.set_type("image/gif");
    let blob = Blob::new_with_u8_array_sequence_and_options(&parts, &opts)
        .map_err(|_| "the browser could not hold the GIF as a file".to_string())?;
    panel::download_blob(&p.doc, &job.name, &blob);
    p.core.gif_made(&job.plan, bytes.len());
    Ok(())
}
