//! The check of cells against curves and the click's pick, on curves
//! whose sides are known by construction.

use super::*;
use crate::protocol::BoundaryPoint;
use crate::views::test_support::map_cell;

/// Omega 0.1 ..= 2.0 in 20 columns (step 0.1), backlash 0 ..= 100 µm in 11
/// rows (step 10).
fn grid() -> MapGrid {
    crate::views::test_support::backlash_grid(100.0, 11)
}

/// A vertical curve at Omega 1.0 from `v0` to `v1`, its unchanged side
/// toward lower Omega.
fn vertical(kind: BoundaryKind, v0: f64, v1: f64) -> BoundaryCurve {
    let points = (0..=10)
        .map(|i| BoundaryPoint {
            omega: 1.0,
            value: v0 + (v1 - v0) * f64::from(i) / 10.0,
            normal: (-1.0, 0.0),
            others_stable: None,
        })
        .collect();
    BoundaryCurve {
        kind,
        mesh: Some(0),
        points,
    }
}

/// Every cell computed: double-sided beyond Omega 1.0, single-sided below,
/// except the cells listed as double-sided.
fn store(g: &MapGrid, planted: &[(u32, u32)]) -> MapStore {
    let mut s = MapStore::new(g.clone(), String::new());
    let mut cells = Vec::new();
    for r in 0..g.value_points {
        for c in 0..g.omega_points {
            let double = g.omega(c) > 1.0 + 1e-9 || planted.contains(&(r, c));
            let regime = if double {
                Regime::DoubleSided
            } else {
                Regime::SingleSided
            };
            cells.push(map_cell(r, c, regime, Some(1)));
        }
    }
    s.add(cells);
    s
}

#[test]
fn only_cells_near_a_curve_on_its_wrong_side_are_marked() {
    let g = grid();
    // Column 8 is Omega 0.9 (one column left of the curve, within the
    // band), column 7 is Omega 0.8 (two columns from it, outside the band
    // of 1.5). Column 9 (Omega 1.0) lies on the curve.
    let s = store(&g, &[(3, 8), (5, 7), (6, 9)]);
    let curve = vertical(BoundaryKind::BackFlanksTouch, 0.0, 100.0);
    let (marks, judged) = disagreements(&g, &s, &[&curve]);
    assert_eq!(marks, vec![(3, 8)]);
    // Columns 8 and 10 (Omega 0.9 and 1.1), every row.
    assert_eq!(judged, 2 * 11);
}

#[test]
fn cells_beyond_a_curves_end_are_not_judged_and_folds_make_no_claim() {
    let g = grid();
    // The curve ends at 50 µm: the planted cell at 80 µm (row 8) lies
    // beyond its end.
    let s = store(&g, &[(8, 8), (2, 8)]);
    let curve = vertical(BoundaryKind::BackFlanksTouch, 0.0, 50.0);
    let (marks, judged) = disagreements(&g, &s, &[&curve]);
    assert_eq!(marks, vec![(2, 8)]);
    // Rows 0 ..= 5 (0 to 50 µm) of columns 8 and 10.
    assert_eq!(judged, 2 * 6);
    let fold = vertical(BoundaryKind::Fold, 0.0, 100.0);
    assert_eq!(disagreements(&g, &s, &[&fold]), (Vec::new(), 0));
}

#[test]
fn the_drive_flanks_part_where_impact_begins() {
    // No impact on the unchanged side, impact beyond: a single-sided cell
    // on the unchanged side disagrees, a no-impact cell beyond disagrees.
    let c = |r| map_cell(0, 0, r, Some(1));
    let k = BoundaryKind::DriveFlanksPart;
    assert_eq!(agrees(k, None, true, &c(Regime::NoImpact)), Some(true));
    assert_eq!(agrees(k, None, true, &c(Regime::SingleSided)), Some(false));
    assert_eq!(agrees(k, None, false, &c(Regime::NoImpact)), Some(false));
    assert_eq!(agrees(k, None, false, &c(Regime::DoubleSided)), Some(true));
    // A doubling on an unstable orbit says nothing about the motion.
    let p2 = map_cell(0, 0, Regime::NoImpact, Some(2));
    let pd = BoundaryKind::PeriodDoubling;
    assert_eq!(agrees(pd, Some(false), false, &p2), None);
    assert_eq!(agrees(pd, Some(true), false, &p2), Some(true));
    assert_eq!(agrees(pd, Some(true), true, &p2), Some(false));
}

#[test]
fn a_click_picks_the_nearest_curve_point_within_the_tolerance() {
    let curve = vertical(BoundaryKind::BackFlanksTouch, 0.0, 100.0);
    // 400 px per unit of Omega, 3 px per µm.
    let px = (400.0, 3.0);
    let p = pick(&[&curve], (1.0 + 4.0 / 400.0, 42.0), px, 6.0);
    let p = p.expect("4 px away");
    assert_eq!((p.omega, p.value), (1.0, 42.0));
    assert_eq!(pick(&[&curve], (1.0 + 10.0 / 400.0, 42.0), px, 6.0), None);
    let text = describe(&p, "backlash_um", Some("s1a1"));
    assert_eq!(
        text,
        "Here on mesh s1a1 the back flanks start to touch (double-sided impact begins): \
         Ω 1.000, backlash 42.0 µm."
    );
}

#[test]
fn the_map_of_one_mesh_shows_that_meshs_contact_curves_and_every_jump() {
    let mut s = BoundaryStore::new(String::new());
    let mut other = vertical(BoundaryKind::DriveFlanksPart, 0.0, 1.0);
    other.mesh = Some(3);
    let mut fold = vertical(BoundaryKind::Fold, 0.0, 1.0);
    fold.mesh = None;
    s.curves = vec![
        vertical(BoundaryKind::BackFlanksTouch, 0.0, 1.0),
        other,
        fold,
    ];
    assert_eq!(s.shown(Some(0)).len(), 2);
    assert_eq!(s.shown(Some(3)).len(), 2);
    assert_eq!(s.shown(None).len(), 3);
}

#[test]
fn a_cell_beyond_another_curve_is_not_judged_by_the_farther_one() {
    let g = grid();
    // Single-sided up to Omega 1.0 (column 9), double-sided beyond, and
    // one planted double-sided cell at row 3, column 8 (Omega 0.9).
    let s = store(&g, &[(3, 8)]);
    // The curve at Omega 1.0 agrees with every cell: alone it marks only
    // the planted one.
    let far = vertical(BoundaryKind::BackFlanksTouch, 0.0, 100.0);
    assert_eq!(disagreements(&g, &s, &[&far]).0, vec![(3, 8)]);
    // A second curve at Omega 0.95 (column 8.5) that says the back flanks
    // touch on its lower-Omega side, where the cells are single-sided.
    let mut near = far.clone();
    near.points.iter_mut().for_each(|p| {
        p.omega = 0.95;
        p.normal = (1.0, 0.0);
    });
    let (marks, _) = disagreements(&g, &s, &[&near, &far]);
    // Columns 7 and 8 lie on its changed side: every single-sided cell
    // there disagrees with it. Column 8 is no longer judged by the curve at
    // 1.0, beyond the nearer one, so its planted cell agrees (the back
    // flanks touch there). Column 10 (Omega 1.1, double-sided) is within
    // the band of the curve at 0.95, on its unchanged side, but the curve
    // at 1.0 lies between: it is not marked.
    let mut expected: Vec<(u32, u32)> = (0..11)
        .flat_map(|r| [(r, 7), (r, 8)])
        .filter(|&cell| cell != (3, 8))
        .collect();
    expected.sort_unstable();
    assert_eq!(marks, expected);
}

#[test]
fn cells_without_backlash_make_no_claim_about_the_back_flanks() {
    let k = BoundaryKind::BackFlanksTouch;
    let no_gap = map_cell(0, 0, Regime::NoGap, Some(1));
    assert_eq!(agrees(k, None, true, &no_gap), None);
    assert_eq!(agrees(k, None, false, &no_gap), None);
}
