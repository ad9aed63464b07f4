# Sourced by the other scripts: the PATH and settings the build needs.
# node_modules/.bin comes first so that Trunk finds binaryen's wasm-opt 132
# (Debian's wasm-opt 108 produces a page that dies); ~/.cargo/bin holds
# trunk and wasm-bindgen.
export PATH="$PWD/node_modules/.bin:$HOME/.cargo/bin:$PATH"
export TRUNK_SKIP_VERSION_CHECK=true
export CARGO_TERM_COLOR="${CARGO_TERM_COLOR:-never}"
