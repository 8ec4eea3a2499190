//! Each trial's fingertip: the plant the trial runs on, drawn from the trial's random
//! stream, and the scene's `[finger]` table that describes it to the simulator (never to
//! a controller: what the controllers believe comes from [`super::lab`]).
//!
//! The plants and the ranges of their parameters are tabled in docs/bench-fingers.md,
//! "The plant: the brush finger by default".
//!
//! A brush finger whose contact at `N_max` would outgrow its meshed patch (too soft for
//! its layer) is drawn again from the same stream, at most [`MAX_DRAWS`] times: the bench's
//! fingers are the ones that can carry the whole force range. The brush's patch has
//! [`BRUSH_ELEMENTS`] elements per side (the plant's default is 24: the gross-slip onset
//! moves by about 1e-3 from 16 to 24, and a run costs less than half).
//!
//! `bench --finger FILE` replaces the draw with one limit-surface finger for every trial.

use crate::brush::{BrushFinger, BrushParams, BrushSettings, BrushShape};
use crate::experiment::{FingerSpec, FlsRig, Rig};
use rand::Rng;
use rand_chacha::ChaCha8Rng;
use softgrip::controller::FingerShape;

/// Patch elements per side of the bench's brush fingers.
pub const BRUSH_ELEMENTS: usize = 16;
/// Most draws of a brush finger before the bench gives up on a trial.
pub const MAX_DRAWS: usize = 1024;

/// Which plant the bench's trials run on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BenchPlant {
    /// The brush finger ([`crate::brush`]), a physical plant softgrip does not model.
    #[default]
    Brush,
    /// softgrip's own limit surface.
    Fls,
}

impl BenchPlant {
    /// The name `--plant` takes and `bench.json` records.
    pub fn name(self) -> &'static str {
        match self {
            BenchPlant::Brush => "brush",
            BenchPlant::Fls => "fls",
        }
    }
}

/// Where the trials' fingers come from.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FingerSource {
    /// Drawn per trial on this plant.
    Drawn(BenchPlant),
    /// One limit-surface finger for every trial (`bench --finger`).
    Fixed(FingerSpec),
}

impl FingerSource {
    /// The plant the trials run on.
    pub fn plant(&self) -> BenchPlant {
        match self {
            FingerSource::Drawn(p) => *p,
            FingerSource::Fixed(_) => BenchPlant::Fls,
        }
    }
}

/// One trial's fingertip.
#[derive(Debug, Clone)]
pub enum TrialFinger {
    /// A brush finger: its shared keys and its `[finger.brush]` table.
    Brush {
        /// Hemicylinder (`rect`) or hemisphere (`disc`).
        shape: FingerShape,
        /// Static μ.
        mu: f64,
        /// Half-length `l` \[m\].
        half_length_m: f64,
        /// Young's modulus \[Pa\].
        young_modulus_pa: f64,
        /// The brush's own keys.
        brush: BrushSettings,
    },
    /// A finger whose contact slips on softgrip's exact limit surface.
    Fls(FingerSpec),
}

const POISSON: f64 = 0.45;

impl TrialFinger {
    /// Draws a finger of `source` from `r`; `n_max_n` is the greatest force it must carry.
    pub fn draw(source: &FingerSource, r: &mut ChaCha8Rng, n_max_n: f64) -> Option<Self> {
        match source {
            FingerSource::Fixed(spec) => Some(TrialFinger::Fls(*spec)),
            FingerSource::Drawn(BenchPlant::Fls) => Some(TrialFinger::Fls(draw_fls(r))),
            FingerSource::Drawn(BenchPlant::Brush) => (0..MAX_DRAWS)
                .map(|_| draw_brush(r))
                .find(|f| f.carries(n_max_n)),
        }
    }

    /// The shape.
    pub fn shape(&self) -> FingerShape {
        match self {
            TrialFinger::Brush { shape, .. } => *shape,
            TrialFinger::Fls(s) => s.shape,
        }
    }

    /// The half-length `l` \[m\] (the finger's geometry, which every controller is told).
    pub fn half_length_m(&self) -> f64 {
        match self {
            TrialFinger::Brush { half_length_m, .. } => *half_length_m,
            TrialFinger::Fls(s) => s.half_length_m,
        }
    }

    /// The static friction coefficient.
    pub fn mu(&self) -> f64 {
        match self {
            TrialFinger::Brush { mu, .. } => *mu,
            TrialFinger::Fls(s) => s.mu,
        }
    }

    /// The same finger with its friction scaled by `ratio` (static and kinetic): a
    /// surface that changed after the lab measured it.
    pub fn with_mu_scaled(&self, ratio: f64) -> Self {
        let mut f = self.clone();
        match &mut f {
            TrialFinger::Brush { mu, brush, .. } => {
                *mu *= ratio;
                brush.mu_kinetic = brush.mu_kinetic.map(|k| k * ratio);
            }
            TrialFinger::Fls(s) => s.mu *= ratio,
        }
        f
    }

    fn brush_params(&self) -> Option<BrushParams> {
        match self {
            TrialFinger::Brush {
                shape,
                mu,
                half_length_m,
                young_modulus_pa,
                brush,
            } => Some(BrushParams::from_settings(
                match shape {
                    FingerShape::Rect => BrushShape::Hemicylinder,
                    FingerShape::Disc => BrushShape::Hemisphere,
                },
                *mu,
                *half_length_m,
                *young_modulus_pa,
                POISSON,
                brush,
            )),
            TrialFinger::Fls(_) => None,
        }
    }

    /// The rig the lab measures and the oracle asks: the brush finger, or the exact
    /// surface over `[n_lo, n_hi]` \[N\].
    pub fn rig(&self, n_lo: f64, n_hi: f64) -> Result<Box<dyn Rig + Send + Sync>, String> {
        match self {
            TrialFinger::Fls(spec) => FlsRig::new(*spec, n_lo, n_hi)
                .map(|r| Box::new(r) as Box<dyn Rig + Send + Sync>)
                .map_err(|e| format!("finger: {e}")),
            TrialFinger::Brush { .. } => {
                let p = self.brush_params().ok_or("no brush")?;
                BrushFinger::new(p)
                    .map(|b| Box::new(b) as Box<dyn Rig + Send + Sync>)
                    .map_err(|e| format!("finger.brush.{e}"))
            }
        }
    }

    /// Whether a brush finger's contact at `n_n` stays inside its meshed patch (a
    /// limit-surface finger always does).
    fn carries(&self, n_n: f64) -> bool {
        let Some(p) = self.brush_params() else {
            return true;
        };
        let mesh = p.mesh_half_width_m;
        BrushFinger::new(p).is_ok_and(|b| b.indentation_half_width_m(n_n) < 0.98 * mesh)
    }

    /// The scene's `[finger]` table (and `[finger.brush]`): the true plant. `believed`
    /// is `(k, c, γ)` as the controller was calibrated: the scene format asks for them
    /// in `[finger]` (they say what the controller believes on the brush plant), and
    /// every trial also sets them in `[controller]`.
    pub fn toml(&self, believed: (f64, f64, f64)) -> String {
        let (k, c, gamma) = believed;
        match self {
            TrialFinger::Fls(s) => format!(
                "[finger]\nmodel = \"fls\"\nshape = \"{}\"\nk = {:?}\nmu = {:?}\nc = {:?}\n\
                 gamma = {:?}\nhalf_length_m = {:?}\n\n",
                s.shape.name(),
                s.k,
                s.mu,
                s.c,
                s.gamma,
                s.half_length_m
            ),
            TrialFinger::Brush {
                shape,
                mu,
                half_length_m,
                young_modulus_pa,
                brush: b,
            } => format!(
                "[finger]\nmodel = \"brush\"\nshape = \"{}\"\nmu = {mu:?}\n\
                 half_length_m = {half_length_m:?}\nyoung_modulus_pa = {young_modulus_pa:?}\n\
                 poisson = {POISSON:?}\nk = {k:?}\nc = {c:?}\ngamma = {gamma:?}\n\n\
                 [finger.brush]\nradius_m = {:?}\nlayer_thickness_m = {:?}\n\
                 stiffening_exponent = {:?}\nmu_kinetic = {:?}\nheight_m = {:?}\n\
                 elements = {}\n\n",
                shape.name(),
                b.radius_m,
                b.layer_thickness_m,
                b.stiffening_exponent,
                b.mu_kinetic.unwrap_or(0.85 * mu),
                b.height_m.unwrap_or(b.radius_m),
                b.elements
            ),
        }
    }
}

fn draw_shape(r: &mut ChaCha8Rng) -> FingerShape {
    if r.random::<bool>() {
        FingerShape::Rect
    } else {
        FingerShape::Disc
    }
}

fn draw_brush(r: &mut ChaCha8Rng) -> TrialFinger {
    let shape = draw_shape(r);
    let radius = r.random_range(0.006..=0.015);
    let layer = radius * r.random_range(0.2..=0.4);
    let young = 10f64.powf(r.random_range(5.0f64..=2e6f64.log10()));
    let n = r.random_range(1.0..=2.0);
    let mu = r.random_range(0.5..=1.2);
    let kinetic = mu * r.random_range(0.75..=0.95);
    let height = radius * r.random_range(0.3..=1.0);
    let half_length = r.random_range(0.005..=0.015);
    TrialFinger::Brush {
        shape,
        mu,
        half_length_m: half_length,
        young_modulus_pa: young,
        brush: BrushSettings {
            radius_m: radius,
            layer_thickness_m: layer,
            stiffening_exponent: n,
            mu_kinetic: Some(kinetic),
            height_m: Some(height),
            elements: BRUSH_ELEMENTS,
            ..BrushSettings::default()
        },
    }
}

fn draw_fls(r: &mut ChaCha8Rng) -> FingerSpec {
    let shape = draw_shape(r);
    let gamma = r.random_range(0.25..=0.5);
    FingerSpec {
        shape,
        mu: r.random_range(0.5..=1.2),
        k: r.random_range(1.5..=4.0),
        c: r.random_range(1.5e-3..=3.5e-3),
        gamma,
        half_length_m: r.random_range(0.005..=0.015),
        skew: None,
    }
}
