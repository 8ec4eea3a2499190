//! The one checksum of the crate: CRC-32/ISCSI, over every frame on the link
//! ([`protocol`](crate::protocol)) and over a table blob
//! ([`controller::blob`](crate::controller::blob)). Its own module so that the controller
//! and the protocol, which both use it, do not depend on each other for it.

use crc::Crc;

/// CRC-32/ISCSI (Castagnoli; poly `0x1EDC6F41`, reflected, init and xorout `0xFFFFFFFF`,
/// check value `0xE3069283`).
///
/// A `static` so its 1 KiB lookup table exists once in flash instead of being rebuilt on
/// the stack at each use.
pub static CRC: Crc<u32> = Crc::<u32>::new(&crc::CRC_32_ISCSI);
