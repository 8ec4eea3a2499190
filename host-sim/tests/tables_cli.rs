//! `host-sim tables`: the three formats, `verify` on good, corrupt and mismatched blobs,
//! the plots and the sweep; and `fls --plot`.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn host_sim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_host-sim"))
        .args(args)
        .output()
        .unwrap()
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("softgrip-tables-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

#[test]
fn bin_blobs_verify_and_damaged_ones_are_refused_in_one_line() {
    let out = tmp("bin");
    let o = host_sim(&["tables", "--out", s(&out)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let blob = out.join("softgrip_tables.bin");
    let o = host_sim(&["tables", "verify", s(&blob)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("largest deviation"), "{text}");

    // f32 precomputation deviates from an f64 recomputation, but within the tolerance.
    let out32 = tmp("bin32");
    assert!(
        host_sim(&["tables", "--precision", "f32", "--out", s(&out32)])
            .status
            .success()
    );
    let o = host_sim(&["tables", "verify", s(&out32.join("softgrip_tables.bin"))]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(!String::from_utf8_lossy(&o.stdout).contains("deviation 0.00e0"));

    let bytes = std::fs::read(&blob).unwrap();
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        (
            "flip",
            {
                let mut b = bytes.clone();
                b[200] ^= 0x10;
                b
            },
            "CRC",
        ),
        ("short", bytes[..bytes.len() - 9].to_vec(), "declares"),
        (
            "magic",
            {
                let mut b = bytes.clone();
                b[1] = b'X';
                b
            },
            "magic",
        ),
        ("empty", Vec::new(), "too short"),
    ];
    for (name, b, why) in cases {
        let p = out.join(format!("{name}.bin"));
        std::fs::write(&p, b).unwrap();
        let o = host_sim(&["tables", "verify", s(&p)]);
        assert_eq!(o.status.code(), Some(1), "{name}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(why), "{name}: {err}");
    }

    // A well-formed blob whose tables were altered and resealed: a mismatch.
    let mut b = bytes.clone();
    let n = b.len();
    // A byte inside the inverse radii (the body's tail), then a fresh CRC.
    for byte in &mut b[n - 40..n - 36] {
        *byte ^= 0x20;
    }
    let crc = softgrip::protocol::CRC.checksum(&b[..n - 4]);
    b[n - 4..].copy_from_slice(&crc.to_le_bytes());
    let p = out.join("altered.bin");
    std::fs::write(&p, b).unwrap();
    let o = host_sim(&["tables", "verify", s(&p)]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("mismatched") || err.contains("tables:"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&out);
    let _ = std::fs::remove_dir_all(&out32);
}

#[test]
fn rust_and_csv_formats_and_a_finger_file() {
    let out = tmp("rs");
    let o = host_sim(&["tables", "--format", "rust", "--out", s(&out)]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("bytes of tables in flash"));
    let src = std::fs::read_to_string(out.join("softgrip_tables.rs")).unwrap();
    for needle in [
        "pub const CONFIG",
        "static FORCE_N: [f32; 48]",
        "static INV_RADIUS: [[f32; 33]; 8]",
        "pub fn tables()",
    ] {
        assert!(src.contains(needle), "{needle}");
    }
    let scene = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("scenes/dome_skew.toml");
    let o = host_sim(&[
        "tables",
        "--format",
        "csv",
        "--finger",
        s(&scene),
        "--out",
        s(&out),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let nodes = std::fs::read_to_string(out.join("tables_nodes.csv")).unwrap();
    assert_eq!(nodes.lines().count(), 49);
    let dirs = std::fs::read_to_string(out.join("tables_directions.csv")).unwrap();
    // The disc has a single surface: 33 directions.
    assert_eq!(dirs.lines().count(), 34);
    let bad = out.join("bad.toml");
    std::fs::write(&bad, "[finger]\nmu = 0.8\nc = 1e-3\n").unwrap();
    let o = host_sim(&["tables", "--finger", s(&bad), "--out", s(&out)]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("gamma"));
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn plots_and_the_parallel_sweep() {
    let out = tmp("plot");
    let o = host_sim(&["tables", "--out", s(&out), "--plot", "--sweep"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for f in [
        "fls_k.svg",
        "fls_skew.svg",
        "fls_skew_k.svg",
        "fls_locus.svg",
    ] {
        let svg = std::fs::read_to_string(out.join(f)).unwrap();
        assert!(
            svg.starts_with("<svg") && svg.contains("Eq. 10 ellipse"),
            "{f}"
        );
    }
    let sweep = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    assert_eq!(sweep.lines().count(), 1 + 6 * 3 * 4 * 3);
    for line in sweep.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert!(v[4] > 0.0 && v[4].is_finite(), "pitch {line}");
        assert!(v[7] > 0.0 && v[7].is_finite(), "N_req {line}");
    }
    let one = out.join("one.svg");
    let o = host_sim(&["fls", "--shape", "disc", "--plot", s(&one)]);
    assert!(o.status.success());
    assert!(std::fs::read_to_string(&one)
        .unwrap()
        .contains("Eq. 10 ellipse"));
    let _ = std::fs::remove_dir_all(&out);
}
