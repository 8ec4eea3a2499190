//! The serial protocol between a host and the device running the controller.
//!
//! `no_std`, heap-free, shared by the firmware and the host tools: the host sends
//! [`Request`]s, the device answers each with one [`Reply`].
//!
//! # Frame layout
//!
//! Each message travels as one frame:
//!
//! ```text
//! P = postcard(message)                      1 ..= MAX_MESSAGE_LEN (176) bytes
//! C = CRC-32/ISCSI(P), little-endian         4 bytes
//! frame = COBS(P ‖ C) ‖ 0x00                 len(P) + 6 ..= MAX_FRAME_LEN (182) bytes
//! ```
//!
//! * `P` is the [postcard 1.x wire format](https://postcard.jamesmunns.com/wire-format):
//!   enum discriminants, integers wider than a byte and string lengths as LEB128-style
//!   varints (7 bits per byte, low first); `f32`/`f64` as their IEEE-754 bits in
//!   little-endian order (so NaN and infinities pass bit for bit); `bool` as `0x00`/`0x01`;
//!   `Option` and `Result` as a tag byte then the value; arrays as their elements, with no
//!   length; structs as their fields in declaration order.
//! * `C` is CRC-32/ISCSI (Castagnoli: polynomial `0x1EDC6F41`, reflected, init and xorout
//!   `0xFFFFFFFF`) of `P` alone, least significant byte first. It was chosen over a CRC-16
//!   (about one corrupt frame in 65 536 would pass) and over the Ethernet CRC-32 because
//!   for frames of this length (up to 180 bytes, 1440 bits) the Castagnoli polynomial
//!   still detects every error of up to 5 flipped bits (Hamming distance 6), where the
//!   Ethernet polynomial guarantees only 4.
//! * COBS (consistent overhead byte stuffing) with `0x00` as the sentinel: the block
//!   contains no `0x00`, and is one byte longer than `P ‖ C` (which is at most 180 bytes,
//!   below COBS's 254-byte run). A single `0x00` ends the frame.
//!
//! The longest frame is [`MAX_FRAME_LEN`] = 182 bytes (`Request::Configure` with a skew,
//! 176 + 4 + 1 + 1; both lengths follow the configuration's fields, `WireMaxLen`, and
//! are today's); [`encode`] never needs a bigger buffer, and a
//! [`DefaultFrameDecoder`] holds any frame. For example `Request::GetStats` (`P` =
//! `03`, `C` = `a5 a0 2d 41`) travels as the seven bytes
//! `06 03 a5 a0 2d 41 00`.
//!
//! A lone `0x00` (an empty frame) is ignored by the receiver: a sender may prefix its
//! first frame with one to end any noise already on the line.
//!
//! # Session
//!
//! The host opens with [`Request::Hello`]; the device answers [`Reply::Hello`] with its
//! [`PROTOCOL_VERSION`], [`SCHEMA_KEY`] and [`MAX_FRAME_LEN`], and the host stops if
//! the version or the schema key differs from its own. Then [`Request::Configure`] (answered by
//! [`Reply::Configured`]), then a stream of [`Request::Sensor`], each answered by a
//! [`Reply::Command`] (or [`Reply::NotConfigured`] until a configuration was accepted).
//!
//! # Reading
//!
//! [`FrameDecoder`] takes the bytes as they come, in reads of any size; frames may be
//! split across reads or several may share one. With a read function shaped like
//! `embedded_io::Read::read`:
//!
//! ```
//! use softgrip::protocol::{encode, DefaultFrameDecoder, Reply, Request, MAX_FRAME_LEN};
//!
//! fn serve<E>(
//!     mut read: impl FnMut(&mut [u8]) -> Result<usize, E>,
//!     mut write_all: impl FnMut(&[u8]) -> Result<(), E>,
//!     mut handle: impl FnMut(Request) -> Reply,
//! ) -> Result<(), E> {
//!     let mut decoder = DefaultFrameDecoder::new();
//!     let mut rx = [0u8; 64];
//!     let mut tx = [0u8; MAX_FRAME_LEN];
//!     loop {
//!         let n = read(&mut rx)?;
//!         if n == 0 {
//!             return Ok(()); // end of stream
//!         }
//!         for request in decoder.frames::<Request>(rx.get(..n).unwrap_or_default()) {
//!             // Dropped frames are already counted in `decoder.counters()`.
//!             let Ok(request) = request else { continue };
//!             if let Ok(len) = encode(&handle(request), &mut tx) {
//!                 write_all(tx.get(..len).unwrap_or_default())?;
//!             }
//!         }
//!     }
//! }
//!
//! // A host's bytes, arriving in two reads that split the second frame.
//! let mut stream = [0u8; 2 * MAX_FRAME_LEN];
//! let a = encode(&Request::hello(), &mut stream).unwrap();
//! let b = encode(&Request::GetStats, &mut stream[a..]).unwrap();
//! let mut chunks = [&stream[..a + 2], &stream[a + 2..a + b]].into_iter();
//! let mut replies = 0;
//! serve::<()>(
//!     |buf| Ok(chunks.next().map_or(0, |c| { buf[..c.len()].copy_from_slice(c); c.len() })),
//!     |_frame| { replies += 1; Ok(()) },
//!     |_request| Reply::hello(),
//! )
//! .unwrap();
//! assert_eq!(replies, 2);
//! ```

mod frame;
mod message;

pub use crate::controller::SlipSignal;
pub use frame::{
    cobs_decode_in_place, cobs_encode_in_place, cobs_max_len, encode, DecoderCounters,
    DefaultFrameDecoder, FrameDecoder, FrameError, Frames, CRC, CRC_LEN, MAX_FRAME_LEN,
    MAX_MESSAGE_LEN,
};
pub use message::{
    fnv1a_32, CommandFrame, CostUnit, Pacing, Reply, Request, SensorFrame, Stats, WireConfigError,
    MAX_FRAME_LEN_U16, PROTOCOL_VERSION, SCHEMA, SCHEMA_KEY,
};
