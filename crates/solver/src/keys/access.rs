//! Reading and writing a parameter set by key: the mapping from each flat
//! key to its field, model by model (the per-kind keys and shortcuts of the
//! compound model included).

use super::*;
use crate::params::TE_HARMONICS;
use crate::waveform::Wave;

fn kind_of(name: &str, prefix: &str, suffix: &str) -> Option<MeshKind> {
    let mid = name.strip_prefix(prefix)?.strip_suffix(suffix)?;
    MeshKind::COMPOUND.into_iter().find(|k| k.key() == mid)
}

/// `te_cos<n>_<kind>_um` / `te_sin<n>_um`: harmonic `n` (2 ..= TE_HARMONICS),
/// 0 for the cosine or 1 for the sine, and the kind's part of the name
/// (empty on the gear pair).
fn te_harmonic(name: &str) -> Option<(usize, usize, &str)> {
    let rest = name.strip_prefix("te_")?.strip_suffix("_um")?;
    let (part, rest) = if let Some(r) = rest.strip_prefix("cos") {
        (0, r)
    } else {
        (1, rest.strip_prefix("sin")?)
    };
    let digit = rest.chars().next()?.to_digit(10)? as usize;
    if !(2..=TE_HARMONICS).contains(&digit) {
        return None;
    }
    let kind = &rest[1..];
    let kind = if kind.is_empty() {
        kind
    } else {
        kind.strip_prefix('_')?
    };
    Some((digit, part, kind))
}

fn wave_value(w: Wave) -> Option<Value> {
    Some(Value::Text(w.name().into()))
}

fn ratio_value(r: Option<f64>) -> Option<Value> {
    Some(match r {
        Some(x) => Value::Num(x),
        None => Value::Text("auto".into()),
    })
}

fn ratio_of(value: &Value) -> Option<f64> {
    match value {
        Value::Num(x) => Some(*x),
        Value::Text(_) => None,
    }
}

fn num(v: &Value) -> f64 {
    match v {
        Value::Num(x) => *x,
        Value::Text(_) => f64::NAN,
    }
}

fn text(v: &Value) -> &str {
    match v {
        Value::Text(t) => t,
        Value::Num(_) => "",
    }
}

/// Reads a key's value. `None` if the key is unknown or does not apply to the model.
pub fn get(params: &ModelParams, name: &str) -> Option<Value> {
    match (params, name) {
        (_, "model") => Some(Value::Text(params.kind().name().to_string())),
        (ModelParams::Ravigneaux(p), _) => get_ravigneaux(p, name),
        (ModelParams::GearPair(p), _) => match name {
            "stiffness_wave" => wave_value(p.stiffness_shape.wave),
            "contact_ratio" => ratio_value(p.stiffness_shape.contact_ratio),
            _ => get_gear_pair(p, name),
        },
    }
}

fn get_gear_pair(p: &GearPairParams, name: &str) -> Option<Value> {
    if let Some((h, part, "")) = te_harmonic(name) {
        return Some(Value::Num(p.te_um.higher[h - 2][part]));
    }
    Some(Value::Num(match name {
        "stiffness_ramp" => p.stiffness_ramp,
        "stiffness_harmonics" => f64::from(p.stiffness_harmonics),
        "backlash_um" => p.backlash_um,
        "te_um" => p.te_um.sin,
        "te_cos_um" => p.te_um.cos,
        "te_mean_um" => p.te_um.mean,
        "stiffness_variation" => p.stiffness_variation,
        "damping_ratio" => p.damping_ratio,
        "module_mm" => p.module_mm,
        "pressure_angle_deg" => p.pressure_angle_deg,
        "teeth_pinion" => f64::from(p.teeth_pinion),
        "teeth_gear" => f64::from(p.teeth_gear),
        "inertia_pinion_kg_m2" => p.inertia_pinion_kg_m2,
        "inertia_gear_kg_m2" => p.inertia_gear_kg_m2,
        "stiffness_n_m" => p.stiffness_n_m,
        "torque_pinion_nm" => p.torque_pinion_nm,
        _ => return None,
    }))
}

fn get_ravigneaux(p: &RavigneauxParams, name: &str) -> Option<Value> {
    let n = |x: f64| Some(Value::Num(x));
    let te = |kind: MeshKind| &p.te_um[RavigneauxParams::kind_index(kind)];
    match name {
        "backlash_um" => {
            let b = p.backlash_um;
            n(if b.s1a == b.s2b && b.s1a == b.ab && b.s1a == b.rb {
                b.s1a
            } else {
                f64::NAN
            })
        }
        "te_um" => n(p.te_um[0].sin),
        "te_meshes" => Some(Value::Text(p.te_meshes.name().into())),
        "ring_support_radius_mm" => Some(match p.ring_support_radius_mm {
            Some(r) => Value::Num(r),
            None => Value::Text("auto".into()),
        }),
        "stiffness_variation" => n(p.stiffness_variation),
        "stiffness_ramp" => n(p.stiffness_ramp),
        "stiffness_harmonics" => n(f64::from(p.stiffness_harmonics)),
        "damping_ratio" => n(p.damping_ratio),
        "torque_s1_nm" => n(p.torque_s1_nm),
        "torque_s2_nm" => Some(match p.torque_s2_nm {
            Some(t) => Value::Num(t),
            None => Value::Text("auto".into()),
        }),
        "planets" => n(f64::from(p.planets)),
        "phasing" => Some(Value::Text(p.phasing.name().into())),
        "module_mm" => n(p.module_mm),
        "pressure_angle_deg" => n(p.pressure_angle_deg),
        "teeth_s1" => n(f64::from(p.teeth_s1)),
        "teeth_s2" => n(f64::from(p.teeth_s2)),
        "teeth_a" => n(f64::from(p.teeth_a)),
        "teeth_r" => n(f64::from(p.teeth_r)),
        "inertia_s1_kg_m2" => n(p.inertia_s1_kg_m2),
        "inertia_s2_kg_m2" => n(p.inertia_s2_kg_m2),
        "inertia_r_kg_m2" => n(p.inertia_r_kg_m2),
        "inertia_c_kg_m2" => n(p.inertia_c_kg_m2),
        "inertia_a_kg_m2" => n(p.inertia_a_kg_m2),
        "inertia_b_kg_m2" => n(p.inertia_b_kg_m2),
        "mass_a_kg" => n(p.mass_a_kg),
        "mass_b_kg" => n(p.mass_b_kg),
        "ring_support_n_m" => n(p.ring_support_n_m),
        _ => {
            if let Some(k) = kind_of(name, "stiffness_", "_n_m") {
                n(p.stiffness_n_m.get(k))
            } else if let Some(k) = kind_of(name, "backlash_", "_um") {
                n(p.backlash_um.get(k))
            } else if let Some(k) = kind_of(name, "te_sin_", "_um") {
                n(te(k).sin)
            } else if let Some(k) = kind_of(name, "te_cos_", "_um") {
                n(te(k).cos)
            } else if let Some(k) = kind_of(name, "te_mean_", "_um") {
                n(te(k).mean)
            } else if let Some(k) = kind_of(name, "phase_", "_deg") {
                n(p.phase_deg.get(k))
            } else if let Some(k) = kind_of(name, "stiffness_wave_", "") {
                wave_value(p.stiffness_shape[RavigneauxParams::kind_index(k)].wave)
            } else if let Some(k) = kind_of(name, "contact_ratio_", "") {
                ratio_value(p.stiffness_shape[RavigneauxParams::kind_index(k)].contact_ratio)
            } else if let Some((h, part, kind)) = te_harmonic(name) {
                let k = MeshKind::COMPOUND.into_iter().find(|k| k.key() == kind)?;
                n(te(k).higher[h - 2][part])
            } else {
                None
            }
        }
    }
}

/// Writes a key's value after checking its type and range. Setting `model`
/// replaces the whole set by that model's defaults.
pub fn set(params: &mut ModelParams, name: &str, value: Value) -> Result<()> {
    let spec = spec(name).ok_or_else(|| unknown(name))?;
    let shown = match &value {
        Value::Num(x) => format!("{x}"),
        Value::Text(t) => t.clone(),
    };
    check(spec, &value, &shown)?;
    // A typed -0 is stored (and so written back in links) as 0.
    let value = match value {
        Value::Num(x) => Value::Num(x + 0.0),
        v => v,
    };
    if name == "model" {
        let kind = ModelKind::from_name(text(&value)).unwrap_or(ModelKind::Ravigneaux);
        if kind != params.kind() {
            *params = ModelParams::defaults(kind);
        }
        return Ok(());
    }
    if !spec.applies.includes(params.kind()) {
        return Err(SolverError::KeyNotForModel {
            key: name.to_string(),
            model: params.kind().name().to_string(),
        });
    }
    let x = num(&value);
    let int = x as u32;
    match params {
        ModelParams::Ravigneaux(p) => set_ravigneaux(p, name, &value, x, int),
        ModelParams::GearPair(p) => match name {
            "stiffness_wave" => p.stiffness_shape.wave = Wave::from_name(text(&value)),
            "contact_ratio" => p.stiffness_shape.contact_ratio = ratio_of(&value),
            _ => set_gear_pair(p, name, x, int),
        },
    }
    Ok(())
}

fn set_gear_pair(p: &mut GearPairParams, name: &str, x: f64, int: u32) {
    if let Some((h, part, "")) = te_harmonic(name) {
        p.te_um.higher[h - 2][part] = x;
        return;
    }
    match name {
        "stiffness_ramp" => p.stiffness_ramp = x,
        "stiffness_harmonics" => p.stiffness_harmonics = int,
        "backlash_um" => p.backlash_um = x,
        "te_um" => p.te_um.sin = x,
        "te_cos_um" => p.te_um.cos = x,
        "te_mean_um" => p.te_um.mean = x,
        "stiffness_variation" => p.stiffness_variation = x,
        "damping_ratio" => p.damping_ratio = x,
        "module_mm" => p.module_mm = x,
        "pressure_angle_deg" => p.pressure_angle_deg = x,
        "teeth_pinion" => p.teeth_pinion = int,
        "teeth_gear" => p.teeth_gear = int,
        "inertia_pinion_kg_m2" => p.inertia_pinion_kg_m2 = x,
        "inertia_gear_kg_m2" => p.inertia_gear_kg_m2 = x,
        "stiffness_n_m" => p.stiffness_n_m = x,
        "torque_pinion_nm" => p.torque_pinion_nm = x,
        _ => {}
    }
}

fn set_ravigneaux(p: &mut RavigneauxParams, name: &str, value: &Value, x: f64, int: u32) {
    match name {
        "backlash_um" => p.backlash_um = PerKind::all(x),
        "te_um" => match p.te_meshes {
            TeMeshes::S1a => p.te_um[0].sin = x,
            TeMeshes::All => p.te_um.iter_mut().for_each(|te| te.sin = x),
        },
        "te_meshes" => {
            let now = if text(value) == "all" {
                TeMeshes::All
            } else {
                TeMeshes::S1a
            };
            // Switching the reading moves the shortcut's amplitude with it:
            // onto every kind, or off every kind but s1a.
            if now != p.te_meshes {
                let amplitude = p.te_um[0].sin;
                for te in p.te_um.iter_mut().skip(1) {
                    te.sin = if now == TeMeshes::All { amplitude } else { 0.0 };
                }
                p.te_meshes = now;
            }
        }
        "ring_support_radius_mm" => {
            p.ring_support_radius_mm = match value {
                Value::Num(r) => Some(*r),
                Value::Text(_) => None,
            }
        }
        "stiffness_variation" => p.stiffness_variation = x,
        "stiffness_ramp" => p.stiffness_ramp = x,
        "stiffness_harmonics" => p.stiffness_harmonics = int,
        "damping_ratio" => p.damping_ratio = x,
        "torque_s1_nm" => p.torque_s1_nm = x,
        "torque_s2_nm" => {
            p.torque_s2_nm = match value {
                Value::Num(t) => Some(*t),
                Value::Text(_) => None,
            }
        }
        "planets" => p.planets = int,
        "phasing" => {
            p.phasing = if text(value) == "sequential" {
                Phasing::Sequential
            } else {
                Phasing::InPhase
            }
        }
        "module_mm" => p.module_mm = x,
        "pressure_angle_deg" => p.pressure_angle_deg = x,
        "teeth_s1" => p.teeth_s1 = int,
        "teeth_s2" => p.teeth_s2 = int,
        "teeth_a" => p.teeth_a = int,
        "teeth_r" => p.teeth_r = int,
        "inertia_s1_kg_m2" => p.inertia_s1_kg_m2 = x,
        "inertia_s2_kg_m2" => p.inertia_s2_kg_m2 = x,
        "inertia_r_kg_m2" => p.inertia_r_kg_m2 = x,
        "inertia_c_kg_m2" => p.inertia_c_kg_m2 = x,
        "inertia_a_kg_m2" => p.inertia_a_kg_m2 = x,
        "inertia_b_kg_m2" => p.inertia_b_kg_m2 = x,
        "mass_a_kg" => p.mass_a_kg = x,
        "mass_b_kg" => p.mass_b_kg = x,
        "ring_support_n_m" => p.ring_support_n_m = x,
        _ => {
            let te = |k: MeshKind| RavigneauxParams::kind_index(k);
            if let Some(k) = kind_of(name, "stiffness_", "_n_m") {
                *p.stiffness_n_m.get_mut(k) = x;
            } else if let Some(k) = kind_of(name, "backlash_", "_um") {
                *p.backlash_um.get_mut(k) = x;
            } else if let Some(k) = kind_of(name, "te_sin_", "_um") {
                p.te_um[te(k)].sin = x;
            } else if let Some(k) = kind_of(name, "te_cos_", "_um") {
                p.te_um[te(k)].cos = x;
            } else if let Some(k) = kind_of(name, "te_mean_", "_um") {
                p.te_um[te(k)].mean = x;
            } else if let Some(k) = kind_of(name, "phase_", "_deg") {
                *p.phase_deg.get_mut(k) = x;
            } else if let Some(k) = kind_of(name, "stiffness_wave_", "") {
                p.stiffness_shape[te(k)].wave = Wave::from_name(text(value));
            } else if let Some(k) = kind_of(name, "contact_ratio_", "") {
                p.stiffness_shape[te(k)].contact_ratio = ratio_of(value);
            } else if let Some((h, part, kind)) = te_harmonic(name) {
                if let Some(k) = MeshKind::COMPOUND.into_iter().find(|k| k.key() == kind) {
                    p.te_um[te(k)].higher[h - 2][part] = x;
                }
            }
        }
    }
}
