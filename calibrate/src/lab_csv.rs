//! The two lab files (docs/experiments.md): reading them with errors that name the file,
//! line and column, and writing them (the experiments of `host-sim experiment`).
//!
//! - indentation: `normal_force_n,half_width_m`, one row per measurement;
//! - slip onsets: `normal_force_n,tangential_force_n,torsional_moment_nm`, one row per
//!   onset of gross slip (pure force, pure torsion and mixed loads in one file).
//!
//! Fields may be padded with spaces; blank lines and lines starting with `#` are skipped
//! (before the header too). Two such comment lines record the rig ([`RigRecord`]):
//! `# shape = rect|disc` and `# half_length_m = <m>`; the writers put them right after the
//! header, where a reader that does not know them skips them as comments, and a file
//! without them reads as before.
//! Forces and the half-width must be finite and > 0 (the normal force, the half-width) or
//! finite (the slip loads, whose signs are ignored: the limit surface is symmetric).
//! Cost: linear in the file's size.

use crate::error::CalibError;
use softgrip::controller::FingerShape;

/// The indentation file's header.
pub const INDENTATION_HEADER: &str = "normal_force_n,half_width_m";
/// The slip-onset file's header.
pub const SLIP_HEADER: &str = "normal_force_n,tangential_force_n,torsional_moment_nm";

/// What a file records about the rig: its finger's shape and half-length, each if given.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RigRecord {
    /// `# shape = rect|disc`.
    pub shape: Option<FingerShape>,
    /// `# half_length_m = <m>` \[m\].
    pub half_length_m: Option<f64>,
}

impl RigRecord {
    /// The record of a rig of `shape`, with the half-length on the rectangle only (the
    /// disc has none).
    pub fn of(shape: FingerShape, half_length_m: f64) -> Self {
        Self {
            shape: Some(shape),
            half_length_m: (shape == FingerShape::Rect).then_some(half_length_m),
        }
    }

    /// The comment lines that record it (none for an empty record).
    pub fn lines(&self) -> String {
        let mut s = String::new();
        if let Some(shape) = self.shape {
            s.push_str(&format!("# shape = {}\n", shape.name()));
        }
        if let Some(l) = self.half_length_m {
            s.push_str(&format!("# half_length_m = {l}\n"));
        }
        s
    }

    /// Reads a comment line's `key = value` into the record: `Ok(false)` for a comment
    /// that records nothing, an error (why) for a bad or a second, different value.
    fn read(&mut self, comment: &str) -> Result<bool, String> {
        let Some((key, value)) = comment.split_once('=') else {
            return Ok(false);
        };
        let (key, value) = (key.trim(), value.trim());
        match key {
            "shape" => {
                let shape = FingerShape::from_name(value)
                    .ok_or_else(|| format!("shape: \"{}\" is not rect or disc", short(value)))?;
                set_once(&mut self.shape, shape, "shape", |s| s.name().to_string())
            }
            "half_length_m" => {
                let l: f64 = value
                    .parse()
                    .ok()
                    .filter(|l: &f64| *l > 0.0 && l.is_finite())
                    .ok_or_else(|| {
                        format!(
                            "half_length_m: \"{}\" is not a finite length > 0",
                            short(value)
                        )
                    })?;
                set_once(&mut self.half_length_m, l, "half_length_m", |l| {
                    l.to_string()
                })
            }
            _ => Ok(false),
        }
    }
}

fn set_once<T: PartialEq + Copy>(
    slot: &mut Option<T>,
    v: T,
    key: &str,
    show: impl Fn(T) -> String,
) -> Result<bool, String> {
    match *slot {
        Some(old) if old != v => Err(format!(
            "{key}: {} here, {} on an earlier line",
            show(v),
            show(old)
        )),
        _ => {
            *slot = Some(v);
            Ok(true)
        }
    }
}

/// One indentation measurement.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Indentation {
    /// Normal force `N` \[N\].
    pub normal_force_n: f64,
    /// Contact half-width `a` \[m\].
    pub half_width_m: f64,
}

/// One onset of gross slip: the load at which the finger slid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlipOnset {
    /// Normal force `N` \[N\].
    pub normal_force_n: f64,
    /// Tangential force `|f_t|` \[N\] at the onset.
    pub tangential_force_n: f64,
    /// Torsional moment `|m_n|` [N·m] at the onset.
    pub torsional_moment_nm: f64,
}

/// Which kind of load an onset is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OnsetKind {
    /// `m_n = 0`.
    Force,
    /// `f_t = 0`.
    Torsion,
    /// Both nonzero.
    Mixed,
}

impl SlipOnset {
    /// The onset's kind.
    pub fn kind(&self) -> OnsetKind {
        if self.torsional_moment_nm == 0.0 {
            OnsetKind::Force
        } else if self.tangential_force_n == 0.0 {
            OnsetKind::Torsion
        } else {
            OnsetKind::Mixed
        }
    }
}

fn short(s: &str) -> String {
    if s.chars().count() <= 60 {
        s.to_string()
    } else {
        let head: String = s.chars().take(52).collect();
        format!("{head}…")
    }
}

/// Rows of a file: each with its 1-based line.
type Rows<const N: usize> = Vec<(usize, [f64; N])>;

/// The rows of a file with `header` and `N` numeric columns, each checked by `check`
/// (column index, value → reason if bad), and what its comment lines record of the rig.
fn parse_rows<const N: usize>(
    file: &str,
    text: &str,
    header: &'static str,
    check: fn(usize, f64) -> Option<&'static str>,
) -> Result<(Rows<N>, RigRecord), CalibError> {
    let mut rig = RigRecord::default();
    let mut seen_header = false;
    let mut rows = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let t = line.trim().trim_start_matches('\u{feff}');
        let cell = |column: usize, message: String| CalibError::Cell {
            file: file.to_string(),
            line: i + 1,
            column,
            message,
        };
        if let Some(comment) = t.strip_prefix('#') {
            rig.read(comment).map_err(|m| cell(1, m))?;
            continue;
        }
        if t.is_empty() {
            continue;
        }
        if !seen_header {
            check_header(file, i + 1, t, header)?;
            seen_header = true;
            continue;
        }
        rows.push((i + 1, parse_row(line, check).map_err(|(c, m)| cell(c, m))?));
    }
    if !seen_header {
        check_header(file, 1, "", header)?;
    }
    Ok((rows, rig))
}

fn check_header(
    file: &str,
    line: usize,
    found: &str,
    header: &'static str,
) -> Result<(), CalibError> {
    let norm: String = found
        .split(',')
        .map(str::trim)
        .collect::<Vec<_>>()
        .join(",");
    if norm == header {
        return Ok(());
    }
    Err(CalibError::Header {
        file: file.to_string(),
        line,
        expected: header,
        found: short(found),
    })
}

/// One row's `N` numbers, or the column and why not.
fn parse_row<const N: usize>(
    line: &str,
    check: fn(usize, f64) -> Option<&'static str>,
) -> Result<[f64; N], (usize, String)> {
    let fields: Vec<&str> = line.split(',').collect();
    if fields.len() != N {
        let column = fields.len().min(N) + 1;
        return Err((
            column.min(fields.len().max(1)),
            format!("{} fields, the header has {N}", fields.len()),
        ));
    }
    let mut row = [0.0; N];
    for (j, (field, slot)) in fields.iter().zip(row.iter_mut()).enumerate() {
        let f = field.trim();
        let v: f64 = f
            .parse()
            .map_err(|_| (j + 1, format!("\"{}\" is not a number", short(f))))?;
        if let Some(why) = check(j, v) {
            return Err((j + 1, format!("{f} {why}")));
        }
        *slot = v;
    }
    Ok(row)
}

fn positive_finite(v: f64) -> Option<&'static str> {
    (!(v > 0.0 && v.is_finite())).then_some("must be a finite number > 0")
}

/// Reads an indentation file's `text` (named `file` in errors).
pub fn parse_indentation(file: &str, text: &str) -> Result<Vec<Indentation>, CalibError> {
    Ok(read_indentation(file, text)?.0)
}

/// [`parse_indentation`], and what the file records of the rig.
pub fn read_indentation(
    file: &str,
    text: &str,
) -> Result<(Vec<Indentation>, RigRecord), CalibError> {
    let (rows, rig) = parse_rows::<2>(file, text, INDENTATION_HEADER, |_, v| positive_finite(v))?;
    let rows = rows
        .into_iter()
        .map(|(_, [n, a])| Indentation {
            normal_force_n: n,
            half_width_m: a,
        })
        .collect();
    Ok((rows, rig))
}

/// Reads a slip-onset file's `text` (named `file` in errors). A row with neither a
/// tangential force nor a moment is refused (it is no onset).
pub fn parse_slip(file: &str, text: &str) -> Result<Vec<SlipOnset>, CalibError> {
    Ok(read_slip(file, text)?.0)
}

/// [`parse_slip`], and what the file records of the rig.
pub fn read_slip(file: &str, text: &str) -> Result<(Vec<SlipOnset>, RigRecord), CalibError> {
    let check = |col: usize, v: f64| -> Option<&'static str> {
        if col == 0 {
            positive_finite(v)
        } else {
            (!v.is_finite()).then_some("must be finite")
        }
    };
    let (rows, rig) = parse_rows::<3>(file, text, SLIP_HEADER, check)?;
    let rows = rows
        .into_iter()
        .map(|(line, [n, ft, mn])| {
            if ft == 0.0 && mn == 0.0 {
                return Err(CalibError::Cell {
                    file: file.to_string(),
                    line,
                    column: 2,
                    message: "an onset needs a tangential force or a moment (both are 0)".into(),
                });
            }
            Ok(SlipOnset {
                normal_force_n: n,
                tangential_force_n: ft.abs(),
                torsional_moment_nm: mn.abs(),
            })
        })
        .collect::<Result<_, _>>()?;
    Ok((rows, rig))
}

/// The indentation file for `rows` (shortest round-trip numbers).
pub fn write_indentation(rows: &[Indentation]) -> String {
    write_indentation_on(&RigRecord::default(), rows)
}

/// The indentation file for `rows`, recording `rig` after the header.
pub fn write_indentation_on(rig: &RigRecord, rows: &[Indentation]) -> String {
    let mut s = format!("{INDENTATION_HEADER}\n{}", rig.lines());
    for r in rows {
        s.push_str(&format!("{},{}\n", r.normal_force_n, r.half_width_m));
    }
    s
}

/// The slip-onset file for `rows`.
pub fn write_slip(rows: &[SlipOnset]) -> String {
    write_slip_on(&RigRecord::default(), rows)
}

/// The slip-onset file for `rows`, recording `rig` after the header.
pub fn write_slip_on(rig: &RigRecord, rows: &[SlipOnset]) -> String {
    let mut s = format!("{SLIP_HEADER}\n{}", rig.lines());
    for r in rows {
        s.push_str(&format!(
            "{},{},{}\n",
            r.normal_force_n, r.tangential_force_n, r.torsional_moment_nm
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_cells_name_file_line_and_column() {
        let text = format!("{SLIP_HEADER}\n1,0.5,0\n\n2,abc,0\n");
        let e = parse_slip("slip.csv", &text).unwrap_err().to_string();
        assert_eq!(e, "slip.csv:4:2: \"abc\" is not a number");
        let e = parse_indentation("ind.csv", "normal_force_n,half_width\n").unwrap_err();
        assert!(e.to_string().contains("normal_force_n,half_width_m"), "{e}");
        let e = parse_indentation("ind.csv", &format!("{INDENTATION_HEADER}\n1,-2\n"));
        assert_eq!(
            e.unwrap_err().to_string(),
            "ind.csv:2:2: -2 must be a finite number > 0"
        );
    }

    #[test]
    fn the_rig_is_read_from_comment_lines() {
        let text = format!(
            "# a lab note\n# shape = disc\n{INDENTATION_HEADER}\n# half_length_m = 0.02\n\
             1,0.002\n# free text = 3\n"
        );
        let (rows, rig) = read_indentation("i", &text).unwrap();
        assert_eq!(rows.len(), 1);
        let want = RigRecord {
            shape: Some(FingerShape::Disc),
            half_length_m: Some(0.02),
        };
        assert_eq!(rig, want);
        // Written right after the header, read back; without them a file records nothing.
        let onsets = vec![SlipOnset {
            normal_force_n: 1.0,
            tangential_force_n: 0.8,
            torsional_moment_nm: 0.0,
        }];
        let rect = RigRecord::of(FingerShape::Rect, 0.01);
        let text = write_slip_on(&rect, &onsets);
        assert!(
            text.starts_with(&format!(
                "{SLIP_HEADER}\n# shape = rect\n# half_length_m = 0.01\n"
            )),
            "{text}"
        );
        assert_eq!(read_slip("s", &text).unwrap(), (onsets.clone(), rect));
        let disc = RigRecord::of(FingerShape::Disc, 0.01);
        assert_eq!(disc.lines(), "# shape = disc\n");
        assert_eq!(
            read_slip("s", &write_slip(&onsets)).unwrap().1,
            RigRecord::default()
        );
        for (text, want) in [
            (
                "# shape = cube\n",
                "i:1:1: shape: \"cube\" is not rect or disc",
            ),
            (
                "# half_length_m = -1\n",
                "i:1:1: half_length_m: \"-1\" is not a finite length > 0",
            ),
            (
                "# shape = rect\n# shape = disc\n",
                "i:2:1: shape: disc here, rect on an earlier line",
            ),
            ("# a note\nforce,width\n", "i:2: the header must be"),
        ] {
            let e = read_indentation("i", text).unwrap_err().to_string();
            assert!(e.starts_with(want), "{e}");
        }
    }

    #[test]
    fn round_trip() {
        let rows = vec![SlipOnset {
            normal_force_n: 1.5,
            tangential_force_n: 0.1 + 0.2,
            torsional_moment_nm: 1e-3,
        }];
        assert_eq!(parse_slip("s", &write_slip(&rows)).unwrap(), rows);
    }
}
