//! The widest vector unit the processor has, chosen at run time.
//!
//! The release build targets every x86-64 processor, so its loops use
//! 128-bit SSE2 vectors; [`dispatch`] runs a hot kernel compiled again
//! with AVX2 (256-bit) where the processor has it (pulp detects it once).
//! Every loop it wraps is elementwise (products and sums in a fixed
//! order, no fused multiply-add: Rust never contracts `a * b + c`), so
//! the wider vectors give the same bits, only sooner. On WebAssembly the
//! kernel runs as compiled (with the 128-bit SIMD the build enables).

/// Runs `kernel` with the processor's widest vector instructions enabled;
/// the kernel's body and what it inlines are compiled for them.
#[cfg(target_arch = "x86_64")]
#[inline(always)]
pub(crate) fn dispatch<R>(kernel: impl FnOnce() -> R) -> R {
    pulp::Arch::new().dispatch(kernel)
}

/// Elsewhere (WebAssembly) the kernel runs as compiled: one copy of it,
/// not one per instruction set, in the page's bundles.
#[cfg(not(target_arch = "x86_64"))]
#[inline(always)]
pub(crate) fn dispatch<R>(kernel: impl FnOnce() -> R) -> R {
    kernel()
}
