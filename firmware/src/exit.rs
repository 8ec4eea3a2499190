//! Leaving the emulator with an exit code: semihosting's `SYS_EXIT_EXTENDED` (0x20) with
//! the block `[ADP_Stopped_ApplicationExit, code]`, which QEMU passes through as its own
//! exit code (docs/firmware.md). On hardware without a debugger this would trap; the loop
//! after it keeps the core parked either way.

#![allow(unsafe_code)]

const SYS_EXIT_EXTENDED: usize = 0x20;
const ADP_STOPPED_APPLICATION_EXIT: usize = 0x20026;

/// Exits with `code`.
pub fn exit(code: u8) -> ! {
    let block = [ADP_STOPPED_APPLICATION_EXIT, usize::from(code)];
    // SAFETY: a semihosting call with a valid parameter block; QEMU (started with
    // `-semihosting-config enable=on`) handles it and exits.
    unsafe {
        cortex_m_semihosting::syscall(SYS_EXIT_EXTENDED, &block);
    }
    loop {
        cortex_m::asm::wfi();
    }
}
