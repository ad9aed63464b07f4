//! A solver failure in plain words, for the messages a user reads: what
//! went wrong in terms of the gears and the computation ("the solver did
//! not converge at Ω 0.1"), then what to try ("Try a load torque above
//! 0: …"). The solver's own messages (`Newton did not converge at Omega =
//! 0.100000: residual 1.870e0 after 48 iterations`) stay in the CLI; the
//! worker sends these instead, each after a subject naming what could not
//! be computed ("The steady state at Ω 0.35 could not be found: …").

use crate::words::short;
use solver::model::Model;
use solver::SolverError;

/// What was being computed: the advice differs (more harmonics help the
/// harmonic balance, not a time integration).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Task {
    /// The selected-Omega steady state (a time integration).
    SteadyState,
    /// The harmonic-balance frequency response.
    HarmonicBalance,
    /// The shooting branches (periodic orbits followed in Omega).
    Shooting,
    /// Anything else (a sweep, a map, the boundaries).
    Other,
}

/// Whether a load presses the model's teeth together: some static mesh
/// force is not zero.
pub fn is_loaded(model: &Model) -> bool {
    model.statics.mesh_force_n.iter().any(|f| f.abs() >= 1e-9)
}

/// Why `e` stopped `task`, and what to try, in one or two sentences that
/// follow a colon: "the solver did not converge at Ω 0.1 (…). Try …".
/// `loaded`: whether the model's teeth carry a load ([`is_loaded`]).
pub fn explain(e: &SolverError, task: Task, loaded: bool) -> String {
    let why = why(e);
    match advice(e, task, loaded) {
        Some(t) => format!("{why}. Try {t}."),
        None => format!("{why}."),
    }
}

/// What went wrong, lower case, no full stop.
fn why(e: &SolverError) -> String {
    match e {
        SolverError::NotConverged {
            omega,
            residual,
            iterations,
        } => format!(
            "the solver did not converge at Ω {} (after {iterations} iterations its equations were still off by {})",
            short(*omega),
            sci(*residual)
        ),
        SolverError::ContinuationStalled { omega, points } => format!(
            "the curve did not reach the end of the range: it stalled at Ω {} after {points} points",
            short(*omega)
        ),
        SolverError::StepSizeTooSmall { t_s, .. } => format!(
            "the time integration needed ever smaller steps and stopped after {} ms: the impacts are too sharp to follow",
            short(t_s * 1e3)
        ),
        SolverError::TooManySteps { t_s, .. } => format!(
            "the time integration used up its step budget after {} ms",
            short(t_s * 1e3)
        ),
        SolverError::NonFinite { t_s } => format!(
            "the numbers blew up (no longer finite) after {} ms",
            short(t_s * 1e3)
        ),
        SolverError::Diverged { mesh, delta_m, .. } => format!(
            "the motion grows without bound (mesh {mesh} deflected {} mm): the time-varying mesh stiffness makes it parametrically unstable here, so there is no steady state",
            short(delta_m.abs() * 1e3)
        ),
        SolverError::Singular { what } => {
            format!("a matrix of the model could not be inverted ({what})")
        }
        // Input errors already name the setting and its range in words.
        other => crate::words::capitalize(&other.to_string())
            .trim_end_matches('.')
            .to_string(),
    }
}

/// What to try, lower case, no full stop; `None` where nothing helps.
fn advice(e: &SolverError, task: Task, loaded: bool) -> Option<String> {
    let numerical = matches!(
        e,
        SolverError::NotConverged { .. }
            | SolverError::ContinuationStalled { .. }
            | SolverError::StepSizeTooSmall { .. }
            | SolverError::TooManySteps { .. }
            | SolverError::NonFinite { .. }
    );
    if !loaded && numerical {
        return Some(
            "a load torque above 0: without load nothing presses the teeth together, they float in the backlash, and no steady state may exist"
                .into(),
        );
    }
    let text = match (e, task) {
        (SolverError::NotConverged { .. }, Task::HarmonicBalance)
        | (SolverError::ContinuationStalled { .. }, Task::HarmonicBalance) => {
            "more harmonics in the balance, more points along the curve, or a frequency range that starts a little higher"
        }
        (SolverError::NotConverged { .. }, Task::Shooting)
        | (SolverError::ContinuationStalled { .. }, Task::Shooting) => {
            "a narrower frequency range, or turn the shooting branches off: the time-integration dots still show what the gears do"
        }
        (SolverError::NotConverged { .. } | SolverError::ContinuationStalled { .. }, _) => {
            "another Ω or a narrower frequency range"
        }
        (SolverError::StepSizeTooSmall { .. } | SolverError::NonFinite { .. }, _) => {
            "more damping, a smaller stiffness variation, or another Ω"
        }
        (SolverError::TooManySteps { .. }, _) => "fewer transient or recorded periods",
        (SolverError::Diverged { .. }, _) => {
            "another Ω (outside the instability band) or more damping"
        }
        (SolverError::Singular { .. }, _) => "other masses and stiffnesses",
        _ => return None,
    };
    Some(text.into())
}

/// A residual as people read it: 1.87, 0.000337.
fn sci(x: f64) -> String {
    if x.abs() >= 1e-3 || x == 0.0 {
        short(x)
    } else {
        format!("{x:.1e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use solver::params::ModelParams;

    fn loaded(link: &str) -> bool {
        let mut p = ModelParams::default();
        for kv in link.split('&').filter(|s| !s.is_empty()) {
            if let Err(e) = solver::keys::set_assignment(&mut p, kv) {
                panic!("{kv}: {e}");
            }
        }
        match Model::new(&p) {
            Ok(m) => is_loaded(&m),
            Err(e) => panic!("{e}"),
        }
    }

    #[test]
    fn a_failure_says_what_went_wrong_and_what_to_try_without_the_solvers_words() {
        let e = SolverError::NotConverged {
            omega: 0.1,
            residual: 1.87,
            iterations: 48,
        };
        // No load: the advice is the torque.
        let text = explain(&e, Task::SteadyState, loaded("torque_s1_nm=0"));
        assert_eq!(
            text,
            "the solver did not converge at Ω 0.1 (after 48 iterations its equations were still off by 1.87). \
             Try a load torque above 0: without load nothing presses the teeth together, they float in the \
             backlash, and no steady state may exist."
        );
        // Under load, each computation its own advice.
        let load = loaded("");
        assert!(load);
        let hbm = explain(&e, Task::HarmonicBalance, load);
        assert!(hbm.contains("Try more harmonics"), "{hbm}");
        let shooting = explain(&e, Task::Shooting, load);
        assert!(shooting.contains("shooting branches off"), "{shooting}");
        for t in [hbm, shooting] {
            for raw in ["Newton", "Omega =", "residual", "e0"] {
                assert!(!t.contains(raw), "{raw} in {t}");
            }
        }
        let diverged = SolverError::Diverged {
            mesh: "s1a1".into(),
            delta_m: -3.21e-3,
            bound_m: 2.99e-3,
            t_s: 0.01,
        };
        let text = explain(&diverged, Task::SteadyState, load);
        assert!(
            text.contains("3.21 mm") && text.contains("Try another Ω"),
            "{text}"
        );
        // A tiny residual is written so that it reads.
        assert_eq!(sci(3.368e-4), "3.4e-4");
    }
}
