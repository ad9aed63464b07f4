//! The family's tests: the fan-out of member jobs, the routing of their
//! replies into the overlay and the small multiples, presets that load a
//! whole family, and bad family input refused with the last state kept.

use super::tests::{posts, ready};
use super::*;
use figures::protocol::{BifMesh, BifSample, HbmMesh, HbmSample, Regime};

/// The member jobs posted: (member, kind, worker, its TE in µm).
fn member_jobs(p: &[(usize, ToWorker)]) -> Vec<(u32, JobKind, usize, f64)> {
    p.iter()
        .filter_map(|(w, m)| match m {
            ToWorker::Run {
                target: Target::Member(member),
                params,
                job,
                ..
            } => {
                let mp = keys::from_json(params).unwrap();
                let te = match keys::get(&mp, "te_um") {
                    Some(keys::Value::Num(x)) => x,
                    other => panic!("{other:?}"),
                };
                Some((*member, job.kind(), *w, te))
            }
            _ => None,
        })
        .collect()
}

fn member_id(c: &Controller, i: usize, kind: JobKind) -> JobId {
    let m = &c.family.as_ref().unwrap().members[i];
    m.comp.status(kind).id
}

fn hbm(id: JobId, amplitude: f64) -> String {
    hbm_meshes(id, 1, |_| amplitude)
}

#[test]
fn a_family_link_fans_out_member_jobs_and_restores_exactly() {
    let q = "model=ravigneaux&backlash_um=200&family=te_um%3A0%2C20%2C30";
    let (mut c, fx) = Controller::new(q, 0.0);
    assert!(fx.is_empty());
    assert!(c.issues.is_empty(), "{:?}", c.issues);
    // Member 0 is the current state.
    assert_eq!(
        keys::get(&c.settings.params, "te_um"),
        Some(keys::Value::Num(0.0))
    );
    let p = ready(&mut c);
    let jobs = member_jobs(&p);
    // Members 1 and 2: one branch, two sweep shards (one per worker) and
    // one selected-Omega run each, with their own TE.
    for (member, te) in [(1, 20.0), (2, 30.0)] {
        let mine: Vec<_> = jobs.iter().filter(|j| j.0 == member).collect();
        assert_eq!(mine.len(), 4, "{mine:?}");
        assert!(mine.iter().all(|j| j.3 == te), "{mine:?}");
        let bif_workers: Vec<usize> = mine
            .iter()
            .filter(|j| j.1 == JobKind::Bif)
            .map(|j| j.2)
            .collect();
        assert_eq!(bif_workers, vec![0, 1]);
        assert_eq!(
            mine.iter()
                .filter(|j| j.1 == JobKind::HarmonicBalance)
                .count(),
            1
        );
        assert_eq!(mine.iter().filter(|j| j.1 == JobKind::Omega).count(), 1);
    }
    // The two members' branches go to different workers.
    let hbm_workers: Vec<usize> = jobs
        .iter()
        .filter(|j| j.1 == JobKind::HarmonicBalance)
        .map(|j| j.2)
        .collect();
    assert_eq!(hbm_workers.len(), 2);
    assert_ne!(hbm_workers[0], hbm_workers[1]);
    // The link carries the family and restores it exactly.
    let link = c.query();
    assert!(link.contains("family=te_um%3A0%2C20%2C30"), "{link}");
    let (again, _) = Controller::new(&link, 0.0);
    assert_eq!(
        again.family.as_ref().unwrap().spec,
        c.family.as_ref().unwrap().spec
    );
    assert_eq!(again.settings, c.settings);
    assert_eq!(again.query(), link);
}

#[test]
fn member_replies_become_coloured_curves_labelled_in_words() {
    let (mut c, _) = Controller::new("family=te_um:0,20,30", 0.0);
    ready(&mut c);
    let main = c.main.status(JobKind::HarmonicBalance).id;
    c.worker_message(1, &hbm(main, 10.0), 2.0);
    let m1 = member_id(&c, 0, JobKind::HarmonicBalance);
    let m2 = member_id(&c, 1, JobKind::HarmonicBalance);
    c.worker_message(0, &hbm(m1, 20.0), 3.0);
    // A stale id (an older job) is ignored.
    c.worker_message(0, &hbm(m2 + 1000, 99.0), 3.0);
    let v = c.fr_view();
    let curves: Vec<(String, Option<usize>, usize)> = v
        .branches
        .iter()
        .map(|b| (b.label.clone(), b.member, b.points.len()))
        .collect();
    assert_eq!(
        curves,
        vec![
            ("TE 0 µm".to_string(), Some(0), 2),
            ("TE 20 µm".to_string(), Some(1), 2),
            ("TE 30 µm".to_string(), Some(2), 0),
        ]
    );
    assert_eq!(v.branches[1].points[0].max_um, 20.0);
    // A TE family shares one backlash: one pair of ±b lines.
    assert_eq!(v.backlash_um, vec![100.0]);
    let st = c.status(4.0);
    assert_eq!(st["family"]["members"][0]["fr_branch_points"], 2);
    assert_eq!(st["family"]["members"][1]["fr_branch_points"], 0);
    assert_eq!(st["family"]["labels"][2], "TE 30 µm");
    // The CSV export says which value each row belongs to.
    let csv = figures::views::fr::fr_csv(&c.fr_view());
    assert!(csv.contains("\nhbm (TE 0 µm),0.5,10,-10,"), "{csv}");
    assert!(csv.contains("\nhbm (TE 20 µm),1,20,-20,"), "{csv}");
    assert!(c.members_running(JobKind::HarmonicBalance));
    c.worker_message(0, &hbm(m2, 30.0), 5.0);
    assert_eq!(c.fr_view().branches[2].points.len(), 2);
    assert!(!c.members_running(JobKind::HarmonicBalance));
}

#[test]
fn the_small_multiples_share_their_axes_and_letter_their_panels() {
    let (mut c, _) = Controller::new("family=backlash_um:50,100,200", 0.0);
    ready(&mut c);
    let sample = |omega: f64, x: f64| BifSample {
        index: 0,
        omega,
        up: true,
        meshes: vec![BifMesh {
            x_um: vec![x],
            rel_min_um: x,
            rel_max_um: x,
            regime: Regime::SingleSided,
            dynamic_factor: None,
        }],
        worst_mesh: 0,
        period: Some(1),
        motion: figures::protocol::Motion::Periodic { period: 1 },
        error: None,
    };
    let bif = |id, x| {
        encode(&FromWorker::BifPoints {
            id,
            points: vec![sample(0.5, x)],
        })
    };
    c.worker_message(0, &bif(c.main.status(JobKind::Bif).id, 10.0), 2.0);
    c.worker_message(0, &bif(member_id(&c, 1, JobKind::Bif), -700.0), 2.0);
    let panels = c.bif_panels();
    let titles: Vec<&str> = panels.iter().map(|p| p.title.as_str()).collect();
    assert_eq!(
        titles,
        vec![
            "(a) backlash 50 µm",
            "(b) backlash 100 µm",
            "(c) backlash 200 µm"
        ]
    );
    // Each panel's ±b is its own member's backlash.
    let b: Vec<Vec<f64>> = panels
        .iter()
        .map(|p| p.data.as_ref().unwrap().backlash_um.clone())
        .collect();
    assert_eq!(b, vec![vec![50.0], vec![100.0], vec![200.0]]);
    // The overlay draws every member's ±b.
    assert_eq!(c.fr_view().backlash_um, vec![50.0, 100.0, 200.0]);
    // One range for all, fitted to the data (as every plot's axes are):
    // it holds panel c's -700 µm and panel a's +10 µm.
    let (x, y) = figures::plots::multiples::bif_ranges(&panels);
    assert_eq!(x, (c.settings.view.omega_from, c.settings.view.omega_to));
    assert!(y.0 < -700.0 && y.1 > 10.0, "{y:?}");
    // The Poincaré panels are lettered d-f.
    let omega = c.omega_panels(3);
    assert_eq!(omega[0].title, "(d) backlash 50 µm");
    assert!(
        omega.iter().all(|p| p.data.is_err()),
        "nothing computed yet"
    );
    // The SVG picture: the three panels with both panels' dots inside the
    // one SVG document (plotters closes it when the chart is presented).
    let svg = c.plot_svg(figures::views::ViewId::Bif).unwrap();
    assert!(svg.contains("(c) backlash 200 µm"));
    assert_eq!(svg.matches("</svg>").count(), 1);
    assert!(svg.trim_end().ends_with("</svg>"));
    let c = figures::plots::regime_color(Regime::SingleSided);
    let orange = format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2);
    assert_eq!(svg.matches(&orange).count(), 2, "two single-sided dots");
}

#[test]
fn a_figure_preset_loads_its_whole_family_and_bad_input_keeps_the_last_state() {
    let (mut c, _) = Controller::new("", 0.0);
    ready(&mut c);
    let fx = c.apply_preset("fig5", 1.0);
    let f = c.family.as_ref().unwrap();
    assert_eq!(
        (f.spec.key.key, f.spec.values.clone()),
        ("te_um", vec![0.0, 20.0, 30.0])
    );
    assert_eq!(member_jobs(&posts(&fx)).len(), 8);
    assert!(c.query().contains("family=te_um%3A0%2C20%2C30"));
    assert_eq!(c.settings.view.omega, 0.5);
    let before = c.query();
    for (key, values, words) in [
        ("te_um", "0, 20, 5000", "TE 5000"),
        ("te_um", "0, NaN", "TE NaN"),
        ("te_um", "1,2,3,4,5,6,7", "2 to 6"),
        ("foo", "1, 2", "cannot vary"),
    ] {
        let e = c.set_family_text(key, values, 2.0).unwrap_err().to_string();
        assert!(e.contains(words), "{e}");
        assert_eq!(c.query(), before, "the last good state is kept");
    }
    // A good one replaces it; the current state takes its first value.
    let fx = c.set_family_text("backlash_um", "50, 100", 3.0).unwrap();
    assert_eq!(member_jobs(&posts(&fx)).len(), 4);
    assert_eq!(
        keys::get(&c.settings.params, "backlash_um"),
        Some(keys::Value::Num(50.0))
    );
    // Moving the family's own control moves the first member.
    c.set_key("backlash_um", "60", 4.0).unwrap();
    assert_eq!(c.family.as_ref().unwrap().spec.values, vec![60.0, 100.0]);
    // One value only: the members' jobs are cancelled.
    let fx = c.clear_family(5.0);
    assert!(posts(&fx).iter().all(|(_, m)| matches!(
        m,
        ToWorker::Cancel {
            target: Target::Member(_),
            kind: None
        }
    )));
    assert!(!c.query().contains("family"));
    // A/B stays: pinning still works beside a family.
    c.set_family_text("te_um", "0, 30", 5.0).unwrap();
    c.pin_a(6.0);
    assert!(c.pinned.is_some() && c.family.is_some());
    let d = link::decode(&c.query());
    assert!(d.pinned.is_some() && d.family.is_some(), "{:?}", d.issues);
}

/// A branch of two points whose mesh `j` swings ±`amplitude(j)`.
fn hbm_meshes(id: JobId, meshes: usize, amplitude: impl Fn(usize) -> f64) -> String {
    encode(&FromWorker::HbmPoints {
        id,
        points: [0.5, 1.0]
            .iter()
            .map(|&omega| HbmSample {
                omega,
                meshes: (0..meshes)
                    .map(|j| HbmMesh {
                        rel_min_um: -amplitude(j),
                        rel_max_um: amplitude(j),
                        regime: Regime::NoImpact,
                    })
                    .collect(),
                stable: Some(true),
                bifurcation: None,
                piece: 0,
            })
            .collect(),
        progress: 1.0,
        finished: true,
        error: None,
        notes: Vec::new(),
    })
}

#[test]
fn fig2_shows_its_four_mesh_panels_as_a_projection_of_the_same_branches() {
    let (mut c, _) = Controller::new("", 0.0);
    ready(&mut c);
    let fx = c.apply_preset("fig2", 1.0);
    let names = ["s1a1", "s2b1", "a1b1", "rb1"];
    assert_eq!(c.panels.as_deref(), Some(&names.map(String::from)[..]));
    // No new computation: the same jobs as the family without panels.
    let link = c.query();
    assert!(link.contains("panels=s1a1%2Cs2b1%2Ca1b1%2Crb1"), "{link}");
    let jobs = member_jobs(&posts(&fx));
    assert_eq!(
        jobs.iter()
            .filter(|j| j.1 == JobKind::HarmonicBalance)
            .count(),
        5
    );
    // Every branch answers for every mesh; each panel projects its mesh.
    let model = c.model.as_ref().unwrap();
    let n = model.system.meshes.len();
    let index: Vec<usize> = names
        .iter()
        .map(|m| model.system.mesh_index(m).unwrap())
        .collect();
    let main = c.main.status(JobKind::HarmonicBalance).id;
    c.worker_message(1, &hbm_meshes(main, n, |j| j as f64 + 1.0), 2.0);
    for i in 0..5 {
        let id = member_id(&c, i, JobKind::HarmonicBalance);
        let scale = 100.0 * (i + 1) as f64;
        c.worker_message(0, &hbm_meshes(id, n, |j| scale + j as f64), 3.0);
    }
    let panels = c.fr_panels();
    assert_eq!(panels.len(), 4);
    assert_eq!(panels[0].title, "(a) s1a1 (small sun – short planet a1)");
    assert_eq!(panels[3].title, "(d) rb1 (ring – long planet b1)");
    for (p, &j) in panels.iter().zip(&index) {
        let v = p.data.as_ref().unwrap();
        let labels: Vec<&str> = v.branches.iter().map(|b| b.label.as_str()).collect();
        assert_eq!(
            labels,
            [
                "TE 5 µm",
                "TE 10 µm",
                "TE 15 µm",
                "TE 20 µm",
                "TE 25 µm",
                "TE 30 µm"
            ]
        );
        assert_eq!(v.branches[0].points[0].max_um, j as f64 + 1.0);
        assert_eq!(v.branches[2].points[1].min_um, -(200.0 + j as f64));
    }
    // The note says the panels hold the branches only (the dots are the
    // plotted mesh's alone).
    let note = figures::views::fr::fr_panels_note(&c.fr_view());
    assert!(note.contains("one panel per mesh") && !note.contains("Hollow dots"));
    // The text alternative and the SVG name all four meshes.
    let label = c.canvas_label(figures::views::ViewId::Fr);
    let svg = c.plot_svg(figures::views::ViewId::Fr).unwrap();
    assert!(svg.contains("height=\"680\""), "the taller canvas");
    for m in names {
        assert!(label.contains(m), "{label}");
        assert!(svg.contains(&figures::panels::mesh_words(m)), "{m}");
    }
    // The link restores the panels; choosing a mesh shows it alone.
    let (again, _) = Controller::new(&link, 0.0);
    assert_eq!(again.panels, c.panels);
    assert_eq!(again.query(), link);
    c.set_key("mesh", "s2b1", 4.0).unwrap();
    assert!(c.panels.is_none() && !c.query().contains("panels"));
}

#[test]
fn a_familys_svg_pictures_are_its_small_multiples() {
    let (mut c, _) = Controller::new("family=te_um:0,20,30", 0.0);
    ready(&mut c);
    for view in [
        figures::views::ViewId::Bif,
        figures::views::ViewId::Phase,
        figures::views::ViewId::Poincare,
    ] {
        let svg = c.plot_svg(view).unwrap();
        let offset = if view == figures::views::ViewId::Poincare {
            3
        } else {
            0
        };
        for (k, te) in [0, 20, 30].iter().enumerate() {
            let letter = char::from(b'a' + (k + offset) as u8);
            assert!(
                svg.contains(&format!("({letter}) TE {te} µm")),
                "{view:?}: {letter}"
            );
        }
    }
}

#[test]
fn the_mesh_panels_export_every_panel() {
    let (mut c, _) = Controller::new("", 0.0);
    ready(&mut c);
    c.apply_preset("fig3", 1.0);
    let n = c.model.as_ref().unwrap().system.meshes.len();
    c.worker_message(
        1,
        &hbm_meshes(c.main.status(JobKind::HarmonicBalance).id, n, |j| {
            j as f64 + 1.0
        }),
        2.0,
    );
    let text = |f| match c.export(figures::views::ViewId::Fr, f).unwrap() {
        Effect::Download { text, .. } => text,
        Effect::Post { .. } => panic!("a data export posts nothing"),
    };
    let csv = text(Format::Csv);
    assert!(csv.starts_with("mesh,branch,omega,"), "{csv}");
    for m in ["s1a1", "s2b1", "a1b1", "rb1"] {
        // Two points of the current state's branch on every panel.
        let rows = csv
            .lines()
            .filter(|l| l.starts_with(&format!("{m},hbm (backlash 50 µm),")))
            .count();
        assert_eq!(rows, 2, "{m}: {csv}");
    }
    let json: serde_json::Value = serde_json::from_str(&text(Format::Json)).unwrap();
    let panels = json["panels"].as_array().unwrap();
    assert_eq!(panels.len(), 4);
    assert_eq!(panels[3]["mesh"], "rb1");
    assert_eq!(panels[3]["view"]["branches"].as_array().unwrap().len(), 4);
}
