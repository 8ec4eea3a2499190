//! The fast path ([`FlsModel::point`]) against an independent brute-force 2-D integration of
//! `docs/model.md`'s definitions (`softgrip-reference`, reference/), and the equilibrium
//! `∫∫ p dΩ = N` of the skewed pressures.
//!
//! # Tolerances, from the brute force's measured convergence
//!
//! The brute force is a composite 4 × 4-point Gauss–Legendre rule with `cells` cells per
//! piece and per axis (see its module docs). Its error against a `cells = 128` reference (and
//! against the exact `∫∫ p = 1`) falls like `cells^-3.7` (k = 4, edge `dist^(1/4)`) to
//! `cells^-4.5` (k = 2) or faster. Measured worst cases over the FLS cases below:
//!
//! | cells | 4      | 8      | 16     | 32      |
//! | ----- | ------ | ------ | ------ | ------- |
//! | error | 2.6e-5 | 2.8e-7 | 7.7e-9 | 5.6e-10 |
//!
//! (worst at `cells = 32`: rectangle, k = 4, skewed, d = 0); for `∫∫ p = 1`, k = 1…4 and peaks
//! up to 0.99: 1.4e-8 at 16 cells and 1.0e-9 at 32. The tests compare at
//! [`FINE`] = 32 and also require `|B(16) − B(32)| ≤` [`CONVERGED`] = 2e-8, which, at the
//! measured rate (each halving of the cell size divides the error by ≥ 12), bounds the error of
//! `B(32)` by about 2e-9 in every case, so a brute force that stopped converging (say after a
//! change that moved a singularity off a cell boundary) fails loudly instead of loosening the
//! check. The fast path's own error is documented as ≤ 1e-10. The agreement tolerance
//! [`TOL`] = 1e-8 is therefore ≥ 5× the sum of both errors (measured agreement: ≤ 1e-10 for
//! the symmetric cases, 5.6e-10 for the skewed rectangle), yet far below the effects it must
//! see: at `d = 0.7` the skew moves `(f̃, m̃)` by 6e-3 (rectangle) and 2.4e-2 (disc), see
//! [`skew_is_resolved`]. The convergence guard was checked by mutation: dropping the cut at
//! the centre of rotation from the brute force gives `|B(16) − B(32)|` ≈ 2e-4 and fails.

use softgrip::skew::SkewLaw;
use softgrip::{FlsConfig, FlsModel, QuadratureOrder, Shape};
use softgrip_reference::{gauss_legendre, pressure_total, Case, Patch};

/// Cells per piece for the brute-force value compared against.
const FINE: usize = 32;
/// Cells per piece for the convergence check.
const COARSE: usize = 16;
/// Largest allowed `|B(COARSE) − B(FINE)|`: the brute force is resolved.
const CONVERGED: f64 = 2e-8;
/// Largest allowed `|fast − B(FINE)|` in `f̃` and in `m̃`.
const TOL: f64 = 1e-8;

/// The skew used throughout: `Δ/a = 0.9`, `α = 1.1`, circular locus `h/a = 0.45`.
const PAPER_SKEW: (f64, f64, f64) = (0.9, 1.1, 0.45);

fn model(case: &Case) -> FlsModel<f64> {
    let shape = match case.patch {
        Patch::Rect { aspect } => Shape::Rect { aspect },
        Patch::Disc => Shape::Disc,
    };
    FlsModel::new(FlsConfig {
        shape,
        k: case.k,
        skew: case.skew,
        order: QuadratureOrder::DEFAULT,
    })
    .expect("valid configuration")
}

/// Compares the fast path with the brute force at `d ∈ {0, 0.3, edge/2, edge, 1.7, 20}`,
/// where the edge is `d = aspect` for the rectangle and `d = 1` for the disc.
fn check_against_brute_force(case: Case) {
    let fast = model(&case);
    let edge = match case.patch {
        Patch::Rect { aspect } => aspect,
        Patch::Disc => 1.0,
    };
    let mut worst: f64 = 0.0;
    for d in [0.0, 0.3, 0.5 * edge, edge, 1.7, 20.0] {
        let fine = case.point(d, FINE);
        let coarse = case.point(d, COARSE);
        let conv = (fine.0 - coarse.0).abs().max((fine.1 - coarse.1).abs());
        assert!(
            conv <= CONVERGED,
            "{case:?} d = {d}: brute force not converged: B({COARSE}) = {coarse:?}, \
             B({FINE}) = {fine:?}, difference {conv:e} > {CONVERGED:e}"
        );
        let p = fast.point(d);
        assert_eq!(p.d, d, "{case:?}: point() must echo d");
        let err = (p.f - fine.0).abs().max((p.m - fine.1).abs());
        assert!(
            err <= TOL,
            "{case:?} d = {d}: fast (f, m) = ({}, {}) vs brute force {fine:?}: \
             difference {err:e} > {TOL:e}",
            p.f,
            p.m
        );
        worst = worst.max(err);
    }
    println!("{case:?}: worst |fast − brute force| = {worst:e}");
}

#[test]
fn rect_k2_square_symmetric() {
    check_against_brute_force(Case {
        patch: Patch::Rect { aspect: 1.0 },
        k: 2.0,
        skew: None,
    });
}

#[test]
fn rect_k4_square_skewed() {
    check_against_brute_force(Case {
        patch: Patch::Rect { aspect: 1.0 },
        k: 4.0,
        skew: Some(PAPER_SKEW),
    });
}

#[test]
fn rect_k2_aspect_0_3() {
    check_against_brute_force(Case {
        patch: Patch::Rect { aspect: 0.3 },
        k: 2.0,
        skew: None,
    });
}

#[test]
fn rect_k2_aspect_3() {
    check_against_brute_force(Case {
        patch: Patch::Rect { aspect: 3.0 },
        k: 2.0,
        skew: None,
    });
}

#[test]
fn disc_k2_symmetric() {
    check_against_brute_force(Case {
        patch: Patch::Disc,
        k: 2.0,
        skew: None,
    });
}

#[test]
fn disc_k3_skewed() {
    check_against_brute_force(Case {
        patch: Patch::Disc,
        k: 3.0,
        skew: Some(PAPER_SKEW),
    });
}

/// The brute force on its own against `docs/model.md`'s closed-form pitches (`m̃` at `d = 0`),
/// so that it is anchored independently of the crate's fast path.
#[test]
fn brute_force_matches_closed_form_pitches() {
    let pitch = |patch, k| {
        let case = Case {
            patch,
            k,
            skew: None,
        };
        let (f, m) = case.point(0.0, FINE);
        assert!(f.abs() <= TOL, "{case:?}: f̃(0) = {f:e}, want 0 by symmetry");
        m
    };
    let square = Patch::Rect { aspect: 1.0 };
    let uniform_square = (2f64.sqrt() + 1f64.asinh()) / 3.0;
    let cases = [
        (Patch::Disc, 2.0, 3.0 * core::f64::consts::PI / 16.0, TOL),
        (Patch::Disc, f64::INFINITY, 2.0 / 3.0, TOL),
        (square, f64::INFINITY, uniform_square, TOL),
        // The paper's Eq. 22 values, printed to four digits.
        (square, 2.0, 0.7114, 5e-5),
        (square, 4.0, 0.7442, 5e-5),
    ];
    for (patch, k, want, tol) in cases {
        let got = pitch(patch, k);
        assert!(
            (got - want).abs() <= tol,
            "{patch:?} k = {k}: brute-force pitch {got} vs {want} (tol {tol:e})"
        );
    }
}

/// The comparison resolves the effect of the skew: the skewed fast path differs from the
/// symmetric brute force by far more than [`TOL`] away from `d = 0`, so the agreement above
/// is not a tautology of a tolerance too loose to see the skew.
#[test]
fn skew_is_resolved() {
    for patch in [Patch::Rect { aspect: 1.0 }, Patch::Disc] {
        let skewed = model(&Case {
            patch,
            k: 3.0,
            skew: Some(PAPER_SKEW),
        });
        let symmetric = Case {
            patch,
            k: 3.0,
            skew: None,
        };
        let d = 0.7;
        let p = skewed.point(d);
        let b = symmetric.point(d, COARSE);
        let gap = (p.f - b.0).abs().max((p.m - b.1).abs());
        println!("{patch:?}: skew moves the point by {gap:e} at d = {d}");
        assert!(
            gap > 1e3 * TOL,
            "{patch:?}: skewed fast path within {gap:e} of the symmetric brute force"
        );
    }
}

/// `∫∫ p dΩ = N` exactly for every peak position (`docs/model.md`, "Skewed"), for the skewed
/// pressures on the rectangle and the disc, including peaks at 0.99 of the way to the edge.
#[test]
fn skewed_pressures_integrate_to_n() {
    let mut peaks: Vec<(f64, f64)> = vec![(0.0, 0.0), (0.0, 0.5), (0.0, -0.7), (0.0, 0.99)];
    // Along the skew law's path (Eq. 16, 17), circular locus, for several Δ/a incl. 0.99.
    for delta in [0.5, 0.9, 0.99] {
        let law = SkewLaw::<f64>::circular(delta, 1.1).expect("valid skew law");
        for d in [0.3, 0.8, 3.0, 20.0] {
            peaks.push(law.peak(d));
        }
    }
    // Off-axis disc peaks in other quadrants.
    peaks.extend([(-0.6, 0.3), (0.5, -0.5), (-0.7, -0.7)]);
    let patches = [
        Patch::Rect { aspect: 1.0 },
        Patch::Rect { aspect: 0.3 },
        Patch::Rect { aspect: 3.0 },
        Patch::Disc,
    ];
    for patch in patches {
        for k in [1.0, 2.0, 3.0, 4.0] {
            for &peak in &peaks {
                let total = pressure_total(patch, k, peak, FINE);
                assert!(
                    (total - 1.0).abs() <= TOL,
                    "{patch:?} k = {k} peak {peak:?}: ∫∫p/N = {total} (error {:e})",
                    total - 1.0
                );
            }
        }
    }
}

/// The brute force's own Gauss–Legendre rule: exact for degree `2n − 1`, not for `2n`.
#[test]
fn gauss_legendre_degree() {
    for n in 1..=8 {
        let rule = gauss_legendre(n);
        let moment = |j: i32| -> f64 { rule.iter().map(|&(x, w)| w * x.powi(j)).sum() };
        for j in 0..(2 * n as i32) {
            let exact = if j % 2 == 0 {
                2.0 / (j as f64 + 1.0)
            } else {
                0.0
            };
            assert!((moment(j) - exact).abs() < 1e-14, "n = {n}, x^{j}");
        }
        let j = 2 * n as i32;
        assert!(
            (moment(j) - 2.0 / (j as f64 + 1.0)).abs() > 1e-6,
            "n = {n}, x^{j}"
        );
    }
}
