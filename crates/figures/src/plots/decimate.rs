//! Decimation to the pixel grid: data reduced to what the plot can show,
//! so that a record of 1000 periods (64 000 samples) costs the main thread
//! what its pixels cost. Each function takes the data and its mapping to
//! pixels (a chart's `backend_coord`) and keeps exactly what changes the
//! picture: a cloud of equal dots one per pixel, a polyline each pixel
//! segment once, vertical lines from a common floor the tallest per column.

use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use std::collections::hash_map::Entry;

/// A pixel position.
pub type Px = (i32, i32);

/// The first point of `points` on each pixel, in their order: a dot drawn
/// at a pixel looks the same however many times it is drawn there.
pub fn one_per_pixel<P: Copy>(points: impl IntoIterator<Item = P>, px: impl Fn(P) -> Px) -> Vec<P> {
    let mut seen = HashSet::default();
    points.into_iter().filter(|&p| seen.insert(px(p))).collect()
}

/// Repeated segments in a row that end a run of [`polyline_runs`]: a
/// shorter repeat is drawn again, so that the runs (one canvas stroke
/// each) stay few: at most one per this many points.
pub const MIN_SKIP: usize = 32;

/// A polyline as runs that leave out what is drawn already: points on the
/// pixel of the point before (a zero-length segment), and stretches of
/// [`MIN_SKIP`] or more segments between pixels already joined, which end
/// a run (the next new segment starts another). An orbit traced a thousand
/// times over the same pixels becomes one run of about one pass; a single
/// point stays a run of one point.
pub fn polyline_runs<P: Copy>(
    points: impl IntoIterator<Item = P>,
    px: impl Fn(P) -> Px,
) -> Vec<Vec<P>> {
    let mut seen: HashSet<(Px, Px)> = HashSet::default();
    let mut runs = Vec::new();
    let mut run: Vec<P> = Vec::new();
    // The points of the repeated segments since the last new one.
    let mut skipped: Vec<P> = Vec::new();
    let mut last: Option<(P, Px)> = None;
    for p in points {
        let q = px(p);
        let Some((lp, lq)) = last else {
            run.push(p);
            last = Some((p, q));
            continue;
        };
        if lq == q {
            continue;
        }
        let key = if lq <= q { (lq, q) } else { (q, lq) };
        if seen.insert(key) {
            if skipped.len() >= MIN_SKIP || run.is_empty() {
                if run.len() > 1 {
                    runs.push(std::mem::take(&mut run));
                }
                run.clear();
                run.push(lp);
            } else {
                run.append(&mut skipped);
            }
            skipped.clear();
            run.push(p);
        } else {
            skipped.push(p);
        }
        last = Some((p, q));
    }
    if run.len() > 1 || (runs.is_empty() && !run.is_empty()) {
        runs.push(run);
    }
    runs
}

/// Of vertical lines `(x, height)` from a common floor, the tallest on each
/// pixel column `column(x)`, in the order of their first line: lines on one
/// column cover the shorter ones.
pub fn tallest_per_column(lines: &[(f64, f64)], column: impl Fn(f64) -> i32) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    let mut at: HashMap<i32, usize> = HashMap::default();
    for &(x, h) in lines {
        match at.entry(column(x)) {
            Entry::Occupied(e) => {
                let k = *e.get();
                if h > out[k].1 {
                    out[k] = (x, h);
                }
            }
            Entry::Vacant(e) => {
                e.insert(out.len());
                out.push((x, h));
            }
        }
    }
    out
}

/// The points from which the page strokes a polyline in one call: a
/// shorter one (a grid line, a tick) costs fewer calls point by point.
pub const LONG_PATH: usize = 32;

/// A long polyline's SVG path data ([`svg_path`]), for the page to stroke
/// in one call (a `Path2D`) rather than one call per point; none for one
/// of fewer than [`LONG_PATH`] points.
pub fn long_path(pts: &[Px]) -> Option<String> {
    (pts.len() >= LONG_PATH).then(|| svg_path(pts))
}

/// The SVG path data of a polyline in pixels, "M1 2L3 4...".
pub fn svg_path(pts: &[Px]) -> String {
    let mut d = String::with_capacity(pts.len() * 10);
    for (k, &(x, y)) in pts.iter().enumerate() {
        d.push(if k == 0 { 'M' } else { 'L' });
        push_int(&mut d, x);
        d.push(' ');
        push_int(&mut d, y);
    }
    d
}

/// SVG path data of polylines in canvas coordinates, "M1 2L3 4.5M...":
/// half pixels kept, one path for many strokes.
pub fn polylines_path(paths: &[Vec<(f64, f64)>]) -> String {
    use std::fmt::Write;
    let mut d = String::with_capacity(paths.iter().map(|p| 12 * p.len()).sum());
    for path in paths {
        for (k, &(x, y)) in path.iter().enumerate() {
            let _ = write!(d, "{}{x} {y}", if k == 0 { 'M' } else { 'L' });
        }
    }
    d
}

/// A line's ends as plotters-canvas strokes them: a horizontal or vertical
/// line half a pixel up or left, on the pixels' centres, so that one pixel
/// wide is sharp.
pub fn crisp_line(from: Px, to: Px) -> Vec<(f64, f64)> {
    let (mut a, mut b) = (
        (f64::from(from.0), f64::from(from.1)),
        (f64::from(to.0), f64::from(to.1)),
    );
    if from.0 == to.0 {
        a.0 -= 0.5;
        b.0 -= 0.5;
    }
    if from.1 == to.1 {
        a.1 -= 0.5;
        b.1 -= 0.5;
    }
    vec![a, b]
}

/// Appends the decimal digits of `v` (no allocation per number).
fn push_int(s: &mut String, v: i32) {
    if v < 0 {
        s.push('-');
    }
    let mut digits = [0u8; 10];
    let mut n = v.unsigned_abs();
    let mut i = digits.len();
    loop {
        i -= 1;
        digits[i] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    s.extend(digits[i..].iter().map(|&b| char::from(b)));
}

#[cfg(test)]
mod tests {
    use super::*;

    fn to_px(p: (f64, f64)) -> Px {
        (p.0.round() as i32, p.1.round() as i32)
    }

    /// The pixel segments a polyline draws (zero-length ones drawn as nothing).
    fn segments(runs: &[Vec<(f64, f64)>]) -> HashSet<(Px, Px)> {
        let mut out = HashSet::default();
        for r in runs {
            for w in r.windows(2) {
                let (a, b) = (to_px(w[0]), to_px(w[1]));
                if a != b {
                    out.insert(if a <= b { (a, b) } else { (b, a) });
                }
            }
        }
        out
    }

    /// A circle of radius 40 px sampled 64 times per turn for 1000 turns:
    /// the runs draw the same pixel segments as the whole polyline, in
    /// about one turn's points.
    #[test]
    fn a_repeated_orbit_is_drawn_about_once() {
        let orbit: Vec<(f64, f64)> = (0..64_000)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 64.0;
                (100.0 + 40.0 * a.cos(), 100.0 + 40.0 * a.sin())
            })
            .collect();
        let runs = polyline_runs(orbit.iter().copied(), to_px);
        assert_eq!(segments(&runs), segments(&[orbit]));
        let drawn: usize = runs.iter().map(|r| r.len().saturating_sub(1)).sum();
        assert!(
            drawn <= 64 + 2 * MIN_SKIP,
            "{drawn} segments for a 64-sided polygon"
        );
    }

    /// A polyline that never repeats itself keeps every point that moves
    /// to another pixel, as one run; a single point stays.
    #[test]
    fn a_fresh_polyline_is_one_run() {
        let line = [
            (0.0, 0.0),
            (0.2, 0.1),
            (3.0, 4.0),
            (10.0, -2.0),
            (10.4, -2.3),
        ];
        let runs = polyline_runs(line, to_px);
        assert_eq!(runs, vec![vec![(0.0, 0.0), (3.0, 4.0), (10.0, -2.0)]]);
        assert_eq!(polyline_runs([(1.0, 1.0)], to_px), vec![vec![(1.0, 1.0)]]);
        assert!(polyline_runs(std::iter::empty::<(f64, f64)>(), to_px).is_empty());
    }

    /// Going back over a short stretch keeps the run whole; a long retraced
    /// stretch ends it, and the next new segment starts another.
    #[test]
    fn only_a_long_retraced_stretch_splits_the_run() {
        let short = [(0.0, 0.0), (5.0, 0.0), (0.0, 0.0), (0.0, 5.0)];
        assert_eq!(polyline_runs(short, to_px), vec![short.to_vec()]);
        // Out along y = 0 in steps of 2 px, back the same way, then up.
        let out: Vec<(f64, f64)> = (0..=40).map(|k| (2.0 * k as f64, 0.0)).collect();
        let mut line = out.clone();
        line.extend(out.iter().rev().skip(1));
        line.push((0.0, 7.0));
        let runs = polyline_runs(line.iter().copied(), to_px);
        assert_eq!(runs, vec![out, vec![(0.0, 0.0), (0.0, 7.0)]]);
        assert_eq!(segments(&runs), segments(&[line]));
    }

    #[test]
    fn a_cloud_keeps_one_dot_per_pixel() {
        let cloud = [(1.1, 1.0), (0.9, 1.2), (5.0, 5.0), (1.0, 1.4), (5.4, 4.6)];
        assert_eq!(one_per_pixel(cloud, to_px), vec![(1.1, 1.0), (5.0, 5.0)]);
    }

    #[test]
    fn the_tallest_line_of_each_column_stays() {
        let lines = [(1.0, 2.0), (1.2, 5.0), (3.0, 1.0), (0.9, 4.0), (2.6, 0.5)];
        let kept = tallest_per_column(&lines, |x| x.round() as i32);
        assert_eq!(kept, vec![(1.2, 5.0), (3.0, 1.0)]);
    }

    /// The path data reads as the points, signs and extremes included.
    #[test]
    fn svg_path_spells_the_points() {
        assert_eq!(svg_path(&[]), "");
        assert_eq!(svg_path(&[(0, 7)]), "M0 7");
        assert_eq!(
            svg_path(&[(12, -3), (760, 400), (-45, 0)]),
            "M12 -3L760 400L-45 0"
        );
        let ext = svg_path(&[(i32::MIN, i32::MAX)]);
        assert_eq!(ext, format!("M{} {}", i32::MIN, i32::MAX));
    }

    /// A path of fewer than 32 points is left to plotters (none); from 32
    /// on it is one path string, with a move then a line per later point.
    #[test]
    fn only_a_long_path_is_one_path_string() {
        let pts: Vec<Px> = (0..40).map(|i| (i, 2 * i)).collect();
        assert_eq!(long_path(&pts[..31]), None);
        let d = long_path(&pts[..32]).expect("a long path");
        assert_eq!((d.matches('M').count(), d.matches('L').count()), (1, 31));
        assert!(d.ends_with("L31 62"));
    }

    #[test]
    fn strokes_batched_as_one_path_keep_their_half_pixels() {
        let h = crisp_line((1, 5), (9, 5));
        let v = crisp_line((3, 0), (3, 7));
        let d = crisp_line((0, 0), (4, 3));
        assert_eq!(h, vec![(1.0, 4.5), (9.0, 4.5)]);
        assert_eq!(v, vec![(2.5, 0.0), (2.5, 7.0)]);
        assert_eq!(d, vec![(0.0, 0.0), (4.0, 3.0)]);
        assert_eq!(
            polylines_path(&[h, v, vec![(1.0, 2.0), (3.0, 4.0), (5.0, -6.0)]]),
            "M1 4.5L9 4.5M2.5 0L2.5 7M1 2L3 4L5 -6"
        );
    }
}
