//! A curve traced both ways from its start: the points in order along the
//! curve, how each end came about, the stable side of every point and the
//! cusps where a fold curve's quadratic coefficient changes sign.

use super::systems::System;
use super::trace::{Stepped, Traced, Tracer};
use super::{BoundaryTrace, Curve, CurveKind, CurvePoint, Cusp, Running, Side};

/// A start within this distance (in units of the box) of a curve of its
/// kind already traced lies on it.
const SAME_CURVE: f64 = 1e-3;

impl BoundaryTrace {
    /// Corrects the next start and begins its curve, unless it lies on one
    /// already traced.
    pub(super) fn begin_next_curve(&mut self) {
        let Some(start) = self.starts.get(self.next_start).cloned() else {
            return;
        };
        self.next_start += 1;
        let n = start.z.len();
        let (omega, p) = (start.z[n - 2], start.z[n - 1]);
        if self.on_traced_curve(start.kind, start.mesh, omega, p) {
            return;
        }
        let system = match (start.kind, start.channel) {
            (CurveKind::Fold, _) => System::fold(&mut self.fam, &start.z[..n - 2], omega, p),
            (CurveKind::PeriodDoubling, _) => {
                System::doubling(&mut self.fam, &start.z[..n - 2], omega, p)
            }
            (kind, Some(channel)) => Ok(System::Contact { channel, kind }),
            (_, None) => return,
        };
        let m = self.fam.assembly(p).map(|a| a.model.m).unwrap_or(1);
        let bounds = (
            self.spec.omega_from,
            self.spec.omega_to,
            self.spec.value_from,
            self.spec.value_to,
        );
        let ds_max = 1.0 / f64::from(self.spec.points);
        let started = system
            .and_then(|s| Tracer::start(&mut self.fam, s, start.z.clone(), m, bounds, ds_max));
        match started {
            Err(e) => self.notes.push(format!(
                "A {} start at Omega {omega:.4}, {} = {p} was not corrected ({e}); no curve from it.",
                start.kind.name(),
                self.spec.key
            )),
            Ok((tracer, first)) => {
                let z = &first.z;
                let (w, v) = (z[z.len() - 2], z[z.len() - 1]);
                if self.on_traced_curve(start.kind, start.mesh, w, v) {
                    return;
                }
                self.stats.newton_iterations += tracer.newton_iterations;
                self.running = Some(Running {
                    kind: start.kind,
                    mesh: start.mesh,
                    start: (tracer.clone(), first.clone()),
                    tracer,
                    forward: vec![first],
                    backward: Vec::new(),
                    first_end: None,
                });
            }
        }
    }

    /// Whether `(omega, p)` lies on a curve of this kind and mesh.
    fn on_traced_curve(&self, kind: CurveKind, mesh: Option<usize>, omega: f64, p: f64) -> bool {
        let om = self.spec.omega_to - self.spec.omega_from;
        let pr = self.spec.value_to - self.spec.value_from;
        let pt = (omega / om, p / pr);
        let near = |c: &Curve| {
            c.points.windows(2).any(|s| {
                let a = (s[0].omega / om, s[0].value / pr);
                let b = (s[1].omega / om, s[1].value / pr);
                segment_distance(pt, a, b) < SAME_CURVE
            }) || c
                .points
                .iter()
                .any(|q| (q.omega / om - pt.0).hypot(q.value / pr - pt.1) < SAME_CURVE)
        };
        self.curves
            .iter()
            .any(|c| c.kind == kind && c.mesh == mesh && near(c))
    }

    /// Advances the running curve by at most `k` points.
    pub(super) fn advance_curve(&mut self, k: usize) -> usize {
        let Some(mut run) = self.running.take() else {
            return 0;
        };
        let mut done = 0;
        while done < k {
            done += 1;
            let stepped = run.tracer.step(&mut self.fam);
            let list = if run.first_end.is_none() {
                &mut run.forward
            } else {
                &mut run.backward
            };
            match stepped {
                Stepped::Point(p) => list.push(p),
                Stepped::End(end, last) => {
                    list.extend(last);
                    self.stats.newton_iterations += run.tracer.newton_iterations;
                    match run.first_end {
                        None if end != super::TraceEnd::Closed => {
                            run.first_end = Some(end);
                            run.tracer = run.start.0.reversed(&run.start.1);
                        }
                        None => {
                            self.finish(run, end, end);
                            return done;
                        }
                        Some(first) => {
                            self.finish(run, end, first);
                            return done;
                        }
                    }
                }
            }
        }
        self.running = Some(run);
        done
    }

    /// Joins both directions into one curve and reads its cusps.
    fn finish(&mut self, run: Running, back_end: super::TraceEnd, front_end: super::TraceEnd) {
        let mut traced: Vec<Traced> = run.backward.into_iter().rev().collect();
        traced.extend(run.forward);
        // A start on the box's edge is also the other direction's clipped
        // end: keep one of each run of equal points.
        traced.dedup_by(|a, b| a.z[a.z.len() - 2..] == b.z[b.z.len() - 2..]);
        self.stats.curve_points += traced.len() as u64;
        let om = self.spec.omega_to - self.spec.omega_from;
        let pr = self.spec.value_to - self.spec.value_from;
        let points: Vec<CurvePoint> = traced
            .iter()
            .map(|t| {
                let n = t.z.len();
                let (a, b) = (t.side.0 * om, t.side.1 * pr);
                let norm = a.hypot(b).max(1e-300);
                let normal = (a / norm, b / norm);
                CurvePoint {
                    omega: t.z[n - 2],
                    value: t.z[n - 1],
                    stable_side: Side::of(normal),
                    normal,
                    others_stable: t.others_stable,
                }
            })
            .collect();
        let index = self.curves.len();
        if run.kind == CurveKind::Fold {
            for (i, pair) in traced.windows(2).enumerate() {
                let (ka, kb) = (pair[0].cusp, pair[1].cusp);
                if ka != 0.0
                    && kb != 0.0
                    && ka.signum() != kb.signum()
                    && turns_back(&points, i, (om, pr))
                {
                    let s = ka / (ka - kb);
                    let (pa, pb) = (&points[i], &points[i + 1]);
                    self.cusps.push(Cusp {
                        omega: pa.omega + s * (pb.omega - pa.omega),
                        value: pa.value + s * (pb.value - pa.value),
                        curve: index,
                    });
                }
            }
        }
        self.curves.push(Curve {
            kind: run.kind,
            mesh: run.mesh,
            points,
            ends: [back_end, front_end],
        });
    }
}

/// Distance from `p` to the segment `a b`.
fn segment_distance(p: (f64, f64), a: (f64, f64), b: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    let s = if len2 > 0.0 {
        (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p.0 - a.0 - s * dx).hypot(p.1 - a.1 - s * dy)
}

/// Whether the curve's projection on the plane (in units of the box,
/// `scale`) turns back between points `i` and `i + 1`, as it does at a
/// cusp: the segments two points before and after point in opposite
/// directions. A sign change of the fold's quadratic coefficient without
/// it (next to a failed end, where the corrector lost the curve) is no cusp.
fn turns_back(points: &[CurvePoint], i: usize, scale: (f64, f64)) -> bool {
    if i < 2 || i + 3 >= points.len() {
        return false;
    }
    let dir = |a: &CurvePoint, b: &CurvePoint| {
        ((b.omega - a.omega) / scale.0, (b.value - a.value) / scale.1)
    };
    let before = dir(&points[i - 2], &points[i]);
    let after = dir(&points[i + 1], &points[i + 3]);
    before.0 * after.0 + before.1 * after.1 < 0.0
}
