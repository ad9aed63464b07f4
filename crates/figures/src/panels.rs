//! Mesh panels: the frequency response of several meshes side by side, as
//! the paper's Figs. 2 and 3 show one mesh of each kind in panels a-d.
//!
//! Panels travel in a link as `panels=MESH,MESH,...` (e.g.
//! `panels=s1a1,s2b1,a1b1,rb1`). Each member of a family already holds
//! every mesh's response in its harmonic-balance branch, so the panels are
//! a projection of the same results, never a new computation. Parsing
//! never panics: an unknown mesh, too few or too many names, or a name
//! given twice is refused with a message in words naming it and what is
//! allowed.

use solver::keys;

/// The link key that carries the panels.
pub const PANELS_KEY: &str = "panels";
/// Fewest panels (one mesh is the ordinary view).
pub const MIN_PANELS: usize = 2;
/// Most panels (each one is a chart of its own on one canvas).
pub const MAX_PANELS: usize = 6;

/// A mesh name in plain words: "s1a1 (small sun – short planet a1)".
pub fn mesh_words(name: &str) -> String {
    let kind = if let Some(rest) = name.strip_prefix("s1") {
        format!("small sun – short planet {rest}")
    } else if let Some(rest) = name.strip_prefix("s2") {
        format!("large sun – long planet {rest}")
    } else if let Some(rest) = name.strip_prefix("rb") {
        format!("ring – long planet b{rest}")
    } else if name.starts_with('a') && name.contains('b') {
        let (a, b) = name.split_at(name.find('b').unwrap_or(0));
        format!("short planet {a} – long planet {b}")
    } else if name == "pg" {
        "pinion – gear".to_string()
    } else {
        return name.to_string();
    };
    format!("{name} ({kind})")
}

/// Parses a link's panels value against the model's mesh names.
pub fn parse(text: &str, meshes: &[String]) -> Result<Vec<String>, PanelsError> {
    let names: Vec<&str> = text
        .split([',', ';', ' '])
        .map(str::trim)
        .filter(|t| !t.is_empty())
        .collect();
    if names.len() < MIN_PANELS || names.len() > MAX_PANELS {
        return Err(PanelsError::Count {
            given: names.len().min(1000),
        });
    }
    let mut out: Vec<String> = Vec::with_capacity(names.len());
    for n in names {
        if !meshes.iter().any(|m| m == n) {
            return Err(PanelsError::NoMesh {
                name: keys::truncate(n, 20),
                meshes: meshes.join(", "),
            });
        }
        if out.iter().any(|m| m == n) {
            return Err(PanelsError::Twice {
                name: n.to_string(),
            });
        }
        out.push(n.to_string());
    }
    Ok(out)
}

/// Why a link's panels were refused (one mesh is shown instead).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum PanelsError {
    /// Too few or too many meshes.
    #[error("From the link: side-by-side panels need {MIN_PANELS} to {MAX_PANELS} meshes; {given} were given, so one mesh is shown.")]
    Count {
        /// How many were given (at most 1000 said).
        given: usize,
    },
    /// A mesh the model does not have.
    #[error("From the link: there is no mesh {name} in this model (it has {meshes}), so one mesh is shown.")]
    NoMesh {
        /// The name as given (shortened).
        name: String,
        /// The model's meshes, comma separated.
        meshes: String,
    },
    /// A mesh named twice.
    #[error("From the link: mesh {name} appears twice in the panels, so one mesh is shown.")]
    Twice {
        /// The mesh.
        name: String,
    },
}

/// The link value, e.g. `s1a1,s2b1,a1b1,rb1`.
pub fn encode(panels: &[String]) -> String {
    panels.join(",")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn meshes() -> Vec<String> {
        ["s1a1", "s2b1", "a1b1", "rb1", "s1a2"]
            .iter()
            .map(|s| s.to_string())
            .collect()
    }

    #[test]
    fn panels_round_trip_and_bad_ones_are_named() {
        let p = parse("s1a1,s2b1,a1b1,rb1", &meshes()).unwrap();
        assert_eq!(p.len(), 4);
        assert_eq!(parse(&encode(&p), &meshes()).unwrap(), p);
        let e = parse("s1a1", &meshes()).unwrap_err().to_string();
        assert!(e.contains("2 to 6") && e.contains("1 were"), "{e}");
        let e = parse("s1a1,zz9", &meshes()).unwrap_err().to_string();
        assert!(e.contains("no mesh zz9") && e.contains("s2b1"), "{e}");
        let e = parse("s1a1,s1a1", &meshes()).unwrap_err().to_string();
        assert!(e.contains("twice"), "{e}");
    }

    #[test]
    fn mesh_panels_ride_along_and_bad_ones_are_named() {
        let d = crate::link::decode("family=te_um:5,10&panels=s1a1%2Cs2b1%2Ca1b1%2Crb1");
        assert!(d.issues.is_empty(), "{:?}", d.issues);
        let p = d.panels.clone().unwrap();
        assert_eq!(p, ["s1a1", "s2b1", "a1b1", "rb1"]);
        let q = crate::link::encode_all(&d.settings, None, d.family.as_ref(), Some(&p));
        assert!(q.ends_with("&panels=s1a1%2Cs2b1%2Ca1b1%2Crb1"), "{q}");
        assert_eq!(crate::link::decode(&q).panels, d.panels);
        // The gear pair has no mesh s1a1: named, dropped, the rest applies.
        let d = crate::link::decode("model=gear-pair&panels=s1a1,pg&te_um=7");
        assert_eq!(d.panels, None);
        assert!(d.issues[0].contains("no mesh s1a1"), "{:?}", d.issues);
        assert_eq!(
            solver::keys::get(&d.settings.params, "te_um"),
            Some(solver::keys::Value::Num(7.0))
        );
    }

    #[test]
    fn meshes_are_named_in_words() {
        assert_eq!(mesh_words("s1a1"), "s1a1 (small sun – short planet a1)");
        assert_eq!(mesh_words("s2b1"), "s2b1 (large sun – long planet b1)");
        assert_eq!(
            mesh_words("a1b1"),
            "a1b1 (short planet a1 – long planet b1)"
        );
        assert_eq!(mesh_words("rb1"), "rb1 (ring – long planet b1)");
        assert_eq!(mesh_words("pg"), "pg (pinion – gear)");
    }
}
