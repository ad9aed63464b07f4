//! Claim 10 as advice: the windows of Omega where no mesh's drive flanks
//! part, from the finer sweeps, with the narrow spikes of impact inside
//! them; and the same windows seen another way, on the harmonic-balance
//! branch without backlash (where every mesh keeps x above 0).

use super::data::Spans;
use super::fig2::{contact_of, line, SINE};
use super::runs::Runs;
use super::sweeps::{Case, Sweep};
use crate::failure::Failure;
use serde::{Deserialize, Serialize};

/// The cases: (backlash µm, TE µm). The TE rows of Fig. 4 at 200 µm and
/// the backlash rows of Fig. 8 at 20 µm.
pub const CASES: [(u32, u32); 5] = [(200, 0), (200, 20), (200, 30), (50, 20), (100, 20)];
/// A run of impacts narrower than this (between the free points around
/// it) is a spike inside a window, not its end: one step of the grid that
/// covers the whole range.
pub const SPIKE: f64 = 0.01;

/// A narrow run of impacts inside a window.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq)]
pub struct Spike {
    /// The first and last Omega where flanks part.
    pub parts: (f64, f64),
    /// The last free Omega before and the first after: the spike is
    /// narrower than this.
    pub between: (f64, f64),
}

/// A window of Omega free of impacts.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Window {
    /// The first and last free Omega.
    pub free: (f64, f64),
    /// The spikes inside.
    pub spikes: Vec<Spike>,
}

/// One case's windows.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct CaseWindows {
    /// Backlash (µm).
    pub backlash_um: u32,
    /// TE (µm).
    pub te_um: u32,
    /// Where no mesh's drive flanks part.
    pub every_mesh: Vec<Window>,
    /// Where those of s1a1 do not.
    pub s1a1: Vec<Window>,
    /// The first Omega where some mesh's back flanks touch, and the mesh.
    pub first_back: Option<(f64, String)>,
    /// The harmonic-balance branch without backlash, the same TE: where
    /// every mesh keeps x at or above 0.
    pub linear_kept: Spans,
    /// The lowest and highest Omega swept.
    pub range: (f64, f64),
}

/// Claim 10's record.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Advice {
    /// Each case.
    pub cases: Vec<CaseWindows>,
}

/// The cases as sweeps' settings.
pub fn cases() -> Vec<Case> {
    CASES.iter().map(|&(b, te)| Case::new(b, te)).collect()
}

/// The harmonic-balance branches without backlash: one per TE.
pub fn lines() -> Vec<String> {
    let mut tes: Vec<u32> = CASES.iter().map(|c| c.1).collect();
    tes.sort_unstable();
    tes.dedup();
    tes.iter().map(|&te| line(SINE, "s1a", te, false)).collect()
}

/// The windows from the runs where flanks part and where they do not: a
/// run of impacts narrower than [`SPIKE`] between two free runs at least
/// as wide is a spike inside one window.
pub fn windows(parts: &Spans, free: &Spans) -> Vec<Window> {
    let mut out: Vec<Window> = Vec::new();
    let mut last_run = (f64::NAN, f64::NAN);
    for &(a, b) in free {
        let wide = |(p, q): (f64, f64)| q - p >= SPIKE;
        let joined = out.last_mut().and_then(|last| {
            // The run of impacts between this free run and the last one.
            let gap = parts
                .iter()
                .copied()
                .find(|&(p, q)| p > last.free.1 && q < a)?;
            (a - last.free.1 < SPIKE && wide(last_run) && wide((a, b))).then_some((last, gap))
        });
        last_run = (a, b);
        match joined {
            Some((last, gap)) => {
                last.spikes.push(Spike {
                    parts: gap,
                    between: (last.free.1, a),
                });
                last.free.1 = b;
            }
            None => out.push(Window {
                free: (a, b),
                spikes: Vec::new(),
            }),
        }
    }
    out
}

/// Reads claim 10 off the sweeps of its cases and the runs.
pub fn compute(runs: &Runs, sweeps: &[&Sweep]) -> Result<Advice, Failure> {
    let mut cases = Vec::new();
    for s in sweeps {
        let Some(fine) = &s.fine else {
            return Err(Failure {
                code: 1,
                message: format!("claim 10 needs the finer sweeps of {}", s.case.sweep()),
            });
        };
        let v = runs.get(&line(SINE, "s1a", s.case.te_um, false))?;
        let range = (
            super::sweeps::FINE_GRIDS[0].0,
            super::sweeps::FINE_GRIDS[0].1,
        );
        cases.push(CaseWindows {
            backlash_um: s.case.backlash_um,
            te_um: s.case.te_um,
            every_mesh: windows(&fine.any.0, &fine.any.1),
            s1a1: windows(&fine.s1a1.0, &fine.s1a1.1),
            first_back: fine.first_back.clone(),
            linear_kept: contact_of(&v, "sine, small-sun meshes", s.case.te_um).kept,
            range,
        });
    }
    Ok(Advice { cases })
}
