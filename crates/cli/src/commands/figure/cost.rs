//! The work and memory budget of a whole figure, checked before any panel
//! is computed: the same caps as `bifurcation`, `simulate` and `frf`, summed
//! over the figure's members (one per panel), with each member's periods
//! priced by its own model's stiffest mode ([`StepCost`]).

use super::{bif_spec, run_options, FigureArgs, Member};
use crate::budget::{check_work, StepCost, MAX_FRF_WORK, MAX_SAMPLES};
use crate::failure::{usage, Failure};

/// What the figure's panels compute.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Panels {
    /// A bifurcation sweep per member.
    Bifurcation,
    /// One steady state per member.
    Orbits,
    /// A harmonic-balance branch per member.
    FrequencyResponse,
}

/// Checks the figure's whole work against the caps; `id` names it.
pub(crate) fn check(
    id: &str,
    panels: Panels,
    members: &[&Member],
    args: &FigureArgs,
) -> Result<(), Failure> {
    match panels {
        Panels::FrequencyResponse => {
            let mut work = 0u64;
            for m in members {
                let v = &m.settings.view;
                let points = u64::from(args.points.unwrap_or(v.fr_points));
                work += points * (2 * u64::from(v.harmonics) + 1).pow(3);
            }
            if work > MAX_FRF_WORK {
                return Err(usage(format!(
                    "figure {id}: {} branches of --points x (2 x harmonics + 1)^3 = {work}, more than the \
                     {MAX_FRF_WORK} one command may take: use fewer --points",
                    members.len()
                )));
            }
            Ok(())
        }
        Panels::Bifurcation | Panels::Orbits => {
            let (mut periods, mut steps, mut samples) = (0u64, 0.0, 0u64);
            for m in members {
                let run = run_options(m, args);
                let per_state = u64::from(run.transient_periods) + u64::from(run.record_periods);
                let cost = StepCost::of(&m.model);
                let (states, per_period) = if panels == Panels::Bifurcation {
                    let spec = bif_spec(m, args);
                    let states = u64::from(spec.points) * spec.directions.list().len() as u64;
                    samples += states * u64::from(run.record_periods);
                    let mean = cost.mean_per_period(spec.omega_from, spec.omega_to, spec.points);
                    (states, mean)
                } else {
                    (1, cost.per_period(m.settings.view.omega))
                };
                periods += states * per_state;
                steps += (states * per_state) as f64 * per_period;
            }
            if samples > MAX_SAMPLES {
                return Err(usage(format!(
                    "figure {id}: {samples} Poincaré samples (points x directions x --record-periods over \
                     {} panels), over the {MAX_SAMPLES} kept at most: fewer --points or --record-periods, \
                     or --shard i/n",
                    members.len()
                )));
            }
            let mean = if periods == 0 {
                0.0
            } else {
                steps / periods as f64
            };
            check_work(
                periods,
                mean,
                &format!(
                    "figure {id}: {} panels x points x (--transient-periods + --record-periods)",
                    members.len()
                ),
                "fewer points or periods, or --shard i/n",
            )
        }
    }
}
