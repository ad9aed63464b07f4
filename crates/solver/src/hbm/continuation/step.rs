//! One continuation step: tangent predictor, bordered Newton corrector,
//! step control from the curve's geometry, fold location.

use super::*;

impl FrfContinuation {
    /// Weights of the arclength metric: Omega in units of the range, the
    /// coefficients in units of `scale` (RMS over coefficients).
    pub(super) fn metric(&self, i: usize) -> f64 {
        if i == self.n_x() {
            let range = self.spec.omega_to - self.spec.omega_from;
            1.0 / (range * range)
        } else {
            1.0 / (self.cursor.scale * self.cursor.scale * self.n_x() as f64)
        }
    }

    /// Grows the amplitude scale of the metric with the largest response seen
    /// (three times its RMS harmonic coefficient, at least 1 um), so that a
    /// resonance peak costs a bounded number of steps whatever its height.
    pub(super) fn update_scale(&mut self) {
        let m = self.asm.model.m;
        let nx = self.n_x();
        let amp = 3.0 * rms(&self.cursor.y[m..nx]);
        if self.spec.step_control == StepControl::Geometry {
            self.cursor.scale = amp.max(1.0);
            self.normalize_tangent();
        } else if amp > self.cursor.scale {
            self.cursor.scale = amp;
            self.normalize_tangent();
        }
    }

    pub(super) fn normalize_tangent(&mut self) {
        let norm: f64 = (0..self.cursor.tangent.len())
            .map(|i| self.metric(i) * self.cursor.tangent[i] * self.cursor.tangent[i])
            .sum::<f64>()
            .sqrt();
        for t in &mut self.cursor.tangent {
            *t /= norm;
        }
    }

    /// One predictor-corrector step; `None` when the branch has left the range.
    ///
    /// The step length follows the curve's geometry: after a converged
    /// corrector, the distance from the predictor to the solution (`d`, in
    /// the arclength metric) and the angle between the old and new tangents
    /// (`alpha`) give the factor `f` ([`overshoot`]) by which the step
    /// overshot its nominal size. `f > 2` rejects the step
    /// and retries with `ds / f`; otherwise the next step is `ds / f`,
    /// growing by at most 2. The step is also capped so that Omega moves by
    /// at most `range / points`.
    pub(super) fn step(&mut self) -> Result<()> {
        let nx = self.n_x();
        let n = nx + 1;
        let omega_now = self.cursor.y[nx];
        let ds_min = 1e-5 * self.cursor.ds_max;
        let bend = self.bend();
        loop {
            let t_om = self.cursor.tangent[nx];
            let end = match self.piece.dir {
                Direction::Up => self.spec.omega_to,
                Direction::Down => self.spec.omega_from,
            };
            // At most `range / points` in Omega per step.
            let range = self.spec.omega_to - self.spec.omega_from;
            let mut ds = match self.spec.step_control {
                StepControl::Geometry => {
                    let omega_cap = range / f64::from(self.spec.points) / t_om.abs().max(1e-300);
                    self.cursor.ds.min(omega_cap).min(DS_CAP).max(ds_min)
                }
                StepControl::Iterations => self.cursor.ds,
            };
            // Land on the end of the range instead of overshooting it.
            let mut landing = false;
            if t_om != 0.0 {
                let to_end = (end - omega_now) / t_om;
                if to_end > 0.0 && to_end <= ds {
                    ds = to_end;
                    landing = true;
                }
            }
            let pred: Vec<f64> = (0..n)
                .map(|i| self.cursor.y[i] + ds * self.cursor.tangent[i])
                .collect();
            // Newton starts on the parabola through the last two points
            // (tangent at the last); the hyperplane it solves on, and the
            // distance the step control measures, stay the tangent's.
            let guess: Vec<f64> = match &bend {
                Some(c) => pred.iter().zip(c).map(|(p, c)| p + ds * ds * c).collect(),
                None => pred.clone(),
            };
            if landing {
                // The last point sits exactly on the end of the range: a
                // natural-parameter Newton at Omega = end from the guess.
                let mut x = guess[..nx].to_vec();
                let mut stats = self.stats;
                if let Ok(iterations) = newton_fixed(&mut self.asm, &mut x, end, &mut stats) {
                    self.stats = stats;
                    self.cursor.y[..nx].copy_from_slice(&x);
                    self.cursor.y[nx] = end;
                    return self.finish_piece(iterations, None, PieceEnd::Reached);
                }
            }
            match self.correct(&pred, &guess) {
                Ok((y_new, t_new, iterations)) => {
                    let cos: f64 = (0..n)
                        .map(|i| self.metric(i) * t_new[i] * self.cursor.tangent[i])
                        .sum();
                    let alpha = cos.clamp(-1.0, 1.0).acos();
                    let dist = (0..n)
                        .map(|i| self.metric(i) * (y_new[i] - pred[i]).powi(2))
                        .sum::<f64>()
                        .sqrt();
                    let geometry = self.spec.step_control == StepControl::Geometry;
                    if geometry {
                        let f = overshoot(dist, alpha);
                        if f > 2.0 && ds > ds_min {
                            self.stats.rejected_steps += 1;
                            self.cursor.ds = (ds / f.min(4.0)).max(ds_min);
                            continue;
                        }
                        self.cursor.ds = (ds / f).clamp(ds_min, DS_CAP);
                    } else {
                        // StepControl::Iterations: the turn limits the
                        // step, the corrector's iterations adapt it.
                        if cos < 0.9 && ds > ds_min {
                            self.stats.rejected_steps += 1;
                            self.cursor.ds = ds * 0.5;
                            continue;
                        }
                        self.cursor.ds = if iterations <= 2 {
                            (ds * 1.4).min(self.cursor.ds_max)
                        } else if iterations >= 5 {
                            ds * 0.6
                        } else {
                            ds
                        }
                        .max(ds_min);
                    }
                    if t_new[nx].signum() != self.cursor.tangent[nx].signum() && !geometry {
                        self.stability.pending_fold = true;
                    } else if t_new[nx].signum() != self.cursor.tangent[nx].signum() {
                        // A fold between the two points: locate it, and
                        // put it on the branch before the new point.
                        if let Some((y_fold, t_fold, it)) = self.locate_fold(ds, t_new[nx]) {
                            let (y_keep, t_keep) = (
                                std::mem::replace(&mut self.cursor.y, y_fold),
                                std::mem::replace(&mut self.cursor.tangent, t_fold),
                            );
                            let fold_point = self.point(it, Some(Bifurcation::Fold));
                            self.cursor.y = y_keep;
                            self.cursor.tangent = t_keep;
                            self.emit(fold_point)?;
                            if !self.started || self.finished {
                                return Ok(());
                            }
                        } else {
                            self.stability.pending_fold = true;
                        }
                    }
                    self.cursor.prev_y = Some(std::mem::replace(&mut self.cursor.y, y_new));
                    self.cursor.tangent = t_new;
                    self.update_scale();
                    let omega = self.cursor.y[nx];
                    let label = std::mem::take(&mut self.stability.pending_fold)
                        .then_some(Bifurcation::Fold);
                    if omega > self.spec.omega_to + 1e-12 || omega < self.spec.omega_from - 1e-12 {
                        // Left through the end it started from: the branch
                        // turned back at a fold and the rest of the range
                        // was not reached.
                        let at_start = match self.piece.dir {
                            Direction::Up => omega < self.spec.omega_from + 1e-9,
                            Direction::Down => omega > self.spec.omega_to - 1e-9,
                        };
                        let how = if at_start {
                            PieceEnd::TurnedBack
                        } else {
                            PieceEnd::Reached
                        };
                        return self.finish_piece(iterations, label, how);
                    }
                    let p = self.point(iterations, label);
                    return self.emit(p);
                }
                Err(e) => {
                    self.stats.rejected_steps += 1;
                    if ds <= ds_min {
                        return Err(e);
                    }
                    self.cursor.ds = (ds * 0.5).max(ds_min);
                }
            }
        }
    }

    /// Locates a fold between the current point (`self.cursor.y`, tangent
    /// `self.cursor.tangent`) and the solution a step `ds` further: the zero of the
    /// tangent's Omega component along the branch, by the Illinois variant
    /// of regula falsi on the step length, each trial a corrector on the
    /// hyperplane normal to the current tangent. Returns the fold's solution,
    /// tangent and the corrector's iterations; `None` if a corrector failed
    /// (the fold is then labelled on the point after it).
    pub(super) fn locate_fold(
        &mut self,
        ds: f64,
        f_end: f64,
    ) -> Option<(Vec<f64>, Vec<f64>, usize)> {
        let nx = self.n_x();
        let n = nx + 1;
        let (mut a, mut fa) = (0.0, self.cursor.tangent[nx]);
        let (mut b, mut fb) = (ds, f_end);
        if fa.signum() == fb.signum() {
            return None;
        }
        let mut best = None;
        let mut omega_prev = f64::NAN;
        for _ in 0..FOLD_ITERATIONS {
            let s = (a * fb - b * fa) / (fb - fa);
            let pred: Vec<f64> = (0..n)
                .map(|i| self.cursor.y[i] + s * self.cursor.tangent[i])
                .collect();
            let (y, t, it) = self.correct(&pred, &pred).ok()?;
            let fs = t[nx];
            let omega = y[nx];
            let converged = (omega - omega_prev).abs() <= FOLD_TOL * (1.0 + omega.abs());
            omega_prev = omega;
            best = Some((y, t, it));
            if converged || fs == 0.0 {
                break;
            }
            if fs.signum() != fb.signum() {
                (a, fa) = (b, fb);
            } else {
                fa *= 0.5;
            }
            (b, fb) = (s, fs);
        }
        best
    }

    /// The second-order term `c` of the parabola `y + s t + s^2 c` (in the
    /// arclength `s` of the metric) through the last point `y` with its
    /// tangent `t` and the point before it; `None` at a piece's start.
    /// A predictor `pred` a step `ds` along the tangent then starts Newton
    /// at `pred + ds^2 c`, about `ds` times closer to the branch than
    /// `pred` where the branch bends smoothly.
    pub(super) fn bend(&self) -> Option<Vec<f64>> {
        let prev = self.cursor.prev_y.as_ref()?;
        let (y, t) = (&self.cursor.y, &self.cursor.tangent);
        let h2: f64 = (0..y.len())
            .map(|i| self.metric(i) * (y[i] - prev[i]).powi(2))
            .sum();
        let h = h2.sqrt();
        if !(h > 0.0 && h.is_finite()) {
            return None;
        }
        let c: Vec<f64> = (0..y.len())
            .map(|i| (prev[i] - y[i] + h * t[i]) / h2)
            .collect();
        c.iter().all(|v| v.is_finite()).then_some(c)
    }

    /// An `n x n` matrix (its entries unspecified) from the corrector's
    /// pool, or a new one.
    fn pooled_matrix(&mut self, n: usize) -> DMatrix<f64> {
        match self.matrix_pool.pop() {
            Some(m) if m.shape() == (n, n) => m,
            _ => DMatrix::zeros(n, n),
        }
    }

    /// Newton on the bordered system whose arclength row keeps the solution
    /// on the hyperplane through the predictor `pred` normal to the
    /// tangent, started at `guess`; returns the solution, its tangent and
    /// the iterations.
    pub(super) fn correct(
        &mut self,
        pred: &[f64],
        guess: &[f64],
    ) -> Result<(Vec<f64>, Vec<f64>, usize)> {
        let nx = self.n_x();
        let n = nx + 1;
        let mut y = guess.to_vec();
        let mut r = vec![0.0; nx];
        // The bordered Jacobian: the residual's rows from `evaluate`, the
        // arclength row below them. A factorization takes it over, and the
        // one it replaces gives its storage back for the next.
        let mut jac = self.pooled_matrix(n);
        let weighted_t: Vec<f64> = (0..n)
            .map(|i| self.metric(i) * self.cursor.tangent[i])
            .collect();
        let mut res_prev = f64::INFINITY;
        // The last factorization and the size of the step it produced: once
        // a step is below `CHORD_STEP`, the Jacobian moves by less than that
        // and the factorization is kept (a chord step, whose error is the
        // product of the two small steps), and it also gives the tangent.
        let mut lu: Option<crate::dense::Lu> = None;
        let mut step_prev = f64::INFINITY;
        for iteration in 1..=NEWTON_MAX {
            // AFT's residual has small kinks where a contact switch crosses
            // a grid point, on which chord steps can stall: it keeps Newton.
            let chord = lu.is_some() && step_prev <= CHORD_STEP && self.asm.method != Method::Aft;
            if chord {
                self.asm.evaluate(&y[..nx], y[nx], &mut r, None);
            } else {
                self.asm.evaluate(&y[..nx], y[nx], &mut r, Some(&mut jac));
            }
            self.stats.jacobians += 1;
            self.stats.newton_iterations += 1;
            let mut g = DVector::zeros(n);
            for i in 0..nx {
                g[i] = r[i];
            }
            g[nx] = (0..n).map(|i| weighted_t[i] * (y[i] - pred[i])).sum();
            let res = inf_norm(&r);
            if !res.is_finite() {
                break;
            }
            // On a kinked residual Newton can stall, bouncing between two
            // linearizations: a residual at round-off level that no longer
            // falls (where smooth Newton would square it) is a solution as
            // it stands.
            let scale_now = 1.0 + inf_norm(&y[..nx]);
            let at_floor =
                iteration > 2 && res <= RESIDUAL_FLOOR * scale_now && res > 0.1 * res_prev;
            res_prev = res;
            if !chord {
                for i in 0..n {
                    jac[(nx, i)] = weighted_t[i];
                }
                let spare = match lu.take() {
                    Some(old) => old.into_matrix(),
                    None => self.pooled_matrix(n),
                };
                lu = Some(crate::dense::Lu::new(std::mem::replace(&mut jac, spare)));
            }
            let Some(factors) = lu.as_ref() else { break };
            let mut step = 0.0;
            if !at_floor {
                let Some(dy) = factors.solve(&g) else { break };
                for i in 0..n {
                    y[i] -= dy[i];
                }
                let scale = 1.0 + inf_norm(&y[..nx]);
                step = inf_norm(&dy.as_slice()[..nx]).max(dy[nx].abs() * scale) / scale;
            }
            // The error left after this step, from how the last two steps
            // contracted (`theta`; a chord step contracts linearly, Newton
            // faster): `theta / (1 - theta)` times the step bounds it. Within
            // the tolerance, with the residual before the step within its
            // bound too, the iterate is converged without one more
            // evaluation to confirm a step it would find below the tolerance.
            let theta = step / step_prev;
            let contracted = !at_floor
                && step_prev.is_finite()
                && theta < 0.5
                && theta / (1.0 - theta) * step <= NEWTON_TOL
                && res <= 1e-6 * (1.0 + inf_norm(&y[..nx]));
            step_prev = step;
            if at_floor || step <= NEWTON_TOL || contracted {
                let scale = 1.0 + inf_norm(&y[..nx]);
                // The residual before this last (tiny) step is already
                // within the bound: the step only reduces it, and a second
                // evaluation is saved. Otherwise check at the result.
                if !at_floor && res > 1e-6 * scale {
                    self.asm.evaluate(&y[..nx], y[nx], &mut r, None);
                    self.stats.jacobians += 1;
                    if inf_norm(&r) > 1e-6 * scale {
                        break;
                    }
                }
                // Converged: the tangent solves [R_X R_Omega; t^T] t_new = [0; 1],
                // with the last factorization (a Jacobian within a chord
                // step of the solution).
                let mut e = DVector::zeros(n);
                e[nx] = 1.0;
                let t = factors.solve(&e).ok_or_else(|| SolverError::Singular {
                    what: format!("bordered Jacobian at Omega = {}", y[nx]),
                })?;
                let mut t: Vec<f64> = t.iter().copied().collect();
                let norm: f64 = (0..n)
                    .map(|i| self.metric(i) * t[i] * t[i])
                    .sum::<f64>()
                    .sqrt();
                let dot: f64 = (0..n)
                    .map(|i| self.metric(i) * t[i] * self.cursor.tangent[i])
                    .sum();
                let sign = if dot < 0.0 { -1.0 } else { 1.0 };
                for v in &mut t {
                    *v *= sign / norm;
                }
                // A step accepted at the residual floor was as easy as a
                // two-iteration one: let the step size grow.
                let effort = if at_floor {
                    iteration.min(2)
                } else {
                    iteration
                };
                self.matrix_pool.push(jac);
                if let Some(spent) = lu.take() {
                    self.matrix_pool.push(spent.into_matrix());
                }
                return Ok((y, t, effort));
            }
        }
        self.asm.evaluate(&y[..nx], y[nx], &mut r, None);
        Err(SolverError::NotConverged {
            omega: y[nx],
            residual: inf_norm(&r),
            iterations: NEWTON_MAX,
        })
    }
}
