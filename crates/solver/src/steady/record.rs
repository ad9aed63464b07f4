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
    n_mesh: usize,
    t_rec: f64,
    period: f64,
    samples_per_period: u32,
    total_samples: u64,
    next_sample: u64,
    prev: Vec<MeshInstant>,
    cur: Vec<MeshInstant>,
    d_min: Vec<f64>,
    d_max: Vec<f64>,
    x_min: Vec<f64>,
    x_max: Vec<f64>,
    f_min: Vec<f64>,
    f_max: Vec<f64>,
    sum: Vec<f64>,
    sum_sq: Vec<f64>,
    contact: Vec<[u64; 3]>,
    n_samples: u64,
    pc_delta: Vec<Vec<f64>>,
    pc_vel: Vec<Vec<f64>>,
    pc_x: Vec<Vec<f64>>,
    pc_xv: Vec<Vec<f64>>,
    pc_points: Vec<Vec<f64>>,
    history_meshes: Vec<usize>,
    histories: Vec<MeshHistory>,
    times: Vec<f64>,
    ybuf: Vec<f64>,
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
            n_mesh,
            t_rec,
            period,
            samples_per_period: opts.samples_per_period,
            total_samples: total,
            next_sample: 0,
            prev: cur.clone(),
            d_min: cur.iter().map(|m| m.delta).collect(),
            d_max: cur.iter().map(|m| m.delta).collect(),
            x_min: cur.iter().map(|m| m.rel).collect(),
            x_max: cur.iter().map(|m| m.rel).collect(),
            f_min: cur.iter().map(|m| m.force).collect(),
            f_max: cur.iter().map(|m| m.force).collect(),
            cur,
            sum: vec![0.0; n_mesh],
            sum_sq: vec![0.0; n_mesh],
            contact: vec![[0; 3]; n_mesh],
            n_samples: 0,
            pc_delta: vec![Vec::new(); n_mesh],
            pc_vel: vec![Vec::new(); n_mesh],
            pc_x: vec![Vec::new(); n_mesh],
            pc_xv: vec![Vec::new(); n_mesh],
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
        if r.total_samples > 0 {
            let inst = r.cur.clone();
            r.sample(ode, t_rec, &inst);
        }
        r
    }

    pub(super) fn sample(&mut self, ode: &MeshOde, t: f64, inst: &[MeshInstant]) {
        for (j, mi) in inst.iter().enumerate() {
            self.sum[j] += mi.delta;
            self.sum_sq[j] += mi.delta * mi.delta;
            let b = ode.backlash(j);
            let c = if mi.rel > b {
                0
            } else if mi.rel < -b {
                2
            } else {
                1
            };
            self.contact[j][c] += 1;
            self.f_min[j] = min(self.f_min[j], mi.force);
            self.f_max[j] = max(self.f_max[j], mi.force);
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
        self.next_sample += 1;
    }

    pub(super) fn sample_time(&self, k: u64) -> f64 {
        self.t_rec + self.period * (k as f64) / f64::from(self.samples_per_period)
    }

    pub(super) fn on_step(&mut self, ode: &MeshOde, int: &Dopri5, info: StepInfo) {
        std::mem::swap(&mut self.prev, &mut self.cur);
        ode.mesh_instants(info.t1, int.y(), &mut self.cur);
        let h = info.t1 - info.t0;
        let mut ybuf = std::mem::take(&mut self.ybuf);
        for j in 0..self.n_mesh {
            let (a, b) = (self.prev[j], self.cur[j]);
            self.d_min[j] = min(self.d_min[j], b.delta);
            self.d_max[j] = max(self.d_max[j], b.delta);
            self.x_min[j] = min(self.x_min[j], b.rel);
            self.x_max[j] = max(self.x_max[j], b.rel);
            self.f_min[j] = min(self.f_min[j], b.force);
            self.f_max[j] = max(self.f_max[j], b.force);
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
                            (&mut self.x_min[j], &mut self.x_max[j])
                        } else {
                            (&mut self.d_min[j], &mut self.d_max[j])
                        };
                        *lo = min(*lo, v);
                        *hi = max(*hi, v);
                        self.f_min[j] = min(self.f_min[j], mi.force);
                        self.f_max[j] = max(self.f_max[j], mi.force);
                    }
                }
            }
        }
        let mut inst = Vec::new();
        while self.next_sample < self.total_samples {
            let ts = self.sample_time(self.next_sample);
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
        for j in 0..self.n_mesh {
            let mi = ode.mesh_instant(j, t, y);
            self.pc_delta[j].push(mi.delta);
            self.pc_vel[j].push(mi.delta_dot);
            self.pc_x[j].push(mi.rel);
            self.pc_xv[j].push(mi.rel_dot);
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
        let all = (self.pc_delta.iter_mut())
            .chain(self.pc_vel.iter_mut())
            .chain(self.pc_x.iter_mut())
            .chain(self.pc_xv.iter_mut());
        for series in all {
            while series.len() < total {
                series.push(series[series.len() - n]);
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
        self.d_min
            .iter()
            .zip(&self.d_max)
            .map(|(lo, hi)| hi - lo)
            .fold(0.0, f64::max)
            * 1e6
    }

    pub(super) fn finish(self, model: &Model) -> (Vec<MeshSteady>, Vec<MeshHistory>, Vec<f64>) {
        let ns = self.n_samples as f64;
        let meshes = (0..self.n_mesh)
            .map(|j| {
                let fs = model.statics.mesh_force_n[j];
                let b = model.system.meshes[j].backlash_m;
                MeshSteady {
                    delta_min_m: self.d_min[j],
                    delta_max_m: self.d_max[j],
                    delta_mean_m: if ns > 0.0 { self.sum[j] / ns } else { f64::NAN },
                    delta_rms_m: if ns > 0.0 {
                        (self.sum_sq[j] / ns).sqrt()
                    } else {
                        f64::NAN
                    },
                    rel_min_m: self.x_min[j],
                    rel_max_m: self.x_max[j],
                    force_max_n: self.f_max[j],
                    force_min_n: self.f_min[j],
                    static_force_n: fs,
                    dynamic_factor: (fs.abs() > 1e-9).then(|| self.f_max[j] / fs),
                    impact: Impact::classify(self.x_min[j], self.x_max[j], b),
                    poincare_delta_m: self.pc_delta[j].clone(),
                    poincare_velocity_m_s: self.pc_vel[j].clone(),
                    poincare_x_m: self.pc_x[j].clone(),
                    poincare_x_velocity_m_s: self.pc_xv[j].clone(),
                    contact_fraction: if ns > 0.0 {
                        let c = self.contact[j];
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
