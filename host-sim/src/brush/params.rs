//! The brush finger's parameters: the scene's `[finger.brush]` table ([`BrushSettings`],
//! serde, with defaults) and the full, checked parameter set of the plant
//! ([`BrushParams`]), with the constants derived from them (foundation modulus, bristle
//! stiffness). Plain data: no cost beyond the check.

use serde::Deserialize;

/// The finger's geometry.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BrushShape {
    /// A hemicylinder of radius `R`, axis along `x`, half-length `L` (scene shape `rect`).
    Hemicylinder,
    /// A hemisphere of radius `R` (scene shape `disc`).
    Hemisphere,
}

/// The scene's `[finger.brush]` table: the brush plant's own keys. The keys shared with
/// the limit-surface finger (`shape`, `mu`, `half_length_m`, `young_modulus_pa`,
/// `poisson`) stay in `[finger]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct BrushSettings {
    /// Radius `R` of the finger's rigid core plus layer \[m\], in (0, 1]; default in `Default`.
    pub radius_m: f64,
    /// Thickness `h` of the soft layer \[m\], in (0, R]; default in `Default`.
    pub layer_thickness_m: f64,
    /// Stiffening exponent `n` of the foundation `p = K·s^n`, in [1, 4]; default 1.
    pub stiffening_exponent: f64,
    /// Kinetic friction coefficient `μ_k` [-], in (0, μ_s]; default a fixed share of `μ_s`
    /// ([`BrushParams::from_settings`]).
    pub mu_kinetic: Option<f64>,
    /// Linear gradient of both friction coefficients across the axis [1/m]:
    /// `μ(y) = μ·max(0, 1 + g·y)`, in [-1e4, 1e4]; default 0.
    pub mu_gradient_per_m: f64,
    /// Height `H` above the contact at which the tangential force acts on the finger
    /// \[m\], in [0, 1]; default `R`.
    pub height_m: Option<f64>,
    /// Elements per side of the patch grid, in [4, 200]; default 24.
    pub elements: usize,
    /// Half-extent of the meshed patch across the axis \[m\], in (0, R]; default the
    /// contact half-width at indentation `h/2`, `sqrt(R·h − h²/4)`.
    pub mesh_half_width_m: Option<f64>,
    /// Damping ratio of the stuck bristles with the object, in [0, 2]; default in `Default`.
    pub damping_ratio: f64,
}

impl Default for BrushSettings {
    fn default() -> Self {
        Self {
            radius_m: 0.01,
            layer_thickness_m: 0.003,
            stiffening_exponent: 1.0,
            mu_kinetic: None,
            mu_gradient_per_m: 0.0,
            height_m: None,
            elements: 24,
            mesh_half_width_m: None,
            damping_ratio: 0.3,
        }
    }
}

/// Every parameter of the plant, with units.
#[derive(Debug, Clone, PartialEq)]
pub struct BrushParams {
    /// Geometry.
    pub shape: BrushShape,
    /// Radius `R` \[m\].
    pub radius_m: f64,
    /// Half-length `L` of the hemicylinder along its axis \[m\] (unused by the hemisphere).
    pub half_length_m: f64,
    /// Young's modulus `E` of the soft layer \[Pa\].
    pub young_modulus_pa: f64,
    /// Poisson's ratio `ν` of the layer [-].
    pub poisson: f64,
    /// Layer thickness `h` \[m\].
    pub layer_thickness_m: f64,
    /// Stiffening exponent `n ≥ 1` [-].
    pub stiffening_exponent: f64,
    /// Static friction coefficient `μ_s` [-].
    pub mu_static: f64,
    /// Kinetic friction coefficient `μ_k ≤ μ_s` [-].
    pub mu_kinetic: f64,
    /// Friction gradient across the axis [1/m].
    pub mu_gradient_per_m: f64,
    /// Height `H` at which the tangential force acts \[m\].
    pub height_m: f64,
    /// Elements per side.
    pub elements: usize,
    /// Half-extent of the mesh across the axis \[m\].
    pub mesh_half_width_m: f64,
    /// Damping ratio of the stuck bristles [-].
    pub damping_ratio: f64,
}

/// A parameter out of its range: the key (as the scene writes it) and why.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamError {
    /// The key, e.g. `layer_thickness_m`.
    pub key: &'static str,
    /// Why it is refused.
    pub why: String,
}

impl std::fmt::Display for ParamError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}: {}", self.key, self.why)
    }
}

fn within(key: &'static str, v: f64, lo: f64, hi: f64, open_lo: bool) -> Result<(), ParamError> {
    let ok = v.is_finite() && v <= hi && if open_lo { v > lo } else { v >= lo };
    if ok {
        Ok(())
    } else {
        let bracket = if open_lo { '(' } else { '[' };
        Err(ParamError {
            key,
            why: format!("{v} must lie in {bracket}{lo}, {hi}]"),
        })
    }
}

impl BrushParams {
    /// The parameters from the scene's shared finger keys and its `[finger.brush]` table.
    pub fn from_settings(
        shape: BrushShape,
        mu: f64,
        half_length_m: f64,
        young_modulus_pa: f64,
        poisson: f64,
        s: &BrushSettings,
    ) -> Self {
        let (r, h) = (s.radius_m, s.layer_thickness_m);
        Self {
            shape,
            radius_m: r,
            half_length_m,
            young_modulus_pa,
            poisson,
            layer_thickness_m: h,
            stiffening_exponent: s.stiffening_exponent,
            mu_static: mu,
            mu_kinetic: s.mu_kinetic.unwrap_or(0.85 * mu),
            mu_gradient_per_m: s.mu_gradient_per_m,
            height_m: s.height_m.unwrap_or(r),
            elements: s.elements,
            mesh_half_width_m: s
                .mesh_half_width_m
                .unwrap_or_else(|| (r * h - h * h / 4.0).max(0.0).sqrt()),
            damping_ratio: s.damping_ratio,
        }
    }

    /// Checks every range; the error names the key.
    pub fn check(&self) -> Result<(), ParamError> {
        within("radius_m", self.radius_m, 0.0, 1.0, true)?;
        within("half_length_m", self.half_length_m, 0.0, 1.0, true)?;
        within("young_modulus_pa", self.young_modulus_pa, 0.0, 1e12, true)?;
        within("poisson", self.poisson, 0.0, 0.499, false)?;
        within(
            "layer_thickness_m",
            self.layer_thickness_m,
            0.0,
            self.radius_m,
            true,
        )?;
        within(
            "stiffening_exponent",
            self.stiffening_exponent,
            1.0,
            4.0,
            false,
        )?;
        within("mu", self.mu_static, 0.0, 10.0, true)?;
        within("mu_kinetic", self.mu_kinetic, 0.0, self.mu_static, true)?;
        within(
            "mu_gradient_per_m",
            self.mu_gradient_per_m,
            -1e4,
            1e4,
            false,
        )?;
        within("height_m", self.height_m, 0.0, 1.0, false)?;
        within("elements", self.elements as f64, 4.0, 200.0, false)?;
        within(
            "mesh_half_width_m",
            self.mesh_half_width_m,
            0.0,
            self.radius_m,
            true,
        )?;
        within("damping_ratio", self.damping_ratio, 0.0, 2.0, false)
    }

    /// The foundation modulus `K = E/h^n` [Pa/m^n]: `p = K·s^n` is in Pa for a
    /// penetration `s` in m (for `n = 1`, the Winkler modulus `E/h`).
    pub fn foundation_modulus(&self) -> f64 {
        self.young_modulus_pa / self.layer_thickness_m.powf(self.stiffening_exponent)
    }

    /// Shear modulus `G = E/(2(1+ν))` \[Pa\].
    pub fn shear_modulus_pa(&self) -> f64 {
        self.young_modulus_pa / (2.0 * (1.0 + self.poisson))
    }

    /// Bristle stiffness per unit area `k_t = G/h` [Pa/m = N/m³].
    pub fn bristle_stiffness_pa_per_m(&self) -> f64 {
        self.shear_modulus_pa() / self.layer_thickness_m
    }
}
