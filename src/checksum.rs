//! The one checksum of the crate: CRC-32/ISCSI, over every frame on the link
//! ([`protocol`](crate::protocol)) and over a table blob
//! ([`controller::blob`](crate::controller::blob)). Its own module so that the controller
//! and the protocol, which both use it, do not depend on each other for it.

use crc::{Crc, NoTable};

/// CRC-32/ISCSI (Castagnoli; poly `0x1EDC6F41`, reflected, init and xorout `0xFFFFFFFF`,
/// check value `0xE3069283`).
///
/// Bitwise (`NoTable`): eight shift-and-xor steps per byte instead of a lookup in a 1 KiB
/// table, which the firmware's flash needed more
/// (docs/decisions/firmware-size-levers.md). It runs on each frame, outside the
/// controller's tick.
pub static CRC: Crc<u32, NoTable> = Crc::<u32, NoTable>::new(&crc::CRC_32_ISCSI);
