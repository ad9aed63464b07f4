//! Tests of the frequency response's stores, view model and exports.

use super::*;
use crate::views::test_support::{ctx, ext, hbm_point};

#[test]
fn a_restarted_branch_is_not_joined_across_its_pieces() {
    // Piece 0 runs up from 0.5 to 1.0; the restart (piece 1) comes down
    // from 2.0 to 1.5. Nothing lies between 1.0 and 1.5.
    let mut st = HbmStore::new(5);
    let mut pts: Vec<HbmSample> = [0.5, 1.0, 2.0, 1.5]
        .iter()
        .map(|&o| hbm_point(o, &[(80.0, 120.0)], true))
        .collect();
    pts[2].piece = 1;
    pts[3].piece = 1;
    st.add(pts, 1.0, true, None);
    st.notes = vec!["The branch was restarted.".into()];
    let (curve, _) = st.curve(Some(0));
    assert_eq!(
        curve.iter().map(|p| p.piece).collect::<Vec<_>>(),
        [0, 0, 1, 1]
    );
    assert!(curve[0].joins(&curve[1]) && !curve[1].joins(&curve[2]));
    // An overlay point in the gap is not compared with a line across it.
    let q = |omega: f64| FrCurvePoint {
        omega,
        max_um: 500.0,
        min_um: 0.0,
        stable: None,
        regime: None,
        period: Some(1),
        bifurcation: None,
        piece: 0,
    };
    let d = discrepancy(&curve, &[q(1.2), q(1.7)]);
    assert_eq!((d.compared, d.off_branch), (1, 1));
    // The note says what the continuation did.
    let v = fr_view(&st, None, None, Some(0), &[100.0], &ctx());
    assert!(fr_note(&v).ends_with(" The branch was restarted."));
}

#[test]
fn fr_store_orders_by_grid_and_picks_meshes() {
    let mut st = FrStore::new(3, 300, 30);
    st.add(vec![FrSample {
        index: 2,
        omega: 2.0,
        meshes: vec![ext(1.0, 2.0, Some(1.1)), ext(-5.0, 9.0, Some(3.0))],
        period: Some(1),
        error: None,
    }]);
    st.add(vec![FrSample {
        index: 0,
        omega: 0.1,
        meshes: vec![],
        period: None,
        error: Some("blew up".into()),
    }]);
    st.add(vec![FrSample {
        index: 7,
        omega: 9.0,
        meshes: vec![],
        period: None,
        error: None,
    }]);
    assert_eq!(st.done(), 2);
    let (pts, failed) = st.curve(Some(0));
    assert_eq!(pts.len(), 1);
    assert_eq!(pts[0].max_um, 2.0);
    assert_eq!(failed.len(), 1);
    assert_eq!(st.curve(None).0[0].max_um, 9.0);
}

#[test]
fn hbm_branch_with_markers_partial_failure_and_overlay() {
    let mut st = HbmStore::new(5);
    let mut p1 = hbm_point(0.5, &[(80.0, 120.0), (90.0, 100.0)], true);
    let mut p2 = hbm_point(1.0, &[(60.0, 140.0), (50.0, 200.0)], false);
    p2.bifurcation = Some(BranchBif::Fold);
    p1.meshes[0].regime = Regime::SingleSided;
    st.add(vec![p1, p2], 0.4, false, None);
    let tail = hbm_point(1.5, &[(80.0, 120.0), (90.0, 100.0)], true);
    st.add(vec![tail], 0.7, true, Some("did not converge".into()));
    assert!(st.finished && !st.is_complete());
    let mut ti = FrStore::new(2, 300, 30);
    ti.add(vec![
        FrSample {
            index: 0,
            omega: 0.75,
            meshes: vec![ext(72.0, 128.0, Some(1.2)), ext(0.0, 1.0, Some(1.0))],
            period: Some(1),
            error: None,
        },
        FrSample {
            index: 1,
            omega: 1.9,
            meshes: vec![],
            period: None,
            error: Some("x".into()),
        },
    ]);
    let prev = st.clone();
    let v = fr_view(&st, Some(&prev), Some(&ti), Some(0), &[100.0, 50.0], &ctx());
    assert_eq!(v.method, "harmonic balance, H = 5, exact");
    assert_eq!(v.backlash_um, vec![100.0]);
    assert_eq!(v.branches.len(), 2);
    assert!(v.branches[0].faded && !v.branches[1].faded);
    let cur = &v.branches[1];
    assert!(cur.label.contains("partial"));
    assert_eq!(cur.points[1].stable, Some(false));
    assert_eq!(
        v.markers,
        vec![FrMarker {
            omega: 1.0,
            value_um: 140.0,
            kind: FrMarkerKind::Fold
        }]
    );
    assert_eq!(v.branch_error, Some((1.5, "did not converge".into())));
    // The overlay point at 0.75 lies on the unstable stretch only: not compared.
    assert_eq!(v.overlay.len(), 1);
    assert_eq!(v.failed.len(), 1);
    assert_eq!(
        v.discrepancy,
        Discrepancy {
            max_um: None,
            compared: 0,
            off_branch: 1
        }
    );
    // On a stable stretch the figure is the larger miss of the two extremes.
    let stable: Vec<FrCurvePoint> = [(0.5, 80.0, 120.0), (1.0, 60.0, 140.0)]
        .iter()
        .map(|&(omega, min_um, max_um)| FrCurvePoint {
            omega,
            max_um,
            min_um,
            stable: Some(true),
            regime: None,
            period: Some(1),
            bifurcation: None,
            piece: 0,
        })
        .collect();
    assert_eq!(discrepancy(&stable, &v.overlay).max_um, Some(2.0));
    // Worst: the mesh with the largest peak-to-peak x at each point.
    let w = fr_view(&st, None, None, None, &[100.0, 50.0], &ctx());
    let maxes: Vec<f64> = w.branches[0].points.iter().map(|p| p.max_um).collect();
    assert_eq!(maxes, vec![120.0, 200.0, 120.0]);
    assert_eq!(w.backlash_um, vec![50.0, 100.0]);
    let csv = fr_csv(&v);
    assert!(
        csv.lines()
            .nth(2)
            .unwrap()
            .starts_with("hbm,1,140,60,false,none,1,fold (jump)"),
        "{csv}"
    );
    assert!(
        csv.lines()
            .nth(4)
            .unwrap()
            .starts_with("time-integration,0.75,128,72,,single-sided,1"),
        "{csv}"
    );
}
