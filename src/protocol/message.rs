//! The messages: what the host and the device say to each other.
//!
//! Every type here is plain data with a fixed upper bound on its encoded size (no
//! unbounded strings or sequences), so a whole frame always fits
//! [`MAX_FRAME_LEN`](super::MAX_FRAME_LEN) bytes.

use core::fmt::{self, Write};

use heapless::String;
use serde::{Deserialize, Serialize};

use super::frame::MAX_FRAME_LEN;
use crate::controller::{
    ControllerConfig, FromTablesError, Measurement, SkewParams, SlipSignal, Status, TableError,
};
use crate::ConfigError;

/// The protocol's version. Bump it when the meaning of a message changes without its
/// encoding changing (the [`SCHEMA_KEY`] follows the encoding by itself).
pub const PROTOCOL_VERSION: u16 = 5;

/// Every message, field and type on the wire, in order, plus the frame format. Its
/// FNV-1a hash is [`SCHEMA_KEY`].
///
/// `ControllerConfig`'s and `SkewParams`' parts are generated from their definitions
/// ([`ControllerConfig::SCHEMA`], [`SkewParams::SCHEMA`]), so a field added there is
/// described here by itself. The rest is written by hand below.
///
/// How to update: whenever a message, one of its fields (name, type, order), an enum
/// variant (including those of `Status`, `FingerShape`, `Mode`) or the frame format
/// changes, edit the hand-written parts so they describe the new definitions.
/// `tests/protocol.rs` (`schema_key_is_pinned`) then fails (as it does when a
/// `ControllerConfig` field changes): add a new line to its `SCHEMA_HISTORY` with the new
/// key and the new golden digest it prints. That test also fails when the encoding changes
/// while this string does not (the golden digest moves but the key does not), and its
/// exhaustive matches stop compiling when a variant or a message field is added, so a
/// change cannot slip through unnoticed.
pub const SCHEMA: &str = {
    const PARTS: [&str; 7] = [
        SCHEMA_MESSAGES,
        ";",
        ControllerConfig::SCHEMA,
        ";FingerShape{Rect,Disc};",
        SkewParams::SCHEMA,
        ";",
        "Mode{Ellipse,Table}",
    ];
    const BYTES: [u8; total_len(&PARTS)] = concat_bytes(&PARTS);
    match core::str::from_utf8(&BYTES) {
        Ok(s) => s,
        Err(_) => panic!("SCHEMA is not UTF-8"),
    }
};

/// The hand-written part of [`SCHEMA`]: the frame and the messages.
const SCHEMA_MESSAGES: &str = "\
softgrip-protocol;\
frame=cobs(postcard(msg)+crc32_iscsi_le(postcard(msg)))+0x00;\
Request{Hello{version:u16,schema_key:u32},Configure(ControllerConfig),Sensor(SensorFrame),\
GetStats,ResetStats,Shutdown{code:u8},SetPacing(Pacing)};\
Pacing{RealTime,Lockstep};\
Reply{Hello{version:u16,schema_key:u32,max_frame_len:u16},\
Configured(Result<(),WireConfigError>),Command(CommandFrame),Stats(Stats),\
NotConfigured{seq:u32},ShuttingDown{code:u8},Incompatible{version:u16,schema_key:u32},\
Paced(Pacing)};\
SensorFrame{seq:u32,timestamp_us:u64,tangential_force_n:[f32;2],torsional_moment_nm:f32,\
normal_force_n:f32,slip:SlipSignal};\
SlipSignal{None,Incipient,Gross};\
CommandFrame{seq:u32,normal_force_n:f32,n_slip_n:f32,utilisation:f32,status:Status,\
fault_active:bool,tick_cost:u32,mu_estimate:f32,margin:f32,load_factor:f32,lead_n:f32};\
Status{Ok,Saturated,SensorFault,StaleInput};\
Stats{frames_received:u32,crc_errors:u32,decode_errors:u32,overruns:u32,frames_sent:u32,\
ticks:u32,worst_tick_cost:u32,last_tick_cost:u32,startup_cost:u32,stack_peak_bytes:u32,\
cost_unit:CostUnit,stale_frames:u32,idle_ticks:u32,command_n:f32,fault_active:bool};\
CostUnit{Nanoseconds,Instructions,Cycles};\
WireConfigError{param:String<32>,message:String<96>}";

/// The summed lengths of `parts` (at compile time).
const fn total_len(parts: &[&str]) -> usize {
    let mut len = 0;
    let mut rest = parts;
    while let Some((part, tail)) = rest.split_first() {
        len += part.len();
        rest = tail;
    }
    len
}

/// `parts` one after the other, as bytes (at compile time: `N` must be their
/// [`total_len`], or the build fails).
#[allow(clippy::indexing_slicing)] // evaluated by the compiler: out of bounds fails the build
const fn concat_bytes<const N: usize>(parts: &[&str]) -> [u8; N] {
    let mut out = [0u8; N];
    let mut at = 0;
    let mut rest = parts;
    while let Some((part, tail)) = rest.split_first() {
        let mut bytes = part.as_bytes();
        while let Some((&b, more)) = bytes.split_first() {
            out[at] = b;
            at += 1;
            bytes = more;
        }
        rest = tail;
    }
    assert!(at == N, "concat_bytes: N is not the parts' total length");
    out
}

/// A key that changes whenever the message definitions change: the 32-bit FNV-1a hash of
/// [`SCHEMA`]. Both ends exchange it in `Hello` and refuse to talk on a mismatch.
pub const SCHEMA_KEY: u32 = fnv1a_32(SCHEMA.as_bytes());

/// 32-bit FNV-1a over `bytes` (offset basis `0x811c9dc5`, prime `0x01000193`).
pub const fn fnv1a_32(bytes: &[u8]) -> u32 {
    let mut hash: u32 = 0x811c_9dc5;
    let mut rest = bytes;
    while let Some((&b, tail)) = rest.split_first() {
        hash ^= b as u32;
        hash = hash.wrapping_mul(0x0100_0193);
        rest = tail;
    }
    hash
}

/// One measurement from the fingertip sensor (host → device inside [`Request::Sensor`]).
///
/// Floats travel bit for bit: NaN and infinities arrive as sent, and it is the controller
/// that rejects them.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct SensorFrame {
    /// Sequence number, chosen by the sender; echoed in the [`CommandFrame`].
    pub seq: u32,
    /// Time of the measurement \[µs\].
    pub timestamp_us: u64,
    /// Tangential force components `(f_x, f_y)` \[N\].
    pub tangential_force_n: [f32; 2],
    /// Torsional moment about the contact normal \[N·m\].
    pub torsional_moment_nm: f32,
    /// Measured normal force \[N\].
    pub normal_force_n: f32,
    /// What a tactile slip sensor saw ([`SlipSignal::None`] without one).
    pub slip: SlipSignal,
}

impl From<&SensorFrame> for Measurement<f32> {
    /// The measurement a sensor frame carries (everything but its sequence number).
    fn from(f: &SensorFrame) -> Self {
        Measurement {
            tangential_force_n: f.tangential_force_n,
            torsional_moment_nm: f.torsional_moment_nm,
            normal_force_n: f.normal_force_n,
            timestamp_us: f.timestamp_us,
            slip: f.slip,
        }
    }
}

/// The controller's answer to one [`SensorFrame`] (device → host inside
/// [`Reply::Command`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CommandFrame {
    /// The `seq` of the sensor frame this answers.
    pub seq: u32,
    /// Commanded normal force \[N\].
    pub normal_force_n: f32,
    /// Least normal force that holds the measured load without slip \[N\].
    pub n_slip_n: f32,
    /// How much of the friction limit the load uses at the commanded force.
    pub utilisation: f32,
    /// What the tick reports about itself.
    pub status: Status,
    /// Whether the controller is at (or moving to) its fault force.
    pub fault_active: bool,
    /// What this tick cost, in the [`CostUnit`] of the device's [`Stats`].
    pub tick_cost: u32,
    /// The friction coefficient the controller now believes (lowered by slip signals).
    pub mu_estimate: f32,
    /// The margin multiplying the safety factor, the controller's
    /// [`TickOutput::margin`](crate::controller::TickOutput::margin): the slip response's
    /// margin (1 until slip signals raise it, at most `slip_margin_max`) times
    /// `load_factor`. So it lies in `[steady_factor, slip_margin_max · cyclic_factor]`
    /// (0.85 to 4.35 at the defaults;
    /// `tests/margins.rs::every_tick_reports_the_parts_of_its_command`), and is below 1
    /// only on a steady hold; the force asked is never below `N_slip` whatever the margin.
    pub margin: f32,
    /// The load's part of `margin` ([`TickOutput::load_factor`](crate::controller::TickOutput::load_factor)):
    /// `cyclic_factor` while the load cycles, the steady factor on a steady hold, else 1.
    pub load_factor: f32,
    /// How far the target leads the requirement for the actuator's lag \[N\]
    /// ([`TickOutput::lead_n`](crate::controller::TickOutput::lead_n)).
    pub lead_n: f32,
}

/// The unit of the tick costs in [`Stats`]: whatever the device can measure.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum CostUnit {
    /// Wall-clock nanoseconds (host builds).
    Nanoseconds,
    /// Retired instructions (e.g. a simulator's instruction counter).
    Instructions,
    /// CPU cycles (e.g. the Cortex-M DWT cycle counter).
    Cycles,
}

/// Link and timing counters of the device (device → host inside [`Reply::Stats`]).
///
/// The first four have the meaning of the [`FrameDecoder`](super::FrameDecoder) counters
/// of the same names. All counters saturate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Stats {
    /// Good frames received.
    pub frames_received: u32,
    /// Frames dropped for a CRC mismatch.
    pub crc_errors: u32,
    /// Frames dropped for invalid COBS or a message that did not decode.
    pub decode_errors: u32,
    /// Frames dropped for being longer than the receive buffer.
    pub overruns: u32,
    /// Frames sent.
    pub frames_sent: u32,
    /// Controller ticks run.
    pub ticks: u32,
    /// Greatest cost of one tick, in `cost_unit`.
    pub worst_tick_cost: u32,
    /// Cost of the latest tick, in `cost_unit`.
    pub last_tick_cost: u32,
    /// Cost of the start-up precomputation (the last successful `Configure`), in
    /// `cost_unit`.
    pub startup_cost: u32,
    /// The most stack the device has used since it started \[bytes\], measured by
    /// painting the stack at start-up (0 where it is not measured, e.g. on the host).
    pub stack_peak_bytes: u32,
    /// The unit of the costs.
    pub cost_unit: CostUnit,
    /// Sensor frames refused for their timestamp (a repeat, an older frame, an
    /// implausible jump: see the controller's "Time" rule).
    pub stale_frames: u32,
    /// Tick periods that passed with no sensor frame, each an idle tick of the controller
    /// (see `softgrip::device`, "Silence").
    pub idle_ticks: u32,
    /// The force the actuator was last given \[N\] (0 before a configuration): after a
    /// silence, where the device has moved the grip on its own.
    pub command_n: f32,
    /// Whether the controller has had no good measurement for its stale timeout and is at
    /// (or moving to) its fault target.
    pub fault_active: bool,
}

/// What paces the device's controller (host → device inside [`Request::SetPacing`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Pacing {
    /// The device keeps time: one tick per sensor frame, and one idle tick per tick period
    /// of its own timer with no sensor frame, so a dead link moves the grip to its fault
    /// target after the stale timeout. What a device starts in; what a real grasp needs.
    #[default]
    RealTime,
    /// The host's sensor frames are the device's only clock: it ticks on frames alone and
    /// never on silence. For lockstep simulations, whose plant runs at its own speed, so
    /// their results do not depend on how fast the host or an emulator is scheduled. A
    /// device left in lockstep holds its command through a dead link.
    Lockstep,
}

/// A [`ConfigError`] in a form that crosses the wire: the parameter's name and the
/// error's message, both truncated to fit (device → host inside [`Reply::Configured`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WireConfigError {
    /// The name of the rejected parameter ([`ConfigError::param`]), at most 32 bytes.
    pub param: String<32>,
    /// What is wrong, at most 96 bytes (see [`WireConfigError::from_config_error`]).
    pub message: String<96>,
}

impl WireConfigError {
    /// Copies `err`'s parameter name and message, cutting each (at a `char` boundary) to
    /// its capacity when too long. Never fails, never panics.
    ///
    /// The message is `err`'s `Display` text, except that an out-of-range value is not
    /// repeated (the sender has it): "mu: out of range, expected a finite number > 0".
    /// The device formats no floating-point number and writes integers by hand, so the
    /// firmware links none of `core::fmt`'s formatting (about 23 KB of flash).
    pub fn from_config_error(err: &ConfigError) -> Self {
        let mut wire = Self::text(err.param(), "");
        let mut m = Truncating::new(&mut wire.message);
        // `Truncating` never reports an error.
        let _ = match *err {
            ConfigError::NonFinite(param) => {
                write_all(&mut m, &[param, ": must be a finite number"])
            }
            ConfigError::OutOfRange {
                param, expected, ..
            } => write_all(&mut m, &[param, ": out of range, expected ", expected]),
            ConfigError::Capacity {
                param,
                requested,
                limit,
            } => write_all(&mut m, &[param, ": "])
                .and_then(|()| write_decimal(&mut m, requested))
                .and_then(|()| write_all(&mut m, &[" does not fit the fixed capacity (limit "]))
                .and_then(|()| write_decimal(&mut m, limit))
                .and_then(|()| m.write_str(")")),
        };
        wire
    }

    /// Why [`Controller::from_tables`](crate::controller::Controller::from_tables) refused,
    /// under the parameter name `tables`: `err`'s `Display` text, written without
    /// `core::fmt` (see [`WireConfigError::from_config_error`]).
    pub fn from_tables_error(err: &FromTablesError) -> Self {
        let table = match err {
            FromTablesError::Config(e) => {
                let mut wire = Self::from_config_error(e);
                wire.param = Self::text("tables", "").param;
                return wire;
            }
            FromTablesError::Tables(t) => *t,
        };
        let mut wire = Self::text("tables", "");
        let mut m = Truncating::new(&mut wire.message);
        let _ = match table {
            TableError::Size {
                what,
                len,
                expected,
            } => write_all(&mut m, &["tables: ", what, " has "])
                .and_then(|()| write_decimal(&mut m, len))
                .and_then(|()| m.write_str(" entries, the configuration needs "))
                .and_then(|()| write_decimal(&mut m, expected)),
            TableError::Invalid { what, index } => write_all(&mut m, &["tables: ", what, "["])
                .and_then(|()| write_decimal(&mut m, index))
                .and_then(|()| m.write_str("] is not a valid value")),
            TableError::Inconsistent { check, index } => {
                write_all(&mut m, &["tables: ", check, " fails at index "])
                    .and_then(|()| write_decimal(&mut m, index))
            }
            TableError::Mismatch { param } => {
                write_all(&mut m, &["tables: they were made for another ", param])
            }
        };
        wire
    }

    /// A parameter name and a fixed message, each cut to its capacity like
    /// [`WireConfigError::from_config_error`].
    pub fn text(param: &str, message: &str) -> Self {
        let mut p = String::new();
        let mut m = String::new();
        // `Truncating` never reports an error, so neither can these writes.
        let _ = Truncating::new(&mut p).write_str(param);
        let _ = Truncating::new(&mut m).write_str(message);
        Self {
            param: p,
            message: m,
        }
    }

    /// A parameter name and any message, each cut to its capacity like
    /// [`WireConfigError::from_config_error`] (through `core::fmt`: host code).
    pub fn new(param: &str, message: &dyn fmt::Display) -> Self {
        let mut wire = Self::text(param, "");
        let _ = write!(Truncating::new(&mut wire.message), "{message}");
        wire
    }
}

fn write_all(out: &mut impl Write, parts: &[&str]) -> fmt::Result {
    parts.iter().try_for_each(|p| out.write_str(p))
}

/// `n` in decimal, by hand: `write!(out, "{n}")` would link `core::fmt`'s integer
/// formatting into the firmware.
fn write_decimal(out: &mut impl Write, mut n: usize) -> fmt::Result {
    let mut digits = [0u8; 20];
    let mut start = digits.len();
    loop {
        start -= 1;
        if let Some(d) = digits.get_mut(start) {
            *d = b'0' + (n % 10) as u8;
        }
        n /= 10;
        if n == 0 || start == 0 {
            break;
        }
    }
    let text = digits.get(start..).unwrap_or_default();
    out.write_str(core::str::from_utf8(text).unwrap_or_default())
}

impl From<&ConfigError> for WireConfigError {
    fn from(err: &ConfigError) -> Self {
        Self::from_config_error(err)
    }
}

impl fmt::Display for WireConfigError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

/// A `fmt::Write` into a fixed string that drops whatever does not fit, from the first
/// character that does not fit on.
struct Truncating<'a, const N: usize> {
    out: &'a mut String<N>,
    full: bool,
}

impl<'a, const N: usize> Truncating<'a, N> {
    fn new(out: &'a mut String<N>) -> Self {
        Self { out, full: false }
    }
}

impl<const N: usize> Write for Truncating<'_, N> {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        for c in s.chars() {
            if self.full || self.out.push(c).is_err() {
                self.full = true;
                break;
            }
        }
        Ok(())
    }
}

/// Host → device.
// The core has no heap to box `Configure` in; a request is decoded in place, one at a
// time, so its size costs one buffer (the firmware's RAM: docs/firmware-costs.md).
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Request {
    /// Opens the session; the device answers [`Reply::Hello`].
    Hello {
        /// The host's [`PROTOCOL_VERSION`].
        version: u16,
        /// The host's [`SCHEMA_KEY`].
        schema_key: u32,
    },
    /// (Re)configures the controller; the device answers [`Reply::Configured`]. The same
    /// configuration again changes nothing; a new one takes over the running command (see
    /// `Controller::take_over_from`), so a grasp is never released by a reconfiguration.
    Configure(ControllerConfig),
    /// One measurement; the device answers [`Reply::Command`], or
    /// [`Reply::NotConfigured`] before a valid configuration.
    Sensor(SensorFrame),
    /// Asks for the counters; the device answers [`Reply::Stats`].
    GetStats,
    /// Zeroes the counters; the device answers [`Reply::Stats`] with the zeroed values.
    ResetStats,
    /// Ends the session: the device answers [`Reply::ShuttingDown`] and stops (the
    /// firmware exits the emulator with `code`; the host's device thread returns).
    Shutdown {
        /// The exit code the device should end with.
        code: u8,
    },
    /// Sets what paces the controller (the device starts in [`Pacing::RealTime`]); the
    /// device answers [`Reply::Paced`]. Allowed before the handshake's `Hello` like
    /// `GetStats`.
    SetPacing(Pacing),
}

impl Request {
    /// `Hello` with this build's [`PROTOCOL_VERSION`] and [`SCHEMA_KEY`].
    pub const fn hello() -> Self {
        Request::Hello {
            version: PROTOCOL_VERSION,
            schema_key: SCHEMA_KEY,
        }
    }
}

/// [`MAX_FRAME_LEN`] as it travels in [`Reply::Hello`].
pub const MAX_FRAME_LEN_U16: u16 = {
    assert!(MAX_FRAME_LEN <= u16::MAX as usize);
    MAX_FRAME_LEN as u16
};

/// Device → host.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Reply {
    /// Answers [`Request::Hello`] with the device's side.
    Hello {
        /// The device's [`PROTOCOL_VERSION`].
        version: u16,
        /// The device's [`SCHEMA_KEY`].
        schema_key: u32,
        /// The longest frame the device sends or accepts, delimiter included
        /// ([`MAX_FRAME_LEN`]).
        max_frame_len: u16,
    },
    /// Answers [`Request::Configure`]: `Ok` once the controller runs with the new
    /// configuration, or why it was rejected (the previous configuration, if any, stays).
    Configured(Result<(), WireConfigError>),
    /// Answers [`Request::Sensor`].
    Command(CommandFrame),
    /// Answers [`Request::GetStats`] and [`Request::ResetStats`].
    Stats(Stats),
    /// Answers a [`Request::Sensor`] that arrived before a valid configuration.
    NotConfigured {
        /// The `seq` of that sensor frame.
        seq: u32,
    },
    /// Answers [`Request::Shutdown`]; the device stops after sending it.
    ShuttingDown {
        /// The exit code it will end with.
        code: u8,
    },
    /// Answers a [`Request::Hello`] whose version or schema key differs from the device's,
    /// and, until a matching `Hello` arrives, every `Configure` and `Sensor`: the device
    /// does not run with a host that speaks another protocol. Carries the device's side.
    Incompatible {
        /// The device's [`PROTOCOL_VERSION`].
        version: u16,
        /// The device's [`SCHEMA_KEY`].
        schema_key: u32,
    },
    /// Answers [`Request::SetPacing`] with the pacing now in force.
    Paced(Pacing),
}

impl Reply {
    /// `Hello` with this build's [`PROTOCOL_VERSION`], [`SCHEMA_KEY`] and
    /// [`MAX_FRAME_LEN`].
    pub const fn hello() -> Self {
        Reply::Hello {
            version: PROTOCOL_VERSION,
            schema_key: SCHEMA_KEY,
            max_frame_len: MAX_FRAME_LEN_U16,
        }
    }
}
