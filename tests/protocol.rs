//! The serial protocol: frame layout, round trips, stream reassembly, corruption and
//! resynchronisation, sizes and the schema key.
//!
//! Run with `cargo test --release --test protocol`.

use std::collections::HashMap;

use proptest::prelude::*;
use serde::ser::SerializeTuple;
use serde::Serialize;
use softgrip::controller::{
    ControllerConfig, FingerShape, FromTablesError, Mode, SkewParams, SlipSignal, Status,
    TableError,
};
use softgrip::protocol::{
    cobs_decode_in_place, cobs_encode_in_place, cobs_max_len, encode, fnv1a_32, CommandFrame,
    CostUnit, DecoderCounters, DefaultFrameDecoder, FrameDecoder, FrameError, Pacing, Reply,
    Request, SensorFrame, Stats, WireConfigError, CRC, CRC_LEN, MAX_FRAME_LEN, MAX_FRAME_LEN_U16,
    MAX_MESSAGE_LEN, PROTOCOL_VERSION, SCHEMA_KEY,
};
use softgrip::ConfigError;

// ---------------------------------------------------------------------------------------
// Helpers
// ---------------------------------------------------------------------------------------

/// One frame, delimiter included.
fn frame_of<M: Serialize>(msg: &M) -> Vec<u8> {
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = encode(msg, &mut buf).expect("every message fits MAX_FRAME_LEN");
    buf[..n].to_vec()
}

/// The postcard bytes of a message (no CRC, no COBS).
fn postcard_of<M: Serialize>(msg: &M) -> Vec<u8> {
    let mut buf = [0u8; 1024];
    postcard::to_slice(msg, &mut buf).unwrap().to_vec()
}

/// Feeds `bytes` one byte at a time and collects every result.
fn push_all<M: serde::de::DeserializeOwned, const N: usize>(
    dec: &mut FrameDecoder<N>,
    bytes: &[u8],
) -> Vec<Result<M, FrameError>> {
    bytes.iter().filter_map(|&b| dec.push::<M>(b)).collect()
}

/// Feeds `bytes` in chunks of the given sizes (cycled) through `frames`.
fn chunked<M: serde::de::DeserializeOwned, const N: usize>(
    dec: &mut FrameDecoder<N>,
    bytes: &[u8],
    sizes: &[usize],
) -> Vec<Result<M, FrameError>> {
    let mut out = Vec::new();
    let mut rest = bytes;
    let mut sizes = sizes.iter().copied().cycle();
    while !rest.is_empty() {
        let n = sizes.next().unwrap_or(1).clamp(1, rest.len());
        let (chunk, tail) = rest.split_at(n);
        out.extend(dec.frames::<M>(chunk));
        rest = tail;
    }
    out
}

/// Bit-exact equality of two messages (NaN payloads included): same encoding.
fn same_bits<M: Serialize>(a: &M, b: &M) -> bool {
    postcard_of(a) == postcard_of(b)
}

/// An independent bitwise CRC-32/ISCSI (reflected polynomial 0x82F63B78).
fn crc32c_reference(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in data {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0x82F6_3B78
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// An independent COBS encoder (without the delimiter).
fn cobs_reference(data: &[u8]) -> Vec<u8> {
    let mut out = vec![0u8];
    let mut code_idx = 0;
    let mut code = 1u8;
    for &b in data {
        if b == 0 {
            out[code_idx] = code;
            code_idx = out.len();
            out.push(0);
            code = 1;
        } else {
            out.push(b);
            code += 1;
            if code == 0xFF {
                out[code_idx] = code;
                code_idx = out.len();
                out.push(0);
                code = 1;
            }
        }
    }
    out[code_idx] = code;
    out
}

/// The frame the module docs describe, built by hand: COBS(P ‖ CRC_le(P)) ‖ 0x00.
fn reference_frame(payload: &[u8]) -> Vec<u8> {
    let mut raw = payload.to_vec();
    raw.extend_from_slice(&crc32c_reference(payload).to_le_bytes());
    let mut frame = cobs_reference(&raw);
    frame.push(0);
    frame
}

/// Serialises its bytes as a postcard tuple, i.e. raw, without a length prefix.
struct Raw<'a>(&'a [u8]);

impl Serialize for Raw<'_> {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut t = s.serialize_tuple(self.0.len())?;
        for b in self.0 {
            t.serialize_element(b)?;
        }
        t.end()
    }
}

/// A tiny deterministic generator for chunk sizes and garbage.
struct XorShift(u64);

impl XorShift {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
}

fn config_with_skew() -> ControllerConfig {
    ControllerConfig {
        skew: Some(SkewParams::PAPER),
        shape: FingerShape::Disc,
        mode: Mode::Table,
        ..ControllerConfig::default()
    }
}

fn sensor(seq: u32) -> SensorFrame {
    SensorFrame {
        seq,
        timestamp_us: 1_000 * u64::from(seq),
        tangential_force_n: [0.5 + seq as f32, -0.25],
        torsional_moment_nm: 0.01,
        normal_force_n: 2.0,
        slip: Default::default(),
    }
}

fn stats_sample() -> Stats {
    Stats {
        frames_received: 10,
        crc_errors: 1,
        decode_errors: 2,
        overruns: 3,
        frames_sent: 9,
        ticks: 1_000_000,
        worst_tick_cost: 12_345,
        last_tick_cost: 4_321,
        startup_cost: 7_654_321,
        stack_peak_bytes: 3_072,
        cost_unit: CostUnit::Cycles,
        stale_frames: Default::default(),
        idle_ticks: 17,
        command_n: 6.5,
        fault_active: true,
    }
}

fn wire_error_sample() -> WireConfigError {
    WireConfigError {
        param: "mu".try_into().unwrap(),
        message: "mu: -1 is out of range, expected a finite number > 0"
            .try_into()
            .unwrap(),
    }
}

/// One value of every request variant (with some sub-variants).
fn all_requests() -> Vec<Request> {
    vec![
        Request::hello(),
        Request::Hello {
            version: 7,
            schema_key: 0xDEAD_BEEF,
        },
        Request::Configure(ControllerConfig::default()),
        Request::Configure(config_with_skew()),
        Request::Sensor(sensor(42)),
        Request::GetStats,
        Request::ResetStats,
        Request::Shutdown { code: 0 },
        Request::Shutdown { code: 3 },
        Request::SetPacing(Pacing::RealTime),
        Request::SetPacing(Pacing::Lockstep),
    ]
}

/// One value of every reply variant (with some sub-variants).
fn all_replies() -> Vec<Reply> {
    vec![
        Reply::hello(),
        Reply::Configured(Ok(())),
        Reply::Configured(Err(wire_error_sample())),
        Reply::Command(CommandFrame {
            seq: 42,
            normal_force_n: 3.5,
            n_slip_n: 2.7,
            utilisation: 0.77,
            status: Status::Ok,
            fault_active: false,
            tick_cost: 12_345,
            margin: Default::default(),
            load_factor: Default::default(),
            lead_n: Default::default(),
            mu_estimate: Default::default(),
        }),
        Reply::Command(CommandFrame {
            seq: u32::MAX,
            normal_force_n: 10.0,
            n_slip_n: f32::NAN,
            utilisation: f32::INFINITY,
            status: Status::StaleInput,
            fault_active: true,
            tick_cost: 0,
            margin: Default::default(),
            load_factor: Default::default(),
            lead_n: Default::default(),
            mu_estimate: Default::default(),
        }),
        Reply::Stats(stats_sample()),
        Reply::NotConfigured { seq: 5 },
        Reply::ShuttingDown { code: 0 },
        Reply::ShuttingDown { code: 3 },
        Reply::Paced(Pacing::RealTime),
        Reply::Paced(Pacing::Lockstep),
    ]
}

// ---------------------------------------------------------------------------------------
// Layout
// ---------------------------------------------------------------------------------------

#[test]
fn crc_is_crc32_iscsi() {
    assert_eq!(CRC.checksum(b"123456789"), 0xE306_9283);
    assert_eq!(crc32c_reference(b"123456789"), 0xE306_9283);
    assert_eq!(CRC_LEN, 4);
}

#[test]
fn frames_match_the_documented_layout_byte_for_byte() {
    for r in all_requests() {
        assert_eq!(frame_of(&r), reference_frame(&postcard_of(&r)), "{r:?}");
    }
    for r in all_replies() {
        assert_eq!(frame_of(&r), reference_frame(&postcard_of(&r)), "{r:?}");
    }
}

#[test]
fn get_stats_frame_is_the_one_in_the_docs() {
    // Module docs: P = 03, C = a5 a0 2d 41, frame = 06 03 a5 a0 2d 41 00.
    assert_eq!(postcard_of(&Request::GetStats), [0x03]);
    assert_eq!(
        CRC.checksum(&[0x03]).to_le_bytes(),
        [0xa5, 0xa0, 0x2d, 0x41]
    );
    assert_eq!(
        frame_of(&Request::GetStats),
        [0x06, 0x03, 0xa5, 0xa0, 0x2d, 0x41, 0x00]
    );
}

#[test]
fn a_frame_contains_exactly_one_zero_at_its_end() {
    for r in all_requests() {
        let f = frame_of(&r);
        assert_eq!(f.iter().filter(|&&b| b == 0).count(), 1);
        assert_eq!(f.last(), Some(&0));
    }
}

// ---------------------------------------------------------------------------------------
// Sizes
// ---------------------------------------------------------------------------------------

fn long_text(n: usize) -> String {
    "x".repeat(n)
}

/// The widest value of every request variant: every varint at its longest, every option
/// filled.
// Today's `ControllerConfig` fields are all set here; one added later takes its default
// (a float has one size; a new integer should be set to its widest here).
#[allow(clippy::needless_update)]
fn largest_requests() -> Vec<Request> {
    // Every float is one whose eight bytes are all non-zero (1.1, f64::MAX), so that the
    // configuration's encoding is one long run without a zero: COBS's worst case.
    let x = 1.1;
    let config = ControllerConfig {
        mu: f64::MAX,
        shape: FingerShape::Disc,
        k: x,
        skew: Some(SkewParams {
            delta_over_a: 0.9,
            alpha: 1.1,
            locus_over_a: 0.45,
        }),
        c_m_per_n_gamma: x,
        gamma: x,
        half_length_m: x,
        safety: x,
        n_min_n: x,
        n_max_n: x,
        rise_rate_n_per_s: x,
        fall_rate_n_per_s: x,
        tick_period_s: x,
        stale_timeout_s: x,
        fault_force_n: x,
        force_range_n: x,
        moment_range_nm: x,
        mode: Mode::Table,
        force_nodes: u16::MAX,
        quadrature_order: u16::MAX,
        table_samples: u16::MAX,
        aspect_count: u16::MAX,
        actuator_lag_s: x,
        actuator_slew_n_per_s: x,
        disc_torsion_factor: x,
        cyclic_factor: x,
        steady_factor: x,
        steady_ramp_s: x,
        slip_step_incipient: x,
        slip_step_gross: x,
        slip_margin_max: x,
        creep_margin_max: x,
        mu_floor_fraction: x,
        untold_lag_s: x,
    };
    vec![
        Request::Hello {
            version: u16::MAX,
            schema_key: u32::MAX,
        },
        Request::Configure(config),
        Request::Sensor(SensorFrame {
            seq: u32::MAX,
            timestamp_us: u64::MAX,
            tangential_force_n: [f32::MAX, f32::MIN],
            torsional_moment_nm: f32::NAN,
            normal_force_n: f32::NEG_INFINITY,
            slip: Default::default(),
        }),
        Request::GetStats,
        Request::ResetStats,
        Request::Shutdown { code: u8::MAX },
    ]
}

/// The widest value of every reply variant.
fn largest_replies() -> Vec<Reply> {
    vec![
        Reply::Hello {
            version: u16::MAX,
            schema_key: u32::MAX,
            max_frame_len: u16::MAX,
        },
        Reply::Configured(Err(WireConfigError {
            param: long_text(32).as_str().try_into().unwrap(),
            message: long_text(96).as_str().try_into().unwrap(),
        })),
        Reply::Command(CommandFrame {
            seq: u32::MAX,
            normal_force_n: f32::MAX,
            n_slip_n: f32::MAX,
            utilisation: f32::MAX,
            status: Status::StaleInput,
            fault_active: true,
            tick_cost: u32::MAX,
            margin: Default::default(),
            load_factor: Default::default(),
            lead_n: Default::default(),
            mu_estimate: Default::default(),
        }),
        Reply::Stats(Stats {
            frames_received: u32::MAX,
            crc_errors: u32::MAX,
            decode_errors: u32::MAX,
            overruns: u32::MAX,
            frames_sent: u32::MAX,
            ticks: u32::MAX,
            worst_tick_cost: u32::MAX,
            last_tick_cost: u32::MAX,
            startup_cost: u32::MAX,
            stack_peak_bytes: u32::MAX,
            cost_unit: CostUnit::Cycles,
            stale_frames: Default::default(),
            idle_ticks: Default::default(),
            command_n: Default::default(),
            fault_active: Default::default(),
        }),
        Reply::NotConfigured { seq: u32::MAX },
        Reply::ShuttingDown { code: u8::MAX },
    ]
}

#[test]
fn max_message_len_is_the_largest_encoding_and_frames_fit() {
    let mut largest = 0;
    for len in largest_requests()
        .iter()
        .map(postcard_of)
        .chain(largest_replies().iter().map(postcard_of))
        .map(|p| p.len())
    {
        assert!(
            len <= MAX_MESSAGE_LEN,
            "a message encodes to {len} > MAX_MESSAGE_LEN = {MAX_MESSAGE_LEN} bytes"
        );
        largest = largest.max(len);
    }
    // Tight: MAX_MESSAGE_LEN (sized from the configuration's field list) is exactly the
    // largest message, so it moves with them; the wire change itself is caught by the
    // schema key's history below.
    assert_eq!(largest, MAX_MESSAGE_LEN);
    assert_eq!(usize::from(MAX_FRAME_LEN_U16), MAX_FRAME_LEN);

    let mut longest_frame = 0;
    for r in largest_requests() {
        let f = frame_of(&r);
        assert!(f.len() <= MAX_FRAME_LEN);
        longest_frame = longest_frame.max(f.len());
        // ... and the default decoder takes it.
        let mut dec = DefaultFrameDecoder::new();
        let got = push_all::<Request, _>(&mut dec, &f);
        assert!(
            matches!(got.as_slice(), [Ok(g)] if same_bits(g, &r)),
            "{got:?}"
        );
    }
    for r in largest_replies() {
        let f = frame_of(&r);
        assert!(f.len() <= MAX_FRAME_LEN);
        longest_frame = longest_frame.max(f.len());
        let mut dec = DefaultFrameDecoder::new();
        assert_eq!(push_all::<Reply, _>(&mut dec, &f), vec![Ok(r)]);
    }
    assert_eq!(longest_frame, MAX_FRAME_LEN);
}

#[test]
fn the_largest_frame_needs_its_whole_buffer() {
    let big = largest_requests().swap_remove(1);
    let mut buf = [0u8; MAX_FRAME_LEN];
    assert_eq!(encode(&big, &mut buf), Ok(MAX_FRAME_LEN));
    for short in 0..MAX_FRAME_LEN {
        let mut buf = vec![0u8; short];
        assert_eq!(
            encode(&big, &mut buf),
            Err(FrameError::BufferTooSmall),
            "{short}"
        );
    }
}

#[test]
fn cobs_bound_holds_for_every_length() {
    // Non-zero bytes are COBS's worst case.
    let data: Vec<u8> = (0..700u32).map(|i| (i % 255 + 1) as u8).collect();
    for n in 0..=data.len() {
        let mut buf = vec![0u8; cobs_max_len(n + CRC_LEN) + 1];
        let len = encode(&Raw(&data[..n]), &mut buf)
            .unwrap_or_else(|e| panic!("payload of {n} bytes: {e}"));
        assert!(len <= cobs_max_len(n + CRC_LEN) + 1, "{n}");
        let mut dec = FrameDecoder::<1024>::new();
        // Read back as a `[u8; 0]`: the frame layer accepts it (COBS and CRC are fine), so
        // only an empty payload is a message; any other is a decode error.
        let decoded: Vec<Result<[u8; 0], _>> = push_all(&mut dec, &buf[..len]);
        let want = if n == 0 {
            Ok([])
        } else {
            Err(FrameError::Deserialize)
        };
        assert_eq!(decoded, vec![want], "{n}");
    }
}

// ---------------------------------------------------------------------------------------
// Round trips
// ---------------------------------------------------------------------------------------

#[test]
fn every_request_round_trips() {
    for r in all_requests().into_iter().chain(largest_requests()) {
        let mut dec = DefaultFrameDecoder::new();
        let got: Vec<Request> = push_all(&mut dec, &frame_of(&r))
            .into_iter()
            .map(Result::unwrap)
            .collect();
        assert_eq!(got.len(), 1);
        assert!(same_bits(&got[0], &r), "{r:?} -> {:?}", got[0]);
        assert_eq!(
            dec.counters(),
            DecoderCounters {
                frames_received: 1,
                ..DecoderCounters::default()
            }
        );
    }
}

#[test]
fn every_reply_round_trips() {
    for r in all_replies().into_iter().chain(largest_replies()) {
        let mut dec = DefaultFrameDecoder::new();
        let got: Vec<Reply> = push_all(&mut dec, &frame_of(&r))
            .into_iter()
            .map(Result::unwrap)
            .collect();
        assert_eq!(got.len(), 1);
        assert!(same_bits(&got[0], &r), "{r:?} -> {:?}", got[0]);
        // Messages without NaN compare equal too.
        let has_nan = matches!(&r, Reply::Command(c) if c.n_slip_n.is_nan());
        if !has_nan {
            assert_eq!(got[0], r);
        }
    }
}

#[test]
fn non_finite_floats_travel_bit_for_bit() {
    let weird_nan = f32::from_bits(0x7FA0_0001); // a signalling NaN with a payload
    let neg_nan = f32::from_bits(0xFFC0_1234);
    let s = SensorFrame {
        seq: 1,
        timestamp_us: 2,
        tangential_force_n: [f32::NAN, weird_nan],
        torsional_moment_nm: f32::INFINITY,
        normal_force_n: neg_nan,
        slip: Default::default(),
    };
    let mut dec = DefaultFrameDecoder::new();
    let got = push_all::<Request, _>(&mut dec, &frame_of(&Request::Sensor(s)));
    let Ok(Request::Sensor(g)) = &got[0] else {
        panic!("{got:?}")
    };
    assert_eq!(g.tangential_force_n[0].to_bits(), f32::NAN.to_bits());
    assert_eq!(g.tangential_force_n[1].to_bits(), 0x7FA0_0001);
    assert_eq!(g.torsional_moment_nm, f32::INFINITY);
    assert_eq!(g.normal_force_n.to_bits(), 0xFFC0_1234);

    let c = ControllerConfig {
        mu: f64::NAN,
        k: f64::INFINITY,
        gamma: f64::NEG_INFINITY,
        safety: f64::from_bits(0x7FF0_0000_0000_0001),
        ..ControllerConfig::default()
    };
    let got = push_all::<Request, _>(&mut dec, &frame_of(&Request::Configure(c)));
    let Ok(Request::Configure(g)) = &got[0] else {
        panic!("{got:?}")
    };
    assert!(g.mu.is_nan());
    assert_eq!(g.k, f64::INFINITY);
    assert_eq!(g.gamma, f64::NEG_INFINITY);
    assert_eq!(g.safety.to_bits(), 0x7FF0_0000_0000_0001);
    assert_eq!(dec.frames_received(), 2);
}

/// What a configuration's bytes decode to: through `Deserialize` (the hand-written
/// binary decoding) or through the derived code (`ControllerConfig::deserialize`), as the
/// configuration's encoding and the number of bytes left, or `None` if refused.
fn config_decodings(bytes: &[u8]) -> [Option<(Vec<u8>, usize)>; 2] {
    let by_trait = postcard::take_from_bytes::<ControllerConfig>(bytes)
        .ok()
        .map(|(c, rest)| (postcard_of(&c), rest.len()));
    let mut de = postcard::Deserializer::from_bytes(bytes);
    let by_derive = ControllerConfig::deserialize(&mut de)
        .ok()
        .and_then(|c| Some((postcard_of(&c), de.finalize().ok()?.len())));
    [by_trait, by_derive]
}

/// The configuration's binary decoding accepts exactly the bytes the derived one accepts,
/// as the same configuration bit for bit: every valid encoding, every truncation of one,
/// every byte of one set to values that matter to varints, tags and variants, and random
/// bytes (below, `arbitrary_bytes_decode_to_the_derived_configuration`).
#[test]
fn the_wire_decodes_a_configuration_as_the_derived_code_does() {
    let mut rng = XorShift(0x5EED_C0F1_6000_0001);
    let mut valid = vec![
        ControllerConfig::default(),
        config_with_skew(),
        ControllerConfig {
            mu: f64::NAN,
            actuator_slew_n_per_s: f64::INFINITY,
            gamma: -0.0,
            force_nodes: 127,
            quadrature_order: 128,
            table_samples: 16_383,
            aspect_count: 16_384,
            ..config_with_skew()
        },
    ];
    for r in largest_requests() {
        if let Request::Configure(c) = r {
            valid.push(c);
        }
    }
    let mut cases = 0;
    for c in &valid {
        let bytes = postcard_of(c);
        let [t, d] = config_decodings(&bytes);
        assert_eq!(t, Some((bytes.clone(), 0)), "{c:?}");
        assert_eq!(d, t);
        let mut long = bytes.clone();
        long.extend([1, 2, 3]);
        assert_eq!(config_decodings(&long)[0], Some((bytes.clone(), 3)));
        for n in 0..bytes.len() {
            let [t, d] = config_decodings(&bytes[..n]);
            assert_eq!((t.is_none(), &d), (true, &t), "truncated to {n}");
            for v in [0u8, 1, 2, 3, 0x7F, 0x80, 0x81, 0xFE, 0xFF] {
                let mut b = bytes.clone();
                b[n] = v;
                let [t, d] = config_decodings(&b);
                assert_eq!(t, d, "byte {n} set to {v:#x}");
                cases += 1;
            }
            for _ in 0..8 {
                let mut b = bytes.clone();
                b[n] = rng.next() as u8;
                let cut = rng.below(b.len() as u64 + 1) as usize;
                let [t, d] = config_decodings(&b[..cut]);
                assert_eq!(t, d, "byte {n} changed, cut at {cut}: {b:?}");
                cases += 1;
            }
        }
    }
    assert!(cases > 3000, "{cases}");
}

#[test]
fn hello_carries_this_builds_constants() {
    assert_eq!(
        Request::hello(),
        Request::Hello {
            version: PROTOCOL_VERSION,
            schema_key: SCHEMA_KEY
        }
    );
    assert_eq!(
        Reply::hello(),
        Reply::Hello {
            version: PROTOCOL_VERSION,
            schema_key: SCHEMA_KEY,
            max_frame_len: MAX_FRAME_LEN_U16
        }
    );
}

// ---------------------------------------------------------------------------------------
// WireConfigError
// ---------------------------------------------------------------------------------------

#[test]
fn wire_config_error_copies_short_errors() {
    let e = ConfigError::OutOfRange {
        param: "mu",
        value: -1.0,
        expected: "a finite number > 0",
    };
    let w = WireConfigError::from_config_error(&e);
    assert_eq!(w.param.as_str(), "mu");
    // The value is not repeated on the wire: the device formats no float (docs/firmware.md).
    assert_eq!(
        w.message.as_str(),
        "mu: out of range, expected a finite number > 0"
    );
    assert_eq!(WireConfigError::from(&e), w);
    assert_eq!(w.to_string(), w.message.as_str());

    let e = ConfigError::NonFinite("k");
    let w = WireConfigError::from_config_error(&e);
    assert_eq!(w.param.as_str(), "k");
    assert_eq!(w.message.as_str(), "k: must be a finite number");
}

/// Integers are written by hand on the wire (no `core::fmt` in the firmware), and read
/// exactly as the errors' `Display` does.
#[test]
fn wire_errors_with_counts_read_as_their_display() {
    for (requested, limit) in [(0, 1), (65, 64), (usize::MAX, 10), (1_000_007, 12)] {
        let e = ConfigError::Capacity {
            param: "force_nodes",
            requested,
            limit,
        };
        let w = WireConfigError::from_config_error(&e);
        assert_eq!(w.message.as_str(), e.to_string());
    }
    let tables = [
        TableError::Size {
            what: "arm_m",
            len: 3,
            expected: 48,
        },
        TableError::Invalid {
            what: "inv_radius",
            index: 1056,
        },
        TableError::Inconsistent {
            check: "arms rise",
            index: 0,
        },
        TableError::Mismatch { param: "n_max" },
    ];
    for t in tables {
        let w = WireConfigError::from_tables_error(&FromTablesError::Tables(t));
        assert_eq!(w.param.as_str(), "tables");
        assert_eq!(w.message.as_str(), t.to_string());
    }
    let e = ConfigError::NonFinite("mu");
    let w = WireConfigError::from_tables_error(&FromTablesError::Config(e));
    assert_eq!(w.param.as_str(), "tables");
    assert_eq!(w.message.as_str(), e.to_string());
}

#[test]
fn wire_config_error_truncates_long_errors_at_char_boundaries() {
    // 40-byte name, and an expectation full of two-byte characters.
    let param = "an_extraordinarily_long_parameter_name_x";
    let expected = "µµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµµ";
    let e = ConfigError::OutOfRange {
        param,
        value: 1e300,
        expected,
    };
    let w = WireConfigError::from_config_error(&e);
    assert_eq!(w.param.as_str(), &param[..32]);
    let full = format!("{param}: out of range, expected {expected}");
    assert!(full.len() > 96);
    assert!(full.starts_with(w.message.as_str()));
    // As long as fits: the next character would not have.
    let next = full[w.message.len()..].chars().next().unwrap();
    assert!(w.message.len() + next.len_utf8() > 96);
    assert!(w.message.len() >= 95);

    // And it crosses the wire intact.
    let r = Reply::Configured(Err(w.clone()));
    let mut dec = DefaultFrameDecoder::new();
    let got = push_all::<Reply, _>(&mut dec, &frame_of(&r));
    assert_eq!(got, vec![Ok(r)]);
}

#[test]
fn over_long_strings_on_the_wire_are_decode_errors() {
    // A `Reply::Configured(Err(..))` whose `param` holds 33 bytes: postcard-valid, CRC-valid,
    // but it does not fit `String<32>`.
    #[derive(Serialize)]
    enum FakeReply {
        _Hello,
        Configured(Result<(), (String, String)>),
    }
    let fake = FakeReply::Configured(Err((long_text(33), "m".into())));
    let mut dec = DefaultFrameDecoder::new();
    let mut stream = frame_of(&fake);
    stream.extend(frame_of(&Reply::NotConfigured { seq: 3 }));
    let got = push_all::<Reply, _>(&mut dec, &stream);
    assert_eq!(
        got,
        vec![
            Err(FrameError::Deserialize),
            Ok(Reply::NotConfigured { seq: 3 })
        ]
    );
    assert_eq!(dec.decode_errors(), 1);
    assert_eq!(dec.crc_errors(), 0);
}

// ---------------------------------------------------------------------------------------
// Streams
// ---------------------------------------------------------------------------------------

fn many_requests(n: u32) -> Vec<Request> {
    (0..n)
        .map(|i| match i % 5 {
            0 => Request::Sensor(sensor(i)),
            1 => Request::Configure(if i % 2 == 0 {
                config_with_skew()
            } else {
                ControllerConfig::default()
            }),
            2 => Request::GetStats,
            3 => Request::Hello {
                version: i as u16,
                schema_key: i.wrapping_mul(0x9E37_79B9),
            },
            _ => Request::ResetStats,
        })
        .collect()
}

fn stream_of(msgs: &[Request]) -> Vec<u8> {
    msgs.iter().flat_map(frame_of).collect()
}

fn assert_all_decoded(got: &[Result<Request, FrameError>], want: &[Request]) {
    assert_eq!(got.len(), want.len());
    for (g, w) in got.iter().zip(want) {
        assert_eq!(g.as_ref(), Ok(w));
    }
}

#[test]
fn a_stream_decodes_in_any_split() {
    let msgs = many_requests(60);
    let stream = stream_of(&msgs);

    // One byte at a time.
    let mut dec = DefaultFrameDecoder::new();
    assert_all_decoded(&push_all(&mut dec, &stream), &msgs);
    assert_eq!(dec.frames_received(), 60);

    // All in one buffer.
    let mut dec = DefaultFrameDecoder::new();
    let got: Vec<_> = dec.frames::<Request>(&stream).collect();
    assert_all_decoded(&got, &msgs);

    // `feed`, in 64-byte reads as from a `[u8; 64]` read buffer.
    let mut dec = DefaultFrameDecoder::new();
    let mut got = Vec::new();
    for chunk in stream.chunks(64) {
        let mut rx = [0u8; 64];
        rx[..chunk.len()].copy_from_slice(chunk);
        dec.feed::<Request>(&rx[..chunk.len()], |m| got.push(Ok(m)));
    }
    assert_all_decoded(&got, &msgs);

    // Random chunk sizes, many times.
    let mut rng = XorShift(0x1234_5678_9ABC_DEF1);
    for _ in 0..200 {
        let sizes: Vec<usize> = (0..50).map(|_| 1 + rng.below(200) as usize).collect();
        let mut dec = DefaultFrameDecoder::new();
        assert_all_decoded(&chunked(&mut dec, &stream, &sizes), &msgs);
        assert_eq!(dec.counters().frames_received, 60);
        assert!(!dec.in_frame());
    }

    // Every two-way split of a shorter stream.
    let msgs = many_requests(8);
    let stream = stream_of(&msgs);
    for cut in 0..=stream.len() {
        let mut dec = DefaultFrameDecoder::new();
        let mut got: Vec<_> = dec.frames::<Request>(&stream[..cut]).collect();
        got.extend(dec.frames::<Request>(&stream[cut..]));
        assert_all_decoded(&got, &msgs);
    }
}

#[test]
fn the_frames_iterator_consumes_lazily() {
    let msgs = many_requests(3);
    let stream = stream_of(&msgs);
    let mut dec = DefaultFrameDecoder::new();
    let first = dec.frames::<Request>(&stream).next();
    assert_eq!(first, Some(Ok(msgs[0].clone())));
    // Only the first frame was consumed; the others are still to come.
    assert_eq!(dec.frames_received(), 1);
    assert!(!dec.in_frame());
}

#[test]
fn empty_frames_are_ignored_and_not_counted() {
    let mut stream = vec![0, 0, 0];
    stream.extend(frame_of(&Request::GetStats));
    stream.extend([0, 0]);
    stream.extend(frame_of(&Request::ResetStats));
    stream.push(0);
    let mut dec = DefaultFrameDecoder::new();
    let got = push_all::<Request, _>(&mut dec, &stream);
    assert_eq!(got, vec![Ok(Request::GetStats), Ok(Request::ResetStats)]);
    assert_eq!(
        dec.counters(),
        DecoderCounters {
            frames_received: 2,
            ..DecoderCounters::default()
        }
    );
}

#[test]
fn every_bit_flip_is_caught_and_the_next_frame_decodes() {
    let before = frame_of(&Request::Sensor(sensor(1)));
    let victim = frame_of(&Request::Sensor(sensor(2)));
    let after = frame_of(&Request::Sensor(sensor(3)));
    let mut crc_seen = 0;
    for pos in 0..victim.len() {
        for bit in 0..8 {
            let mut bad = victim.clone();
            bad[pos] ^= 1 << bit;
            let mut stream = before.clone();
            stream.extend(&bad);
            stream.extend(&after);

            let mut dec = DefaultFrameDecoder::new();
            let got = push_all::<Request, _>(&mut dec, &stream);
            let c = dec.counters();
            let ctx = format!("byte {pos} bit {bit}: {got:?}");
            assert_eq!(got.first(), Some(&Ok(Request::Sensor(sensor(1)))), "{ctx}");
            assert!(!got.contains(&Ok(Request::Sensor(sensor(2)))), "{ctx}");
            assert_eq!(
                c.frames_received,
                got.iter().filter(|r| r.is_ok()).count() as u32
            );
            assert_eq!(c.overruns, 0);
            let errors = c.crc_errors + c.decode_errors;
            if pos == victim.len() - 1 {
                // The delimiter itself: victim and `after` merge into one bad frame.
                assert_eq!((c.frames_received, errors), (1, 1), "{ctx}");
            } else {
                assert_eq!(got.last(), Some(&Ok(Request::Sensor(sensor(3)))), "{ctx}");
                assert_eq!(c.frames_received, 2, "{ctx}");
                // A flip that makes a 0x00 may cut the victim in two bad frames.
                let mut pieces: Vec<&[u8]> = bad.split(|&b| b == 0).collect();
                pieces.pop();
                let pieces = pieces.iter().filter(|p| !p.is_empty()).count() as u32;
                assert_eq!(errors, pieces, "{ctx}");
            }
            crc_seen += c.crc_errors;
        }
    }
    // Flips of data bytes keep COBS valid: those are CRC errors.
    assert!(crc_seen > 8 * (victim.len() as u32) / 2, "{crc_seen}");
}

#[test]
fn truncated_frames_are_dropped() {
    let victim = frame_of(&Request::Configure(ControllerConfig::default()));
    let next = frame_of(&Request::GetStats);
    for keep in 1..victim.len() - 1 {
        // The tail is lost but the delimiter arrives.
        let mut stream = victim[..keep].to_vec();
        stream.push(0);
        stream.extend(&next);
        let mut dec = DefaultFrameDecoder::new();
        let got = push_all::<Request, _>(&mut dec, &stream);
        assert_eq!(got.len(), 2, "{keep}");
        assert!(got[0].is_err(), "{keep}");
        assert_eq!(got[1], Ok(Request::GetStats));
        assert_eq!(dec.crc_errors() + dec.decode_errors(), 1);

        // The head is lost (the receiver starts mid-frame).
        let mut stream = victim[keep..].to_vec();
        stream.extend(&next);
        let mut dec = DefaultFrameDecoder::new();
        let got = push_all::<Request, _>(&mut dec, &stream);
        assert_eq!(got.len(), 2, "{keep}");
        assert!(got[0].is_err(), "{keep}");
        assert_eq!(got[1], Ok(Request::GetStats));
    }
    // Frames too short to hold a CRC.
    for short in [&[0x01u8][..], &[0x02, 0x05], &[0x04, 1, 2, 3]] {
        let mut stream = short.to_vec();
        stream.push(0);
        stream.extend(&next);
        let mut dec = DefaultFrameDecoder::new();
        let got = push_all::<Request, _>(&mut dec, &stream);
        assert_eq!(got, vec![Err(FrameError::Malformed), Ok(Request::GetStats)]);
        assert_eq!(dec.decode_errors(), 1);
    }
    // Invalid COBS: a code byte pointing past the end of the block.
    let mut dec = DefaultFrameDecoder::new();
    let got = push_all::<Request, _>(&mut dec, &[0x09, 1, 2, 0]);
    assert_eq!(got, vec![Err(FrameError::Malformed)]);
}

#[test]
fn crc_valid_frames_that_are_not_one_message_are_decode_errors() {
    let mut dec = DefaultFrameDecoder::new();
    // No message at all: P is empty, C is the CRC of nothing.
    let empty = reference_frame(&[]);
    // An unknown variant.
    let unknown = reference_frame(&[0x63]);
    // A valid request followed by extra bytes (a `Reply::Stats` read as a request is
    // `GetStats` plus leftovers).
    let trailing = frame_of(&Reply::Stats(stats_sample()));
    let mut stream = empty;
    stream.extend(unknown);
    stream.extend(trailing);
    stream.extend(frame_of(&Request::ResetStats));
    let got = push_all::<Request, _>(&mut dec, &stream);
    assert_eq!(
        got,
        vec![
            Err(FrameError::Deserialize),
            Err(FrameError::Deserialize),
            Err(FrameError::Deserialize),
            Ok(Request::ResetStats)
        ]
    );
    assert_eq!(
        dec.counters(),
        DecoderCounters {
            frames_received: 1,
            crc_errors: 0,
            decode_errors: 3,
            overruns: 0
        }
    );
}

#[test]
fn garbage_bursts_between_frames_are_skipped() {
    let msgs = many_requests(30);
    let mut rng = XorShift(0xC0FF_EE00_1234_5678);
    let mut stream = Vec::new();
    let mut bursts = 0u32;
    for (i, m) in msgs.iter().enumerate() {
        if i % 3 == 1 {
            // Noise on the line, then the sender's flushing 0x00.
            let n = 1 + rng.below(100) as usize;
            stream.extend((0..n).map(|_| rng.next() as u8 | 1));
            stream.push(0);
            bursts += 1;
        }
        if i % 7 == 3 {
            // Noise with zeros of its own.
            stream.extend((0..40).map(|_| rng.next() as u8));
            stream.push(0);
        }
        stream.extend(frame_of(m));
    }
    let mut dec = DefaultFrameDecoder::new();
    let got = push_all::<Request, _>(&mut dec, &stream);
    let ok: Vec<_> = got
        .iter()
        .filter_map(|r| r.as_ref().ok())
        .cloned()
        .collect();
    assert_eq!(ok, msgs);
    let c = dec.counters();
    assert_eq!(c.frames_received, 30);
    assert!(c.crc_errors + c.decode_errors >= bursts);
    assert_eq!(
        c.crc_errors + c.decode_errors + c.overruns,
        (got.len() - 30) as u32
    );
}

#[test]
fn an_oversized_frame_is_one_overrun_and_the_next_frame_decodes() {
    let mut stream = frame_of(&Request::GetStats);
    stream.extend(std::iter::repeat_n(0xAB, 1000));
    stream.push(0);
    stream.extend(frame_of(&Request::Sensor(sensor(9))));
    for sizes in [&[1usize][..], &[7, 64, 13], &[4096]] {
        let mut dec = DefaultFrameDecoder::new();
        let got = chunked::<Request, _>(&mut dec, &stream, sizes);
        assert_eq!(
            got,
            vec![
                Ok(Request::GetStats),
                Err(FrameError::Overrun),
                Ok(Request::Sensor(sensor(9)))
            ]
        );
        assert_eq!(
            dec.counters(),
            DecoderCounters {
                frames_received: 2,
                crc_errors: 0,
                decode_errors: 0,
                overruns: 1
            }
        );
    }
}

#[test]
fn the_buffer_holds_exactly_n_bytes() {
    // GetStats is a 6-byte COBS block plus its delimiter.
    let f = frame_of(&Request::GetStats);
    assert_eq!(f.len(), 7);
    let mut exact = FrameDecoder::<6>::new();
    assert_eq!(push_all(&mut exact, &f), vec![Ok(Request::GetStats)]);
    let mut short = FrameDecoder::<5>::new();
    assert_eq!(
        push_all::<Request, _>(&mut short, &f),
        vec![Err(FrameError::Overrun)]
    );
    assert_eq!(short.overruns(), 1);
    // A zero-capacity decoder overruns on every non-empty frame and never panics.
    let mut none = FrameDecoder::<0>::new();
    let got = push_all::<Request, _>(&mut none, &stream_of(&many_requests(5)));
    assert_eq!(got, vec![Err(FrameError::Overrun); 5]);
}

#[test]
fn clear_and_reset_counters() {
    let f = frame_of(&Request::GetStats);
    let mut dec = DefaultFrameDecoder::new();
    assert!(dec.frames::<Request>(&f[..3]).next().is_none());
    assert!(dec.in_frame());
    dec.clear();
    assert!(!dec.in_frame());
    assert_eq!(push_all(&mut dec, &f), vec![Ok(Request::GetStats)]);
    assert_eq!(dec.frames_received(), 1);
    dec.reset_counters();
    assert_eq!(dec.counters(), DecoderCounters::default());
}

#[test]
fn encode_reports_small_buffers_without_panicking() {
    for r in all_requests() {
        let full = frame_of(&r);
        for n in 0..full.len() {
            let mut buf = vec![0u8; n];
            assert_eq!(encode(&r, &mut buf), Err(FrameError::BufferTooSmall));
        }
        let mut buf = vec![0u8; full.len()];
        assert_eq!(encode(&r, &mut buf), Ok(full.len()));
    }
}

// ---------------------------------------------------------------------------------------
// Schema key
// ---------------------------------------------------------------------------------------

/// Every `(SCHEMA_KEY, golden digest)` the protocol has had, oldest first.
///
/// When `schema_key_is_pinned` fails: if you changed the messages on purpose, update
/// `SCHEMA` in `src/protocol/message.rs` to describe them (that changes `SCHEMA_KEY`), then
/// append the pair the failure prints. Never edit or reuse an old line.
const SCHEMA_HISTORY: &[(u32, u32)] = &[
    // Protocol 1: the first release.
    (0x3fd0_aa18, 0x0827_bcdf),
    // Protocol 2: tick_cost in CommandFrame, stack_peak_bytes in Stats, Shutdown/ShuttingDown.
    (0xc3d4_8d21, 0x7281_1450),
    // Protocol 3: the slip signal in SensorFrame, the μ estimate and margin in
    // CommandFrame, the actuator's lag and slew in ControllerConfig, stale_frames in
    // Stats, the Incompatible reply to a mismatched Hello.
    (0xf871_8816, 0xb90f_1896),
    // Protocol 4: the device ticks its controller through silence; Stats reports
    // idle_ticks, command_n and fault_active; SetPacing/Paced for lockstep simulations.
    (0x4322_0509, 0x83d5_8a64),
    // Protocol 5: the margins in ControllerConfig (disc_torsion_factor to untold_lag_s),
    // the margin's load factor and the actuator lead in CommandFrame.
    (0xd7cf_d0e5, 0xfb09_5d82),
];

/// A fixed value of every variant, encoded: it moves whenever the encoding does.
// Every field of today's `ControllerConfig` is pinned here; one added later takes its
// default (the digest moves anyway, with the encoding), so none needs listing.
#[allow(clippy::needless_update)]
fn golden_digest() -> u32 {
    let config = ControllerConfig {
        mu: 0.8,
        shape: FingerShape::Rect,
        k: 2.0,
        skew: Some(SkewParams {
            delta_over_a: 0.9,
            alpha: 1.1,
            locus_over_a: 0.45,
        }),
        c_m_per_n_gamma: 2.5e-3,
        gamma: 0.5,
        half_length_m: 10e-3,
        safety: 1.3,
        n_min_n: 0.2,
        n_max_n: 20.0,
        rise_rate_n_per_s: 400.0,
        fall_rate_n_per_s: 20.0,
        tick_period_s: 1e-3,
        stale_timeout_s: 20e-3,
        fault_force_n: 10.0,
        force_range_n: 100.0,
        moment_range_nm: 2.0,
        mode: Mode::Table,
        force_nodes: 48,
        quadrature_order: 28,
        table_samples: 48,
        aspect_count: 8,
        actuator_lag_s: Default::default(),
        actuator_slew_n_per_s: Default::default(),
        ..ControllerConfig::DEFAULT
    };
    let requests = [
        Request::Hello {
            version: 1,
            schema_key: 2,
        },
        Request::Configure(config),
        Request::Configure(ControllerConfig {
            shape: FingerShape::Disc,
            skew: None,
            mode: Mode::Ellipse,
            ..config
        }),
        Request::Sensor(sensor(7)),
        Request::GetStats,
        Request::ResetStats,
        Request::Shutdown { code: 5 },
        Request::SetPacing(Pacing::RealTime),
        Request::SetPacing(Pacing::Lockstep),
    ];
    let statuses = [
        Status::Ok,
        Status::Saturated,
        Status::SensorFault,
        Status::StaleInput,
    ];
    let units = [
        CostUnit::Nanoseconds,
        CostUnit::Instructions,
        CostUnit::Cycles,
    ];
    let mut replies = vec![
        Reply::Hello {
            version: 1,
            schema_key: 2,
            max_frame_len: 3,
        },
        Reply::Configured(Ok(())),
        Reply::Configured(Err(wire_error_sample())),
        Reply::NotConfigured { seq: 4 },
        Reply::ShuttingDown { code: 6 },
        Reply::Incompatible {
            version: 9,
            schema_key: 0x1234_5678,
        },
        Reply::Paced(Pacing::RealTime),
        Reply::Paced(Pacing::Lockstep),
    ];
    for (i, status) in statuses.into_iter().enumerate() {
        replies.push(Reply::Command(CommandFrame {
            seq: i as u32,
            normal_force_n: 1.5,
            n_slip_n: 1.25,
            utilisation: 0.5,
            status,
            fault_active: i % 2 == 1,
            tick_cost: 1_000 + 300 * i as u32,
            margin: Default::default(),
            load_factor: Default::default(),
            lead_n: Default::default(),
            mu_estimate: Default::default(),
        }));
    }
    for cost_unit in units {
        replies.push(Reply::Stats(Stats {
            cost_unit,
            ..stats_sample()
        }));
    }
    let mut bytes = Vec::new();
    for r in &requests {
        bytes.extend(frame_of(r));
    }
    for r in &replies {
        bytes.extend(frame_of(r));
    }
    fnv1a_32(&bytes)
}

/// Compiles only while these are all the variants and fields: adding one is a schema
/// change, and breaks this function until `SCHEMA` and `SCHEMA_HISTORY` follow.
#[allow(dead_code)]
fn every_variant_and_field_is_known(req: &Request, rep: &Reply) {
    match req {
        Request::Hello {
            version: _,
            schema_key: _,
        }
        | Request::GetStats
        | Request::ResetStats
        | Request::Shutdown { code: _ } => {}
        Request::SetPacing(pacing) => match pacing {
            Pacing::RealTime | Pacing::Lockstep => {}
        },
        // Its fields are not listed here: `SCHEMA` lists them from the definition
        // (`ControllerConfig::SCHEMA`, `SkewParams::SCHEMA`), so a new one changes the key.
        Request::Configure(ControllerConfig { shape, mode, .. }) => {
            match shape {
                FingerShape::Rect | FingerShape::Disc => {}
            }
            match mode {
                Mode::Ellipse | Mode::Table => {}
            }
        }
        Request::Sensor(SensorFrame {
            seq: _,
            timestamp_us: _,
            tangential_force_n: [_, _],
            torsional_moment_nm: _,
            normal_force_n: _,
            slip,
        }) => match slip {
            SlipSignal::None | SlipSignal::Incipient | SlipSignal::Gross => {}
        },
    }
    match rep {
        Reply::Hello {
            version: _,
            schema_key: _,
            max_frame_len: _,
        }
        | Reply::Configured(Ok(()))
        | Reply::NotConfigured { seq: _ }
        | Reply::ShuttingDown { code: _ }
        | Reply::Incompatible {
            version: _,
            schema_key: _,
        } => {}
        Reply::Paced(pacing) => match pacing {
            Pacing::RealTime | Pacing::Lockstep => {}
        },
        Reply::Configured(Err(WireConfigError {
            param: _,
            message: _,
        })) => {}
        Reply::Command(CommandFrame {
            seq: _,
            normal_force_n: _,
            n_slip_n: _,
            utilisation: _,
            status,
            fault_active: _,
            tick_cost: _,
            mu_estimate: _,
            margin: _,
            load_factor: _,
            lead_n: _,
        }) => match status {
            Status::Ok | Status::Saturated | Status::SensorFault | Status::StaleInput => {}
        },
        Reply::Stats(Stats {
            frames_received: _,
            crc_errors: _,
            decode_errors: _,
            overruns: _,
            frames_sent: _,
            ticks: _,
            worst_tick_cost: _,
            last_tick_cost: _,
            startup_cost: _,
            stack_peak_bytes: _,
            cost_unit,
            stale_frames: _,
            idle_ticks: _,
            command_n: _,
            fault_active: _,
        }) => match cost_unit {
            CostUnit::Nanoseconds | CostUnit::Instructions | CostUnit::Cycles => {}
        },
    }
}

#[test]
fn schema_key_is_pinned() {
    let current = (SCHEMA_KEY, golden_digest());
    let pinned = *SCHEMA_HISTORY.last().unwrap();
    assert_eq!(
        current, pinned,
        "the encoding or SCHEMA changed: current (SCHEMA_KEY, golden digest) = \
         ({:#010x}, {:#010x}). Update SCHEMA in src/protocol/message.rs if the encoding \
         changed, then append the new pair to SCHEMA_HISTORY",
        current.0, current.1
    );
    for (i, a) in SCHEMA_HISTORY.iter().enumerate() {
        for b in &SCHEMA_HISTORY[..i] {
            assert_ne!(a.0, b.0, "a schema key was reused: change SCHEMA");
            assert_ne!(a.1, b.1, "a golden digest came back: check the encoding");
        }
    }
    assert_eq!(SCHEMA_KEY, fnv1a_32(softgrip::protocol::SCHEMA.as_bytes()));
}

#[test]
fn fnv1a_matches_published_vectors() {
    assert_eq!(fnv1a_32(b""), 0x811c_9dc5);
    assert_eq!(fnv1a_32(b"a"), 0xe40c_292c);
    assert_eq!(fnv1a_32(b"foobar"), 0xbf9c_f968);
}

// ---------------------------------------------------------------------------------------
// Properties
// ---------------------------------------------------------------------------------------

fn f32_bits() -> impl Strategy<Value = f32> {
    any::<u32>().prop_map(f32::from_bits)
}

fn f64_bits() -> impl Strategy<Value = f64> {
    any::<u64>().prop_map(f64::from_bits)
}

fn arb_sensor() -> impl Strategy<Value = SensorFrame> {
    (
        any::<u32>(),
        any::<u64>(),
        [f32_bits(), f32_bits()],
        f32_bits(),
        f32_bits(),
    )
        .prop_map(
            |(seq, timestamp_us, tangential_force_n, torsional_moment_nm, normal_force_n)| {
                SensorFrame {
                    seq,
                    timestamp_us,
                    tangential_force_n,
                    torsional_moment_nm,
                    normal_force_n,
                    slip: Default::default(),
                }
            },
        )
}

// Today's fields are drawn here; one added later takes its default.
#[allow(clippy::needless_update)]
fn arb_config() -> impl Strategy<Value = ControllerConfig> {
    (
        prop::array::uniform15(f64_bits()),
        prop::option::of(prop::array::uniform3(f64_bits())),
        any::<bool>(),
        any::<bool>(),
        any::<[u16; 4]>(),
    )
        .prop_map(|(f, skew, disc, table, n)| ControllerConfig {
            mu: f[0],
            shape: if disc {
                FingerShape::Disc
            } else {
                FingerShape::Rect
            },
            k: f[1],
            skew: skew.map(|s| SkewParams {
                delta_over_a: s[0],
                alpha: s[1],
                locus_over_a: s[2],
            }),
            c_m_per_n_gamma: f[2],
            gamma: f[3],
            half_length_m: f[4],
            safety: f[5],
            n_min_n: f[6],
            n_max_n: f[7],
            rise_rate_n_per_s: f[8],
            fall_rate_n_per_s: f[9],
            tick_period_s: f[10],
            stale_timeout_s: f[11],
            fault_force_n: f[12],
            force_range_n: f[13],
            moment_range_nm: f[14],
            mode: if table { Mode::Table } else { Mode::Ellipse },
            force_nodes: n[0],
            quadrature_order: n[1],
            table_samples: n[2],
            aspect_count: n[3],
            actuator_lag_s: Default::default(),
            actuator_slew_n_per_s: Default::default(),
            ..ControllerConfig::DEFAULT
        })
}

fn arb_request() -> impl Strategy<Value = Request> {
    prop_oneof![
        (any::<u16>(), any::<u32>()).prop_map(|(version, schema_key)| Request::Hello {
            version,
            schema_key
        }),
        arb_config().prop_map(Request::Configure),
        arb_sensor().prop_map(Request::Sensor),
        Just(Request::GetStats),
        Just(Request::ResetStats),
        any::<u8>().prop_map(|code| Request::Shutdown { code }),
    ]
}

fn arb_reply() -> impl Strategy<Value = Reply> {
    let status = prop_oneof![
        Just(Status::Ok),
        Just(Status::Saturated),
        Just(Status::SensorFault),
        Just(Status::StaleInput),
    ];
    let unit = prop_oneof![
        Just(CostUnit::Nanoseconds),
        Just(CostUnit::Instructions),
        Just(CostUnit::Cycles),
    ];
    prop_oneof![
        any::<(u16, u32, u16)>().prop_map(|(version, schema_key, max_frame_len)| {
            Reply::Hello {
                version,
                schema_key,
                max_frame_len,
            }
        }),
        Just(Reply::Configured(Ok(()))),
        ("\\PC{0,12}", "\\PC{0,40}").prop_map(|(p, m)| {
            let mut param = heapless::String::new();
            let mut message = heapless::String::new();
            // Keep what fits.
            for c in p.chars() {
                if param.push(c).is_err() {
                    break;
                }
            }
            for c in m.chars() {
                if message.push(c).is_err() {
                    break;
                }
            }
            Reply::Configured(Err(WireConfigError { param, message }))
        }),
        (
            any::<u32>(),
            f32_bits(),
            f32_bits(),
            f32_bits(),
            status,
            any::<bool>(),
            any::<u32>()
        )
            .prop_map(
                |(seq, normal_force_n, n_slip_n, utilisation, status, fault_active, tick_cost)| {
                    Reply::Command(CommandFrame {
                        seq,
                        normal_force_n,
                        n_slip_n,
                        utilisation,
                        status,
                        fault_active,
                        tick_cost,
                        margin: Default::default(),
                        load_factor: Default::default(),
                        lead_n: Default::default(),
                        mu_estimate: Default::default(),
                    })
                }
            ),
        (any::<[u32; 10]>(), unit).prop_map(|(c, cost_unit)| Reply::Stats(Stats {
            frames_received: c[0],
            crc_errors: c[1],
            decode_errors: c[2],
            overruns: c[3],
            frames_sent: c[4],
            ticks: c[5],
            worst_tick_cost: c[6],
            last_tick_cost: c[7],
            startup_cost: c[8],
            stack_peak_bytes: c[9],
            cost_unit,
            stale_frames: Default::default(),
            idle_ticks: Default::default(),
            command_n: Default::default(),
            fault_active: Default::default(),
        })),
        any::<u32>().prop_map(|seq| Reply::NotConfigured { seq }),
        any::<u8>().prop_map(|code| Reply::ShuttingDown { code }),
    ]
}

/// One edit of a valid stream.
#[derive(Debug, Clone)]
enum Edit {
    FlipBit(prop::sample::Index, u8),
    Delete(prop::sample::Index),
    Insert(prop::sample::Index, Vec<u8>),
}

fn arb_edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<prop::sample::Index>(), 0u8..8).prop_map(|(i, b)| Edit::FlipBit(i, b)),
        any::<prop::sample::Index>().prop_map(Edit::Delete),
        (
            any::<prop::sample::Index>(),
            prop_oneof![
                prop::collection::vec(any::<u8>(), 1..40),
                prop::collection::vec(1u8..=255, 1..300),
            ]
        )
            .prop_map(|(i, v)| Edit::Insert(i, v)),
    ]
}

fn apply(stream: &mut Vec<u8>, edit: &Edit) {
    if stream.is_empty() {
        return;
    }
    match edit {
        Edit::FlipBit(i, bit) => {
            let at = i.index(stream.len());
            stream[at] ^= 1 << bit;
        }
        Edit::Delete(i) => {
            stream.remove(i.index(stream.len()));
        }
        Edit::Insert(i, bytes) => {
            let at = i.index(stream.len() + 1);
            stream.splice(at..at, bytes.iter().copied());
        }
    }
}

/// What a decoder with an `n`-byte buffer must report for `stream`: one entry per
/// non-empty delimited segment, `Some(frame)` for a segment that is an intact frame (which
/// must decode to a message re-encoding to exactly that frame), `None` for an error, and
/// whether that error must be an overrun.
fn expected(
    stream: &[u8],
    intact: &HashMap<Vec<u8>, ()>,
    n: usize,
) -> Vec<(Option<Vec<u8>>, bool)> {
    let mut segments: Vec<&[u8]> = stream.split(|&b| b == 0).collect();
    segments.pop(); // after the last delimiter: not delimited (yet)
    segments
        .into_iter()
        .filter(|s| !s.is_empty())
        .map(|s| {
            if s.len() > n {
                (None, true)
            } else {
                let mut f = s.to_vec();
                f.push(0);
                (intact.contains_key(&f).then_some(f), false)
            }
        })
        .collect()
}

fn check_against<const N: usize>(
    stream: &[u8],
    intact: &HashMap<Vec<u8>, ()>,
    sizes: &[usize],
) -> Result<usize, TestCaseError> {
    let mut dec = FrameDecoder::<N>::new();
    let got = chunked::<Request, N>(&mut dec, stream, sizes);
    let want = expected(stream, intact, N);
    prop_assert_eq!(got.len(), want.len());
    let mut good = 0;
    for (g, (w, overrun)) in got.iter().zip(&want) {
        match (g, w) {
            (Ok(m), Some(f)) => {
                prop_assert_eq!(&frame_of(m), f);
                good += 1;
            }
            (Err(e), None) => {
                if *overrun {
                    prop_assert_eq!(*e, FrameError::Overrun);
                } else {
                    prop_assert_ne!(*e, FrameError::Overrun);
                }
            }
            (g, w) => prop_assert!(false, "got {:?}, expected frame {:?}", g, w),
        }
    }
    let c = dec.counters();
    prop_assert_eq!(c.frames_received as usize, good);
    prop_assert_eq!(
        (c.crc_errors + c.decode_errors + c.overruns) as usize,
        got.len() - good
    );
    prop_assert_eq!(c.overruns as usize, want.iter().filter(|(_, o)| *o).count());
    Ok(good)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn arbitrary_bytes_decode_to_the_derived_configuration(
        bytes in prop::collection::vec(
            prop_oneof![4 => any::<u8>(), 1 => Just(0u8), 1 => Just(1u8), 1 => Just(0x80u8)],
            0..240),
    ) {
        let [t, d] = config_decodings(&bytes);
        prop_assert_eq!(t, d);
    }

    #[test]
    fn arbitrary_bytes_never_panic_and_counters_add_up(
        bytes in prop::collection::vec(
            prop_oneof![3 => any::<u8>(), 1 => Just(0u8)], 0..2000),
        sizes in prop::collection::vec(1usize..100, 1..20),
    ) {
        let none = HashMap::new();
        check_against::<{ MAX_FRAME_LEN - 1 }>(&bytes, &none, &sizes)?;
        check_against::<16>(&bytes, &none, &sizes)?;
        // Byte-level pushes of the same stream give the same counters.
        let mut a = DefaultFrameDecoder::new();
        let _ = push_all::<Reply, _>(&mut a, &bytes);
        let mut b = DefaultFrameDecoder::new();
        b.feed::<Reply>(&bytes, |_| {});
        prop_assert_eq!(a.counters(), b.counters());
    }

    #[test]
    fn corrupted_streams_still_yield_every_intact_frame(
        msgs in prop::collection::vec(arb_request(), 1..25),
        edits in prop::collection::vec(arb_edit(), 0..6),
        sizes in prop::collection::vec(1usize..200, 1..20),
    ) {
        let mut intact = HashMap::new();
        let mut stream = Vec::new();
        for m in &msgs {
            let f = frame_of(m);
            stream.extend(&f);
            intact.insert(f, ());
        }
        for e in &edits {
            apply(&mut stream, e);
        }
        let good = check_against::<{ MAX_FRAME_LEN - 1 }>(&stream, &intact, &sizes)?;
        // Each edit spoils at most two frames.
        prop_assert!(good + 2 * edits.len() >= msgs.len(), "{} of {}", good, msgs.len());
        // A small buffer: long frames overrun, the rest still decode.
        check_against::<40>(&stream, &intact, &sizes)?;
    }

    #[test]
    fn replies_round_trip(reply in arb_reply(), lead in prop::bool::ANY) {
        let mut stream = if lead { vec![0] } else { Vec::new() };
        stream.extend(frame_of(&reply));
        let mut dec = DefaultFrameDecoder::new();
        let got = push_all::<Reply, _>(&mut dec, &stream);
        prop_assert_eq!(got.len(), 1);
        let g = got[0].as_ref().map_err(|e| TestCaseError::fail(e.to_string()))?;
        prop_assert!(same_bits(g, &reply));
        prop_assert!(stream.len() <= MAX_FRAME_LEN + 1);
    }
}

// ---------------------------------------------------------------------------------------
// The framing's own COBS against the `cobs` crate, byte for byte.

proptest! {
    #![proptest_config(ProptestConfig::with_cases(4000))]

    /// Any payload (zeros, runs of 254 and 255 non-zero bytes, the empty one) encodes to
    /// exactly the `cobs` crate's block, and decodes back.
    #[test]
    fn own_cobs_encodes_as_the_cobs_crate_does(
        data in prop_oneof![
            proptest::collection::vec(any::<u8>(), 0..600),
            proptest::collection::vec(prop_oneof![Just(0u8), 1u8..=255], 0..600),
            (0usize..3, 250usize..260, 0usize..3).prop_map(|(a, n, b)| {
                let mut v = vec![0u8; a];
                v.extend((0..n).map(|i| (i % 255 + 1) as u8));
                v.extend(vec![0u8; b]);
                v
            }),
        ]
    ) {
        let mut want = vec![0u8; cobs::max_encoding_length(data.len())];
        let want_len = cobs::encode(&data, &mut want);
        let mut got = vec![0u8; cobs_max_len(data.len())];
        got[..data.len()].copy_from_slice(&data);
        let got_len = cobs_encode_in_place(&mut got, data.len()).expect("cobs_max_len suffices");
        prop_assert_eq!(&got[..got_len], &want[..want_len]);
        // A buffer of exactly the block's length suffices; one byte shorter is refused.
        let mut exact = data.clone();
        exact.resize(got_len, 0);
        prop_assert_eq!(cobs_encode_in_place(&mut exact, data.len()), Some(got_len));
        prop_assert_eq!(&exact[..], &want[..want_len]);
        if got_len > data.len() {
            let mut short = data.clone();
            short.resize(got_len - 1, 0);
            prop_assert_eq!(cobs_encode_in_place(&mut short, data.len()), None);
        }
        let mut block = got[..got_len].to_vec();
        let n = cobs_decode_in_place(&mut block).expect("a valid block decodes");
        prop_assert_eq!(&block[..n], &data[..]);
    }

    /// Any zero-free block (what the decoder collects between delimiters) is accepted by
    /// the own decoder exactly when the `cobs` crate accepts it, with the same bytes.
    #[test]
    fn own_cobs_decodes_as_the_cobs_crate_does(
        block in prop_oneof![
            proptest::collection::vec(1u8..=255, 1..400),
            proptest::collection::vec(prop_oneof![1u8..=8, Just(255u8), 1u8..=255], 1..400),
        ]
    ) {
        let mut want = block.clone();
        let want = cobs::decode_in_place(&mut want).ok().map(|n| want[..n].to_vec());
        let mut got = block.clone();
        let got = cobs_decode_in_place(&mut got).map(|n| got[..n].to_vec());
        prop_assert_eq!(got, want);
    }
}
