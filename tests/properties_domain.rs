//! Property tests over the whole valid domain, where `tests/fls_properties.rs` and
//! `tests/controller.rs` cover a part of it (`k ≤ 60`, `l/a ∈ [0.05, 20]`, `Δ/a ≤ 0.95`,
//! seven fixed controller configurations). Here: `k` from 1 to 1e6 and `∞`, `l/a` from 1e-3
//! to 1e3, `Δ/a` up to 0.999999, `α` from 1e-3 to 1e3, and random controller
//! configurations (`tests/common/stress_cases.rs`, `random_config`: both shapes, `μ` 0.05–3,
//! `γ` 0–1/2, grids from 1e-3 N to 1e4 N wide, 16–64 force nodes, 48–128 sweep samples,
//! 8–12 aspects, `s` 1–3).
//!
//! Every documented caveat is a stated, measured bound of the property, not an exclusion:
//! - thin rectangles leave the Eq. 10 ellipse: by at most [`THIN_OUTSIDE`] in `(f̃, m̃)`;
//! - skewed surfaces: `m̃` may rise along the sweep and the curve need not be convex;
//! - table mode against ellipse mode: table mode (raised exact surface) asks at most its
//!   raise more than ellipse mode (inscribed ellipse), and ellipse mode at most
//!   `(1 + O)/min(A, B)` more than table mode, with `(A, B)` its inscribed semi-axes and
//!   `O` the surface's excursion outside the unit circle in `(f̃, m̃/pitch)`
//!   ([`OUT_NORMALISED`]; [`GAP_NORMALISED`] is what Eq. 10 itself would under-ask).

#[path = "common/stress_cases.rs"]
mod stress_cases;

use proptest::prelude::*;
use softgrip::contact::ContactSize;
use softgrip::controller::{
    Controller, ControllerConfig, FingerShape, Libm, Measurement, Micromath, Mode, TickMath,
    MAX_ILLINOIS_ITERATIONS, UTILISATION_MAX,
};
use softgrip::fls::ellipse_radius;
use softgrip::fls::RadialGap;
use softgrip::skew::SkewLaw;
use softgrip::{FlsTable, Real, Shape};
use softgrip_reference::{pressure_total, Patch};
use stress_cases::*;

/// How far a symmetric rectangle's surface leaves the Eq. 10 ellipse, radially in
/// `(f̃, m̃)`, over `l/a ∈ [1e-3, 0.5)` and all `k` (`RadialGap::max_outside`). Measured with
/// 256-sample sweeps: 0 for `l/a ≥ 0.45`; 0.0055 (k = 1) to 0.0133 (uniform) at 0.3; 0.042
/// (k = 1) at 0.05; 0.0450 (k = 1), 0.0387 (k = 2), 0.0359 (uniform) at 1e-3, the thin-strip
/// limit. docs/core.md's "up to 0.04 at l/a = 0.05" is the k = 2 figure.
const THIN_OUTSIDE: f64 = 0.046;

/// The largest radial gap between the exact surface and the Eq. 10 ellipse in the
/// controller's coordinates `(f̃, m̃/pitch)`, where the ellipse is the unit circle (how far
/// inside it the exact surface lies, which is why ellipse mode now tests against an
/// inscribed ellipse instead): measured over 1024-sample sweeps, 0.1340 for long
/// rectangles (every `k`; l/a = 1: 0.0706 at k = 2), 0.051 (k = 1) to 0.066 (uniform) on the
/// disc. docs/controller.md quotes the gap in `(f̃, m̃)` (12.2 % for long patches), which is smaller
/// where the pitch is far from 1.
const GAP_NORMALISED: f64 = 0.1341;

/// The largest excursion outside the unit circle in `(f̃, m̃/pitch)` (thin strips): 0.0616
/// (k = 1), 0.052 (k = 2), 0.047 (uniform), at l/a = 1e-3; 0 for `l/a ≥ 0.45`.
const OUT_NORMALISED: f64 = 0.0617;

fn k_strategy() -> impl Strategy<Value = f64> {
    prop_oneof![
        4 => (0.0f64..(1e6f64).ln()).prop_map(f64::exp),
        1 => Just(f64::INFINITY),
        1 => Just(1.0),
    ]
}

fn aspect_strategy() -> impl Strategy<Value = f64> {
    ((1e-3f64).ln()..(1e3f64).ln()).prop_map(f64::exp)
}

fn cross(o: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    (a.0 - o.0) * (b.1 - o.1) - (a.1 - o.1) * (b.0 - o.0)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Symmetric surfaces anywhere in the domain: finite, `f̃` rises from 0 and `m̃` falls from
    /// the pitch, convex (to rounding, relative to the surface's scale), and inside the Eq. 10
    /// ellipse for the disc and `l/a ≥ 0.5`; below that outside it by at most
    /// [`THIN_OUTSIDE`], and never by more than the refined [`RadialGap`] reports.
    #[test]
    fn symmetric_surfaces_are_monotone_convex_and_inside_the_ellipse_where_documented(
        k in k_strategy(),
        aspect in aspect_strategy(),
        disc in prop::bool::weighted(0.25),
    ) {
        let shape = if disc { Shape::Disc } else { Shape::Rect { aspect } };
        let m = model(shape, k, None, 28);
        let table = FlsTable::<f64, 100>::sweep(&m, 96).unwrap();
        let pts = table.points();
        let pitch = table.pitch();
        let scale = pitch.max(1.0);
        prop_assert!(table.is_star_shaped());
        prop_assert!(pitch.is_finite() && pitch > 0.0);
        prop_assert_eq!(pts[0].f, 0.0);
        for w in pts.windows(2) {
            prop_assert!(w[1].f > w[0].f && w[1].m < w[0].m, "{:?} -> {:?}", w[0], w[1]);
            prop_assert!(w[1].f <= 1.0 && w[1].m >= 0.0);
        }
        for w in pts.windows(3) {
            let c = cross((w[0].f, w[0].m), (w[1].f, w[1].m), (w[2].f, w[2].m));
            prop_assert!(c <= 1e-12 * scale, "not convex at {:?}: {:e}", w[1], c);
        }
        let inside = disc || aspect >= 0.5;
        let allowed = if inside { 1e-12 * scale } else { THIN_OUTSIDE };
        let mut outside = 0.0f64;
        for p in pts {
            outside = outside.max(p.f.hypot(p.m) - ellipse_radius(pitch, p.f, p.m));
        }
        prop_assert!(outside <= allowed, "outside the ellipse by {} (l/a = {})", outside, aspect);
        if !inside {
            let gap = RadialGap::find(&m, &table);
            prop_assert!(gap.max_outside <= THIN_OUTSIDE, "{:?}", gap);
            prop_assert!(gap.max_outside >= outside - 1e-12);
        }
    }

    /// Skewed rectangles anywhere in the domain (`Δ/a` up to 0.999999, `α` 1e-3 to 1e3):
    /// finite, `f̃` rises, the direction turns monotonically (star-shaped: the table can be
    /// built), the pitch is the symmetric one. Not asserted, because it is false: `m̃` falling
    /// (it rises by up to 20 % of the pitch for a fast skew on a thin strip, e.g. k = 1.24,
    /// l/a = 0.012, Δ/a = 0.79, α = 340) and convexity (cross products up to +3.9e-4).
    #[test]
    fn skewed_rectangles_rise_in_force_and_stay_star_shaped(
        k in k_strategy(),
        aspect in aspect_strategy(),
        delta in prop_oneof![0.0f64..0.999_999, Just(0.999_999)],
        alpha in ((1e-3f64).ln()..(1e3f64).ln()).prop_map(f64::exp),
    ) {
        let shape = Shape::Rect { aspect };
        let m = model(shape, k, Some((delta, alpha, delta / 2.0)), 28);
        let table = FlsTable::<f64, 100>::sweep(&m, 96).unwrap();
        let plain = model(shape, k, None, 28).pitch();
        prop_assert!((table.pitch() - plain).abs() <= 1e-14 * plain.max(1.0));
        prop_assert!(table.is_star_shaped());
        for w in table.points().windows(2) {
            prop_assert!(w[1].f > w[0].f, "{:?} {:?}", w[0], w[1]);
            prop_assert!(w[1].f <= 1.0 && w[1].m >= 0.0 && w[1].m.is_finite());
        }
    }

    /// Equilibrium `∫∫p = N` for every skew, checked two independent ways: the brute-force
    /// 2-D integral of the crate's pressure with the peak where the skew law puts it
    /// (32 cells: its documented error is 1e-9; measured 4.6e-9 with the peak 1e-6 from the
    /// edge and k = 1e6, and 2.3e-8 on the disc with k = 21 and the peak 6e-6 from the edge,
    /// where the brute force's cells cannot resolve the peak's ray scaling; so 5e-8), and the fast path's far-field force `f̃(1e8) = ∫p/N`
    /// (the rest is `O(d⁻²)` = 1e-16; the quadrature's documented accuracy is 5e-11, and a
    /// steep profile with a strong skew reaches 1.6e-12, e.g. k = 3670, Δ/a = 0.91: 1e-10).
    #[test]
    fn equilibrium_holds_for_every_skew(
        k in prop_oneof![(0.0f64..(1e6f64).ln()).prop_map(f64::exp), Just(1.0)],
        aspect in aspect_strategy(),
        delta in prop_oneof![0.0f64..0.999_999, Just(0.999_999)],
        alpha in ((1e-2f64).ln()..(1e2f64).ln()).prop_map(f64::exp),
        d in ((1e-3f64).ln()..(1e3f64).ln()).prop_map(f64::exp),
        disc in prop::bool::weighted(0.3),
    ) {
        let (patch, shape, locus) = if disc {
            (Patch::Disc, Shape::Disc, 0.0)
        } else {
            (Patch::Rect { aspect }, Shape::Rect { aspect }, delta / 2.0)
        };
        let law = SkewLaw::<f64>::new(delta, alpha, locus).unwrap();
        let peak = law.peak(d);
        let total = pressure_total(patch, k, peak, 32);
        prop_assert!((total - 1.0).abs() <= 5e-8, "∫p/N = {} at peak {:?}", total, peak);
        let far = model(shape, k, Some((delta, alpha, locus)), 28).point(1e8);
        prop_assert!((far.f - 1.0).abs() <= 1e-10, "{:?}", far);
    }
}

fn build<T: Real, M: TickMath<T>>(cfg: ControllerConfig) -> Option<Controller<T, M>> {
    match Controller::<T, M>::new_precomputed_in::<f64>(cfg) {
        Ok(c) => Some(c),
        // A valid-looking configuration may still be refused, with a named field: only the
        // sensor range that would overflow the tick's precision, or (table mode) a surface
        // that is not star-shaped.
        Err(e) => {
            assert!(
                matches!(e.param(), "force_range_n" | "locus"),
                "{cfg:?} refused: {e}"
            );
            None
        }
    }
}

/// A load that needs about `n_target` on the configuration's contact: shares `u`, `v` of
/// the translation and torsion the contact at `n_target` can carry.
fn load_for(cfg: &ControllerConfig, n_target: f64, u: f64, v: f64) -> (f64, f64) {
    let a = ContactSize::<f64>::new(cfg.c_m_per_n_gamma, cfg.gamma)
        .unwrap()
        .half_width_m(n_target);
    (u * cfg.mu * n_target, v * cfg.mu * n_target * a)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// `N_slip` over random configurations and loads whose answers fall below, inside and
    /// above the grid: finite, non-negative, monotone in each load component (1e-12
    /// relative: the solver's 8-ulp tolerance), continuous with relative Lipschitz constant 1
    /// (`N_req(λ·load) ≤ λ·N_req(load)` for `λ ≥ 1`: the contact does not shrink as `N`
    /// grows; 3ε allowed for the interpolated arm), and `N_slip ≤ N_req(s) ≤ s·N_slip`.
    ///
    /// Two exceptions, both found by this test, both in table mode:
    /// - *below* `N_min` (a closed form with the load's direction taken at `N_min`,
    ///   `Capacity::below_grid`) `N_slip` can fall when the tangential force grows (see
    ///   [`table_mode_below_the_grid`]). There the property is asserted on what the
    ///   controller acts on, `max(N, N_min)`;
    /// - with a fast skew (`α > 2`): the skewed surface need not be convex and `m̃` can rise
    ///   along the sweep, so the region it bounds is not "down-closed": a larger load
    ///   component can lie inside where a smaller one does not, and `N_slip` falls. Measured
    ///   over 36 000 loads on 3000 random skewed configurations (`α` up to 100): by up to
    ///   3.5 % inside the grid (disc, k = 1.2, Δ/a = 0.95, α = 16); 1.7 % already for `α`
    ///   in 2–6; never for `α ≤ 2` (the paper's 1.1). 10 % allowed. *Above* `N_max` the
    ///   closed form holds the arm at `R(N_max)` (`Capacity::above_grid`, a conservative
    ///   bound: 2.6 × the grid-free rule in the case below), where the surface's own fall
    ///   is not diluted by a growing arm: 18 % when `f̃` grows 2.4-fold (rect, Δ/a = 0.98,
    ///   α = 70, regression `fcf7f851`), where the grid-free rule rises by 17 %. The
    ///   controller acts there on `N_max` alone (the command saturates, the status stays
    ///   `Saturated`), so for a fast skew the property is asserted on
    ///   `clamp(N, N_min, N_max)`.
    #[test]
    fn n_slip_is_monotone_and_continuous_over_the_domain(
        seed in any::<u64>(),
        table in any::<bool>(),
        skewed in prop::bool::weighted(0.3),
        loads in prop::collection::vec((-3.0f64..3.0, 0.0f64..1.0, 0.0f64..1.0, 1.0f64..4.0), 12),
    ) {
        let mut rng = SplitMix(seed);
        let mut cfg = random_config(&mut rng, skewed && table);
        cfg.mode = if table { Mode::Table } else { Mode::Ellipse };
        let Some(c) = build::<f64, Libm>(cfg) else { return Ok(()) };
        let fast_skew = cfg.skew.is_some_and(|p| p.alpha > 2.0 && p.delta_over_a > 0.0);
        let exempt = |x: f64| table && (x < cfg.n_min_n || (fast_skew && x > cfg.n_max_n));
        let fall = if table && fast_skew { 0.10 } else { 1e-12 };
        let acted = |x: f64| match (table, fast_skew) {
            (true, true) => x.clamp(cfg.n_min_n, cfg.n_max_n),
            (true, false) => x.max(cfg.n_min_n),
            _ => x,
        };
        let n = |f: f64, m: f64, s: f64| c.required_force(f, m, s).unwrap().force_n;
        for (decades, u, v, grow) in loads {
            let target = (cfg.n_min_n * cfg.n_max_n).sqrt() * 10f64.powf(decades);
            let (f, m) = load_for(&cfg, target, u, v);
            let base = n(f, m, 1.0);
            prop_assert!(base.is_finite() && base >= 0.0, "{:?}: N_slip({}, {}) = {}", cfg, f, m, base);
            for bigger in [n(f * grow, m, 1.0), n(f, m * grow, 1.0)] {
                prop_assert!(
                    acted(bigger) >= acted(base) * (1.0 - fall),
                    "{:?} ({}, {}) × {}: {} -> {}", cfg, f, m, grow, base, bigger
                );
                if !exempt(base) {
                    prop_assert!(bigger >= base * (1.0 - fall), "{:?} ({}, {})", cfg, f, m);
                }
            }
            for eps in [1e-9, 1e-6, 1e-3] {
                let bumped = n(f * (1.0 + eps), m * (1.0 + eps), 1.0);
                prop_assert!(acted(bumped) >= acted(base) * (1.0 - fall));
                prop_assert!(exempt(base) || bumped >= base * (1.0 - fall));
                prop_assert!(
                    bumped <= base * (1.0 + 3.0 * eps) + 1e-300,
                    "{:?} ({}, {}) ε = {}: {} -> {}", cfg, f, m, eps, base, bumped
                );
            }
            let req = n(f, m, cfg.safety);
            prop_assert!(req >= base * (1.0 - 1e-12) && req <= cfg.safety * base * (1.0 + 1e-9),
                "{:?} ({}, {}): N_slip {} N_req {}", cfg, f, m, base, req);
        }
    }

    /// The command over random configurations, in f32 (both backends) and f64, under
    /// streams of plausible loads across the grid, raw bit patterns (NaN, ±∞, subnormal,
    /// huge), repeated and backwards timestamps: always finite and within
    /// `[N_min, N_max]`, every output finite, the utilisation within `[0, 1e6]`, the
    /// iterations within the cap.
    #[test]
    fn the_command_is_always_finite_and_within_its_limits_over_the_domain(
        seed in any::<u64>(),
        table in any::<bool>(),
        frames in prop::collection::vec(
            (any::<u64>(), any::<u64>(), any::<u64>(), any::<u64>(), 0u64..3000, 0u8..4),
            1..200,
        ),
    ) {
        let mut rng = SplitMix(seed);
        let mut cfg = random_config(&mut rng, table && seed % 3 == 0);
        cfg.mode = if table { Mode::Table } else { Mode::Ellipse };
        stream::<f32, Libm>(cfg, &frames)?;
        stream::<f32, Micromath>(cfg, &frames)?;
        stream::<f64, Libm>(cfg, &frames)?;
    }
}

fn stream<T: Real, M: TickMath<T>>(
    cfg: ControllerConfig,
    frames: &[(u64, u64, u64, u64, u64, u8)],
) -> Result<(), TestCaseError> {
    let Some(mut c) = build::<T, M>(cfg) else {
        return Ok(());
    };
    let (lo, hi) = (T::of(cfg.n_min_n), T::of(cfg.n_max_n));
    let mut t = 0u64;
    for &(fx, fy, mz, nz, dt, kind) in frames {
        // 0: a plausible load across the grid; 1: raw f64 bit patterns; 2: raw f32 bit
        // patterns; 3: the sensor's range edges.
        let v = |b: u64, scale: f64| -> T {
            match kind {
                0 => T::of((b % 10_000) as f64 / 10_000.0 * scale),
                1 => T::of(f64::from_bits(b)),
                2 => T::of(f64::from(f32::from_bits(b as u32))),
                _ => T::of(
                    if b.is_multiple_of(2) { scale } else { -scale }
                        * (1.0 + (b % 3) as f64 * 1e-7),
                ),
            }
        };
        t = t
            .wrapping_add(dt)
            .saturating_sub(if dt < 100 { 500 } else { 0 });
        let n_span = cfg.n_max_n * 2.0;
        let m = Measurement {
            tangential_force_n: [v(fx, n_span * cfg.mu), v(fy, cfg.force_range_n)],
            torsional_moment_nm: v(mz, cfg.moment_range_nm),
            normal_force_n: v(nz, n_span),
            timestamp_us: t,
            slip: Default::default(),
        };
        let o = c.tick(&m);
        prop_assert!(
            o.command_n.is_finite() && o.command_n >= lo && o.command_n <= hi,
            "{:?}: command {:?}",
            cfg,
            o.command_n
        );
        prop_assert!(
            o.required_n.is_finite() && o.required_n >= T::zero(),
            "{:?}: {:?}",
            cfg,
            o
        );
        prop_assert!(
            o.n_slip_n.is_finite() && o.n_slip_n >= T::zero(),
            "{:?}: {:?}",
            cfg,
            o
        );
        prop_assert!(
            o.utilisation >= T::zero() && o.utilisation <= T::of(UTILISATION_MAX),
            "{:?}: {:?}",
            cfg,
            o
        );
        prop_assert!(o.iterations <= 2 * MAX_ILLINOIS_ITERATIONS);
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    /// Table mode against ellipse mode on the same load, answers inside `[N_min, N_max]`.
    /// Both are conservative by construction (tests/conservative.rs): ellipse mode tests the
    /// load against an ellipse `x²/A² + y²/B² ≤ 1` *inscribed* in the exact surface (in
    /// `(x, y) = (f̃, m̃/pitch)`, `A, B ≤ 1`, read from `demand_scale() = (1/A, 1/B)`), and
    /// table mode against the exact surface's chord polygon with its rows raised by
    /// `row_raise` (so that the interpolation between aspects never under-asks). So table
    /// mode, the closer of the two to the exact surface, asks at most what ellipse mode asks,
    /// and ellipse mode asks at most its overhead over the exact surface more. In numbers:
    /// - upper, every case: the table's region contains the ellipse but for its own margin,
    ///   `N_table ≤ N_ellipse·(1 + raise + 1e-3)`: the raise, and the table's chords and
    ///   33-direction polygon, which may cut inside the point where the ellipse touches the
    ///   exact surface (≤ 1e-3). Measured over 11 000 loads: at most `raise + 7e-6`. (With
    ///   Eq. 10's unit circle, ellipse mode asked up to 13.4 % less than table mode here.)
    /// - lower: the ellipse's radius is at least `min(A, B)`, so it asks at most
    ///   `1/min(A, B)` times what Eq. 10's unit circle asks (the demand falls at least like
    ///   `1/N`, the arm grows with `N`), and the table, never below the exact surface
    ///   (to 1e-6), asks at least the unit circle's answer over `1 + O`, the exact surface's
    ///   largest radius there: `N_table ≥ N_ellipse·min(A, B)·(1 − 1e-6)/(1 + O)`, with
    ///   `O = 0` when every aspect on the grid is ≥ 0.45 or the patch is a disc,
    ///   [`OUT_NORMALISED`] otherwise. Measured, the ratio over `min(A, B)`: down to
    ///   1.00001 when wide (a load near pure translation, where the ellipse's whole
    ///   overhead `1/A` shows), 0.962 otherwise (bound 0.942);
    /// - lower, skewed: a skew moves the surface outward, by as much as it likes for a
    ///   fast, strong skew near `k = 1`: the table asked down to 0.899 of the unit circle
    ///   (k = 1.22, Δ/a = 0.61, α = 29, l/a 0.15–0.7), so `0.88·min(A, B)` is allowed
    ///   (measured now 0.957·min(A, B): the ellipse is fitted to the skewed surface too).
    #[test]
    fn table_and_ellipse_mode_agree_within_the_radial_gap(
        seed in any::<u64>(),
        skewed in prop::bool::weighted(0.3),
        loads in prop::collection::vec((0.0f64..1.0, 0.0f64..std::f64::consts::FRAC_PI_2), 16),
    ) {
        let mut rng = SplitMix(seed);
        let cfg = random_config(&mut rng, skewed);
        let Some(e) = build::<f64, Libm>(ControllerConfig { mode: Mode::Ellipse, ..cfg }) else {
            return Ok(());
        };
        let Some(t) = build::<f64, Libm>(ControllerConfig { mode: Mode::Table, ..cfg }) else {
            return Ok(());
        };
        let [sf, sm] = e.capacity().demand_scale();
        prop_assert!(sf >= 1.0 - 1e-6 && sm >= 1.0 - 1e-6 && sf.is_finite() && sm.is_finite(),
            "{:?}: demand scale ({}, {}) is not inscribed", cfg, sf, sm);
        prop_assert_eq!(t.capacity().demand_scale(), [1.0, 1.0]);
        let min_axis = 1.0 / sf.max(sm);
        let raise = row_raise(&t);
        let contact = ContactSize::<f64>::new(cfg.c_m_per_n_gamma, cfg.gamma).unwrap();
        let thinnest = cfg.half_length_m / contact.half_width_m(cfg.n_max_n);
        let wide = cfg.shape == FingerShape::Disc || thinnest >= 0.45;
        let upper = 1.0 + raise + 1e-3;
        let lower = min_axis * match (skewed, wide) {
            (true, _) => 0.88,
            (false, true) => 1.0 - 1e-6,
            (false, false) => (1.0 - 1e-6) / (1.0 + OUT_NORMALISED),
        };
        for (pos, theta) in loads {
            let target = cfg.n_min_n * (cfg.n_max_n / cfg.n_min_n).powf(pos);
            let (f, m) = load_for(&cfg, target, 0.5 * theta.cos(), 0.5 * theta.sin());
            let ne = e.required_force(f, m, cfg.safety).unwrap().force_n;
            let nt = t.required_force(f, m, cfg.safety).unwrap().force_n;
            if !(ne >= cfg.n_min_n && ne <= cfg.n_max_n && nt >= cfg.n_min_n && nt <= cfg.n_max_n) {
                continue;
            }
            let r = nt / ne;
            prop_assert!(r <= upper && r >= lower,
                "{:?}: load ({}, {}): table {} / ellipse {} = {} not in [{}, {}]",
                cfg, f, m, nt, ne, r, lower, upper);
        }
    }
}

/// Table mode's raise of its rows (`Capacity::inflate_rows`), recomputed from the stored
/// rows: the raise multiplies every row by the same factor, so the relative first and
/// second differences it is made of are those of the rows before it (up to rounding).
fn row_raise(c: &Controller<f64, Libm>) -> f64 {
    let rows = c.capacity().tables().inv_radius;
    let (mut curve, mut slope) = (0.0f64, 0.0f64);
    for i in 0..rows.first().map_or(0, |r| r.len()) {
        let w = |e: usize| rows[e][i];
        for e in 1..rows.len() {
            slope = slope.max((w(e) - w(e - 1)).abs() / w(e).min(w(e - 1)));
        }
        for e in 1..rows.len().saturating_sub(1) {
            curve = curve.max((w(e + 1) - 2.0 * w(e) + w(e - 1)).abs() / w(e));
        }
    }
    if rows.len() > 2 {
        curve / 4.0 + slope * 0.01
    } else {
        slope * 0.5
    }
}

/// The constants above, re-measured so that they cannot go stale: the normalised gap and
/// excursion of the symmetric surfaces at the extreme aspects, for k = 1, 2 and uniform.
#[test]
fn the_documented_gaps_are_the_measured_ones() {
    let (mut gap, mut out, mut thin) = (0.0f64, 0.0f64, 0.0f64);
    for k in [1.0, 2.0, f64::INFINITY] {
        for shape in [
            Shape::Rect { aspect: 1e-3 },
            Shape::Rect { aspect: 0.45 },
            Shape::Rect { aspect: 1e3 },
            Shape::Disc,
        ] {
            let m = model(shape, k, None, 28);
            let t = FlsTable::<f64, 1100>::sweep(&m, 1024).unwrap();
            let p = t.pitch();
            for q in t.points() {
                let r = q.f.hypot(q.m / p);
                gap = gap.max(1.0 - r);
                if shape == (Shape::Rect { aspect: 0.45 }) {
                    assert!(r <= 1.0 + 1e-12, "l/a = 0.45 is inside: {q:?}");
                } else {
                    out = out.max(r - 1.0);
                }
            }
            thin = thin.max(RadialGap::find(&m, &t).max_outside);
        }
    }
    eprintln!("normalised gap {gap:.4}, normalised excursion {out:.4}, (f̃, m̃) excursion {thin:.4}");
    assert!(
        gap <= GAP_NORMALISED && gap > GAP_NORMALISED - 2e-4,
        "{gap}"
    );
    assert!(
        out <= OUT_NORMALISED && out > OUT_NORMALISED - 2e-4,
        "{out}"
    );
    assert!(thin <= THIN_OUTSIDE && thin > THIN_OUTSIDE - 2e-3, "{thin}");
}

/// The one place where `N_slip` is not monotone in the load (found by
/// [`n_slip_is_monotone_and_continuous_over_the_domain`]): table mode below `N_min`, where
/// `Capacity::below_grid` solves a quadratic with the surface's inverse radius `w` taken
/// in the load's direction *at `N_min`*. A larger tangential force turns that direction
/// toward translation, where `w` is smaller, and the answer can fall (here by 5.7 % when
/// `f̃` grows tenfold). What still holds, and is asserted: the answer stays a conservative
/// bound (above the grid-free rule, here by 30–86 %), and below `N_min`, so the command,
/// which is clamped to `[N_min, N_max]`, is not affected.
#[test]
fn table_mode_below_the_grid() {
    let cfg = ControllerConfig {
        mu: 0.623,
        shape: FingerShape::Disc,
        k: 3.295,
        c_m_per_n_gamma: 2.267e-3,
        gamma: 0.5,
        n_min_n: 0.0662,
        n_max_n: 164.7,
        fault_force_n: 90.0,
        mode: Mode::Table,
        force_nodes: 50,
        table_samples: 79,
        ..ControllerConfig::default()
    };
    let c = Controller::<f64>::new(cfg).unwrap();
    let (f, m) = (6.793e-5, 2.981e-7);
    let first = c.slip_force(f, m).unwrap().force_n;
    let mut fell = 0.0f64;
    for grow in [1.0, 1.5, 2.0, 4.0, 10.0] {
        let n = c.slip_force(f * grow, m).unwrap().force_n;
        let exact = exact_required(&cfg, f * grow, m, 1.0);
        assert!(
            n >= exact && n < cfg.n_min_n,
            "f × {grow}: {n} vs exact {exact}"
        );
        fell = fell.max(1.0 - n / first);
    }
    eprintln!(
        "table mode below N_min: N_slip falls by up to {:.1} % as f grows",
        100.0 * fell
    );
}
