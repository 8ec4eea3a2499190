//! The margins' fit: the rows grouped into tests, each fraction judged against the
//! thresholds, the shares with their intervals and the factors they give (the rule: the
//! parent module's documentation).

use crate::error::CalibError;
use crate::estimate::Estimate;
use crate::interval::t975;
use crate::margin_csv::{Axis, CyclicRow, HoldRow};
use serde::Serialize;
use softgrip::controller::FingerShape;

/// Median slide per cycle above which the cycles ratchet \[m\]
/// (docs/decisions/margin-protocols.md).
pub const RATCHET_SLIDE_M: f64 = 1e-6;
/// Median turn per cycle above which the cycles ratchet \[rad\]
/// (docs/decisions/margin-protocols.md).
pub const RATCHET_TURN_RAD: f64 = 2e-5;
/// Slide rate at the end of a hold above which it creeps \[m/s\]
/// (docs/decisions/margin-protocols.md).
pub const CREEP_SLIDE_M_S: f64 = 1e-6;
/// Turn rate at the end of a hold above which it creeps \[rad/s\]
/// (docs/decisions/margin-protocols.md).
pub const CREEP_TURN_RAD_S: f64 = 2e-5;

/// Why a margin is absent, for the TOML and the reports.
pub fn not_measured(kind: &str) -> String {
    format!("not measured: run `host-sim experiment {kind}`")
}

/// One test: an axis, its onsets, and whether each fraction held.
#[derive(Debug, Clone, Default)]
struct Test {
    onsets: Vec<f64>,
    /// `(fraction, held)`, one per row group, in the file's order.
    fractions: Vec<(f64, bool)>,
}

/// The tests of each axis: `[force, torsion]`.
type Tests = [Vec<Test>; 2];

fn index(axis: Axis) -> usize {
    match axis {
        Axis::Force => 0,
        Axis::Torsion => 1,
    }
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    match n {
        0 => 0.0,
        _ if n % 2 == 1 => v[n / 2],
        _ => 0.5 * (v[n / 2 - 1] + v[n / 2]),
    }
}

/// A test and the indices of its fractions' rows.
type Split = (Test, Vec<usize>);

/// Splits rows into tests: an onset row after a fraction's row of the same axis begins a
/// new test; `onset(row)` is its load when it is an onset row. A fraction's row before
/// any onset of its axis is refused.
fn split<R>(
    file: &str,
    rows: &[R],
    axis: impl Fn(&R) -> Axis,
    onset: impl Fn(&R) -> Option<f64>,
) -> Result<[Vec<Split>; 2], CalibError> {
    let mut out: [Vec<Split>; 2] = [Vec::new(), Vec::new()];
    for (i, r) in rows.iter().enumerate() {
        let tests = &mut out[index(axis(r))];
        match onset(r) {
            Some(load) => {
                if tests.last().is_none_or(|(_, members)| !members.is_empty()) {
                    tests.push((Test::default(), Vec::new()));
                }
                if let Some((t, _)) = tests.last_mut() {
                    t.onsets.push(load);
                }
            }
            None => match tests.last_mut() {
                Some((_, members)) => members.push(i),
                None => {
                    return Err(CalibError::TooFew {
                        file: file.to_string(),
                        needed: format!(
                            "a {} test needs its onset rows before its fractions' rows",
                            axis(r).name()
                        ),
                    })
                }
            },
        }
    }
    Ok(out)
}

/// The fractions of a test's rows in first-seen order, each with its rows.
fn by_fraction(members: &[usize], fraction: impl Fn(usize) -> f64) -> Vec<(f64, Vec<usize>)> {
    let mut out: Vec<(f64, Vec<usize>)> = Vec::new();
    for &i in members {
        let f = fraction(i);
        match out.iter_mut().find(|(g, _)| *g == f) {
            Some((_, rows)) => rows.push(i),
            None => out.push((f, vec![i])),
        }
    }
    out
}

/// The cyclic file's tests, each fraction judged (ratchets or not).
fn cyclic_tests(file: &str, rows: &[CyclicRow]) -> Result<Tests, CalibError> {
    let split = split(file, rows, |r| r.axis, |r| (r.cycle == 0).then(|| r.load()))?;
    Ok(split.map(|tests| {
        tests
            .into_iter()
            .map(|(mut test, members)| {
                let groups = by_fraction(&members, |i| rows[i].fraction);
                let most = groups.iter().map(|(_, g)| g.len()).max().unwrap_or(0);
                for (fraction, group) in groups {
                    let mut cycles: Vec<&CyclicRow> = group.iter().map(|&i| &rows[i]).collect();
                    cycles.sort_by_key(|r| r.cycle);
                    let late = &cycles[cycles.len() / 2..];
                    let slide = median(late.iter().map(|r| r.slide_m).collect());
                    let turn = median(late.iter().map(|r| r.turn_rad).collect());
                    let held = cycles.len() == most
                        && slide <= RATCHET_SLIDE_M
                        && turn <= RATCHET_TURN_RAD;
                    test.fractions.push((fraction, held));
                }
                test
            })
            .collect()
    }))
}

/// The hold file's tests, each fraction judged (creeps or not; a fraction held only if
/// every row of it did).
fn hold_tests(file: &str, rows: &[HoldRow]) -> Result<Tests, CalibError> {
    let split = split(
        file,
        rows,
        |r| r.axis,
        |r| (r.time_s == 0.0).then(|| r.load()),
    )?;
    Ok(split.map(|tests| {
        tests
            .into_iter()
            .map(|(mut test, members)| {
                let longest = members.iter().map(|&i| rows[i].time_s).fold(0.0, f64::max);
                for (fraction, group) in by_fraction(&members, |i| rows[i].fraction) {
                    let held = group.iter().all(|&i| {
                        let r = &rows[i];
                        r.time_s >= longest
                            && r.slide_rate_m_s <= CREEP_SLIDE_M_S
                            && r.turn_rate_rad_s <= CREEP_TURN_RAD_S
                    });
                    test.fractions.push((fraction, held));
                }
                test
            })
            .collect()
    }))
}

/// The onsets' pooled relative standard deviation and its degrees of freedom.
fn onset_scatter(tests: &Tests) -> (f64, usize) {
    let (mut ss, mut df) = (0.0, 0);
    for t in tests.iter().flatten() {
        let n = t.onsets.len();
        if n < 2 {
            continue;
        }
        let mean = t.onsets.iter().sum::<f64>() / n as f64;
        ss += t
            .onsets
            .iter()
            .map(|x| (x / mean - 1.0).powi(2))
            .sum::<f64>();
        df += n - 1;
    }
    if df == 0 {
        (0.0, 0)
    } else {
        ((ss / df as f64).sqrt(), df)
    }
}

/// One axis's share: the least over its tests, `None` without tests, an error when every
/// fraction of a test failed (the share is below the fractions tried).
fn axis_share(
    tests: &[Test],
    (sd, df): (f64, usize),
    what: &str,
) -> Result<Option<Estimate>, String> {
    let mut best: Option<(f64, f64, f64)> = None;
    for t in tests.iter().filter(|t| !t.fractions.is_empty()) {
        let mut fr = t.fractions.clone();
        fr.sort_by(|a, b| a.0.total_cmp(&b.0));
        let first_fail = fr.iter().position(|(_, held)| !held);
        let Some(last_held) = first_fail.map_or(fr.last(), |k| k.checked_sub(1).map(|j| &fr[j]))
        else {
            return Err(format!(
                "every fraction {what} (the least is {}): its share is below them; test \
                 lower fractions",
                fr[0].0
            ));
        };
        let se = if df > 0 && !t.onsets.is_empty() {
            t975(df) * sd / (t.onsets.len() as f64).sqrt()
        } else {
            0.0
        };
        let value = last_held.0.min(1.0);
        let lo = (value * (1.0 - se)).clamp(0.0, 1.0);
        let hi = first_fail.map_or(1.0, |k| (fr[k].0 * (1.0 + se)).min(1.0));
        if best.is_none_or(|b| value < b.0) {
            best = Some((value, lo.min(value), hi.max(value)));
        }
    }
    Ok(best.map(|(v, lo, hi)| Estimate::fitted(v, (lo, hi))))
}

/// An estimate held for `reason`.
fn absent(reason: String) -> Estimate {
    Estimate::held(f64::NAN, None, reason)
}

/// The margins the cyclic protocol gives.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CyclicMargins {
    /// The share of the tangential force's onset cycles may reach without ratcheting.
    pub force_share: Estimate,
    /// The same for the moment.
    pub torsion_share: Estimate,
    /// `r`: the lesser of the two.
    pub share: Estimate,
    /// `1/r`.
    pub cyclic_factor: Estimate,
}

/// The margins the hold protocol gives.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HoldMargins {
    /// `h_t`: the share of the tangential force's onset a sustained load may reach
    /// without creeping.
    pub force_share: Estimate,
    /// `h_m`: the same for the moment.
    pub torsion_share: Estimate,
    /// `max(1, h_t/h_m)` on the disc; held (not applicable) on the rectangle.
    pub disc_torsion_factor: Estimate,
    /// The least `safety·steady_factor` the hold allows: `1/h_t` on the disc,
    /// `1/min(h_t, h_m)` on the rectangle.
    pub least_safety_steady: Estimate,
}

/// A protocol's margins, or why there are none.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(untagged)]
pub enum Measured<T> {
    /// Fitted from the protocol's rows.
    Fitted(T),
    /// Not measured (no rows given), or the rows fit no share.
    Not {
        /// Always `false`.
        measured: bool,
        /// Why.
        reason: String,
    },
}

impl<T> Measured<T> {
    fn not(reason: String) -> Self {
        Self::Not {
            measured: false,
            reason,
        }
    }

    /// The fitted margins, if any.
    pub fn fitted(&self) -> Option<&T> {
        match self {
            Self::Fitted(t) => Some(t),
            Self::Not { .. } => None,
        }
    }
}

/// The controller's margins of a finger.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Margins {
    /// From `cyclic.csv`.
    pub cyclic: Measured<CyclicMargins>,
    /// From `hold.csv`.
    pub hold: Measured<HoldMargins>,
}

/// `1/share` with its interval (the ends swap).
fn inverse(share: &Estimate) -> Estimate {
    let [lo, hi] = share.ci95.unwrap_or([share.value; 2]);
    Estimate::fitted(1.0 / share.value, (1.0 / hi, 1.0 / lo))
}

/// The lesser of two shares (either may be absent), with the lesser ends.
fn lesser(a: &Estimate, b: &Estimate) -> Estimate {
    match (a.identified, b.identified) {
        (true, true) => {
            let [al, ah] = a.ci95.unwrap_or([a.value; 2]);
            let [bl, bh] = b.ci95.unwrap_or([b.value; 2]);
            Estimate::fitted(a.value.min(b.value), (al.min(bl), ah.min(bh)))
        }
        (true, false) => a.clone(),
        _ => b.clone(),
    }
}

fn shares(tests: &Tests, what: &str, kind: &str) -> Result<[Estimate; 2], String> {
    let scatter = onset_scatter(tests);
    let mut out = [absent(String::new()), absent(String::new())];
    for (axis, slot) in [Axis::Force, Axis::Torsion].into_iter().zip(out.iter_mut()) {
        *slot = match axis_share(&tests[index(axis)], scatter, what) {
            Ok(Some(e)) => e,
            Ok(None) => absent(format!("no {} rows: {}", axis.name(), not_measured(kind))),
            Err(e) => return Err(format!("{}: {e}", axis.name())),
        };
    }
    if !(out[0].identified || out[1].identified) {
        return Err(not_measured(kind));
    }
    Ok(out)
}

/// The cyclic margins of `rows` (`file` names the file in errors); `Not` when the rows fit
/// no share (every fraction ratcheted), with why.
pub fn fit_cyclic(file: &str, rows: &[CyclicRow]) -> Result<Measured<CyclicMargins>, CalibError> {
    let tests = cyclic_tests(file, rows)?;
    let [force_share, torsion_share] = match shares(&tests, "ratcheted", "cyclic") {
        Ok(s) => s,
        Err(why) => return Ok(Measured::not(format!("{file}: {why}"))),
    };
    let share = lesser(&force_share, &torsion_share);
    Ok(Measured::Fitted(CyclicMargins {
        cyclic_factor: inverse(&share),
        force_share,
        torsion_share,
        share,
    }))
}

/// The hold margins of `rows` for a finger of `shape`; `Not` when the rows fit no share.
pub fn fit_hold(
    file: &str,
    rows: &[HoldRow],
    shape: FingerShape,
) -> Result<Measured<HoldMargins>, CalibError> {
    let tests = hold_tests(file, rows)?;
    let [force_share, torsion_share] = match shares(&tests, "crept", "hold") {
        Ok(s) => s,
        Err(why) => return Ok(Measured::not(format!("{file}: {why}"))),
    };
    let disc = shape == FingerShape::Disc;
    let disc_torsion_factor = if !disc {
        absent("a round patch's (disc's) only: this finger is a rect".into())
    } else if force_share.identified && torsion_share.identified {
        let [tl, th] = force_share.ci95.unwrap_or([force_share.value; 2]);
        let [ml, mh] = torsion_share.ci95.unwrap_or([torsion_share.value; 2]);
        let ratio = (force_share.value / torsion_share.value).max(1.0);
        Estimate::fitted(ratio, ((tl / mh).max(1.0), (th / ml).max(1.0)))
    } else {
        absent(format!(
            "needs both axes' hold rows: {}",
            not_measured("hold")
        ))
    };
    let least_safety_steady = if disc && force_share.identified {
        inverse(&force_share)
    } else {
        inverse(&lesser(&force_share, &torsion_share))
    };
    Ok(Measured::Fitted(HoldMargins {
        force_share,
        torsion_share,
        disc_torsion_factor,
        least_safety_steady,
    }))
}

impl Margins {
    /// Neither protocol measured.
    pub fn none() -> Self {
        Self {
            cyclic: Measured::not(not_measured("cyclic")),
            hold: Measured::not(not_measured("hold")),
        }
    }

    /// Each factor at the upper end of its interval (more margin), as
    /// `--conservative` takes every parameter at its capacity-lowering end.
    pub fn conservative(&self) -> Self {
        let up = |e: &mut Estimate| {
            if let (true, Some([_, hi])) = (e.identified, e.ci95) {
                e.value = hi;
            }
        };
        let mut out = self.clone();
        if let Measured::Fitted(c) = &mut out.cyclic {
            up(&mut c.cyclic_factor);
        }
        if let Measured::Fitted(h) = &mut out.hold {
            up(&mut h.disc_torsion_factor);
            up(&mut h.least_safety_steady);
        }
        out
    }
}
