//! Impact-regime maps: the known regime sequence of the gear pair as TE
//! grows (Kahraman & Singh), shards that merge into the unsharded map, and
//! bad input named.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::keys;
use solver::map::{canonical_cells, MapCell, MapSpec, RegimeMap};
use solver::params::ModelParams;
use solver::steady::Impact;

fn pair() -> ModelParams {
    let mut p = ModelParams::default();
    keys::set_assignment(&mut p, "model=gear-pair").unwrap();
    p
}

fn run(map: &mut RegimeMap) -> Vec<MapCell> {
    let mut cells = Vec::new();
    while !map.is_finished() {
        cells.extend(map.advance(3));
    }
    cells
}

#[test]
fn gear_pair_regimes_go_none_single_double_as_te_grows() {
    // The same sequence as tests/gear_pair.rs at Omega 0.9, now as map rows.
    let mut spec = MapSpec::new((0.9, 1.0, 2), "te_um", (0.5, 40.0, 2));
    spec.value_points = 2;
    let rows = [0.5, 3.0, 10.0, 40.0];
    let expected = [
        Impact::None,
        Impact::SingleSided,
        Impact::SingleSided,
        Impact::DoubleSided,
    ];
    for (te, want) in rows.iter().zip(expected) {
        spec.value_from = *te;
        spec.value_to = *te;
        spec.value_points = 1;
        let mut map = RegimeMap::new(&pair(), spec.clone()).unwrap();
        let cells = run(&mut map);
        assert_eq!(cells.len(), 2);
        assert_eq!(cells[0].omega, 0.9);
        assert_eq!(cells[0].impact, want, "TE {te} um");
        assert!(cells.iter().all(|c| c.error.is_none()));
    }
}

#[test]
fn sharded_maps_merge_into_the_unsharded_map() {
    let mut spec = MapSpec::new((0.4, 1.6, 4), "backlash_um", (20.0, 200.0, 3));
    spec.steady.transient_periods = 100;
    spec.steady.record_periods = 20;
    let whole = run(&mut RegimeMap::new(&pair(), spec.clone()).unwrap());
    assert_eq!(whole.len(), 12);
    let mut parts = Vec::new();
    for i in 0..2 {
        let mut s = spec.clone();
        s.shard = Some((i, 2));
        parts.extend(run(&mut RegimeMap::new(&pair(), s).unwrap()));
    }
    canonical_cells(&mut parts);
    assert_eq!(parts, whole);
    // Rows are the key's values, columns Omega.
    assert_eq!(whole[4].row, 1);
    assert_eq!(whole[4].value, 110.0);
    assert_eq!(whole[5].omega, 0.8);
}

#[test]
fn bad_input_is_named() {
    let e = RegimeMap::new(
        &pair(),
        MapSpec::new((0.4, 1.6, 4), "no_such_key", (1.0, 2.0, 2)),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("no_such_key"), "{e}");
    let e = RegimeMap::new(
        &pair(),
        MapSpec::new((0.4, 1.6, 4), "backlash_um", (-5.0, 2.0, 2)),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("backlash_um") && e.contains("-5"), "{e}");
    let e = RegimeMap::new(
        &pair(),
        MapSpec::new((0.4, 1.6, 5000), "backlash_um", (1.0, 2.0, 2)),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("omega-points"), "{e}");
}
