//! `gearshock campbell`: the natural frequencies against the input
//! member's speed, the mesh-frequency orders, and their crossings (the
//! critical speeds) with the mode and how much the planets' phasing lets
//! the meshes excite it (`solver::campbell`); with sequentially phased
//! planets also the planet-pass orders and their crossings.

use crate::args::{stream_header, ParamArgs};
use crate::failure::Failure;
use crate::output::output;
use clap::Args;
use serde_json::{json, Value};
use solver::campbell::{rpm_at, Campbell, CANCELLED, MAX_ORDER};
use solver::params::Phasing;
use solver::{ModelKind, ModelParams};

/// Options of `gearshock campbell`.
#[derive(Debug, Args)]
pub struct CampbellArgs {
    #[command(flatten)]
    p: ParamArgs,
    /// Lowest input speed (rpm of the small sun s1, or of the pinion).
    #[arg(long, default_value_t = 0.0)]
    rpm_from: f64,
    /// Highest input speed (rpm); default: the speed at Omega 2.
    #[arg(long)]
    rpm_to: Option<f64>,
    /// Mesh-frequency orders drawn, 1 up to this.
    #[arg(long, default_value_t = 4)]
    orders: u32,
}

/// Builds the diagram and prints it.
pub fn run(a: &CampbellArgs) -> Result<(), Failure> {
    let (params, model) = a.p.load()?;
    let rpm_to = a.rpm_to.unwrap_or_else(|| rpm_at(&model, 2.0));
    check(a.rpm_from, rpm_to, a.orders)?;
    let mut c = Campbell::new(&model, a.rpm_from, rpm_to, a.orders)?;
    if let ModelParams::Ravigneaux(p) = &params {
        if p.phasing == Phasing::Sequential {
            let carrier = model.system.speed.carrier_per_input();
            c = c.with_planet_pass(p.planets, carrier, a.orders)?;
        }
    }
    let input = match model.system.model {
        ModelKind::GearPair => "pinion",
        ModelKind::Ravigneaux => "s1",
    };
    let mut value = stream_header(&model, &params, None);
    value["input_member"] = json!(input);
    value["mesh_hz_per_rpm"] = json!(c.mesh_hz_per_rpm);
    value["omega_ref_rad_s"] = json!(model.system.omega_ref_rad_s);
    value["rpm_from"] = json!(c.rpm_range.0);
    value["rpm_to"] = json!(c.rpm_range.1);
    value["orders"] = json!(c.orders);
    value["modes"] = c
        .modes
        .iter()
        .map(|m| {
            json!({
                "frequency_hz": m.frequency_hz,
                "omega": m.omega,
                "kind": m.kind.name(),
                "multiplicity": m.multiplicity,
                "participation": m.participation,
            })
        })
        .collect();
    value["crossings"] = c
        .crossings
        .iter()
        .map(|x| {
            let m = &c.modes[x.mode];
            json!({
                "rpm": x.rpm,
                "order": x.order,
                "omega": x.omega,
                "mesh_frequency_hz": x.mesh_frequency_hz,
                "mode": x.mode,
                "mode_kind": m.kind.name(),
                "mode_frequency_hz": m.frequency_hz,
                "multiplicity": m.multiplicity,
                "participation": x.participation,
                "excited": x.participation > CANCELLED,
            })
        })
        .collect();
    value["planet_pass"] = c.planet_pass.as_ref().map_or(Value::Null, |pp| {
        json!({
            "planets": pp.planets,
            "hz_per_rpm": pp.hz_per_rpm,
            "orders": pp.orders,
            "crossings": pp.crossings.iter().map(|x| {
                let m = &c.modes[x.mode];
                json!({
                    "rpm": x.rpm,
                    "order": x.order,
                    "omega": x.omega,
                    "mesh_order": x.mesh_order,
                    "mode": x.mode,
                    "mode_kind": m.kind.name(),
                    "mode_frequency_hz": m.frequency_hz,
                })
            }).collect::<Vec<_>>(),
        })
    });
    output(a.p.format, &value, csv)
}

/// Refuses a speed range or an order count outside what the diagram takes,
/// naming the option and the allowed values.
fn check(rpm_from: f64, rpm_to: f64, orders: u32) -> Result<(), Failure> {
    const MAX_RPM: f64 = 1e6;
    if !rpm_from.is_finite() || !(0.0..MAX_RPM).contains(&rpm_from) {
        return Err(crate::failure::usage(format!(
            "--rpm-from {rpm_from} is out of range: allowed 0 up to 1 000 000 rpm"
        )));
    }
    if !rpm_to.is_finite() || rpm_to <= rpm_from || rpm_to > MAX_RPM {
        return Err(crate::failure::usage(format!(
            "--rpm-to {rpm_to} is out of range: allowed above --rpm-from ({rpm_from}) up to 1 000 000 rpm"
        )));
    }
    if !(1..=MAX_ORDER).contains(&orders) {
        return Err(crate::failure::usage(format!(
            "--orders {orders} is out of range: allowed 1 ..= {MAX_ORDER}"
        )));
    }
    Ok(())
}

/// The crossings as one CSV table: the mesh orders', then the planet-pass
/// orders' (`line` says which; their mesh frequency, multiplicity,
/// participation and excitation are left blank).
fn csv(v: &Value) -> String {
    let mut out = String::from(
        "rpm,order,omega,mesh_frequency_hz,mode,mode_kind,mode_frequency_hz,multiplicity,participation,excited,line\n",
    );
    for x in v["crossings"].as_array().into_iter().flatten() {
        out.push_str(&format!(
            "{},{},{},{},{},{},{},{},{},{}",
            x["rpm"],
            x["order"],
            x["omega"],
            x["mesh_frequency_hz"],
            x["mode"],
            x["mode_kind"].as_str().unwrap_or(""),
            x["mode_frequency_hz"],
            x["multiplicity"],
            x["participation"],
            x["excited"]
        ));
        out.push_str(",mesh order\n");
    }
    for x in v["planet_pass"]["crossings"]
        .as_array()
        .into_iter()
        .flatten()
    {
        out.push_str(&format!(
            "{},{},{},,{},{},{},,,,planet-pass order\n",
            x["rpm"],
            x["order"],
            x["omega"],
            x["mode"],
            x["mode_kind"].as_str().unwrap_or(""),
            x["mode_frequency_hz"],
        ));
    }
    out
}
