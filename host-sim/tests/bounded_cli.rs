//! A bounded host (issue 13, item 6, and the host findings of its "Why" list): `simulate`
//! streams its ticks, so its memory does not grow with a scene's duration; every file
//! input is read with a size cap; zero-length scenes, a non-physical `--order` and bad
//! settings are refused with an error naming what the user typed, its value shortened.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

const BIN: &str = env!("CARGO_BIN_EXE_host-sim");

fn scene_text(name: &str) -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(format!("{name}.toml"));
    std::fs::read_to_string(p).unwrap()
}

fn tmp(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("softgrip-bounded-{}-{name}", std::process::id()))
}

/// Runs `host-sim ARGS`, killing it (and failing) if it takes longer than `limit`: a
/// command that hangs on an endless input fails here instead of hanging the suite.
fn run_within(args: &[&str], limit: Duration) -> Output {
    let mut child = Command::new(BIN)
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        if child.try_wait().unwrap().is_some() {
            return child.wait_with_output().unwrap();
        }
        if start.elapsed() > limit {
            let _ = child.kill();
            let _ = child.wait();
            panic!("host-sim {args:?} still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(10));
    }
}

fn run(args: &[&str]) -> (i32, String) {
    let o = run_within(args, Duration::from_secs(120));
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

/// Runs `host-sim simulate SCENE --controller constant --out OUT` with its address space
/// limited to `limit_kib` (`ulimit -v`); whether it succeeded.
fn simulate_under(scene: &Path, out: &Path, limit_kib: u64) -> bool {
    let status = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {limit_kib} && exec \"$0\" \"$@\""))
        .arg(BIN)
        .args(["simulate", scene.to_str().unwrap()])
        .args(["--controller", "constant", "--out", out.to_str().unwrap()])
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .status()
        .unwrap();
    status.success()
}

/// The memory ceiling: find the least address space (to 2 MiB) in which a 10 s scene
/// (10 000 ticks) runs, then run a 1 000 s scene (10⁶ ticks, 100 times longer, a 257 MB
/// CSV) under that ceiling plus 8 MiB. Before streaming, `simulate` reserved 136 bytes a
/// tick up front (136 MB here, 13.6 GB at the 1e8-tick cap) and copied the samples for
/// the plots, so the long scene failed under this ceiling.
#[test]
fn a_100_times_longer_scene_runs_under_the_same_memory_ceiling() {
    let base = scene_text("lift_hold");
    let short = tmp("short.toml");
    let long = tmp("long.toml");
    std::fs::write(
        &short,
        base.replace("duration_s = 3.0", "duration_s = 10.0"),
    )
    .unwrap();
    std::fs::write(
        &long,
        base.replace("duration_s = 3.0", "duration_s = 1000.0"),
    )
    .unwrap();
    let out = tmp("mem-out");
    let (mut lo, mut hi) = (4 * 1024u64, 512 * 1024u64);
    assert!(
        simulate_under(&short, &out, hi),
        "the short scene fails in 512 MiB"
    );
    while hi - lo > 2048 {
        let mid = (lo + hi) / 2;
        if simulate_under(&short, &out, mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    let ceiling = hi + 8 * 1024;
    let ok = simulate_under(&long, &out, ceiling);
    // The scene is named after its file: timeseries_<stem>_constant.csv.
    let csv = std::fs::read_dir(&out).ok().and_then(|d| {
        d.filter_map(|e| e.ok())
            .find(|e| {
                let name = e.file_name().to_string_lossy().into_owned();
                name.starts_with("timeseries_") && name.contains("long")
            })
            .and_then(|e| e.metadata().ok())
            .map(|m| m.len())
    });
    let _ = std::fs::remove_dir_all(&out);
    let _ = std::fs::remove_file(&short);
    let _ = std::fs::remove_file(&long);
    assert!(
        ok,
        "10 s needs {hi} KiB; 1000 s fails under {ceiling} KiB (CSV {csv:?} bytes)"
    );
    // Every tick reached the CSV: a header and 10⁶ rows of about 257 bytes.
    assert!(csv.is_some_and(|n| n > 100_000_000), "{csv:?}");
}

/// Every file input is read with a cap: `/dev/zero` and an oversized file are refused at
/// once (before: `/dev/zero` hung `simulate` and `tables`), naming the input and the cap.
#[test]
fn file_inputs_are_capped_and_dev_zero_fails_fast() {
    let big = tmp("big.toml");
    // A valid scene padded with a comment past the 1 MiB cap.
    let mut text = scene_text("lift_hold");
    text.push('#');
    text.push_str(&"x".repeat(1 << 20));
    text.push('\n');
    std::fs::write(&big, &text).unwrap();
    let big = big.to_str().unwrap().to_string();
    let out = tmp("cap-out");
    let out = out.to_str().unwrap();
    for (args, named, code) in [
        (vec!["simulate", "/dev/zero", "--out", out], "/dev/zero", 2),
        (vec!["simulate", &big, "--out", out], big.as_str(), 2),
        (
            vec!["tables", "--finger", "/dev/zero", "--out", out],
            "--finger",
            2,
        ),
        (
            vec!["tables", "--finger", &big, "--out", out],
            "--finger",
            2,
        ),
        (vec!["tables", "verify", "/dev/zero"], "/dev/zero", 1),
        (vec!["tables", "verify", &big], big.as_str(), 1),
    ] {
        let o = run_within(&args, Duration::from_secs(20));
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(code), "{args:?}: {err}");
        assert!(
            err.contains(named) && err.contains("larger than the 1 MiB"),
            "{args:?}: {err}"
        );
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    }
    let _ = std::fs::remove_file(&big);
    let _ = std::fs::remove_dir_all(out);
}

fn scene_with(name: &str, edit: impl Fn(String) -> String) -> PathBuf {
    let p = tmp(name);
    std::fs::write(&p, edit(scene_text("lift_hold"))).unwrap();
    p
}

/// A scene of zero ticks is refused naming `duration_s` (before: it "held" with a mean
/// force of 0 N).
#[test]
fn a_zero_length_scene_is_refused() {
    let p = scene_with("zero.toml", |t| {
        t.replace("duration_s = 3.0", "duration_s = 1e-4")
    });
    let (code, err) = run(&["simulate", p.to_str().unwrap(), "--out", "/nonexistent"]);
    let _ = std::fs::remove_file(&p);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("duration_s") && err.contains("0 ticks"),
        "{err}"
    );
}

/// A bad `controller.constant_force_n` is reported on that key (before: "unknown
/// controller \"constant\"").
#[test]
fn a_bad_constant_force_names_its_key() {
    for value in ["-1.0", "0.0"] {
        let p = scene_with("constant.toml", |t| {
            t.replace(
                "[controller]\n",
                &format!("[controller]\nconstant_force_n = {value}\n"),
            )
        });
        for controller in ["constant", "fixed-torsion"] {
            let (code, err) = run(&[
                "simulate",
                p.to_str().unwrap(),
                "--controller",
                controller,
                "--out",
                tmp("constant-out").to_str().unwrap(),
            ]);
            assert_eq!(code, 2, "{err}");
            assert!(
                err.contains("controller.constant_force_n") && !err.contains("unknown"),
                "{err}"
            );
        }
        let _ = std::fs::remove_file(&p);
    }
    let _ = std::fs::remove_dir_all(tmp("constant-out"));
}

/// Scene errors name the scene key the user wrote, with its value shortened: a μ that
/// overflows the tick names `finger.mu` (before: `controller: force_range_n`), a
/// degenerate `half_length_m` names it (before: `controller: aspect`).
#[test]
fn scene_errors_name_the_key_the_user_wrote() {
    for (from, to, named, value) in [
        ("mu = 0.8", "mu = 1e-300", "finger.mu", "1e-300"),
        (
            "half_length_m = 0.01",
            "half_length_m = 1e-300",
            "finger.half_length_m",
            "1e-300",
        ),
        (
            "c = 2.5e-3",
            "c = 1e300",
            "finger.c = 1e300",
            "half_length_m",
        ),
    ] {
        let p = scene_with("key.toml", |t| t.replace(from, to));
        let (code, err) = run(&["simulate", p.to_str().unwrap(), "--out", "/nonexistent"]);
        let _ = std::fs::remove_file(&p);
        assert_eq!(code, 2, "{to}: {err}");
        assert!(err.contains(named) && err.contains(value), "{to}: {err}");
        assert!(
            !err.contains("force_range_n:") && !err.contains("aspect") && err.len() < 400,
            "{to}: {err}"
        );
    }
}

/// A `--order` too low for the surface gives `f̃ > 1`, which no load can: refused naming
/// `--order` (before: printed with exit code 0).
#[test]
fn a_non_physical_order_is_refused() {
    for args in [
        vec!["fls", "--order", "4"],
        vec!["fls", "--order", "6", "--format", "json"],
        vec![
            "fls", "--order", "4", "--k", "1", "--skew", "0.999999", "--alpha", "1e3",
        ],
    ] {
        let (code, err) = run(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains("--order") && err.contains("> 1"), "{err}");
    }
    // The default and moderate orders answer.
    for order in ["28", "16"] {
        let (code, err) = run(&["fls", "--order", order]);
        assert_eq!(code, 0, "{order}: {err}");
    }
}

/// `required-force` names the flags the user typed: a μ that overflows the tick names
/// `--mu` (before: `--ft`), an extreme safety names `--safety`, a degenerate length names
/// `--length` (before: `--aspect`, which `required-force` does not have); values are
/// shortened (before: `1e300` printed as 301 digits, `1e-9` as `0.000000001`).
#[test]
fn required_force_errors_name_the_flags_typed() {
    let base = [
        "required-force",
        "--ft",
        "1",
        "--mn",
        "0.004",
        "--c",
        "2.5e-3",
        "--gamma",
        "0.5",
    ];
    for (extra, named, not) in [
        (vec!["--mu", "1e-300"], "--mu 1e-300", "--ft"),
        (
            vec!["--mu", "0.8", "--safety", "1e300"],
            "--safety 1e300",
            "--ft",
        ),
        (
            // Ellipse mode's inscribed ellipse needs the aspect sampled.
            vec!["--mu", "0.8", "--length", "1e-300", "--mode", "ellipse"],
            "--length",
            "--aspect",
        ),
        (vec!["--mu", "0.8", "--length", "1e300"], "--length", "--ft"),
        (
            vec![
                "--mu", "0.8", "--n-min", "1e-9", "--n-max", "1e6", "--length", "1e-20",
            ],
            "--n-min: 1e-9",
            "0.000000001",
        ),
    ] {
        let mut args = base.to_vec();
        args.extend(extra);
        let (code, err) = run(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(named) && !err.contains(not), "{args:?}: {err}");
        assert!(err.len() < 300, "{err}");
    }
    // fls: shortened values too.
    let (code, err) = run(&["fls", "--aspect", "1e300"]);
    assert_eq!(code, 2);
    assert!(err.contains("--aspect: 1e300") && err.len() < 200, "{err}");
}

/// Baselines run in this process: `--link qemu` or `direct` with only baselines is an
/// error, not a silent in-process run (issue 15).
#[test]
fn a_link_with_only_baselines_is_refused() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/lift_hold.toml");
    for link in ["qemu", "direct"] {
        let (code, err) = run(&[
            "simulate",
            scene.to_str().unwrap(),
            "--link",
            link,
            "--controller",
            "constant",
            "--out",
            "/nonexistent",
        ]);
        assert_eq!(code, 2, "{err}");
        assert!(err.contains("--link") && err.contains("constant"), "{err}");
    }
}

/// A file QEMU could not boot is refused before QEMU starts, in one line saying what is
/// wrong with it (it used to end in "serial link: Broken pipe").
#[test]
fn a_bad_firmware_elf_is_named_and_explained() {
    let text = tmp("not-an-elf.bin");
    std::fs::write(&text, b"not an elf at all").unwrap();
    let out = tmp("bad-elf-out");
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/lift_hold.toml");
    let scene = scene.to_str().unwrap();
    let host_elf = BIN; // an ELF, but for this machine, not the Cortex-M4F
    for (firmware, why) in [
        (text.to_str().unwrap(), "is not an ELF file"),
        (host_elf, "not the 32-bit Arm Cortex-M4F"),
    ] {
        let (code, err) = run(&[
            "simulate",
            scene,
            "--link",
            "qemu",
            "--firmware",
            firmware,
            "--out",
            out.to_str().unwrap(),
        ]);
        assert_eq!(code, 2, "{firmware}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains("--firmware") && err.contains(why), "{err}");
        assert!(!err.contains("Broken pipe"), "{err}");
    }
    let _ = std::fs::remove_file(&text);
}
