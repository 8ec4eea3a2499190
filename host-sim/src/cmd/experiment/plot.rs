//! The experiments' plots: half-width against force; onsets as `f_t/N` against `m_n/N`
//! (a surface in units the lab knows, before any fit), one colour per kind.

use crate::plot::{plot_panels, Panel, Series};
use crate::CliError;
use softgrip_calibrate::lab_csv::{Indentation, OnsetKind, SlipOnset};
use std::path::{Path, PathBuf};

fn fail(e: String) -> CliError {
    CliError::Failed(format!("--out: {e}"))
}

/// Half-width [mm] against normal force [N].
pub fn indentation(path: &Path, rows: &[Indentation]) -> Result<PathBuf, CliError> {
    let panel = Panel {
        title: "Indentation".into(),
        x_label: "normal force N [N]".into(),
        y_label: "half-width a [mm]".into(),
        series: vec![Series {
            label: "measured".into(),
            points: rows
                .iter()
                .map(|r| (r.normal_force_n, r.half_width_m * 1e3))
                .collect(),
            line: false,
        }],
    };
    plot_panels(path, &[panel]).map_err(fail)?;
    Ok(path.to_path_buf())
}

/// Onsets: `f_t/N` against `m_n/N` [mm], by kind.
pub fn onsets(path: &Path, rows: &[SlipOnset]) -> Result<PathBuf, CliError> {
    let series = [
        (OnsetKind::Force, "pure force"),
        (OnsetKind::Torsion, "pure torsion"),
        (OnsetKind::Mixed, "mixed"),
    ]
    .into_iter()
    .map(|(kind, label)| Series {
        label: label.into(),
        points: rows
            .iter()
            .filter(|o| o.kind() == kind)
            .map(|o| {
                let n = o.normal_force_n;
                (o.torsional_moment_nm / n * 1e3, o.tangential_force_n / n)
            })
            .collect(),
        line: false,
    })
    .filter(|s| !s.points.is_empty())
    .collect();
    let panel = Panel {
        title: "Onsets of gross slip".into(),
        x_label: "m_n/N [mm]".into(),
        y_label: "f_t/N".into(),
        series,
    };
    plot_panels(path, &[panel]).map_err(fail)?;
    Ok(path.to_path_buf())
}
