//! The shooting branches of the bifurcation diagram (their own job):
//! the store of the continuation's points, and the lines the diagram draws
//! from them, stable solid and unstable thin, one line per Poincaré sample
//! of a period-n orbit (n lines on a period-n branch), as continuation
//! tools draw their diagrams.

use super::fr::FrMarkerKind;
use crate::protocol::OrbitSample;

/// The continuation's points as they arrive, for one job.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct OrbitStore {
    /// Points in continuation order.
    pub points: Vec<OrbitSample>,
    /// Every branch has ended.
    pub finished: bool,
    /// The failure that ended the continuation, if any.
    pub error: Option<String>,
}

/// One drawn stretch of a branch: consecutive points of one branch, one
/// sample index, one stability.
#[derive(Debug, Clone, PartialEq)]
pub struct OrbitLine {
    /// Period of the branch's orbits (mesh periods).
    pub period: u32,
    /// Stable (solid) or unstable (thin).
    pub stable: bool,
    /// `(omega, x_um)` along the stretch.
    pub points: Vec<(f64, f64)>,
}

/// A bifurcation located on a branch, where the diagram marks it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrbitMarker {
    /// Dimensionless frequency.
    pub omega: f64,
    /// Its first Poincaré sample of x (µm).
    pub x_um: f64,
    /// What it is.
    pub kind: FrMarkerKind,
}

impl OrbitStore {
    /// The lines of mesh `mesh`: each branch (piece) cut where its
    /// stability changes, one line per sample index; a stretch shares its
    /// end point with the next, so the branch is drawn unbroken.
    pub fn lines(&self, mesh: usize) -> Vec<OrbitLine> {
        let mut out: Vec<OrbitLine> = Vec::new();
        let mut open: Vec<usize> = Vec::new();
        let mut last: Option<&OrbitSample> = None;
        for p in &self.points {
            let Some(xs) = p.x_um.get(mesh) else { continue };
            let stable = p.stable == Some(true);
            let same = last.is_some_and(|l| {
                l.piece == p.piece
                    && l.period == p.period
                    && l.x_um.get(mesh).map(Vec::len) == Some(xs.len())
            });
            if same && out[open[0]].stable == stable {
                for (k, &x) in xs.iter().enumerate() {
                    out[open[k]].points.push((p.omega, x));
                }
            } else {
                let joined = last.filter(|_| same).and_then(|l| l.x_um.get(mesh));
                open = (0..xs.len())
                    .map(|k| {
                        let mut points = Vec::new();
                        if let Some(prev) = joined {
                            points.push((last.map_or(p.omega, |l| l.omega), prev[k]));
                        }
                        points.push((p.omega, xs[k]));
                        out.push(OrbitLine {
                            period: p.period,
                            stable,
                            points,
                        });
                        out.len() - 1
                    })
                    .collect();
            }
            last = Some(p);
        }
        out
    }

    /// The bifurcations located on the branches, on mesh `mesh`.
    pub fn markers(&self, mesh: usize) -> Vec<OrbitMarker> {
        self.points
            .iter()
            .filter_map(|p| {
                let kind: FrMarkerKind = p.bifurcation?.into();
                let x_um = *p.x_um.get(mesh)?.first()?;
                Some(OrbitMarker {
                    omega: p.omega,
                    x_um,
                    kind,
                })
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::protocol::BranchBif;

    fn sample(omega: f64, period: u32, stable: bool, piece: u32) -> OrbitSample {
        OrbitSample {
            omega,
            period,
            stable: Some(stable),
            bifurcation: None,
            piece,
            x_um: vec![(0..period).map(|k| omega + f64::from(k)).collect()],
        }
    }

    /// Stretches follow stability and branches, a period-2 branch draws
    /// two lines, and a change of stability leaves no gap.
    #[test]
    fn lines_follow_stability_and_branches() {
        let mut st = OrbitStore {
            points: vec![
                sample(0.1, 1, true, 0),
                sample(0.2, 1, true, 0),
                sample(0.3, 1, false, 0),
                sample(0.4, 1, false, 0),
                sample(0.35, 2, true, 1),
                sample(0.45, 2, true, 1),
            ],
            ..OrbitStore::default()
        };
        st.points[2].bifurcation = Some(BranchBif::PeriodDoubling);
        let lines = st.lines(0);
        assert_eq!(lines.len(), 4, "{lines:?}");
        assert!(lines[0].stable && lines[0].points.len() == 2);
        // The unstable stretch starts where the stable one ended.
        assert!(!lines[1].stable);
        assert_eq!(lines[1].points, vec![(0.2, 0.2), (0.3, 0.3), (0.4, 0.4)]);
        // The period-2 branch: two lines, one per Poincaré sample.
        assert!(lines[2..].iter().all(|l| l.period == 2 && l.stable));
        assert_eq!(lines[3].points, vec![(0.35, 1.35), (0.45, 1.45)]);
        let m = st.markers(0);
        assert_eq!(m.len(), 1);
        assert_eq!(m[0].kind, FrMarkerKind::PeriodDoubling);
        assert!(st.lines(3).is_empty());
    }
}
