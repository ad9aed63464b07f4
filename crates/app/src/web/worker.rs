//! The Web Worker's shell: feeds the page's messages to the job runner
//! ([`WorkerCore`]) and runs its steps in time slices ([`Slicer`] says when
//! to yield and when to pause), yielding to the worker's event loop so
//! that newer jobs and cancels arrive.

use super::check;
use crate::worker::slicer::{Next, Slicer, SLICE_PAUSE_MS};
use crate::worker::{ready_message, WorkerCore};
use std::cell::{Cell, RefCell};
use std::rc::Rc;
use wasm_bindgen::prelude::*;
use wasm_bindgen::JsCast;
use web_sys::{DedicatedWorkerGlobalScope, MessageChannel, MessageEvent};

/// Runs a Web Worker: posts "ready", then serves jobs in bounded chunks,
/// yielding to the event loop through a `MessageChannel` (which, unlike
/// `setTimeout`, is not clamped) after a slice, through a timer for a pause.
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
    let slicer = Rc::new(Cell::new(Slicer::default()));
    let tick = {
        let (core, scheduled, post) = (core.clone(), scheduled.clone(), post.clone());
        let schedule = schedule.clone();
        Closure::<dyn FnMut(MessageEvent)>::new(move |_e: MessageEvent| {
            scheduled.set(false);
            // One step is one steady state.
            let mut s = slicer.get();
            let next = s.slice(js_sys::Date::now, || {
                post(core.borrow_mut().step());
                core.borrow().has_work()
            });
            slicer.set(s);
            match next {
                Next::Idle => {}
                Next::Yield => schedule(),
                Next::Pause => pause(),
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
