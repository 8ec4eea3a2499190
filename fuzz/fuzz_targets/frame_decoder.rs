//! The frame decoder on arbitrary bytes, as requests (the device's side) and as replies
//! (the host's side), in reads whose size the first byte chooses. Checks: no panic; every
//! non-empty frame (bytes up to a 0x00) is counted exactly once; every decoded message
//! re-encodes to a frame that decodes to the same bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;
use softgrip::protocol::{encode, DefaultFrameDecoder, Reply, Request, MAX_FRAME_LEN};

fn check<M>(data: &[u8], chunk: usize)
where
    M: serde::Serialize + serde::de::DeserializeOwned,
{
    let mut d = DefaultFrameDecoder::new();
    let mut ok = Vec::new();
    let mut results = 0u32;
    for piece in data.chunks(chunk) {
        for r in d.frames::<M>(piece) {
            results += 1;
            if let Ok(m) = r {
                ok.push(m);
            }
        }
    }
    let c = d.counters();
    assert_eq!(c.frames_received as usize, ok.len());
    assert_eq!(
        c.frames_received + c.crc_errors + c.decode_errors + c.overruns,
        results
    );
    // Frames ended by a delimiter: each non-empty one gave exactly one result.
    let mut ended = 0u32;
    let mut len = 0usize;
    for &b in data {
        if b == 0 {
            ended += u32::from(len > 0);
            len = 0;
        } else {
            len += 1;
        }
    }
    assert_eq!(ended, results);
    for m in &ok {
        let mut buf = [0u8; MAX_FRAME_LEN];
        let n = encode(m, &mut buf).expect("a decoded message re-encodes");
        let mut again = DefaultFrameDecoder::new();
        let back: Vec<M> = buf[..n]
            .iter()
            .filter_map(|&b| again.push::<M>(b))
            .map(|r| r.expect("round trip"))
            .collect();
        assert_eq!(back.len(), 1);
        let mut buf2 = [0u8; MAX_FRAME_LEN];
        let n2 = encode(&back[0], &mut buf2).unwrap();
        assert_eq!(&buf[..n], &buf2[..n2]);
    }
}

fuzz_target!(|data: &[u8]| {
    let Some((&first, rest)) = data.split_first() else {
        return;
    };
    let chunk = usize::from(first % 64) + 1;
    check::<Request>(rest, chunk);
    check::<Reply>(rest, chunk);
});
