//! The solver's one error type: every failure carries the values that explain it.
//!
//! Errors are created where they are detected and handled once, by the caller
//! that can tell the user (the CLI prints one line and exits 2 or 1; the app
//! shows a message and keeps its last good state).

use thiserror::Error;

/// Everything that can go wrong in the solver, with the data that explains it.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SolverError {
    /// A parameter value outside its allowed range (or not a finite number).
    #[error("{key} = {value} is out of range: allowed {allowed}")]
    OutOfRange {
        /// The user-facing key, e.g. `backlash_um`.
        key: String,
        /// The offending value as the user wrote it.
        value: String,
        /// The allowed range or set, e.g. `0 ..= 1000`.
        allowed: String,
    },
    /// A key that no model knows.
    #[error("unknown parameter key `{key}`{hint}")]
    UnknownKey {
        /// The key as given.
        key: String,
        /// A "did you mean" suffix (may be empty).
        hint: String,
    },
    /// A key that exists but does not apply to the chosen model.
    #[error("parameter key `{key}` does not apply to model {model}")]
    KeyNotForModel {
        /// The key as given.
        key: String,
        /// The model's name.
        model: String,
    },
    /// A value that is not of the key's type (not a number, not one of the choices).
    #[error("{key} = {value}: {message}")]
    InvalidValue {
        /// The key.
        key: String,
        /// The value as given.
        value: String,
        /// What was expected.
        message: String,
    },
    /// The external torques would accelerate the free rigid-body mode.
    #[error(
        "torques do not balance over the rigid-body mode: torque_s1_nm = {torque_s1_nm} N m needs \
         torque_s2_nm = {balancing_s2_nm:.3} N m, got {torque_s2_nm} N m (leave torque_s2_nm as \
         \"auto\" to use the balancing value)"
    )]
    UnbalancedTorque {
        /// Input torque on the small sun.
        torque_s1_nm: f64,
        /// Torque on the large sun as given.
        torque_s2_nm: f64,
        /// The value that balances `torque_s1_nm`.
        balancing_s2_nm: f64,
    },
    /// Tooth counts or geometry that cannot be built.
    #[error("impossible geometry: {message}")]
    Geometry {
        /// What is wrong, naming the keys and values.
        message: String,
    },
    /// An analysis option outside its allowed range.
    #[error("option {option} = {value} is out of range: allowed {allowed}")]
    BadOption {
        /// The option's name (as the CLI spells it).
        option: String,
        /// The value given.
        value: String,
        /// The allowed range.
        allowed: String,
    },
    /// The adaptive step size fell below its floor: the solution is not smooth enough to follow.
    #[error("step size fell to {h_s:.3e} s at t = {t_s:.6e} s; the integration was stopped")]
    StepSizeTooSmall {
        /// Time at which the integrator gave up.
        t_s: f64,
        /// The step size it had reached.
        h_s: f64,
    },
    /// The state became NaN or infinite (a blow-up).
    #[error("the solution blew up (non-finite state) at t = {t_s:.6e} s")]
    NonFinite {
        /// Time of the blow-up.
        t_s: f64,
    },
    /// The response grows without bound: a mesh deflection left the range a
    /// bounded response can reach.
    #[error(
        "the response grows without bound: mesh {mesh} deflected {:.2} mm after {:.2} ms, \
         beyond {:.2} mm (100 times the static deflection, backlash and TE, more under light damping); \
         the time-varying mesh stiffness makes the motion parametrically unstable here",
        delta_m * 1e3,
        t_s * 1e3,
        bound_m * 1e3
    )]
    Diverged {
        /// The mesh.
        mesh: String,
        /// Its deflection (m).
        delta_m: f64,
        /// The bound (m).
        bound_m: f64,
        /// Time (s).
        t_s: f64,
    },
    /// A linear model (no backlash on any mesh) whose periodic response is
    /// unstable: every motion but that orbit grows without bound, so there
    /// is no steady state to report.
    #[error(
        "the response grows without bound: with no backlash the gear set is linear, and at \
         Omega = {omega:.4} its periodic response has a Floquet multiplier of modulus \
         {modulus:.4}, above 1 (the time-varying mesh stiffness makes it parametrically unstable)"
    )]
    ParametricallyUnstable {
        /// Dimensionless mesh frequency.
        omega: f64,
        /// The largest multiplier's modulus.
        modulus: f64,
    },
    /// The step budget was used up before the end time was reached.
    #[error("more than {max_steps} steps needed by t = {t_s:.6e} s; the integration was stopped")]
    TooManySteps {
        /// The budget.
        max_steps: u64,
        /// Time reached.
        t_s: f64,
    },
    /// Newton's method did not converge.
    #[error("Newton did not converge at Omega = {omega:.6}: residual {residual:.3e} after {iterations} iterations")]
    NotConverged {
        /// Dimensionless mesh frequency.
        omega: f64,
        /// Final residual norm.
        residual: f64,
        /// Iterations spent.
        iterations: usize,
    },
    /// Continuation used its point budget without leaving the range.
    #[error("continuation stalled at Omega = {omega:.6}: {points} points used without reaching the end of the range")]
    ContinuationStalled {
        /// Dimensionless mesh frequency reached.
        omega: f64,
        /// Points computed.
        points: u64,
    },
    /// A matrix that must be invertible (or positive definite) was not.
    #[error("singular or indefinite matrix: {what}")]
    Singular {
        /// Which matrix.
        what: String,
    },
    /// Malformed input data (JSON parameter file, shard file, link).
    #[error("{0}")]
    Parse(String),
}

impl SolverError {
    /// An out-of-range option, as an `Err`: the one constructor behind every
    /// options struct's `validate`.
    pub(crate) fn bad_option<T>(option: &str, value: impl ToString, allowed: &str) -> Result<T> {
        Err(SolverError::BadOption {
            option: option.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        })
    }
}

/// Shorthand for the solver's results.
pub type Result<T> = std::result::Result<T, SolverError>;
