//! The values of the document's second half, the claims of the time
//! domain (Figs. 4-11: claims 3 to 9), each with the premises its fixed
//! words rest on.

use super::fill::Values;
use super::lookup::{back_words, need, sections_of};
use super::orbits::{Orbit, Row};
use super::record::Record;
use super::scale::PAPER_SECTIONS;
use super::sweeps::{Sweep, FINE_GRIDS, HIGH};
use super::words::{
    and, arrows, clip, ints, list, m_s, om, om3, omega_arg, omf, over, range_of, span, spanf,
    spans_and, um, width,
};
use crate::failure::Failure;

/// The 0.05 grid of the overview sweeps.
const COARSE: f64 = 0.05;

/// Sets every value of the second half.
pub fn set(v: &mut Values, r: &Record) -> Result<(), Failure> {
    claim3(v, r)?;
    claim4(v, r)?;
    claim5(v, r)?;
    claim6(v, r)?;
    claim7(v, r)?;
    claim8(v, r)?;
    claim9(v, r)
}

fn per_te(sweeps: &[Sweep], value: fn(&Sweep) -> f64) -> String {
    arrows(&sweeps.iter().map(value).collect::<Vec<_>>(), um)
}

fn ratio(sweeps: &[Sweep], value: fn(&Sweep) -> f64) -> f64 {
    match (sweeps.first(), sweeps.last()) {
        (Some(a), Some(b)) => value(b) / value(a),
        _ => f64::NAN,
    }
}

fn claim3(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let s = &r.scale;
    let low = |x: &Sweep| x.amplitude_at[1];
    let literal = |x: &Sweep| x.amplitude_at[2];
    let peak = |x: &Sweep| x.fine.as_ref().map_or(f64::NAN, |f| f.first_mode_peak.1);
    v.set("c3.low", per_te(&r.fig4, low));
    v.set("c3.literal", per_te(&r.fig4, literal));
    v.set("c3.peak", per_te(&r.fig4, peak));
    v.ensure(
        [low, literal, peak]
            .iter()
            .all(|f| ratio(&r.fig4, *f) < 3.0),
        "with the TE on the small-sun meshes x grows nowhere near tenfold at low frequency",
    );
    v.ensure(
        (super::sweeps::AMPLITUDE_AT[1] - s.matched(0.4)).abs() < COARSE / 2.0,
        "Ω 0.25 is the grid point nearest the paper's 0.4 matched",
    );
    v.set("c3.delta", per_te(&r.fig4, |x| x.delta_at_025_um));
    let every = &r.readings.every_mesh.fig4;
    v.set("c3.low_all", per_te(every, low));
    v.set("c3.literal_all", per_te(every, literal));
    v.ensure(
        ratio(every, low) > 5.0 && ratio(every, literal) > 5.0,
        "with the TE on every mesh x grows tenfold and more at low frequency",
    );
    // 3b: Fig. 4's resonance against Fig. 2's first mode.
    let fig2 = super::lookup::row(r, super::fig2::READINGS[0].0, false, 30)?;
    let fig2_first = need(
        fig2.peaks.iter().map(|p| p.0).min_by(|a, b| {
            (a - s.first_mode)
                .abs()
                .total_cmp(&(b - s.first_mode).abs())
        }),
        "Fig. 2's first-mode peak",
    )?;
    let fines: Vec<&super::sweeps::Fine> = r.fig4.iter().filter_map(|x| x.fine.as_ref()).collect();
    v.ensure(
        fines.len() == r.fig4.len(),
        "Fig. 4's finer sweeps are in the record",
    );
    let peaks: Vec<f64> = fines.iter().map(|f| f.first_mode_peak.0).collect();
    v.ensure(
        peaks
            .iter()
            .all(|w| *w < fig2_first && fig2_first - w < 0.03),
        "the sweeps peak just below Fig. 2's first mode",
    );
    v.set("c3b.peaks", list(&peaks, omf));
    v.set("c3b.fig2", om3(fig2_first));
    let step = (FINE_GRIDS[1].1 - FINE_GRIDS[1].0) / f64::from(FINE_GRIDS[1].2 - 1);
    v.set("c3b.step", omega_arg(step));
    let parts: Vec<(f64, f64)> = fines
        .iter()
        .filter_map(|f| {
            f.any
                .0
                .iter()
                .copied()
                .find(|(a, b)| *a <= f.first_mode_peak.0 && f.first_mode_peak.0 <= *b)
        })
        .collect();
    v.ensure(
        parts.len() == fines.len(),
        "the flanks of some mesh part at each peak",
    );
    v.set(
        "c3b.parts",
        format!(
            "over Ω {}",
            and(&parts.iter().map(spanf).collect::<Vec<_>>())
        ),
    );
    let mut all = peaks.clone();
    all.push(fig2_first);
    v.set(
        "c3b.paper",
        range_of(&all.iter().map(|w| w / s.factor).collect::<Vec<_>>(), om3),
    );
    v.ensure(
        all.iter().all(|w| (w / s.factor - 0.4).abs() < 0.05),
        "on the matched scale both resonances are close to the paper's 0.4",
    );
    Ok(())
}

fn claim4(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let f = &r.fig4;
    let high = |x: &Sweep| x.largest_high_um;
    let matched = |x: &Sweep| x.largest_high_matched_um;
    let (first, last) = (need(f.first(), "Fig. 4")?, need(f.last(), "Fig. 4")?);
    v.set("c4.first", um(high(first)));
    v.set("c4.last", um(high(last)));
    for x in f {
        v.set(&format!("c4.high_{}", x.case.te_um), um(high(x)));
    }
    v.set("c4.matched_range", span(&first.high_matched));
    v.set("c4.matched_0", um(matched(first)));
    v.set("c4.matched_30", um(matched(last)));
    v.ensure(
        ratio(f, high) > 5.0 && ratio(f, matched) > 5.0,
        "the TE raises the high-frequency amplitude manyfold on both scales",
    );
    v.ensure(
        f.iter().all(|x| x.any_back.is_empty())
            && f.iter().skip(1).all(|x| {
                width(&clip(&x.not_periodic, HIGH.0, HIGH.1, COARSE)) > 0.5 * (HIGH.1 - HIGH.0)
                    && !clip(&x.s1a1_parts, HIGH.0, HIGH.1, COARSE).is_empty()
            }),
        "with TE the motion at high frequency is mostly not periodic, with single-sided impacts",
    );
    // 4b.
    let from = need(
        f.get(1).and_then(|x| x.not_periodic.first()),
        "Fig. 4's not-periodic ranges",
    )?
    .0;
    v.set("c4b.from", om(from));
    for x in f {
        let words = if x.case.te_um == 0 {
            over(&x.not_periodic)
        } else {
            spans_and(&x.not_periodic)
        };
        v.set(&format!("c4b.np_{}", x.case.te_um), words);
    }
    v.ensure(
        f.iter()
            .skip(1)
            .all(|x| width(&x.not_periodic) > 0.7 * (2.0 - from)),
        "with TE the motion is not periodic over most of the range above its onset",
    );
    let s = &r.scale;
    let (mid_lo, mid_hi) = (
        PAPER_SECTIONS[1].1 * s.factor,
        PAPER_SECTIONS[1].2 * s.factor,
    );
    let (hi_lo, hi_hi) = (
        PAPER_SECTIONS[2].1 * s.factor,
        PAPER_SECTIONS[2].2 * s.factor,
    );
    v.set(
        "c4b.sections",
        format!(
            "the high section ({}–{}) throughout and the medium one ({}–{}) from Ω {} up",
            om3(hi_lo),
            om3(hi_hi),
            om3(mid_lo),
            om3(mid_hi),
            om(from)
        ),
    );
    v.ensure(
        f.iter().skip(1).all(|x| {
            let high = clip(&x.not_periodic, hi_lo, hi_hi, COARSE);
            let mid = clip(&x.not_periodic, mid_lo, mid_hi, COARSE);
            high.len() == 1
                && (high[0].1 - high[0].0) >= (hi_hi - hi_lo) - 2.0 * COARSE
                && mid.first().is_some_and(|m| (m.0 - from).abs() < 1e-9)
        }),
        "matched, with TE the high section is not periodic throughout and the medium one from the onset up",
    );
    Ok(())
}

fn claim5(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let s = &r.scale;
    let f = &r.fig4;
    v.set(
        "c5.lowest",
        list(&f.iter().map(|x| x.lowest_x_um.0).collect::<Vec<_>>(), um),
    );
    v.set(
        "c5.lowest_matched",
        list(&f.iter().map(|x| x.lowest_x_um.1).collect::<Vec<_>>(), um),
    );
    v.ensure(
        f.iter()
            .all(|x| x.lowest_x_um.0 > 0.0 && x.any_back.is_empty()),
        "at Fig. 4's backlash x never goes negative and no back flanks touch",
    );
    let every = &r.readings.every_mesh.fig4;
    let gap = &r.readings.full_gap.fig4;
    v.set("c5.all", back_words(every, |x| x.case.te_um, " TE"));
    v.set("c5.gap", back_words(gap, |x| x.case.te_um, " TE"));
    let largest_only = |sweeps: &[Sweep]| {
        sweeps.iter().rev().skip(1).all(|x| x.any_back.is_empty())
            && sweeps.last().is_some_and(|x| !x.any_back.is_empty())
    };
    v.ensure(
        largest_only(every) && largest_only(gap),
        "under the other readings only the largest TE brings back-flank contact",
    );
    let where_ = |sweeps: &[Sweep]| {
        let back = sweeps.last().map_or(Vec::new(), |x| x.any_back.clone());
        format!(
            "in the paper's {} sections read literally ({} matched)",
            and(&sections_of(&back, 1.0, COARSE)
                .iter()
                .map(|x| x.to_string())
                .collect::<Vec<_>>()),
            and(&sections_of(&back, s.factor, COARSE)
                .iter()
                .map(|x| if *x == "above" {
                    "above its range".to_string()
                } else {
                    x.to_string()
                })
                .collect::<Vec<_>>())
        )
    };
    v.set(
        "c5.sections",
        format!(
            "with the TE on every mesh {}, with the whole gap {}",
            where_(every),
            where_(gap)
        ),
    );
    for x in f {
        v.set(&format!("c5.part_{}", x.case.te_um), over(&x.s1a1_parts));
    }
    let low = PAPER_SECTIONS[0].2;
    let low_m = low * s.factor;
    let te: Vec<&Sweep> = f.iter().skip(1).collect();
    let per = |hi: f64| {
        let words: Vec<String> = te
            .iter()
            .map(|x| over(&clip(&x.s1a1_parts, 0.0, hi, COARSE)))
            .collect();
        let tes: Vec<u32> = te.iter().map(|x| x.case.te_um).collect();
        if words.windows(2).all(|p| p[0] == p[1]) {
            let w = words.first().cloned().unwrap_or_default();
            if w == "nowhere" {
                w
            } else {
                format!("{w} with {} µm", ints(&tes))
            }
        } else {
            and(&words
                .iter()
                .zip(&tes)
                .map(|(w, t)| format!("{w} with {t} µm"))
                .collect::<Vec<_>>())
        }
    };
    v.set("c5.low_lit", per(low));
    v.set("c5.low_matched", per(low_m));
    v.ensure(
        te.iter().all(|x| {
            let hi = clip(&x.s1a1_parts, PAPER_SECTIONS[2].1, PAPER_SECTIONS[2].2, COARSE);
            let hi_m = clip(&x.s1a1_parts, PAPER_SECTIONS[2].1 * s.factor, PAPER_SECTIONS[2].2 * s.factor, COARSE);
            !hi.is_empty() && !hi_m.is_empty()
        }),
        "once a TE is present the drive flanks of s1a1 part in the paper's high section on both scales",
    );
    let high = |x: &Sweep, factor: f64| {
        clip(
            &x.s1a1_parts,
            PAPER_SECTIONS[2].1 * factor,
            PAPER_SECTIONS[2].2 * factor,
            COARSE,
        )
    };
    let (lit0, mat0) = (high(&f[0], 1.0), high(&f[0], s.factor));
    v.ensure(
        width(&lit0) + width(&mat0) < COARSE,
        "without TE the drive flanks of s1a1 barely part in the paper's high section",
    );
    v.set(
        "c5.high_0",
        format!(
            "{} there read literally and {} matched",
            over(&lit0),
            over(&mat0)
        ),
    );
    Ok(())
}

fn find(rows: &[Row], figure: u32, matched: bool) -> Result<&Row, Failure> {
    need(
        rows.iter()
            .find(|x| x.figure == figure && x.matched == matched),
        &format!("Fig. {figure}'s orbits"),
    )
}

fn motions(row: &Row) -> Vec<&str> {
    row.orbits.iter().map(|o| o.motion.as_str()).collect()
}

fn claim6(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let s = &r.scale;
    let o = &r.orbits;
    let (f5, f6, f7) = (find(o, 5, false)?, find(o, 6, false)?, find(o, 7, false)?);
    let velocities = |row: &Row| {
        row.orbits
            .iter()
            .map(|x| x.velocity_m_s)
            .collect::<Vec<_>>()
    };
    v.ensure(
        [f6, f7].iter().all(|row| {
            let m = motions(row);
            m[0] == "period 1" && m[1..].iter().all(|x| *x != "period 1")
        }),
        "at the paper's 0.84 and 1.97 the TE destroys period 1",
    );
    v.ensure(
        [f5, f6, f7]
            .iter()
            .all(|row| velocities(row).windows(2).all(|p| p[0] < p[1])),
        "the penetration velocity grows with the TE at the paper's three Ω",
    );
    v.set("c6.v197", arrows(&velocities(f7), m_s));
    v.ensure(
        [f5, f6, f7]
            .iter()
            .all(|row| motions(row)[1..].iter().all(|m| *m == "chaotic"))
            && motions(f5)[0] == "chaotic",
        "at the paper's Ω the motion with TE is chaotic, and at 0.5 even without",
    );
    let (m5, m6, m7) = (find(o, 5, true)?, find(o, 6, true)?, find(o, 7, true)?);
    let omega = |row: &Row| row.orbits.first().map_or(f64::NAN, |x| x.omega);
    v.set("c6.w05", om3(omega(m5)));
    v.set("c6.w084", om3(omega(m6)));
    v.set("c6.w197", om3(omega(m7)));
    v.set("c6.m084", motions(m6).join(" → "));
    let mm5 = motions(m5);
    v.ensure(
        mm5.first() == Some(&"period 2") && mm5.last() == Some(&"period 1"),
        "at the paper's 0.5 matched the TE turns period 2 into period 1",
    );
    v.set("c6.m05_first", mm5[0]);
    v.set("c6.m05_last", mm5[mm5.len() - 1]);
    let mm6 = motions(m6);
    v.ensure(
        mm6[0] == "period 1" && mm6[1] != "period 1" && mm6[mm6.len() - 1] == "chaotic",
        "at the paper's 0.84 matched period 1 gives way to other motion and chaos",
    );
    let band = need(s.band_of(omega(m7)), "a band at the paper's 1.97 matched")?;
    v.set("c6.band197", format!("{}–{}", om3(band.0), om3(band.1)));
    v.set("c6.m197_first", motions(m7)[0]);
    v.ensure(
        motions(m7)[0] != "period 1",
        "in that band the motion without TE is not period 1",
    );
    Ok(())
}

fn same(row: &Row) -> bool {
    let first = &row.orbits[0];
    row.orbits.iter().all(|o| {
        o.motion == first.motion
            && (o.amplitude_um - first.amplitude_um).abs() < 0.05
            && (o.velocity_m_s - first.velocity_m_s).abs() < 0.005
    })
}

fn claim7(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let s = &r.scale;
    let o = &r.orbits;
    let (l9, l10, l11) = (find(o, 9, false)?, find(o, 10, false)?, find(o, 11, false)?);
    let (m9, m10, m11) = (find(o, 9, true)?, find(o, 10, true)?, find(o, 11, true)?);
    v.ensure(
        same(m9) && same(m10),
        "at the paper's 0.5 and 0.84 matched the backlashes give the very same motion",
    );
    let words = |row: &Row| {
        let x = &row.orbits[0];
        format!("{}, {} µm", x.motion, um(x.amplitude_um))
    };
    let omega = |row: &Row| row.orbits.first().map_or(f64::NAN, |x| x.omega);
    v.set("c7a.w05", om3(omega(m9)));
    v.set("c7a.w084", om3(omega(m10)));
    v.set("c7a.m05", words(m9));
    v.set("c7a.m084", words(m10));
    let lit: Vec<&str> = motions(l9).into_iter().chain(motions(l10)).collect();
    v.ensure(
        lit.iter().all(|m| *m == "chaotic"),
        "at the paper's 0.5 and 0.84 the motion is chaotic for every backlash",
    );
    v.set("c7a.literal", "chaotic");
    v.ensure(
        [l9, l10, m9, m10].iter().all(|row| {
            let m = motions(row);
            !m.windows(2)
                .any(|p| p[0] == "period 1" && p[1] == "period 2")
        }),
        "no backlash turns period 1 into period 2",
    );
    let v9: Vec<f64> = l9.orbits.iter().map(|x| x.velocity_m_s).collect();
    v.set("c7a.v05", range_of(&v9, m_s));
    v.set("c7a.v05_max", m_s(v9.iter().copied().fold(0.0, f64::max)));
    let v11: Vec<f64> = l11.orbits.iter().map(|x| x.velocity_m_s).collect();
    v.set("c7a.v197", range_of(&v11, m_s));
    v.ensure(
        l9.orbits
            .iter()
            .chain(&m9.orbits)
            .all(|x| x.back_flanks.is_empty())
            && v9
                .iter()
                .all(|x| *x < 0.5 * v11.iter().copied().fold(f64::INFINITY, f64::min)),
        "at the paper's 0.5 no back flanks touch and the penetration velocity is low",
    );
    // 7b.
    v.ensure(
        motions(l11).iter().all(|m| *m == "chaotic")
            && motions(m11).iter().all(|m| *m == "chaotic"),
        "at the paper's 1.97, literal and matched, the motion is chaotic for every backlash",
    );
    let (lo, hi) = (
        v11.iter().copied().fold(f64::INFINITY, f64::min),
        v11.iter().copied().fold(0.0, f64::max),
    );
    v.ensure(
        hi - lo < 0.05 * lo,
        "the penetration velocity at 1.97 does not depend on the backlash",
    );
    v.set(
        "c7b.smallest",
        l11.values.first().map_or(String::new(), u32::to_string),
    );
    v.set("c7b.velocities", range_of(&v11, m_s));
    v.set("c7b.w", om3(omega(m11)));
    let band = need(s.band_of(omega(m11)), "a band at the paper's 1.97 matched")?;
    v.set("c7b.band", format!("{}–{}", om3(band.0), om3(band.1)));
    let touching: Vec<&Orbit> = m11
        .orbits
        .iter()
        .filter(|x| !x.back_flanks.is_empty())
        .collect();
    v.ensure(
        touching.len() == 1 && std::ptr::eq(touching[0], &m11.orbits[0]),
        "at the paper's 1.97 matched only the smallest backlash brings back flanks into contact",
    );
    v.set("c7b.back", and(&m11.orbits[0].back_flanks));
    Ok(())
}

fn claim8(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let s = &r.scale;
    let onset: Vec<f64> = r
        .chaos
        .iter()
        .filter_map(|c| c.chaotic.first().map(|x| x.0))
        .collect();
    v.ensure(
        onset.len() == r.chaos.len() && onset.windows(2).all(|p| (p[0] - p[1]).abs() < 1e-9),
        "chaos starts at the same Ω for every backlash",
    );
    let onset = need(onset.first().copied(), "the onset of chaos")?;
    v.set("c8.onset", om(onset));
    v.set(
        "c8.backlashes",
        ints(
            &r.fig8
                .iter()
                .map(|x| x.case.backlash_um)
                .collect::<Vec<_>>(),
        ),
    );
    let coarse: Vec<Option<f64>> = r.fig8.iter().map(|x| x.first_not_period_1).collect();
    let fine: Vec<Option<f64>> = r
        .fig8
        .iter()
        .map(|x| x.fine.as_ref().and_then(|f| f.first_not_period_1))
        .collect();
    let one = |xs: &[Option<f64>]| {
        xs.windows(2).all(|p| p[0] == p[1]) && xs.first().is_some_and(Option::is_some)
    };
    v.ensure(
        one(&coarse) && one(&fine),
        "period 1 ends at the same Ω for every backlash",
    );
    let c = need(coarse.first().copied().flatten(), "the end of period 1")?;
    let f = need(fine.first().copied().flatten(), "the end of period 1")?;
    v.set("c8.first_coarse", om(c));
    v.set("c8.first_fine", omf(f));
    v.ensure(
        (f - s.first_mode).abs() < 0.03 && f < s.matched(0.4),
        "on the finer grid period 1 is lost in the first mode's resonance, just below the paper's 0.4 matched",
    );
    let m08 = s.matched(0.8);
    v.ensure(
        onset > m08 && onset - m08 < 0.05,
        "chaos starts just above the paper's 0.8 matched",
    );
    let negative: Vec<Option<f64>> = r
        .fig8
        .iter()
        .map(|x| x.x_negative.first().map(|s| s.0))
        .collect();
    v.ensure(
        negative.windows(2).all(|p| match (p[0], p[1]) {
            (Some(a), Some(b)) => a < b,
            (Some(_), None) => true,
            _ => false,
        }) && negative.last() == Some(&None),
        "more backlash moves the first negative x up, and removes it",
    );
    v.set(
        "c8.negative",
        and(&negative
            .iter()
            .map(|x| x.map_or("nowhere".into(), om))
            .collect::<Vec<_>>()),
    );
    Ok(())
}

fn claim9(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let s = &r.scale;
    let f = &r.fig8;
    let [small, middle, large] = f.as_slice() else {
        return need(None, "three Fig. 8 sweeps");
    };
    v.ensure(
        !small.any_back.is_empty() && middle.any_back.is_empty() && large.any_back.is_empty(),
        "the back flanks touch only with the smallest backlash",
    );
    v.set("c9.smallest", small.case.backlash_um.to_string());
    v.set("c9.negative", over_omega_words(&small.x_negative));
    v.set("c9.middle", middle.case.backlash_um.to_string());
    v.set("c9.largest", large.case.backlash_um.to_string());
    v.set("c9.negative_middle", over(&middle.x_negative));
    v.set("c9.negative_largest", over(&large.x_negative));
    let top = s.matched(2.0);
    v.set("c9.matched_top", om3(top));
    let back_m = clip(&small.any_back, 0.0, top, COARSE);
    v.ensure(
        !back_m.is_empty(),
        "matched, the back flanks touch with the smallest backlash",
    );
    v.set("c9.back_matched", over(&back_m));
    let vel = |i: usize| {
        f.iter()
            .map(|x| {
                if i == 0 {
                    x.largest_velocity_m_s.0
                } else {
                    x.largest_velocity_m_s.1
                }
            })
            .collect::<Vec<_>>()
    };
    for (i, name) in [(0, "c9.velocity"), (1, "c9.velocity_matched")] {
        let xs = vel(i);
        let (lo, hi) = (
            xs.iter().copied().fold(f64::INFINITY, f64::min),
            xs.iter().copied().fold(0.0, f64::max),
        );
        v.ensure(
            hi - lo < 0.15 * lo,
            "the largest penetration velocity barely depends on the backlash",
        );
        v.set(name, list(&xs, m_s));
    }
    Ok(())
}

fn over_omega_words(s: &super::data::Spans) -> String {
    super::lookup::over_omega(s)
}
