//! The two lab files (docs/experiments.md): reading them with errors that name the file,
//! line and column, and writing them (the experiments of `host-sim experiment`).
//!
//! - indentation: `normal_force_n,half_width_m`, one row per measurement;
//! - slip onsets: `normal_force_n,tangential_force_n,torsional_moment_nm`, one row per
//!   onset of gross slip (pure force, pure torsion and mixed loads in one file).
//!
//! Fields may be padded with spaces; blank lines and lines starting with `#` are skipped.
//! Forces and the half-width must be finite and > 0 (the normal force, the half-width) or
//! finite (the slip loads, whose signs are ignored: the limit surface is symmetric).
//! Cost: linear in the file's size.

use crate::error::CalibError;

/// The indentation file's header.
pub const INDENTATION_HEADER: &str = "normal_force_n,half_width_m";
/// The slip-onset file's header.
pub const SLIP_HEADER: &str = "normal_force_n,tangential_force_n,torsional_moment_nm";

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

/// The rows of a file with `header` and `N` numeric columns, each checked by `check`
/// (column index, value → reason if bad).
fn parse_rows<const N: usize>(
    file: &str,
    text: &str,
    header: &'static str,
    check: fn(usize, f64) -> Option<&'static str>,
) -> Result<Vec<(usize, [f64; N])>, CalibError> {
    let mut lines = text.lines().enumerate();
    let first = lines.next().map_or("", |(_, l)| l);
    let norm: String = first
        .split(',')
        .map(str::trim)
        .collect::<Vec<_>>()
        .join(",");
    if norm.trim_start_matches('\u{feff}') != header {
        return Err(CalibError::Header {
            file: file.to_string(),
            expected: header,
            found: short(first.trim()),
        });
    }
    let mut rows = Vec::new();
    for (i, line) in lines {
        let t = line.trim();
        if t.is_empty() || t.starts_with('#') {
            continue;
        }
        let cell = |column: usize, message: String| CalibError::Cell {
            file: file.to_string(),
            line: i + 1,
            column,
            message,
        };
        let fields: Vec<&str> = line.split(',').collect();
        if fields.len() != N {
            let column = fields.len().min(N) + 1;
            return Err(cell(
                column.min(fields.len().max(1)),
                format!("{} fields, the header has {N}", fields.len()),
            ));
        }
        let mut row = [0.0; N];
        for (j, (field, slot)) in fields.iter().zip(row.iter_mut()).enumerate() {
            let f = field.trim();
            let v: f64 = f
                .parse()
                .map_err(|_| cell(j + 1, format!("\"{}\" is not a number", short(f))))?;
            if let Some(why) = check(j, v) {
                return Err(cell(j + 1, format!("{f} {why}")));
            }
            *slot = v;
        }
        rows.push((i + 1, row));
    }
    Ok(rows)
}

fn positive_finite(v: f64) -> Option<&'static str> {
    (!(v > 0.0 && v.is_finite())).then_some("must be a finite number > 0")
}

/// Reads an indentation file's `text` (named `file` in errors).
pub fn parse_indentation(file: &str, text: &str) -> Result<Vec<Indentation>, CalibError> {
    let rows = parse_rows::<2>(file, text, INDENTATION_HEADER, |_, v| positive_finite(v))?;
    Ok(rows
        .into_iter()
        .map(|(_, [n, a])| Indentation {
            normal_force_n: n,
            half_width_m: a,
        })
        .collect())
}

/// Reads a slip-onset file's `text` (named `file` in errors). A row with neither a
/// tangential force nor a moment is refused (it is no onset).
pub fn parse_slip(file: &str, text: &str) -> Result<Vec<SlipOnset>, CalibError> {
    let check = |col: usize, v: f64| -> Option<&'static str> {
        if col == 0 {
            positive_finite(v)
        } else {
            (!v.is_finite()).then_some("must be finite")
        }
    };
    let rows = parse_rows::<3>(file, text, SLIP_HEADER, check)?;
    rows.into_iter()
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
        .collect()
}

/// The indentation file for `rows` (shortest round-trip numbers).
pub fn write_indentation(rows: &[Indentation]) -> String {
    let mut s = format!("{INDENTATION_HEADER}\n");
    for r in rows {
        s.push_str(&format!("{},{}\n", r.normal_force_n, r.half_width_m));
    }
    s
}

/// The slip-onset file for `rows`.
pub fn write_slip(rows: &[SlipOnset]) -> String {
    let mut s = format!("{SLIP_HEADER}\n");
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
    fn round_trip() {
        let rows = vec![SlipOnset {
            normal_force_n: 1.5,
            tangential_force_n: 0.1 + 0.2,
            torsional_moment_nm: 1e-3,
        }];
        assert_eq!(parse_slip("s", &write_slip(&rows)).unwrap(), rows);
    }
}
