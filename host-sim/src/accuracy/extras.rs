//! Two interpolation schemes measured on their own, outside the controller:
//!
//! - [`aspect_grid_rows`]: the core's [`AspectGrid`], whose pitch is interpolated linearly
//!   in `ln(pitch)` against `ln(l/a)` and whose surfaces are interpolated in
//!   `(f̃, m̃/pitch)`, against the exact pitch and surface at aspects between its entries
//!   (the controller instead computes the exact pitch at every force node);
//! - [`representation_rows`]: how far the Eq. 10 ellipse and the chord polygon of an
//!   [`FlsTable`] lie from the exact surface at fixed aspects (radially).

use super::knobs::{log_space, median, Budget};
use crate::exact::ExactSurface;
use softgrip::controller::DIRECTIONS;
use softgrip::fls::AspectGrid;
use softgrip::{FlsModel, FlsTable};
use std::hint::black_box;
use std::time::Instant;

/// One aspect-grid size: its errors and build time.
#[derive(Debug, Clone, Copy)]
pub struct AspectGridRow {
    /// Aspects in the grid.
    pub count: usize,
    /// Largest relative error of the log-log interpolated pitch.
    pub pitch_err: f64,
    /// Largest relative radial error of the interpolated surface.
    pub surface_err: f64,
    /// Build time \[µs\] (median).
    pub build_us: f64,
}

/// The aspect range of the reference rectangle's contact over its grid forces.
pub fn aspect_range(rect: &ExactSurface) -> (f64, f64) {
    let f = rect.finger();
    let l = f.cfg.half_length_m;
    (l / f.a(f.cfg.n_max_n), l / f.a(f.cfg.n_min_n))
}

/// Measures [`AspectGrid`] (f64, 48 samples per sweep, default order) with `counts`
/// aspects over the rectangle's aspect range, at aspects between the entries.
pub fn aspect_grid_rows(
    rect: &ExactSurface,
    counts: &[u16],
    b: &Budget,
) -> Result<Vec<AspectGridRow>, String> {
    let (lo, hi) = aspect_range(rect);
    let fast: FlsModel<f64> =
        super::knobs::exact_engine(rect.finger().clone(), 28)?.model_at_aspect(1.0);
    let probes = log_space(lo, hi, if b.quick { 9 } else { 29 });
    let dirs = b.grid_directions;
    // Exact pitch and utilisations at the probes, shared by every grid size.
    let mut exact = Vec::new();
    for &asp in &probes {
        let model = rect.model_at_aspect(asp);
        let pitch = model.pitch();
        let mut us = Vec::new();
        for j in 0..dirs {
            let psi = std::f64::consts::FRAC_PI_2 * (j as f64 + 0.5) / dirs as f64;
            let (f, m) = (0.5 * psi.cos(), 0.5 * pitch * psi.sin());
            us.push((f, m, rect.utilisation_normalised(&model, f, m)));
        }
        exact.push((asp, pitch, us));
    }
    let mut rows = Vec::new();
    for &count in counts {
        let count = usize::from(count);
        let build = || AspectGrid::<f64, 12, 49>::build(&fast, lo, hi, count, 48);
        let grid = build().map_err(|e| format!("aspect grid: {e}"))?;
        let (mut pitch_err, mut surface_err) = (0.0f64, 0.0f64);
        for (asp, pitch, us) in &exact {
            pitch_err = pitch_err.max((grid.pitch(*asp) / pitch - 1.0).abs());
            for &(f, m, u) in us {
                surface_err = surface_err.max((u / grid.utilisation(*asp, f, m) - 1.0).abs());
            }
        }
        let mut times = Vec::new();
        for _ in 0..b.rounds.min(5) {
            let t0 = Instant::now();
            black_box(build().ok());
            times.push(t0.elapsed().as_secs_f64() * 1e6);
        }
        rows.push(AspectGridRow {
            count,
            pitch_err,
            surface_err,
            build_us: median(times),
        });
    }
    Ok(rows)
}

/// A surface representation and its largest radial error at each probe.
#[derive(Debug, Clone)]
pub struct RepresentationRow {
    /// What it is.
    pub name: String,
    /// Largest relative radial error at each probe of [`representation_probes`].
    pub errors: Vec<f64>,
}

/// The probes of [`representation_rows`]: the rectangle at both ends of its aspect range,
/// at `l/a = 1` and `2.6` (aspects whose ellipse gap docs/decisions/conservative-capacity.md
/// records), and the disc.
pub fn representation_probes(rect: &ExactSurface) -> Vec<(String, Option<f64>)> {
    let (lo, hi) = aspect_range(rect);
    vec![
        (format!("rect l/a = {lo:.3}"), Some(lo)),
        ("rect l/a = 1".into(), Some(1.0)),
        ("rect l/a = 2.6".into(), Some(2.6)),
        (format!("rect l/a = {hi:.2}"), Some(hi)),
        ("disc".into(), None),
    ]
}

/// Radial error of the Eq. 10 ellipse and of chord tables of `samples` points (f64,
/// default order) against the exact surface, at each probe.
pub fn representation_rows(
    rect: &ExactSurface,
    disc: &ExactSurface,
    samples: &[u16],
    b: &Budget,
) -> Result<Vec<RepresentationRow>, String> {
    let probes = representation_probes(rect);
    let dirs = 2 * b.grid_directions;
    let mut ellipse = Vec::new();
    let mut chords: Vec<Vec<f64>> = vec![Vec::new(); samples.len()];
    let mut polygon_exact = Vec::new();
    let mut polygon_48 = Vec::new();
    for (_, aspect) in &probes {
        let (reference, model) = match aspect {
            Some(a) => (rect, rect.model_at_aspect(*a)),
            None => (disc, disc.model_at(1.0)),
        };
        let fast = super::knobs::exact_engine(reference.finger().clone(), 28)?;
        let fast = match aspect {
            Some(a) => fast.model_at_aspect(*a),
            None => fast.model_at(1.0),
        };
        let pitch = model.pitch();
        let tables: Vec<FlsTable<f64, 129>> = samples
            .iter()
            .map(|&s| FlsTable::sweep(&fast, usize::from(s)).map_err(|e| e.to_string()))
            .collect::<Result<_, _>>()?;
        // The controller's storage: the inverse L1 radius in (f̃, m̃/pitch) at DIRECTIONS
        // directions, interpolated linearly in the direction t = y/(x + y).
        let table_48 = FlsTable::<f64, 129>::sweep(&fast, 48).map_err(|e| e.to_string())?;
        let rows: [Vec<f64>; 2] = [
            directions(|f, m| reference.utilisation_normalised(&model, f, m), pitch),
            directions(|f, m| table_48.utilisation(f, m), table_48.pitch()),
        ];
        let (mut e_pe, mut e_p48) = (0.0f64, 0.0f64);
        let mut e_ell = 0.0f64;
        let mut e_tab = vec![0.0f64; samples.len()];
        for j in 0..dirs {
            let psi = std::f64::consts::FRAC_PI_2 * (j as f64 + 0.5) / dirs as f64;
            let (f, m) = (0.5 * psi.cos(), 0.5 * pitch * psi.sin());
            let u = reference.utilisation_normalised(&model, f, m);
            e_ell = e_ell.max((u / 0.5 - 1.0).abs());
            for (e, t) in e_tab.iter_mut().zip(&tables) {
                *e = e.max((u / t.utilisation(f, m) - 1.0).abs());
            }
            e_pe = e_pe.max((u / polygon(&rows[0], f, m / pitch) - 1.0).abs());
            e_p48 = e_p48.max((u / polygon(&rows[1], f, m / table_48.pitch()) - 1.0).abs());
        }
        ellipse.push(e_ell);
        polygon_exact.push(e_pe);
        polygon_48.push(e_p48);
        for (c, e) in chords.iter_mut().zip(e_tab) {
            c.push(e);
        }
    }
    let mut rows = vec![RepresentationRow {
        name: "Eq. 10 ellipse, exact pitch".into(),
        errors: ellipse,
    }];
    for (s, errors) in samples.iter().zip(chords) {
        rows.push(RepresentationRow {
            name: format!("chords of a {s}-sample sweep"),
            errors,
        });
    }
    rows.push(RepresentationRow {
        name: format!("{DIRECTIONS} directions of the exact surface"),
        errors: polygon_exact,
    });
    rows.push(RepresentationRow {
        name: format!("{DIRECTIONS} directions of a 48-sample sweep (the controller's table)"),
        errors: polygon_48,
    });
    Ok(rows)
}

/// The inverse L1 radii of a surface in `(f̃, m̃/pitch)` at the controller's
/// [`DIRECTIONS`] directions `t = i/(DIRECTIONS − 1)`, from its utilisation `u(f̃, m̃)`.
fn directions(u: impl Fn(f64, f64) -> f64, pitch: f64) -> Vec<f64> {
    (0..DIRECTIONS)
        .map(|i| {
            let t = i as f64 / (DIRECTIONS - 1) as f64;
            u(1.0 - t, t * pitch)
        })
        .collect()
}

/// The utilisation of `(x, y) = (f̃, m̃/pitch)` on the polygon of [`directions`].
fn polygon(w: &[f64], x: f64, y: f64) -> f64 {
    let s = x + y;
    let pos = (y / s * (DIRECTIONS - 1) as f64).clamp(0.0, (DIRECTIONS - 1) as f64);
    let i = (pos as usize).min(DIRECTIONS - 2);
    let frac = pos - i as f64;
    s * (w[i] + (w[i + 1] - w[i]) * frac)
}
