//! Fig. 3: the response with a 60 µm TE as the backlash grows (claim 2),
//! by time integration at the paper's three resonances on both scales,
//! under the mean reading of its E_im, and on the harmonic-balance
//! branches (seven harmonics and the paper's one).

use super::data::{items, omega, stable};
use super::fig2::{incomplete, Hbm, ONE_HARMONIC, PAPER_RESONANCES};
use super::orbits::Orbit;
use super::runs::Runs;
use super::scale::Scale;
use crate::failure::Failure;
use serde::{Deserialize, Serialize};

/// Time integration: `$b`, `$w` filled in.
pub const SIMULATE: &str =
    "gearshock simulate --set backlash_um=$b --set te_um=60 --mesh s1a1 --omega $w";
/// E_im read as a mean (constant) TE.
pub const MEAN: &str = "gearshock simulate --set backlash_um=$b --set te_um=0 --set te_mean_s1a_um=60 --mesh s1a1 --omega $w";
/// The TE on every mesh instead of the small sun's three (the other
/// reading of Table 1), added to [`SIMULATE`].
pub const EVERY_MESH: &str = super::readings::EVERY_MESH;
/// The harmonic-balance branch.
pub const FRF: &str =
    "gearshock frf --set backlash_um=$b --set te_um=60 --mesh s1a1 --omega-from 0.1 --omega-to 2";
/// The backlashes (µm).
pub const BACKLASHES: [u32; 4] = [50, 100, 150, 200];
/// The backlashes of the mean reading (it does not depend on them).
pub const MEAN_BACKLASHES: [u32; 2] = [50, 200];
/// Half the window of Omega over which a branch's largest amplitude is
/// read around each of the paper's resonances.
pub const HALF_WINDOW: f64 = 0.05;
/// The middle of the range where the seven-harmonic branch is checked.
pub const MIDDLE: (f64, f64) = (0.5, 1.7);

/// One backlash by time integration.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Row {
    /// The backlash (µm).
    pub backlash_um: u32,
    /// The orbit at each Omega.
    pub orbits: Vec<Orbit>,
}

/// Fig. 3's record.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Fig3 {
    /// The paper's resonances literally, then matched.
    pub omegas: Vec<f64>,
    /// The time integrations.
    pub rows: Vec<Row>,
    /// The same with the TE on every mesh.
    pub every_mesh: Vec<Row>,
    /// Under the mean reading: (backlash, amplitude of x_s1a1 at each Omega, µm).
    pub mean: Vec<(u32, Vec<f64>)>,
    /// The one-harmonic branch: (backlash, the largest amplitude near each Omega).
    pub one_harmonic: Vec<(u32, Vec<Hbm>)>,
    /// The seven-harmonic branch with the smallest backlash over the
    /// middle of the range: (unstable points, points).
    pub middle_unstable: (usize, usize),
}

/// A command line with the backlash and Omega filled in.
pub fn line(template: &str, b: u32, w: f64) -> String {
    template
        .replace("$b", &b.to_string())
        .replace("$w", &super::words::omega_arg(w))
}

/// A time integration's line, under the default reading or with the TE
/// on every mesh.
pub fn simulate_line(b: u32, w: f64, every_mesh: bool) -> String {
    let l = line(SIMULATE, b, w);
    if every_mesh {
        l.replace(" --mesh", &format!("{EVERY_MESH} --mesh"))
    } else {
        l
    }
}

/// The Omegas: the paper's resonances, literally and matched.
pub fn omegas(scale: &Scale) -> Vec<f64> {
    let mut out = PAPER_RESONANCES.to_vec();
    out.extend(PAPER_RESONANCES.map(|w| scale.matched(w)));
    out
}

/// Every command line of Fig. 3.
pub fn lines(scale: &Scale) -> Vec<String> {
    let mut out = Vec::new();
    for b in BACKLASHES {
        for &w in &omegas(scale) {
            out.push(simulate_line(b, w, false));
            out.push(simulate_line(b, w, true));
        }
        out.push(line(FRF, b, 0.0));
        out.push(format!("{}{ONE_HARMONIC}", line(FRF, b, 0.0)));
    }
    for b in MEAN_BACKLASHES {
        for &w in &omegas(scale) {
            out.push(line(MEAN, b, w));
        }
    }
    out
}

/// Reads Fig. 3 off the runs.
pub fn compute(runs: &Runs, scale: &Scale) -> Result<Fig3, Failure> {
    let omegas = omegas(scale);
    let mut rows = Vec::new();
    let mut every_mesh = Vec::new();
    let mut one_harmonic = Vec::new();
    for b in BACKLASHES {
        for (every, out) in [(false, &mut rows), (true, &mut every_mesh)] {
            let mut orbits = Vec::new();
            for &w in &omegas {
                orbits.push(Orbit::of(&*runs.get(&simulate_line(b, w, every))?));
            }
            out.push(Row {
                backlash_um: b,
                orbits,
            });
        }
        let l = format!("{}{ONE_HARMONIC}", line(FRF, b, 0.0));
        let v = runs.get(&l)?;
        if v["complete"] != true {
            return Err(incomplete(&l));
        }
        let branch = items(&v, "branch");
        let cells = omegas
            .iter()
            .map(|w| Hbm::of(branch, w - HALF_WINDOW, w + HALF_WINDOW))
            .collect();
        one_harmonic.push((b, cells));
    }
    let mut mean = Vec::new();
    for b in MEAN_BACKLASHES {
        let mut cells = Vec::new();
        for &w in &omegas {
            cells.push(Orbit::of(&*runs.get(&line(MEAN, b, w))?).amplitude_um);
        }
        mean.push((b, cells));
    }
    let l = line(FRF, BACKLASHES[0], 0.0);
    let v = runs.get(&l)?;
    if v["complete"] != true {
        return Err(incomplete(&l));
    }
    let middle: Vec<_> = items(&v, "branch")
        .iter()
        .filter(|p| super::data::within(omega(p), MIDDLE.0, MIDDLE.1))
        .collect();
    let unstable = middle.iter().filter(|p| !stable(p)).count();
    Ok(Fig3 {
        omegas,
        rows,
        every_mesh,
        mean,
        one_harmonic,
        middle_unstable: (unstable, middle.len()),
    })
}
