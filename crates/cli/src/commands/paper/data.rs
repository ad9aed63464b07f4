//! Reading the commands' JSON: numbers, the points of a sweep or a branch,
//! the Omega spans where something holds, a run's motion in words.

use serde_json::Value;

/// Omega spans where something holds on a grid: each (first, last) point.
pub type Spans = Vec<(f64, f64)>;

/// A number of the JSON (NaN if missing or null).
pub fn f(x: &Value) -> f64 {
    x.as_f64().unwrap_or(f64::NAN)
}

/// A field in micrometres.
pub fn um(x: &Value) -> f64 {
    f(x) * 1e6
}

/// The items of an array field (none if it is not one).
pub fn items<'a>(v: &'a Value, key: &str) -> &'a [Value] {
    v[key].as_array().map_or(&[], Vec::as_slice)
}

/// The Omega of a point.
pub fn omega(p: &Value) -> f64 {
    f(&p["omega"])
}

/// Half the peak-to-peak of the tooth deflection x (TE included), in µm.
pub fn x_amp(p: &Value) -> f64 {
    um(&p["x_amplitude_m"])
}

/// The points of several sweeps in order of Omega (a point computed by
/// two sweeps appears twice, once from each).
pub fn merged(sweeps: &[&Value]) -> Vec<Value> {
    let mut pts: Vec<Value> = sweeps
        .iter()
        .flat_map(|v| items(v, "points").iter().cloned())
        .collect();
    pts.sort_by(|a, b| omega(a).total_cmp(&omega(b)));
    pts
}

/// The point at `w` (within 1e-6).
pub fn at(points: &[Value], w: f64) -> Option<&Value> {
    points.iter().find(|p| (omega(p) - w).abs() < 1e-6)
}

/// Whether `w` lies in `lo..=hi` (with a rounding margin).
pub fn within(w: f64, lo: f64, hi: f64) -> bool {
    (lo - 1e-9..=hi + 1e-9).contains(&w)
}

/// The largest of `value` over the points with Omega in `lo..=hi` (NaN if
/// there are none).
pub fn largest(points: &[Value], lo: f64, hi: f64, value: impl Fn(&Value) -> f64) -> f64 {
    points
        .iter()
        .filter(|p| within(omega(p), lo, hi))
        .map(value)
        .fold(f64::NAN, f64::max)
}

/// The smallest of `value` over the points with Omega in `lo..=hi`.
pub fn smallest(points: &[Value], lo: f64, hi: f64, value: impl Fn(&Value) -> f64) -> f64 {
    points
        .iter()
        .filter(|p| within(omega(p), lo, hi))
        .map(value)
        .fold(f64::NAN, f64::min)
}

/// Contiguous runs of grid points where `pred` holds. A point computed by
/// two sweeps counts as holding if either says so.
pub fn spans(points: &[Value], pred: impl Fn(&Value) -> bool) -> Spans {
    runs_of(points, pred, true)
}

/// Contiguous runs of grid points where `pred` does not hold: the gaps
/// between [`spans`]' runs (a point computed twice counts as holding if
/// either run says so).
pub fn spans_not(points: &[Value], pred: impl Fn(&Value) -> bool) -> Spans {
    runs_of(points, pred, false)
}

fn runs_of(points: &[Value], pred: impl Fn(&Value) -> bool, want: bool) -> Spans {
    let mut grid: Vec<(f64, bool)> = Vec::new();
    for p in points {
        let (w, holds) = (omega(p), pred(p));
        match grid.last_mut() {
            Some(last) if (last.0 - w).abs() < 1e-9 => last.1 |= holds,
            _ => grid.push((w, holds)),
        }
    }
    let mut out: Spans = Vec::new();
    let mut run: Option<(f64, f64)> = None;
    for (w, holds) in grid {
        if holds == want {
            run = Some(run.map_or((w, w), |(a, _)| (a, w)));
        } else if let Some(r) = run.take() {
            out.push(r);
        }
    }
    out.extend(run);
    out
}

/// The first point where `pred` holds.
pub fn first(points: &[Value], pred: impl Fn(&Value) -> bool) -> Option<f64> {
    points.iter().find(|p| pred(p)).map(omega)
}

/// The motion of a run in the document's words: "period n" or, for a
/// motion that is not periodic, what its Lyapunov exponent says.
pub fn motion(v: &Value) -> String {
    if let Some(n) = v["period"].as_u64() {
        return format!("period {n}");
    }
    let verdict = v["verdict"].as_str().unwrap_or_default();
    if verdict.contains("Lyapunov") {
        verdict.rsplit(": ").next().unwrap_or(verdict).to_string()
    } else {
        "not periodic".into()
    }
}

/// Whether some mesh's drive flanks part at a swept point (the worst of
/// the twelve meshes).
pub fn any_part(p: &Value) -> bool {
    matches!(
        p["impact_worst"].as_str(),
        Some("single-sided" | "double-sided")
    )
}

/// Whether the back flanks of some mesh touch at a swept point.
pub fn any_back(p: &Value) -> bool {
    p["impact_worst"] == "double-sided"
}

/// Whether the drive flanks of the reported mesh part.
pub fn mesh_parts(p: &Value) -> bool {
    matches!(p["impact"].as_str(), Some("single-sided" | "double-sided"))
}

/// One mesh's branch out of a `--mesh all` frequency response, each point
/// with its Omega and stability.
pub fn branch_of(v: &Value, mesh: &str) -> Vec<Value> {
    items(v, "branch")
        .iter()
        .map(|p| {
            let mut m = p["meshes"][mesh].clone();
            m["omega"] = p["omega"].clone();
            m["stable"] = p["stable"].clone();
            m
        })
        .collect()
}

/// Whether a branch point is stable (Floquet multipliers inside the unit
/// circle).
pub fn stable(p: &Value) -> bool {
    p["stable"] == true
}
