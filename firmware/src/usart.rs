//! USART1 of the STM32F405 from its registers alone (QEMU's model needs no clock set-up; a
//! board's clock, pins and baud rate are `board::init`'s),
//! as an `embedded-io` byte stream. Reads block until a byte arrives, then take what is
//! already waiting (`read_ready` says whether one has); writes wait for an empty transmit
//! register.

#![allow(unsafe_code)]

use core::convert::Infallible;

const USART1: usize = 0x4001_1000;
const SR: usize = USART1;
const DR: usize = USART1 + 0x04;
const CR1: usize = USART1 + 0x0C;
const SR_RXNE: u32 = 1 << 5;
const SR_TXE: u32 = 1 << 7;
const SR_TC: u32 = 1 << 6;
const CR1_UE: u32 = 1 << 13;
const CR1_TE: u32 = 1 << 3;
const CR1_RE: u32 = 1 << 2;

fn write(addr: usize, value: u32) {
    // SAFETY: a documented, aligned USART1 register of the STM32F405.
    unsafe { core::ptr::write_volatile(addr as *mut u32, value) }
}

fn read(addr: usize) -> u32 {
    // SAFETY: as above.
    unsafe { core::ptr::read_volatile(addr as *const u32) }
}

/// USART1, enabled for transmit and receive.
pub struct Usart1;

impl Usart1 {
    /// Enables the USART.
    pub fn init() -> Self {
        write(CR1, CR1_UE | CR1_TE | CR1_RE);
        Self
    }

    /// Waits until the last byte has left.
    pub fn drain() {
        while read(SR) & SR_TC == 0 {}
    }
}

impl embedded_io::ErrorType for Usart1 {
    type Error = Infallible;
}

impl embedded_io::Read for Usart1 {
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, Infallible> {
        if buf.is_empty() {
            return Ok(0);
        }
        while read(SR) & SR_RXNE == 0 {}
        let mut n = 0;
        for slot in buf.iter_mut() {
            if read(SR) & SR_RXNE == 0 {
                break;
            }
            *slot = (read(DR) & 0xFF) as u8;
            n += 1;
        }
        Ok(n)
    }
}

impl embedded_io::ReadReady for Usart1 {
    fn read_ready(&mut self) -> Result<bool, Infallible> {
        Ok(read(SR) & SR_RXNE != 0)
    }
}

impl embedded_io::Write for Usart1 {
    fn write(&mut self, buf: &[u8]) -> Result<usize, Infallible> {
        for &b in buf {
            while read(SR) & SR_TXE == 0 {}
            write(DR, u32::from(b));
        }
        Ok(buf.len())
    }

    fn flush(&mut self) -> Result<(), Infallible> {
        Ok(())
    }
}
