//! The excitation's waveforms in links: a link that sets a stiffness
//! waveform, a contact ratio and TE harmonics round-trips exactly, and the
//! default links do not name them.

// Tests may panic: that is how they fail.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::panic)]

use figures::link::{decode, encode};
use solver::keys::{self, Value};

#[test]
fn a_link_with_waveforms_and_te_harmonics_round_trips_exactly() {
    for query in [
        "model=gear-pair&stiffness_wave=trapezoid&contact_ratio=1.63&stiffness_ramp=0.15\
         &stiffness_harmonics=9&te_cos2_um=2.5&te_sin3_um=-0.8125",
        "model=ravigneaux&stiffness_wave_s1a=rectangular&contact_ratio_rb=1.7\
         &te_sin2_s1a_um=1.25&te_cos6_ab_um=0.1",
    ] {
        let d = decode(query);
        assert!(d.issues.is_empty(), "{query}: {:?}", d.issues);
        let again = encode(&d.settings);
        assert_eq!(decode(&again).settings, d.settings, "{again}");
        assert_eq!(encode(&decode(&again).settings), again);
        for pair in query.split('&').skip(1) {
            assert!(again.contains(pair), "{pair} in {again}");
        }
    }
    let d = decode("model=gear-pair&te_sin3_um=-0.8125");
    assert_eq!(
        keys::get(&d.settings.params, "te_sin3_um"),
        Some(Value::Num(-0.8125))
    );
}

#[test]
fn default_links_name_no_waveform() {
    for model in ["ravigneaux", "gear-pair"] {
        let q = encode(&decode(&format!("model={model}")).settings);
        assert!(
            !q.contains("wave") && !q.contains("contact_ratio") && !q.contains("te_cos2"),
            "{q}"
        );
    }
    let bad = decode("model=gear-pair&stiffness_wave=square&contact_ratio=4");
    assert_eq!(bad.issues.len(), 2, "{:?}", bad.issues);
}
