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

#[test]
fn a_map_in_slices_of_steps_is_the_same_as_cell_by_cell() {
    // The compound set (long steady states), and cells that fail (a step
    // budget too small) so that the rows go on from the static state.
    for budget in [200_000, 3] {
        let mut spec = MapSpec::new((0.5, 1.1, 3), "backlash_um", (50.0, 100.0, 2));
        spec.steady.transient_periods = 60;
        spec.steady.record_periods = 10;
        spec.steady.max_steps_per_period = budget;
        let base = ModelParams::default();
        let want = run(&mut RegimeMap::new(&base, spec.clone()).unwrap());
        assert_eq!(want.len(), 6);
        // `advance(usize::MAX)` is the whole map (and allocates no more).
        let whole = RegimeMap::new(&base, spec.clone())
            .unwrap()
            .advance(usize::MAX);
        assert_eq!(whole, want);
        assert_eq!(
            want.iter().all(|c| c.error.is_some()),
            budget == 3,
            "budget {budget}"
        );
        for slice in [1, 7, 3000] {
            let mut map = RegimeMap::new(&base, spec.clone()).unwrap();
            let mut cells = Vec::new();
            let mut pauses = 0u64;
            while !map.is_finished() {
                let got = map.advance_steps(slice);
                pauses += u64::from(got.is_empty());
                cells.extend(got);
                assert!(pauses < 10_000_000, "the map never ends");
            }
            assert_eq!(cells, want, "slices of {slice} steps, budget {budget}");
            assert_eq!(map.done(), 6);
            if budget > 3 && slice < 3000 {
                assert!(pauses > 6, "slices of {slice}: no pause inside a cell");
            }
        }
    }
}
