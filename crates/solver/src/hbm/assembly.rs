//! The harmonic-balance residual `R(X, Omega)`, its Jacobian `dR/dX` and
//! its derivative `dR/dOmega`, assembled from the linear part (block
//! diagonal over harmonics) and the channels (AFT, the seed's describing
//! function, or exact piecewise integration).
//!
//! Unknowns are laid out coefficient by coefficient: `X[c * m + i]` is
//! coefficient `c` (mean, cos 1, sin 1, cos 2, ...) of coordinate `i`.

use super::harmonic::{
    channel_aft, channel_df, channel_exact, mult_operator, n_coef, ChannelTables, ExactScratch,
    Grid, Scratch, SwitchTable,
};
use super::model::HbmModel;
use crate::error::{Result, SolverError};
use nalgebra::Complex;
use nalgebra::DMatrix;

/// How the nonlinear forces are balanced.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Alternating frequency–time on a time grid, any number of harmonics.
    Aft,
    /// The seed paper's closed-form one-harmonic describing function (`H = 1`).
    DescribingFunction,
    /// Closed-form integration between the contact switches, any number of
    /// harmonics: no quadrature error and a smooth residual.
    Exact,
}

impl Method {
    /// Name for output and the CLI.
    pub fn name(self) -> &'static str {
        match self {
            Method::Aft => "aft",
            Method::DescribingFunction => "describing-function",
            Method::Exact => "exact",
        }
    }

    /// Parses a name written by [`Method::name`].
    pub fn from_name(s: &str) -> Option<Self> {
        match s {
            "aft" => Some(Method::Aft),
            "describing-function" | "df" => Some(Method::DescribingFunction),
            "exact" => Some(Method::Exact),
            _ => None,
        }
    }
}

/// Residual evaluator with its tables and scratch space.
#[derive(Debug, Clone)]
pub struct Assembly {
    /// The problem.
    pub model: HbmModel,
    /// Harmonics.
    pub h: usize,
    /// Method.
    pub method: Method,
    /// Time grid (AFT; also used to reconstruct orbits).
    pub grid: Grid,
    /// Samples on which contact switches are bracketed (exact method, stability).
    pub switch_table: SwitchTable,
    tables: Vec<ChannelTables>,
    te_rate_cos: Vec<f64>,
    te_rate_sin: Vec<f64>,
    /// The TE-rate forcing of harmonics 2, 3, ... up to the excitation's
    /// highest and `h` (empty for a one-harmonic TE).
    te_rate_higher: Vec<(Vec<f64>, Vec<f64>)>,
    scratch: Scratch,
    exact_scratch: ExactScratch,
    u_coef: Vec<f64>,
    force: Vec<f64>,
    slope: Vec<Complex<f64>>,
    op: Vec<f64>,
    /// A Jacobian block's factors `coef d_a`, one per coordinate.
    block_factors: Vec<f64>,
    /// Channel displacement coefficients of the last evaluation, channel after channel.
    pub channel_coef: Vec<f64>,
}

impl Assembly {
    /// An evaluator for `h` harmonics (`h = 1` for the describing function)
    /// on a grid of `grid_n` points.
    pub fn new(model: HbmModel, h: usize, method: Method, grid_n: usize) -> Self {
        Self::with_grid(model, method, Grid::new(Self::harmonics(h, method), grid_n))
    }

    /// The harmonics an assembly of `method` keeps for `h` asked: one for
    /// the describing function, `h` otherwise.
    pub fn harmonics(h: usize, method: Method) -> usize {
        if method == Method::DescribingFunction {
            1
        } else {
            h
        }
    }

    /// Refuses a balance of `h` harmonics by `method` that would drop
    /// harmonics of the excitation (the describing function keeps one).
    pub fn check_harmonics(model: &HbmModel, h: usize, method: Method) -> Result<()> {
        let need = model.excitation_harmonics();
        let kept = Self::harmonics(h, method);
        if kept >= need {
            return Ok(());
        }
        let allowed = if method == Method::DescribingFunction {
            format!(
                "the excitation has {need} harmonics (stiffness waveform or TE) and the describing \
                 function keeps one: use the exact or AFT balance with at least {need} harmonics"
            )
        } else {
            format!(
                "at least {need}: the excitation has {need} harmonics (stiffness waveform or TE), \
                 and a balance of fewer would drop some"
            )
        };
        SolverError::bad_option("harmonics", kept, &allowed)
    }

    /// The same on a grid built before, whose harmonics are the
    /// assembly's (see [`Assembly::harmonics`]). A grid depends on its
    /// harmonics and size alone, so a family of assemblies along a
    /// parameter shares one (a boundary trace at the page's settings
    /// took 49.1 s with a grid built for every new value, 34.1 s shared).
    pub fn with_grid(model: HbmModel, method: Method, grid: Grid) -> Self {
        Self::with_grid_from(model, method, grid, None)
    }

    /// The same, taking a channel's stiffness and TE tables from `donor`
    /// (an assembly on the same grid) where that channel's law differs
    /// from the donor's at most in its backlash, which the tables do not
    /// hold, and the contact switches' table (which depends on the
    /// harmonics alone). Along the backlash every table is the donor's (that trace:
    /// 34.1 s with tables built anew, 30.9 s shared).
    pub fn with_grid_from(
        model: HbmModel,
        method: Method,
        grid: Grid,
        donor: Option<&Assembly>,
    ) -> Self {
        let h = grid.h;
        // A grid is its harmonics and size (`Grid::new`).
        let donor = donor.filter(|d| (d.grid.h, d.grid.n) == (grid.h, grid.n));
        let tables = model
            .channels
            .iter()
            .enumerate()
            .map(|(i, c)| {
                let same = |d: &&Assembly| {
                    d.model
                        .channels
                        .get(i)
                        .is_some_and(|dc| dc.law.same_tables(&c.law))
                };
                match donor.filter(same).and_then(|d| d.tables.get(i)) {
                    Some(t) => t.clone(),
                    None => ChannelTables::new(&c.law, &grid),
                }
            })
            .collect();
        let (te_rate_cos, te_rate_sin) = model.te_rate_forcing();
        let te_rate_higher = (2..=h.min(model.excitation_harmonics()))
            .map(|n| model.te_rate_forcing_harmonic(n))
            .collect();
        let nc = n_coef(h);
        Assembly {
            h,
            method,
            tables,
            te_rate_cos,
            te_rate_sin,
            te_rate_higher,
            scratch: Scratch::default(),
            exact_scratch: ExactScratch::default(),
            // The switch table depends on `h` alone: a donor's is the same
            // (its 16 (2h + 1) phases of every basis function took an eighth
            // of a boundary trace, built for every new value of the key).
            switch_table: donor.map_or_else(|| SwitchTable::new(h), |d| d.switch_table.clone()),
            u_coef: vec![0.0; nc],
            force: vec![0.0; nc],
            slope: vec![Complex::new(0.0, 0.0); 2 * h + 1],
            op: vec![0.0; nc * nc],
            block_factors: Vec::new(),
            channel_coef: vec![0.0; model.channels.len() * nc],
            grid,
            model,
        }
    }

    /// Number of unknown coefficients.
    pub fn n_x(&self) -> usize {
        self.model.m * n_coef(self.h)
    }

    /// Evaluates `r = R(x, omega)`; with `jac`, also `dR/dX` into its first
    /// `n_x` columns and `dR/dOmega` into column `n_x` (the matrix must be at
    /// least `n_x x (n_x + 1)`; every other entry is set to zero).
    pub fn evaluate(
        &mut self,
        x: &[f64],
        omega: f64,
        r: &mut [f64],
        jac: Option<&mut DMatrix<f64>>,
    ) {
        // With the widest vector instructions (the same bits, `crate::simd`).
        crate::simd::dispatch(
            #[inline(always)]
            || self.evaluate_here(x, omega, r, jac),
        )
    }

    /// [`Assembly::evaluate`]'s body, inlined into the vector unit's dispatch.
    #[cfg_attr(target_arch = "x86_64", inline(always))]
    fn evaluate_here(
        &mut self,
        x: &[f64],
        omega: f64,
        r: &mut [f64],
        mut jac: Option<&mut DMatrix<f64>>,
    ) {
        let m = self.model.m;
        let nc = n_coef(self.h);
        let nx = m * nc;
        if let Some(j) = jac.as_deref_mut() {
            j.as_mut_slice().fill(0.0);
        }
        // Linear part.
        let k = &self.model.stiffness;
        let c = &self.model.damping;
        for i in 0..m {
            let mut s = -self.model.load[i];
            for l in 0..m {
                s += k[(i, l)] * x[l];
            }
            r[i] = s;
        }
        if let Some(j) = jac.as_deref_mut() {
            for i in 0..m {
                for l in 0..m {
                    j[(i, l)] = k[(i, l)];
                }
            }
        }
        for hk in 1..=self.h {
            let kf = hk as f64;
            let (ic, is) = ((2 * hk - 1) * m, 2 * hk * m);
            let w2 = kf * kf * omega * omega;
            for i in 0..m {
                let mut rc = -w2 * x[ic + i];
                let mut rs = -w2 * x[is + i];
                let mut dc = -2.0 * kf * kf * omega * x[ic + i];
                let mut ds = -2.0 * kf * kf * omega * x[is + i];
                for l in 0..m {
                    rc += k[(i, l)] * x[ic + l] + kf * omega * c[(i, l)] * x[is + l];
                    rs += k[(i, l)] * x[is + l] - kf * omega * c[(i, l)] * x[ic + l];
                    dc += kf * c[(i, l)] * x[is + l];
                    ds -= kf * c[(i, l)] * x[ic + l];
                }
                if hk == 1 {
                    rc -= self.model.force_cos[i] + omega * self.te_rate_cos[i];
                    rs -= self.model.force_sin[i] + omega * self.te_rate_sin[i];
                    dc -= self.te_rate_cos[i];
                    ds -= self.te_rate_sin[i];
                } else if let Some((fc, fs)) = self.te_rate_higher.get(hk - 2) {
                    rc -= omega * fc[i];
                    rs -= omega * fs[i];
                    dc -= fc[i];
                    ds -= fs[i];
                }
                r[ic + i] = rc;
                r[is + i] = rs;
                if let Some(j) = jac.as_deref_mut() {
                    j[(ic + i, nx)] = dc;
                    j[(is + i, nx)] = ds;
                    for l in 0..m {
                        let kv = k[(i, l)] - if i == l { w2 } else { 0.0 };
                        j[(ic + i, ic + l)] = kv;
                        j[(is + i, is + l)] = kv;
                        j[(ic + i, is + l)] = kf * omega * c[(i, l)];
                        j[(is + i, ic + l)] = -kf * omega * c[(i, l)];
                    }
                }
            }
        }
        // Channels.
        for (ch_idx, ch) in self.model.channels.iter().enumerate() {
            for cc in 0..nc {
                self.u_coef[cc] = (0..m).map(|i| ch.d[i] * x[cc * m + i]).sum();
            }
            self.channel_coef[ch_idx * nc..(ch_idx + 1) * nc].copy_from_slice(&self.u_coef);
            let exact = self.method == Method::Exact
                && channel_exact(
                    self.h,
                    &self.switch_table,
                    &ch.law,
                    &self.u_coef,
                    &mut self.exact_scratch,
                    &mut self.force,
                    &mut self.slope,
                );
            if self.method == Method::DescribingFunction {
                channel_df(&ch.law, &self.u_coef, &mut self.force, &mut self.slope);
            } else if !exact {
                // AFT, and the exact method's fallback for laws it does not integrate.
                channel_aft(
                    &self.grid,
                    &ch.law,
                    &self.tables[ch_idx],
                    &self.u_coef,
                    &mut self.scratch,
                    &mut self.force,
                    &mut self.slope,
                );
            }
            let w = ch.multiplicity;
            for cc in 0..nc {
                let f = w * self.force[cc];
                for i in 0..m {
                    r[cc * m + i] += f * ch.d[i];
                }
            }
            if let Some(j) = jac.as_deref_mut() {
                mult_operator(&self.slope, self.h, &mut self.op);
                // Block (p, q) gains `coef d d^T`, entry (a, b) the product
                // `(coef d_a) d_b`. Column by column on the column-major
                // storage, each column's `m` rows one contiguous slice, the
                // factors `coef d_a` formed once per block.
                let rows_total = j.nrows();
                let storage = j.as_mut_slice();
                let d = &ch.d;
                let ca = &mut self.block_factors;
                ca.resize(m, 0.0);
                for q in 0..nc {
                    for p in 0..nc {
                        let coef = w * self.op[p * nc + q];
                        if coef == 0.0 {
                            continue;
                        }
                        for (c, &da) in ca.iter_mut().zip(d) {
                            *c = coef * da;
                        }
                        for (b, &db) in d.iter().enumerate() {
                            let start = (q * m + b) * rows_total + p * m;
                            for (entry, &c) in storage[start..start + m].iter_mut().zip(ca.iter()) {
                                // A zero factor adds nothing (not even a
                                // signed zero), as before.
                                *entry = if c != 0.0 { *entry + c * db } else { *entry };
                            }
                        }
                    }
                }
            }
        }
        let _ = nx;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::keys::{self, Value};
    use crate::params::ModelParams;
    use crate::Model;

    fn hbm(backlash_um: f64, te_um: f64) -> HbmModel {
        let mut p = ModelParams::default();
        keys::set(&mut p, "backlash_um", Value::Num(backlash_um)).unwrap();
        keys::set(&mut p, "te_um", Value::Num(te_um)).unwrap();
        HbmModel::from_system(&Model::new(&p).unwrap().system, true).unwrap()
    }

    fn residual_and_jacobian(a: &mut Assembly) -> (Vec<f64>, DMatrix<f64>) {
        let nx = a.n_x();
        let x: Vec<f64> = (0..nx).map(|i| 20.0 * (0.37 * i as f64).sin()).collect();
        let mut r = vec![0.0; nx];
        let mut j = DMatrix::zeros(nx, nx + 1);
        a.evaluate(&x, 0.7, &mut r, Some(&mut j));
        (r, j)
    }

    /// An assembly that takes its tables from a donor (another backlash:
    /// shared; another TE: built anew) evaluates to the same bits as one
    /// built alone.
    #[test]
    fn tables_from_a_donor_give_the_same_bits() {
        let h = 3;
        let grid = || Grid::new(h, Grid::default_size(h));
        let donor = Assembly::with_grid(hbm(50.0, 10.0), Method::Aft, grid());
        for (b, te) in [(100.0, 10.0), (100.0, 20.0)] {
            let mut alone = Assembly::new(hbm(b, te), h, Method::Aft, Grid::default_size(h));
            let mut shared =
                Assembly::with_grid_from(hbm(b, te), Method::Aft, grid(), Some(&donor));
            assert_eq!(shared.tables, alone.tables, "backlash {b}, TE {te}");
            assert_eq!(shared.switch_table, alone.switch_table);
            assert_eq!(
                residual_and_jacobian(&mut shared),
                residual_and_jacobian(&mut alone)
            );
        }
        // The TE differs: the tables differ from the donor's.
        let other = Assembly::with_grid_from(hbm(100.0, 20.0), Method::Aft, grid(), Some(&donor));
        assert_ne!(other.tables, donor.tables);
    }
}
