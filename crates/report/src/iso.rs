//! The dynamic factor K_v of ISO 6336-1 (method B) beside the model's own,
//! as JSON: added to `gearshock simulate`'s output per mesh, with the
//! inputs it used and every intermediate quantity of the standard.

use serde_json::{json, Map, Value};
use solver::iso6336::{rate_model, IsoInputs, ModelMeshRating};
use solver::params::ModelParams;
use solver::steady::Model;

use crate::num;

fn opt(x: Option<f64>) -> Value {
    x.map_or(Value::Null, num)
}

/// The inputs as JSON (`null`: the standard's default rule, see
/// `solver::iso6336`).
pub fn iso_inputs_json(i: &IsoInputs) -> Value {
    json!({
        "accuracy_grade": num(i.accuracy_grade),
        "face_width_mm": num(i.face_width_mm),
        "application_factor": num(i.application_factor),
        "tip_relief_um": opt(i.tip_relief_um),
        "running_in_pitch_um": opt(i.running_in_pitch_um),
        "running_in_profile_um": opt(i.running_in_profile_um),
        "sigma_hlim_n_mm2": num(i.sigma_hlim_n_mm2),
    })
}

fn mesh_json(model: &Model, r: &ModelMeshRating, mesh_freq_hz: f64) -> Value {
    let g = &r.rating;
    let n = g.resonance_ratio(mesh_freq_hz);
    let mut o = Map::new();
    o.insert("kv".into(), num(g.kv(n)));
    o.insert("resonance_ratio".into(), num(n));
    o.insert("range".into(), json!(g.range(n).name()));
    if let Value::Object(rest) = rating_json(model, r) {
        o.extend(rest);
    }
    Value::Object(o)
}

/// What the standard rates of one mesh whatever the speed.
fn rating_json(model: &Model, r: &ModelMeshRating) -> Value {
    let g = &r.rating;
    json!({
        "resonance_mesh_freq_hz": num(g.resonance_mesh_freq_hz),
        "resonance_input_speed_rpm": num(model.system.speed.input_speed_rpm(g.resonance_mesh_freq_hz)),
        "teeth": [r.mesh.teeth_1, r.mesh.teeth_2],
        "internal": r.mesh.internal,
        "contact_ratio": num(g.contact_ratio),
        "reduced_mass_kg_mm": num(g.reduced_mass_kg_mm),
        "mesh_stiffness_n_mm_um": num(g.mesh_stiffness_n_mm_um),
        "single_stiffness_n_mm_um": num(g.single_stiffness_n_mm_um),
        "tangential_load_n": num(r.mesh.tangential_load_n),
        "line_load_n_mm": num(g.line_load_n_mm),
        "pitch_deviation_um": num(g.pitch_deviation_um),
        "profile_deviation_um": num(g.profile_deviation_um),
        "running_in_pitch_um": num(g.running_in_pitch_um),
        "running_in_profile_um": num(g.running_in_profile_um),
        "tip_relief_um": num(g.tip_relief_um),
        "b_p": num(g.b_p),
        "b_f": num(g.b_f),
        "b_k": num(g.b_k),
        "n_s": num(g.n_s),
    })
}

/// The method, the inputs and the planetary rule, as every K_v block
/// starts.
fn iso_head(inputs: &IsoInputs) -> Map<String, Value> {
    let mut iso = Map::new();
    iso.insert("method".into(), json!("ISO 6336-1, method B"));
    iso.insert("inputs".into(), iso_inputs_json(inputs));
    iso.insert(
        "planetary_rule".into(),
        json!(
            "sun-planet: m_red = m_P m_S / (m_S + p m_P); planet-ring: m_red = m_P (ring \
             infinitely heavy); planet-planet: a plain pair; m = J / r_b^2"
        ),
    );
    iso
}

/// Adds K_v to a frequency response's JSON (`frf_json` or
/// `shooting_frf_json`): `kv_iso6336` beside each branch point's
/// extremes, per reported mesh (inlined with one mesh, under `meshes`
/// with several), at the point's mesh frequency; and `iso6336` with the
/// inputs and each reported mesh's speed-independent quantities. Where
/// the standard cannot rate the model, every `kv_iso6336` is `null` and
/// `iso6336.error` says why.
pub fn add_branch_iso6336(
    value: &mut Value,
    params: &ModelParams,
    model: &Model,
    inputs: &IsoInputs,
) {
    let mut iso = iso_head(inputs);
    let names: Vec<String> = value["meshes"]
        .as_array()
        .map(|a| {
            a.iter()
                .filter_map(|n| n.as_str().map(str::to_string))
                .collect()
        })
        .unwrap_or_default();
    let ratings = match rate_model(params, model, inputs) {
        Ok(rs) => rs,
        Err(e) => {
            iso.insert("error".into(), json!(e.to_string()));
            Vec::new()
        }
    };
    let rated: Vec<(String, Option<&ModelMeshRating>)> = names
        .iter()
        .map(|n| {
            let r = model.system.mesh_index(n).and_then(|j| ratings.get(j));
            (n.clone(), r)
        })
        .collect();
    if !ratings.is_empty() {
        let meshes: Map<String, Value> = rated
            .iter()
            .filter_map(|(n, r)| Some((n.clone(), rating_json(model, (*r)?))))
            .collect();
        iso.insert("meshes".into(), Value::Object(meshes));
    }
    let one = rated.len() == 1;
    if let Some(points) = value["branch"].as_array_mut() {
        for p in points {
            let Some(omega) = p["omega"].as_f64() else {
                continue;
            };
            let hz = model.system.mesh_freq_hz(omega);
            for (name, r) in &rated {
                let kv = r.map_or(Value::Null, |r| {
                    num(r.rating.kv(r.rating.resonance_ratio(hz)))
                });
                let at = if one { &mut *p } else { &mut p["meshes"][name] };
                if let Some(o) = at.as_object_mut() {
                    o.insert("kv_iso6336".into(), kv);
                }
            }
        }
    }
    value["iso6336"] = Value::Object(iso);
}

/// Adds K_v to a `simulate_json` value at `mesh_freq_hz`: `kv_iso6336`
/// beside `dynamic_factor` (for the reported mesh `mesh` and under each
/// of `all_meshes`), and `iso6336` with the inputs and each mesh's
/// quantities. Where the standard cannot rate the model (a mesh without
/// load), every `kv_iso6336` is `null` and `iso6336.error` says why.
pub fn add_iso6336(
    value: &mut Value,
    params: &ModelParams,
    model: &Model,
    mesh: usize,
    mesh_freq_hz: f64,
    inputs: &IsoInputs,
) {
    let mut iso = iso_head(inputs);
    let ratings = rate_model(params, model, inputs);
    let kvs: Vec<Value> = match &ratings {
        Ok(rs) => {
            let mut meshes = Map::new();
            let mut kvs = Vec::new();
            for (m, r) in model.system.meshes.iter().zip(rs) {
                let j = mesh_json(model, r, mesh_freq_hz);
                kvs.push(j["kv"].clone());
                meshes.insert(m.name.clone(), j);
            }
            iso.insert("meshes".into(), Value::Object(meshes));
            kvs
        }
        Err(e) => {
            iso.insert("error".into(), json!(e.to_string()));
            vec![Value::Null; model.system.meshes.len()]
        }
    };
    value["kv_iso6336"] = kvs.get(mesh).cloned().unwrap_or(Value::Null);
    if let Some(all) = value["all_meshes"].as_object_mut() {
        for (m, kv) in model.system.meshes.iter().zip(&kvs) {
            if let Some(o) = all.get_mut(&m.name).and_then(Value::as_object_mut) {
                o.insert("kv_iso6336".into(), kv.clone());
            }
        }
    }
    value["iso6336"] = Value::Object(iso);
}
