//! `tables --sweep`: pitch, gap to the ellipse and required force over k × skew ×
//! aspect × μ, in parallel, into `sweep.csv`.

use super::{bar, write};
use crate::CliError;
use rayon::prelude::*;
use softgrip::controller::{Controller, ControllerConfig, FingerShape, Mode, SkewParams};
use softgrip::fls::RadialGap;
use softgrip::{FlsConfig, FlsModel, FlsTable, QuadratureOrder, Shape};
use std::path::Path;

pub(super) fn sweep(out: &Path, quiet: bool) -> Result<(), CliError> {
    let ks = [1.0, 2.0, 4.0, 8.0, 50.0, f64::INFINITY];
    let skews = [0.0, 0.5, 0.9];
    let aspects = [0.5, 1.0, 2.0, 4.0];
    let mus = [0.4, 0.8, 1.2];
    let mut sets = Vec::new();
    for &k in &ks {
        for &s in &skews {
            for &a in &aspects {
                for &mu in &mus {
                    sets.push((k, s, a, mu));
                }
            }
        }
    }
    let b = bar(sets.len() as u64, "parameter sets", quiet);
    let rows: Vec<Result<String, String>> = sets
        .par_iter()
        .map(|&(k, s, a, mu)| {
            let skew = (s > 0.0).then_some((s, 1.1, s / 2.0));
            let model = FlsModel::<f64>::new(FlsConfig {
                shape: Shape::Rect { aspect: a },
                k,
                skew,
                order: QuadratureOrder::DEFAULT,
            })
            .map_err(|e| e.to_string())?;
            let table = FlsTable::<f64, 129>::sweep(&model, 128).map_err(|e| e.to_string())?;
            let gap = RadialGap::find(&model, &table);
            // The force a contact of fixed size (γ = 0, a = l/aspect with l = 10 mm) needs
            // for 1 N and 5 mN·m with the default safety factor, by the exact surface.
            let cfg = ControllerConfig {
                mu,
                shape: FingerShape::Rect,
                k,
                skew: skew.map(|(d, al, h)| SkewParams {
                    delta_over_a: d,
                    alpha: al,
                    locus_over_a: h,
                }),
                gamma: 0.0,
                c_m_per_n_gamma: 0.01 / a,
                mode: Mode::Table,
                ..ControllerConfig::default()
            };
            let cfg = cfg.check().map_err(|e| e.to_string())?;
            let n_req = Controller::<f64>::from_checked(&cfg)
                .map_err(|e| e.to_string())?
                .required_force(1.0, 0.005, ControllerConfig::DEFAULT.safety)
                .map_or(f64::NAN, |s| s.force_n);
            b.inc(1);
            Ok(format!(
                "{k},{s},{a},{mu},{},{},{},{n_req}",
                model.pitch(),
                gap.max_relative_gap,
                gap.max_outside
            ))
        })
        .collect();
    b.finish_and_clear();
    let mut csv = String::from(
        "k,skew_delta_over_a,aspect,mu,pitch,max_relative_gap,max_outside,n_req_1n_5mnm_n\n",
    );
    for r in rows {
        csv.push_str(&r.map_err(CliError::Failed)?);
        csv.push('\n');
    }
    let path = out.join("sweep.csv");
    write(&path, csv.as_bytes())?;
    println!(
        "wrote {} ({} parameter sets, in parallel on {} threads)",
        path.display(),
        sets.len(),
        rayon::current_num_threads()
    );
    Ok(())
}
