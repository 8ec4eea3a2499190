//! Link faults end to end: the firmware loop (`softgrip::device::Device`) on its own thread
//! behind a real pseudo-terminal (`PtyLink`), fed a synthetic grasp while the line corrupts,
//! truncates and drops frames, sprays bursts of garbage (short, long enough to overrun the
//! 165-byte receive buffer, terminated or running into the next frame), goes silent, and
//! delivers a frozen sensor's stale frames.
//!
//! Checked at every tick: the device's command is finite, inside `[N_min, N_max]`, and equal
//! bit for bit to a `Controller` called directly with exactly the frames the device decoded,
//! so the state it is in is the documented one (hold the last command; after
//! `stale_timeout_s` worth of bad ticks go, rate-limited, to `fault_force_n`; recover on the
//! next good frame). Checked at the end: every sensor frame is accounted for,
//! `sent = ticks + corrupt + lost`, with the garbage bursts that ended in their own
//! delimiter counted apart (`device errors = corrupt sensor frames + garbage frames`).
//!
//! The link is paced in lockstep (`Pacing::Lockstep`): the device ticks only when a frame
//! arrives, so a silent line changes nothing on it, and a frame that arrives after the
//! silence with a fresh timestamp is a good frame like any other; the stale timeout counts
//! *bad ticks*, and the comparison with the direct controller is exact whatever the host's
//! scheduling. A device paced in real time (the firmware, `Pacing::RealTime`) ticks
//! through silence instead: `host-sim/tests/silence_link.rs`.

use host_sim::link::{pty::PtyLink, Link};
use host_sim::sim::run::run;
use host_sim::sim::scene::Scene;
use softgrip::controller::{Controller, ControllerConfig, Libm, Measurement, Status};
use softgrip::protocol::{encode, Reply, Request, SensorFrame, Stats, MAX_FRAME_LEN};
use std::time::Duration;

/// SplitMix64: a reproducible stream of faults.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
    /// A byte that is not the frame delimiter.
    fn nonzero(&mut self) -> u8 {
        1 + (self.next() % 255) as u8
    }
}

/// The load of a synthetic grasp at tick `i` (1 kHz): lift, twist, a shake, a hold.
fn grasp(i: u32) -> SensorFrame {
    let t = f64::from(i) * 1e-3;
    let lift = 2.0 * (1.0 - (-t / 0.3).exp());
    let twist = if (1.0..2.5).contains(&t) {
        0.02 * (std::f64::consts::PI * (t - 1.0) / 1.5).sin()
    } else {
        0.0
    };
    let shake = if (2.5..3.5).contains(&t) {
        1.5 * (2.0 * std::f64::consts::PI * 4.0 * t).sin()
    } else {
        0.0
    };
    SensorFrame {
        seq: i,
        timestamp_us: 1000 * u64::from(i) + 1,
        tangential_force_n: [(lift + shake) as f32, (0.3 * shake) as f32],
        torsional_moment_nm: twist as f32,
        normal_force_n: (3.0 + lift) as f32,
        slip: Default::default(),
    }
}

fn measurement(f: &SensorFrame) -> Measurement<f32> {
    Measurement {
        tangential_force_n: f.tangential_force_n,
        torsional_moment_nm: f.torsional_moment_nm,
        normal_force_n: f.normal_force_n,
        timestamp_us: f.timestamp_us,
        slip: Default::default(),
    }
}

fn frame_bytes(f: &SensorFrame) -> Vec<u8> {
    let mut buf = [0u8; MAX_FRAME_LEN];
    let len = encode(&Request::Sensor(*f), &mut buf).unwrap();
    buf[..len].to_vec()
}

fn stats(link: &mut PtyLink) -> Stats {
    match link.exchange(&Request::GetStats).unwrap() {
        Reply::Stats(s) => s,
        other => panic!("{other:?}"),
    }
}

/// The plant's ledger.
#[derive(Debug, Default)]
struct Ledger {
    /// Sensor frames the plant meant to deliver (every tick's frame, and the resent ones).
    sent: u64,
    /// Sensor frames the device answered.
    delivered: u64,
    /// Sensor frames damaged on the line (bit flips, truncation, garbage run into them).
    corrupt: u64,
    /// Sensor frames the line swallowed.
    lost: u64,
    /// Garbage bursts that ended in their own delimiter: one device error each.
    garbage_frames: u64,
    /// Of those, bursts longer than the receive buffer (overruns).
    long_bursts: u64,
}

/// Sends one sensor frame and checks the device's answer against the direct controller.
fn deliver(
    link: &mut PtyLink,
    direct: &mut Controller<f32, Libm>,
    cfg: &ControllerConfig,
    f: &SensorFrame,
    ledger: &mut Ledger,
) -> softgrip::protocol::CommandFrame {
    ledger.sent += 1;
    ledger.delivered += 1;
    let reply = link.exchange(&Request::Sensor(*f)).unwrap();
    let Reply::Command(c) = reply else {
        panic!("seq {}: {reply:?}", f.seq)
    };
    // A corrupt frame that slipped through would have been answered, and its reply
    // (another seq) would be read here first.
    assert_eq!(
        c.seq, f.seq,
        "a reply to a frame that should have been dropped"
    );
    let want = direct.tick(&measurement(f));
    assert_eq!(
        c.normal_force_n.to_bits(),
        want.command_n.to_bits(),
        "seq {}",
        f.seq
    );
    assert_eq!(
        c.n_slip_n.to_bits(),
        want.n_slip_n.to_bits(),
        "seq {}",
        f.seq
    );
    assert_eq!(c.utilisation.to_bits(), want.utilisation.to_bits());
    assert_eq!((c.status, c.fault_active), (want.status, want.fault_active));
    let n = f64::from(c.normal_force_n);
    assert!(
        n.is_finite() && n >= cfg.n_min_n * (1.0 - 1e-7) && n <= cfg.n_max_n * (1.0 + 1e-7),
        "seq {}: command {n}",
        f.seq
    );
    c
}

/// The hostile line's session: the device behind its pty, the direct controller it is
/// checked against, the plant's ledger and the fault counts.
struct Hostile {
    cfg: ControllerConfig,
    link: PtyLink,
    direct: Controller<f32, Libm>,
    /// The device's counters before the grasp.
    base: Stats,
    rng: Rng,
    ledger: Ledger,
    last_good: Option<SensorFrame>,
    /// The last command the device answered.
    last_cmd: f32,
    /// Frames with flipped bits, truncated, with garbage run into them, stale duplicates.
    flips: u32,
    cuts: u32,
    merged: u32,
    dups: u32,
    /// Stale frames of the frozen sensor answered so far.
    frozen_seen: u32,
    /// Whether the frozen sensor drove the device into its fault state.
    fault_seen: bool,
}

impl Hostile {
    /// A configured device and a direct controller with the same configuration.
    fn new() -> Self {
        let cfg = ControllerConfig::default();
        let mut link = PtyLink::spawn::<Libm>().unwrap();
        assert_eq!(
            link.exchange(&Request::Configure(cfg)).unwrap(),
            Reply::Configured(Ok(()))
        );
        let direct = Controller::<f32, Libm>::new(cfg).unwrap();
        let base = stats(&mut link);
        Self {
            cfg,
            link,
            direct,
            base,
            rng: Rng(0x11_fa17),
            ledger: Ledger::default(),
            last_good: None,
            last_cmd: cfg.n_min_n as f32,
            flips: 0,
            cuts: 0,
            merged: 0,
            dups: 0,
            frozen_seen: 0,
            fault_seen: false,
        }
    }

    /// Sends `f` intact ([`deliver`]).
    fn deliver(&mut self, f: &SensorFrame) -> softgrip::protocol::CommandFrame {
        deliver(
            &mut self.link,
            &mut self.direct,
            &self.cfg,
            f,
            &mut self.ledger,
        )
    }

    /// Sends `f` intact and takes it as the last good frame.
    fn deliver_good(&mut self, f: &SensorFrame) -> softgrip::protocol::CommandFrame {
        let c = self.deliver(f);
        self.last_good = Some(*f);
        self.last_cmd = c.normal_force_n;
        c
    }

    /// A tick of the dead line (`first`: its first): the plant's frame never arrives.
    fn silent(&mut self, first: bool) {
        self.ledger.sent += 1;
        self.ledger.lost += 1;
        if first {
            std::thread::sleep(Duration::from_millis(50));
            // Nothing happened on the device meanwhile: in lockstep it ticks only on frames.
            let s = stats(&mut self.link);
            assert_eq!(u64::from(s.ticks - self.base.ticks), self.ledger.delivered);
            assert_eq!(s.idle_ticks, 0);
        }
    }

    /// The first frame after the silence.
    fn after_silence(&mut self, f: &SensorFrame) {
        // After 100 ms of silence, a fresh frame is a good frame: a lockstep device
        // does not time the silence (see above).
        let c = self.deliver_good(f);
        assert_eq!(c.status, Status::Ok);
        assert!(!c.fault_active);
    }

    /// A tick of the frozen sensor, in place of `f`.
    fn frozen(&mut self, f: &SensorFrame) {
        // The sensor repeats its last good frame (same timestamp): stale input. The
        // command holds for stale_timeout_s / tick_period_s = 20 bad ticks, then moves
        // to the fault force at the rise rate (0.4 N a tick), fault_active set.
        let stale = SensorFrame {
            seq: f.seq,
            ..self.last_good.unwrap()
        };
        let c = self.deliver(&stale);
        self.frozen_seen += 1;
        assert_eq!(c.status, Status::StaleInput);
        let last_cmd = self.last_cmd;
        if self.frozen_seen < 20 {
            assert!(!c.fault_active);
            assert_eq!(c.normal_force_n.to_bits(), last_cmd.to_bits(), "holds");
        } else {
            assert!(c.fault_active, "fault after 20 stale ticks");
            self.fault_seen = true;
            let step = (c.normal_force_n - last_cmd).abs();
            assert!(step <= 0.4 + 1e-5, "rate-limited: {step}");
            let fault = self.cfg.fault_force_n as f32;
            let towards = (fault - c.normal_force_n).abs() <= (fault - last_cmd).abs();
            assert!(towards, "heads to the fault force");
        }
        self.last_cmd = c.normal_force_n;
    }

    /// The first good frame after the frozen sensor.
    fn after_frozen(&mut self, f: &SensorFrame) {
        let c = self.deliver_good(f);
        assert_eq!((c.status, c.fault_active), (Status::Ok, false), "recovered");
    }

    /// An ordinary tick: `f` is lost, damaged, follows garbage or a stale duplicate, or
    /// arrives intact, at random.
    fn ordinary(&mut self, f: &SensorFrame) {
        let roll = self.rng.unit();
        if roll < 0.04 {
            self.ledger.sent += 1;
            self.ledger.lost += 1;
        } else if roll < 0.09 {
            self.flipped(f);
        } else if roll < 0.13 {
            self.truncated(f);
        } else if roll < 0.16 {
            self.merged_garbage(f);
        } else if roll < 0.19 {
            self.garbage_burst(f);
        } else if roll < 0.21 && self.last_good.is_some() {
            // A duplicate of the last good frame arrives late, then the frame.
            let dup = SensorFrame {
                seq: f.seq,
                ..self.last_good.unwrap()
            };
            let c = self.deliver(&dup);
            assert_eq!(c.status, Status::StaleInput);
            self.dups += 1;
            self.deliver_good(f);
        } else {
            self.deliver_good(f);
        }
    }

    /// Injects `b`, a damaged copy of a sensor frame.
    fn inject_corrupt(&mut self, b: &[u8]) {
        self.link.inject(b).unwrap();
        self.ledger.sent += 1;
        self.ledger.corrupt += 1;
    }

    /// 1 to 3 flipped bits in the block (never making a 0x00: a new delimiter would split
    /// the frame, and frames, not pieces, are counted).
    fn flipped(&mut self, f: &SensorFrame) {
        let mut b = frame_bytes(f);
        for _ in 0..1 + self.rng.below(3) {
            let j = self.rng.below(b.len() - 1);
            let mut bit = self.rng.below(8);
            if b[j] ^ (1 << bit) == 0 {
                bit = (bit + 1) % 8;
            }
            b[j] ^= 1 << bit;
        }
        self.inject_corrupt(&b);
        self.flips += 1;
    }

    /// Truncated: the line drops the tail, the receiver sees the delimiter early.
    fn truncated(&mut self, f: &SensorFrame) {
        let mut b = frame_bytes(f);
        let cut = 1 + self.rng.below(b.len() - 2);
        b.truncate(cut);
        b.push(0);
        self.inject_corrupt(&b);
        self.cuts += 1;
    }

    /// Garbage with no delimiter runs into the frame: one bad (or oversized) frame.
    fn merged_garbage(&mut self, f: &SensorFrame) {
        let rng = &mut self.rng;
        let mut b: Vec<u8> = (0..1 + rng.below(300)).map(|_| rng.nonzero()).collect();
        b.extend(frame_bytes(f));
        self.inject_corrupt(&b);
        self.merged += 1;
    }

    /// A burst of garbage that ends in its own delimiter (short, or longer than the
    /// 165-byte buffer), then the frame, intact.
    fn garbage_burst(&mut self, f: &SensorFrame) {
        let rng = &mut self.rng;
        let len = if rng.below(3) == 0 {
            166 + rng.below(400)
        } else {
            1 + rng.below(165)
        };
        let mut b: Vec<u8> = (0..len).map(|_| rng.nonzero()).collect();
        b.push(0);
        self.link.inject(&b).unwrap();
        self.ledger.garbage_frames += 1;
        self.ledger.long_bursts += u64::from(len > 165);
        self.deliver_good(f);
    }

    /// At the end: every sensor frame is accounted for, on both sides of the line.
    fn check_ledger(mut self) {
        let (base, ledger) = (self.base, &self.ledger);
        let (flips, cuts, merged, dups) = (self.flips, self.cuts, self.merged, self.dups);
        let s = stats(&mut self.link);
        let ticks_done = u64::from(s.ticks - base.ticks);
        let errors = u64::from(
            (s.crc_errors - base.crc_errors)
                + (s.decode_errors - base.decode_errors)
                + (s.overruns - base.overruns),
        );
        eprintln!(
            "{ledger:?}; flips {flips}, truncations {cuts}, merged garbage {merged}, stale \
             duplicates {dups}; device: ticks {ticks_done}, crc {}, decode {}, overruns {}",
            s.crc_errors - base.crc_errors,
            s.decode_errors - base.decode_errors,
            s.overruns - base.overruns
        );
        // Every sensor frame is accounted for.
        assert_eq!(ledger.sent, ledger.delivered + ledger.corrupt + ledger.lost);
        assert_eq!(ticks_done, ledger.delivered);
        assert_eq!(errors, ledger.corrupt + ledger.garbage_frames);
        // Every long burst is exactly one overrun; merged garbage may overrun too.
        assert!(u64::from(s.overruns - base.overruns) >= ledger.long_bursts);
        // Requests the device decoded: the sensor frames it answered and two GetStats (one
        // during the silence, this one).
        assert_eq!(
            u64::from(s.frames_received - base.frames_received),
            ledger.delivered + 2
        );
        // The plant's side saw only clean replies.
        let plant = self.link.counters();
        assert_eq!(plant.crc_errors + plant.decode_errors + plant.overruns, 0);
        assert!(
            flips > 100 && cuts > 100 && merged > 50 && dups > 50,
            "{ledger:?}"
        );
        assert!(ledger.long_bursts > 20 && ledger.garbage_frames > 80);
    }
}

#[test]
fn a_grasp_over_a_hostile_line_stays_in_the_documented_safe_state_and_every_frame_is_counted() {
    let mut line = Hostile::new();
    let ticks = 4000u32;
    let silence = 1500..1600u32; // 100 ms with no frame at all
    let frozen = 2600..2660u32; // a frozen sensor: the last good frame, again and again
    for i in 0..ticks {
        let f = grasp(i);
        if silence.contains(&i) {
            line.silent(i == silence.start);
        } else if i == silence.end {
            line.after_silence(&f);
        } else if frozen.contains(&i) {
            line.frozen(&f);
        } else if i == frozen.end {
            line.after_frozen(&f);
        } else {
            line.ordinary(&f);
        }
    }
    assert!(line.fault_seen);
    line.check_ledger();
}

/// Garbage with no delimiter at all, longer than the buffer, then a clean frame: the device
/// counts one overrun for the merged mess and answers the next frame; the same with a
/// burst of 0x00 bytes (empty frames, ignored, not counted).
#[test]
fn a_flood_of_garbage_is_one_overrun_and_a_flood_of_delimiters_is_nothing() {
    let cfg = ControllerConfig::default();
    let mut link = PtyLink::spawn::<Libm>().unwrap();
    link.exchange(&Request::Configure(cfg)).unwrap();
    let base = stats(&mut link);
    let mut rng = Rng(7);
    let flood: Vec<u8> = (0..20_000).map(|_| rng.nonzero()).collect();
    link.inject(&flood).unwrap();
    link.inject(&[0]).unwrap();
    link.inject(&[0u8; 5000]).unwrap();
    let f = grasp(1);
    let Reply::Command(c) = link.exchange(&Request::Sensor(f)).unwrap() else {
        panic!()
    };
    assert_eq!(c.seq, 1);
    let s = stats(&mut link);
    assert_eq!(s.overruns - base.overruns, 1);
    assert_eq!(s.crc_errors - base.crc_errors, 0);
    assert_eq!(s.decode_errors - base.decode_errors, 0);
    assert_eq!(s.ticks - base.ticks, 1);
}

/// The same over the simulator itself: a lift-and-hold scene whose line flips bits,
/// truncates and drops a tenth of the frames each (the `link_faults` effect writes the
/// damaged bytes onto the pty), with latency and sensor faults. The run's ledger balances,
/// and every command the plant applied is finite and inside `[N_min, N_max]`.
#[test]
fn during_a_scene_every_frame_is_accounted_for_under_heavy_faults() {
    let text = r#"
description = "lift and hold over a very bad line"
duration_s = 1.5
tick_hz = 1000.0
seed = 99
effects = ["gravity", "sensor_noise", "sensor_faults", "link_latency", "link_faults"]

[finger]
mu = 0.8
c = 2.5e-3
gamma = 0.5

[object]
mass_kg = 0.2
com_offset_m = 0.005

[[task]]
kind = "lift"
start_s = 0.2
end_s = 1.0
accel_m_s2 = 3.0

[effect.link_latency]
delay_ticks = 2

[effect.link_faults]
bit_flip_prob = 0.1
truncate_prob = 0.1
drop_prob = 0.1

[effect.sensor_faults]
dropout_prob = 0.05
nan_prob = 0.05

[controller]
n_min_n = 0.5
n_max_n = 15.0
"#;
    let mut scene = Scene::parse(text).unwrap();
    scene.name = "very_bad_line".into();
    let out = run(&scene, "softgrip", None).unwrap();
    let l = &out.summary.link;
    eprintln!("{l:?}");
    assert_eq!(
        l.frames_sent,
        l.frames_received + l.frames_corrupt + l.frames_lost
    );
    assert!(l.frames_corrupt > 200 && l.frames_lost > 100, "{l:?}");
    // The latency line holds its last 2 frames at the end.
    assert_eq!(l.frames_sent + 2, out.summary.ticks);
    for s in &out.samples {
        assert!(
            s.n_cmd_n.is_finite() && s.n_cmd_n >= 0.5 * (1.0 - 1e-7) && s.n_cmd_n <= 15.0,
            "t = {}: {}",
            s.t_s,
            s.n_cmd_n
        );
    }
}
