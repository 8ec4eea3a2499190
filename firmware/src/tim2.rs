//! TIM2 as an instruction counter: under QEMU's `-icount shift=0` one instruction is one
//! virtual nanosecond and TIM2 on `netduinoplus2` counts at 1 GHz, so its 32-bit count is
//! the number of retired instructions (docs/firmware.md). On a board (feature `board`) it
//! counts at the core clock after reset, 16 MHz, so its count is core cycles.

#![allow(unsafe_code)]

use softgrip::device::CostClock;
use softgrip::protocol::CostUnit;

const TIM2: usize = 0x4000_0000;
const CR1: usize = TIM2;
const EGR: usize = TIM2 + 0x14;
const CNT: usize = TIM2 + 0x24;
const PSC: usize = TIM2 + 0x28;
const ARR: usize = TIM2 + 0x2C;

fn write(addr: usize, value: u32) {
    // SAFETY: a documented, aligned TIM2 register of the STM32F405.
    unsafe { core::ptr::write_volatile(addr as *mut u32, value) }
}

fn read(addr: usize) -> u32 {
    // SAFETY: as above.
    unsafe { core::ptr::read_volatile(addr as *const u32) }
}

/// TIM2's count rate [Hz] under QEMU: 1 GHz, one count per virtual nanosecond, which
/// with `-icount shift=0` is one retired instruction. The silence watch times the tick
/// period with it.
#[cfg(not(feature = "board"))]
pub const TIMER_HZ: f64 = 1e9;
/// TIM2's count rate [Hz] on a board: the core clock after reset (APB1 undivided, so the
/// timer clock is the core clock), one count per core cycle.
#[cfg(feature = "board")]
pub const TIMER_HZ: f64 = crate::board::SYSCLK_HZ as f64;

/// What one count of TIM2 is.
#[cfg(not(feature = "board"))]
const COUNT_UNIT: CostUnit = CostUnit::Instructions;
#[cfg(feature = "board")]
const COUNT_UNIT: CostUnit = CostUnit::Cycles;

/// The running counter.
pub struct InstructionCounter;

impl InstructionCounter {
    /// Free-running, no prescaler, full 32-bit range.
    pub fn start() -> Self {
        write(PSC, 0);
        write(ARR, u32::MAX);
        write(EGR, 1);
        write(CR1, 1);
        Self
    }
}

impl CostClock for InstructionCounter {
    const UNIT: CostUnit = COUNT_UNIT;
    fn now(&mut self) -> u32 {
        read(CNT)
    }
}
