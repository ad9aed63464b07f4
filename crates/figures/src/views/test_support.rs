//! Test fixtures shared by the views' tests: a view context over the
//! default Omega range, harmonic-balance points and time-integration
//! extremes built from a few numbers.

use super::ViewContext;
use crate::protocol::{HbmMesh, HbmSample, MapSample, MeshExtremes, Motion, OmegaResult, Regime};

/// The view context of the tests: Omega 0.1 to 2, 0.5 selected, mesh s1a1,
/// no natural frequencies.
pub fn ctx() -> ViewContext {
    ViewContext {
        omega_from: 0.1,
        omega_to: 2.0,
        selected_omega: 0.5,
        mesh_label: "s1a1".into(),
        natural: vec![],
        speed: Default::default(),
    }
}

/// A harmonic-balance point at `omega` with one `(min, max)` (µm) per mesh,
/// no impact, of the given stability, in piece 0.
pub fn hbm_point(omega: f64, meshes: &[(f64, f64)], stable: bool) -> HbmSample {
    HbmSample {
        omega,
        meshes: meshes
            .iter()
            .map(|&(lo, hi)| HbmMesh {
                rel_min_um: lo,
                rel_max_um: hi,
                regime: Regime::NoImpact,
            })
            .collect(),
        stable: Some(stable),
        bifurcation: None,
        piece: 0,
    }
}

/// A harmonic-balance point with one mesh peaking at `hi` µm in `regime`.
pub fn hbm_peak(omega: f64, hi: f64, regime: Regime, stable: bool) -> HbmSample {
    let mut p = hbm_point(omega, &[(0.0, hi)], stable);
    p.meshes[0].regime = regime;
    p
}

/// One mesh's time-integration extremes (µm), single-sided impact, with
/// the dynamic factor `df`.
pub fn ext(lo: f64, hi: f64, df: Option<f64>) -> MeshExtremes {
    MeshExtremes {
        rel_min_um: lo,
        rel_max_um: hi,
        regime: Regime::SingleSided,
        dynamic_factor: df,
    }
}

/// A map cell at `(row, column)` with its regime and period (Omega and
/// value left at 0: the stores place cells by their indices).
pub fn map_cell(row: u32, column: u32, regime: Regime, period: Option<u32>) -> MapSample {
    MapSample {
        row,
        column,
        omega: 0.0,
        value: 0.0,
        regime,
        period,
        error: None,
    }
}

/// A period-1 exact steady state at Ω 0.84 on s1a1 (100 µm backlash,
/// single-sided impact): x = 110 + 30 sin, 20 recorded periods.
pub fn omega_result() -> OmegaResult {
    let n = 64 * 20;
    let x: Vec<f64> = (0..n)
        .map(|k| 110.0 + 30.0 * (k as f64 / 64.0 * std::f64::consts::TAU).sin())
        .collect();
    let v: Vec<f64> = (0..n)
        .map(|k| 0.5 * (k as f64 / 64.0 * std::f64::consts::TAU).cos())
        .collect();
    OmegaResult {
        omega: 0.84,
        mesh: 0,
        mesh_name: "s1a1".into(),
        backlash_um: 100.0,
        regime: Regime::SingleSided,
        period: Some(1),
        motion: Motion::PeriodicExact {
            period: 1,
            max_multiplier_modulus: 0.9,
            newton_iterations: 0,
        },
        dynamic_factor: Some(1.4),
        mesh_freq_hz: 4500.0,
        transient_periods_run: 100,
        settled: true,
        samples_per_period: 64,
        record_periods: 20,
        x_um: x,
        xdot_m_s: v,
        poincare_x_um: vec![110.0; 20],
        poincare_xdot_m_s: vec![0.5; 20],
        spectrum_order: vec![0.0, 1.0, 2.0],
        spectrum_um: vec![110.0, 30.0, 0.1],
        all_meshes: vec![],
        anim: Default::default(),
        load_sharing: Vec::new(),
        force_orders: None,
        steps: 1,
        cli_json: "{}".into(),
        preview: false,
        end_state: vec![],
    }
}

/// A map grid of backlash rows, 0 ..= `value_to` µm in `rows` rows, over
/// Omega 0.1 ..= 2.0 in 20 columns (step 0.1).
pub fn backlash_grid(value_to: f64, rows: u32) -> crate::views::map::MapGrid {
    crate::views::map::MapGrid {
        key: "backlash_um".into(),
        omega_from: 0.1,
        omega_to: 2.0,
        omega_points: 20,
        value_from: 0.0,
        value_to,
        value_points: rows,
    }
}
