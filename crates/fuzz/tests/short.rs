//! The short fuzz run CI does on every `cargo test`: a few thousand inputs
//! per target (set GEARSHOCK_FUZZ_INPUTS for more; the long run is the
//! `gearshock-fuzz` binary). Zero panics, zero broken invariants.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

fn inputs() -> u64 {
    std::env::var("GEARSHOCK_FUZZ_INPUTS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1500)
}

fn check(target: &str) {
    let r = fuzz::run(target, 0x5eed, inputs());
    assert_eq!(r.inputs, inputs());
    assert!(r.failures.is_empty(), "{target}: {:#?}", r.failures);
}

#[test]
fn link_decoder_survives_hostile_links() {
    check("link");
}

#[test]
fn parameter_json_survives_hostile_files() {
    check("params");
}

#[test]
fn shard_merger_survives_forged_shards() {
    check("shards");
}

#[test]
fn te_file_reader_survives_hostile_tables() {
    check("te_file");
}

#[test]
fn the_generators_reach_what_they_target() {
    // A harness whose inputs never get past the first check tests nothing:
    // some links must carry a pinned state, some parameter files must be
    // accepted, and some forged shard sets must still merge.
    let keys = fuzz::all_keys();
    let (sweeps, maps) = fuzz::base_shards();
    assert_eq!((sweeps.len(), maps.len()), (2, 2));
    let (mut pinned, mut params_ok, mut merged, mut refused) = (0, 0, 0, 0);
    for n in 0..400 {
        let mut r = fuzz::Rng::new(7, n);
        if figures::link::decode(&fuzz::link_input(&mut r, &keys))
            .pinned
            .is_some()
        {
            pinned += 1;
        }
        if solver::keys::from_json_str(&fuzz::params_input(&mut r, &keys)).is_ok() {
            params_ok += 1;
        }
        let s = fuzz::shards_input(&mut r, &sweeps, &maps);
        if report::merge_shards(&s).is_ok() || report::merge_maps(&s).is_ok() {
            merged += 1;
        } else {
            refused += 1;
        }
    }
    // Some hostile tables must still be read and fitted.
    let fitted = (0..400)
        .filter(|&n| {
            let t = fuzz::te_input(&mut fuzz::Rng::new(9, n));
            solver::te_file::parse(&t)
                .and_then(|tb| solver::te_file::fit(&tb, 1.0, 1))
                .is_ok()
        })
        .count();
    assert!(fitted > 10, "{fitted}");
    assert!(pinned > 10, "{pinned}");
    assert!(params_ok > 10, "{params_ok}");
    assert!(
        merged > 10 && refused > 100,
        "{merged} merged, {refused} refused"
    );
}
