//! The margins' report: the finger TOML's `[margins]` table, the text report's lines and
//! the JSON report, all from one list of lines.

use super::fit::{Margins, Measured};
use crate::estimate::Estimate;
use crate::finger_toml::{num, sig4};
use crate::Calibration;
use serde::Serialize;
use softgrip::controller::FingerShape;

/// `lo, hi` of an estimate's interval, 4 significant digits (the value twice without one).
fn ends(e: &Estimate) -> (String, String) {
    let [lo, hi] = e.ci95.unwrap_or([e.value; 2]);
    (sig4(lo), sig4(hi))
}

/// A share for people: `value [lo, hi]`, or why it is absent.
fn share_note(e: &Estimate) -> String {
    if e.identified {
        let (lo, hi) = ends(e);
        format!("{} [{lo}, {hi}]", sig4(e.value))
    } else {
        e.reason.clone().unwrap_or_default()
    }
}

/// One margin as the outputs show it: its name, its estimate when it has one (with what
/// it is made of), else why not.
struct Line {
    name: &'static str,
    value: Option<Estimate>,
    note: String,
    /// A TOML key (`false`: a comment, as the least safety·steady_factor is).
    key: bool,
}

/// The margins' lines: `cyclic_factor`, `disc_torsion_factor`, and the least
/// `safety·steady_factor`.
fn lines(m: &Margins, shape: FingerShape) -> Vec<Line> {
    let disc = shape == FingerShape::Disc;
    let line = |name, value: Option<Estimate>, note: String, key| Line {
        name,
        value,
        note,
        key,
    };
    let cyclic = match &m.cyclic {
        Measured::Fitted(c) => line(
            "cyclic_factor",
            Some(c.cyclic_factor.clone()),
            format!(
                "1/r, cyclic share r = {}: force {}; torsion {}",
                sig4(c.share.value),
                share_note(&c.force_share),
                share_note(&c.torsion_share)
            ),
            true,
        ),
        Measured::Not { reason, .. } => line("cyclic_factor", None, reason.clone(), true),
    };
    let (torsion, steady) = match &m.hold {
        Measured::Fitted(h) => {
            let d = &h.disc_torsion_factor;
            let shares = format!(
                "hold shares h_t {}; h_m {}",
                share_note(&h.force_share),
                share_note(&h.torsion_share)
            );
            let torsion = match d.identified {
                true => line(
                    "disc_torsion_factor",
                    Some(d.clone()),
                    "max(1, h_t/h_m)".into(),
                    true,
                ),
                false => line(
                    "disc_torsion_factor",
                    None,
                    d.reason.clone().unwrap_or_default(),
                    true,
                ),
            };
            let inverse = if disc { "1/h_t" } else { "1/min(h_t, h_m)" };
            let steady = line(
                "safety·steady_factor",
                Some(h.least_safety_steady.clone()),
                format!("{inverse}; {shares}"),
                false,
            );
            (torsion, steady)
        }
        Measured::Not { reason, .. } => (
            line("disc_torsion_factor", None, reason.clone(), true),
            line("safety·steady_factor", None, reason.clone(), false),
        ),
    };
    let mut out = vec![cyclic, torsion, steady];
    if !disc {
        out[1] = line(
            "disc_torsion_factor",
            None,
            "a round patch's (disc's) only: this finger is a rect".into(),
            true,
        );
    }
    out
}

/// The finger TOML's `[margins]` table: each measured margin a key with its interval and
/// what it is made of in a comment, one not measured a comment saying so, and the least
/// `safety·steady_factor` the hold allows as a comment. Without a measured key it is
/// comments alone, so that the file stays a finger table a scene can copy.
pub fn margins_toml(m: &Margins, shape: FingerShape) -> String {
    let all = lines(m, shape);
    let (keys, notes): (Vec<&Line>, Vec<&Line>) =
        all.iter().partition(|l| l.key && l.value.is_some());
    let mut s = if keys.is_empty() {
        "\n# [margins]: none measured\n".to_string()
    } else {
        "\n[margins]\n".to_string()
    };
    for l in keys {
        if let Some(e) = &l.value {
            let (lo, hi) = ends(e);
            s.push_str(&format!(
                "{} = {}  # 95 %: [{lo}, {hi}]; {}\n",
                l.name,
                num(e.value),
                l.note
            ));
        }
    }
    for l in notes {
        match &l.value {
            Some(e) => {
                let (lo, hi) = ends(e);
                s.push_str(&format!(
                    "# {} >= {} (95 %: [{lo}, {hi}]): {}\n",
                    l.name,
                    sig4(e.value),
                    l.note
                ));
            }
            None => s.push_str(&format!("# {}: {}\n", l.name, l.note)),
        }
    }
    s
}

/// The margins for people, one line each, as the text report's parameters.
pub fn margins_text(m: &Margins, shape: FingerShape) -> String {
    let mut s = String::new();
    for l in lines(m, shape) {
        let text = match &l.value {
            Some(e) => {
                let (lo, hi) = ends(e);
                let at_least = if l.key { "" } else { ">= " };
                format!(
                    "{at_least}{}  95 % [{lo}, {hi}]  ({})",
                    sig4(e.value),
                    l.note
                )
            }
            None => l.note.clone(),
        };
        s.push_str(&format!("{:<18} {text}\n", l.name));
    }
    s
}

/// The report `host-sim calibrate --format json` and Python's `softgrip.calibrate` give:
/// the calibration's fields, and `"margins"`.
#[derive(Debug, Serialize)]
pub struct Report<'a> {
    /// The finger's parameters.
    #[serde(flatten)]
    pub calibration: &'a Calibration,
    /// Its margins.
    pub margins: &'a Margins,
    /// [`Calibration::safety_for_mu`]: the least safety factor `μ`'s interval needs.
    pub safety_for_mu: Option<f64>,
}
