//! The whole device loop (`Device::run`: decoder, request handling, start-up, ticks,
//! replies) over arbitrary bytes, after a valid configuration so that sensor frames tick.
//! Checks: no panic; every reply the device writes decodes cleanly; commands are finite and
//! inside the configuration's bounds.
#![no_main]

use libfuzzer_sys::fuzz_target;
use softgrip::controller::{ControllerConfig, Libm};
use softgrip::device::{Device, NoActuator, NoClock};
use softgrip::protocol::{encode, DefaultFrameDecoder, Reply, Request, MAX_FRAME_LEN};

struct Wire<'a> {
    input: &'a [u8],
    chunk: usize,
    output: Vec<u8>,
}

impl embedded_io::ErrorType for Wire<'_> {
    type Error = core::convert::Infallible;
}

impl embedded_io::Read for Wire<'_> {
    fn read(&mut self, buf: &mut [u8]) -> Result<usize, Self::Error> {
        let n = self.input.len().min(buf.len()).min(self.chunk);
        buf[..n].copy_from_slice(&self.input[..n]);
        self.input = &self.input[n..];
        Ok(n)
    }
}

impl embedded_io::Write for Wire<'_> {
    fn write(&mut self, buf: &[u8]) -> Result<usize, Self::Error> {
        self.output.extend_from_slice(buf);
        Ok(buf.len())
    }
    fn flush(&mut self) -> Result<(), Self::Error> {
        Ok(())
    }
}

fuzz_target!(|data: &[u8]| {
    let Some((&first, rest)) = data.split_first() else {
        return;
    };
    let cfg = ControllerConfig {
        force_nodes: 8,
        ..ControllerConfig::default()
    };
    let mut stream = vec![0u8; MAX_FRAME_LEN];
    let n = encode(&Request::Configure(cfg), &mut stream).unwrap();
    stream.truncate(n);
    stream.extend_from_slice(rest);
    let mut wire = Wire {
        input: &stream,
        chunk: usize::from(first % 64) + 1,
        output: Vec::new(),
    };
    let mut device = Device::<Libm>::new();
    device
        .run(&mut wire, &mut NoActuator, &mut NoClock)
        .unwrap();
    let mut d = DefaultFrameDecoder::new();
    let mut replies = Vec::new();
    d.feed::<Reply>(&wire.output, |r| replies.push(r));
    let c = d.counters();
    assert_eq!(c.crc_errors + c.decode_errors + c.overruns, 0);
    // Commands from any configuration that arrived later may have other bounds: only the
    // finite checks are universal; the first configuration's bounds hold until another
    // `Configured(Ok)`.
    let mut bounds = Some((cfg.n_min_n as f32, cfg.n_max_n as f32));
    for (i, r) in replies.iter().enumerate() {
        match r {
            Reply::Configured(Ok(())) if i > 0 => bounds = None,
            Reply::Command(cmd) => {
                assert!(cmd.normal_force_n.is_finite());
                if let Some((lo, hi)) = bounds {
                    assert!(cmd.normal_force_n >= lo && cmd.normal_force_n <= hi);
                }
            }
            _ => {}
        }
    }
});
