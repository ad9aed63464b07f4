//! `gearshock presets`: every preset of the page (the paper's figures panel
//! for panel, the Table 1 defaults and the teaching cases) as JSON, read
//! from the same table the page uses (`figures::presets`).

use figures::presets::{Preset, PRESETS};
use serde_json::{json, Map, Value};

/// A link value as JSON: a number where it reads as one, a word otherwise.
fn typed(text: &str) -> Value {
    text.parse::<f64>()
        .ok()
        .filter(|x| x.is_finite())
        .map_or_else(|| Value::String(text.to_string()), keys_number)
}

/// Whole numbers as integers (as `gearshock params` writes them).
fn keys_number(x: f64) -> Value {
    solver::keys::value_to_json(&solver::keys::Value::Num(x))
}

/// One preset as JSON: `id`, `title`, `settings` (flat link keys, including
/// `omega` where one Omega is selected), `family` ({`key`, `values`} or
/// null), `meshes` (the panels' meshes or null), `note`, `query` (the link
/// of the first member) and `pinned` (an A/B comparison's state A or null).
pub fn preset_json(p: &Preset) -> Value {
    let settings: Map<String, Value> = p
        .settings
        .iter()
        .map(|(k, v)| ((*k).to_string(), typed(v)))
        .collect();
    json!({
        "id": p.id,
        "title": p.title,
        "settings": settings,
        "family": p.family.map(|f| json!({
            "key": f.key,
            "values": f.values.iter().map(|x| keys_number(*x)).collect::<Vec<_>>(),
        })),
        "meshes": p.meshes,
        "note": p.note,
        "query": p.query(),
        "pinned": p.pinned,
    })
}

/// Every preset, in the page's menu order.
pub fn all_json() -> Value {
    json!({ "presets": PRESETS.iter().map(preset_json).collect::<Vec<_>>() })
}

/// Prints the preset table.
pub fn run() -> Result<(), crate::failure::Failure> {
    crate::output::emit(&all_json())
}
