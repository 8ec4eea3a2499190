//! The true limit of a plant that has no limit surface of its own (the brush finger),
//! tabulated from its gross-slip onsets, for the oracle.
//!
//! At [`FORCE_NODES`] normal forces spaced evenly in `ln N` over the bench's force range,
//! the plant's onset is found along [`ANGLES`] directions of the load plane normalised by
//! that force's pure-force limit `F(N)` and pure-torsion limit `M(N)`: the direction at
//! angle `φ` ramps `(f_t, m_n) = λ·(F·cos φ, M·sin φ)` and the onset gives the radius
//! `ρ(N, φ) = λ` (1 on both axes by construction). A load `(f_t, m_n)` holds at `N` when
//! `|(f_t/F(N), m_n/M(N))| ≤ ρ(N, φ)`, with `ln F`, `ln M` interpolated linearly in
//! `ln N` and `ρ` bilinearly in `(ln N, φ)`.
//!
//! Accuracy: on rays between the nodes (forces between its force nodes, directions
//! between its angles) the tabulated edge is within 3 % of the finger's own onset
//! (`host-sim/tests/bench_lab.rs::the_brush_oracle_table_agrees_with_the_finger_s_own_onsets`,
//! which prints the worst case with `--nocapture`). The oracle is the reference every
//! controller is divided by, so an error common to a trial scales all of them alike.
//! Cost: `FORCE_NODES × (ANGLES − 2) + 2·FORCE_NODES` onsets to build, a few flops per
//! lookup.

use crate::experiment::Rig;

/// Normal forces of the table.
pub const FORCE_NODES: usize = 6;
/// Directions per force, from pure force (0) to pure torsion (90°).
pub const ANGLES: usize = 5;

/// The tabulated limit.
#[derive(Debug, Clone)]
pub struct OnsetTable {
    ln_n: [f64; FORCE_NODES],
    ln_f: [f64; FORCE_NODES],
    ln_m: [f64; FORCE_NODES],
    rho: [[f64; ANGLES]; FORCE_NODES],
}

/// A ramp that never slips counts as this far out (the onset search's own bound).
const NO_SLIP_RHO: f64 = 3.0;

impl OnsetTable {
    /// Tabulates `rig` over `[n_lo_n, n_hi_n]` \[N\]; an error when a pure-force or
    /// pure-torsion ramp never slips.
    pub fn build(rig: &dyn Rig, n_lo_n: f64, n_hi_n: f64) -> Result<Self, String> {
        let mut t = Self {
            ln_n: [0.0; FORCE_NODES],
            ln_f: [0.0; FORCE_NODES],
            ln_m: [0.0; FORCE_NODES],
            rho: [[1.0; ANGLES]; FORCE_NODES],
        };
        let (lo, hi) = (n_lo_n.ln(), n_hi_n.ln());
        for i in 0..FORCE_NODES {
            let ln_n = lo + (hi - lo) * i as f64 / (FORCE_NODES - 1) as f64;
            let n = ln_n.exp();
            let f = rig
                .slip_onset(n, 1.0, 0.0)
                .map(|o| o.0)
                .filter(|f| *f > 0.0)
                .ok_or_else(|| format!("the plant never slips under a force at {n} N"))?;
            let m = rig
                .slip_onset(n, 0.0, 1e-3)
                .map(|o| o.1)
                .filter(|m| *m > 0.0)
                .ok_or_else(|| format!("the plant never slips under a moment at {n} N"))?;
            t.ln_n[i] = ln_n;
            t.ln_f[i] = f.ln();
            t.ln_m[i] = m.ln();
            for j in 1..ANGLES - 1 {
                let phi = angle(j);
                t.rho[i][j] = rig
                    .slip_onset(n, f * phi.cos(), m * phi.sin())
                    .map_or(NO_SLIP_RHO, |(ft, _)| ft / (f * phi.cos()));
            }
        }
        Ok(t)
    }

    /// The pure-torsion limit `M(N)` [N·m] (interpolated).
    pub fn torsion_limit_nm(&self, n_n: f64) -> f64 {
        let (i, w) = self.bracket(n_n);
        lerp(self.ln_m[i], self.ln_m[i + 1], w).exp()
    }

    /// Whether the load `(ft_n, mn_nm)` holds at normal force `n_n`.
    pub fn holds(&self, ft_n: f64, mn_nm: f64, n_n: f64) -> bool {
        let (i, w) = self.bracket(n_n);
        let f = lerp(self.ln_f[i], self.ln_f[i + 1], w).exp();
        let m = lerp(self.ln_m[i], self.ln_m[i + 1], w).exp();
        let (x, y) = (ft_n.abs() / f, mn_nm.abs() / m);
        let r = x.hypot(y);
        if r == 0.0 {
            return true;
        }
        if !r.is_finite() {
            return false;
        }
        let phi = y.atan2(x);
        let step = angle(1);
        let j = ((phi / step).floor() as usize).min(ANGLES - 2);
        let v = (phi - angle(j)) / step;
        let at = |row: &[f64; ANGLES]| lerp(row[j], row[j + 1], v);
        r <= lerp(at(&self.rho[i]), at(&self.rho[i + 1]), w)
    }

    /// The node below `n_n` and the weight of the one above (clamped to the table).
    fn bracket(&self, n_n: f64) -> (usize, f64) {
        let x = n_n.max(f64::MIN_POSITIVE).ln();
        let (lo, hi) = (self.ln_n[0], self.ln_n[FORCE_NODES - 1]);
        let s =
            ((x - lo) / (hi - lo) * (FORCE_NODES - 1) as f64).clamp(0.0, (FORCE_NODES - 1) as f64);
        let i = (s.floor() as usize).min(FORCE_NODES - 2);
        (i, s - i as f64)
    }
}

fn angle(j: usize) -> f64 {
    std::f64::consts::FRAC_PI_2 * j as f64 / (ANGLES - 1) as f64
}

fn lerp(a: f64, b: f64, w: f64) -> f64 {
    a + (b - a) * w
}
