//! The Web Worker's shell: feeds the page's messages to the job runner
//! ([`WorkerCore`]) and runs its steps in time slices, yielding to the
//! worker's event loop so that newer jobs and cancels arrive.

use super::check;
use crate::worker::{ready_message, WorkerCore};
use std::cell::{Cell, RefCell};
use std::rc::Rc;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{DedicatedWorkerGlobalScope, MessageChannel, MessageEvent};

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
                check(scope.post_message(&JsValue::from_str(&crate::protocol::encode(&m))));
            }
        }
    };

    let schedule = {
        let scheduled = scheduled.clone();
        let port = port.clone();
        move || {
            if !scheduled.get() {
                scheduled.set(true);
                check(port.post_message(&JsValue::NULL));
            }
        }
    };

    // Every PAUSE_EVERY_MS of work the worker pauses briefly (a timer, not the
    // unclamped channel): on the 2-core target two busy workers otherwise
    // leave the page's main thread too little CPU to draw within 100 ms.
    let resume = {
        let port = port.clone();
        Closure::<dyn FnMut()>::new(move || {
            check(port.post_message(&JsValue::NULL));
        })
    };
    let pause = {
        let scheduled = scheduled.clone();
        let scope = scope.clone();
        move || {
            if !scheduled.get() {
                scheduled.set(true);
                check(scope.set_timeout_with_callback_and_timeout_and_arguments_0(
                    resume.as_ref().unchecked_ref(),
                    SLICE_PAUSE_MS,
                ));
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
    check(scope.post_message(&JsValue::from_str(&ready_message())));
}
