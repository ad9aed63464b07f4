//! Harmonic balance: periodic responses as truncated Fourier series, solved by
//! Newton's method and followed in Omega by pseudo-arclength continuation,
//! with Floquet stability and bifurcation points.
//!
//! - [`model`]: the problem in scaled modal coordinates (rigid mode removed),
//!   full or reduced by the cyclic symmetry of in-phase planets.
//! - [`harmonic`]: AFT, exact integration between the contact switches, the
//!   seed's describing function, the multiplication operator.
//! - [`assembly`]: residual and analytic Jacobian.
//! - [`stability`]: monodromy matrix and Floquet multipliers.
//! - [`cost`]: what each of these operations costs on a model, in work units.
//! - [`continuation`]: Newton, pseudo-arclength continuation in Omega,
//!   folds, stability changes and restarts (the frequency response).

pub mod assembly;
pub mod continuation;
pub mod cost;
pub mod harmonic;
pub mod model;
pub mod stability;

pub use assembly::{Assembly, Method};
pub use continuation::{
    Bifurcation, BranchMesh, BranchPoint, FrfContinuation, FrfSpec, FrfStats, LeftOut,
    LeftOutReason, PieceEnd, Restart, StepControl, SAMPLED_STABILITY_STRIDE,
};
pub use cost::HbmCost;
pub use model::{HbmModel, Reduction};
pub use stability::Floquet;
