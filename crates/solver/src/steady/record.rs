//! The recorded window of a steady run: per-mesh extremes (exact, from the
//! dense output), mean and RMS, contact shares, Poincaré samples and time
//! histories, accumulated step by step and turned into [`MeshSteady`]s.

use super::{poincare_point, Impact, MeshHistory, MeshSteady, Model, SteadyOptions};
use crate::dynamics::{MeshInstant, MeshOde};
use crate::fastmath::{max, min};
use crate::ode::{Dopri5, StepInfo};

/// Accumulates the recorded window.
#[derive(Debug, Clone)]
pub(super) struct Recorder {
    clock: SampleClock,
    /// The mesh states at the last step's start and end.
    prev: Vec<MeshInstant>,
    cur: Vec<MeshInstant>,
    /// Each mesh's extremes, sums and Poincaré samples.
    meshes: Vec<MeshWindow>,
    n_samples: u64,
    /// The Poincaré points in mesh space, one per period.
    pc_points: Vec<Vec<f64>>,
    history_meshes: Vec<usize>,
    histories: Vec<MeshHistory>,
    times: Vec<f64>,
    /// Scratch state for the dense output.
    ybuf: Vec<f64>,
}

/// When the recorded window is sampled: `samples_per_period` evenly spaced
/// samples per period from `t_rec`, `total_samples` in all.
#[derive(Debug, Clone, Copy)]
struct SampleClock {
    t_rec: f64,
    period: f64,
    samples_per_period: u32,
    total_samples: u64,
    next_sample: u64,
}

/// One mesh's share of the window: exact extremes of the deflection
/// `delta`, of `x = delta - e` and of the force; the sums of the samples;
/// the sample counts in drive contact, apart and in back contact; the Poincaré
/// samples.
#[derive(Debug, Clone)]
struct MeshWindow {
    d_min: f64,
    d_max: f64,
    x_min: f64,
    x_max: f64,
    f_min: f64,
    f_max: f64,
    sum: f64,
    sum_sq: f64,
    contact: [u64; 3],
    pc_delta: Vec<f64>,
    pc_vel: Vec<f64>,
    pc_x: Vec<f64>,
    pc_xv: Vec<f64>,
}

impl MeshWindow {
    fn new(m: &MeshInstant) -> Self {
        MeshWindow {
            d_min: m.delta,
            d_max: m.delta,
            x_min: m.rel,
            x_max: m.rel,
            f_min: m.force,
            f_max: m.force,
            sum: 0.0,
            sum_sq: 0.0,
            contact: [0; 3],
            pc_delta: Vec::new(),
            pc_vel: Vec::new(),
            pc_x: Vec::new(),
            pc_xv: Vec::new(),
        }
    }
}

impl Recorder {
    pub(super) fn new(
        model: &Model,
        ode: &MeshOde,
        opts: &SteadyOptions,
        t_rec: f64,
        period: f64,
        y: &[f64],
    ) -> Self {
        let n_mesh = model.system.meshes.len();
        let history_meshes: Vec<usize> = opts
            .history_meshes
            .iter()
            .copied()
            .filter(|&j| j < n_mesh)
            .collect();
        let mut cur = Vec::with_capacity(n_mesh);
        ode.mesh_instants(t_rec, y, &mut cur);
        let total = if opts.samples_per_period > 0 {
            u64::from(opts.samples_per_period) * u64::from(opts.record_periods)
        } else {
            0
        };
        let mut r = Recorder {
            clock: SampleClock {
                t_rec,
                period,
                samples_per_period: opts.samples_per_period,
                total_samples: total,
                next_sample: 0,
            },
            prev: cur.clone(),
            meshes: cur.iter().map(MeshWindow::new).collect(),
            cur,
            n_samples: 0,
            pc_points: Vec::new(),
            histories: history_meshes
                .iter()
                .map(|&mesh| MeshHistory {
                    mesh,
                    delta_m: Vec::new(),
                    velocity_m_s: Vec::new(),
                    rel_m: Vec::new(),
                    force_n: Vec::new(),
                })
                .collect(),
            history_meshes,
            times: Vec::new(),
            ybuf: vec![0.0; y.len()],
        };
        if r.clock.total_samples > 0 {
            let inst = r.cur.clone();
            r.sample(ode, t_rec, &inst);
        }
        r
    }

    pub(super) fn sample(&mut self, ode: &MeshOde, t: f64, inst: &[MeshInstant]) {
        for (j, (mi, w)) in inst.iter().zip(&mut self.meshes).enumerate() {
            w.sum += mi.delta;
            w.sum_sq += mi.delta * mi.delta;
            let b = ode.backlash(j);
            let c = if mi.rel > b {
                0
            } else if mi.rel < -b {
                2
            } else {
                1
            };
            w.contact[c] += 1;
            w.f_min = min(w.f_min, mi.force);
            w.f_max = max(w.f_max, mi.force);
        }
        for h in &mut self.histories {
            let mi = inst[h.mesh];
            h.delta_m.push(mi.delta);
            h.velocity_m_s.push(mi.delta_dot);
            h.rel_m.push(mi.rel);
            h.force_n.push(mi.force);
        }
        if !self.history_meshes.is_empty() {
            self.times.push(t);
        }
        self.n_samples += 1;
        self.clock.next_sample += 1;
    }

    pub(super) fn sample_time(&self, k: u64) -> f64 {
        let c = &self.clock;
        c.t_rec + c.period * (k as f64) / f64::from(c.samples_per_period)
    }

    pub(super) fn on_step(&mut self, ode: &MeshOde, int: &Dopri5, info: StepInfo) {
        std::mem::swap(&mut self.prev, &mut self.cur);
        ode.mesh_instants(info.t1, int.y(), &mut self.cur);
        let h = info.t1 - info.t0;
        let mut ybuf = std::mem::take(&mut self.ybuf);
        for (j, w) in self.meshes.iter_mut().enumerate() {
            let (a, b) = (self.prev[j], self.cur[j]);
            w.d_min = min(w.d_min, b.delta);
            w.d_max = max(w.d_max, b.delta);
            w.x_min = min(w.x_min, b.rel);
            w.x_max = max(w.x_max, b.rel);
            w.f_min = min(w.f_min, b.force);
            w.f_max = max(w.f_max, b.force);
            // Interior extremum of delta or of x: the rate changes sign.
            for rel in [false, true] {
                let (v0, v1, r0, r1) = if rel {
                    (a.rel, b.rel, a.rel_dot, b.rel_dot)
                } else {
                    (a.delta, b.delta, a.delta_dot, b.delta_dot)
                };
                if r0 * r1 < 0.0 {
                    if let Some(theta) = hermite_extremum(v0, v1, r0 * h, r1 * h) {
                        let t = info.t0 + theta * h;
                        int.dense_components(t, ode.mesh_components(j), &mut ybuf);
                        let mi = ode.mesh_instant(j, t, &ybuf);
                        let v = if rel { mi.rel } else { mi.delta };
                        let (lo, hi) = if rel {
                            (&mut w.x_min, &mut w.x_max)
                        } else {
                            (&mut w.d_min, &mut w.d_max)
                        };
                        *lo = min(*lo, v);
                        *hi = max(*hi, v);
                        w.f_min = min(w.f_min, mi.force);
                        w.f_max = max(w.f_max, mi.force);
                    }
                }
            }
        }
        let mut inst = Vec::new();
        while self.clock.next_sample < self.clock.total_samples {
            let ts = self.sample_time(self.clock.next_sample);
            if ts > info.t1 {
                break;
            }
            int.dense(ts, &mut ybuf);
            ode.mesh_instants(ts, &ybuf, &mut inst);
            self.sample(ode, ts, &inst);
        }
        self.ybuf = ybuf;
    }

    pub(super) fn on_period(&mut self, ode: &MeshOde, t: f64, y: &[f64], omega_rad_s: f64) {
        for (j, w) in self.meshes.iter_mut().enumerate() {
            let mi = ode.mesh_instant(j, t, y);
            w.pc_delta.push(mi.delta);
            w.pc_vel.push(mi.delta_dot);
            w.pc_x.push(mi.rel);
            w.pc_xv.push(mi.rel_dot);
        }
        self.pc_points.push(poincare_point(ode, t, y, omega_rad_s));
    }

    /// Extends the Poincaré samples of an exact period-`n` orbit, recorded
    /// over at least `n` periods, to `total` by its periodicity: the
    /// samples of the orbit repeat after `n` periods (to the shooting
    /// tolerance, checked on the recorded ones), so the rest of the window
    /// need not be integrated.
    pub(super) fn repeat_poincare(&mut self, n: usize, total: usize) {
        if n == 0 || self.pc_points.len() < n {
            return;
        }
        for w in &mut self.meshes {
            for series in [&mut w.pc_delta, &mut w.pc_vel, &mut w.pc_x, &mut w.pc_xv] {
                while series.len() < total {
                    series.push(series[series.len() - n]);
                }
            }
        }
        while self.pc_points.len() < total {
            self.pc_points
                .push(self.pc_points[self.pc_points.len() - n].clone());
        }
    }

    /// The Poincaré points in mesh space (µm) recorded so far, oldest first.
    pub(super) fn points(&self) -> &[Vec<f64>] {
        &self.pc_points
    }

    /// The largest range of a mesh deflection so far (µm).
    pub(super) fn span_um(&self) -> f64 {
        self.meshes
            .iter()
            .map(|w| w.d_max - w.d_min)
            .fold(0.0, f64::max)
            * 1e6
    }

    pub(super) fn finish(self, model: &Model) -> (Vec<MeshSteady>, Vec<MeshHistory>, Vec<f64>) {
        let ns = self.n_samples as f64;
        let meshes = (self.meshes.into_iter().enumerate())
            .map(|(j, w)| {
                let fs = model.statics.mesh_force_n[j];
                let b = model.system.meshes[j].backlash_m;
                MeshSteady {
                    delta_min_m: w.d_min,
                    delta_max_m: w.d_max,
                    delta_mean_m: if ns > 0.0 { w.sum / ns } else { f64::NAN },
                    delta_rms_m: if ns > 0.0 {
                        (w.sum_sq / ns).sqrt()
                    } else {
                        f64::NAN
                    },
                    rel_min_m: w.x_min,
                    rel_max_m: w.x_max,
                    force_max_n: w.f_max,
                    force_min_n: w.f_min,
                    static_force_n: fs,
                    dynamic_factor: (fs.abs() > 1e-9).then(|| w.f_max / fs),
                    impact: Impact::classify(w.x_min, w.x_max, b),
                    poincare_delta_m: w.pc_delta,
                    poincare_velocity_m_s: w.pc_vel,
                    poincare_x_m: w.pc_x,
                    poincare_x_velocity_m_s: w.pc_xv,
                    contact_fraction: if ns > 0.0 {
                        let c = w.contact;
                        [c[0] as f64 / ns, c[1] as f64 / ns, c[2] as f64 / ns]
                    } else {
                        [0.0; 3]
                    },
                }
            })
            .collect();
        (meshes, self.histories, self.times)
    }
}

/// Position in `(0, 1)` of the extremum of the cubic Hermite model with end
/// values `v0`, `v1` and end slopes `s0`, `s1` (already times `h`) whose slopes
/// have opposite signs: the root of the quadratic `p'` inside the step.
pub(super) fn hermite_extremum(v0: f64, v1: f64, s0: f64, s1: f64) -> Option<f64> {
    let a = 6.0 * (v0 - v1) + 3.0 * (s0 + s1);
    let b = -6.0 * (v0 - v1) - 4.0 * s0 - 2.0 * s1;
    let c = s0;
    let roots = if a.abs() <= 1e-14 * (b.abs() + c.abs()) {
        [-c / b, f64::NAN]
    } else {
        let disc = max(b * b - 4.0 * a * c, 0.0);
        let q = -0.5 * (b + b.signum() * disc.sqrt());
        [q / a, if q != 0.0 { c / q } else { f64::NAN }]
    };
    // p' changes sign on [0, 1], so exactly one root (or three, counted
    // with multiplicity) lies inside; take the one nearest the middle.
    roots
        .into_iter()
        .filter(|t| t.is_finite() && (0.0..=1.0).contains(t))
        .min_by(|x, y| (x - 0.5).abs().total_cmp(&(y - 0.5).abs()))
}
