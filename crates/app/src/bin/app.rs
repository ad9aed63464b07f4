//! The explorer page's main-thread entry point (built for wasm32 by Trunk).

#[cfg(target_arch = "wasm32")]
fn main() {
    app::web::start_app();
}

#[cfg(not(target_arch = "wasm32"))]
fn main() {
    println!(
        "The gearshock explorer runs in the browser: build and serve it with scripts/serve.sh."
    );
}
