//! Reading the files the user names, bounded: every file input of `host-sim` (scenes,
//! `--finger` files, table blobs, the firmware ELF) goes through [`read_capped`], so a huge
//! file or an endless one (`/dev/zero`, a FIFO) is refused after reading at most its cap
//! plus one byte, with an error naming the flag and the cap; and the value shortening
//! every error message uses ([`short`], [`short_num`]).

use std::fmt;
use std::io::Read;
use std::path::Path;

/// Largest scene file \[bytes\] (the shipped scenes are below 2 KiB).
pub const SCENE_CAP_BYTES: u64 = 1 << 20;
/// Largest `--finger` file \[bytes\] (a scene or a `[finger]` table).
pub const FINGER_CAP_BYTES: u64 = 1 << 20;
/// Largest table blob \[bytes\] (a blob holds at most 12 × 33 f32 rows and a header: under
/// 2 KiB; `tests/tables_export.rs::the_largest_configuration_fits_blob_max_len`).
pub const BLOB_CAP_BYTES: u64 = 1 << 20;
/// Largest firmware ELF \[bytes\] (the debug build with symbols is under 1 MiB).
pub const ELF_CAP_BYTES: u64 = 64 << 20;

/// A file that could not be read, or was larger than its cap.
#[derive(Debug)]
pub struct InputError {
    /// The flag or argument that named the file (`--finger`, `scene`, ...).
    pub flag: String,
    /// What went wrong, with the path.
    pub message: String,
}

impl fmt::Display for InputError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.flag, self.message)
    }
}

impl std::error::Error for InputError {}

/// `n` bytes for people: `1 MiB`, `64 MiB`, `512 B`.
fn bytes(n: u64) -> String {
    if n >= 1 << 20 && n.is_multiple_of(1 << 20) {
        format!("{} MiB", n >> 20)
    } else if n >= 1 << 10 && n.is_multiple_of(1 << 10) {
        format!("{} KiB", n >> 10)
    } else {
        format!("{n} B")
    }
}

/// Reads at most `cap` bytes of the file at `path`, which the user named with `flag`.
/// A regular file larger than `cap` is refused before reading; anything else (a device,
/// a pipe) is read up to `cap + 1` bytes and refused if it gets there. Costs at most
/// `cap + 1` bytes of memory and reading.
pub fn read_capped(path: &Path, flag: &str, cap: u64) -> Result<Vec<u8>, InputError> {
    let fail = |message: String| InputError {
        flag: flag.to_string(),
        message,
    };
    let shown = short(&path.display().to_string());
    let too_big = || {
        fail(format!(
            "{shown}: larger than the {} this input may have",
            bytes(cap)
        ))
    };
    let file = std::fs::File::open(path).map_err(|e| fail(format!("{shown}: {e}")))?;
    let meta = file.metadata().map_err(|e| fail(format!("{shown}: {e}")))?;
    if meta.is_dir() {
        return Err(fail(format!("{shown}: is a directory")));
    }
    if meta.is_file() && meta.len() > cap {
        return Err(too_big());
    }
    let mut data = Vec::new();
    file.take(cap + 1)
        .read_to_end(&mut data)
        .map_err(|e| fail(format!("{shown}: {e}")))?;
    if data.len() as u64 > cap {
        return Err(too_big());
    }
    Ok(data)
}

/// [`read_capped`] as UTF-8 text.
pub fn read_capped_text(path: &Path, flag: &str, cap: u64) -> Result<String, InputError> {
    let data = read_capped(path, flag, cap)?;
    String::from_utf8(data).map_err(|e| InputError {
        flag: flag.to_string(),
        message: format!(
            "{}: not UTF-8 text (byte {})",
            short(&path.display().to_string()),
            e.utf8_error().valid_up_to()
        ),
    })
}

/// Longest text an error message quotes whole \[chars\].
pub const SHORT_CHARS: usize = 48;

/// `s` as an error message quotes it: whole up to [`SHORT_CHARS`] characters, else its
/// start, `…` and its length.
pub fn short(s: &str) -> String {
    let n = s.chars().count();
    if n <= SHORT_CHARS {
        s.to_string()
    } else {
        let head: String = s.chars().take(SHORT_CHARS - 8).collect();
        format!("{head}… ({n} chars)")
    }
}

/// A number as an error message quotes it: plain between 1e-4 and 1e6 (as Rust prints it,
/// the shortest round-trip form), else in scientific notation (`1e300`, not 301 digits).
pub fn short_num(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 || !v.is_finite() || (1e-4..1e6).contains(&a) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// A core configuration error as the command line reports it: the `flag` the user typed
/// (without the dashes; the caller maps the core's parameter name to it), then
/// [`config_reason`].
pub fn config_error(flag: &str, e: &softgrip::ConfigError) -> String {
    format!("--{flag}: {}", config_reason(e))
}

/// Why a core configuration error refused its parameter, as the tools print it after their
/// name for the parameter: the value shortened ([`short_num`]), a capacity as "below the
/// least" or "above the most".
pub fn config_reason(e: &softgrip::ConfigError) -> String {
    use softgrip::ConfigError as E;
    match *e {
        E::NonFinite(_) => "must be a finite number".into(),
        E::OutOfRange {
            value, expected, ..
        } => format!("{} is out of range, expected {expected}", short_num(value)),
        E::Capacity {
            requested, limit, ..
        } => {
            if requested < limit {
                format!("{requested} is below the least, {limit}")
            } else {
                format!("{requested} is above the most, {limit}")
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_and_text_are_shortened() {
        assert_eq!(short_num(1e300), "1e300");
        assert_eq!(short_num(1e-9), "1e-9");
        assert_eq!(short_num(0.5), "0.5");
        assert_eq!(short_num(-2.5e7), "-2.5e7");
        assert_eq!(short_num(f64::NAN), "NaN");
        let long = "x".repeat(500);
        let s = short(&long);
        assert!(s.chars().count() < 60 && s.ends_with("(500 chars)"), "{s}");
        assert_eq!(short("abc"), "abc");
    }
}
