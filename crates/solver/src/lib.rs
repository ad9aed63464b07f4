//! gearshock's solver: vibration and tooth impacts of a Ravigneaux compound
//! planetary gear set (and of a single spur gear pair) with backlash,
//! time-varying mesh stiffness and transmission error.
//!
//! The crate is pure computation: no web, UI, clock, thread or I/O
//! dependency, so it builds unchanged for native targets and
//! `wasm32-unknown-unknown`. The physics is `docs/model.md`'s; see the
//! repository's `ARCHITECTURE.md` for the map. Results as JSON and the
//! merge of sharded runs live outside it, in the `report` crate.
//!
//! - [`dense`]: the LU factorization of the correctors' dense systems, and
//!   eigenvalues by a bounded iteration.
//! - [`params`] and [`keys`]: the parameter sets and their flat user-facing keys.
//! - [`system`]: the compiled model (mass matrix, mesh vectors, loads).
//! - [`modal`]: statics, natural modes, the linear receptance.
//! - [`ode`]: the adaptive Dormand–Prince integrator with event location.
//! - [`dynamics`]: the equations of motion as an ODE.
//! - [`trig`]: the mesh phase's sine and cosine, the same bits in native and wasm.
//! - [`fastmath`]: max, min and a power function for the hot loops, likewise.
//! - [`model`]: the compiled model (system, modes, statics) every run starts from.
//! - [`steady`]: steady-state runs, Poincaré samples, impact regimes, spectra.
//! - [`sweep`]: bifurcation sweeps with bounded work per call.
//! - [`hbm`]: harmonic balance, continuation, Floquet stability.
//! - [`iso6336`]: the dynamic factor K_v of ISO 6336-1 (method B) per mesh.
//! - [`lyapunov`]: the largest Lyapunov exponent of the Poincaré map.
//! - `separation`: mesh-space separations shared by it and the steady run's probe.
//! - [`parametric`]: parametric instability of the fully engaged set over Omega.
//! - [`map`]: impact-regime maps over Omega and a second parameter.
//! - [`boundaries`]: the map's boundaries (folds, contact changes, cusps) traced as curves.
//! - [`shooting`]: periodic orbits by Newton on the Poincaré map, Floquet
//!   multipliers, continuation of periodic branches.
//! - [`orbits`]: branches of periodic orbits by shooting continuation in Omega.

pub mod bifurcation;
pub mod boundaries;
pub mod campbell;
pub mod dense;
pub mod dynamics;
pub mod error;
pub(crate) mod fastmath;
pub mod hbm;
pub mod iso6336;
pub mod keys;
pub mod lyapunov;
pub mod map;
pub mod modal;
pub mod model;
pub mod ode;
pub mod orbits;
pub mod orders;
pub mod parametric;
pub mod params;
pub mod rpm;
pub(crate) mod separation;
pub mod sharing;
pub mod shooting;
pub(crate) mod simd;
pub mod steady;
pub mod sweep;
pub mod system;
pub mod te_file;
pub(crate) mod trig;
pub mod waveform;

pub use error::{Result, SolverError};
pub use model::Model;
pub use params::{ModelKind, ModelParams};
pub use steady::{SteadyOptions, SteadyState};
