//! The stack's high-water mark, by painting: at start-up every free word between the end
//! of the static data (`__sheap`, from cortex-m-rt's linker script) and a little below
//! the present stack pointer is set to a pattern; later the first word from the bottom
//! that no longer holds it marks the deepest the stack has reached.

#![allow(unsafe_code)]

const PATTERN: u32 = 0xA5A5_A5A5;
/// Left unpainted below the stack pointer at the time of painting [bytes].
const GUARD: usize = 64;

extern "C" {
    static mut __sheap: u32;
    static mut _stack_start: u32;
}

fn bounds() -> (usize, usize) {
    // Only the addresses of the linker symbols are taken.
    (
        core::ptr::addr_of!(__sheap) as usize,
        core::ptr::addr_of!(_stack_start) as usize,
    )
}

/// Paints the free stack. Call first thing in `main`.
pub fn paint() {
    let (bottom, _) = bounds();
    let sp = cortex_m::register::msp::read() as usize;
    let mut addr = bottom;
    while addr + GUARD < sp {
        // SAFETY: `[__sheap, sp − GUARD)` is RAM that neither the statics nor the live
        // stack occupy; aligned word writes.
        unsafe { core::ptr::write_volatile(addr as *mut u32, PATTERN) };
        addr += 4;
    }
}

/// The most stack used since [`paint`] \[bytes\].
pub fn peak_bytes() -> u32 {
    let (bottom, top) = bounds();
    let mut addr = bottom;
    while addr < top {
        // SAFETY: an aligned word of RAM inside the stack region.
        let word = unsafe { core::ptr::read_volatile(addr as *const u32) };
        if word != PATTERN {
            break;
        }
        addr += 4;
    }
    (top - addr) as u32
}
