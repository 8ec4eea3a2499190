//! The two margin files (docs/experiments.md): cyclic loading and sustained loads at
//! fractions of the static onset, read with errors that name the file, line and column,
//! and written (`host-sim experiment cyclic`, `hold`).
//!
//! - cyclic: `axis,normal_force_n,fraction,cycle,tangential_force_n,torsional_moment_nm,
//!   slide_m,turn_rad`, one row per load cycle; `cycle = 0` is the static onset the
//!   fractions refer to (a ramp to gross slip from fresh contacts, `fraction = 1`);
//! - hold: `axis,normal_force_n,fraction,tangential_force_n,torsional_moment_nm,time_s,
//!   slide_m,turn_rad,slide_rate_m_s,turn_rate_rad_s`, one row per sustained load;
//!   `time_s` is how long the test lasted, ramp included (less than the ramp and hold
//!   when the plate slid off), and 0 for an onset row.
//!
//! `axis` is `force` (the load across the cylinder axis) or `torsion` (about the contact
//! normal). Loads, slides and turns are magnitudes (signs ignored). Blank lines and lines
//! starting with `#` are skipped (before the header too); fields may be padded with
//! spaces. Cost: linear in the
//! file's size.

use crate::error::CalibError;

/// The cyclic file's header.
pub const CYCLIC_HEADER: &str = "axis,normal_force_n,fraction,cycle,tangential_force_n,\
                                 torsional_moment_nm,slide_m,turn_rad";
/// The hold file's header.
pub const HOLD_HEADER: &str = "axis,normal_force_n,fraction,tangential_force_n,\
                               torsional_moment_nm,time_s,slide_m,turn_rad,slide_rate_m_s,\
                               turn_rate_rad_s";

/// Which load a margin test applies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Axis {
    /// A tangential force across the cylinder axis.
    Force,
    /// A moment about the contact normal.
    Torsion,
}

impl Axis {
    /// The file's spelling.
    pub fn name(self) -> &'static str {
        match self {
            Axis::Force => "force",
            Axis::Torsion => "torsion",
        }
    }

    fn parse(s: &str) -> Option<Self> {
        match s {
            "force" => Some(Axis::Force),
            "torsion" => Some(Axis::Torsion),
            _ => None,
        }
    }
}

/// One row of the cyclic file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CyclicRow {
    /// The load's axis.
    pub axis: Axis,
    /// Normal force `N` \[N\].
    pub normal_force_n: f64,
    /// The cycles' peak as a fraction of the measured onset (1 for an onset row).
    pub fraction: f64,
    /// The cycle, from 1; 0 for the onset.
    pub cycle: usize,
    /// The peak tangential force \[N\] (the onset's for `cycle = 0`).
    pub tangential_force_n: f64,
    /// The peak moment [N·m] (the onset's for `cycle = 0`).
    pub torsional_moment_nm: f64,
    /// How far the plate slid over the cycle \[m\] (load back at 0 to load back at 0).
    pub slide_m: f64,
    /// How far it turned over the cycle \[rad\].
    pub turn_rad: f64,
}

impl CyclicRow {
    /// The load on the row's axis: the force \[N\] or the moment [N·m].
    pub fn load(&self) -> f64 {
        match self.axis {
            Axis::Force => self.tangential_force_n,
            Axis::Torsion => self.torsional_moment_nm,
        }
    }
}

/// One row of the hold file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HoldRow {
    /// The load's axis.
    pub axis: Axis,
    /// Normal force `N` \[N\].
    pub normal_force_n: f64,
    /// The held load as a fraction of the measured onset (1 for an onset row).
    pub fraction: f64,
    /// The held tangential force \[N\] (the onset's for `time_s = 0`).
    pub tangential_force_n: f64,
    /// The held moment [N·m] (the onset's for `time_s = 0`).
    pub torsional_moment_nm: f64,
    /// How long the test lasted, ramp included \[s\]; 0 for an onset row.
    pub time_s: f64,
    /// How far the plate slid over the hold \[m\].
    pub slide_m: f64,
    /// How far it turned over the hold \[rad\].
    pub turn_rad: f64,
    /// The slide's rate at the end of the hold \[m/s\].
    pub slide_rate_m_s: f64,
    /// The turn's rate at the end of the hold \[rad/s\].
    pub turn_rate_rad_s: f64,
}

impl HoldRow {
    /// The load on the row's axis: the force \[N\] or the moment [N·m].
    pub fn load(&self) -> f64 {
        match self.axis {
            Axis::Force => self.tangential_force_n,
            Axis::Torsion => self.torsional_moment_nm,
        }
    }
}

/// A file's data rows: (line, fields), after its header (the first line that is neither
/// blank nor a comment) is checked.
fn rows<'t>(
    file: &str,
    text: &'t str,
    header: &'static str,
) -> Result<Vec<(usize, Vec<&'t str>)>, CalibError> {
    let skipped = |l: &str| {
        let t = l.trim().trim_start_matches('\u{feff}');
        t.is_empty() || t.starts_with('#')
    };
    let mut lines = text.lines().enumerate().filter(|(_, l)| !skipped(l));
    let (at, first) = lines.next().unwrap_or((0, ""));
    let norm: Vec<&str> = first.split(',').map(str::trim).collect();
    if norm.join(",").trim_start_matches('\u{feff}') != header {
        let found: String = first.trim().chars().take(60).collect();
        return Err(CalibError::Cell {
            file: file.to_string(),
            line: at + 1,
            column: 1,
            message: format!("the header must be `{header}` (found `{found}`)"),
        });
    }
    let columns = header.split(',').count();
    let mut out = Vec::new();
    for (i, line) in lines {
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        if fields.len() != columns {
            return Err(CalibError::Cell {
                file: file.to_string(),
                line: i + 1,
                column: fields.len().min(columns),
                message: format!("{} fields, the header has {columns}", fields.len()),
            });
        }
        out.push((i + 1, fields));
    }
    Ok(out)
}

/// Reads one row's fields: the axis, then numbers, each checked.
struct Cells<'a> {
    file: &'a str,
    line: usize,
    fields: &'a [&'a str],
}

impl Cells<'_> {
    fn error(&self, column: usize, message: String) -> CalibError {
        CalibError::Cell {
            file: self.file.to_string(),
            line: self.line,
            column: column + 1,
            message,
        }
    }

    fn axis(&self) -> Result<Axis, CalibError> {
        Axis::parse(self.fields[0]).ok_or_else(|| {
            let f: String = self.fields[0].chars().take(40).collect();
            self.error(0, format!("\"{f}\" is not an axis (force or torsion)"))
        })
    }

    /// Column `j`'s number, finite; `positive`: also > 0. Signs are otherwise dropped.
    fn number(&self, j: usize, positive: bool) -> Result<f64, CalibError> {
        let f = self.fields[j];
        let v: f64 = f.parse().map_err(|_| {
            let short: String = f.chars().take(40).collect();
            self.error(j, format!("\"{short}\" is not a number"))
        })?;
        if positive && !(v > 0.0 && v.is_finite()) {
            return Err(self.error(j, format!("{f} must be a finite number > 0")));
        }
        if !v.is_finite() {
            return Err(self.error(j, format!("{f} must be finite")));
        }
        Ok(v.abs())
    }
}

/// Reads a cyclic file's `text` (named `file` in errors). The cycle is a whole number
/// (0 for the onset); a row needs a load on its axis.
pub fn parse_cyclic(file: &str, text: &str) -> Result<Vec<CyclicRow>, CalibError> {
    let mut out = Vec::new();
    for (line, fields) in rows(file, text, CYCLIC_HEADER)? {
        let c = Cells {
            file,
            line,
            fields: &fields,
        };
        let cycle = c.number(3, false)?;
        if cycle.fract() != 0.0 || cycle > 1e9 {
            return Err(c.error(3, format!("{} must be a whole number", fields[3])));
        }
        let row = CyclicRow {
            axis: c.axis()?,
            normal_force_n: c.number(1, true)?,
            fraction: c.number(2, true)?,
            cycle: cycle as usize,
            tangential_force_n: c.number(4, false)?,
            torsional_moment_nm: c.number(5, false)?,
            slide_m: c.number(6, false)?,
            turn_rad: c.number(7, false)?,
        };
        if row.load() == 0.0 {
            let col = if row.axis == Axis::Force { 4 } else { 5 };
            return Err(c.error(col, format!("a {} row needs a load on it", row.axis.name())));
        }
        out.push(row);
    }
    Ok(out)
}

/// Reads a hold file's `text` (named `file` in errors); a row needs a load on its axis.
pub fn parse_hold(file: &str, text: &str) -> Result<Vec<HoldRow>, CalibError> {
    let mut out = Vec::new();
    for (line, fields) in rows(file, text, HOLD_HEADER)? {
        let c = Cells {
            file,
            line,
            fields: &fields,
        };
        let row = HoldRow {
            axis: c.axis()?,
            normal_force_n: c.number(1, true)?,
            fraction: c.number(2, true)?,
            tangential_force_n: c.number(3, false)?,
            torsional_moment_nm: c.number(4, false)?,
            time_s: c.number(5, false)?,
            slide_m: c.number(6, false)?,
            turn_rad: c.number(7, false)?,
            slide_rate_m_s: c.number(8, false)?,
            turn_rate_rad_s: c.number(9, false)?,
        };
        if row.load() == 0.0 {
            let col = if row.axis == Axis::Force { 3 } else { 4 };
            return Err(c.error(col, format!("a {} row needs a load on it", row.axis.name())));
        }
        out.push(row);
    }
    Ok(out)
}

/// `v` as the files write it: shortest round-trip, in exponent form below 1e-3 and from
/// 1e6 (a slide of micrometres in exponent form, not a row of zeros).
fn csv_num(v: f64) -> String {
    if v == 0.0 || (1e-3..1e6).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// The cyclic file for `rows` (shortest round-trip numbers).
pub fn write_cyclic(rows: &[CyclicRow]) -> String {
    let mut s = format!("{CYCLIC_HEADER}\n");
    for r in rows {
        s.push_str(&format!(
            "{},{},{},{},{},{},{},{}\n",
            r.axis.name(),
            csv_num(r.normal_force_n),
            csv_num(r.fraction),
            r.cycle,
            csv_num(r.tangential_force_n),
            csv_num(r.torsional_moment_nm),
            csv_num(r.slide_m),
            csv_num(r.turn_rad)
        ));
    }
    s
}

/// The hold file for `rows`.
pub fn write_hold(rows: &[HoldRow]) -> String {
    let mut s = format!("{HOLD_HEADER}\n");
    for r in rows {
        s.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{}\n",
            r.axis.name(),
            csv_num(r.normal_force_n),
            csv_num(r.fraction),
            csv_num(r.tangential_force_n),
            csv_num(r.torsional_moment_nm),
            csv_num(r.time_s),
            csv_num(r.slide_m),
            csv_num(r.turn_rad),
            csv_num(r.slide_rate_m_s),
            csv_num(r.turn_rate_rad_s)
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_trips_and_errors_name_the_cell() {
        let rows = vec![CyclicRow {
            axis: Axis::Torsion,
            normal_force_n: 2.0,
            fraction: 0.7,
            cycle: 3,
            tangential_force_n: 0.0,
            torsional_moment_nm: 1e-3,
            slide_m: 0.0,
            turn_rad: 2e-5,
        }];
        assert_eq!(parse_cyclic("c", &write_cyclic(&rows)).unwrap(), rows);
        let held = vec![HoldRow {
            axis: Axis::Force,
            normal_force_n: 2.0,
            fraction: 0.9,
            tangential_force_n: 1.2,
            torsional_moment_nm: 0.0,
            time_s: 2.5,
            slide_m: 1e-6,
            turn_rad: 0.0,
            slide_rate_m_s: 1e-7,
            turn_rate_rad_s: 0.0,
        }];
        assert_eq!(parse_hold("h", &write_hold(&held)).unwrap(), held);
        let text = format!("{CYCLIC_HEADER}\nshear,2,0.5,1,1,0,0,0\n");
        let e = parse_cyclic("cyclic.csv", &text).unwrap_err().to_string();
        assert_eq!(
            e,
            "cyclic.csv:2:1: \"shear\" is not an axis (force or torsion)"
        );
        let text = format!("{CYCLIC_HEADER}\nforce,2,0.5,1.5,1,0,0,0\n");
        let e = parse_cyclic("cyclic.csv", &text).unwrap_err().to_string();
        assert_eq!(e, "cyclic.csv:2:4: 1.5 must be a whole number");
        let text = format!("{HOLD_HEADER}\n\ntorsion,2,0.5,1,0,1,0,0,0,0\n");
        let e = parse_hold("hold.csv", &text).unwrap_err().to_string();
        assert_eq!(e, "hold.csv:3:5: a torsion row needs a load on it");
        let e = parse_hold("hold.csv", "axis,fraction\n")
            .unwrap_err()
            .to_string();
        assert!(e.contains(HOLD_HEADER), "{e}");
    }
}
