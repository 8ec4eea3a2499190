//! `#[no_panic]` wrappers around the paths that face the world. The binary only exists to
//! make the linker check them: each wrapper's guard calls an undefined symbol on unwinding,
//! and the link fails unless the optimiser removed every path by which a panic could leave
//! the wrapper. See `scripts/no-panic.sh`.
//!
//! With `--features scan` the attributes are off, the binary links, and
//! `scripts/panic-paths.py` walks the disassembly's call graph from each wrapper to the
//! panic machinery, to show which paths a failed check still has.

#[cfg(not(feature = "scan"))]
use no_panic::no_panic;
use softgrip::controller::{
    Controller, ControllerConfig, Libm, Measurement, Micromath, TickOutput,
};
use softgrip::controller::blob::Blob;
use softgrip::device::{Device, NoActuator, NoClock, SilenceWatch};
use softgrip::protocol::{encode, DefaultFrameDecoder, FrameError, Reply, Request, SensorFrame};
use std::hint::black_box;

/// The tick the firmware runs: f32, libm's square root.
#[cfg_attr(not(feature = "scan"), no_panic)]
#[inline(never)]
fn tick_f32(c: &mut Controller<f32, Libm>, m: &Measurement<f32>) -> TickOutput<f32> {
    c.tick(m)
}

/// The fast-math firmware variant's tick.
#[cfg_attr(not(feature = "scan"), no_panic)]
#[inline(never)]
fn tick_f32_micromath(c: &mut Controller<f32, Micromath>, m: &Measurement<f32>) -> TickOutput<f32> {
    c.tick(m)
}

/// The host's tick (required-force, the simulator's baselines).
#[cfg_attr(not(feature = "scan"), no_panic)]
#[inline(never)]
fn tick_f64(c: &mut Controller<f64, Libm>, m: &Measurement<f64>) -> TickOutput<f64> {
    c.tick(m)
}

/// The pure rule.
#[cfg_attr(not(feature = "scan"), no_panic)]
#[inline(never)]
fn required_force_f32(c: &Controller<f32, Libm>, f: f32, m: f32) -> f32 {
    c.required_force(f, m, 1.3).map_or(0.0, |s| s.force_n)
}

/// The device's frame decoder, one byte at a time, decoding requests.
#[cfg_attr(not(feature = "scan"), no_panic)]
#[inline(never)]
fn decode_request(d: &mut DefaultFrameDecoder, byte: u8) -> Option<Result<Request, FrameError>> {
    d.push::<Request>(byte)
}

/// The host's frame decoder, decoding replies.
#[cfg_attr(not(feature = "scan"), no_panic)]
#[inline(never)]
fn decode_reply(d: &mut DefaultFrameDecoder, byte: u8) -> Option<Result<Reply, FrameError>> {
    d.push::<Reply>(byte)
}

/// A whole received chunk through the decoder (the `frames` iterator the docs show).
#[cfg_attr(not(feature = "scan"), no_panic)]
#[inline(never)]
fn decode_chunk(d: &mut DefaultFrameDecoder, bytes: &[u8]) -> usize {
    d.frames::<Request>(bytes).filter(Result::is_ok).count()
}

/// Encoding a reply into the device's transmit buffer.
#[cfg_attr(not(feature = "scan"), no_panic)]
#[inline(never)]
fn encode_reply(r: &Reply, out: &mut [u8]) -> Result<usize, FrameError> {
    encode(r, out)
}

/// The device's handling of a sensor frame: the tick and the reply.
#[cfg_attr(not(feature = "scan"), no_panic)]
#[inline(never)]
fn device_sensor(d: &mut Device<Libm>, f: SensorFrame) -> Reply {
    d.handle(Request::Sensor(f), &mut NoActuator, &mut NoClock)
}

/// The device's handling of any request, configuration (the whole start-up
/// precomputation) included.
#[cfg_attr(not(feature = "scan"), no_panic)]
#[inline(never)]
fn device_any(d: &mut Device<Libm>, r: Request) -> Reply {
    d.handle(r, &mut NoActuator, &mut NoClock)
}

/// The silence path: the idle ticks due at a timer reading, each ticking the controller
/// and driving the actuator (the firmware's loop between received bytes).
#[cfg_attr(not(feature = "scan"), no_panic)]
#[inline(never)]
fn device_idle(d: &mut Device<Libm>, w: &mut SilenceWatch, now: u32) -> u32 {
    d.idle_ticks_due(w, now, &mut NoActuator)
}

/// Building a controller from a received configuration (validation and precomputation).
#[cfg_attr(not(feature = "scan"), no_panic)]
#[inline(never)]
fn controller_new(cfg: ControllerConfig) -> bool {
    Controller::<f32, Libm>::new(cfg).is_ok()
}

/// Checking a table blob (header, CRC, sizes, monotonicity, arms against inverse arms)
/// and building the controller it holds, as the prebuilt-tables firmware does.
#[cfg_attr(not(feature = "scan"), no_panic)]
#[inline(never)]
fn blob_controller(bytes: &[u8]) -> bool {
    Blob::parse(bytes).is_ok_and(|b| b.controller::<Libm>().is_ok())
}

/// An in-memory serial port for the device loop.
struct Wire<'a> {
    input: &'a [u8],
    output: usize,
}

impl embedded_io::ErrorType for Wire<'_> {
    type Error = core::convert::Infallible;
}

impl embedded_io::Read for Wire<'_> {
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, Self::Error> {
        let n = self.input.len().min(buf.len());
        let (head, tail) = self.input.split_at(n);
        for (b, h) in buf.iter_mut().zip(head) {
            *b = *h;
        }
        self.input = tail;
        Ok(n)
    }
}

impl embedded_io::Write for Wire<'_> {
    fn write(&mut self, buf: &[u8]) -> Result<usize, Self::Error> {
        self.output = self.output.wrapping_add(buf.len());
        Ok(buf.len())
    }
    fn flush(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }
}

/// One `poll` of the device loop: read, decode, handle, encode, write.
#[cfg_attr(not(feature = "scan"), no_panic)]
#[inline(never)]
fn device_poll(d: &mut Device<Libm>, input: &[u8]) -> usize {
    let mut wire = Wire { input, output: 0 };
    match d.poll(&mut wire, &mut NoActuator, &mut NoClock) {
        Ok(n) => n.wrapping_add(wire.output),
        Err(e) => match e {},
    }
}

fn main() {
    let cfg = black_box(ControllerConfig::default());
    let m32 = black_box(Measurement::<f32>::default());
    let m64 = black_box(Measurement::<f64>::default());
    let mut sum = 0.0f64;
    if let Ok(mut c) = Controller::<f32, Libm>::new(cfg) {
        sum += f64::from(tick_f32(&mut c, &m32).command_n);
        sum += f64::from(required_force_f32(&c, black_box(1.0), black_box(0.004)));
    }
    if let Ok(mut c) = Controller::<f32, Micromath>::new(cfg) {
        sum += f64::from(tick_f32_micromath(&mut c, &m32).command_n);
    }
    if let Ok(mut c) = Controller::<f64, Libm>::new(cfg) {
        sum += tick_f64(&mut c, &m64).command_n;
    }
    let mut d = DefaultFrameDecoder::new();
    let bytes: Vec<u8> = black_box(vec![6, 3, 0xa5, 0xa0, 0x2d, 0x41, 0]);
    let mut n = 0usize;
    for &b in &bytes {
        n += usize::from(decode_request(&mut d, b).is_some());
        n += usize::from(decode_reply(&mut d, b).is_some());
    }
    n += decode_chunk(&mut d, &bytes);
    let mut out = [0u8; 200];
    n += encode_reply(&black_box(Reply::hello()), &mut out).unwrap_or(0);
    let mut dev = Device::<Libm>::new();
    let _ = device_any(&mut dev, black_box(Request::Configure(cfg)));
    let frame = SensorFrame {
        seq: 1,
        timestamp_us: 1000,
        tangential_force_n: [1.0, 0.0],
        torsional_moment_nm: 0.004,
        normal_force_n: 3.0,
        slip: Default::default(),
    };
    let _ = device_sensor(&mut dev, black_box(frame));
    n += device_poll(&mut dev, &bytes);
    let mut watch = SilenceWatch::new(black_box(1e9));
    n += device_idle(&mut dev, &mut watch, black_box(5_000_000)) as usize;
    n += usize::from(controller_new(cfg));
    n += usize::from(blob_controller(black_box(&bytes)));
    println!("{sum} {n}");
}
