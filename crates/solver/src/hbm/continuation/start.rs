//! The first point of a piece: Newton at fixed Omega, continued in the
//! number of harmonics, or a continuation from below as the fallback.

use super::*;

impl FrfContinuation {
    /// The first point of a piece: Newton at fixed Omega, continued in the
    /// number of harmonics (1, 2, ..., H, each solution padded with zeros as
    /// the next guess) because a many-harmonic Newton from the static guess
    /// can wander into the dead zone and stall.
    pub(super) fn start(&mut self) -> Result<()> {
        let omega = self.piece.start_omega;
        let nx = self.n_x();
        let found = match self.start_in_h(omega) {
            Ok(found) => Ok(found),
            // The fallback (a continuation from below) only for the first
            // piece: a restart that cannot start directly tries the next.
            Err(direct) if self.piece.index == 0 => {
                self.start_from_below(omega).map_err(|_| direct)
            }
            Err(direct) => Err(direct),
        };
        let (x, iterations) = match found {
            Ok(found) => found,
            Err(e) if self.piece.index > 0 => {
                // No piece: the restart is withdrawn and the next one tried
                // (elsewhere in the same gap, or the next gap).
                self.coverage.failed_starts.push(omega);
                return match self.coverage.restarts.pop() {
                    Some(r) => {
                        self.piece.index -= 1;
                        self.end_piece(r.reason, r.stopped_at)
                    }
                    None => {
                        self.finished = true;
                        Err(e)
                    }
                };
            }
            Err(e) => {
                self.finished = true;
                return Err(e);
            }
        };
        let mut r = vec![0.0; nx];
        let mut jac = DMatrix::zeros(nx, nx + 1);
        if self.piece.index > 0 && inf_norm(&x) > self.piece.divergence {
            // A start beyond the divergence bound lies in a gap where the
            // response is unbounded: a pole, which the pieces on both sides
            // approached. It is left out, and the next gap is tried.
            if let (Some(r), Some(&gap)) = (
                self.coverage.restarts.pop(),
                self.coverage_gaps()
                    .iter()
                    .find(|g| g.0 <= omega && omega <= g.1),
            ) {
                self.piece.index -= 1;
                self.coverage.left_out.push(LeftOut {
                    from: gap.0,
                    to: gap.1,
                    reason: LeftOutReason::Unbounded,
                });
                return self.end_piece(r.reason, r.stopped_at);
            }
        }
        self.cursor.scale = (3.0 * rms(&x[self.asm.model.m..])).max(1.0);
        self.cursor.y = x;
        self.cursor.prev_y = None;
        self.cursor.y.push(omega);
        // First tangent: [R_X R_Omega] t = 0 with t_Omega = +-1.
        self.asm
            .evaluate(&self.cursor.y[..nx], omega, &mut r, Some(&mut jac));
        let lu = crate::dense::Lu::new(jac.columns(0, nx).into_owned());
        let rhs = DVector::from_iterator(nx, (0..nx).map(|i| -jac[(i, nx)]));
        let tx = lu.solve(&rhs).ok_or_else(|| SolverError::Singular {
            what: format!("harmonic-balance Jacobian at Omega = {omega}"),
        })?;
        let sign = if self.piece.dir == Direction::Up {
            1.0
        } else {
            -1.0
        };
        self.cursor.tangent = tx.iter().map(|v| v * sign).collect();
        self.cursor.tangent.push(sign);
        self.normalize_tangent();
        self.started = true;
        let p = self.point(iterations, None);
        self.emit(p)
    }

    /// Newton at `omega` continued in the number of harmonics.
    pub(super) fn start_in_h(&mut self, omega: f64) -> Result<(Vec<f64>, usize)> {
        let m = self.asm.model.m;
        let mut x: Vec<f64> = self.recon.x0[..m].to_vec();
        let mut iterations = 0;
        for hh in 1..=self.asm.h {
            x.resize(m * harmonic::n_coef(hh), 0.0);
            if hh == self.asm.h {
                iterations += newton_fixed(&mut self.asm, &mut x, omega, &mut self.stats)?;
            } else {
                let grid = harmonic::Grid::default_size(hh).max(self.asm.grid.n.min(1 << 12));
                let mut coarse = Assembly::new(self.asm.model.clone(), hh, self.asm.method, grid);
                iterations += newton_fixed(&mut coarse, &mut x, omega, &mut self.stats)?;
            }
        }
        Ok((x, iterations))
    }

    /// Fallback start when Newton at `omega` fails from the static guess
    /// (resonance zones, contact loss): continue upward from `START_OMEGA`,
    /// where the response is quasi-static and Newton is reliable, to `omega`
    /// and polish there. The branch reached is the one an upward sweep
    /// follows. A one-time cost of up to one full continuation.
    pub(super) fn start_from_below(&mut self, omega: f64) -> Result<(Vec<f64>, usize)> {
        if omega <= START_OMEGA * 1.5 {
            return Err(SolverError::NotConverged {
                omega,
                residual: f64::NAN,
                iterations: 0,
            });
        }
        let mut spec = self.spec.clone();
        spec.omega_from = START_OMEGA;
        spec.omega_to = omega;
        spec.direction = Direction::Up;
        spec.stability = false;
        spec.points = spec.points.max(200);
        let mut inner = FrfContinuation::with_model(
            self.asm.model.clone(),
            spec,
            self.recon.x0.clone(),
            None,
            self.recon.mesh_to_channel.clone(),
        )?;
        inner.coverage.restarts_allowed = false;
        let mut last = None;
        while !inner.is_finished() {
            if let Some(p) = inner.advance(64)?.pop() {
                last = Some(p);
            }
        }
        self.stats.newton_iterations += inner.stats.newton_iterations;
        self.stats.jacobians += inner.stats.jacobians;
        let mut x = last
            .filter(|p| (p.omega - omega).abs() < 0.05 * omega)
            .map(|p| p.coefficients)
            .ok_or(SolverError::NotConverged {
                omega,
                residual: f64::NAN,
                iterations: 0,
            })?;
        let iterations = newton_fixed(&mut self.asm, &mut x, omega, &mut self.stats)?;
        Ok((x, iterations))
    }
}

/// Damped Newton at fixed Omega: the step is halved (down to 1/128) while
/// it does not reduce the residual. Converged when the step is below
/// `NEWTON_TOL` of the solution's scale and the residual below `1e-6` of it.
pub(super) fn newton_fixed(
    asm: &mut Assembly,
    x: &mut [f64],
    omega: f64,
    stats: &mut FrfStats,
) -> Result<usize> {
    let nx = asm.n_x();
    let mut r = vec![0.0; nx];
    let mut jac = DMatrix::zeros(nx, nx + 1);
    let mut trial = x.to_vec();
    let mut r_trial = vec![0.0; nx];
    let mut iterations = 0;
    loop {
        asm.evaluate(x, omega, &mut r, Some(&mut jac));
        stats.jacobians += 1;
        let res = inf_norm(&r);
        let not_converged = |residual: f64, iterations: usize| SolverError::NotConverged {
            omega,
            residual,
            iterations,
        };
        if !res.is_finite() {
            return Err(not_converged(res, iterations));
        }
        let lu = crate::dense::Lu::new(jac.columns(0, nx).into_owned());
        let dx = lu
            .solve(&DVector::from_column_slice(&r))
            .ok_or_else(|| not_converged(res, iterations))?;
        let mut lambda = 1.0;
        for _ in 0..8 {
            for i in 0..nx {
                trial[i] = x[i] - lambda * dx[i];
            }
            asm.evaluate(&trial, omega, &mut r_trial, None);
            if inf_norm(&r_trial) <= res || lambda < 1e-2 {
                break;
            }
            lambda *= 0.5;
        }
        x.copy_from_slice(&trial);
        iterations += 1;
        stats.newton_iterations += 1;
        let scale = 1.0 + inf_norm(x);
        let step = inf_norm(dx.as_slice()) * lambda;
        let res_new = inf_norm(&r_trial);
        if (step <= NEWTON_TOL * scale && res_new <= 1e-6 * scale)
            || (res_new <= RESIDUAL_FLOOR * scale && step <= 1e-6 * scale)
        {
            return Ok(iterations);
        }
        if iterations >= 4 * NEWTON_MAX {
            return Err(not_converged(inf_norm(&r_trial), iterations));
        }
    }
}
