//! The values of the document's sections before the claims: how the
//! numbers are read, the readings, the frequency scale and the impact
//! criterion, each with the premises its fixed words rest on.

use super::fig2::READINGS;
use super::fill::Values;
use super::lookup::{anchor, back_words, need, row, stable_only, stable_um};
use super::record::Record;
use super::scale::PAPER_SECTIONS;
use super::sweeps::{Sweep, AMPLITUDE_AT, FINE_GRIDS, LYAPUNOV_GRID};
use super::words::{
    and, arrows, grouped, inside, ints, list, om, om3, omega_arg, over, spans3, spans_and, um,
    width,
};
use crate::failure::Failure;

/// Sets every value of the sections before the claims.
pub fn set(v: &mut Values, r: &Record) -> Result<(), Failure> {
    read(v, r)?;
    readings(v, r)?;
    scale(v, r)?;
    impact(v, r)
}

fn read(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let te30 = need(r.fig4.last(), "Fig. 4's sweeps")?;
    v.set("read.delta_30", um(te30.delta_at_025_um));
    v.set("read.x_30", um(te30.amplitude_at[1]));
    v.set("read.w_low", omega_arg(AMPLITUDE_AT[1]));
    v.ensure(
        te30.amplitude_at[1] < te30.delta_at_025_um / 3.0,
        "below the first natural frequency delta swings with the TE while x barely moves",
    );
    v.set("read.static", um(r.static_deflection_um));
    v.set("read.transient", r.transient_periods.to_string());
    v.set("read.omega_ref", grouped(r.scale.omega_ref_rad_s));
    v.set("read.rpm_per_omega", grouped(r.scale.rpm_per_omega));
    Ok(())
}

fn readings(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let s = &r.scale;
    v.set(
        "readings.delta",
        arrows(
            &r.fig4.iter().map(|x| x.delta_at_025_um).collect::<Vec<_>>(),
            um,
        ),
    );
    v.set(
        "readings.x",
        arrows(
            &r.fig4.iter().map(|x| x.amplitude_at[1]).collect::<Vec<_>>(),
            um,
        ),
    );
    // Fig. 2's first-mode peak at 5 µm under each reading.
    let first = anchor(r, s.first_mode)?;
    for (name, (words, _, _)) in ["readings.ec_sine", "readings.ec_s1a", "readings.ec_cosine"]
        .iter()
        .zip(READINGS)
    {
        let cell = row(r, words, false, 5)?.cells[first];
        v.ensure(
            stable_only(&cell),
            "the first-mode peak of each reading is stable",
        );
        v.set(name, um(stable_um(&cell)));
    }
    // The TE on every mesh (Figs. 4-11).
    let every = &r.readings.every_mesh;
    v.set(
        "readings.all_low",
        arrows(
            &every
                .fig4
                .iter()
                .map(|x| x.amplitude_at[1])
                .collect::<Vec<_>>(),
            um,
        ),
    );
    v.set(
        "readings.all_back",
        back_words(&every.fig4, |s| s.case.te_um, " TE"),
    );
    let fig9 = need(
        every.orbits.iter().find(|o| o.figure == 9 && !o.matched),
        "Fig. 9 with the TE on every mesh",
    )?;
    let counts: Vec<usize> = fig9.orbits.iter().map(|o| o.back_flanks.len()).collect();
    v.ensure(
        counts.windows(2).any(|c| c[0] != c[1]),
        "with the TE on every mesh the backlash acts at once at Fig. 9's Ω",
    );
    v.set(
        "readings.all_7a",
        format!(
            "at Ω {} the back flanks of {} meshes touch with {} µm",
            om(fig9.paper_omega),
            and(&counts.iter().map(usize::to_string).collect::<Vec<_>>()),
            ints(&fig9.values)
        ),
    );
    // The sun's eccentricity: once per revolution relative to the carrier.
    let top = 2.0 / f64::from(r.teeth_s1);
    v.set("readings.teeth_s1", r.teeth_s1.to_string());
    v.set("readings.ecc_top", om3(top));
    v.ensure(
        top < s.first_mode / 4.0,
        "once per revolution lies below a quarter of the first natural frequency",
    );
    // E_im as a mean TE.
    let (_, mean) = need(r.fig3.mean.first(), "Fig. 3's mean reading")?;
    let n = r.fig3.omegas.len() / 2;
    v.set("readings.mean", list(&mean[..n], um));
    let te0 = need(r.fig4.first(), "Fig. 4's sweep without TE")?;
    v.ensure(
        r.fig3.mean.iter().all(|(_, xs)| {
            xs.iter()
                .zip(&mean[..])
                .all(|(a, b)| (a - b).abs() < 0.01 * b.abs().max(1.0))
        }),
        "under the mean reading x does not depend on the backlash",
    );
    let at04 = te0.amplitude_at[2];
    v.ensure(
        (mean[0] - at04).abs() < 0.01 * at04,
        "under the mean reading x is that of no TE",
    );
    // The backlash as the whole gap.
    let gap = &r.readings.full_gap;
    v.set("readings.gap_fig4", gap.fig4_backlash_um.to_string());
    v.set("readings.gap_fig8", ints(&gap.backlashes_um));
    v.set(
        "readings.gap_back",
        back_words(&gap.fig4, |s| s.case.te_um, " TE"),
    );
    v.set(
        "readings.gap_9",
        back_words(&gap.fig8, |s| s.case.backlash_um, ""),
    );
    let order = |sweeps: &[Sweep]| {
        sweeps
            .windows(2)
            .all(|p| width(&p[0].any_back) >= width(&p[1].any_back))
            && sweeps.first().is_some_and(|x| !x.any_back.is_empty())
    };
    v.ensure(
        order(&gap.fig8),
        "read as the whole gap, the smallest backlash still reaches the back flanks most",
    );
    // The method.
    let h7 = row(r, READINGS[0].0, false, 5)?.cells[first];
    let h1 = row(r, READINGS[0].0, true, 5)?.cells[first];
    v.ensure(
        stable_only(&h7) && stable_only(&h1) && stable_um(&h1) > stable_um(&h7),
        "the one-harmonic first-mode peak is larger, on stable points",
    );
    v.set("readings.h7", um(stable_um(&h7)));
    v.set("readings.h1", um(stable_um(&h1)));
    let halves = [
        s.first_mode / 2.0,
        s.rotational.get(1).map_or(f64::NAN, |w| w / 2.0),
    ];
    v.ensure(
        r.fig2.rows.iter().filter(|x| x.one_harmonic).all(|x| {
            x.peaks
                .iter()
                .all(|(w, _)| halves.iter().all(|h| (w - h).abs() > 0.01))
        }),
        "the one-harmonic branches have no superharmonic peak",
    );
    let literal = &r.fig3.one_harmonic;
    v.ensure(
        literal
            .iter()
            .all(|(_, cells)| cells[..n].iter().all(|c| c.unstable_um.is_some())),
        "the one-harmonic branch of Fig. 3 takes its largest amplitude near the paper's three Ω on unstable points",
    );
    v.set("readings.ring", format!("{:.1}", r.ring_base_radius_mm));
    let ratio = (r.ring_base_radius_mm / 15.79).powi(2);
    v.ensure(
        (90.0..110.0).contains(&ratio),
        "the printed ring radius softens the support a hundredfold",
    );
    Ok(())
}

fn scale(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let s = &r.scale;
    let modes3 = |xs: &[f64]| xs.iter().map(|&w| om3(w)).collect::<Vec<_>>().join(", ");
    v.set("scale.rotational", modes3(&s.rotational));
    v.set("scale.planet", modes3(&s.planet));
    v.set("scale.printed", modes3(&s.printed_rotational));
    v.set("scale.bands", spans3(&s.bands));
    v.set("scale.factor", format!("{:.2}", s.factor));
    let reference = row(r, READINGS[0].0, false, 30)?;
    v.set("scale.peaks", super::tables::peaks(&reference.peaks));
    v.ensure(
        reference.peaks.iter().all(|p| p.1),
        "every peak of Fig. 2's response is on a stable point",
    );
    v.set("scale.peak_words", "every one of them on a stable point");
    // The paper's 1.2 and 1.4 read literally.
    let mut all: Vec<(f64, bool)> = s.rotational.iter().map(|&w| (w, true)).collect();
    all.extend(s.planet.iter().map(|&w| (w, false)));
    let nearest = |w: f64| {
        all.iter()
            .copied()
            .min_by(|a, b| (a.0 - w).abs().total_cmp(&(b.0 - w).abs()))
    };
    let n12 = need(nearest(1.2), "the modes")?;
    let n14 = need(nearest(1.4), "the modes")?;
    v.ensure(
        s.rotational.get(3) == Some(&n12.0),
        "the mode nearest the paper's 1.2 is the fourth rotational mode",
    );
    v.ensure(!n14.1, "the mode nearest the paper's 1.4 is a planet mode");
    v.ensure(
        reference
            .peaks
            .iter()
            .all(|(w, _)| (w - n14.0).abs() > 0.03),
        "the response has no peak at the planet mode",
    );
    v.set("scale.near_12", om3(n12.0));
    v.set("scale.near_14", om3(n14.0));
    // The peaks: the first two modes and half of each.
    let m1 = s.first_mode;
    let m2 = need(s.rotational.get(1).copied(), "the second mode")?;
    let targets = [
        ("scale.peak_half_1", m1 / 2.0),
        ("scale.peak_1", m1),
        ("scale.peak_half_2", m2 / 2.0),
        ("scale.peak_2", m2),
    ];
    v.ensure(
        reference.peaks.len() == targets.len()
            && reference
                .peaks
                .iter()
                .zip(targets)
                .all(|((w, _), (_, t))| (w - t).abs() < 0.005),
        "the response peaks at the first two modes and at half of each, and nowhere else",
    );
    for ((w, _), (name, _)) in reference.peaks.iter().zip(targets) {
        v.set(name, om3(*w));
    }
    v.ensure(
        reference.peaks.iter().all(|(w, _)| (w - 0.4).abs() > 0.05)
            && all.iter().all(|(w, _)| (w - 0.4).abs() > 0.05),
        "nothing lies near 0.4",
    );
    // The matched scale.
    let m08 = s.matched(0.8);
    v.set("scale.m08", om3(m08));
    v.set("scale.m04", om3(s.matched(0.4)));
    let band = need(
        s.band_of(m08),
        "a band of parametric instability at the paper's 0.8 matched",
    )?;
    v.ensure(
        s.bands.first() == Some(&band),
        "the paper's 0.8 matched lies in the first band of parametric instability",
    );
    v.set(
        "scale.m08_band",
        format!(
            "inside gearshock's first band of parametric instability ({}–{})",
            om3(band.0),
            om3(band.1)
        ),
    );
    let m3 = need(s.rotational.get(2).copied(), "the third mode")?;
    v.set("scale.mode_3", om3(m3));
    v.ensure(
        (s.matched(1.4) - m3).abs() < 0.01,
        "matched, the paper's 1.4 falls on the third mode",
    );
    v.ensure(
        all.iter().all(|(w, _)| (w - s.matched(1.2)).abs() > 0.05),
        "matched, the paper's 1.2 falls on no mode",
    );
    let onset = need(
        r.chaos.first().and_then(|c| c.chaotic.first()),
        "the onset of chaos",
    )?
    .0;
    v.ensure(
        m08 < onset && onset - m08 < 0.05,
        "the paper's 0.8 matched lies just below the onset of chaos",
    );
    let sections = |factor: f64, digits: fn(f64) -> String| {
        let mut lo = 0.0;
        let mut out = Vec::new();
        for (i, (_, _, hi)) in PAPER_SECTIONS.iter().enumerate() {
            let hi = hi * factor;
            out.push(if i == 0 {
                format!("up to {}", digits(hi))
            } else {
                format!("{}–{}", digits(lo), digits(hi))
            });
            lo = hi;
        }
        and(&out)
    };
    v.set("scale.sections", sections(1.0, omega_arg));
    v.set("scale.sections_matched", sections(s.factor, om3));
    v.set(
        "scale.low",
        format!("Ω up to {}", omega_arg(PAPER_SECTIONS[0].2)),
    );
    v.set(
        "scale.low_matched",
        format!("up to {}", om3(PAPER_SECTIONS[0].2 * s.factor)),
    );
    v.set(
        "scale.printed_first",
        om3(s.printed_rotational.first().copied().unwrap_or(f64::NAN)),
    );
    let shift = s
        .rotational
        .iter()
        .zip(&s.printed_rotational)
        .skip(1)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    v.set("scale.printed_shift", om3(shift));
    v.ensure(
        s.printed_rotational
            .first()
            .is_some_and(|w| *w < m1 / 5.0 && (w - 0.4).abs() > 0.1),
        "the printed ring radius drops the first mode far below 0.4",
    );
    Ok(())
}

fn impact(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let s = &r.scale;
    let steps: Vec<f64> = FINE_GRIDS
        .iter()
        .map(|(a, b, n)| (b - a) / f64::from(n - 1))
        .collect();
    let contains = |i: usize, w: f64| FINE_GRIDS[i].0 <= w && w <= FINE_GRIDS[i].1;
    v.ensure(
        contains(1, s.first_mode) && contains(1, s.matched(0.8)) && contains(2, s.first_mode / 2.0),
        "the finer grids cover the first mode, the first band and half the first mode",
    );
    v.set(
        "impact.fine_words",
        format!(
            "steps of {} over Ω {}–{}, of {} over {}–{} (the first mode, half the second and the first band of parametric instability) and of {} over {}–{} (half the first natural frequency)",
            omega_arg(steps[0]),
            omega_arg(FINE_GRIDS[0].0),
            omega_arg(FINE_GRIDS[0].1),
            omega_arg(steps[1]),
            omega_arg(FINE_GRIDS[1].0),
            omega_arg(FINE_GRIDS[1].1),
            omega_arg(steps[2]),
            omega_arg(FINE_GRIDS[2].0),
            omega_arg(FINE_GRIDS[2].1),
        ),
    );
    v.ensure(
        contains(1, s.rotational.get(1).map_or(f64::NAN, |w| w / 2.0)),
        "the finer grid covers half the second mode",
    );
    let (from, to, n) = LYAPUNOV_GRID;
    v.set("impact.lyapunov_from", om(from));
    v.set("impact.lyapunov_to", om(to));
    v.set("impact.lyapunov_step", om((to - from) / f64::from(n - 1)));
    v.set("impact.chaos", omega_arg(super::sweeps::CHAOS));
    let smallest = need(r.fig8.first(), "Fig. 8's sweeps")?;
    v.set("impact.smallest", smallest.case.backlash_um.to_string());
    v.set("impact.negative", spans_and(&smallest.x_negative));
    v.set("impact.s1a1_back", over(&smallest.s1a1_back));
    v.ensure(
        inside(&smallest.s1a1_back, &smallest.x_negative)
            && width(&smallest.s1a1_back) < width(&smallest.x_negative) / 2.0,
        "with the smallest backlash x is negative over a wide band, the back flanks of s1a1 touch over a narrower one",
    );
    Ok(())
}
