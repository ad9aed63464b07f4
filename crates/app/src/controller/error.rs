//! Why the page refused what the reader asked for: one enum, each message
//! written once and in plain words. The page shows it beside the control
//! (or in its messages) and keeps the last good state.

use figures::family_spec::FamilyError;
use solver::SolverError;

/// A refused input: a typed value, a family, a click.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InputError {
    /// A value outside its key's type or range, said with the allowed
    /// range ("Backlash b must be between 0 and 1000 µm (not 5000).").
    #[error("{}", figures::words::must_be(key, text))]
    Refused {
        /// The control's key.
        key: String,
        /// The text as typed.
        text: String,
    },
    /// A range whose start was not below its end: the message says which
    /// range was reset to what.
    #[error("{0}")]
    RangeReset(String),
    /// Parameters the model cannot be built from (tooth counts, torques),
    /// or a TE table the solver cannot read or fit (its line and reason).
    #[error(transparent)]
    Model(#[from] SolverError),
    /// A count of TE harmonics to fit outside what the fit takes.
    #[error("the harmonics fitted must be 1 to {most} (not {given})")]
    TeHarmonics {
        /// The most the fit takes.
        most: usize,
        /// The text as given.
        given: String,
    },
    /// A family that cannot be shown.
    #[error(transparent)]
    Family(#[from] FamilyError),
    /// A speed typed in rpm outside its key's range.
    #[error("{what} must be between {lo} and {hi} rpm of the {input} (not {text}).")]
    Rpm {
        /// The speed field in words ("The selected speed").
        what: String,
        /// The lowest rpm allowed, as written.
        lo: String,
        /// The highest rpm allowed, as written.
        hi: String,
        /// The member the rpm are of ("small sun").
        input: String,
        /// The text as typed (shortened).
        text: String,
    },
    /// A click that falls on no cell of the map.
    #[error("the click is outside the map")]
    OutsideMap,
}

impl InputError {
    /// A refused value of `key`, said with its allowed range.
    pub(super) fn refused(key: &str, text: &str) -> Self {
        InputError::Refused {
            key: key.to_string(),
            text: text.to_string(),
        }
    }
}
