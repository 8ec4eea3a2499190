//! The grip actuator's drive on a board (feature `board`): TIM3 channel 1 (PA6, alternate
//! function 2) as a 20 kHz PWM output, behind embedded-hal's [`SetDutyCycle`], so that the
//! core's [`softgrip::device::PwmForce`] turns each commanded force into a duty cycle. From
//! the reference manual (RM0090, general-purpose timers TIM2 to TIM5): PWM mode 1 with the
//! compare register preloaded, so a new duty takes effect at the next period, never
//! mid-period. `board::init` enables TIM3's clock and routes PA6 to it.
//!
//! QEMU's `netduinoplus2` emulates TIM2 to TIM5 (its STM32F2xx timer model), and its
//! `CCR1` reads back what was written: `host-sim/tests/qemu_pwm.rs` reads it through
//! QEMU's monitor after every tick and checks it is the duty the commanded force asks for.

#![allow(unsafe_code)]

use core::convert::Infallible;
use embedded_hal::pwm::{ErrorType, SetDutyCycle};

const TIM3: usize = 0x4000_0400;
const CR1: usize = TIM3;
const EGR: usize = TIM3 + 0x14;
const CCMR1: usize = TIM3 + 0x18;
const CCER: usize = TIM3 + 0x20;
const PSC: usize = TIM3 + 0x28;
const ARR: usize = TIM3 + 0x2C;
const CCR1: usize = TIM3 + 0x34;

/// `CR1`: counter enabled, auto-reload preloaded.
const CR1_CEN_ARPE: u32 = 1 | 1 << 7;
/// `CCMR1`: channel 1 as output in PWM mode 1 (`OC1M = 110`: high while the count is below
/// `CCR1`), compare preload enabled (`OC1PE`).
const CCMR1_OC1_PWM1_PRELOAD: u32 = 0b110 << 4 | 1 << 3;
/// `CCER`: channel 1's output enabled, active high.
const CCER_CC1E: u32 = 1;

/// The PWM frequency [Hz]: above hearing, and within what common H-bridge and
/// current-mode motor drivers take.
pub const PWM_HZ: u32 = 20_000;
/// Timer counts in one PWM period at the board's 16 MHz reset clock: 800, so the duty has
/// 800 steps (`ARR = 799`; `CCR1 = 800` holds the output high for the whole period).
pub const PERIOD_COUNTS: u16 = (crate::board::SYSCLK_HZ / PWM_HZ) as u16;
/// The actuator's force at 100 % duty [N]: the default configuration's `n_max_n`, so the
/// whole commanded range maps onto the duty range. A board with another actuator changes
/// it.
pub const FULL_SCALE_N: f32 = 20.0;

fn write(addr: usize, value: u32) {
    // SAFETY: a documented, aligned TIM3 register of the STM32F405.
    unsafe { core::ptr::write_volatile(addr as *mut u32, value) }
}

/// TIM3 channel 1 as a PWM output.
pub struct Tim3Ch1;

impl Tim3Ch1 {
    /// No prescaler, [`PERIOD_COUNTS`] counts a period, duty 0 (output low: no force
    /// until the first command), then counting. Call after `board::init`.
    pub fn init() -> Self {
        write(PSC, 0);
        write(ARR, u32::from(PERIOD_COUNTS) - 1);
        write(CCR1, 0);
        write(CCMR1, CCMR1_OC1_PWM1_PRELOAD);
        write(CCER, CCER_CC1E);
        // Load the preloaded prescaler, period and compare value before counting.
        write(EGR, 1);
        write(CR1, CR1_CEN_ARPE);
        Self
    }
}

impl ErrorType for Tim3Ch1 {
    type Error = Infallible;
}

impl SetDutyCycle for Tim3Ch1 {
    fn max_duty_cycle(&self) -> u16 {
        PERIOD_COUNTS
    }

    fn set_duty_cycle(&mut self, duty: u16) -> Result<(), Infallible> {
        write(CCR1, u32::from(duty.min(PERIOD_COUNTS)));
        Ok(())
    }
}
