//! A parameter family's small multiples: one panel per member (the
//! paper's panels a-c, d-f), each with its letter and value in words and
//! the member's data or why there is none yet. The plots draw the panels
//! side by side on shared axes (`plots::multiples`).

/// One panel of a small multiple.
#[derive(Debug, Clone)]
pub struct Panel<T> {
    /// "(a) TE 0 µm".
    pub title: String,
    /// The member's data, or why there is none yet.
    pub data: Result<T, String>,
}

/// The panel titles of values labelled `labels`, lettered from `offset`
/// ("(a) TE 0 µm", ...; the Poincaré panels of a figure start at d).
pub fn panel_titles(labels: &[String], offset: usize) -> Vec<String> {
    labels
        .iter()
        .enumerate()
        .map(|(i, l)| {
            let letter = char::from(b'a' + ((i + offset) % 26) as u8);
            format!("({letter}) {l}")
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn panels_are_lettered_in_order_from_the_offset() {
        let labels = vec!["TE 0 µm".to_string(), "TE 20 µm".into(), "TE 30 µm".into()];
        assert_eq!(
            panel_titles(&labels, 0),
            vec!["(a) TE 0 µm", "(b) TE 20 µm", "(c) TE 30 µm"]
        );
        assert_eq!(panel_titles(&labels, 3)[2], "(f) TE 30 µm");
    }
}
