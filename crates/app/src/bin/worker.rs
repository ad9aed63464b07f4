//! The explorer's Web Worker entry point: runs solver jobs off the main thread.

#[cfg(target_arch = "wasm32")]
fn main() {
    app::web::start_worker();
}

#[cfg(not(target_arch = "wasm32"))]
fn main() {
    println!("The gearshock worker runs inside the browser page: see scripts/serve.sh.");
}
