//! The Web Worker's shell: feeds the page's messages to the job runner
//! ([`WorkerCore`]) and runs its steps in time slices ([`Slicer`] says when
//! to yield, when to pause and when a wake is already on its way),
//! yielding to the worker's event loop so that newer jobs and cancels
//! arrive.

use super::check;
use std::cell::{Cell, RefCell};
use std::rc::Rc;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{DedicatedWorkerGlobalScope, MessageChannel, MessageEvent};
use worker::slicer::{Next, Slicer, SLICE_PAUSE_MS};
use worker::{ready_message, WorkerCore};

/// Runs a Web Worker: posts "ready", then serves jobs in bounded chunks,
/// woken through a `MessageChannel` (which, unlike `setTimeout`, is not
/// clamped) after a slice, through a timer for a pause.
pub fn start_worker() {
    let scope: DedicatedWorkerGlobalScope = js_sys::global().unchecked_into();
    let core = Rc::new(RefCell::new(WorkerCore::new()));
    let slicer = Rc::new(Cell::new(Slicer::default()));
    let Ok(channel) = MessageChannel::new() else {
        return;
    };
    let port = channel.port2();

    let post = {
        let scope = scope.clone();
        move |msgs: Vec<figures::protocol::FromWorker>| {
            for m in msgs {
                check(scope.post_message(&JsValue::from_str(&figures::protocol::encode(&m))));
            }
        }
    };

    let resume = {
        let port = port.clone();
        Closure::<dyn FnMut()>::new(move || check(port.post_message(&JsValue::NULL)))
    };
    // Arranges the wake the slicer asks for.
    let wake = {
        let scope = scope.clone();
        Rc::new(move |next: Option<Next>| match next {
            Some(Next::Yield) => check(port.post_message(&JsValue::NULL)),
            Some(Next::Pause) => {
                check(scope.set_timeout_with_callback_and_timeout_and_arguments_0(
                    resume.as_ref().unchecked_ref(),
                    SLICE_PAUSE_MS,
                ))
            }
            Some(Next::Idle) | None => {}
        })
    };
    let tick = {
        let (core, slicer, post, wake) = (core.clone(), slicer.clone(), post.clone(), wake.clone());
        Closure::<dyn FnMut(MessageEvent)>::new(move |_e: MessageEvent| {
            // One step is one steady state.
            let mut s = slicer.get();
            let next = s.woke(js_sys::Date::now, || {
                post(core.borrow_mut().step());
                core.borrow().has_work()
            });
            slicer.set(s);
            wake(next);
        })
    };
    channel
        .port1()
        .set_onmessage(Some(tick.as_ref().unchecked_ref()));
    tick.forget();

    let onmessage = Closure::<dyn FnMut(MessageEvent)>::new(move |e: MessageEvent| {
        let text = e.data().as_string().unwrap_or_default();
        let replies = core.borrow_mut().handle(&text);
        post(replies);
        let mut s = slicer.get();
        let next = s.after_message(core.borrow().has_work());
        slicer.set(s);
        wake(next);
    });
    scope.set_onmessage(Some(onmessage.as_ref().unchecked_ref()));
    onmessage.forget();
    check(scope.post_message(&JsValue::from_str(&ready_message())));
}
