//! The controller's tests: jobs, replies, links and presets, with real or
//! hand-made worker messages.

use super::*;
use figures::protocol::{FrSample, HbmMesh, HbmSample, OmegaSpec};

pub(super) fn posts(fx: &[Effect]) -> Vec<(usize, ToWorker)> {
    fx.iter()
        .filter_map(|e| match e {
            Effect::Post { worker, text } => Some((*worker, serde_json::from_str(text).unwrap())),
            Effect::Download { .. } => None,
        })
        .collect()
}

pub(super) fn ready(c: &mut Controller) -> Vec<(usize, ToWorker)> {
    let mut fx = c.worker_message(0, r#"{"type":"ready"}"#, 1.0);
    fx.extend(c.worker_message(1, r#"{"type":"ready"}"#, 1.0));
    posts(&fx)
}

fn hbm_points(id: JobId, omegas: &[f64], finished: bool, error: Option<&str>) -> String {
    encode(&FromWorker::HbmPoints {
        id,
        points: omegas
            .iter()
            .map(|&omega| HbmSample {
                omega,
                meshes: vec![HbmMesh {
                    rel_min_um: 80.0,
                    rel_max_um: 120.0,
                    regime: figures::protocol::Regime::NoImpact,
                }],
                stable: Some(true),
                bifurcation: None,
                piece: 0,
            })
            .collect(),
        progress: omegas.last().map_or(0.0, |o| (o - 0.1) / 1.9),
        finished,
        error: error.map(str::to_string),
        notes: Vec::new(),
    })
}

/// The bands arrive from the sweep's shard-0 worker and are kept for
/// the view; another job's bands are ignored.
#[test]
fn instability_bands_come_from_the_current_sweep() {
    let (mut c, _) = Controller::new("", 0.0);
    ready(&mut c);
    let id = c.main.status(JobKind::Bif).id;
    let msg = |id, bands: Vec<(f64, f64)>| {
        encode(&FromWorker::Bands {
            id,
            bands,
            error: None,
        })
    };
    c.worker_message(0, &msg(id + 100, vec![(0.2, 0.3)]), 1.0);
    assert!(c.instability_bands().is_empty());
    c.dirty = Dirty::default();
    c.worker_message(0, &msg(id, vec![(0.99, 1.22)]), 2.0);
    assert_eq!(c.instability_bands(), vec![(0.99, 1.22)]);
    assert!(c.dirty.jobs.contains(JobKind::Bif));
    assert_eq!(c.bif_view().unstable_bands, vec![(0.99, 1.22)]);
}

#[test]
fn jobs_queue_until_ready_then_split_over_two_workers() {
    let (mut c, fx) = Controller::new("", 0.0);
    assert!(fx.is_empty(), "nothing may be posted before ready");
    let p = ready(&mut c);
    // Omega on worker 0, the HBM branch on worker 1, bifurcation shards on
    // both; no time-integration overlay by default.
    // Lyapunov chains are shared by both workers too; the shooting
    // branches go to the first, the map's boundaries to the other, so the
    // map's rows to the first.
    assert_eq!(p.iter().filter(|(w, _)| *w == 0).count(), 5);
    assert_eq!(p.iter().filter(|(w, _)| *w == 1).count(), 4);
    assert!(p.iter().any(|(w, m)| *w == c.hbm_worker()
        && matches!(
            m,
            ToWorker::Run {
                job: JobSpec::HarmonicBalance {
                    harmonics: 5,
                    points: 150,
                    stability: true,
                    ..
                },
                ..
            }
        )));
    let shards: Vec<u32> = p
        .iter()
        .filter_map(|(_, m)| match m {
            ToWorker::Run {
                job: JobSpec::Bif { shard, chains, .. },
                ..
            } => {
                assert_eq!(*chains, 2);
                Some(*shard)
            }
            _ => None,
        })
        .collect();
    assert_eq!(shards, vec![0, 1]);
    assert_eq!(c.fr_method(), "harmonic balance, H = 5, exact");
}

#[test]
fn slider_change_restarts_and_stale_replies_are_ignored() {
    let (mut c, _) = Controller::new("", 0.0);
    ready(&mut c);
    let old = c.main.status(JobKind::HarmonicBalance).id;
    let fx = c.set_key("backlash_um", "150", 10.0).unwrap();
    // Omega, branch, two bifurcation and two Lyapunov shards, the shooting
    // branches; the map over backlash does not depend on the backlash, so
    // it goes on.
    assert_eq!(posts(&fx).len(), 7);
    assert_ne!(c.main.status(JobKind::HarmonicBalance).id, old);
    assert!(c.query().contains("backlash_um=150"));
    c.worker_message(1, &hbm_points(old, &[0.1], false, None), 11.0);
    assert!(c.main.hbm.points.is_empty());
    // Out of range: refused in a sentence naming the setting and its range; nothing restarts.
    let e = c
        .set_key("backlash_um", "5000", 12.0)
        .unwrap_err()
        .to_string();
    assert_eq!(e, "Backlash must be between 0 and 1000 µm (not 5000).");
    // The selected Omega restarts only the Omega job.
    let fx = c.select_omega(1.23456, 13.0);
    let p = posts(&fx);
    assert_eq!(p.len(), 1);
    assert!(
        matches!(&p[0].1, ToWorker::Run { job: JobSpec::Omega(OmegaSpec { omega, .. }), .. } if (*omega - 1.2346).abs() < 1e-12)
    );
    assert!(c.query().contains("omega=1.2346"));
    // The harmonics restart only the branch, on its worker, and the map's
    // boundaries, traced at the same harmonics.
    let p = posts(&c.set_key("harmonics", "3", 14.0).unwrap());
    assert_eq!(p.len(), 2);
    assert!(p.iter().any(|(w, m)| *w == c.hbm_worker()
        && matches!(
            m,
            ToWorker::Run {
                job: JobSpec::HarmonicBalance { harmonics: 3, .. },
                ..
            }
        )));
    assert!(p.iter().any(|(_, m)| matches!(
        m,
        ToWorker::Run {
            job: JobSpec::Boundaries { harmonics: 3, .. },
            ..
        }
    )));
    assert!(c.set_key("harmonics", "16", 15.0).is_err());
}

/// Runs the Omega jobs among `p` on a real worker core and feeds the
/// replies back to the controller.
fn run_omega_jobs(c: &mut Controller, p: &[(usize, ToWorker)], now_ms: f64) {
    for (w, m) in p {
        if matches!(
            m,
            ToWorker::Run {
                job: JobSpec::Omega(OmegaSpec { .. }),
                ..
            }
        ) {
            let mut core = worker::WorkerCore::new();
            core.handle(&encode(m));
            while core.has_work() {
                for reply in core.step() {
                    c.worker_message(*w, &encode(&reply), now_ms);
                }
            }
        }
    }
}

#[test]
fn a_slider_change_previews_the_selected_omega_from_the_last_end_state() {
    let (mut c, _) = Controller::new("transient_periods=40&record_periods=10", 0.0);
    let p = ready(&mut c);
    // No previous state: no preview, the views wait for the worker.
    assert!(c.main.omega.is_none() && c.main.status(JobKind::Omega).preview_ms.is_none());
    run_omega_jobs(&mut c, &p, 5.0);
    let full = c.main.omega.clone().expect("the worker's result");
    assert!(!full.preview && !full.cli_json.is_empty());
    assert_eq!(
        full.end_state.len(),
        2 * c.model.as_ref().unwrap().system.dof()
    );

    let p = posts(&c.set_key("backlash_um", "150", 10.0).unwrap());
    // The preview shows at once, under the new backlash, while the
    // worker's job runs; it is bounded and carries no CLI JSON.
    let pre = c.main.omega.clone().expect("a preview");
    assert!(pre.preview && pre.cli_json.is_empty());
    assert_eq!(c.main.status(JobKind::Omega).preview_ms, Some(10.0));
    assert!(c.main.status(JobKind::Omega).running());
    assert_eq!(pre.backlash_um, 150.0);
    assert_eq!(
        pre.record_periods,
        worker::jobs::omega::PREVIEW_RUN.record_periods
    );
    // Bounded: its transient, plus its window where shooting from the
    // window's end confirmed an orbit (the window then counts as transient).
    let bound = worker::jobs::omega::PREVIEW_RUN;
    assert!(pre.transient_periods_run <= bound.transient_periods + bound.record_periods);
    assert!(figures::views::omega::summary_line(&pre, &[]).starts_with("Preview ("));
    // The full run (from the static state, as the CLI starts) replaces it.
    run_omega_jobs(&mut c, &p, 20.0);
    let after = c.main.omega.clone().unwrap();
    assert!(!after.preview && after.backlash_um == 150.0);
    assert!(!c.main.status(JobKind::Omega).running());
    // A preview that cannot start (a model with other coordinates) is
    // skipped: the last result stays until the worker answers.
    c.main.omega.as_mut().unwrap().end_state.pop();
    c.set_key("backlash_um", "120", 30.0).unwrap();
    assert!(!c.main.omega.as_ref().unwrap().preview);
}

#[test]
fn progress_shows_only_for_long_jobs() {
    let (mut c, _) = Controller::new("fr_points=4", 0.0);
    ready(&mut c);
    assert_eq!(
        c.main.status(JobKind::HarmonicBalance).progress(100.0),
        None
    );
    assert_eq!(
        c.main.status(JobKind::HarmonicBalance).progress(300.0),
        Some((0, 100))
    );
    let id = c.main.status(JobKind::HarmonicBalance).id;
    c.worker_message(1, &hbm_points(id, &[0.1, 1.05], false, None), 350.0);
    assert_eq!(
        c.main.status(JobKind::HarmonicBalance).progress(360.0),
        Some((50, 100))
    );
    c.worker_message(1, &hbm_points(id, &[2.0], true, None), 400.0);
    assert_eq!(
        c.main.status(JobKind::HarmonicBalance).finished_ms,
        Some(400.0)
    );
    assert_eq!(
        c.main.status(JobKind::HarmonicBalance).progress(500.0),
        None
    );
    assert!(c.main.hbm.is_complete());
    // The complete branch is kept, faded, while the next one computes.
    c.set_key("harmonics", "3", 600.0).unwrap();
    let v = c.fr_view();
    assert_eq!(v.branches.len(), 2);
    assert!(v.branches[0].faded && v.branches[0].points.len() == 3);
}

#[test]
fn a_solver_failure_ends_the_branch_as_partial_and_is_reported() {
    let (mut c, _) = Controller::new("", 0.0);
    ready(&mut c);
    let id = c.main.status(JobKind::HarmonicBalance).id;
    c.worker_message(1, &hbm_points(id, &[0.1, 0.5], false, None), 10.0);
    c.worker_message(
        1,
        &hbm_points(id, &[], true, Some("Newton did not converge")),
        20.0,
    );
    assert!(!c.main.status(JobKind::HarmonicBalance).running());
    let e = c
        .main
        .status(JobKind::HarmonicBalance)
        .error
        .clone()
        .unwrap();
    assert!(e.contains("Ω 0.5:") && e.contains("partial"), "{e}");
    assert!(c.issues.contains(&e));
    let v = c.fr_view();
    assert_eq!(v.branches.last().unwrap().points.len(), 2);
    assert!(v.branches.last().unwrap().label.contains("partial"));
    assert_eq!(v.branch_error.as_ref().map(|b| b.0), Some(0.5));
    let s: serde_json::Value = c.status(30.0);
    assert_eq!(s["fr_partial"], "Newton did not converge");
    // A new branch clears the old branch's failure message.
    c.set_key("harmonics", "3", 40.0).unwrap();
    assert!(c.issues.is_empty());
}

#[test]
fn the_time_integration_overlay_runs_on_both_workers_when_asked() {
    let (mut c, _) = Controller::new("fr_ti_points=4", 0.0);
    let p = ready(&mut c);
    let ti: Vec<usize> = p
        .iter()
        .filter(|(_, m)| {
            matches!(
                m,
                ToWorker::Run {
                    job: JobSpec::Overlay { points: 4, .. },
                    ..
                }
            )
        })
        .map(|(w, _)| *w)
        .collect();
    assert_eq!(ti, vec![0, 1]);
    let id = c.main.status(JobKind::Overlay).id;
    let pts = (0..4)
        .map(|i| FrSample {
            index: i,
            omega: 0.1 * f64::from(i + 1),
            meshes: vec![],
            period: None,
            error: Some("x".into()),
        })
        .collect();
    c.worker_message(
        1,
        &encode(&FromWorker::OverlayPoints { id, points: pts }),
        400.0,
    );
    assert_eq!(c.main.status(JobKind::Overlay).finished_ms, Some(400.0));
    assert_eq!(c.fr_view().failed.len(), 4);
    // Switching it off cancels it on both workers.
    let p = posts(&c.set_key("fr_ti_points", "0", 500.0).unwrap());
    assert_eq!(p.len(), 2);
    assert!(p.iter().all(|(_, m)| matches!(
        m,
        ToWorker::Cancel {
            kind: Some(JobKind::Overlay),
            ..
        }
    )));
    assert!(c.fr_view().overlay_source.is_none());
}

/// Truth by default: with no overlay job (the defaults), the frequency
/// response's dots are the bifurcation sweep's upward steady states, and
/// each arriving sweep point marks the frequency response for a redraw.
#[test]
fn at_the_defaults_the_frequency_response_shows_the_sweeps_steady_states() {
    use figures::protocol::{BifMesh, BifSample, Regime};
    let (mut c, _) = Controller::new("", 0.0);
    ready(&mut c);
    assert_eq!(
        c.main.status(JobKind::Overlay).id,
        0,
        "no overlay job at the defaults"
    );
    let id = c.main.status(JobKind::Bif).id;
    let sample = |index: u32, omega: f64, up: bool, lo: f64, hi: f64| BifSample {
        index,
        omega,
        up,
        meshes: vec![BifMesh {
            x_um: vec![lo],
            rel_min_um: lo,
            rel_max_um: hi,
            regime: Regime::SingleSided,
            dynamic_factor: None,
        }],
        worst_mesh: 0,
        period: None,
        motion: Default::default(),
        error: None,
    };
    c.dirty.jobs = KindSet::NONE;
    let points = vec![
        sample(1, 1.0, true, 2.0, 9.0),
        sample(0, 0.5, true, 10.0, 70.0),
        sample(0, 0.5, false, 0.0, 5.0),
    ];
    c.main.bif.total = 3;
    c.worker_message(0, &encode(&FromWorker::BifPoints { id, points }), 10.0);
    assert!(
        c.dirty.jobs.contains(JobKind::Overlay),
        "the sweep's last point redraws the frequency response"
    );
    let v = c.fr_view();
    assert!(
        matches!(v.overlay_source, Some(FrSource::Sweep { .. })),
        "{:?}",
        v.overlay_source
    );
    let got: Vec<(f64, f64, f64)> = v
        .overlay
        .iter()
        .map(|p| (p.omega, p.min_um, p.max_um))
        .collect();
    assert_eq!(got, vec![(0.5, 10.0, 70.0), (1.0, 2.0, 9.0)]);
    // An overlay job of its own replaces them.
    c.set_key("fr_ti_points", "4", 20.0).unwrap();
    assert!(matches!(
        c.fr_view().overlay_source,
        Some(FrSource::TimeIntegration { .. })
    ));
}

/// The tour's step sets its state and rides in the link; ending it takes
/// it out; a link with a step starts the tour there.
#[test]
fn the_tour_sets_each_steps_state_and_its_step_is_in_the_link() {
    let (mut c, _) = Controller::new("", 0.0);
    ready(&mut c);
    let fx = c.tour_go(Some(3), 10.0);
    assert_eq!(c.settings.view.omega, 1.2);
    assert!(!posts(&fx).is_empty(), "the new Ω starts its run");
    assert!(c.query().ends_with("&tour=4"), "{}", c.query());
    // A step whose state is already there restarts nothing.
    assert!(c.tour_go(Some(3), 15.0).is_empty());
    // The backlash step moves the backlash itself.
    assert!(!posts(&c.tour_go(Some(1), 20.0)).is_empty());
    assert!(c.query().contains("backlash_um=150"), "{}", c.query());
    assert!(c.query().ends_with("&tour=2"));
    c.tour_go(None, 30.0);
    assert!(!c.query().contains("tour="));
    let (d, _) = Controller::new("omega=0.5&tour=5", 0.0);
    assert_eq!(d.tour, Some(4));
    assert!(d.issues.is_empty(), "{:?}", d.issues);
    assert_eq!(d.settings.view.omega, 0.5);
}

fn map_cells(id: JobId, cells: &[(u32, u32, figures::protocol::Regime, Option<u32>)]) -> String {
    encode(&FromWorker::MapCells {
        id,
        cells: cells
            .iter()
            .map(
                |&(row, column, regime, period)| figures::protocol::MapSample {
                    row,
                    column,
                    omega: 0.0,
                    value: 0.0,
                    regime,
                    period,
                    error: None,
                },
            )
            .collect(),
    })
}

#[test]
fn the_map_shards_rows_and_a_cell_click_sets_both_parameters() {
    use figures::protocol::Regime;
    // Without the shooting branches and the boundaries, whose workers the
    // rows leave free.
    let (mut c, _) = Controller::new(
        "map_omega_points=20&map_value_points=4&map_from=40&map_to=160&branches=off&boundaries=off",
        0.0,
    );
    let p = ready(&mut c);
    let shards: Vec<(usize, u32, u32)> = p
        .iter()
        .filter_map(|(w, m)| match m {
            ToWorker::Run {
                job:
                    JobSpec::Map {
                        shard,
                        shards,
                        omega_points: 20,
                        value_points: 4,
                        ..
                    },
                ..
            } => Some((*w, *shard, *shards)),
            _ => None,
        })
        .collect();
    assert_eq!(shards, vec![(0, 0, 2), (1, 1, 2)]);
    let id = c.main.status(JobKind::Map).id;
    c.worker_message(
        0,
        &map_cells(id, &[(0, 0, Regime::NoImpact, Some(1))]),
        10.0,
    );
    c.worker_message(
        1,
        &map_cells(id, &[(1, 0, Regime::DoubleSided, Some(2))]),
        11.0,
    );
    assert_eq!(c.main.status(JobKind::Map).done, 2);
    assert_eq!(c.main.map.counts().0, [0, 1, 0, 1, 0]);
    // Row 2 is 120 um, column 10 is Omega = 0.1 + 10 * 1.9 / 19 = 1.1.
    let fx = c.pick_map_point(1.1 + 0.02, 120.0 - 5.0, 20.0).unwrap();
    assert!(c.query().contains("backlash_um=120"), "{}", c.query());
    assert_eq!(c.settings.view.omega, 1.1);
    assert!(c.query().contains("omega=1.1&"), "{}", c.query());
    // The map goes on (same signature), everything else restarts.
    assert_eq!(c.main.status(JobKind::Map).id, id);
    assert!(!posts(&fx).iter().any(|(_, m)| matches!(
        m,
        ToWorker::Run {
            job: JobSpec::Map { .. },
            ..
        }
    )));
    assert_eq!(c.main.status(JobKind::Map).done, 2);
    assert!(c.pick_map_point(5.0, 100.0, 21.0).is_err());
    // On the TE axis, with its own default range, a click sets te_um.
    c.set_key("map_key", "te_um", 30.0).unwrap();
    assert_eq!(
        (c.settings.view.map_from, c.settings.view.map_to),
        (0.0, 60.0)
    );
    assert_ne!(c.main.status(JobKind::Map).id, id);
    c.set_key("map_value_points", "7", 31.0).unwrap();
    c.pick_map_point(0.1, 30.0, 32.0).unwrap();
    assert!(c.query().contains("te_um=30"), "{}", c.query());
    assert_eq!(c.settings.view.omega, 0.1);
    // Another parameter changes the map's model: it restarts.
    let before = c.main.status(JobKind::Map).id;
    c.set_key("damping_ratio", "0.05", 40.0).unwrap();
    assert_ne!(c.main.status(JobKind::Map).id, before);
}

#[test]
fn the_lyapunov_curve_collects_both_chains_and_can_be_switched_off() {
    let (mut c, _) = Controller::new("lyap_points=4", 0.0);
    let p = ready(&mut c);
    assert_eq!(
        p.iter()
            .filter(|(_, m)| matches!(
                m,
                ToWorker::Run {
                    job: JobSpec::Lyap {
                        points: 4,
                        chains: 2,
                        ..
                    },
                    ..
                }
            ))
            .count(),
        2
    );
    let id = c.main.status(JobKind::Lyap).id;
    let pts = |idx: &[u32]| {
        encode(&FromWorker::LyapPoints {
            id,
            points: idx
                .iter()
                .map(|&i| figures::protocol::LyapSample {
                    index: i,
                    omega: 0.1 + f64::from(i),
                    per_period: Some(-0.1 * f64::from(i)),
                    per_s: Some(-1.0),
                    error: None,
                })
                .collect(),
        })
    };
    c.worker_message(1, &pts(&[1, 3]), 5.0);
    c.worker_message(0, &pts(&[0, 2]), 6.0);
    assert_eq!(c.main.status(JobKind::Lyap).finished_ms, Some(6.0));
    let curve = c.main.lyap.curve();
    assert_eq!(curve.len(), 4);
    assert!(curve.windows(2).all(|w| w[0].0 < w[1].0));
    let p = posts(&c.set_key("lyap_points", "0", 7.0).unwrap());
    assert!(p.iter().all(|(_, m)| matches!(
        m,
        ToWorker::Cancel {
            kind: Some(JobKind::Lyap),
            ..
        }
    )));
    assert_eq!(c.main.status(JobKind::Lyap).id, 0);
}

#[test]
fn a_link_with_a_pinned_state_computes_both_and_pinning_keeps_a() {
    let (mut c, _) = Controller::new("backlash_um=150&a=backlash_um%3D100%26omega%3D0.5", 0.0);
    assert!(c.issues.is_empty(), "{:?}", c.issues);
    let p = ready(&mut c);
    let pinned: Vec<(usize, JobKind)> = p
        .iter()
        .filter_map(|(w, m)| match m {
            ToWorker::Run {
                target: Target::A,
                job,
                params,
                ..
            } => {
                assert_eq!(params["backlash_s1a_um"].as_f64(), Some(100.0));
                Some((*w, job.kind()))
            }
            _ => None,
        })
        .collect();
    assert_eq!(
        pinned,
        vec![
            (0, JobKind::Bif),
            (c.hbm_worker(), JobKind::HarmonicBalance),
            (1, JobKind::Bif)
        ]
    );
    let a_id = c
        .pinned
        .as_ref()
        .unwrap()
        .comp
        .status(JobKind::HarmonicBalance)
        .id;
    c.worker_message(1, &hbm_points(a_id, &[0.1, 1.0, 2.0], true, None), 5.0);
    let a = c.pinned.as_ref().unwrap();
    assert_eq!(a.comp.hbm.points.len(), 3);
    assert!(c.main.hbm.points.is_empty(), "A's points must not reach B");
    let v = c.fr_view();
    let labels: Vec<&str> = v.branches.iter().map(|b| b.label.as_str()).collect();
    assert!(
        labels[0].starts_with("A: backlash 100 µm") && v.branches[0].pinned,
        "{labels:?}"
    );
    assert!(labels[1].starts_with("B: backlash 150 µm"), "{labels:?}");
    assert!(
        c.query().contains("&a=model%3Dravigneaux%26omega%3D0.5%26"),
        "{}",
        c.query()
    );
    assert_eq!(link::decode(&c.query()).pinned.unwrap().view.omega, 0.5);
    // Clear A: the link loses it, and A's jobs are cancelled on every worker.
    let fx = posts(&c.clear_a(6.0));
    assert!(fx.iter().all(|(_, m)| matches!(
        m,
        ToWorker::Cancel {
            target: Target::A,
            ..
        }
    )));
    assert!(c.pinned.is_none() && !c.query().contains("&a="));
}

#[test]
fn pin_as_a_keeps_finished_results_while_b_changes() {
    let (mut c, _) = Controller::new("bif_points=2&bif_dir=up", 0.0);
    ready(&mut c);
    let id = c.main.status(JobKind::HarmonicBalance).id;
    c.worker_message(1, &hbm_points(id, &[0.1, 2.0], true, None), 5.0);
    c.main.status_mut(JobKind::Bif).finished_ms = Some(6.0);
    let fx = c.pin_a(7.0);
    assert!(fx.is_empty(), "finished results are kept, not recomputed");
    c.set_key("backlash_um", "150", 8.0).unwrap();
    let a = c.pinned.as_ref().unwrap();
    assert_eq!(a.comp.hbm.points.len(), 2);
    assert_eq!(
        keys::get(&a.settings.params, "backlash_um"),
        Some(keys::Value::Num(100.0))
    );
    let (ta, tb) = c.ab_labels().unwrap();
    assert_eq!(
        (ta.as_str(), tb.as_str()),
        ("backlash 100 µm", "backlash 150 µm")
    );
    assert!(c.bif_view().ab_labels.is_some());
}

#[test]
fn presets_links_and_model_switch() {
    let (mut c, _) = Controller::new("backlash_um=oops&te_um=25", 0.0);
    assert!(c.issues.iter().any(|i| i.contains("Backlash must be")));
    assert!(c.query().contains("te_um=25"));
    c.apply_preset("pair", 1.0);
    assert!(c.preset_note.is_some());
    assert_eq!(c.mesh_names(), vec!["pg".to_string()]);
    c.set_key("model", "ravigneaux", 2.0).unwrap();
    assert_eq!(c.settings.view.mesh, MeshSel::Named("s1a1".into()));
    assert!(c.set_key("nonsense", "1", 3.0).is_err());
    assert!(c.cli_commands().contains("--mesh s1a1"));
    let cli = c.cli_commands();
    assert!(
        cli.starts_with("gearshock frf --params gearshock-params.json --omega-from ")
            && cli
                .lines()
                .next()
                .unwrap()
                .ends_with("--points 150 --harmonics 5 --mesh s1a1"),
        "{cli}"
    );
    let _ = c.fr_view();
    let _ = c.bif_view();
    let s: serde_json::Value = c.status(5.0);
    assert!(s["query"].as_str().unwrap().starts_with("model=ravigneaux"));
}

/// The messages box shows eight messages, counts the rest, and says how to
/// dismiss them; cleared, it is empty.
#[test]
fn the_messages_box_shows_eight_and_counts_the_rest() {
    let (mut c, _) = Controller::new("", 0.0);
    assert_eq!(c.messages_text(), "");
    c.issues = (1..=10).map(|i| format!("m{i}")).collect();
    let text = c.messages_text();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[..8], ["m1", "m2", "m3", "m4", "m5", "m6", "m7", "m8"]);
    assert_eq!(lines[8..], ["… and 2 more", "(click to dismiss)"]);
    c.clear_issues();
    assert_eq!(c.messages_text(), "");
}

/// A view with nothing to plot says why: computing, switched off, or its
/// job's failure (only while it has no data); with data it plots.
#[test]
fn views_without_data_say_why() {
    use figures::views::ViewId;
    let (mut c, _) = Controller::new("lyap_points=0", 0.0);
    ready(&mut c);
    let omega = c.settings.view.omega;
    assert_eq!(
        c.placeholder(ViewId::Phase),
        Some(format!(
            "Computing the steady state at Ω = {omega} in a Web Worker…"
        ))
    );
    assert!(c.placeholder(ViewId::Lyap).unwrap().starts_with("Off:"));
    assert_eq!(c.placeholder(ViewId::Bif), None, "a running sweep plots");
    let failed = |id| {
        encode(&FromWorker::Failed {
            id,
            message: "no luck".into(),
        })
    };
    c.worker_message(0, &failed(c.main.status(JobKind::Bif).id), 5.0);
    assert_eq!(
        c.placeholder(ViewId::Bif),
        Some("Not computed: no luck".into())
    );
    c.worker_message(0, &failed(c.main.status(JobKind::Omega).id), 6.0);
    for v in [
        ViewId::Phase,
        ViewId::Poincare,
        ViewId::Time,
        ViewId::Spectrum,
    ] {
        assert_eq!(c.placeholder(v), Some("Not computed: no luck".into()));
    }
    assert_eq!(c.placeholder(ViewId::Fr), None, "the branch still computes");
}

/// A job's failure is in the messages while that job's state is on
/// screen: a new job of its kind takes it back, and a replaced job's late
/// failure never joins them.
#[test]
fn a_failure_leaves_the_messages_with_its_job() {
    let (mut c, _) = Controller::new("", 0.0);
    ready(&mut c);
    let failed = |id, message: &str| {
        encode(&FromWorker::Failed {
            id,
            message: message.into(),
        })
    };
    let old = c.main.status(JobKind::Omega).id;
    c.worker_message(0, &failed(old, "The steady state could not be found."), 5.0);
    assert_eq!(c.issues, ["The steady state could not be found."]);
    // A new Omega: a new job, the old failure gone.
    c.select_omega(0.5, 6.0);
    assert!(c.issues.is_empty(), "{:?}", c.issues);
    // The replaced job's failure arriving late is not the state's.
    c.worker_message(0, &failed(old, "late"), 7.0);
    assert!(c.issues.is_empty(), "{:?}", c.issues);
    // The harmonic balance's partial branch, likewise.
    let hbm = c.main.status(JobKind::HarmonicBalance).id;
    c.worker_message(
        1,
        &encode(&FromWorker::HbmPoints {
            id: hbm,
            points: Vec::new(),
            progress: 0.0,
            finished: true,
            error: Some("it failed.".into()),
            notes: Vec::new(),
        }),
        8.0,
    );
    assert_eq!(c.issues.len(), 1, "{:?}", c.issues);
    assert!(c.set_key("backlash_um", "80", 9.0).is_ok());
    assert!(c.issues.is_empty(), "{:?}", c.issues);
}

mod hold;
mod pool;
mod redraw;
