//! What a real STM32F405/F407 needs before USART1, TIM2 and the actuator's PWM work
//! (feature `board`), from the reference manual (RM0090) alone: the clocks of GPIOA,
//! USART1, TIM2 and TIM3, PA9 (TX) and PA10 (RX) in alternate function 7, PA6 (TIM3
//! channel 1, the actuator's PWM: `pwm`) in alternate function 2, and USART1's baud rate.
//! QEMU's `netduinoplus2` needs none of it (its RCC and GPIO are unimplemented devices
//! that ignore writes), so the same build also boots there (host-sim/tests/qemu_board.rs,
//! qemu_pwm.rs).
//!
//! The clock is the one after reset: the 16 MHz HSI drives the core, AHB, APB1 and APB2
//! undivided, so USART1 runs from 16 MHz and TIM2 counts at 16 MHz, one count per core
//! cycle. A board whose start-up code raises the clock must change [`SYSCLK_HZ`].

#![allow(unsafe_code)]

/// The core clock after reset [Hz]: the HSI, with no PLL and no bus prescaler.
pub const SYSCLK_HZ: u32 = 16_000_000;
/// The link's baud rate (docs/firmware.md: 115 200 8N1, no flow control).
pub const BAUD: u32 = 115_200;

const RCC: usize = 0x4002_3800;
const RCC_AHB1ENR: usize = RCC + 0x30;
const RCC_APB1ENR: usize = RCC + 0x40;
const RCC_APB2ENR: usize = RCC + 0x44;
const GPIOAEN: u32 = 1 << 0;
const TIM2EN: u32 = 1 << 0;
const TIM3EN: u32 = 1 << 1;
const USART1EN: u32 = 1 << 4;

const GPIOA: usize = 0x4002_0000;
const GPIOA_MODER: usize = GPIOA;
const GPIOA_AFRL: usize = GPIOA + 0x20;
const GPIOA_AFRH: usize = GPIOA + 0x24;
const MODER_AF: u32 = 0b10;
const AF7: u32 = 7;
/// TIM3's alternate function on PA6.
const AF2: u32 = 2;
const PWM_PIN: u32 = 6;

const USART1_BRR: usize = 0x4001_1008;

fn write(addr: usize, value: u32) {
    // SAFETY: documented, aligned RCC, GPIOA and USART1 registers of the STM32F405.
    unsafe { core::ptr::write_volatile(addr as *mut u32, value) }
}

fn read(addr: usize) -> u32 {
    // SAFETY: as above.
    unsafe { core::ptr::read_volatile(addr as *const u32) }
}

fn set(addr: usize, bits: u32) {
    write(addr, read(addr) | bits);
}

/// USART1's `BRR` for `baud` from `clock_hz` with 16× oversampling: the divider
/// `clock / baud` in 12.4 fixed point, rounded to nearest (16 MHz, 115 200 baud: 139 =
/// 0x8B, 115 108 baud, 0.08 % slow).
pub const fn brr(clock_hz: u32, baud: u32) -> u32 {
    (clock_hz + baud / 2) / baud
}

/// Clocks on, pins to USART1 and TIM3, baud rate set. Call before
/// [`crate::usart::Usart1::init`], [`crate::tim2::InstructionCounter::start`] and
/// [`crate::pwm::Tim3Ch1::init`].
pub fn init() {
    set(RCC_AHB1ENR, GPIOAEN);
    set(RCC_APB1ENR, TIM2EN | TIM3EN);
    set(RCC_APB2ENR, USART1EN);
    // Read back once: the RM0090's errata ask for a delay of two peripheral clock cycles
    // after enabling a clock before its registers are written.
    let _ = read(RCC_APB2ENR);
    for pin in [9u32, 10] {
        let moder = read(GPIOA_MODER) & !(0b11 << (2 * pin));
        write(GPIOA_MODER, moder | MODER_AF << (2 * pin));
        let shift = 4 * (pin - 8);
        let afrh = read(GPIOA_AFRH) & !(0xF << shift);
        write(GPIOA_AFRH, afrh | AF7 << shift);
    }
    let moder = read(GPIOA_MODER) & !(0b11 << (2 * PWM_PIN));
    write(GPIOA_MODER, moder | MODER_AF << (2 * PWM_PIN));
    let afrl = read(GPIOA_AFRL) & !(0xF << (4 * PWM_PIN));
    write(GPIOA_AFRL, afrl | AF2 << (4 * PWM_PIN));
    write(USART1_BRR, brr(SYSCLK_HZ, BAUD));
}

/// Leaves the firmware on a board: a system reset (semihosting would trap without a
/// debugger). The board comes back waiting for a `Hello`, as after power-on.
pub fn reset() -> ! {
    cortex_m::peripheral::SCB::sys_reset()
}
