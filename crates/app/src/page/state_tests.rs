//! The page core's tests that every control shows the state after every
//! change: a shortcut's per-mesh-kind fields, the labels and the
//! subtitle of the model shown, and a refused value that keeps the last
//! good state and says why in plain words.

use super::*;

fn page(link: &str) -> Page {
    let (ctl, _) = Controller::new(link, 0.0);
    Page::new(ctl, false)
}

/// The writes of one frame after `key` was set to `value`.
fn after(p: &mut Page, key: &str, value: &str) -> Vec<Write> {
    p.input(key, value, 1.0);
    let (_, mut w) = p.apply_pending(1.0);
    let (d, _) = p.begin_frame(2.0);
    w.extend(p.end_frame(&d));
    w
}

fn value_of(w: &[Write], id: &str) -> Option<String> {
    w.iter().rev().find_map(|x| match x {
        Write::Value { id: i, value } if i == id => Some(value.clone()),
        _ => None,
    })
}

fn text_of(w: &[Write], id: &str) -> Option<String> {
    w.iter().rev().find_map(|x| match x {
        Write::Text { id: i, text } if i == id => Some(text.clone()),
        _ => None,
    })
}

#[test]
fn backlash_on_all_meshes_shows_in_every_per_mesh_kind_field() {
    let mut p = page("");
    let w = after(&mut p, "backlash_um", "73");
    for kind in ["s1a", "s2b", "ab", "rb"] {
        let id = format!("num-backlash_{kind}_um");
        assert_eq!(value_of(&w, &id).as_deref(), Some("73"), "{id}");
    }
    // One kind set apart: the shortcut's field reads as mixed (empty).
    let w = after(&mut p, "backlash_ab_um", "40");
    assert_eq!(value_of(&w, "num-backlash_um").as_deref(), Some(""));
    assert_eq!(value_of(&w, "num-backlash_ab_um").as_deref(), Some("40"));
}

#[test]
fn the_gear_pair_names_its_one_mesh_and_itself() {
    let mut p = page("");
    let w = after(&mut p, "model", "gear-pair");
    let sub = text_of(&w, "model-subtitle").unwrap_or_default();
    assert!(
        sub.contains("gear pair") && !sub.contains("Ravigneaux"),
        "{sub}"
    );
    for c in figures::controls::controls() {
        if !figures::controls::shown_for(&c, solver::params::ModelKind::GearPair) {
            continue;
        }
        let label = text_of(&w, &format!("label-{}", c.key)).unwrap_or_default();
        assert!(
            !label.is_empty() && !label.contains("meshes"),
            "{}: {label}",
            c.key
        );
    }
    let w = after(&mut p, "model", "ravigneaux");
    let sub = text_of(&w, "model-subtitle").unwrap_or_default();
    assert!(sub.contains("Ravigneaux"), "{sub}");
    assert_eq!(
        text_of(&w, "label-backlash_um").as_deref(),
        Some("Backlash b (all meshes)")
    );
}

#[test]
fn a_negative_torque_is_refused_in_words_and_the_last_state_kept() {
    for (link, key) in [
        ("", "torque_s1_nm"),
        ("model=gear-pair", "torque_pinion_nm"),
    ] {
        let mut p = page(link);
        let before = p.ctl().settings().params.clone();
        let w = after(&mut p, key, "-5");
        assert_eq!(p.ctl().settings().params, before, "{key}");
        let msg = p.ctl().issues.join(" ");
        assert!(
            msg.contains("(not -5)") && msg.contains("between 0 and"),
            "{msg}"
        );
        assert!(!msg.contains(key) && !msg.contains("NaN"), "{msg}");
        // The field goes back to the value in force.
        let shown = value_of(&w, &format!("num-{key}")).unwrap_or_default();
        let kept = match solver::keys::get(&before, key) {
            Some(solver::keys::Value::Num(x)) => figures::controls::field_text(x),
            _ => String::new(),
        };
        assert_eq!(shown, kept, "{key}");
    }
}

/// A torque that deflects the teeth by millimetres is warned about beside
/// the summary as soon as it is set, and the warning goes with it.
#[test]
fn a_load_outside_the_models_validity_is_warned_until_it_is_lowered() {
    let mut p = page("");
    let w = after(&mut p, "torque_s1_nm", "900000");
    let shown = w.contains(&Write::Hidden {
        id: "validity".into(),
        hidden: false,
    });
    let text = text_of(&w, "validity").unwrap_or_default();
    assert!(shown && text.starts_with("Outside the model"), "{text}");
    let w = after(&mut p, "torque_s1_nm", "2000");
    assert!(w.contains(&Write::Hidden {
        id: "validity".into(),
        hidden: true,
    }));
}
