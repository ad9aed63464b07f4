//! The other readings of what the paper leaves open, computed where
//! gearshock can: the TE on every mesh instead of the small sun's three
//! (Figs. 4-11), and the figures' backlash as the whole gap instead of
//! half of it.

use super::orbits;
use super::record::{FIG4_BACKLASH, FIG8_TE};
use super::runs::Runs;
use super::scale::Scale;
use super::sweeps::{self, Case, Sweep};
use crate::failure::Failure;
use serde::{Deserialize, Serialize};

/// The TE on every mesh (`--set`s added to each command).
pub const EVERY_MESH: &str = " --set te_meshes=all";

/// The figures recomputed under one reading.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Reading {
    /// The settings added to every command.
    pub extra: String,
    /// Fig. 4's backlash (µm).
    pub fig4_backlash_um: u32,
    /// Figs. 8-11's backlashes (µm).
    pub backlashes_um: Vec<u32>,
    /// Fig. 4's sweeps, one per TE.
    pub fig4: Vec<Sweep>,
    /// Fig. 8's sweeps, one per backlash.
    pub fig8: Vec<Sweep>,
    /// Figs. 5-7 and 9-11.
    pub orbits: Vec<orbits::Row>,
}

/// Both other readings.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Readings {
    /// The TE on every mesh.
    pub every_mesh: Reading,
    /// The backlash as the whole gap: every b halved.
    pub full_gap: Reading,
}

fn specs() -> [(String, u32, Vec<u32>); 2] {
    let halve = |b: u32| b / 2;
    [
        (
            EVERY_MESH.to_string(),
            FIG4_BACKLASH,
            orbits::BACKLASHES.to_vec(),
        ),
        (
            String::new(),
            halve(FIG4_BACKLASH),
            orbits::BACKLASHES.map(halve).to_vec(),
        ),
    ]
}

fn cases(extra: &str, fig4_b: u32, backlashes: &[u32]) -> (Vec<Case>, Vec<Case>) {
    let case = |b: u32, te: u32| Case {
        backlash_um: b,
        te_um: te,
        extra: extra.to_string(),
    };
    (
        orbits::TES.iter().map(|&te| case(fig4_b, te)).collect(),
        backlashes.iter().map(|&b| case(b, FIG8_TE)).collect(),
    )
}

/// Every command line of both readings.
pub fn lines(scale: &Scale) -> Vec<String> {
    let mut out = Vec::new();
    for (extra, fig4_b, backlashes) in specs() {
        let (fig4, fig8) = cases(&extra, fig4_b, &backlashes);
        for c in fig4.iter().chain(&fig8) {
            out.extend(c.lines(false));
        }
        out.extend(orbits::lines(scale, &extra, &backlashes, fig4_b));
    }
    out
}

/// Reads both readings off the runs.
pub fn compute(runs: &Runs, scale: &Scale) -> Result<Readings, Failure> {
    let [every, full] = specs().map(|(extra, fig4_b, backlashes)| {
        let (fig4, fig8) = cases(&extra, fig4_b, &backlashes);
        let sweep = |c: &Case| sweeps::compute(runs, scale, c, false);
        Ok::<_, Failure>(Reading {
            fig4: fig4.iter().map(sweep).collect::<Result<_, _>>()?,
            fig8: fig8.iter().map(sweep).collect::<Result<_, _>>()?,
            orbits: orbits::compute(runs, scale, &extra, &backlashes, fig4_b)?,
            extra,
            fig4_backlash_um: fig4_b,
            backlashes_um: backlashes,
        })
    });
    Ok(Readings {
        every_mesh: every?,
        full_gap: full?,
    })
}
