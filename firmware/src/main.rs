//! The Cortex-M4F firmware: the device loop of `softgrip::device` on an STM32F405 (QEMU's
//! `netduinoplus2`), serving the protocol over USART1, one tick per sensor frame and one
//! idle tick per tick period without one.
//!
//! - Start-up: TIM2 is set to count instructions (under `-icount shift=0`), the free stack
//!   is painted, then the loop waits for a `Configure` request, whose precomputation is
//!   counted as the start-up cost.
//! - Each sensor frame: one tick, counted in instructions and returned in the command
//!   frame (`tick_cost`) and the statistics.
//! - Silence: the loop never blocks on the USART (it reads only what has arrived), and
//!   between reads it checks TIM2 against the silence watch: every tick period with no
//!   sensor frame is one idle tick (`Device::idle_ticks_due`), so after the stale timeout
//!   the command moves to the fault target on its own. This is TIM2 polled at the loop's
//!   pace (a few hundred instructions at most between checks, far below the 1 ms tick)
//!   rather than an interrupt: the controller stays in the main loop, with no state shared
//!   with an interrupt handler and no critical section around the tick. A `Configure`'s
//!   precomputation holds the loop for its start-up cost; the missed periods are caught up
//!   after it.
//! - `Shutdown`: the firmware exits the emulator through semihosting with the requested
//!   code. A panic exits with code 101 (none is reachable by design).
//! - On a board (feature `board`, `scripts/firmware-build.sh board`): the clocks, pins and
//!   baud rate are set first (`board`), TIM2 counts core cycles at the reset clock, every
//!   command drives the actuator as TIM3's PWM duty (`pwm`, through embedded-hal's
//!   `SetDutyCycle` and the core's `PwmForce`), and `Shutdown` or a panic resets the chip
//!   instead of calling the emulator. The emulator's default build has no actuator.
//!
//! The tick's square root is the FPU's `VSQRT` (bit-identical to `libm`'s, which is
//! software here; `sqrt-check` builds a firmware that checks that and exits). Variants
//! (cargo features): `soft-sqrt` ticks with the `Libm` backend, `fast-math` with
//! micromath's square root, `precompute-f64` precomputes in f64. Build with
//! `scripts/firmware-build.sh`. `prebuilt-tables` links in tables made on the host instead
//! of precomputing them (only their configuration is then accepted). `defmt` adds the
//! core's defmt log lines with a sink logger (`defmt_sink`), to measure their cost.

#![no_std]
#![no_main]

#[cfg(feature = "board")]
mod board;
#[cfg(feature = "defmt")]
mod defmt_sink;
#[cfg(not(feature = "board"))]
mod exit;
#[cfg(not(any(feature = "fast-math", feature = "soft-sqrt")))]
mod fpu_sqrt;
mod interrupts;
#[cfg(feature = "board")]
mod pwm;
#[cfg(feature = "sqrt-check")]
mod sqrt_check;
mod stack;
mod tim2;
mod usart;

use cortex_m_rt::entry;
use softgrip::device::{Device, SilenceWatch};

/// The tables `host-sim tables --format rust` made (feature `prebuilt-tables`).
#[cfg(feature = "prebuilt-tables")]
mod prebuilt {
    include!(concat!(env!("OUT_DIR"), "/prebuilt_tables.rs"));
}

#[cfg(feature = "fast-math")]
type Math = softgrip::controller::Micromath;
#[cfg(all(feature = "soft-sqrt", not(feature = "fast-math")))]
type Math = softgrip::controller::Libm;
#[cfg(not(any(feature = "fast-math", feature = "soft-sqrt")))]
type Math = fpu_sqrt::FpuSqrt;

#[cfg(all(feature = "precompute-f64", not(feature = "prebuilt-tables")))]
type Precompute = f64;
#[cfg(not(any(feature = "precompute-f64", feature = "prebuilt-tables")))]
type Precompute = f32;

#[entry]
fn main() -> ! {
    #[cfg(feature = "sqrt-check")]
    sqrt_check::run_and_exit::<Math>();
    stack::paint();
    #[cfg(feature = "board")]
    board::init();
    let mut clock = tim2::InstructionCounter::start();
    let mut serial = usart::Usart1::init();
    // The actuator: on a board the force as TIM3's PWM duty; under QEMU's default build
    // none (the command travels back over the link).
    #[cfg(feature = "board")]
    let mut actuator = softgrip::device::PwmForce::new(pwm::Tim3Ch1::init(), pwm::FULL_SCALE_N);
    #[cfg(not(feature = "board"))]
    let mut actuator = softgrip::device::NoActuator;
    #[cfg(not(feature = "prebuilt-tables"))]
    let mut device = Device::<Math, softgrip::device::Precompute<Precompute>>::new();
    #[cfg(feature = "prebuilt-tables")]
    let mut device = Device::<Math, _>::with_source(softgrip::device::Prebuilt {
        config: prebuilt::CONFIG,
        tables: prebuilt::tables(),
    });
    device.set_stack_probe(stack::peak_bytes);
    let mut watch = SilenceWatch::new(tim2::TIMER_HZ);
    let code = loop {
        let ready = match embedded_io::ReadReady::read_ready(&mut serial) {
            Ok(ready) => ready,
            Err(never) => match never {},
        };
        if ready {
            match device.poll(&mut serial, &mut actuator, &mut clock) {
                Ok(_) => {}
                Err(never) => match never {},
            }
        }
        let now = softgrip::device::CostClock::now(&mut clock);
        device.idle_ticks_due(&mut watch, now, &mut actuator);
        if let Some(code) = device.shutdown_requested() {
            break code;
        }
    };
    usart::Usart1::drain();
    #[cfg(feature = "board")]
    {
        let _ = code;
        board::reset()
    }
    #[cfg(not(feature = "board"))]
    exit::exit(code)
}

#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    #[cfg(feature = "board")]
    board::reset();
    #[cfg(not(feature = "board"))]
    exit::exit(101)
}
