//! The values of the claims of the frequency domain (Figs. 2 and 3:
//! claims 1, 1b and 2), each with the premises its fixed words rest on.

use super::fig2::READINGS;
use super::fill::Values;
use super::lookup::{anchor, need, row, stable_only, stable_um};
use super::record::Record;
use super::words::{and, hbm_um, ints, list, om, om3, omega_arg, range_of, spans3_and, um};
use crate::failure::Failure;

/// A peak of a branch: (Omega, stable).
type Peak = (f64, bool);

/// Sets every value of claims 1, 1b and 2.
pub fn set(v: &mut Values, r: &Record) -> Result<(), Failure> {
    claim1(v, r)?;
    straddling(v, r);
    claim1b(v, r)?;
    claim2(v, r)
}

fn claim1(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let s = &r.scale;
    v.set("c1.half", omega_arg(super::fig2::HALF_WINDOW));
    let first = anchor(r, s.first_mode)?;
    let sine = READINGS[0].0;
    let (r5, r30) = (row(r, sine, false, 5)?, row(r, sine, false, 30)?);
    let (a, b) = (r5.cells[first], r30.cells[first]);
    v.ensure(
        stable_only(&a) && stable_only(&b) && stable_um(&b) > stable_um(&a),
        "the first-mode peak grows with the TE on stable points",
    );
    v.set(
        "c1.first",
        format!("{} to {}", um(stable_um(&a)), um(stable_um(&b))),
    );
    // Every peak at 30 µm is there at 5 µm already.
    let near = |ps: &[Peak], w: f64| ps.iter().any(|p| (p.0 - w).abs() <= 0.01);
    let pairs: Vec<(&[Peak], &[Peak])> = {
        let mut out: Vec<(&[Peak], &[Peak])> = Vec::new();
        for x in r.fig2.rows.iter().filter(|x| x.te_um == 30) {
            let y = row(r, &x.reading, x.one_harmonic, 5)?;
            out.push((&y.peaks, &x.peaks));
        }
        for x in r.fig2.panels.iter().filter(|x| x.te_um == 30) {
            if let Some(y) = r
                .fig2
                .panels
                .iter()
                .find(|y| y.mesh == x.mesh && y.te_um == 5)
            {
                out.push((&y.peaks, &x.peaks));
            }
        }
        out
    };
    v.ensure(
        pairs
            .iter()
            .all(|(p5, p30)| p30.iter().all(|p| near(p5, p.0))),
        "every peak of the 30 µm responses is there at 5 µm already",
    );
    // The one-harmonic method at the superharmonic.
    let half = anchor(r, s.first_mode / 2.0)?;
    let h1 = row(r, sine, true, 5)?.cells[half];
    let h7 = r5.cells[half];
    v.ensure(
        stable_only(&h1) && stable_only(&h7),
        "both methods are stable at half the first mode",
    );
    v.set(
        "c1.h1_superharmonic",
        format!(
            "no peak ({} µm there on stable points, against {} µm with seven harmonics)",
            um(stable_um(&h1)),
            um(stable_um(&h7))
        ),
    );
    let literal = anchor(r, 0.4)?;
    let (a, b) = (r5.cells[literal], r30.cells[literal]);
    v.ensure(
        stable_only(&a) && stable_only(&b) && stable_um(&b) > 2.0 * stable_um(&a),
        "at the paper's 0.4 the amplitude grows with the TE on stable points",
    );
    v.set(
        "c1.at04",
        format!("{} to {} µm", um(stable_um(&a)), um(stable_um(&b))),
    );
    // The paper's 1.2 and 1.4 matched.
    let (m12, m14) = (s.matched(1.2), s.matched(1.4));
    v.set("c1.m12", om3(m12));
    v.set("c1.m14", om3(m14));
    let i12 = anchor(r, m12)?;
    let (a, b) = (r5.cells[i12], r30.cells[i12]);
    v.set(
        "c1.at_m12",
        if stable_only(&a) && stable_only(&b) {
            format!(
                "{} µm at 5 µm and {} µm at 30 µm, both on stable points",
                um(stable_um(&a)),
                um(stable_um(&b))
            )
        } else {
            format!("{} at 5 µm, {} at 30 µm", hbm_um(&a), hbm_um(&b))
        },
    );
    v.ensure(
        r30.peaks.iter().all(|(w, _)| (w - m12).abs() > 0.03)
            && s.rotational
                .iter()
                .chain(&s.planet)
                .all(|w| (w - m12).abs() > 0.03),
        "the paper's 1.2 matched falls on no mode and no peak",
    );
    let band14 = need(s.band_of(m14), "a band at the paper's 1.4 matched")?;
    let k = need(s.bands.iter().position(|b| *b == band14), "the band")?;
    v.set(
        "c1.m14_band",
        format!("{}–{}", om3(band14.0), om3(band14.1)),
    );
    let (unstable, points) = need(r30.bands.get(k).copied(), "the band's points")?;
    v.ensure(
        unstable * 2 > points,
        "most of the branch is unstable in the band at the paper's 1.4 matched",
    );
    v.set(
        "c1.m14_unstable",
        of_points(unstable, points, "the branch's", "in the band"),
    );
    let cell = r30.cells[anchor(r, m14)?];
    let straddles =
        m14 - super::fig2::HALF_WINDOW < band14.0 || m14 + super::fig2::HALF_WINDOW > band14.1;
    v.ensure(
        unstable == points || cell.stable_um.is_none(),
        "the stable amplitudes near the paper's 1.4 matched lie outside the band",
    );
    v.set(
        "c1.at_m14_30",
        match (cell.stable_um, cell.unstable_um) {
            (Some(st), Some(u)) if straddles => format!(
                "{} µm on unstable points, {} µm on stable ones just outside the band",
                um(u),
                um(st)
            ),
            _ => hbm_um(&cell),
        },
    );
    let band12 = need(s.band_of(1.2), "a band at the paper's 1.2")?;
    v.set(
        "c1.l12_band",
        format!("{}–{}", om3(band12.0), om3(band12.1)),
    );
    let k12 = need(s.bands.iter().position(|b| *b == band12), "the band")?;
    let (u12, p12) = need(r30.bands.get(k12).copied(), "the band's points")?;
    v.set("c1.l12_unstable", of_points(u12, p12, "its", "unstable"));
    Ok(())
}

/// "all 18 of the branch's points in the band are unstable", "16 of ...".
fn of_points(unstable: usize, points: usize, whose: &str, what: &str) -> String {
    let tail = if what == "unstable" {
        String::new()
    } else {
        format!(" {what} are unstable")
    };
    if unstable == points {
        format!("all {points} of {whose} points{tail}")
    } else {
        format!("{unstable} of {whose} {points} points{tail}")
    }
}

/// The windows of Fig. 2 that reach past the edge of a band of
/// parametric instability.
fn straddling(v: &mut Values, r: &Record) {
    let h = super::fig2::HALF_WINDOW;
    let across: Vec<String> = r
        .fig2
        .anchors
        .iter()
        .filter(|a| {
            r.scale.bands.iter().any(|&(lo, hi)| {
                let (a0, a1) = (a.omega - h, a.omega + h);
                (a0 < lo && lo < a1) || (a0 < hi && hi < a1)
            })
        })
        .map(|a| om3(a.omega))
        .collect();
    v.set(
        "c1.straddle",
        if across.is_empty() {
            String::new()
        } else {
            format!(
                " The windows at Ω {} reach past the edge of a band of parametric instability: their stable amplitudes are those of the points outside the band.",
                and(&across)
            )
        },
    );
}

fn claim1b(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let s = &r.scale;
    let of = |reading: &str, te: u32| {
        need(
            r.fig2
                .contact
                .iter()
                .find(|c| c.reading == reading && c.te_um == te),
            "Fig. 2's contact",
        )
    };
    let sine = READINGS[0].0;
    let (c5, c30) = (of(sine, 5)?, of(sine, 30)?);
    v.set("c1b.kept_5", spans3_and(&c5.kept));
    v.set("c1b.kept_30", spans3_and(&c30.kept));
    v.set("c1b.from", om(c5.range.0));
    let top = need(c5.kept.last(), "a window at 5 µm")?.1;
    v.set("c1b.top_5", om3(top));
    v.set("c1b.top_5_paper", om3(top / s.factor));
    // The gaps between the windows hold the response's peaks.
    let reference = row(r, sine, false, 30)?;
    v.ensure(
        c5.kept.windows(2).all(|p| {
            reference
                .peaks
                .iter()
                .any(|(w, _)| p[0].1 < *w && *w < p[1].0)
        }),
        "every gap between the 5 µm windows holds a resonance peak",
    );
    let beyond: Vec<String> = r
        .fig2
        .contact
        .iter()
        .filter_map(|c| {
            let later: super::data::Spans = c.kept.iter().copied().filter(|w| w.0 > top).collect();
            (!later.is_empty()).then(|| {
                format!(
                    "with {} µm TE on the {} one more window is left, {}",
                    c.te_um,
                    c.reading.trim_start_matches("sine, "),
                    spans3_and(&later)
                )
            })
        })
        .collect();
    v.set(
        "c1b.high_words",
        if beyond.is_empty() {
            String::new()
        } else {
            format!(" (except that {})", and(&beyond))
        },
    );
    v.ensure(
        c30.kept.last().is_some_and(|w| w.1 < top),
        "30 µm leaves fewer windows than 5 µm",
    );
    Ok(())
}

fn claim2(v: &mut Values, r: &Record) -> Result<(), Failure> {
    let s = &r.scale;
    let f3 = &r.fig3;
    let n = f3.omegas.len() / 2;
    let first = need(f3.rows.first(), "Fig. 3's rows")?;
    let last = need(f3.rows.last(), "Fig. 3's rows")?;
    v.set("c2.first_b", first.backlash_um.to_string());
    v.set("c2.last_b", last.backlash_um.to_string());
    v.set("c2.half", omega_arg(super::fig3::HALF_WINDOW));
    let (unstable, points) = f3.middle_unstable;
    v.ensure(
        unstable * 10 >= points * 9,
        "the multi-harmonic branch of Fig. 3 is unstable over the middle of the range",
    );
    v.set("c2.middle", unstable.to_string());
    v.set("c2.middle_points", points.to_string());
    v.set("c2.middle_from", om(super::fig3::MIDDLE.0));
    v.set("c2.middle_to", om(super::fig3::MIDDLE.1));
    let at = |i: usize| {
        f3.rows
            .iter()
            .map(|x| x.orbits[i].amplitude_um)
            .collect::<Vec<_>>()
    };
    let idx = |w: f64| {
        need(
            f3.omegas.iter().position(|x| (x - w).abs() < 1e-9),
            "an Ω of Fig. 3",
        )
    };
    let (i04, i12, i14) = (idx(0.4)?, idx(1.2)?, idx(1.4)?);
    let a04 = at(i04);
    let (lo, hi) = (
        a04.iter().copied().fold(f64::INFINITY, f64::min),
        a04.iter().copied().fold(0.0, f64::max),
    );
    v.ensure(hi - lo < 0.15 * lo, "x barely changes at the paper's 0.4");
    v.set("c2.at04", range_of(&a04, um));
    let a14 = at(i14);
    let (imax, max) = a14
        .iter()
        .copied()
        .enumerate()
        .fold((0, f64::NEG_INFINITY), |b, x| if x.1 > b.1 { x } else { b });
    v.ensure(
        a14[0] < max && a14[0] < a14[a14.len() - 1],
        "x rises at the paper's 1.4 with the backlash",
    );
    v.set("c2.at14_first", um(a14[0]));
    v.set("c2.at14_max", um(max));
    v.set("c2.at14_max_b", f3.rows[imax].backlash_um.to_string());
    v.set("c2.at14_last", um(a14[a14.len() - 1]));
    let back14: Vec<u32> = f3
        .rows
        .iter()
        .filter(|x| x.orbits[i14].impact == "double-sided")
        .map(|x| x.backlash_um)
        .collect();
    v.ensure(
        back14.first() == Some(&first.backlash_um)
            && f3
                .rows
                .iter()
                .filter(|x| back14.contains(&x.backlash_um))
                .all(|x| x.orbits[i14].amplitude_um < max),
        "at the paper's 1.4 the smallest backlashes strike the back flanks and swing less",
    );
    v.set("c2.back14", ints(&back14));
    let band12 = need(s.band_of(1.2), "a band at 1.2")?;
    v.set("c2.band12", format!("{}–{}", om3(band12.0), om3(band12.1)));
    let a12 = at(i12);
    v.ensure(
        !(a12.windows(2).all(|p| p[0] <= p[1]) || a12.windows(2).all(|p| p[0] >= p[1])),
        "at the paper's 1.2 the amplitude scatters with no trend",
    );
    v.set("c2.at12", list(&a12, um));
    let all: Vec<&super::orbits::Orbit> = f3.rows.iter().flat_map(|x| &x.orbits).collect();
    let chaotic = all.iter().filter(|o| o.motion == "chaotic").count();
    v.ensure(
        chaotic * 10 >= all.len() * 9,
        "the motion of Fig. 3 is chaotic almost everywhere",
    );
    v.set(
        "c2.chaotic",
        format!("{chaotic} of these {} runs", all.len()),
    );
    // Matched: 1.2 and 1.4.
    let (m12, m14) = (idx(s.matched(1.2))?, idx(s.matched(1.4))?);
    let (b12, b14) = (at(m12), at(m14));
    let rise = |xs: &[f64]| xs[xs.len() - 1] - xs[0];
    v.ensure(
        rise(&b12) > 0.0
            && rise(&b14) > 0.0
            && rise(&b12) > 0.5 * rise(&b14)
            && rise(&b12) < 2.0 * rise(&b14),
        "matched, x rises as much at the paper's 1.2 as at its 1.4",
    );
    v.set("c2.w12", om3(s.matched(1.2)));
    v.set("c2.w14", om3(s.matched(1.4)));
    v.set(
        "c2.rise12",
        format!("{} → {}", um(b12[0]), um(b12[b12.len() - 1])),
    );
    v.set(
        "c2.rise14",
        format!("{} → {}", um(b14[0]), um(b14[b14.len() - 1])),
    );
    // The TE on every mesh.
    let every = |i: usize| {
        f3.every_mesh
            .iter()
            .map(|x| x.orbits[i].amplitude_um)
            .collect::<Vec<_>>()
    };
    let (e04, e12, e14) = (every(i04), every(i12), every(i14));
    let spread = |xs: &[f64]| {
        let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
        (xs.iter().copied().fold(0.0, f64::max) - lo) / lo
    };
    v.ensure(
        spread(&e04) > 0.15 && rise(&e12) > 0.0 && rise(&e14) > 0.0,
        "with the TE on every mesh x changes at the paper's 0.4 and rises at its 1.2 as at 1.4",
    );
    v.set("c2.all04", range_of(&e04, um));
    v.set(
        "c2.all12",
        format!("{} → {}", um(e12[0]), um(e12[e12.len() - 1])),
    );
    v.set(
        "c2.all14",
        format!("{} → {}", um(e14[0]), um(e14[e14.len() - 1])),
    );
    // The one-harmonic branch: where its largest amplitude is stable.
    let mut except: Vec<(f64, Vec<u32>)> = Vec::new();
    for (b, cells) in &f3.one_harmonic {
        for (i, c) in cells.iter().enumerate() {
            if c.unstable_um.is_none() {
                let w = f3.omegas[i];
                match except.iter_mut().find(|e| (e.0 - w).abs() < 1e-9) {
                    Some(e) => e.1.push(*b),
                    None => except.push((w, vec![*b])),
                }
            }
        }
    }
    v.ensure(
        except.iter().all(|(w, _)| f3.omegas[n..].contains(w)),
        "the one-harmonic branch is unstable near every literal Ω",
    );
    v.set(
        "c2.h1_except",
        if except.is_empty() {
            String::new()
        } else {
            format!(
                ", except {}",
                and(&except
                    .iter()
                    .map(|(w, bs)| format!("at Ω {} with {} µm", om3(*w), ints(bs)))
                    .collect::<Vec<_>>())
            )
        },
    );
    // Panel d: rb1.
    let i_first = idx(s.matched(0.4))?;
    let rb = |i: usize| {
        f3.rows
            .iter()
            .map(|x| x.orbits[i].rb1_amplitude_um)
            .collect::<Vec<_>>()
    };
    let rb1 = rb(i_first);
    let (lo, hi) = (
        rb1.iter().copied().fold(f64::INFINITY, f64::min),
        rb1.iter().copied().fold(0.0, f64::max),
    );
    v.ensure(
        hi - lo < 0.05 * lo,
        "x_rb1 does not change at the first mode",
    );
    v.set("c2.w04", om3(s.matched(0.4)));
    v.set("c2.rb_first", range_of(&rb1, um));
    let rb3 = rb(m14);
    v.ensure(
        rb3.windows(2).all(|p| p[0] < p[1]),
        "x_rb1 grows with the backlash at the third mode",
    );
    v.set(
        "c2.rb_third",
        format!("{} → {}", um(rb3[0]), um(rb3[rb3.len() - 1])),
    );
    Ok(())
}
