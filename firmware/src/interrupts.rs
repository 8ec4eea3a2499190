//! The interrupt part of the vector table: the STM32F405/F407's 82 interrupt vectors,
//! each to cortex-m-rt's `DefaultHandler` (the firmware polls and enables no interrupt).
//! With cortex-m-rt's `device` feature the runtime leaves this table to the device;
//! without it the runtime fills 240 vectors, 632 bytes of flash more
//! (docs/decisions/firmware-size-levers.md).

/// The STM32F405/F407's interrupt vectors (RM0090, table 61: positions 0 to 81).
const STM32F405_INTERRUPTS: usize = 82;

extern "C" {
    /// cortex-m-rt's default handler (its `link.x` provides it).
    fn DefaultHandler();
}

/// Read by the hardware only: placed by cortex-m-rt's `link.x` right after the exceptions.
// SAFETY: the one definition of `__INTERRUPTS` (cortex-m-rt's `device` feature leaves it
// to the device), in the section `link.x` reserves for it; nothing in Rust reads it.
#[allow(unsafe_code)]
#[link_section = ".vector_table.interrupts"]
#[no_mangle]
#[used]
static __INTERRUPTS: [unsafe extern "C" fn(); STM32F405_INTERRUPTS] =
    [DefaultHandler; STM32F405_INTERRUPTS];
