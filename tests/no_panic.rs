//! The paths that face the world, driven by proptest in the normal test run: the
//! configuration decoder (postcard bytes of a `ControllerConfig`, as a `Configure` request
//! carries them) into `Controller::new` and ticks, and the whole device loop
//! (`Device::run`: frame decoder, request handling, controller start-up, ticks, replies)
//! over arbitrary byte streams. `tests/protocol.rs` already drives the frame decoder alone
//! with arbitrary and corrupted streams; this is what sits behind it.
//!
//! A panic anywhere fails the test. The machine-checked half of "no panic is reachable from
//! the tick or the frame decoder" is `scripts/no-panic.sh` (the `no-panic` crate on the
//! optimised build); the fuzz targets in `fuzz/` do the same as these at a larger scale.

use proptest::prelude::*;
use softgrip::controller::{
    Controller, ControllerConfig, FingerShape, Libm, Measurement, Micromath, Mode, SkewParams,
    UTILISATION_MAX,
};
use softgrip::device::{Device, NoActuator, NoClock};
use softgrip::protocol::{
    encode, DecoderCounters, DefaultFrameDecoder, Reply, Request, SensorFrame, MAX_FRAME_LEN,
    PROTOCOL_VERSION, SCHEMA_KEY,
};
use std::collections::VecDeque;

/// A byte stream in chunks, and what the device wrote back.
struct Wire {
    input: VecDeque<Vec<u8>>,
    output: Vec<u8>,
}

impl embedded_io::ErrorType for Wire {
    type Error = core::convert::Infallible;
}

impl embedded_io::Read for Wire {
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, Self::Error> {
        // Reads of any size; an empty queue is the end of the stream.
        let Some(chunk) = self.input.front_mut() else {
            return Ok(0);
        };
        let n = chunk.len().min(buf.len());
        buf[..n].copy_from_slice(&chunk[..n]);
        chunk.drain(..n);
        if chunk.is_empty() {
            self.input.pop_front();
        }
        Ok(n)
    }
}

impl embedded_io::Write for Wire {
    fn write(&mut self, buf: &[u8]) -> Result<usize, Self::Error> {
        self.output.extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }
}

fn frame(req: &Request) -> Vec<u8> {
    let mut buf = [0u8; MAX_FRAME_LEN];
    let n = encode(req, &mut buf).unwrap();
    buf[..n].to_vec()
}

/// Runs a fresh device over `chunks` (one read each) to the end of the stream; returns the
/// device, the bytes it wrote, the replies they decode to, and the counters of that decoding.
fn serve(chunks: VecDeque<Vec<u8>>) -> (Device<Libm>, Vec<u8>, Vec<Reply>, DecoderCounters) {
    let mut wire = Wire {
        input: chunks,
        output: Vec::new(),
    };
    let mut device = Device::<Libm>::new();
    device
        .run(&mut wire, &mut NoActuator, &mut NoClock)
        .unwrap();
    let mut decoder = DefaultFrameDecoder::new();
    let mut replies = Vec::new();
    decoder.feed::<Reply>(&wire.output, |r| replies.push(r));
    (device, wire.output, replies, decoder.counters())
}

/// A cheap configuration to start from (ellipse mode, few nodes) and a table-mode one.
fn base_configs() -> [ControllerConfig; 3] {
    [
        ControllerConfig {
            force_nodes: 8,
            ..ControllerConfig::default()
        },
        ControllerConfig {
            mode: Mode::Table,
            force_nodes: 8,
            table_samples: 12,
            aspect_count: 3,
            skew: Some(SkewParams::PAPER),
            ..ControllerConfig::default()
        },
        ControllerConfig {
            shape: FingerShape::Disc,
            gamma: 0.0,
            force_nodes: 4,
            ..ControllerConfig::default()
        },
    ]
}

/// Whether `cfg` lies well inside f32's range: every dimensional field, and each rate
/// limit's step per tick, of magnitude 1e-30 to 1e30, and the skew's `alpha` and
/// `locus_over_a` at most 1e30. `ControllerConfig::validate` checks the fields in f64 only,
/// so [`exercise`] asks for finite `required_n`, `n_slip_n` and `required_force` only of a
/// configuration that fits; beyond, it checks the command and the utilisation alone. (One
/// such configuration, `n_min_n = 1e-300`, was once accepted and ticked with NaN in
/// `required_n` and `n_slip_n`; `Controller::<f32>::new` now refuses it or ticks finite:
/// [`values_beyond_f32_are_accepted`].)
fn fits_f32(cfg: &ControllerConfig) -> bool {
    let fine = |x: f64| (1e-30..=1e30).contains(&x.abs());
    [
        cfg.mu,
        cfg.c_m_per_n_gamma,
        cfg.half_length_m,
        cfg.safety,
        cfg.n_min_n,
        cfg.n_max_n,
        cfg.rise_rate_n_per_s * cfg.tick_period_s,
        cfg.fall_rate_n_per_s * cfg.tick_period_s,
        cfg.fault_force_n,
        cfg.force_range_n,
        cfg.moment_range_nm,
    ]
    .into_iter()
    .all(fine)
        && cfg
            .skew
            .is_none_or(|s| s.alpha <= 1e30 && s.locus_over_a <= 1e30)
}

/// Checks a controller built from decoded bytes: ticks on hostile measurements give a
/// command that is finite and inside `[N_min, N_max]` (as f32) always, and every other
/// output finite when the configuration fits f32.
fn exercise(cfg: ControllerConfig, ticks: &[(u32, u32, u32, u32, u16)]) {
    let built = Controller::<f32, Libm>::new(cfg);
    let Ok(mut c) = built else {
        // Refused: the error names a field of the configuration (or a capacity).
        let e = built.unwrap_err();
        assert!(!e.param().is_empty());
        let _ = e.to_string();
        return;
    };
    let micro = Controller::<f32, Micromath>::new(cfg).unwrap();
    let (lo, hi) = (cfg.n_min_n as f32, cfg.n_max_n as f32);
    let mut t = 0u64;
    for &(fx, fy, mz, nz, dt) in ticks {
        t = t.wrapping_add(u64::from(dt));
        let m = Measurement {
            tangential_force_n: [f32::from_bits(fx), f32::from_bits(fy)],
            torsional_moment_nm: f32::from_bits(mz),
            normal_force_n: f32::from_bits(nz),
            timestamp_us: t,
            slip: Default::default(),
        };
        let o = c.tick(&m);
        assert!(o.command_n.is_finite() && o.command_n >= lo && o.command_n <= hi);
        assert!(o.utilisation >= 0.0 && o.utilisation <= UTILISATION_MAX as f32);
        if !fits_f32(&cfg) {
            continue;
        }
        assert!(
            o.required_n.is_finite() && o.n_slip_n.is_finite(),
            "{cfg:?}: {m:?} -> {o:?}"
        );
        // The pure rule on the same load with the micromath backend: finite for every load
        // within the sensor ranges (beyond them a finite f32 load can overflow: the tick
        // refuses those as sensor faults, `required_force` does not check).
        let (f, mz) = (m.tangential_force_n[0], m.torsional_moment_nm);
        let r = micro.required_force(f, mz, cfg.safety as f32);
        let in_range =
            f.abs() <= cfg.force_range_n as f32 && mz.abs() <= cfg.moment_range_nm as f32;
        if in_range && fits_f32(&cfg) {
            let r = r.unwrap();
            assert!(
                r.force_n.is_finite() && r.force_n >= 0.0,
                "{cfg:?}: ({f}, {mz}) {r:?}"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Arbitrary bytes as a configuration: postcard either refuses them or yields a
    /// configuration that `Controller::new` refuses with a named field or accepts; an
    /// accepted one ticks on raw bit patterns within its bounds.
    #[test]
    fn arbitrary_bytes_as_a_configuration(
        bytes in prop::collection::vec(any::<u8>(), 0..200),
        ticks in prop::collection::vec((any::<u32>(), any::<u32>(), any::<u32>(), any::<u32>(), any::<u16>()), 0..20),
    ) {
        if let Ok((cfg, _)) = postcard::take_from_bytes::<ControllerConfig>(&bytes) {
            exercise(cfg, &ticks);
        }
    }

    /// Valid configurations' encodings with a few bytes overwritten (so that the decoder
    /// succeeds and the values are hostile: NaN, ±∞, subnormal, huge, every enum
    /// discriminant, the table sizes at and beyond their capacities).
    #[test]
    fn mutated_configurations(
        which in 0usize..3,
        edits in prop::collection::vec((any::<prop::sample::Index>(), any::<u8>()), 1..6),
        ticks in prop::collection::vec((any::<u32>(), any::<u32>(), any::<u32>(), any::<u32>(), any::<u16>()), 0..20),
    ) {
        let mut buf = [0u8; 256];
        let mut bytes = postcard::to_slice(&base_configs()[which], &mut buf).unwrap().to_vec();
        for (at, b) in &edits {
            let i = at.index(bytes.len());
            bytes[i] = *b;
        }
        if let Ok((cfg, _)) = postcard::take_from_bytes::<ControllerConfig>(&bytes) {
            exercise(cfg, &ticks);
        }
    }
}

/// One piece of a stream to the device.
#[derive(Debug, Clone)]
enum Piece {
    /// A well-formed request.
    Request(Request),
    /// A well-formed request's frame with one byte changed: XOR with a nonzero mask, so the
    /// byte always differs (an overwrite with the byte's own value left the frame intact,
    /// and the device rightly obeyed it).
    Damaged(Request, prop::sample::Index, u8),
    /// Raw bytes.
    Raw(Vec<u8>),
}

fn arb_measurement_frame() -> impl Strategy<Value = SensorFrame> {
    (
        any::<u32>(),
        any::<u64>(),
        any::<[u32; 4]>(),
        any::<bool>(),
        0.0f32..40.0,
    )
        .prop_map(|(seq, ts, bits, raw, plausible)| SensorFrame {
            seq,
            timestamp_us: ts % 10_000_000,
            tangential_force_n: if raw {
                [f32::from_bits(bits[0]), f32::from_bits(bits[1])]
            } else {
                [plausible, plausible / 3.0]
            },
            torsional_moment_nm: if raw {
                f32::from_bits(bits[2])
            } else {
                plausible / 1000.0
            },
            normal_force_n: if raw {
                f32::from_bits(bits[3])
            } else {
                plausible / 2.0
            },
            slip: Default::default(),
        })
}

fn arb_request() -> impl Strategy<Value = Request> {
    prop_oneof![
        6 => arb_measurement_frame().prop_map(Request::Sensor),
        1 => (0usize..3, any::<u64>()).prop_map(|(i, salt)| {
            let mut cfg = base_configs()[i];
            // Some of them bad.
            match salt % 5 {
                0 => cfg.mu = f64::NAN,
                1 => cfg.force_nodes = (salt % 200) as u16,
                2 => cfg.n_max_n = f64::from_bits(salt),
                _ => {}
            }
            Request::Configure(cfg)
        }),
        1 => Just(Request::GetStats),
        1 => Just(Request::ResetStats),
        1 => Just(Request::hello()),
        1 => any::<u8>().prop_map(|code| Request::Shutdown { code }),
    ]
}

fn arb_piece() -> impl Strategy<Value = Piece> {
    prop_oneof![
        6 => arb_request().prop_map(Piece::Request),
        2 => (arb_request(), any::<prop::sample::Index>(), 1u8..=255)
            .prop_map(|(r, i, b)| Piece::Damaged(r, i, b)),
        2 => prop::collection::vec(any::<u8>(), 0..400).prop_map(Piece::Raw),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// The device loop over any stream, in reads of any size: it never panics, every
    /// reply it writes is a well-formed frame, commands are finite and inside the bounds of
    /// the configuration in force, and it stops reading after a `Shutdown`.
    #[test]
    fn the_device_loop_serves_any_byte_stream(
        pieces in prop::collection::vec(arb_piece(), 1..60),
        chunk in 1usize..200,
    ) {
        let mut bytes = Vec::new();
        let mut shutdown_at = None;
        for p in &pieces {
            match p {
                Piece::Request(r) => {
                    // A shutdown frame that starts on a frame boundary is decoded (one
                    // that garbage runs into is not).
                    let clean = bytes.last().is_none_or(|&b| b == 0);
                    if matches!(r, Request::Shutdown { .. }) && clean && shutdown_at.is_none() {
                        shutdown_at = Some(bytes.len());
                    }
                    bytes.extend(frame(r));
                }
                Piece::Damaged(r, at, mask) => {
                    let mut f = frame(r);
                    let i = at.index(f.len());
                    f[i] ^= *mask;
                    bytes.extend(f);
                }
                Piece::Raw(raw) => bytes.extend(raw),
            }
        }
        let (device, output, replies, c) =
            serve(bytes.chunks(chunk).map(<[u8]>::to_vec).collect());
        // Every reply decodes as one well-formed frame.
        prop_assert_eq!(c.crc_errors + c.decode_errors + c.overruns, 0);
        prop_assert!(!output.is_empty() || replies.is_empty());
        // The command lies within the bounds of whichever accepted configuration is in
        // force; a frame may have been merged with garbage and dropped, so take the union
        // over the valid configurations in the stream.
        let valid: Vec<ControllerConfig> = pieces
            .iter()
            .filter_map(|p| match p {
                Piece::Request(Request::Configure(cfg)) => Some(*cfg),
                _ => None,
            })
            .filter(|cfg| Controller::<f32>::new(*cfg).is_ok())
            .collect();
        let lo = valid.iter().map(|c| c.n_min_n as f32).fold(f32::INFINITY, f32::min);
        let hi = valid.iter().map(|c| c.n_max_n as f32).fold(f32::NEG_INFINITY, f32::max);
        for r in &replies {
            match r {
                Reply::Command(cmd) => {
                    prop_assert!(!valid.is_empty(), "a command without a configuration");
                    prop_assert!(cmd.normal_force_n.is_finite());
                    prop_assert!(cmd.normal_force_n >= lo && cmd.normal_force_n <= hi);
                    prop_assert!(cmd.n_slip_n.is_finite() && cmd.utilisation.is_finite());
                }
                Reply::Hello { version, schema_key, .. } => {
                    prop_assert_eq!((*version, *schema_key), (PROTOCOL_VERSION, SCHEMA_KEY));
                }
                _ => {}
            }
        }
        if shutdown_at.is_some() {
            prop_assert!(device.shutdown_requested().is_some());
            let last_is_shutdown = matches!(replies.last(), Some(Reply::ShuttingDown { .. }));
            prop_assert!(last_is_shutdown, "{:?}", replies.last());
        }
    }
}

/// Found by `mutated_configurations`: `ControllerConfig::validate` checks `N_min > 0` in f64,
/// but an f32 controller precomputed in f32 (the device's default) stores `1e-300` as 0, its
/// grid gets `ln 0` and NaN nodes, and every tick then reports `required_n` and `n_slip_n`
/// as NaN (the command stays finite, at 0 = `N_min` in f32). The same configuration over
/// the wire was accepted by the device, whose `Command` replies then carried NaN. Fixed:
/// `Controller::new` now refuses a grid its precision cannot hold (param `n_min_n`).
#[test]
fn values_beyond_f32_are_accepted() {
    let cfg = ControllerConfig {
        n_min_n: 1e-300,
        shape: FingerShape::Disc,
        gamma: 0.0,
        ..ControllerConfig::default()
    };
    if let Ok(mut c) = Controller::<f32>::new(cfg) {
        let o = c.tick(&Measurement {
            tangential_force_n: [1.0, 0.0],
            torsional_moment_nm: 0.004,
            normal_force_n: 3.0,
            timestamp_us: 1,
            slip: Default::default(),
        });
        assert!(o.required_n.is_finite() && o.n_slip_n.is_finite(), "{o:?}");
    }
}

/// The device's side of `the_device_loop_serves_any_byte_stream`'s damaged frames, walked
/// exhaustively: a `Configure` frame with any one byte changed (every position, masks
/// that flip one bit, a nibble or all eight) is never obeyed (a sensor frame after it gets
/// no command, the device stays unconfigured) and is counted as a CRC, decode or overrun
/// error, and the intact frames that follow it are decoded. A damaged delimiter would merge
/// the frame with the next one into one dropped frame, so each case sends a lone 0 (an
/// empty frame, ignored) after the damaged frame, as a link's resynchronisation would.
#[test]
fn a_configure_frame_with_any_byte_changed_is_counted_and_never_obeyed() {
    let cfg = base_configs()[0];
    let good = frame(&Request::Configure(cfg));
    let sensor = frame(&Request::Sensor(SensorFrame {
        seq: 1,
        timestamp_us: 1_000,
        tangential_force_n: [1.0, 0.0],
        torsional_moment_nm: 0.001,
        normal_force_n: 2.0,
        slip: Default::default(),
    }));
    let mut runs = 0;
    for i in 0..good.len() {
        for mask in [0x01u8, 0x10, 0x80, 0x0f, 0xf0, 0xff] {
            let mut bad = good.clone();
            bad[i] ^= mask;
            let mut bytes = bad;
            bytes.push(0);
            bytes.extend(&sensor);
            bytes.extend(frame(&Request::GetStats));
            let (device, _, replies, _) = serve(VecDeque::from([bytes]));
            assert!(
                device.controller().is_none(),
                "byte {i} ^ {mask:#04x}: the damaged configuration was obeyed"
            );
            assert!(
                !replies.iter().any(|r| matches!(r, Reply::Command(_))),
                "byte {i} ^ {mask:#04x}: a command without a configuration: {replies:?}"
            );
            let Some(Reply::Stats(s)) = replies.last() else {
                panic!("byte {i} ^ {mask:#04x}: no stats reply: {replies:?}");
            };
            assert!(
                s.crc_errors + s.decode_errors + s.overruns >= 1,
                "byte {i} ^ {mask:#04x}: the damaged frame was not counted: {s:?}"
            );
            runs += 1;
        }
    }
    assert_eq!(runs, good.len() * 6);
}
