//! Hard cases for the numerics, table-driven: every case asserts a finite result within a
//! stated tolerance of a reference (a closed form written in `tests/common/stress_cases.rs`
//! from docs/model.md, an asymptotic law, the brute force of `softgrip-reference` (reference/), or
//! the same integral at the highest quadrature order).
//!
//! The domain's corners: `k` from 1 to 1e6 and `∞`; skew `Δ/a` up to 0.999999; the centre of
//! rotation at 0, 1e-12, exactly on the patch edge and at 1e12; aspect ratios 1e-3 to 1e3;
//! `γ` at 0 and 1/2; normal forces from 1e-9 to 1e6 N; `T/μN` at 0, 1 − 1e-15, 1 and above
//! in the partial-slip formulas; zero loads, and loads no force up to `N_max` can hold.
//!
//! `cargo test --release --test stress -- --nocapture` prints the worst deviation of each
//! table; docs/robustness.md quotes them.

#[path = "common/stress_cases.rs"]
mod stress_cases;

use softgrip::contact::ContactSize;
use softgrip::controller::{
    Controller, ControllerConfig, FingerShape, Measurement, Micromath, Mode, SkewParams, Status,
    MAX_ILLINOIS_ITERATIONS_F32, UTILISATION_MAX,
};
use softgrip::partial_slip::{deflection_m, stick_radius, Elasticity};
use softgrip::skew::SkewLaw;
use softgrip::Shape;
use softgrip_reference::{pressure_total, Case, Patch};
use stress_cases::*;

/// One checked value: `got − want` must lie in `[lo, hi]`.
struct Row {
    case: String,
    got: f64,
    want: f64,
    lo: f64,
    hi: f64,
}

impl Row {
    /// `|got − want| ≤ tol`.
    fn tol(case: impl Into<String>, got: f64, want: f64, tol: f64) -> Self {
        Self {
            case: case.into(),
            got,
            want,
            lo: -tol,
            hi: tol,
        }
    }

    /// `got − want ∈ [lo, hi]`: a one-sided (conservative) error band.
    fn band(case: impl Into<String>, got: f64, want: f64, lo: f64, hi: f64) -> Self {
        Self {
            case: case.into(),
            got,
            want,
            lo,
            hi,
        }
    }
}

/// Checks every row, prints the range of the errors and the worst use of a band (the error
/// over the bound on its side), and fails listing every row that is not finite or out of
/// its band.
fn check(table: &str, rows: &[Row]) {
    let mut bad = Vec::new();
    let mut worst = (0.0f64, String::new());
    let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
    for r in rows {
        let err = r.got - r.want;
        if !(r.got.is_finite() && err >= r.lo && err <= r.hi) {
            bad.push(format!(
                "{}: got {:e}, want {:e} (error {:e} outside [{:e}, {:e}])",
                r.case, r.got, r.want, err, r.lo, r.hi
            ));
        }
        min = min.min(err);
        max = max.max(err);
        let bound = if err >= 0.0 { r.hi } else { r.lo };
        let used = if bound == 0.0 { 0.0 } else { err / bound };
        if used > worst.0 || worst.1.is_empty() {
            worst = (used, r.case.clone());
        }
    }
    eprintln!(
        "{table}: {} cases, errors in [{min:.2e}, {max:.2e}], worst {:.3} of its bound ({})",
        rows.len(),
        worst.0,
        worst.1
    );
    assert!(bad.is_empty(), "{table}:\n{}", bad.join("\n"));
}

const K_VALUES: [f64; 10] = [
    1.0,
    1.0 + 1e-9,
    1.5,
    2.0,
    3.0,
    7.5,
    50.0,
    1e3,
    1e6,
    f64::INFINITY,
];
const ASPECTS: [f64; 9] = [1e-3, 1e-2, 0.1, 0.5, 1.0, 2.0, 10.0, 100.0, 1e3];
/// The largest skew of the suite, and its rate.
const DELTA: f64 = 0.999_999;

fn shape_name(shape: Shape) -> String {
    match shape {
        Shape::Rect { aspect } => format!("rect l/a={aspect:e}"),
        Shape::Disc => "disc".into(),
    }
}

fn edge(shape: Shape) -> f64 {
    match shape {
        Shape::Rect { aspect } => aspect,
        Shape::Disc => 1.0,
    }
}

/// Pitches against closed forms over the whole range of `k` and of the aspect ratio.
///
/// Tolerances: the fast path is within 5e-11 of the converged integral at the default order
/// (tests/fls_accuracy.rs); `ln Γ` at the tiny arguments `j/k` of `k = 1e6` (about 13 in
/// magnitude) adds 1e-14. So 1e-10 absolute on the disc; relative 1e-10 on the rectangle,
/// whose pitch grows like `λ/2`.
#[test]
fn pitches_over_k_and_aspect_match_closed_forms() {
    let mut rows = Vec::new();
    for k in K_VALUES {
        let got = model(Shape::Disc, k, None, 28).pitch();
        rows.push(Row::tol(
            format!("disc k={k:e}: B(3/k,1+1/k)/B(2/k,1+1/k)"),
            got,
            disc_pitch(k),
            1e-10,
        ));
    }
    for aspect in ASPECTS {
        let want = rect_uniform_pitch(aspect);
        let shape = Shape::Rect { aspect };
        rows.push(Row::tol(
            format!("rect l/a={aspect:e} k=inf: uniform closed form"),
            model(shape, f64::INFINITY, None, 28).pitch(),
            want,
            1e-10 * want,
        ));
        // k = 1e6 is uniform pressure up to a boundary layer of width ~1/k where the
        // profile falls by O(1/k): its weight is (π²/6)/k² ≈ 2e-12.
        rows.push(Row::tol(
            format!("rect l/a={aspect:e} k=1e6: effectively uniform"),
            model(shape, 1e6, None, 28).pitch(),
            want,
            1e-10 * want,
        ));
    }
    // A vanishingly thin strip across the sliding direction: the pitch tends to E|y| (in
    // units of a); at l/a = 1e-3 the difference is O(λ² ln(1/λ)) ≈ 7e-6.
    for k in [1.0, 2.0, 4.0, 1e6, f64::INFINITY] {
        let got = model(Shape::Rect { aspect: 1e-3 }, k, None, 28).pitch();
        rows.push(Row::tol(
            format!("rect l/a=1e-3 k={k:e}: thin-strip limit E|y|"),
            got,
            rect_abs_y(k),
            2e-5,
        ));
    }
    check("pitch closed forms", &rows);
}

/// Limit-surface points at the hard centres of rotation, for the corners of the domain,
/// against the same integral at the highest order (converged to about 1e-15). Tolerance
/// 1e-9 times the surface's scale `max(1, pitch)` (the pitch grows like `λ/2`): the
/// documented accuracy of the default order is 5e-11 for aspects 0.05 to 20. The thin strip
/// `l/a = 1e-3` converges more slowly in `f̃` (the row kernels vary on the scale `λ` in `y`,
/// where the `y` integral has no split): measured 3.2e-9 at `d ≈ λ` (orders 28, 40, 64:
/// 3.2e-9, 8e-12, 3e-16), so 5e-9 there.
#[test]
fn points_at_hard_centres_of_rotation_match_the_converged_integral() {
    let mut rows = Vec::new();
    let shapes = [
        Shape::Rect { aspect: 1e-3 },
        Shape::Rect { aspect: 1.0 },
        Shape::Rect { aspect: 1e3 },
        Shape::Disc,
    ];
    for shape in shapes {
        for k in [1.0, 2.0, 1e6, f64::INFINITY] {
            // The skewed disc is a 2-D integral (about 4 ms a point at order 128): only k = 2.
            let skews: &[Option<(f64, f64, f64)>] = match shape {
                Shape::Disc if k != 2.0 => &[None],
                _ => &[None, Some((DELTA, 1.1, DELTA / 2.0))],
            };
            for &skew in skews {
                let fast = model(shape, k, skew, 28);
                let exact = model(shape, k, skew, REFERENCE_ORDER);
                let e = edge(shape);
                let scale = fast.pitch().max(1.0);
                let tol = if e < 0.05 { 5e-9 } else { 1e-9 };
                for d in [
                    0.0,
                    1e-12,
                    1e-6,
                    0.5 * e,
                    e,
                    e * (1.0 + 1e-12),
                    3.0 * e,
                    1e6,
                    1e12,
                ] {
                    let (a, b) = (fast.point(d), exact.point(d));
                    let name = format!(
                        "{} k={k:e} skew={} d={d:e}",
                        shape_name(shape),
                        skew.is_some()
                    );
                    rows.push(Row::tol(format!("{name} f"), a.f, b.f, tol));
                    rows.push(Row::tol(format!("{name} m"), a.m, b.m, tol * scale));
                }
            }
        }
    }
    check("points vs order 128", &rows);
}

/// `E[yⁿ]` under the rectangle's pressure with the peak at `Δy` (units of `a`; `Δy = 0` is
/// the symmetric profile), from the profile's moments `G_j = ∫₀¹ s^j g(s) ds`: above the
/// peak `y = Δy + ρ₊ s`, below `y = Δy − ρ₋ s`, `ρ± = 1 ∓ Δy`, each half weighted by its
/// length (the ray-scaled profile).
fn rect_y_moment(k: f64, dy: f64, n: i32) -> f64 {
    let (up, down) = (1.0 - dy, 1.0 + dy);
    let mut sum = 0.0;
    let mut binom = 1.0;
    for j in 0..=n {
        let g = profile_moment(k, f64::from(j));
        let rest = dy.powi(n - j);
        sum += binom * rest * g * (up * up.powi(j) + down * (-down).powi(j));
        binom = binom * f64::from(n - j) / f64::from(j + 1);
    }
    sum / (2.0 * profile_moment(k, 0.0))
}

/// The far field: with the centre of rotation at `d ≫ 1` the patch nearly translates.
/// Expanding `(x(x−d) + y²)/|(−y, x−d)|` in `1/d` (the terms odd in `x` vanish by symmetry):
///
/// `m̃·d = E[y²] + (2E[x²y²] − E[y⁴]/2)/d² + O(d⁻⁴)`, and `f̃ = ∫p/N + O(d⁻²)`,
///
/// with `E[x²y²] = (λ²/3)E[y²]` on the rectangle and `E[r⁴]/8`, `E[y⁴] = 3E[r⁴]/8` on the
/// disc. At `d = 1e6` and `1e12` this checks the fast path's cancellation-free far field
/// *relatively* (the absolute comparison above sees only zeros there), including the
/// second-order term, which is 6.7e-7 of `m̃·d` at `l/a = 1e3`, `d = 1e6`: tolerance 1e-9
/// relative on `m̃·d` (the neglected `O((λ/d)⁴)` is 1e-12), 1e-12 on `f̃ − 1`.
#[test]
fn far_field_moment_falls_like_the_second_moment_over_d() {
    let mut rows = Vec::new();
    for k in [1.0, 2.0, 4.0, 1e6, f64::INFINITY] {
        for d in [1e6, 1e12] {
            for aspect in [1e-3, 1.0, 1e3] {
                let shape = Shape::Rect { aspect };
                let name = format!("{} k={k:e} d={d:e}", shape_name(shape));
                // The skew saturates far out (Δy = Δ).
                for dy in [0.0, DELTA] {
                    let skew = (dy > 0.0).then_some((DELTA, 1.1, 0.0));
                    let p = model(shape, k, skew, 28).point(d);
                    let (y2, y4) = (rect_y_moment(k, dy, 2), rect_y_moment(k, dy, 4));
                    let want = y2 + (2.0 * aspect * aspect / 3.0 * y2 - y4 / 2.0) / (d * d);
                    rows.push(Row::tol(
                        format!("{name} Δy={dy} m·d"),
                        p.m * d,
                        want,
                        1e-9 * want,
                    ));
                    rows.push(Row::tol(format!("{name} Δy={dy} f"), p.f, 1.0, 1e-12));
                }
            }
            let p = model(Shape::Disc, k, None, 28).point(d);
            let r2 = profile_moment(k, 3.0) / profile_moment(k, 1.0);
            let r4 = profile_moment(k, 5.0) / profile_moment(k, 1.0);
            let want = r2 / 2.0 + r4 / 16.0 / (d * d);
            rows.push(Row::tol(
                format!("disc k={k:e} d={d:e} m·d"),
                p.m * d,
                want,
                1e-9 * want,
            ));
            rows.push(Row::tol(format!("disc k={k:e} d={d:e} f"), p.f, 1.0, 1e-12));
        }
    }
    // The moments themselves: the symmetric E[y²] is docs/model.md's 1/4 for k = 2 (Hertz strip)
    // and 1/3 for uniform pressure.
    assert!((rect_y_moment(2.0, 0.0, 2) - 0.25).abs() < 1e-15);
    assert!((rect_y_moment(f64::INFINITY, 0.0, 2) - 1.0 / 3.0).abs() < 1e-15);
    assert!((rect_y_moment(2.0, 0.3, 0) - 1.0).abs() < 1e-15);
    check("far field", &rows);
}

/// The largest skews: the pitch does not move (the skew law puts the peak at the centre at
/// `d = 0`), the ray-scaled pressure still integrates to `N` with the peak 1e-6 from the
/// edge (brute force at 32 cells: documented 1e-9; 1e-8 allowed), and the fast path's
/// far-field force is `∫p/N = 1` (tolerance 1e-12: the `O(d⁻²)` rest is 1e-16 at
/// `d = 1e8`).
#[test]
fn skews_up_to_0_999999_keep_the_pitch_and_the_equilibrium() {
    let mut rows = Vec::new();
    for delta in [0.9, 0.99, 0.9999, DELTA] {
        for k in [1.0, 2.0, 4.0, 1e6, f64::INFINITY] {
            for shape in [
                Shape::Rect { aspect: 1e-3 },
                Shape::Rect { aspect: 1.0 },
                Shape::Rect { aspect: 1e3 },
                Shape::Disc,
            ] {
                let name = format!("{} k={k:e} Δ/a={delta}", shape_name(shape));
                let plain = model(shape, k, None, 28).pitch();
                // Locus 0 on the disc keeps it cheap (1-D rows); the circular locus is
                // covered at k = 2 below.
                let locus = if shape == Shape::Disc {
                    0.0
                } else {
                    delta / 2.0
                };
                let skewed = model(shape, k, Some((delta, 1.1, locus)), 28);
                rows.push(Row::tol(
                    format!("{name} pitch"),
                    skewed.pitch(),
                    plain,
                    1e-14 * plain.max(1.0),
                ));
                rows.push(Row::tol(
                    format!("{name} f̃(1e8) = ∫p/N"),
                    skewed.point(1e8).f,
                    1.0,
                    1e-12,
                ));
            }
            if k.is_finite() {
                // Brute-force pressure totals with the peak where the skew law puts it.
                let law = SkewLaw::<f64>::circular(delta, 1.1).unwrap();
                for patch in [Patch::Rect { aspect: 1.0 }, Patch::Disc] {
                    for d in [0.3, 3.0, 50.0] {
                        let peak = law.peak(d);
                        let peak = if patch == Patch::Disc {
                            peak
                        } else {
                            (0.0, peak.1)
                        };
                        rows.push(Row::tol(
                            format!("{patch:?} k={k:e} Δ/a={delta} peak {peak:?}: ∫p/N"),
                            pressure_total(patch, k, peak, 32),
                            1.0,
                            1e-8,
                        ));
                    }
                }
            }
        }
    }
    // The skewed disc with the circular locus (a 2-D integral), at its largest skew.
    let disc = model(Shape::Disc, 2.0, Some((DELTA, 1.1, DELTA / 2.0)), 28);
    rows.push(Row::tol(
        "disc k=2 circular locus Δ/a=0.999999 f̃(1e8)",
        disc.point(1e8).f,
        1.0,
        1e-12,
    ));
    let case = Case {
        patch: Patch::Disc,
        k: 2.0,
        skew: Some((DELTA, 1.1, DELTA / 2.0)),
    };
    for d in [0.05, 0.7, 2.0] {
        let (f, m) = case.point(d, 32);
        let p = disc.point(d);
        rows.push(Row::tol(
            format!("disc k=2 circular Δ/a={DELTA} d={d}: f vs brute force"),
            p.f,
            f,
            1e-7,
        ));
        rows.push(Row::tol(
            format!("disc k=2 circular Δ/a={DELTA} d={d}: m vs brute force"),
            p.m,
            m,
            1e-7,
        ));
    }
    check("largest skews", &rows);
}

/// The contact size from 1e-9 to 1e6 N (and the total function's edges), in f64 and f32,
/// against `c·N^γ` computed here. f64: 1 ulp of `powf`; f32: a few ulp.
#[test]
fn contact_size_from_1e_9_to_1e6_newtons() {
    let mut rows = Vec::new();
    for gamma in [0.0, 1.0 / 3.0, 0.5] {
        let c = 2.5e-3;
        let s64 = ContactSize::<f64>::new(c, gamma).unwrap();
        let s32 = ContactSize::<f32>::new(c, gamma).unwrap();
        for n in [1e-9f64, 1e-6, 1e-3, 1.0, 1e3, 1e6] {
            let want = c * n.powf(gamma);
            rows.push(Row::tol(
                format!("γ={gamma} N={n:e} f64"),
                s64.half_width_m(n),
                want,
                4.0 * f64::EPSILON * want,
            ));
            rows.push(Row::tol(
                format!("γ={gamma} N={n:e} f32"),
                f64::from(s32.half_width_m(n as f32)),
                want,
                8.0 * f64::from(f32::EPSILON) * want,
            ));
            if gamma > 0.0 {
                let back = s64.normal_force_n(want).unwrap();
                rows.push(Row::tol(
                    format!("γ={gamma} N={n:e} inverse"),
                    back,
                    n,
                    1e-13 * n,
                ));
            }
        }
        // The total function's edges: no force, a negative or NaN force.
        for n in [0.0, -1.0, f64::NAN] {
            rows.push(Row::tol(
                format!("γ={gamma} N={n}"),
                s64.half_width_m(n),
                if gamma == 0.0 { c } else { 0.0 },
                0.0,
            ));
        }
    }
    check("contact size", &rows);
}

/// Cattaneo–Mindlin at the edges of the load ratio, in f64 and f32. References from the
/// exact complement `1 − r` (Sterbenz: exact for `r ∈ [½, 1]`): the stick radius
/// `a·cbrt(1 − r)` and the deflection bracket `1 − (1 − r)^(2/3)`; at and above 1 (and NaN)
/// gross slip. Tolerance: 4 ulp of the result. In f32, `1 − 1e-15` rounds to 1: gross slip.
#[test]
fn partial_slip_at_zero_near_one_one_and_beyond() {
    let mut rows = Vec::new();
    let a = 0.01;
    let el64 = Elasticity::<f64>::new(3e5, 0.45).unwrap();
    let el32 = Elasticity::<f32>::new(3e5, 0.45).unwrap();
    let (mu_n, g) = (2.0, 3e5 / (2.0 + 2.0 * 0.45));
    let limit = 3.0 * mu_n / (16.0 * a) * (2.0 - 0.45) / g;
    let ratios = [
        0.0,
        f64::from_bits(1), // the smallest subnormal
        1e-300,
        1e-15,
        0.5,
        1.0 - 1e-15,
        1.0 - f64::EPSILON / 2.0,
        1.0,
        1.0 + 1e-15,
        2.0,
        1e300,
        f64::INFINITY,
        -0.5,
        -(1.0 - 1e-15),
        f64::NAN,
    ];
    for r in ratios {
        let q = if r.is_nan() { 1.0 } else { r.abs().min(1.0) };
        let comp = 1.0 - q; // exact for q >= 1/2; q < 1/2 is exact enough (relative 1 ulp)
        let stick = a * comp.cbrt();
        // 1 − (1 − q)^(2/3) without cancellation for tiny q: −expm1(⅔·ln1p(−q)).
        let bracket = if q == 1.0 {
            1.0
        } else {
            -((2.0 / 3.0) * (-q).ln_1p()).exp_m1()
        };
        rows.push(Row::tol(
            format!("stick radius f64 r={r:e}"),
            stick_radius(a, r),
            stick,
            4.0 * f64::EPSILON * stick,
        ));
        rows.push(Row::tol(
            format!("deflection f64 r={r:e}"),
            deflection_m(&el64, mu_n, a, r),
            limit * bracket,
            8.0 * f64::EPSILON * limit * bracket,
        ));
        let r32 = r as f32;
        let q32 = if r32.is_nan() {
            1.0
        } else {
            f64::from(r32.abs().min(1.0))
        };
        let stick32 = a * (1.0 - q32).cbrt();
        let bracket32 = if q32 == 1.0 {
            1.0
        } else {
            -((2.0 / 3.0) * (-q32).ln_1p()).exp_m1()
        };
        rows.push(Row::tol(
            format!("stick radius f32 r={r:e}"),
            f64::from(stick_radius(a as f32, r32)),
            stick32,
            4.0 * f64::from(f32::EPSILON) * stick32,
        ));
        rows.push(Row::tol(
            format!("deflection f32 r={r:e}"),
            f64::from(deflection_m(&el32, mu_n as f32, a as f32, r32)),
            limit * bracket32,
            8.0 * f64::from(f32::EPSILON) * limit * bracket32 + f64::from(f32::MIN_POSITIVE),
        ));
    }
    check("partial slip", &rows);
}

fn cfg_for(shape: FingerShape, gamma: f64, mode: Mode) -> ControllerConfig {
    ControllerConfig {
        shape,
        gamma,
        c_m_per_n_gamma: if gamma == 0.0 { 6e-3 } else { 2.5e-3 },
        mode,
        ..ControllerConfig::default()
    }
}

/// The demand scale `(1/A, 1/B)` of a controller: ellipse mode tests the load against the
/// ellipse `x²/A² + y²/B² ≤ 1` inscribed in the exact surface, which is Eq. 10's unit
/// circle applied to the load `(f/A, m/B)`; `(1, 1)` in table mode.
fn demand_scale(c: &Controller<f64>) -> (f64, f64) {
    let [sf, sm] = c.capacity().demand_scale();
    (sf, sm)
}

/// `N_req(s)` for a disc with `a = c·√N` in ellipse mode, for the load as the test sees
/// it (`f`, `m` already times the demand scale): the root of
/// `N³ − F²N − (M/(c·pitch))² = 0` (Newton from above, converged to the last bit).
fn disc_half_gamma_ellipse(cfg: &ControllerConfig, f: f64, m: f64, s: f64) -> f64 {
    let (ff, mm) = (
        s * f / cfg.mu,
        s * m / (cfg.mu * cfg.c_m_per_n_gamma * disc_pitch(cfg.k)),
    );
    let mut n = ff + mm.powf(2.0 / 3.0) + 1.0;
    for _ in 0..200 {
        let next = n - (n * n * n - ff * ff * n - mm * mm) / (3.0 * n * n - ff * ff);
        if next >= n {
            break;
        }
        n = next;
    }
    n
}

/// The rule at `γ = 0` and `γ = 1/2` on both shapes, in both modes, against references
/// without any grid: the closed form of a fixed rectangle
/// (`N = s·|(F/A, M/(c·pitch·B))|`, pitch at order 128), the cubic of the disc with
/// `a ∝ √N`, and the bisection of `exact_required` (ellipse mode on the rectangle with
/// `γ = 1/2`; table mode). Ellipse mode's references use the controller's own inscribed
/// semi-axes `(A, B)` (`demand_scale()` is `(1/A, 1/B)`): the load `(f/A, m/B)` against the
/// unit circle.
///
/// Tolerances and their sign: a fixed contact has an exact arm, so the answer is exact to
/// the solver's 8 ulp (1e-12 relative). With `γ = 1/2` the arm is interpolated linearly
/// between nodes spaced `Δ ln N = ln(100)/47` apart, which understates the concave arm by at
/// most `γ(1−γ)/8·(Δ ln N)² = 3.0e-4` relative and so overstates the force: the error must
/// lie in `[−1e-12, 3.1e-4]`. Table mode adds its chords' error and the raise of its rows
/// that makes the aspect interpolation conservative (about 1e-3), both on the safe side:
/// `[−1e-12, 3e-3]` (measured up to 1.75e-3). Outside `[N_min, N_max]` only the
/// conservative sign is promised.
#[test]
fn the_rule_at_gamma_zero_and_one_half_on_both_shapes() {
    let mut rows = Vec::new();
    let mut unsafe_rows = Vec::new();
    let loads = [
        (0.0, 1e-6),
        (1e-4, 0.0),
        (0.05, 1e-5),
        (1.0, 0.0),
        (0.5, 4e-3),
        (0.0, 0.02),
        (6.0, 0.05),
        (20.0, 0.3),
    ];
    for shape in [FingerShape::Rect, FingerShape::Disc] {
        for gamma in [0.0, 0.5] {
            for mode in [Mode::Ellipse, Mode::Table] {
                let cfg = cfg_for(shape, gamma, mode);
                let c = Controller::<f64>::new(cfg).unwrap();
                let s = cfg.safety;
                let (sf, sm) = demand_scale(&c);
                if mode == Mode::Table {
                    assert_eq!((sf, sm), (1.0, 1.0), "table mode scales no demand");
                } else {
                    // Inscribed in the exact surface, which crosses the axes at 1.
                    assert!(sf >= 1.0 && sm >= 1.0, "{shape:?} γ={gamma}: {sf} {sm}");
                }
                for &(f, m) in &loads {
                    let got = c.required_force(f, m, s).unwrap().force_n;
                    let (want, tol) = match (shape, gamma == 0.0, mode) {
                        (FingerShape::Rect, true, Mode::Ellipse) => {
                            let a = cfg.c_m_per_n_gamma;
                            let pitch = model(
                                Shape::Rect {
                                    aspect: cfg.half_length_m / a,
                                },
                                cfg.k,
                                None,
                                REFERENCE_ORDER,
                            )
                            .pitch();
                            let want = s * (f * sf / cfg.mu).hypot(m * sm / (cfg.mu * a * pitch));
                            (want, 1e-12)
                        }
                        (FingerShape::Disc, true, Mode::Ellipse) => {
                            let a = cfg.c_m_per_n_gamma;
                            let want = s
                                * (f * sf / cfg.mu)
                                    .hypot(m * sm / (cfg.mu * a * disc_pitch(cfg.k)));
                            (want, 1e-12)
                        }
                        (FingerShape::Disc, _, Mode::Ellipse) => {
                            (disc_half_gamma_ellipse(&cfg, f * sf, m * sm, s), 3.1e-4)
                        }
                        // Eq. 10 at the scaled load in ellipse mode (sf = sm = 1 in table
                        // mode, where `exact_required` reads the 1024-sample surface).
                        _ => (exact_required(&cfg, f * sf, m * sm, s), 3e-3),
                    };
                    let rel = (got - want) / want;
                    let name = format!("{shape:?} γ={gamma} {mode:?} load ({f}, {m})");
                    if rel < -1e-12 {
                        unsafe_rows.push(format!("{name}: {got} < exact {want}"));
                    }
                    if want >= cfg.n_min_n && want <= cfg.n_max_n {
                        let lo = if tol > 1e-12 { -1e-12 } else { -tol };
                        rows.push(Row::band(name, rel, 0.0, lo, tol));
                    }
                }
            }
        }
    }
    check("rule at γ = 0, 1/2 (relative error, one-sided band)", &rows);
    assert!(unsafe_rows.is_empty(), "{}", unsafe_rows.join("\n"));
}

/// Table mode's raise of its rows (`Capacity::inflate_rows`), recomputed from the stored
/// rows: the raise multiplies every row by the same factor, so the relative first and
/// second differences it is made of are those of the rows before it (up to rounding).
fn row_raise(c: &Controller<f64>) -> f64 {
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

/// A grid from 1e-9 to 1e6 N (64 nodes, `Δ ln N = ln(1e15)/63 = 0.55`), loads whose answers
/// span it, in f64 and f32, both modes, `γ = 1/3` and `1/2`, against the grid-free rule
/// (ellipse mode: Eq. 10 at the load times the controller's demand scale `(1/A, 1/B)`, its
/// inscribed ellipse; table mode: the 1024-sample exact surface).
///
/// - Ellipse mode: the arm's interpolation error `γ(1−γ)/8·(Δ ln N)² ≤ 9.4e-3`, always
///   conservative: the error must lie in `[−1e-9, 9.4e-3]` (measured: −8e-14 to 4.5e-3).
/// - Table mode is conservative by construction: its rows are raised (`row_raise`) to cover
///   the interpolation of the surface between 12 aspects spread over the 7.5 decades of
///   `l/a` this range of forces sweeps, which is linear in `ln(l/a)` and not conservative
///   by itself. On this coarse aspect grid the raise is large: 1.36e-2 (rectangle,
///   `γ = 1/3`) and 2.04e-2 (`γ = 1/2`); 0 on the disc (one row). So the error must lie in
///   `[−1e-6, raise + 9.4e-3 + 1e-3]`: the raise, the arm's interpolation, and the chords
///   and 33-direction polygon (≤ 1e-3). Measured: 7.7e-4 to 2.41e-2, the raise plus −2.7e-3
///   to 4.8e-3.
/// - f32 (grid precomputed in f64, stored and solved in f32) against f64: within 7e-7,
///   except below 5e-9 N on the disc with `γ = 1/2`, where `φ ≈ N²R² ≈ 1e-32` and the
///   Illinois secant product `φ·(b − a)` underflows f32's normal range, so the 16 steps end
///   with a wider bracket (measured: 1.1e-3 at 2.8e-9 N, all 16 steps spent), on the safe
///   side (the upper end). Band `[−1e-6, 1e-2]` below 5e-9 N as for the translations
///   below, `[−1e-6, 1e-4]` above.
/// - Pure translations need exactly `s·f_t/(μ·A)` in ellipse mode (`A` the inscribed
///   ellipse's force semi-axis): f64 within 1e-13. In f32 the same underflow costs
///   accuracy below about 1e-8 N where the arm is small (the disc: `R = a·pitch ≈ 5e-8 m`
///   at 1e-9 N, so `φ ≈ 1e-33`): measured 5.6e-3 at 1.6e-9 N, 2.5e-5 at 1e-8 N, 3.7e-7 at
///   1e-7 N (disc, `γ = 1/2`), always high (safe); the rectangle's arm stays near `l/2` and
///   keeps 5e-7. Bands: `[−1e-6, 1e-2]` below 5e-9 N, `1e-4` below 5e-8 N, `1e-6` above.
#[test]
fn normal_forces_from_1e_9_to_1e6_newtons() {
    let mut rows = Vec::new();
    for shape in [FingerShape::Rect, FingerShape::Disc] {
        for gamma in [1.0 / 3.0, 0.5] {
            for mode in [Mode::Ellipse, Mode::Table] {
                let cfg = corner_grid_config(shape, mode, gamma);
                let c64 = Controller::<f64>::new(cfg).unwrap();
                let c32 = Controller::<f32>::new_precomputed_in::<f64>(cfg).unwrap();
                let contact = ContactSize::<f64>::new(cfg.c_m_per_n_gamma, gamma).unwrap();
                let (sf, sm) = demand_scale(&c64);
                let raise = row_raise(&c64);
                // Pure translations: in ellipse mode `N = s·f_t/(μ·A)` exactly, whatever
                // the arm (`A` the inscribed force semi-axis: `1/A` is the f32 controller's
                // own stored scale in f32, rounded from the f64 fit).
                if mode == Mode::Ellipse {
                    let sf32 = f64::from(c32.capacity().demand_scale()[0]);
                    for n in [1.2e-9, 1.6e-9, 3e-9, 1e-8, 1e-7, 1e-6, 1.0, 5e5] {
                        let f = n * cfg.mu / cfg.safety;
                        let sol = c32
                            .required_force(f as f32, 0.0, cfg.safety as f32)
                            .unwrap();
                        let got = f64::from(sol.force_n);
                        let want = n * sf32;
                        // A solve stopped by the f32 iteration cap returns its bracket's
                        // upper end: conservative, by up to 1 % on this coarse grid
                        // (tests/controller.rs, `the_f32_iteration_cap_...`).
                        let at_cap = sol.iterations >= MAX_ILLINOIS_ITERATIONS_F32;
                        rows.push(Row::band(
                            format!("{shape:?} γ={gamma:.3} translation N={want:e} f32"),
                            got / want - 1.0,
                            0.0,
                            -1e-6,
                            if want < 5e-9 || at_cap {
                                1e-2
                            } else if want < 5e-8 {
                                1e-4
                            } else {
                                1e-6
                            },
                        ));
                        let got = c64.required_force(f, 0.0, cfg.safety).unwrap().force_n;
                        let want = n * sf;
                        rows.push(Row::tol(
                            format!("{shape:?} γ={gamma:.3} translation N={want:e} f64"),
                            got / want - 1.0,
                            0.0,
                            1e-13,
                        ));
                    }
                }
                for n in [3e-9, 1e-6, 1e-3, 1.0, 1e3, 5e5] {
                    // A load that needs about `n`: a share of the translation and of the
                    // torsion the contact at `n` can carry.
                    let a = contact.half_width_m(n);
                    let (f, m) = (0.4 * cfg.mu * n, 0.3 * cfg.mu * n * a);
                    // Ellipse mode: Eq. 10 at the scaled load (sf = sm = 1 in table mode).
                    let want = exact_required(&cfg, f * sf, m * sm, cfg.safety);
                    let got = c64.required_force(f, m, cfg.safety).unwrap().force_n;
                    let got32 = f64::from(
                        c32.required_force(f as f32, m as f32, cfg.safety as f32)
                            .unwrap()
                            .force_n,
                    );
                    let name = format!("{shape:?} γ={gamma:.3} {mode:?} N≈{n:e}");
                    let (lo, hi) = match mode {
                        Mode::Ellipse => (-1e-9, 9.4e-3),
                        Mode::Table => (-1e-6, raise + 9.4e-3 + 1e-3),
                    };
                    rows.push(Row::band(
                        format!("{name} f64 vs grid-free"),
                        (got - want) / want,
                        0.0,
                        lo,
                        hi,
                    ));
                    rows.push(Row::band(
                        format!("{name} f32 vs f64"),
                        got32 / got - 1.0,
                        0.0,
                        -1e-6,
                        if got < 5e-9 { 1e-2 } else { 1e-4 },
                    ));
                }
            }
        }
    }
    check("1e-9 to 1e6 N (relative error)", &rows);
}

fn meas(f: f64, m: f64, n: f64, t: u64) -> Measurement<f64> {
    Measurement {
        tangential_force_n: [f, 0.0],
        torsional_moment_nm: m,
        normal_force_n: n,
        timestamp_us: t,
        slip: Default::default(),
    }
}

/// Zero loads ask for nothing, hold with utilisation 0 and let the command relax to `N_min`;
/// a load on no normal force gets the utilisation cap; loads no force up to `N_max` can hold
/// are `Saturated` at `N_max` with the above-grid closed form `|(F/A, M/(R(N_max)·B))|`
/// (ellipse mode, with its inscribed semi-axes `(A, B)`; a round patch's `M` times its
/// `DISC_TORSION_SAFETY_FACTOR`) as their finite requirement, up to
/// the largest loads the sensor range admits.
#[test]
fn zero_loads_and_loads_no_force_can_hold() {
    for (name, cfg) in [
        (
            "rect ellipse",
            cfg_for(FingerShape::Rect, 0.5, Mode::Ellipse),
        ),
        ("rect table", cfg_for(FingerShape::Rect, 0.5, Mode::Table)),
        (
            "disc γ=0 ellipse",
            cfg_for(FingerShape::Disc, 0.0, Mode::Ellipse),
        ),
        (
            "disc γ=0 table",
            cfg_for(FingerShape::Disc, 0.0, Mode::Table),
        ),
    ] {
        let mut c = Controller::<f64>::new(cfg).unwrap();
        let c32 = Controller::<f32, Micromath>::new(cfg).unwrap();
        // Zero loads.
        for s in [1.0, cfg.safety, 1e6] {
            assert_eq!(
                c.required_force(0.0, 0.0, s).unwrap().force_n,
                0.0,
                "{name}"
            );
            assert_eq!(
                c.required_force(-0.0, 0.0, s).unwrap().force_n,
                0.0,
                "{name}"
            );
            assert_eq!(c32.required_force(0.0, 0.0, s as f32).unwrap().force_n, 0.0);
        }
        assert_eq!(c.utilisation(0.0, 0.0, 0.0), Some(0.0), "{name}");
        assert_eq!(
            c.utilisation(1.0, 0.0, 0.0),
            Some(UTILISATION_MAX),
            "{name}"
        );
        assert_eq!(
            c.utilisation(0.0, 1e-3, -5.0),
            Some(UTILISATION_MAX),
            "{name}"
        );
        // The command rises to N_max on a heavy load, then relaxes to N_min at zero load.
        let mut t = 0;
        let mut next = || {
            t += 1000;
            t
        };
        for _ in 0..200 {
            c.tick(&meas(50.0, 0.0, 5.0, next()));
        }
        assert_eq!(c.command_n(), cfg.n_max_n, "{name}");
        let fall_ticks = ((cfg.n_max_n - cfg.n_min_n) / (cfg.fall_rate_n_per_s * cfg.tick_period_s))
            .ceil() as usize;
        let mut last = None;
        for _ in 0..fall_ticks + 1 {
            last = Some(c.tick(&meas(0.0, 0.0, 5.0, next())));
        }
        let o = last.unwrap();
        assert_eq!(o.command_n, cfg.n_min_n, "{name}");
        assert_eq!(
            (o.status, o.required_n, o.n_slip_n, o.utilisation),
            (Status::Ok, 0.0, 0.0, 0.0)
        );
        // Loads no force up to N_max can hold, up to the sensor range.
        for (f, m) in [
            (30.0, 0.0),
            (0.0, 1.9),
            (100.0, 2.0),
            (1e-300, 2.0),
            (100.0, 1e-300),
        ] {
            let o = c.tick(&meas(f, m, 5.0, next()));
            assert_eq!(o.status, Status::Saturated, "{name} ({f}, {m})");
            assert!(
                o.required_n > cfg.n_max_n && o.required_n.is_finite(),
                "{name}"
            );
            assert!(o.utilisation > 1.0 && o.utilisation.is_finite(), "{name}");
            assert!(o.command_n <= cfg.n_max_n, "{name}");
            if cfg.mode == Mode::Ellipse {
                // Above the grid the arm is R(N_max): N = |(F/A, M/(R·B))|, scaled by s,
                // with the controller's inscribed semi-axes (A, B).
                let r = *c.capacity().arms_m().last().unwrap();
                let (sf, sm) = demand_scale(&c);
                // (Times the tick's margin: a load held steady gets the steady load's
                // factor; the safety asked is never below 1.)
                // A round patch's moment carries its own factor on top.
                let safety = (cfg.safety * o.margin).max(1.0);
                let m = m * cfg.torsion_factor();
                let want = safety * (f * sf / cfg.mu).hypot(m * sm / (cfg.mu * r));
                assert!(
                    (o.required_n / want - 1.0).abs() < 1e-14,
                    "{name} ({f}, {m}): {} vs {want}",
                    o.required_n
                );
            }
        }
    }
}

/// The model's point is total: NaN reads as 0, the sign of `d` is ignored, `∞` and huge `d`
/// give the translation limit `(1, 0)`, subnormal `d` gives the pitch; in f32 as in f64.
///
/// This found a bug (fixed in `src/fls/rect.rs`, `row_kernels`): a skewed rectangle whose
/// peak `Δy = Δ·tanh(α d)` is below about 1e-291 (a subnormal `d`, or `Δ/a = 1e-300`, or
/// `--at 1e-300` with any skew) put quadrature nodes at subnormal `y`, where
/// `(u₂ + R₂)/|y|` overflowed: `f̃ = ∞`, `m̃ = NaN`. The kernels now treat `y² = 0` as the
/// row through the centre.
#[test]
fn the_point_is_total_at_non_finite_and_extreme_centres() {
    for shape in [
        Shape::Rect { aspect: 1e-3 },
        Shape::Rect { aspect: 1e3 },
        Shape::Disc,
    ] {
        for k in [1.0, 1e6, f64::INFINITY] {
            let m = model(shape, k, Some((DELTA, 1e3, 0.0)), 28);
            let pitch = m.pitch();
            assert_eq!(m.point(f64::NAN), m.point(0.0));
            assert_eq!(m.point(-2.5).f, m.point(2.5).f);
            assert_eq!(m.point(-2.5).m, m.point(2.5).m);
            for d in [f64::INFINITY, f64::MAX, 1e300] {
                let p = m.point(d);
                assert_eq!((p.f, p.m), (1.0, 0.0), "{shape:?} k={k} d={d}");
            }
            // A subnormal centre of rotation (with a subnormal skew peak): the pitch and no
            // force, to the surface's absolute accuracy in f64 (1e-12).
            let p = m.point(f64::from_bits(1));
            assert!(
                (p.m - pitch).abs() <= 1e-12 && p.f < 1e-12,
                "{p:?} vs {pitch}"
            );
            let m32 = softgrip::FlsModel::<f32>::new(softgrip::FlsConfig {
                shape,
                k,
                skew: Some((DELTA, 1e3, 0.0)),
                order: softgrip::QuadratureOrder::DEFAULT,
            })
            .unwrap();
            for d in [
                0.0,
                f32::from_bits(1),
                1e-12,
                1.0,
                1e12,
                f32::MAX,
                f32::INFINITY,
            ] {
                let p = m32.point(d);
                assert!(
                    p.f.is_finite() && p.m.is_finite(),
                    "{shape:?} k={k} d={d}: {p:?}"
                );
                // f32's documented accuracy is 2e-6: f̃ may exceed 1 by an ulp.
                assert!((0.0..=1.0 + 2e-6).contains(&p.f), "{p:?}");
            }
        }
    }
}

/// Skew parameters at their extremes (`α` from 1e-6 to 1e6, `Δ/a` from 1e-300): finite
/// sweeps, pitch unchanged.
#[test]
fn extreme_skew_rates_give_finite_sweeps() {
    for alpha in [1e-6, 1e-3, 1.0, 1e3, 1e6] {
        for delta in [1e-300, 0.5, DELTA] {
            for shape in [Shape::Rect { aspect: 1.0 }, Shape::Disc] {
                let locus = if shape == Shape::Disc {
                    0.0
                } else {
                    delta / 2.0
                };
                let m = model(shape, 2.0, Some((delta, alpha, locus)), 28);
                let t = softgrip::FlsTable::<f64, 40>::sweep(&m, 32).unwrap();
                for p in t.points() {
                    assert!(
                        p.f.is_finite() && p.m.is_finite(),
                        "α={alpha} Δ={delta}: {p:?}"
                    );
                    assert!((0.0..=1.0).contains(&p.f) && p.m >= 0.0, "{p:?}");
                }
                let plain = model(shape, 2.0, None, 28).pitch();
                assert!((t.pitch() - plain).abs() < 1e-14, "α={alpha} Δ={delta}");
            }
        }
    }
}

/// The skew never needs to be named for the controller: `SkewParams` at the largest skew
/// in table mode builds (rectangle) and gives finite, conservative answers. At safety 1.5
/// the heaviest load asks 17.9 N, inside the grid (above `N_max` the answer is the
/// closed form's conservative bound instead, `Capacity::above_grid`).
#[test]
fn table_mode_at_the_largest_skew() {
    let cfg = ControllerConfig {
        mode: Mode::Table,
        safety: 1.5,
        skew: Some(SkewParams {
            delta_over_a: DELTA,
            alpha: 1.1,
            locus_over_a: DELTA / 2.0,
        }),
        ..ControllerConfig::default()
    };
    let c = Controller::<f64>::new(cfg).unwrap();
    for &(f, m) in &[(1.0, 0.0), (0.5, 4e-3), (0.0, 0.02), (6.0, 0.05)] {
        let got = c.required_force(f, m, cfg.safety).unwrap().force_n;
        let want = exact_required(&cfg, f, m, cfg.safety);
        let rel = (got - want) / want;
        eprintln!("largest skew, table: ({f}, {m}) {got} vs {want} ({rel:e})");
        assert!(
            got.is_finite() && rel.abs() < 3e-3,
            "({f}, {m}): {got} vs {want}"
        );
    }
}
