//! Regression test: the exported data of one fixed link, computed by the
//! real controller and worker job runner natively, compared byte for byte
//! with the snapshot in `tests/snapshots/exports.txt`.
//!
//! A refactoring that changes any exported number, column or file name
//! fails here. To regenerate it after an intended change, run
//! `GEARSHOCK_BLESS=1 cargo test -p app --test exports` and review the diff.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use app::controller::{Controller, Effect};
use figures::protocol::encode;
use worker::WorkerCore;

/// A small but complete page: a few Omega points per view, a small map and
/// Lyapunov curve, the time-integration overlay on.
const LINK: &str = "omega=1.05&omega_from=0.8&omega_to=1.3&fr_points=12&fr_ti_points=4\
&fr_record_periods=5&bif_points=6&bif_dir=up&transient_periods=60&record_periods=12\
&harmonics=3&map_omega_points=3&map_value_points=2&map_transient_periods=40\
&map_record_periods=8&lyap_points=3&lyap_transient_periods=40&lyap_periods=20";

/// Delivers every posted message to its worker, runs the workers until they
/// are idle and feeds the replies back, until nothing more is posted.
/// Returns the downloads the controller asked for.
fn settle(c: &mut Controller, cores: &mut [WorkerCore], mut fx: Vec<Effect>) -> Vec<Effect> {
    let mut downloads = Vec::new();
    let mut now = 10.0;
    for _round in 0..10_000 {
        let mut replies = Vec::new();
        for e in fx.drain(..) {
            match e {
                Effect::Post { worker, text } => {
                    for r in cores[worker].handle(&text) {
                        replies.push((worker, encode(&r)));
                    }
                }
                d @ Effect::Download { .. } => downloads.push(d),
            }
        }
        for (w, core) in cores.iter_mut().enumerate() {
            if core.has_work() {
                for r in core.step() {
                    replies.push((w, encode(&r)));
                }
            }
        }
        if replies.is_empty() && cores.iter().all(|c| !c.has_work()) {
            return downloads;
        }
        for (w, text) in replies {
            now += 1.0;
            fx.extend(c.worker_message(w, &text, now));
        }
    }
    panic!("the jobs did not finish");
}

/// The same page with a family of three TE values: every export holds
/// every member.
fn family_link() -> String {
    format!("{LINK}&family=te_um:0,20,30")
}

fn exports() -> String {
    let mut out = exports_of(LINK, 2);
    out.push_str("##### the same link with a family of three TE values\n");
    out.push_str(&exports_of(&family_link(), 2));
    out
}

/// Every export of link `link` computed by a pool of `workers` workers.
fn exports_of(link: &str, workers: usize) -> String {
    let (mut c, fx) = Controller::with_workers(link, 0.0, workers);
    assert_eq!(c.workers(), workers);
    assert!(c.issues.is_empty(), "{:?}", c.issues);
    let mut cores: Vec<WorkerCore> = (0..workers).map(|_| WorkerCore::new()).collect();
    let mut fx = fx;
    for w in 0..workers {
        fx.extend(c.worker_message(w, r#"{"type":"ready"}"#, 1.0));
    }
    let downloads = settle(&mut c, &mut cores, fx);
    assert!(downloads.is_empty());
    assert!(c.issues.is_empty(), "{:?}", c.issues);
    let mut out = String::new();
    for (name, text) in files(&mut c, &mut cores) {
        out.push_str(&format!("===== {name}\n{text}\n"));
    }
    out
}

/// Every export of the page, as the page's export buttons ask the
/// controller for them: (file name, text).
fn files(c: &mut Controller, cores: &mut [WorkerCore]) -> Vec<(String, String)> {
    use app::controller::Format;
    use figures::views::{ViewId, VIEWS};
    let mut out = Vec::new();
    let file = |e: Effect| match e {
        Effect::Download { name, text, .. } => (name, text),
        Effect::Post { .. } => panic!("a data export posts nothing"),
    };
    // The order the snapshot was written in: the sweeps, the map and the
    // Lyapunov curve, then the selected-Omega views, then the Campbell
    // diagram's critical speeds, then the dynamic factor, then the mesh
    // force by order.
    let order = [ViewId::Fr, ViewId::Bif, ViewId::Map, ViewId::Lyap]
        .into_iter()
        .chain([
            ViewId::Phase,
            ViewId::Poincare,
            ViewId::Time,
            ViewId::Spectrum,
            ViewId::Campbell,
            ViewId::Dynamic,
            ViewId::Orders,
        ]);
    assert_eq!(order.clone().count(), VIEWS.len());
    for view in order {
        for format in Format::ALL {
            out.push(file(c.export(view, format).unwrap()));
        }
    }
    let sim = c.export_cli(ViewId::Time, 2.0).unwrap();
    assert_eq!(sim.len(), 1);
    out.extend(sim.into_iter().map(file));
    out.push(file(c.export_params()));
    let fx = c
        .export_cli(ViewId::Bif, 2.0)
        .expect("a bifurcation export");
    for d in settle(c, cores, fx) {
        if let Effect::Download { name, mime, text } = d {
            out.push((format!("{name} ({mime})"), text));
        }
    }
    out.push(("cli-commands".into(), c.cli_commands()));
    out
}

#[test]
fn the_exports_of_a_fixed_link_are_unchanged() {
    let got = exports();
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/snapshots/exports.txt");
    if std::env::var_os("GEARSHOCK_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, &got).unwrap();
    }
    let want = std::fs::read_to_string(&path).expect("the snapshot file");
    if got != want {
        let first = got
            .lines()
            .zip(want.lines())
            .position(|(a, b)| a != b)
            .unwrap_or(got.lines().count().min(want.lines().count()));
        panic!(
            "the exports differ from the snapshot at line {}:\n got: {:?}\nwant: {:?}",
            first + 1,
            got.lines().nth(first),
            want.lines().nth(first)
        );
    }
}

/// One file of an export listing (`===== name` then its text).
fn file_text<'a>(all: &'a str, name: &str) -> &'a str {
    let head = format!("===== {name}\n");
    let start = all.find(&head).map(|i| i + head.len()).expect(name);
    let rest = &all[start..];
    &rest[..rest.find("\n===== ").unwrap_or(rest.len())]
}

#[test]
fn a_familys_exports_hold_every_member() {
    let all = exports_of(&family_link(), 2);
    let labels = ["TE 0 µm", "TE 20 µm", "TE 30 µm"];
    for name in [
        "gearshock-bif-s1a1-te_um-0_20_30.csv",
        "gearshock-phase-s1a1-omega1.05-te_um-0_20_30.csv",
        "gearshock-poincare-s1a1-omega1.05-te_um-0_20_30.csv",
        "gearshock-time-s1a1-omega1.05-te_um-0_20_30.csv",
        "gearshock-spectrum-s1a1-omega1.05-te_um-0_20_30.csv",
    ] {
        let csv = file_text(&all, name);
        assert!(csv.starts_with("member,"), "{name}: {csv}");
        let mut seen: Vec<&str> = csv
            .lines()
            .skip(1)
            .filter_map(|l| l.split(',').next())
            .collect();
        seen.dedup();
        assert_eq!(seen, labels, "{name}");
    }
    for name in [
        "gearshock-bif-s1a1-te_um-0_20_30.json",
        "gearshock-phase-s1a1-omega1.05-te_um-0_20_30.json",
        "gearshock-spectrum-s1a1-omega1.05-te_um-0_20_30.json",
    ] {
        let j: serde_json::Value = serde_json::from_str(file_text(&all, name)).expect(name);
        assert_eq!(j["family"]["values"], serde_json::json!([0.0, 20.0, 30.0]));
        let members = j["members"].as_array().expect(name);
        assert_eq!(members.len(), 3, "{name}");
        for (m, label) in members.iter().zip(labels) {
            assert_eq!(m["member"], label, "{name}");
            assert!(m.get("error").is_none(), "{name}: {m}");
        }
    }
    // Each member is its own computation: the bifurcation rows differ.
    let bif = file_text(&all, "gearshock-bif-s1a1-te_um-0_20_30.csv");
    let rows = |l: &str| -> Vec<String> {
        bif.lines()
            .filter(|r| r.starts_with(l))
            .map(|r| r[l.len()..].to_string())
            .collect()
    };
    assert_eq!(rows("TE 0 µm,").len(), rows("TE 30 µm,").len());
    assert_ne!(rows("TE 0 µm,"), rows("TE 30 µm,"));
}

#[test]
fn every_export_is_the_same_whatever_the_pool_size() {
    // 400 sweep points make 8 chains (3 Lyapunov chains, 3 overlay chains),
    // dealt unevenly over 3 workers and one each over 8: each chain must
    // continue from the same states, and the shards merge into the same
    // CLI JSON, as with 2 workers.
    // Each setting replaced in place: a key given twice is named as an
    // issue (its first value counts).
    let link = LINK
        .replace("bif_points=6", "bif_points=400")
        .replace("fr_ti_points=4", "fr_ti_points=150")
        .replace("lyap_points=3", "lyap_points=150");
    assert!(
        link.contains("bif_points=400")
            && link.contains("fr_ti_points=150")
            && link.contains("lyap_points=150")
    );
    assert_eq!(app::store::kinds::chain_count(400), 8);
    assert_eq!(app::store::kinds::chain_count(150), 3);
    let two = exports_of(&link, 2);
    assert!(
        two.contains("gearshock-bif-bifurcation"),
        "no CLI sweep export"
    );
    for workers in [1, 3, 8] {
        let got = exports_of(&link, workers);
        assert!(
            got == two,
            "the exports of {workers} workers differ from 2 workers'"
        );
    }
}
