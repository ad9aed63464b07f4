//! `gearshock map`: shards of rows merged equal the unsharded map.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use test_support::cli::{gearshock, json, words};

#[test]
fn map_shards_merge_into_the_unsharded_map() {
    let args = |extra: &[&'static str]| -> Vec<&'static str> {
        let mut a = words("map --model gear-pair --omega-from 0.4 --omega-to 1.6 --omega-points 4 --key te_um --value-from 1 --value-to 40 --value-points 3 --transient-periods 100 --record-periods 20");
        a.extend_from_slice(extra);
        a
    };
    let whole = json(&args(&[]));
    let cells = whole["cells"].as_array().unwrap();
    assert_eq!(cells.len(), 12);
    assert!(cells.iter().all(|c| c["impact"].is_string()));
    let dir = std::env::temp_dir().join(format!("gearshock-map-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let mut files = Vec::new();
    for s in ["0/2", "1/2"] {
        let v = json(&args(&["--shard", s]));
        let f = dir.join(format!("{}.json", s.replace('/', "-")));
        std::fs::write(&f, v.to_string()).unwrap();
        files.push(f.to_string_lossy().into_owned());
    }
    let merged = json(&["merge", &files[0], &files[1]]);
    assert_eq!(merged, whole);
    let out = gearshock(&args(&["--shard", "2/2"]));
    assert_eq!(out.status.code(), Some(2));
}
