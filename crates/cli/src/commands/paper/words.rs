//! Numbers in the document's words: Omega, micrometres, spans of Omega,
//! input speeds, harmonic-balance amplitudes with their stability, lists.

use super::data::Spans;
use super::fig2::Hbm;

/// Omega as a command line takes it: the shortest of at most 4 decimals.
pub fn omega_arg(w: f64) -> String {
    let s = format!("{w:.4}");
    let s = s.trim_end_matches('0');
    s.strip_suffix('.')
        .map_or_else(|| s.to_string(), str::to_string)
}

/// Omega as the document writes it: at least 2 decimals, at most 4.
pub fn om(w: f64) -> String {
    let s = omega_arg(w);
    match s.split_once('.') {
        Some((_, d)) if d.len() >= 2 => s,
        Some((i, d)) => format!("{i}.{d:0<2}"),
        None => format!("{s}.00"),
    }
}

/// Omega on a finer grid: at least 3 decimals, at most 4.
pub fn omf(w: f64) -> String {
    let s = om(w);
    match s.split_once('.') {
        Some((i, d)) if d.len() < 3 => format!("{i}.{d:0<3}"),
        _ => s,
    }
}

/// A span of a finer grid: "a–b", or "a" for one point.
pub fn spanf(&(a, b): &(f64, f64)) -> String {
    if (a - b).abs() < 1e-9 {
        omf(a)
    } else {
        format!("{}–{}", omf(a), omf(b))
    }
}

/// Two values as a span written by `each`, or one if they are written
/// alike.
pub fn pair(a: f64, b: f64, each: impl Fn(f64) -> String) -> String {
    let (x, y) = (each(a), each(b));
    if x == y {
        x
    } else {
        format!("{x}–{y}")
    }
}

/// Omega to 3 decimals (modes, bands, matched values).
pub fn om3(w: f64) -> String {
    format!("{w:.3}")
}

/// A span of Omega: "a–b", or "a" for one point.
pub fn span(&(a, b): &(f64, f64)) -> String {
    if (a - b).abs() < 1e-9 {
        om(a)
    } else {
        format!("{}–{}", om(a), om(b))
    }
}

/// Spans as a table writes them: "a–b, c", or "none".
pub fn spans(s: &Spans) -> String {
    if s.is_empty() {
        "none".into()
    } else {
        s.iter().map(span).collect::<Vec<_>>().join(", ")
    }
}

/// Spans in a sentence: "a–b, c–d and e", or "nowhere".
pub fn spans_and(s: &Spans) -> String {
    if s.is_empty() {
        "nowhere".into()
    } else {
        and(&s.iter().map(span).collect::<Vec<_>>())
    }
}

/// Spans to 3 decimals (the bands): "a–b, c–d".
pub fn spans3(s: &Spans) -> String {
    s.iter()
        .map(|(a, b)| format!("{}–{}", om3(*a), om3(*b)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A list in a sentence: "a", "a and b", "a, b and c".
pub fn and(items: &[String]) -> String {
    match items {
        [] => String::new(),
        [one] => one.clone(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

/// Micrometres to 1 decimal.
pub fn um(x: f64) -> String {
    format!("{x:.1}")
}

/// A velocity to 2 decimals.
pub fn m_s(x: f64) -> String {
    format!("{x:.2}")
}

/// A whole number with its thousands set apart by a space: "34 068".
pub fn grouped(x: f64) -> String {
    let n = x.round() as i64;
    let digits = n.unsigned_abs().to_string();
    let mut out = String::new();
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(' ');
        }
        out.push(c);
    }
    if n < 0 {
        format!("−{out}")
    } else {
        out
    }
}

/// A harmonic-balance amplitude in a table that says "stable unless
/// marked": "170.5", "12.1 (12.4 unstable)", "7.4 unstable".
pub fn hbm(h: &Hbm) -> String {
    match (h.stable_um, h.unstable_um) {
        (Some(s), Some(u)) => format!("{} ({} unstable)", um(s), um(u)),
        (Some(s), None) => um(s),
        (None, Some(u)) => format!("{} unstable", um(u)),
        (None, None) => "–".into(),
    }
}

/// A harmonic-balance amplitude in a sentence: "170.5 µm (stable)",
/// "12.1 µm (stable; 12.4 µm on unstable points)", "7.4 µm (unstable)".
pub fn hbm_um(h: &Hbm) -> String {
    match (h.stable_um, h.unstable_um) {
        (Some(s), Some(u)) => format!("{} µm (stable; {} µm on unstable points)", um(s), um(u)),
        (Some(s), None) => format!("{} µm (stable)", um(s)),
        (None, Some(u)) => format!("{} µm (unstable)", um(u)),
        (None, None) => "no point".into(),
    }
}

/// Spans in a sentence with their preposition: "over 0.50–0.55, 1.05–1.15
/// and 1.80", "at 1.35 and 1.45", or "nowhere".
pub fn over(s: &Spans) -> String {
    if s.is_empty() {
        "nowhere".into()
    } else if s.iter().all(|(a, b)| (a - b).abs() < 1e-9) {
        format!("at {}", spans_and(s))
    } else {
        format!("over {}", spans_and(s))
    }
}

/// The parts of spans of grid points (a grid of `step`) inside
/// `lo..=hi`: a span is cut at the last grid point inside.
pub fn clip(s: &Spans, lo: f64, hi: f64, step: f64) -> Spans {
    let lo = (lo / step - 1e-6).ceil() * step;
    let hi = (hi / step + 1e-6).floor() * step;
    s.iter()
        .filter(|(a, b)| *b >= lo - 1e-9 && *a <= hi + 1e-9)
        .map(|&(a, b)| (a.max(lo), b.min(hi)))
        .collect()
}

/// Spans of real Omegas (not grid points) to 3 decimals, in a sentence:
/// "0.100–0.115, 0.116–0.211 and 0.254–0.264", or "nowhere".
pub fn spans3_and(s: &Spans) -> String {
    if s.is_empty() {
        "nowhere".into()
    } else {
        and(&s
            .iter()
            .map(|(a, b)| format!("{}–{}", om3(*a), om3(*b)))
            .collect::<Vec<_>>())
    }
}

/// The width of spans taken together.
pub fn width(s: &Spans) -> f64 {
    s.iter().map(|(a, b)| b - a).sum()
}

/// Whether every span of `inner` lies inside some span of `outer`.
pub fn inside(inner: &Spans, outer: &Spans) -> bool {
    inner
        .iter()
        .all(|(a, b)| outer.iter().any(|(c, d)| c - 1e-9 <= *a && *b <= d + 1e-9))
}

/// Numbers as a list in a sentence, each written by `each`.
pub fn list(xs: &[f64], each: fn(f64) -> String) -> String {
    and(&xs.iter().map(|&x| each(x)).collect::<Vec<_>>())
}

/// Whole numbers as a list in a sentence: "50, 100 and 200".
pub fn ints(xs: &[u32]) -> String {
    and(&xs.iter().map(u32::to_string).collect::<Vec<_>>())
}

/// The least and the largest of `xs`, as "a–b" (or "a" if they agree
/// when written by `each`).
pub fn range_of(xs: &[f64], each: fn(f64) -> String) -> String {
    let lo = xs.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let (a, b) = (each(lo), each(hi));
    if a == b {
        a
    } else {
        format!("{a}–{b}")
    }
}

/// Numbers joined by arrows: "2.9 → 3.0 → 3.5".
pub fn arrows(xs: &[f64], each: fn(f64) -> String) -> String {
    xs.iter().map(|&x| each(x)).collect::<Vec<_>>().join(" → ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_in_words() {
        assert_eq!(omega_arg(0.29), "0.29");
        assert_eq!(omega_arg(0.4), "0.4");
        assert_eq!(omega_arg(2.0), "2");
        assert_eq!(omega_arg(0.1148), "0.1148");
        assert_eq!(om(0.5), "0.50");
        assert_eq!(om(1.0), "1.00");
        assert_eq!(om(0.115), "0.115");
        assert_eq!(omf(0.02), "0.020");
        assert_eq!(omf(0.1148), "0.1148");
        assert_eq!(spanf(&(0.32, 0.38)), "0.320–0.380");
        assert_eq!(pair(0.498, 0.498, om3), "0.498");
        assert_eq!(span(&(0.5, 0.55)), "0.50–0.55");
        assert_eq!(
            spans_and(&vec![(0.5, 0.5), (1.0, 1.2), (1.8, 1.8)]),
            "0.50, 1.00–1.20 and 1.80"
        );
        assert_eq!(grouped(34068.2), "34 068");
        assert_eq!(grouped(516.0), "516");
        assert_eq!(grouped(1000.0), "1 000");
        let h = Hbm {
            stable_um: Some(5.6),
            unstable_um: Some(7.7),
        };
        assert_eq!(hbm(&h), "5.6 (7.7 unstable)");
        assert_eq!(hbm_um(&h), "5.6 µm (stable; 7.7 µm on unstable points)");
        assert_eq!(over(&vec![(1.3, 1.35)]), "over 1.30–1.35");
        assert_eq!(over(&vec![(1.35, 1.35), (1.45, 1.45)]), "at 1.35 and 1.45");
        assert_eq!(over(&vec![]), "nowhere");
        assert_eq!(
            span(&clip(&vec![(0.5, 1.7), (1.9, 2.0)], 0.0, 1.159, 0.05)[0]),
            "0.50–1.15"
        );
        assert!(inside(&vec![(1.3, 1.35)], &vec![(0.85, 1.65)]));
        assert_eq!(range_of(&[2.41, 2.45, 2.42], m_s), "2.41–2.45");
    }
}
