//! [`ControllerConfig::validate`]: every field checked once, the first bad one named.

use super::{ControllerConfig, FingerShape};
use crate::error::{check, ConfigError};
use crate::quadrature::QuadratureOrder;

fn positive(param: &'static str, v: f64) -> Result<(), ConfigError> {
    check(param, v, v > 0.0 && v.is_finite(), "a finite number > 0")
}

impl ControllerConfig {
    /// Checks every field (except the table sizes, which the controller checks against
    /// its capacities) and returns the first bad one.
    pub fn validate(&self) -> Result<(), ConfigError> {
        self.validate_contact()?;
        self.validate_forces()?;
        self.validate_timing()?;
        self.validate_ranges()?;
        self.validate_margins()?;
        QuadratureOrder::new(usize::from(self.quadrature_order)).map(|_| ())
    }

    /// The contact: `μ`, the pressure exponent `k` and its skew, the size law `a = c·N^γ`,
    /// the rectangle's half-length \[m\].
    fn validate_contact(&self) -> Result<(), ConfigError> {
        positive("mu", self.mu)?;
        check("k", self.k, self.k >= 1.0, "k >= 1 (inf for uniform)")?;
        if let Some(s) = self.skew {
            check(
                "skew",
                s.delta_over_a,
                (0.0..1.0).contains(&s.delta_over_a),
                "0 <= skew < 1",
            )?;
            positive("alpha", s.alpha)?;
            check(
                "locus",
                s.locus_over_a,
                s.locus_over_a >= 0.0 && s.locus_over_a.is_finite(),
                "locus >= 0",
            )?;
        }
        positive("c_m_per_n_gamma", self.c_m_per_n_gamma)?;
        check(
            "gamma",
            self.gamma,
            (0.0..=0.5).contains(&self.gamma),
            "0 <= gamma <= 1/2",
        )?;
        if self.shape == FingerShape::Rect {
            positive("half_length_m", self.half_length_m)?;
        }
        Ok(())
    }

    /// The safety factor, the force range `[N_min, N_max]` \[N\] and the rate limits \[N/s\].
    fn validate_forces(&self) -> Result<(), ConfigError> {
        check(
            "safety",
            self.safety,
            self.safety >= 1.0 && self.safety.is_finite(),
            "safety >= 1",
        )?;
        positive("n_min_n", self.n_min_n)?;
        check(
            "n_max_n",
            self.n_max_n,
            self.n_max_n > self.n_min_n && self.n_max_n.is_finite(),
            "n_max_n > n_min_n",
        )?;
        positive("rise_rate_n_per_s", self.rise_rate_n_per_s)?;
        positive("fall_rate_n_per_s", self.fall_rate_n_per_s)
    }

    /// The tick period and stale timeout \[s\], and the force held on a fault \[N\].
    fn validate_timing(&self) -> Result<(), ConfigError> {
        positive("tick_period_s", self.tick_period_s)?;
        check(
            "stale_timeout_s",
            self.stale_timeout_s,
            self.stale_timeout_s >= self.tick_period_s && self.stale_timeout_s.is_finite(),
            "stale_timeout_s >= tick_period_s",
        )?;
        check(
            "fault_force_n",
            self.fault_force_n,
            (self.n_min_n..=self.n_max_n).contains(&self.fault_force_n),
            "n_min_n <= fault_force_n <= n_max_n",
        )
    }

    /// The sensor's ranges (force \[N\], moment \[N·m\]) and the actuator's lag \[s\] and
    /// slew \[N/s\].
    fn validate_ranges(&self) -> Result<(), ConfigError> {
        check(
            "force_range_n",
            self.force_range_n,
            self.force_range_n > 0.0 && self.force_range_n <= 1e9,
            "0 < force_range_n <= 1e9",
        )?;
        check(
            "moment_range_nm",
            self.moment_range_nm,
            self.moment_range_nm > 0.0 && self.moment_range_nm <= 1e9,
            "0 < moment_range_nm <= 1e9",
        )?;
        check(
            "actuator_lag_s",
            self.actuator_lag_s,
            (0.0..=1.0).contains(&self.actuator_lag_s),
            "0 <= actuator_lag_s <= 1",
        )?;
        check(
            "actuator_slew_n_per_s",
            self.actuator_slew_n_per_s,
            self.actuator_slew_n_per_s > 0.0,
            "actuator_slew_n_per_s > 0 (inf when not slew-limited)",
        )
    }

    /// The margins: factors on the safety factor, the slip response's steps and caps, the
    /// untold actuator's lag \[s\] (docs/controller.md, "Margins").
    fn validate_margins(&self) -> Result<(), ConfigError> {
        // One loop over a table of bounds (`[lo, hi]`, `lo` excluded where flagged): ten
        // inlined checks cost the firmware about 1 KB of flash.
        let inf = f64::INFINITY;
        let rows: [(&'static str, f64, f64, f64, bool, &'static str); 10] = [
            (
                "disc_torsion_factor",
                self.disc_torsion_factor,
                1.0,
                inf,
                false,
                ">= 1",
            ),
            ("cyclic_factor", self.cyclic_factor, 1.0, inf, false, ">= 1"),
            (
                "steady_factor",
                self.steady_factor,
                0.0,
                1.0,
                true,
                "0 < x <= 1",
            ),
            ("steady_ramp_s", self.steady_ramp_s, 0.0, inf, false, ">= 0"),
            (
                "slip_step_incipient",
                self.slip_step_incipient,
                0.0,
                inf,
                false,
                ">= 0",
            ),
            (
                "slip_step_gross",
                self.slip_step_gross,
                0.0,
                inf,
                false,
                ">= 0",
            ),
            (
                "slip_margin_max",
                self.slip_margin_max,
                1.0,
                inf,
                false,
                ">= 1",
            ),
            (
                "creep_margin_max",
                self.creep_margin_max,
                1.0,
                self.slip_margin_max,
                false,
                "1 <= creep_margin_max <= slip_margin_max",
            ),
            (
                "mu_floor_fraction",
                self.mu_floor_fraction,
                0.0,
                1.0,
                true,
                "0 < x <= 1",
            ),
            (
                "untold_lag_s",
                self.untold_lag_s,
                0.0,
                1.0,
                false,
                "0 <= x <= 1",
            ),
        ];
        for (param, v, lo, hi, open_below, expected) in rows {
            let above = if open_below { v > lo } else { v >= lo };
            check(param, v, above && v <= hi && v.is_finite(), expected)?;
        }
        Ok(())
    }
}
