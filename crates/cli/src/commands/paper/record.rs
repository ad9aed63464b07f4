//! The record: every number the document and the page quote about the
//! paper, read off the commands they quote. Computing it runs each command
//! once, all that are known in advance at once on several cores.

use super::advice::{self, Advice};
use super::fig2::{self, Fig2};
use super::fig3::{self, Fig3};
use super::orbits;
use super::readings::{self, Readings};
use super::runs::Runs;
use super::scale::{self, Scale};
use super::sweeps::{self, Case, Chaos, Sweep};
use crate::failure::Failure;
use serde::{Deserialize, Serialize};

/// Fig. 4's backlash (µm).
pub const FIG4_BACKLASH: u32 = 200;
/// Fig. 8's TE (µm).
pub const FIG8_TE: u32 = 20;

/// Everything the document and the page's claims quote.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Record {
    /// The transient budget of every run (mesh periods).
    pub transient_periods: u64,
    /// The static deflection of s1a1 under the load beyond the backlash
    /// (µm): x at rest is b plus this.
    pub static_deflection_um: f64,
    /// The small sun's teeth.
    pub teeth_s1: u32,
    /// The ring's base radius, where its support acts by default (mm).
    pub ring_base_radius_mm: f64,
    /// The frequency scale.
    pub scale: Scale,
    /// Fig. 2 (claim 1, conclusion 1).
    pub fig2: Fig2,
    /// Fig. 3 (claim 2).
    pub fig3: Fig3,
    /// Fig. 4: one sweep per TE at 200 µm backlash (claims 3-5).
    pub fig4: Vec<Sweep>,
    /// Fig. 8: one sweep per backlash at 20 µm TE (claims 8, 9).
    pub fig8: Vec<Sweep>,
    /// Fig. 8's Lyapunov exponents.
    pub chaos: Vec<Chaos>,
    /// Figs. 5-7 and 9-11 (claims 6, 7a, 7b).
    pub orbits: Vec<orbits::Row>,
    /// Claim 10.
    pub advice: Advice,
    /// The other readings.
    pub readings: Readings,
}

/// Fig. 4's cases.
pub fn fig4_cases() -> Vec<Case> {
    orbits::TES
        .iter()
        .map(|&te| Case::new(FIG4_BACKLASH, te))
        .collect()
}

/// Fig. 8's cases.
pub fn fig8_cases() -> Vec<Case> {
    orbits::BACKLASHES
        .iter()
        .map(|&b| Case::new(b, FIG8_TE))
        .collect()
}

/// Runs every command and reads the record off them.
pub fn compute(runs: &Runs) -> Result<Record, Failure> {
    runs.prefetch(&scale::lines())?;
    let scale = scale::compute(runs)?;
    let mut lines = fig2::lines();
    lines.extend(fig3::lines(&scale));
    for case in fig4_cases()
        .iter()
        .chain(&fig8_cases())
        .chain(&advice::cases())
    {
        lines.extend(case.lines(true));
    }
    lines.extend(orbits::BACKLASHES.map(sweeps::lyapunov_line));
    lines.extend(orbits::lines(
        &scale,
        "",
        &orbits::BACKLASHES,
        FIG4_BACKLASH,
    ));
    lines.extend(advice::lines());
    lines.extend(readings::lines(&scale));
    runs.prefetch(&lines)?;

    let sweep = |c: &Case| sweeps::compute(runs, &scale, c, true);
    let fig4: Vec<Sweep> = fig4_cases().iter().map(sweep).collect::<Result<_, _>>()?;
    let fig8: Vec<Sweep> = fig8_cases().iter().map(sweep).collect::<Result<_, _>>()?;
    let claim10: Vec<Sweep> = advice::cases()
        .iter()
        .map(sweep)
        .collect::<Result<_, _>>()?;
    let modes = runs.get(scale::MODES)?;
    let params = runs.get(scale::PARAMS)?;
    let coarse = runs.get(&fig4_cases()[0].sweep())?;
    let number = |v: &serde_json::Value| super::data::f(v);
    let whole = |v: &serde_json::Value, what: &str| {
        super::lookup::need(v.as_u64().and_then(|n| u32::try_from(n).ok()), what)
    };
    Ok(Record {
        transient_periods: u64::from(whole(
            &coarse["spec"]["transient_periods"],
            "the sweeps' transient budget",
        )?),
        static_deflection_um: super::data::um(&modes["static_mesh_deflection_m"]["s1a1"])
            - number(&params["backlash_s1a_um"]),
        teeth_s1: whole(&params["teeth_s1"], "the small sun's teeth")?,
        ring_base_radius_mm: number(&params["module_mm"]) * number(&params["teeth_r"]) / 2.0
            * number(&params["pressure_angle_deg"]).to_radians().cos(),
        fig2: fig2::compute(runs, &scale)?,
        fig3: fig3::compute(runs, &scale)?,
        chaos: orbits::BACKLASHES
            .iter()
            .map(|&b| sweeps::chaos(runs, b))
            .collect::<Result<_, _>>()?,
        orbits: orbits::compute(runs, &scale, "", &orbits::BACKLASHES, FIG4_BACKLASH)?,
        advice: advice::compute(runs, &claim10.iter().collect::<Vec<_>>())?,
        readings: readings::compute(runs, &scale)?,
        fig4,
        fig8,
        scale,
    })
}
