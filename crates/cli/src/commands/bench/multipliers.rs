//! `gearshock bench --multipliers`: how accurate the harmonic balance's
//! Floquet multipliers are. On the benchmark sweep (the default model,
//! Omega 0.1 to 0.5, H = 7, 400 nominal points: the CLI's defaults), each
//! branch point's monodromy is integrated again with 8, 16 (the solver's
//! default) and 32 RK4 steps a period of the fastest mode and compared with
//! 128, apart for orbits whose meshes part (or touch their back flanks)
//! and orbits in constant contact; docs/model.md quotes the figures.

use super::median;
use serde_json::{json, Value};
use solver::hbm::stability::{floquet_with_steps, ORBIT_STEPS_PER_FASTEST};
use solver::hbm::{FrfContinuation, FrfSpec};
use solver::steady::{Impact, Model};
use solver::SolverError;

/// The step counts compared with the reference.
const STEPS: [f64; 3] = [8.0, ORBIT_STEPS_PER_FASTEST, 32.0];
/// The reference: RK4's error falls as the fourth power of the step, so
/// at 128 steps it is 4 096 times below the default's.
const REFERENCE_STEPS: f64 = 128.0;
/// A point is stable when its largest modulus is at most this (as the
/// continuation decides it).
const STABLE_BELOW: f64 = 1.0 + 1e-6;

/// The multipliers' accuracy on the benchmark sweep (`quick`: 50 nominal
/// points over Omega 0.1 to 0.2).
pub(super) fn multiplier_accuracy(model: &Model, quick: bool) -> Result<Value, SolverError> {
    let (omega_to, points) = if quick { (0.2, 50) } else { (0.5, 400) };
    let mut spec = FrfSpec::new(0.1, omega_to, points);
    spec.harmonics = 7;
    let mut c = FrfContinuation::new(model, spec)?;
    let mut branch = Vec::new();
    while !c.is_finished() {
        branch.extend(c.advance(64)?);
    }
    // Per group (constant contact, impacting) and step count: the
    // distances of the largest modulus from the reference's, with their
    // Omega, and the points whose stability differs.
    let mut dist: [Vec<Vec<(f64, f64)>>; 2] =
        std::array::from_fn(|_| vec![Vec::new(); STEPS.len()]);
    let mut flips = [[0usize; STEPS.len()]; 2];
    let mut failed = 0;
    let asm = c.assembly();
    for p in &branch {
        let impacting = p
            .meshes
            .iter()
            .any(|m| matches!(m.impact, Impact::SingleSided | Impact::DoubleSided));
        let g = usize::from(impacting);
        let radius = |steps| {
            floquet_with_steps(asm, &p.coefficients, p.omega, steps)
                .map(|f| f.spectral_radius())
                .filter(|r| r.is_finite())
        };
        let Some(reference) = radius(REFERENCE_STEPS) else {
            failed += 1;
            continue;
        };
        for (k, &steps) in STEPS.iter().enumerate() {
            let Some(r) = radius(steps) else {
                failed += 1;
                continue;
            };
            dist[g][k].push(((r - reference).abs(), p.omega));
            if (r <= STABLE_BELOW) != (reference <= STABLE_BELOW) {
                flips[g][k] += 1;
            }
        }
    }
    let group = |g: usize| -> Value {
        let rows: Vec<Value> = STEPS
            .iter()
            .enumerate()
            .map(|(k, &steps)| {
                let d = &dist[g][k];
                let (largest, at) =
                    d.iter()
                        .copied()
                        .fold((0.0, f64::NAN), |a, b| if b.0 > a.0 { b } else { a });
                json!({
                    "steps_per_fastest_period": steps,
                    "largest_difference": largest,
                    "at_omega": at,
                    "median_difference": median(d.iter().map(|x| x.0).collect()),
                    "stability_differs_at": flips[g][k],
                })
            })
            .collect();
        json!({ "points": dist[g].first().map_or(0, Vec::len), "against_reference": rows })
    };
    // The observed order of convergence: log2 of the ratio of the largest
    // differences at 8 and 16 steps over all points (4 for RK4).
    let largest = |k: usize| {
        dist.iter()
            .flat_map(|d| d[k].iter().map(|x| x.0))
            .fold(0.0, f64::max)
    };
    Ok(json!({
        "sweep": {
            "omega_from": 0.1,
            "omega_to": omega_to,
            "harmonics": 7,
            "nominal_points": points,
            "branch_points": branch.len(),
        },
        "reference_steps_per_fastest_period": REFERENCE_STEPS,
        "default_steps_per_fastest_period": ORBIT_STEPS_PER_FASTEST,
        "constant_contact": group(0),
        "impacting": group(1),
        "observed_order_8_to_16": (largest(0) / largest(1)).log2(),
        "monodromies_failed": failed,
    }))
}
