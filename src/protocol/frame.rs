//! The frame layer: postcard bytes + CRC-32/ISCSI, COBS-encoded, `0x00`-terminated.
//!
//! See the [module documentation](super) for the byte layout.

use core::fmt;
use core::marker::PhantomData;

pub use crate::checksum::CRC;
use crate::controller::{ControllerConfig, WireMaxLen};
use serde::de::DeserializeOwned;
use serde::Serialize;

/// Bytes of CRC after the message: the CRC-32 in little-endian order.
pub const CRC_LEN: usize = 4;

/// The longest postcard encoding of any [`Request`](super::Request) or
/// [`Reply`](super::Reply): `Request::Configure` (its variant byte) with `skew: Some(..)`
/// and the widest varints, sized from the configuration's own field list
/// ([`WireMaxLen`]: 176 bytes with today's fields), so a new field resizes it.
/// `tests/protocol.rs` checks it is met, and met exactly, by the largest values of every
/// variant, so it cannot silently go stale.
pub const MAX_MESSAGE_LEN: usize = 1 + ControllerConfig::WIRE_MAX_LEN;

/// The greatest COBS encoding of `n` bytes, without the delimiter: one code byte per
/// started run of 254 bytes, plus one (the classic `n + n/254 + 1` bound, which also
/// covers a final code byte after an exact multiple of 254).
pub const fn cobs_max_len(n: usize) -> usize {
    n + n / 254 + 1
}

/// The longest frame on the wire, delimiter included:
/// `cobs_max_len(MAX_MESSAGE_LEN + CRC_LEN) + 1` (182 bytes with today's configuration). An
/// encode buffer of this size
/// always suffices.
pub const MAX_FRAME_LEN: usize = cobs_max_len(MAX_MESSAGE_LEN + CRC_LEN) + 1;

/// A decoder sized for the longest frame this protocol produces (its COBS block of
/// `MAX_FRAME_LEN - 1` bytes).
pub type DefaultFrameDecoder = FrameDecoder<{ MAX_FRAME_LEN - 1 }>;

/// Why a frame could not be encoded or was dropped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum FrameError {
    /// Encoding: the output buffer is too small for the frame.
    BufferTooSmall,
    /// Encoding: postcard could not serialise the message.
    Serialize,
    /// Decoding: the COBS block is invalid, or decodes to fewer bytes than a CRC.
    /// Counted in `decode_errors`.
    Malformed,
    /// Decoding: the CRC does not match the message bytes. Counted in `crc_errors`.
    Crc,
    /// Decoding: the CRC matched but the bytes are not exactly one message of the
    /// expected type. Counted in `decode_errors`.
    Deserialize,
    /// Decoding: the frame was longer than the decoder's buffer; it was skipped up to
    /// its delimiter. Counted in `overruns`.
    Overrun,
}

impl fmt::Display for FrameError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            FrameError::BufferTooSmall => "output buffer too small for the frame",
            FrameError::Serialize => "message could not be serialised",
            FrameError::Malformed => "invalid COBS block or frame shorter than its CRC",
            FrameError::Crc => "CRC mismatch",
            FrameError::Deserialize => "frame is not one message of the expected type",
            FrameError::Overrun => "frame longer than the receive buffer",
        })
    }
}

impl core::error::Error for FrameError {}

/// Writes `msg` as one complete frame (COBS block and trailing `0x00`) to the start of
/// `out` and returns the frame's length. Allocates nothing; `out` of [`MAX_FRAME_LEN`]
/// bytes always suffices for a [`Request`](super::Request) or [`Reply`](super::Reply).
///
/// postcard writes the message to the start of `out`, its CRC (little-endian) follows;
/// [`cobs_encode_in_place`] then frames them where they lie. Both steps index only through checked accessors, so
/// the encoder is proven free of panics at link time (`scripts/no-panic.sh`).
///
/// On error the contents of `out` are unspecified.
#[inline(never)]
pub fn encode<M: Serialize + ?Sized>(msg: &M, out: &mut [u8]) -> Result<usize, FrameError> {
    let body_len = match postcard::to_slice(msg, out) {
        Ok(bytes) => bytes.len(),
        Err(postcard::Error::SerializeBufferFull) => return Err(FrameError::BufferTooSmall),
        Err(_) => return Err(FrameError::Serialize),
    };
    let crc = CRC.checksum(out.get(..body_len).ok_or(FrameError::BufferTooSmall)?);
    let raw_len = body_len + CRC_LEN;
    out.get_mut(body_len..raw_len)
        .ok_or(FrameError::BufferTooSmall)?
        .copy_from_slice(&crc.to_le_bytes());
    let len = cobs_encode_in_place(out, raw_len).ok_or(FrameError::BufferTooSmall)?;
    *out.get_mut(len).ok_or(FrameError::BufferTooSmall)? = 0;
    Ok(len + 1)
}

/// The length of the COBS block of `data` (without a delimiter).
fn cobs_len(data: &[u8]) -> usize {
    let mut len = 1usize;
    let mut run = 0u8;
    let mut rest = data.len();
    for &byte in data {
        rest -= 1;
        if byte == 0 {
            len += 1;
            run = 0;
            continue;
        }
        len += 1;
        run += 1;
        if run == 0xFE {
            run = 0;
            if rest > 0 {
                len += 1;
            }
        }
    }
    if data.is_empty() {
        0
    } else {
        len
    }
}

/// COBS-encodes the first `n` bytes of `buf` in place (no delimiter) and returns the
/// block's length, or `None` if `buf` is too short for the block ([`cobs_max_len`]`(n)`
/// always suffices) or `n > buf.len()`.
///
/// Byte-for-byte the encoding of the `cobs` crate (tests/protocol.rs compares them): a
/// code byte before each run of at most 254 non-zero bytes, `0xFF` for a full run that is
/// not followed by an implied zero, nothing for empty data. The data is first moved right
/// by the block's overhead, so the block written from the start never overtakes the bytes
/// still to be read. Panic-free by construction: every access is checked.
pub fn cobs_encode_in_place(buf: &mut [u8], n: usize) -> Option<usize> {
    let block_len = cobs_len(buf.get(..n)?);
    if block_len > buf.len() {
        return None;
    }
    let shift = block_len - n;
    for j in (0..n).rev() {
        let byte = *buf.get(j)?;
        *buf.get_mut(j + shift)? = byte;
    }
    if n == 0 {
        return Some(0);
    }
    let mut code_at = 0usize;
    let mut write = 1usize;
    let mut code = 1u8;
    for i in 0..n {
        let byte = *buf.get(i + shift)?;
        if byte == 0 {
            *buf.get_mut(code_at)? = code;
            code_at = write;
            write += 1;
            code = 1;
            continue;
        }
        *buf.get_mut(write)? = byte;
        write += 1;
        code = code.wrapping_add(1);
        if code == 0xFF {
            *buf.get_mut(code_at)? = code;
            if i + 1 == n {
                // A full run at the very end: no further code byte.
                return Some(write);
            }
            code_at = write;
            write += 1;
            code = 1;
        }
    }
    *buf.get_mut(code_at)? = code;
    Some(write)
}

/// Decodes a COBS block (without its delimiter) in place and returns the decoded length,
/// or `None` for an invalid block: a zero byte inside it, or a code that points past its
/// end. The decoded bytes never overtake the encoded ones, so decoding in place is exact.
///
/// Accepts exactly the blocks the `cobs` crate accepts and decodes them to the same bytes
/// (tests/protocol.rs compares them); panic-free by construction: every access is checked.
pub fn cobs_decode_in_place(block: &mut [u8]) -> Option<usize> {
    let len = block.len();
    let mut read = 0usize;
    let mut write = 0usize;
    while read < len {
        let code = *block.get(read)?;
        if code == 0 {
            return None;
        }
        read += 1;
        for _ in 1..code {
            let byte = *block.get(read)?;
            if byte == 0 {
                return None;
            }
            *block.get_mut(write)? = byte;
            write += 1;
            read += 1;
        }
        if code != 0xFF && read < len {
            *block.get_mut(write)? = 0;
            write += 1;
        }
    }
    Some(write)
}

/// The decoder's counters. All saturate at `u32::MAX`.
///
/// Every non-empty frame that ends in a delimiter is counted in exactly one of them.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct DecoderCounters {
    /// Frames that passed the CRC and decoded to one message.
    pub frames_received: u32,
    /// Frames whose CRC did not match.
    pub crc_errors: u32,
    /// Frames with an invalid COBS block, too short for a CRC, or whose bytes did not
    /// decode to exactly one message.
    pub decode_errors: u32,
    /// Frames longer than the buffer.
    pub overruns: u32,
}

/// Reassembles frames from a byte stream, whatever the reads' boundaries, into a fixed
/// buffer of `N` bytes: the longest COBS block it accepts, delimiter excluded (use
/// [`DefaultFrameDecoder`] for this protocol's frames).
///
/// A bad frame (invalid COBS, wrong CRC, not a message, or longer than `N`) is counted,
/// reported once at its delimiter and dropped; decoding resumes with the next byte after
/// that delimiter. Empty frames (`0x00` right after `0x00`, or at the very start) are
/// ignored and not counted, so a sender may send a lone `0x00` to flush a line of
/// earlier noise. Bytes received before the first delimiter are a frame like any other:
/// if the decoder starts in the middle of a frame, that tail is counted as an error.
#[derive(Debug, Clone)]
pub struct FrameDecoder<const N: usize> {
    buf: [u8; N],
    len: usize,
    overrun: bool,
    counters: DecoderCounters,
}

impl<const N: usize> Default for FrameDecoder<N> {
    fn default() -> Self {
        Self::new()
    }
}

impl<const N: usize> FrameDecoder<N> {
    /// An empty decoder with zero counters.
    pub const fn new() -> Self {
        Self {
            buf: [0; N],
            len: 0,
            overrun: false,
            counters: DecoderCounters {
                frames_received: 0,
                crc_errors: 0,
                decode_errors: 0,
                overruns: 0,
            },
        }
    }

    /// Takes one received byte. Returns `None` while a frame is incomplete (or the byte
    /// ended an empty frame), and at each delimiter that ends a non-empty frame either
    /// the decoded message or why the frame was dropped (already counted).
    #[inline(never)]
    pub fn push<M: DeserializeOwned>(&mut self, byte: u8) -> Option<Result<M, FrameError>> {
        let payload_len = match self.push_frame(byte)? {
            Ok(len) => len,
            Err(e) => return Some(Err(e)),
        };
        let decoded = self
            .buf
            .get(..payload_len)
            .and_then(|payload| postcard::take_from_bytes::<M>(payload).ok())
            .and_then(|(msg, rest)| rest.is_empty().then_some(msg));
        Some(match decoded {
            Some(msg) => {
                self.counters.frames_received = self.counters.frames_received.saturating_add(1);
                Ok(msg)
            }
            None => {
                self.counters.decode_errors = self.counters.decode_errors.saturating_add(1);
                Err(FrameError::Deserialize)
            }
        })
    }

    /// Takes a chunk of received bytes and calls `on_msg` with every message completed in
    /// it, in order. Dropped frames are only counted.
    pub fn feed<M: DeserializeOwned>(&mut self, bytes: &[u8], mut on_msg: impl FnMut(M)) {
        for msg in self.frames::<M>(bytes).flatten() {
            on_msg(msg);
        }
    }

    /// Takes a chunk of received bytes lazily: the iterator yields one result per frame
    /// completed in `bytes` (as [`push`](Self::push) does), and consumes only as much of
    /// `bytes` as it has been asked for. Unlike [`feed`](Self::feed) it lets the caller
    /// `.await` (e.g. to write a reply) between messages.
    pub fn frames<'a, M: DeserializeOwned>(&'a mut self, bytes: &'a [u8]) -> Frames<'a, N, M> {
        Frames {
            decoder: self,
            bytes: bytes.iter(),
            _msg: PhantomData,
        }
    }

    /// The counters so far.
    pub fn counters(&self) -> DecoderCounters {
        self.counters
    }

    /// Frames that passed the CRC and decoded to one message.
    pub fn frames_received(&self) -> u32 {
        self.counters.frames_received
    }

    /// Frames whose CRC did not match.
    pub fn crc_errors(&self) -> u32 {
        self.counters.crc_errors
    }

    /// Frames with invalid COBS, too short for a CRC, or not exactly one message.
    pub fn decode_errors(&self) -> u32 {
        self.counters.decode_errors
    }

    /// Frames longer than `N` bytes.
    pub fn overruns(&self) -> u32 {
        self.counters.overruns
    }

    /// Zeroes the counters (the frame in progress, if any, is kept).
    pub fn reset_counters(&mut self) {
        self.counters = DecoderCounters::default();
    }

    /// Drops the frame in progress, if any: the next byte starts a new frame. Nothing is
    /// counted for the dropped bytes.
    pub fn clear(&mut self) {
        self.len = 0;
        self.overrun = false;
    }

    /// Whether part of a frame has been received (its delimiter not yet).
    pub fn in_frame(&self) -> bool {
        self.len > 0 || self.overrun
    }

    /// The frame layer: at a delimiter, decodes the COBS block in place and checks the
    /// CRC, returning the length of the message bytes now at the start of `buf`. Counts
    /// every error it returns.
    fn push_frame(&mut self, byte: u8) -> Option<Result<usize, FrameError>> {
        if byte != 0 {
            if !self.overrun {
                match self.buf.get_mut(self.len) {
                    Some(slot) => {
                        *slot = byte;
                        self.len = self.len.saturating_add(1);
                    }
                    None => self.overrun = true,
                }
            }
            return None;
        }
        let encoded_len = core::mem::replace(&mut self.len, 0);
        if core::mem::replace(&mut self.overrun, false) {
            self.counters.overruns = self.counters.overruns.saturating_add(1);
            return Some(Err(FrameError::Overrun));
        }
        if encoded_len == 0 {
            return None;
        }
        let checked = self
            .buf
            .get_mut(..encoded_len)
            .and_then(|block| {
                let decoded_len = cobs_decode_in_place(block)?;
                let frame = block.get(..decoded_len)?;
                let payload_len = decoded_len.checked_sub(CRC_LEN)?;
                let (payload, crc) = frame.split_at_checked(payload_len)?;
                Some((payload_len, crc == CRC.checksum(payload).to_le_bytes()))
            })
            .ok_or(FrameError::Malformed)
            .and_then(|(payload_len, crc_ok)| {
                if crc_ok {
                    Ok(payload_len)
                } else {
                    Err(FrameError::Crc)
                }
            });
        match checked {
            Err(FrameError::Crc) => {
                self.counters.crc_errors = self.counters.crc_errors.saturating_add(1);
            }
            Err(_) => {
                self.counters.decode_errors = self.counters.decode_errors.saturating_add(1);
            }
            Ok(_) => {}
        }
        Some(checked)
    }
}

/// The iterator of [`FrameDecoder::frames`]: one result per frame completed in the
/// chunk.
pub struct Frames<'a, const N: usize, M> {
    decoder: &'a mut FrameDecoder<N>,
    bytes: core::slice::Iter<'a, u8>,
    _msg: PhantomData<fn() -> M>,
}

impl<const N: usize, M: DeserializeOwned> Iterator for Frames<'_, N, M> {
    type Item = Result<M, FrameError>;

    fn next(&mut self) -> Option<Self::Item> {
        self.bytes.by_ref().find_map(|&b| self.decoder.push(b))
    }
}
