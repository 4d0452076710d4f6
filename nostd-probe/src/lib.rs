//! A `#![no_std]` staticlib with its own panic handler that links the core. Any `std` or
//! `alloc` in the core's dependency graph fails this build with E0152 (duplicate lang item
//! `panic_impl`) or an unresolved allocator; the test command builds it on every run.
#![cfg_attr(not(test), no_std)]

use nlsubdiv::blend::f4;

/// F4 of four points on a line, through the core: 1.5 when the core works.
#[unsafe(no_mangle)]
pub extern "C" fn nls_probe_f4_midpoint() -> f64 {
    match f4([0.0; 3], [1.0, 0.0, 0.0], [2.0, 0.0, 0.0], [3.0, 0.0, 0.0]) {
        Ok(p) => p[0],
        Err(_) => -1.0,
    }
}

#[cfg(not(test))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    loop {}
}
