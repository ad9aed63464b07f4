//! Boundaries traced in two parameters on the single gear pair (Kahraman &
//! Singh's form), against independent facts: one-parameter continuations
//! at levels the trace did not start from, one-parameter runs on either
//! side of each cusp, and time integration on either side of each contact
//! boundary.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::boundaries::{BoundarySpec, BoundaryTrace, Curve, CurveKind, CurvePoint, Side};
use solver::hbm::{Bifurcation, FrfContinuation, FrfSpec};
use solver::keys;
use solver::params::ModelParams;
use solver::steady::{steady_state, Impact, Model, SteadyOptions, SteadyState};
use solver::SolverError;
use std::sync::OnceLock;

fn pair(assignments: &[&str]) -> ModelParams {
    let mut p = ModelParams::default();
    keys::set_assignment(&mut p, "model=gear-pair").unwrap();
    for a in assignments {
        keys::set_assignment(&mut p, a).unwrap();
    }
    p
}

/// The (Omega, TE amplitude) trace every test reads: TE 0.2-40 um, Omega
/// 0.4-1.3, seeded at TE 0.2, 10.15, 20.1, 30.05 and 40 um.
fn te_trace() -> &'static BoundaryTrace {
    static TRACE: OnceLock<BoundaryTrace> = OnceLock::new();
    TRACE.get_or_init(|| {
        let mut spec = BoundarySpec::new("te_um", (0.2, 40.0), (0.4, 1.3));
        spec.levels = 5;
        spec.points = 80;
        traced(&pair(&[]), spec)
    })
}

/// The whole trace of `spec` on `params`.
fn traced(params: &ModelParams, spec: BoundarySpec) -> BoundaryTrace {
    let mut t = BoundaryTrace::new(params, spec).unwrap();
    while !t.is_finished() {
        t.advance(50).unwrap();
    }
    t
}

/// The folds of a one-parameter continuation (H = 7, exact) at `te_um`.
fn folds_at(te_um: f64, omega: (f64, f64), points: u32) -> Vec<f64> {
    let model = Model::new(&pair(&[&format!("te_um={te_um}")])).unwrap();
    let mut spec = FrfSpec::new(omega.0, omega.1, points);
    spec.harmonics = 7;
    spec.stability = false;
    let mut c = FrfContinuation::new(&model, spec).unwrap();
    let mut folds = Vec::new();
    while !c.is_finished() {
        for p in c.advance(64).unwrap() {
            if p.bifurcation == Some(Bifurcation::Fold) {
                folds.push(p.omega);
            }
        }
    }
    folds
}

/// Where the curves of `kind` cross the level `value` (linear between points).
fn crossings(curves: &[Curve], kind: CurveKind, value: f64) -> Vec<f64> {
    let mut out = Vec::new();
    for c in curves.iter().filter(|c| c.kind == kind) {
        for s in c.points.windows(2) {
            let (a, b) = (&s[0], &s[1]);
            if (a.value - value) * (b.value - value) <= 0.0 && a.value != b.value {
                let t = (value - a.value) / (b.value - a.value);
                out.push(a.omega + t * (b.omega - a.omega));
            }
        }
    }
    out.sort_by(f64::total_cmp);
    out
}

#[test]
fn fold_curves_pass_through_the_one_parameter_folds_at_every_level() {
    let t = te_trace();
    assert!(t.curves().iter().any(|c| c.kind == CurveKind::Fold));
    // Levels the trace was not seeded from.
    for te in [3.0, 13.0, 25.0, 36.0] {
        let mut one = folds_at(te, (0.4, 1.3), 400);
        one.sort_by(f64::total_cmp);
        let two = crossings(t.curves(), CurveKind::Fold, te);
        assert_eq!(
            one.len(),
            two.len(),
            "TE {te}: one-parameter folds {one:?}, fold curves cross at {two:?}"
        );
        for (a, b) in one.iter().zip(&two) {
            assert!((a - b).abs() < 2e-3, "TE {te}: fold at {a}, curve at {b}");
        }
    }
}

/// The period doublings a one-parameter continuation (H = 7, exact, with
/// stability) labels at `te_um`: the Omega interval between the point
/// before the crossing and the labelled point.
fn doublings_at(te_um: f64) -> Vec<(f64, f64)> {
    let model = Model::new(&pair(&[&format!("te_um={te_um}")])).unwrap();
    let mut spec = FrfSpec::new(0.4, 1.3, 400);
    spec.harmonics = 7;
    let mut c = FrfContinuation::new(&model, spec).unwrap();
    let mut out = Vec::new();
    let mut prev = f64::NAN;
    while !c.is_finished() {
        for p in c.advance(64).unwrap() {
            if p.bifurcation == Some(Bifurcation::PeriodDoubling) {
                out.push((prev.min(p.omega), prev.max(p.omega)));
            }
            prev = p.omega;
        }
    }
    out
}

#[test]
fn period_doubling_curves_pass_through_the_one_parameter_doublings() {
    let t = te_trace();
    assert!(t
        .curves()
        .iter()
        .any(|c| c.kind == CurveKind::PeriodDoubling));
    for te in [13.0, 25.0, 36.0] {
        let one = doublings_at(te);
        let two = crossings(t.curves(), CurveKind::PeriodDoubling, te);
        assert_eq!(
            one.len(),
            two.len(),
            "TE {te}: one-parameter doublings {one:?}, curves cross at {two:?}"
        );
        for &(a, b) in &one {
            assert!(
                two.iter().any(|&w| a - 2e-3 <= w && w <= b + 2e-3),
                "TE {te}: doubling in {a}..{b}, curves cross at {two:?}"
            );
        }
    }
}

/// The folds of a one-parameter continuation of the pair with `assignment`.
fn folds_with(assignment: &str, omega: (f64, f64)) -> Vec<f64> {
    let model = Model::new(&pair(&[assignment])).unwrap();
    let mut spec = FrfSpec::new(omega.0, omega.1, 400);
    spec.harmonics = 7;
    spec.stability = false;
    let mut c = FrfContinuation::new(&model, spec).unwrap();
    let mut folds = Vec::new();
    while !c.is_finished() {
        folds.extend(
            c.advance(64)
                .unwrap()
                .into_iter()
                .filter(|p| p.bifurcation == Some(Bifurcation::Fold))
                .map(|p| p.omega),
        );
    }
    folds.sort_by(f64::total_cmp);
    folds
}

#[test]
fn fold_curves_in_torque_and_damping_pass_through_the_one_parameter_folds() {
    for (key, range, levels) in [
        ("torque_pinion_nm", (100.0, 3000.0), [400.0, 1700.0]),
        ("damping_ratio", (0.02, 0.2), [0.05, 0.13]),
    ] {
        let mut spec = BoundarySpec::new(key, range, (0.4, 1.3));
        spec.levels = 5;
        spec.points = 80;
        let t = traced(&pair(&[]), spec);
        for level in levels {
            let one = folds_with(&format!("{key}={level}"), (0.4, 1.3));
            let two = crossings(t.curves(), CurveKind::Fold, level);
            assert!(!one.is_empty(), "{key} {level}: no fold to compare");
            // Every fold has a curve within 2e-3 in Omega and every
            // crossing a fold: a fold pair much narrower than that, born
            // between two seeding levels, may be missed (torque 400 N m
            // has one 0.0015 wide beside the jump's fold).
            let near = |w: f64, set: &[f64]| set.iter().any(|v| (v - w).abs() < 2e-3);
            for &a in &one {
                assert!(
                    near(a, &two),
                    "{key} {level}: fold at {a}, curves at {two:?}"
                );
            }
            for &b in &two {
                assert!(
                    near(b, &one),
                    "{key} {level}: curve at {b}, folds at {one:?}"
                );
            }
        }
    }
}

#[test]
fn each_cusp_has_two_folds_on_one_side_and_none_on_the_other() {
    let t = te_trace();
    // The secondary jump near Omega 0.46 disappears below TE 22 um (the
    // primary resonance's persists down to TE 0: the stiffness
    // fluctuation under load excites it alone).
    assert!(!t.cusps().is_empty(), "cusps {:?}", t.cusps());
    for cusp in t.cusps() {
        // The two folds leave the cusp toward the same side of its value.
        let curve = &t.curves()[cusp.curve];
        let near: Vec<f64> = curve
            .points
            .iter()
            .filter(|p| (p.omega - cusp.omega).abs() < 0.03)
            .map(|p| p.value - cusp.value)
            .collect();
        let side = near.iter().sum::<f64>().signum();
        let delta = (0.05 * 39.8f64).min(0.2 * cusp.value.abs());
        let window = (cusp.omega - 0.06, cusp.omega + 0.06);
        let inside = folds_at(cusp.value + side * delta, window, 400);
        let outside = folds_at(cusp.value - side * delta, window, 400);
        assert_eq!(inside.len(), 2, "cusp {cusp:?}: folds beyond it {inside:?}");
        assert!(
            outside.is_empty(),
            "cusp {cusp:?}: folds before it {outside:?}"
        );
    }
}

/// The steady state by time integration at `(omega, te_um)` after
/// `transient` periods, `record` recorded.
fn integrated(omega: f64, te_um: f64, transient: u32, record: u32) -> SteadyState {
    let model = Model::new(&pair(&[&format!("te_um={te_um}")])).unwrap();
    let mut opts = SteadyOptions::new(omega);
    opts.transient_periods = transient;
    opts.record_periods = record;
    steady_state(&model, &opts, None).unwrap()
}

/// The regime of mesh 0 by time integration at `(omega, te_um)`.
fn regime(omega: f64, te_um: f64) -> Impact {
    integrated(omega, te_um, 400, 20).meshes[0].impact
}

/// The scales of the traced plane (Omega, TE um): steps and distances are
/// measured in fractions of them.
const PLANE: (f64, f64) = (0.9, 39.8);

/// Whether a curve point is fit to check against time integration: inside
/// the box, away from its edges, and away from every fold (where the
/// periodic branch need not be what the gears do).
fn checkable(folds: &[&Curve], p: &CurvePoint) -> bool {
    let (om, pr) = PLANE;
    let clear = folds.iter().all(|f| {
        f.points
            .iter()
            .all(|q| ((q.omega - p.omega) / om).hypot((q.value - p.value) / pr) > 0.04)
    });
    clear && p.omega > 0.45 && p.omega < 1.25 && p.value > 1.0 && p.value < 38.0
}

/// The points 2 % of the plane either side of a curve point, along its
/// normal: (the side it marks stable, the other).
fn either_side(p: &CurvePoint) -> ((f64, f64), (f64, f64)) {
    let (om, pr) = PLANE;
    let at = |s: f64| {
        (
            p.omega + s * 0.02 * om * p.normal.0,
            p.value + s * 0.02 * pr * p.normal.1,
        )
    };
    (at(1.0), at(-1.0))
}

/// The curves of one kind in a trace.
fn curves_of(t: &BoundaryTrace, kind: CurveKind) -> Vec<&Curve> {
    t.curves().iter().filter(|c| c.kind == kind).collect()
}

#[test]
fn contact_boundaries_agree_with_time_integration_a_small_step_either_side() {
    let t = te_trace();
    let folds = curves_of(t, CurveKind::Fold);
    let mut checked = 0;
    for c in curves_of(t, CurveKind::DriveFlanksPart) {
        // A few points per curve, away from the box's edges and from every
        // fold (where the periodic branch need not be what the gears do).
        for p in c.points.iter().step_by(6) {
            if !checkable(&folds, p) {
                continue;
            }
            let ((w1, v1), (w2, v2)) = either_side(p);
            assert_eq!(regime(w1, v1), Impact::None, "stable side of {p:?}");
            assert_ne!(regime(w2, v2), Impact::None, "other side of {p:?}");
            checked += 1;
        }
    }
    assert!(checked >= 3, "only {checked} contact points checked");
}

/// The period (in mesh periods) of the motion by time integration.
fn period(omega: f64, te_um: f64) -> Option<u32> {
    integrated(omega, te_um, 600, 32).period
}

#[test]
fn period_doubling_curves_agree_with_time_integration_a_small_step_either_side() {
    // Where the doubling happens on a stable orbit (every other multiplier
    // inside the unit circle) and the branch is the only one: period 1 on
    // the stable side, 2 on the other.
    let t = te_trace();
    let folds = curves_of(t, CurveKind::Fold);
    let mut checked = 0;
    for c in curves_of(t, CurveKind::PeriodDoubling) {
        for p in c.points.iter().step_by(10) {
            // Inside a jump's hysteresis band (between two fold crossings
            // at this TE) time integration from rest may settle on the
            // other branch: the comparison holds where the branch is unique.
            let band = crossings(t.curves(), CurveKind::Fold, p.value);
            let unique = band
                .chunks(2)
                .all(|w| w.len() < 2 || p.omega < w[0] - 0.02 || p.omega > w[1] + 0.02);
            if !(checkable(&folds, p) && unique && p.others_stable == Some(true)) {
                continue;
            }
            let ((w1, v1), (w2, v2)) = either_side(p);
            assert_eq!(period(w1, v1), Some(1), "stable side of {p:?}");
            assert_eq!(period(w2, v2), Some(2), "other side of {p:?}");
            checked += 1;
        }
    }
    assert!(checked >= 3, "only {checked} points checked");
}

#[test]
fn the_stable_side_of_a_fold_is_where_its_branch_exists() {
    // On the primary resonance's jump at TE 20 um the upper fold's branch
    // exists below it in Omega, the lower fold's above it.
    let t = te_trace();
    let mut seen = Vec::new();
    for c in t.curves().iter().filter(|c| c.kind == CurveKind::Fold) {
        for s in c.points.windows(2) {
            if (s[0].value - 20.0) * (s[1].value - 20.0) <= 0.0 && s[0].omega > 0.47 {
                seen.push((s[0].omega, s[0].stable_side));
            }
        }
    }
    seen.sort_by(|a, b| a.0.total_cmp(&b.0));
    assert_eq!(seen.len(), 2, "{seen:?}");
    assert_eq!(seen[0].1, Side::HigherOmega, "{seen:?}");
    assert_eq!(seen[1].1, Side::LowerOmega, "{seen:?}");
}

#[test]
fn keys_that_move_the_modes_and_empty_ranges_are_refused() {
    let base = pair(&[]);
    let refused = |key: &str, values: (f64, f64), omegas: (f64, f64)| {
        BoundaryTrace::new(&base, BoundarySpec::new(key, values, omegas)).unwrap_err()
    };
    // The mean stiffness moves the natural modes: not a boundary key.
    let e = refused("stiffness_n_m", (1e8, 1e9), (0.4, 1.0));
    assert!(
        matches!(&e, SolverError::BadOption { option, .. } if option == "key"),
        "{e}"
    );
    assert!(e.to_string().contains("backlash_um"), "{e}");
    // An integer key.
    assert!(refused("teeth_pinion", (20.0, 40.0), (0.4, 1.0))
        .to_string()
        .contains("teeth_pinion"));
    // Empty ranges name their flag.
    let e = refused("te_um", (10.0, 10.0), (0.4, 1.0));
    assert!(
        matches!(&e, SolverError::BadOption { option, .. } if option == "value-to"),
        "{e}"
    );
    let e = refused("te_um", (1.0, 10.0), (1.0, 0.4));
    assert!(
        matches!(&e, SolverError::BadOption { option, .. } if option == "omega-to"),
        "{e}"
    );
    // A value outside the key's own range names the key and its range.
    let e = refused("backlash_um", (-5.0, 10.0), (0.4, 1.0));
    assert!(e.to_string().contains("backlash_um"), "{e}");
    // AFT's sampled Jacobian has no derivative for a fold's test: refused,
    // saying so, rather than a trace without folds.
    let mut spec = BoundarySpec::new("te_um", (0.2, 40.0), (0.4, 1.3));
    spec.method = solver::hbm::Method::Aft;
    let e = BoundaryTrace::new(&base, spec).unwrap_err();
    assert!(
        matches!(&e, SolverError::BadOption { option, allowed, .. }
            if option == "method" && allowed.contains("exact")),
        "{e}"
    );
}

/// The gear pair's te_um box at `points` a curve, seeded at two levels.
fn te_box(points: u32) -> BoundaryTrace {
    let mut spec = BoundarySpec::new("te_um", (0.2, 40.0), (0.4, 1.3));
    spec.levels = 2;
    spec.points = points;
    traced(&pair(&[]), spec)
}

/// Distance in units of the box from `(omega, value)` to a curve's polyline.
fn distance_to(c: &Curve, omega: f64, value: f64) -> f64 {
    let (om, pr) = (0.9, 39.8);
    let p = (omega / om, value / pr);
    c.points
        .windows(2)
        .map(|s| {
            let a = (s[0].omega / om, s[0].value / pr);
            let b = (s[1].omega / om, s[1].value / pr);
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len2 = dx * dx + dy * dy;
            let t = if len2 > 0.0 {
                (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
        })
        .fold(f64::INFINITY, f64::min)
}

/// At a coarse step the two fold branches beside the cusp near Omega 0.46
/// run less than a step apart, in opposite directions: a closure test on
/// nearness alone closed the curve from one branch to the other and
/// traced it twice at 20 points (four times at 10), with its cusp each
/// time. Coarse traces give the fine trace's curves, each once, every
/// point on the fine curve of its kind, and the one cusp.
#[test]
fn coarse_traces_give_the_fine_traces_curves_once() {
    let fine = te_box(60);
    let kinds = |t: &BoundaryTrace| {
        let mut k: Vec<(&str, Option<usize>)> =
            t.curves().iter().map(|c| (c.kind.name(), c.mesh)).collect();
        k.sort();
        k
    };
    assert_eq!(fine.cusps().len(), 1, "{:?}", fine.cusps());
    for points in [10, 20] {
        let coarse = te_box(points);
        assert_eq!(kinds(&coarse), kinds(&fine), "{points} points");
        assert_eq!(coarse.cusps().len(), 1, "{points}: {:?}", coarse.cusps());
        let (a, b) = (coarse.cusps()[0], fine.cusps()[0]);
        assert!(
            (a.omega - b.omega).abs() < 1e-3 && (a.value - b.value).abs() < 0.1,
            "{points}: cusp {a:?}, fine {b:?}"
        );
        for c in coarse.curves() {
            assert!(
                !c.ends.contains(&solver::boundaries::TraceEnd::Closed),
                "{points}: {:?} {:?}",
                c.kind,
                c.ends
            );
            for p in &c.points {
                let d = fine
                    .curves()
                    .iter()
                    .filter(|f| f.kind == c.kind && f.mesh == c.mesh)
                    .map(|f| distance_to(f, p.omega, p.value))
                    .fold(f64::INFINITY, f64::min);
                assert!(
                    d < 0.02,
                    "{points}: {:?} point {p:?} is {d} from the fine curves",
                    c.kind
                );
            }
        }
    }
}

/// A period-doubling start on the key's upper limit (backlash 1000 um)
/// differences its gradient in the key backward: it is traced, not
/// refused as out of the key's range.
#[test]
fn a_doubling_start_at_the_keys_upper_limit_is_traced() {
    let mut spec = BoundarySpec::new("backlash_um", (900.0, 1000.0), (0.3, 3.0));
    spec.levels = 2;
    spec.points = 20;
    let t = traced(&pair(&[]), spec);
    assert!(
        t.notes().iter().all(|n| !n.contains("out of range")),
        "{:?}",
        t.notes()
    );
    let from_top = t
        .curves()
        .iter()
        .filter(|c| c.kind == CurveKind::PeriodDoubling)
        .filter(|c| c.points.iter().any(|p| p.value == 1000.0))
        .count();
    assert!(from_top >= 1, "{:?}", t.curves());
}

/// The gear pair's (Omega, backlash) trace: backlash 0-200 um, Omega
/// 0.1-2, H = 5, 40 points.
fn backlash_trace() -> &'static BoundaryTrace {
    static TRACE: OnceLock<BoundaryTrace> = OnceLock::new();
    TRACE.get_or_init(|| {
        let mut spec = BoundarySpec::new("backlash_um", (0.0, 200.0), (0.1, 2.0));
        spec.harmonics = 5;
        spec.points = 40;
        traced(&pair(&[]), spec)
    })
}

/// Where the flanks do not part, backlash only shifts the mean
/// deflection, and a boundary does not move with it: such curves are
/// vertical lines in (Omega, backlash). Traced at the box's step, a line
/// over most of the box takes some 50 points (twice that when the metric
/// counted the mean's shift like the vibration, and a hundred times
/// that on the compound set). The period doubling at Omega 1.831 turns a
/// corner near backlash 7 um into one with contact that runs to Omega
/// 0.754: the trace follows it round the corner, and no curve ends by
/// running out of points.
#[test]
fn vertical_curves_take_few_points_and_the_doubling_turns_its_corner() {
    let t = backlash_trace();
    let mut vertical = 0;
    for c in t.curves() {
        assert!(
            !c.ends.contains(&solver::boundaries::TraceEnd::Budget),
            "{:?} {:?}",
            c.kind,
            c.ends
        );
        let (lo, hi) = c.points.iter().fold((f64::MAX, f64::MIN), |(a, b), p| {
            (a.min(p.omega), b.max(p.omega))
        });
        let span = c.points.iter().map(|p| p.value).fold(f64::MIN, f64::max)
            - c.points.iter().map(|p| p.value).fold(f64::MAX, f64::min);
        if hi - lo < 1e-6 && span > 100.0 {
            vertical += 1;
            assert!(
                c.points.len() <= 70,
                "{:?}: {} points",
                c.kind,
                c.points.len()
            );
        }
    }
    assert!(vertical >= 5, "{vertical} vertical curves");
    assert!(
        t.curves()
            .iter()
            .any(|c| c.kind == CurveKind::PeriodDoubling
                && c.points.iter().any(|p| p.omega < 0.76)
                && c.points.iter().any(|p| p.omega > 1.83)),
        "no period doubling from Omega 1.83 round the corner to 0.76"
    );
}

/// A contact curve that runs down to zero backlash, the key's own lower
/// limit and the box's edge, leaves the box there: its last point lies on
/// the edge and the end is `left-range`. (A step across the edge cannot be
/// evaluated, backlash below 0 being refused, so before the step landed on
/// the edge such a curve ended as a corrector failure a hair above it.)
#[test]
fn a_contact_curve_reaching_zero_backlash_leaves_the_box_there() {
    let t = backlash_trace();
    let at_zero: Vec<&Curve> = t
        .curves()
        .iter()
        .filter(|c| {
            matches!(
                c.kind,
                CurveKind::DriveFlanksPart | CurveKind::BackFlanksTouch
            ) && c.points.iter().any(|p| p.value < 1.0)
        })
        .collect();
    assert!(
        !at_zero.is_empty(),
        "{:?}",
        t.curves().iter().map(|c| c.kind).collect::<Vec<_>>()
    );
    for c in at_zero {
        let ends = [c.points[0].value, c.points[c.points.len() - 1].value];
        let i = if ends[0] < ends[1] { 0 } else { 1 };
        assert_eq!(ends[i], 0.0, "{:?} {:?}", c.kind, c.ends);
        assert_eq!(
            c.ends[i],
            solver::boundaries::TraceEnd::LeftRange,
            "{:?}",
            c.kind
        );
    }
}

/// The compound set's trace restricted to one mesh's contact boundaries
/// is the whole trace less the other meshes' contact curves, curve for
/// curve: the folds and period doublings are the set's and stay; the
/// restriction only skips starts, it changes no curve that is traced.
#[test]
fn contact_boundaries_of_one_mesh_are_the_whole_traces_for_that_mesh() {
    let base = ModelParams::default();
    let trace = |only: Option<usize>| {
        let mut spec = BoundarySpec::new("backlash_um", (0.0, 200.0), (0.6, 1.6));
        spec.harmonics = 3;
        spec.points = 20;
        spec.levels = 2;
        spec.contact_mesh = only;
        traced(&base, spec).curves().to_vec()
    };
    let all = trace(None);
    let meshes: Vec<usize> = all.iter().filter_map(|c| c.mesh).collect();
    let &mesh = meshes.first().expect("the whole trace has contact curves");
    assert!(
        meshes.iter().any(|&m| m != mesh),
        "the whole trace has other meshes' contact curves: {:?}",
        all.iter().map(|c| (c.kind, c.mesh)).collect::<Vec<_>>()
    );
    let one = trace(Some(mesh));
    let kept: Vec<Curve> = all
        .into_iter()
        .filter(|c| c.mesh.is_none() || c.mesh == Some(mesh))
        .collect();
    assert!(
        kept.iter().any(|c| c.mesh.is_none()),
        "folds or doublings stay"
    );
    assert_eq!(one, kept);
}
