//! Plain-text tables: `--format csv` outputs and the key listing.

use report::{display_shape, num};
use serde_json::Value;
use solver::keys::{self, KEYS};
use solver::params::ModelParams;
use solver::steady::{Model, SteadyState};
use std::fmt::Write;

fn cell(v: &Value) -> String {
    match v {
        Value::Null => String::new(),
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// `params --format csv`: key, value, unit.
pub fn params(p: &ModelParams) -> String {
    let mut s = String::from("key,value,unit\n");
    for spec in keys::primary_keys(p.kind()) {
        if let Some(v) = keys::get(p, spec.name) {
            let _ = writeln!(
                s,
                "{},{},{}",
                spec.name,
                cell(&keys::value_to_json(&v)),
                spec.unit
            );
        }
    }
    s
}

/// One line per key, `row` formatting its name, unit, models, allowed
/// values and meaning.
fn key_rows(mut s: String, row: fn(&mut String, [&str; 5])) -> String {
    for k in KEYS.iter() {
        let models = match k.applies {
            keys::Applies::Both => "both",
            keys::Applies::Ravigneaux => "ravigneaux",
            keys::Applies::GearPair => "gear-pair",
        };
        let allowed = k.ty.allowed();
        row(&mut s, [k.name, k.unit, models, &allowed, k.description]);
    }
    s
}

/// `keys`: an aligned text listing.
pub fn keys_text() -> String {
    key_rows(
        String::new(),
        |s, [name, unit, models, allowed, meaning]| {
            let _ = writeln!(
                s,
                "{name:<24} {unit:<7} {models:<11} {allowed:<28} {meaning}"
            );
        },
    )
}

/// `keys --markdown`: the table of docs/model.md.
pub fn keys_markdown() -> String {
    let head = String::from("| key | unit | models | allowed | meaning |\n|---|---|---|---|---|\n");
    key_rows(head, |s, [name, unit, models, allowed, meaning]| {
        let _ = writeln!(
            s,
            "| `{name}` | {unit} | {models} | {allowed} | {meaning} |"
        );
    })
}

/// `modes --format csv`: one row per mode, the shape in coordinate columns.
pub fn modes(model: &Model) -> String {
    let mut s = String::from("frequency_hz,omega,kind,multiplicity");
    for n in &model.system.dof_names {
        let _ = write!(s, ",{n}");
    }
    s.push('\n');
    for m in &model.modes.modes {
        let _ = write!(
            s,
            "{},{},{},{}",
            m.frequency_hz,
            m.omega,
            m.kind.name(),
            m.multiplicity
        );
        for x in display_shape(m) {
            let _ = write!(s, ",{x}");
        }
        s.push('\n');
    }
    s
}

/// `simulate --format csv`: the recorded time history of the mesh.
pub fn history(ss: &SteadyState, mesh: usize) -> String {
    let mut s = String::from("t_s,delta_m,velocity_m_s,relative_m,force_n\n");
    if let Some(h) = ss.histories.iter().find(|h| h.mesh == mesh) {
        for (i, t) in ss.sample_times_s.iter().enumerate() {
            let _ = writeln!(
                s,
                "{},{},{},{},{}",
                cell(&num(*t)),
                cell(&num(h.delta_m[i])),
                cell(&num(h.velocity_m_s[i])),
                cell(&num(h.rel_m[i])),
                cell(&num(h.force_n[i]))
            );
        }
    }
    s
}

/// `bifurcation --format csv`: one row per Poincaré sample.
pub fn sweep(v: &Value) -> String {
    let mut s = String::from("omega,direction,mesh,sample,delta_m,velocity_m_s,impact,period\n");
    let mesh_names: Vec<String> = v["spec"]["meshes"]
        .as_array()
        .map(|a| a.iter().map(cell).collect())
        .unwrap_or_default();
    let Some(points) = v["points"].as_array() else {
        return s;
    };
    for p in points {
        let omega = cell(&p["omega"]);
        let dir = cell(&p["direction"]);
        let period = cell(&p["period"]);
        for (name, m) in mesh_rows(&mesh_names, p) {
            let d = m["poincare_delta_m"]
                .as_array()
                .cloned()
                .unwrap_or_default();
            let vel = m["poincare_velocity_m_s"]
                .as_array()
                .cloned()
                .unwrap_or_default();
            for (k, (dk, vk)) in d.iter().zip(&vel).enumerate() {
                let _ = writeln!(
                    s,
                    "{omega},{dir},{name},{k},{},{},{},{period}",
                    cell(dk),
                    cell(vk),
                    cell(&m["impact"])
                );
            }
        }
    }
    s
}

/// A point's rows, one per mesh: with one mesh the point itself carries its
/// fields, with several each mesh's are under `meshes`.
fn mesh_rows<'a>(mesh_names: &[String], p: &'a Value) -> Vec<(String, &'a Value)> {
    match mesh_names {
        [one] => vec![(one.clone(), p)],
        names => names.iter().map(|n| (n.clone(), &p["meshes"][n])).collect(),
    }
}

/// A frequency-response branch: one row per point and mesh, in continuation order.
pub fn frf(v: &Value) -> String {
    branch_rows(v, &[])
}

/// A shooting branch: as [`frf`], with each point's piece (the branch it
/// lies on: 0 the first, then each switched or restarted one) and period
/// in mesh periods.
pub fn shooting_frf(v: &Value) -> String {
    branch_rows(v, &["piece", "period"])
}

/// A branch's rows: `index`, the point's fields `extra`, then Omega, the
/// mesh's extremes, stability, bifurcation and ISO 6336-1's K_v.
fn branch_rows(v: &Value, extra: &[&str]) -> String {
    let mut s = String::from("index,");
    for e in extra {
        s.push_str(e);
        s.push(',');
    }
    s.push_str(
        "omega,mesh,delta_max_m,delta_min_m,delta_amplitude_m,x_max_m,x_min_m,impact,stable,bifurcation,kv_iso6336\n",
    );
    let mesh_names: Vec<String> = v["meshes"]
        .as_array()
        .map(|a| a.iter().map(cell).collect())
        .unwrap_or_default();
    let Some(points) = v["branch"].as_array() else {
        return s;
    };
    for (i, p) in points.iter().enumerate() {
        let head: String = extra.iter().map(|e| format!("{},", cell(&p[*e]))).collect();
        for (name, m) in mesh_rows(&mesh_names, p) {
            s.push_str(&format!(
                "{i},{head}{},{name},{},{},{},{},{},{},{},{},{}\n",
                cell(&p["omega"]),
                cell(&m["delta_max_m"]),
                cell(&m["delta_min_m"]),
                cell(&m["delta_amplitude_m"]),
                cell(&m["x_max_m"]),
                cell(&m["x_min_m"]),
                cell(&m["impact"]),
                cell(&p["stable"]),
                cell(&p["bifurcation"]),
                cell(&m["kv_iso6336"]),
            ));
        }
    }
    s
}

/// A table of one row per element of `items`: `header`, then each
/// element's `fields` (commas inside a text replaced by semicolons).
fn table(header: &str, items: Option<&Vec<Value>>, fields: &[&str]) -> String {
    let mut s = format!("{header}\n");
    for item in items.into_iter().flatten() {
        let row: Vec<String> = fields
            .iter()
            .map(|f| cell(&item[*f]).replace(',', ";"))
            .collect();
        s.push_str(&row.join(","));
        s.push('\n');
    }
    s
}

/// A regime map: one row per cell.
pub fn map(v: &Value) -> String {
    let key = cell(&v["spec"]["key"]);
    table(
        &format!("row,column,omega,{key},impact,period,error"),
        v["cells"].as_array(),
        &[
            "row", "column", "omega", "value", "impact", "period", "error",
        ],
    )
}

/// A Lyapunov sweep: one row per Omega.
pub fn lyapunov(v: &Value) -> String {
    let fields = ["omega", "exponent_per_period", "exponent_per_s"];
    table(&fields.join(","), v["points"].as_array(), &fields)
}

/// A parametric-instability scan: one row per Omega.
pub fn instability(v: &Value) -> String {
    let fields = ["omega", "spectral_radius", "growth_per_period", "unstable"];
    table(&fields.join(","), v["points"].as_array(), &fields)
}

/// Boundaries: one row per curve point (`curve` its index, `kind` its
/// name), then the cusps as rows of kind `cusp` (`curve` the fold curve).
pub fn boundaries(v: &Value) -> String {
    let key = cell(&v["spec"]["key"]);
    let mut s = format!("curve,kind,omega,{key},stable_side\n");
    for (i, c) in v["curves"].as_array().into_iter().flatten().enumerate() {
        for p in c["points"].as_array().into_iter().flatten() {
            let _ = writeln!(
                s,
                "{i},{},{},{},{}",
                cell(&c["kind"]),
                cell(&p["omega"]),
                cell(&p["value"]),
                cell(&p["stable_side"])
            );
        }
    }
    for c in v["cusps"].as_array().into_iter().flatten() {
        let _ = writeln!(
            s,
            "{},cusp,{},{},",
            cell(&c["curve"]),
            cell(&c["omega"]),
            cell(&c["value"])
        );
    }
    s
}
