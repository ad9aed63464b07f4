//! The job that paces a view's redraws while a job it draws besides its
//! data's streams points.

use super::super::*;
use super::ready;
use figures::views::ViewId;

/// The bifurcation diagram's own sweep is over while the shooting branches
/// still stream their points: the branches' job paces its redraws (as the
/// sweep's did while it ran); once they end too, its own finished job does.
/// A view that draws one job's data is paced by that job alone.
#[test]
fn the_shooting_branches_pace_the_bifurcation_diagram_after_its_sweep() {
    let (mut c, _) = Controller::new("", 0.0);
    ready(&mut c);
    let bif = c.main.status(JobKind::Bif).id;
    let orbits = c.main.status(JobKind::Orbits).id;
    assert!(
        bif != 0 && orbits != 0 && bif != orbits,
        "both run by default"
    );
    assert_eq!(c.redraw_status(ViewId::Bif).id, bif);
    c.main.status_mut(JobKind::Bif).finished_ms = Some(5.0);
    assert_eq!(c.redraw_status(ViewId::Bif).id, orbits);
    assert!(c.redraw_status(ViewId::Bif).running());
    c.main.status_mut(JobKind::Orbits).finished_ms = Some(9.0);
    assert_eq!(c.redraw_status(ViewId::Bif).id, bif);
    assert!(!c.redraw_status(ViewId::Bif).running());
    let omega = c.main.status(JobKind::Omega).id;
    assert_eq!(c.redraw_status(ViewId::Phase).id, omega);
}
