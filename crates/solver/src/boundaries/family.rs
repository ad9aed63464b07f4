//! The harmonic-balance residual as a function of the orbit, Omega and a
//! second parameter `p` (any numeric key that leaves the modal basis
//! unchanged): one [`Assembly`] per value of `p`, built from the parameter
//! set through the key table (for `backlash_um`, which sets every mesh's
//! backlash and nothing else, by setting the laws' backlash on one built
//! model), and the derivatives in `p` by one-sided differences.

use crate::error::{Result, SolverError};
use crate::hbm::harmonic::Grid;
use crate::hbm::model::Law;
use crate::hbm::{Assembly, HbmCost, HbmModel, Method};
use crate::keys::{self, KeyType, Value};
use crate::model::Model;
use crate::params::ModelParams;
use crate::system::MeshSystem;
use nalgebra::DMatrix;

/// Assemblies kept for recent values of `p` (the point and its
/// difference neighbour, over a few iterates).
const CACHE: usize = 6;

/// The family of harmonic-balance problems along a parameter key.
#[derive(Debug, Clone)]
pub(crate) struct Family {
    base: ModelParams,
    key: String,
    method: Method,
    symmetric: bool,
    /// Allowed range of the key.
    key_min: f64,
    key_max: f64,
    /// Relative step of the differences in `p` (of the traced range).
    dp: f64,
    cache: Vec<(u64, Assembly)>,
    /// The grid every assembly of the family shares (built once).
    grid: Grid,
    /// What its operations cost.
    cost: HbmCost,
    /// Work units spent so far ([`HbmCost`]): every evaluation, assembly,
    /// monodromy and factorization the curves made.
    pub(crate) work: f64,
    /// For the key `backlash_um`: the model built at one value, whose laws'
    /// backlash [`with_backlash`] sets for the others.
    backlash_model: Option<HbmModel>,
}

impl Family {
    /// The family along `key` from `base`; `p_scale` is the traced range
    /// (sets the difference step).
    pub(crate) fn new(
        base: &ModelParams,
        key: &str,
        h: usize,
        method: Method,
        symmetric: bool,
        p_scale: f64,
    ) -> Result<Self> {
        let spec = keys::spec(key).ok_or_else(|| SolverError::UnknownKey {
            key: key.into(),
            hint: String::new(),
        })?;
        let (key_min, key_max) = match spec.ty {
            KeyType::Float { min, max } => (min, max),
            _ => {
                return Err(SolverError::BadOption {
                    option: "key".into(),
                    value: key.into(),
                    allowed: "a key with a real-number value".into(),
                })
            }
        };
        let hbm = HbmModel::from_system(&MeshSystem::build(base)?, symmetric)?;
        Assembly::check_harmonics(&hbm, h, method)?;
        Ok(Family {
            cost: HbmCost::of(&hbm, Assembly::harmonics(h, method)),
            work: 0.0,
            backlash_model: None,
            base: base.clone(),
            key: key.into(),
            method,
            symmetric,
            key_min,
            key_max,
            dp: 1e-6 * p_scale.abs().max(1e-3),
            cache: Vec::new(),
            grid: Grid::new(Assembly::harmonics(h, method), Grid::default_size(h)),
        })
    }

    /// The parameter set at `p`.
    pub(crate) fn params_at(&self, p: f64) -> Result<ModelParams> {
        let mut params = self.base.clone();
        keys::set(&mut params, &self.key, Value::Num(p))?;
        Ok(params)
    }

    /// The compiled model at `p`.
    pub(crate) fn model_at(&self, p: f64) -> Result<Model> {
        Model::new(&self.params_at(p)?)
    }

    /// The harmonic-balance problem at `p` (as the one-parameter
    /// continuation builds it, from the model's system: its modes and
    /// static equilibrium, which the harmonic balance does not read, are
    /// not computed).
    pub(crate) fn hbm_at(&self, p: f64) -> Result<HbmModel> {
        // `base` was validated by `new`, the key's value by `params_at`.
        HbmModel::from_system(
            &MeshSystem::build_validated(&self.params_at(p)?)?,
            self.symmetric,
        )
    }

    /// [`Self::hbm_at`], for `backlash_um` from the model built at its
    /// first value: a corrector iteration needs two new values, and
    /// building the mesh system and its harmonic-balance problem for each
    /// was a sixth of the page's trace.
    fn built_at(&mut self, p: f64) -> Result<HbmModel> {
        if self.key != "backlash_um" {
            return self.hbm_at(p);
        }
        // The key's value is checked as `hbm_at` checks it.
        self.params_at(p)?;
        match &self.backlash_model {
            Some(base) => Ok(with_backlash(base, p)),
            None => {
                let hbm = self.hbm_at(p)?;
                self.backlash_model = Some(hbm.clone());
                Ok(hbm)
            }
        }
    }

    /// The evaluator at `p`, built once per value.
    pub(crate) fn assembly(&mut self, p: f64) -> Result<&mut Assembly> {
        let bits = p.to_bits();
        let index = match self.cache.iter().position(|(b, _)| *b == bits) {
            Some(i) => i,
            None => {
                self.work += self.cost.assembly();
                let hbm = self.built_at(p)?;
                // The evicted assembly's grid is the family's: moved, not
                // copied again (a copy per new value of the key was a
                // twentieth of the trace).
                let grid = if self.cache.len() >= CACHE {
                    self.cache.remove(0).1.grid
                } else {
                    self.grid.clone()
                };
                let donor = self.cache.last().map(|(_, a)| a);
                let asm = Assembly::with_grid_from(hbm, self.method, grid, donor);
                self.cache.push((bits, asm));
                self.cache.len() - 1
            }
        };
        Ok(&mut self.cache[index].1)
    }

    /// The two values of `p` a derivative is differenced over: `p` itself
    /// and the next value up, or down at the key's upper limit. One-sided,
    /// so that a derivative costs one new assembly and evaluation (the
    /// point's own are at hand): central differences built two per
    /// corrector iteration, a fifth of the trace, for an accuracy (1e-6 of
    /// the range) the Newton steps and the sides do not need.
    pub(crate) fn neighbours(&self, p: f64) -> (f64, f64) {
        if p + self.dp <= self.key_max {
            (p, p + self.dp)
        } else {
            ((p - self.dp).max(self.key_min), p)
        }
    }

    /// Residual and Jacobian (`n_x` columns of `dR/dX`, then `dR/dOmega`) at
    /// `(x, omega, p)`.
    pub(crate) fn evaluate(
        &mut self,
        x: &[f64],
        omega: f64,
        p: f64,
        r: &mut [f64],
        jac: Option<&mut DMatrix<f64>>,
    ) -> Result<()> {
        self.work += if jac.is_some() {
            self.cost.jacobian()
        } else {
            self.cost.residual()
        };
        self.assembly(p)?.evaluate(x, omega, r, jac);
        if r.iter().all(|v| v.is_finite()) {
            Ok(())
        } else {
            Err(SolverError::NotConverged {
                omega,
                residual: f64::NAN,
                iterations: 0,
            })
        }
    }

    /// What its operations cost.
    pub(crate) fn cost(&self) -> HbmCost {
        self.cost
    }

    /// Counts the factorization of a dense matrix of size `n`.
    pub(crate) fn factored(&mut self, n: usize) {
        self.work += HbmCost::factor(n);
    }

    /// Counts `units` of other work.
    pub(crate) fn spend(&mut self, units: f64) {
        self.work += units;
    }

    /// Counts a monodromy matrix at `omega`.
    pub(crate) fn integrated_monodromy(&mut self, omega: f64) {
        self.work += self.cost.monodromy(omega);
    }

    /// Whether the key changes only what the harmonic balance's laws, loads
    /// and damping hold, so that the coordinates mean the same at every
    /// value: the modal basis at `a` and `b` is the same.
    pub(crate) fn same_basis(&self, a: f64, b: f64) -> Result<bool> {
        let (ha, hb) = (self.hbm_at(a)?, self.hbm_at(b)?);
        Ok(ha.m == hb.m
            && ha.transform == hb.transform
            && ha.stiffness == hb.stiffness
            && ha.channels.len() == hb.channels.len()
            && ha
                .channels
                .iter()
                .zip(&hb.channels)
                .all(|(x, y)| x.d == y.d))
    }
}

/// `base` with every mesh's backlash `backlash_um` (as the mesh system
/// holds it, in metres, and the laws again in um: the same bits as a
/// model built at that value).
fn with_backlash(base: &HbmModel, backlash_um: f64) -> HbmModel {
    let b_um = (backlash_um * 1e-6) * 1e6;
    let mut hbm = base.clone();
    for ch in &mut hbm.channels {
        if let Law::Mesh { backlash_um, .. } = &mut ch.law {
            *backlash_um = b_um;
        }
    }
    hbm.mesh_backlash_um.iter_mut().for_each(|b| *b = b_um);
    hbm
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::ModelKind;

    #[test]
    fn a_models_backlash_set_in_place_is_the_model_built_at_that_value() {
        for base in [ModelKind::Ravigneaux, ModelKind::GearPair].map(ModelParams::defaults) {
            for symmetric in [true, false] {
                let fam =
                    Family::new(&base, "backlash_um", 5, Method::Exact, symmetric, 200.0).unwrap();
                let first = fam.hbm_at(37.5).unwrap();
                for p in [0.0, 1e-3, 12.345678, 100.0, 199.99] {
                    assert_eq!(with_backlash(&first, p), fam.hbm_at(p).unwrap(), "p = {p}");
                }
            }
        }
    }
}
