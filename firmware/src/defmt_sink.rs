//! The `defmt` build's global logger: frames encoded as a real transport would encode
//! them (defmt's rzCOBS `Encoder`), each byte written to a volatile sink that nothing
//! reads. It exists so that the `defmt` firmware links and its flash cost can be measured
//! (scripts/firmware-size.sh); a board would put defmt-rtt or a UART here instead.

#![allow(unsafe_code)]

use core::ptr::addr_of_mut;
use core::sync::atomic::{AtomicBool, Ordering};

static TAKEN: AtomicBool = AtomicBool::new(false);
static mut ENCODER: defmt::Encoder = defmt::Encoder::new();
static mut SINK: u8 = 0;

fn put(bytes: &[u8]) {
    for &b in bytes {
        // SAFETY: a byte store to a static only this logger touches, under `TAKEN`.
        unsafe { core::ptr::write_volatile(addr_of_mut!(SINK), b) };
    }
}

#[defmt::global_logger]
struct Sink;

// SAFETY: `acquire` takes the logger exclusively (the firmware has no interrupts that
// log); the other methods run only between `acquire` and `release`, as the trait asks.
unsafe impl defmt::Logger for Sink {
    fn acquire() {
        if TAKEN.swap(true, Ordering::Acquire) {
            // Re-entered: drop the frame rather than corrupt the one being written.
            return;
        }
        // SAFETY: exclusive while `TAKEN` is held.
        unsafe { (*addr_of_mut!(ENCODER)).start_frame(put) }
    }

    unsafe fn flush() {}

    unsafe fn release() {
        // SAFETY: between `acquire` and `release`.
        unsafe { (*addr_of_mut!(ENCODER)).end_frame(put) };
        TAKEN.store(false, Ordering::Release);
    }

    unsafe fn write(bytes: &[u8]) {
        // SAFETY: between `acquire` and `release`.
        unsafe { (*addr_of_mut!(ENCODER)).write(bytes, put) }
    }
}
