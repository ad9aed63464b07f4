//! How a command fails: a message and an exit code (2 for bad input, 1 for
//! a solver failure, 3 for a failed write: [`crate::output::EXIT_IO`]),
//! with the solver's errors mapped to the flags the user typed.

use solver::SolverError;

/// A failure and its exit code.
pub struct Failure {
    /// The process's exit code.
    pub code: u8,
    /// One line for stderr (after `gearshock: `); empty for a closed
    /// pipe, whose reader wants no word.
    pub message: String,
}

/// The solver's option names that are this program's flags (`--NAME`).
const FLAGS: &[&str] = &[
    "omega",
    "omega-from",
    "omega-to",
    "points",
    "omega-points",
    "value-points",
    "transient-periods",
    "record-periods",
    "periods",
    "rtol",
    "atol",
    "chains",
    "shard",
    "harmonics",
    "grid",
    "period",
    "levels",
];

impl From<SolverError> for Failure {
    fn from(e: SolverError) -> Self {
        // An option the user typed is named as typed: `--omega -1`.
        if let SolverError::BadOption {
            option,
            value,
            allowed,
        } = &e
        {
            if FLAGS.contains(&option.as_str()) {
                return usage(format!(
                    "--{option} {value} is out of range: allowed {allowed}"
                ));
            }
        }
        let code = match e {
            SolverError::StepSizeTooSmall { .. }
            | SolverError::NonFinite { .. }
            | SolverError::Diverged { .. }
            | SolverError::ParametricallyUnstable { .. }
            | SolverError::TooManySteps { .. }
            | SolverError::NotConverged { .. }
            | SolverError::ContinuationStalled { .. }
            | SolverError::Singular { .. } => 1,
            _ => 2,
        };
        Failure {
            code,
            message: e.to_string(),
        }
    }
}

/// A usage failure (exit code 2): bad input, named in `message`.
pub fn usage(message: impl Into<String>) -> Failure {
    Failure {
        code: 2,
        message: message.into(),
    }
}
