//! Time integration against an independent reference: `tools/reference.py`,
//! a separate NumPy implementation of `docs/model.md` integrated by scipy's
//! DOP853 at rtol 1e-12 (no event location, steps capped at T/40). Its Poincaré
//! samples of `delta_s1a1` over 40 periods from the static equilibrium are
//! stored in `fixtures/reference.json`.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use solver::keys::{self, Value as KeyValue};
use solver::params::ModelParams;
use solver::steady::{steady_state, Model};
use test_support::models::strict_run;

#[test]
fn poincare_samples_match_the_scipy_reference() {
    let text = include_str!("fixtures/reference.json");
    let v: serde_json::Value = serde_json::from_str(text).expect("fixture");
    let cases = v["cases"].as_array().expect("cases");
    assert_eq!(cases.len(), 3);
    for case in cases {
        let omega = case["omega"].as_f64().expect("omega");
        let mut p = ModelParams::default();
        if let Some(b) = case["kw"]["backlash_um"].as_f64() {
            keys::set(&mut p, "backlash_um", KeyValue::Num(b)).expect("b");
        }
        if let Some(e) = case["kw"]["te_sin_um"].as_f64() {
            keys::set(&mut p, "te_um", KeyValue::Num(e)).expect("te");
        }
        let model = Model::new(&p).expect("model");
        let reference: Vec<f64> = case["poincare_delta_s1a1_m"]
            .as_array()
            .expect("samples")
            .iter()
            .map(|x| x.as_f64().expect("number"))
            .collect();
        let mut opts = strict_run(omega, (0, 40), (1e-10, 1e-16));
        opts.samples_per_period = 0;
        let ss = steady_state(&model, &opts, None).expect("run");
        let ours = &ss.meshes[0].poincare_delta_m;
        // The responses are sensitive (chaotic transients), so differences
        // grow with time; over the first 10 periods both integrators agree to
        // a few 1e-6 um on deflections of some 100 um.
        for k in 1..=10 {
            let diff_um = (ours[k - 1] - reference[k]).abs() * 1e6;
            assert!(diff_um < 2e-5, "Omega {omega}, period {k}: {diff_um} um");
        }
    }
}
