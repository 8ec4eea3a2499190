//! The controller's tables as a versioned binary blob, for a device that receives them
//! over the link or keeps them in flash instead of precomputing them.
//!
//! ```text
//! offset  size  field
//! 0       4     magic "SGTB"
//! 4       2     format version (little-endian), BLOB_VERSION
//! 6       4     body length B (little-endian)
//! 10      B     body: postcard of { config: ControllerConfig (every parameter),
//!               nodes: u16, shapes: u16, directions: u16, force_n, arm_m,
//!               inv_arm_per_m, aspect_pos: [f32; nodes], inv_radius: [f32; shapes·directions],
//!               demand_scale: [f32; 2] }
//! 10+B    4     CRC-32/ISCSI of bytes 0 .. 10+B (little-endian)
//! ```
//!
//! [`Blob::parse`] checks, in order: length, magic, version, declared length, CRC, the
//! body's encoding, the sizes against the configuration, then every value (through
//! [`Capacity::from_tables`](super::Capacity::from_tables)). Each failure is a
//! [`BlobError`] variant (`tests/tables_export.rs`). Cost: one CRC pass and one decode,
//! no allocation.

use crate::checksum::CRC;
use crate::controller::capacity::{Tables, DIRECTIONS, MAX_ASPECTS, MAX_FORCE_NODES};
use crate::controller::config::ControllerConfig;
use crate::controller::tick::{Controller, FromTablesError};
use crate::controller::TickMath;
use heapless::Vec;
use serde::{Deserialize, Serialize};

/// The blob's magic bytes.
pub const BLOB_MAGIC: [u8; 4] = *b"SGTB";
/// The blob format's version.
pub const BLOB_VERSION: u16 = 3;
const HEADER_LEN: usize = 10;
/// A buffer of this many bytes holds any blob: header, body, CRC. The largest grid (table
/// mode, every capacity at its maximum, with skew) encodes to 2 807 bytes
/// (`tests/tables_export.rs` checks it fits and needs more than half of this).
pub const BLOB_MAX_LEN: usize = 3400;

#[derive(Debug, Clone, Serialize, Deserialize)]
struct Body {
    config: ControllerConfig,
    nodes: u16,
    shapes: u16,
    directions: u16,
    force_n: Vec<f32, MAX_FORCE_NODES>,
    arm_m: Vec<f32, MAX_FORCE_NODES>,
    inv_arm_per_m: Vec<f32, MAX_FORCE_NODES>,
    aspect_pos: Vec<f32, MAX_FORCE_NODES>,
    inv_radius: Vec<f32, { MAX_ASPECTS * DIRECTIONS }>,
    demand_scale: [f32; 2],
}

/// Why a blob was refused.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BlobError {
    /// Shorter than a header and a CRC.
    TooShort {
        /// Its length.
        len: usize,
    },
    /// Not a softgrip table blob.
    BadMagic,
    /// A format version this build does not read.
    Version {
        /// The blob's version.
        found: u16,
    },
    /// The declared body length does not match the blob's length.
    Length {
        /// The declared total length.
        declared: usize,
        /// The actual length.
        actual: usize,
    },
    /// The CRC does not match: the blob is corrupt.
    Crc {
        /// The CRC stored in the blob.
        stored: u32,
        /// The CRC of its bytes.
        computed: u32,
    },
    /// The body does not decode.
    Malformed,
    /// The body decodes, but its header fields contradict its contents (`check` names
    /// the failed check).
    Implausible {
        /// The failed check.
        check: &'static str,
    },
    /// The blob was made for another number of load directions.
    Directions {
        /// The blob's.
        found: u16,
    },
    /// The blob's configuration or tables were refused.
    Tables(FromTablesError),
    /// The output buffer is too small (encoding).
    BufferTooSmall,
}

impl core::fmt::Display for BlobError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            BlobError::TooShort { len } => write!(f, "blob: {len} bytes is too short"),
            BlobError::BadMagic => write!(f, "blob: not a softgrip table blob (bad magic)"),
            BlobError::Version { found } => {
                write!(
                    f,
                    "blob: format version {found}, this build reads {BLOB_VERSION}"
                )
            }
            BlobError::Length { declared, actual } => {
                write!(f, "blob: declares {declared} bytes but has {actual}")
            }
            BlobError::Crc { stored, computed } => write!(
                f,
                "blob: CRC mismatch (stored {stored:#010x}, computed {computed:#010x}): corrupt"
            ),
            BlobError::Malformed => write!(f, "blob: the body does not decode"),
            BlobError::Implausible { check } => write!(f, "blob: implausible contents: {check}"),
            BlobError::Directions { found } => write!(
                f,
                "blob: made for {found} load directions, this build uses {DIRECTIONS}"
            ),
            BlobError::Tables(e) => write!(f, "blob: {e}"),
            BlobError::BufferTooSmall => write!(f, "blob: output buffer too small"),
        }
    }
}

impl core::error::Error for BlobError {}

/// Writes `tables` of `config` as a blob into `out`; returns its length.
pub fn encode(
    config: &ControllerConfig,
    tables: &Tables<'_, f32>,
    out: &mut [u8],
) -> Result<usize, BlobError> {
    let vec = |s: &[f32]| {
        Vec::<f32, MAX_FORCE_NODES>::from_slice(s).map_err(|_| BlobError::BufferTooSmall)
    };
    let mut inv_radius = Vec::new();
    for row in tables.inv_radius {
        inv_radius
            .extend_from_slice(row)
            .map_err(|_| BlobError::BufferTooSmall)?;
    }
    let body = Body {
        config: *config,
        nodes: tables.force_n.len() as u16,
        shapes: tables.inv_radius.len() as u16,
        directions: DIRECTIONS as u16,
        force_n: vec(tables.force_n)?,
        arm_m: vec(tables.arm_m)?,
        inv_arm_per_m: vec(tables.inv_arm_per_m)?,
        aspect_pos: vec(tables.aspect_pos)?,
        inv_radius,
        demand_scale: tables.demand_scale,
    };
    let (header, rest) = out
        .split_at_mut_checked(HEADER_LEN)
        .ok_or(BlobError::BufferTooSmall)?;
    let used = postcard::to_slice(&body, rest)
        .map_err(|_| BlobError::BufferTooSmall)?
        .len();
    header
        .get_mut(..4)
        .ok_or(BlobError::BufferTooSmall)?
        .copy_from_slice(&BLOB_MAGIC);
    header
        .get_mut(4..6)
        .ok_or(BlobError::BufferTooSmall)?
        .copy_from_slice(&BLOB_VERSION.to_le_bytes());
    header
        .get_mut(6..10)
        .ok_or(BlobError::BufferTooSmall)?
        .copy_from_slice(&(used as u32).to_le_bytes());
    let end = HEADER_LEN + used;
    let crc = CRC.checksum(out.get(..end).ok_or(BlobError::BufferTooSmall)?);
    out.get_mut(end..end + 4)
        .ok_or(BlobError::BufferTooSmall)?
        .copy_from_slice(&crc.to_le_bytes());
    Ok(end + 4)
}

/// A checked blob: its configuration and tables.
#[derive(Debug, Clone)]
pub struct Blob {
    body: Body,
    rows: [[f32; DIRECTIONS]; MAX_ASPECTS],
}

fn le_u16(b: &[u8], at: usize) -> Option<u16> {
    Some(u16::from_le_bytes(b.get(at..at + 2)?.try_into().ok()?))
}

fn le_u32(b: &[u8], at: usize) -> Option<u32> {
    Some(u32::from_le_bytes(b.get(at..at + 4)?.try_into().ok()?))
}

impl Blob {
    /// Checks a blob (see the module docs for the order of the checks) and that a
    /// controller can be built from it.
    pub fn parse(bytes: &[u8]) -> Result<Self, BlobError> {
        let len = bytes.len();
        if len < HEADER_LEN + 4 {
            return Err(BlobError::TooShort { len });
        }
        if bytes.get(..4) != Some(&BLOB_MAGIC[..]) {
            return Err(BlobError::BadMagic);
        }
        let version = le_u16(bytes, 4).ok_or(BlobError::TooShort { len })?;
        if version != BLOB_VERSION {
            return Err(BlobError::Version { found: version });
        }
        let body_len = le_u32(bytes, 6).ok_or(BlobError::TooShort { len })? as usize;
        let declared = HEADER_LEN.saturating_add(body_len).saturating_add(4);
        if declared != len {
            return Err(BlobError::Length {
                declared,
                actual: len,
            });
        }
        let end = HEADER_LEN + body_len;
        let stored = le_u32(bytes, end).ok_or(BlobError::TooShort { len })?;
        let computed = CRC.checksum(bytes.get(..end).ok_or(BlobError::TooShort { len })?);
        if stored != computed {
            return Err(BlobError::Crc { stored, computed });
        }
        let body: Body = postcard::from_bytes(bytes.get(HEADER_LEN..end).unwrap_or(&[]))
            .map_err(|_| BlobError::Malformed)?;
        if usize::from(body.directions) != DIRECTIONS {
            return Err(BlobError::Directions {
                found: body.directions,
            });
        }
        let shapes = usize::from(body.shapes);
        if shapes > MAX_ASPECTS || body.inv_radius.len() != shapes * DIRECTIONS {
            return Err(BlobError::Implausible {
                check: "shapes × directions = inv_radius entries",
            });
        }
        let nodes = usize::from(body.nodes);
        if nodes > MAX_FORCE_NODES {
            return Err(BlobError::Implausible {
                check: "nodes <= MAX_FORCE_NODES",
            });
        }
        if [
            body.force_n.len(),
            body.arm_m.len(),
            body.inv_arm_per_m.len(),
            body.aspect_pos.len(),
        ]
        .iter()
        .any(|&n| n != nodes)
        {
            return Err(BlobError::Implausible {
                check: "nodes = entries of every node table",
            });
        }
        if usize::from(body.config.force_nodes) != nodes {
            return Err(BlobError::Implausible {
                check: "nodes = the configuration's force_nodes",
            });
        }
        let mut rows = [[0.0f32; DIRECTIONS]; MAX_ASPECTS];
        for (row, chunk) in rows
            .iter_mut()
            .zip(body.inv_radius.chunks_exact(DIRECTIONS))
        {
            row.copy_from_slice(chunk);
        }
        let blob = Self { body, rows };
        // Everything a controller checks, checked now.
        Controller::<f32, crate::controller::Libm>::from_tables(blob.config(), &blob.tables())
            .map_err(BlobError::Tables)?;
        Ok(blob)
    }

    /// The configuration the tables were made for.
    pub fn config(&self) -> ControllerConfig {
        self.body.config
    }

    /// The tables.
    pub fn tables(&self) -> Tables<'_, f32> {
        Tables {
            force_n: &self.body.force_n,
            arm_m: &self.body.arm_m,
            inv_arm_per_m: &self.body.inv_arm_per_m,
            aspect_pos: &self.body.aspect_pos,
            inv_radius: self
                .rows
                .get(..usize::from(self.body.shapes))
                .unwrap_or(&[]),
            demand_scale: self.body.demand_scale,
        }
    }

    /// A controller from the blob: no precomputation.
    pub fn controller<M: TickMath<f32>>(&self) -> Result<Controller<f32, M>, BlobError> {
        Controller::from_tables(self.config(), &self.tables()).map_err(BlobError::Tables)
    }
}
