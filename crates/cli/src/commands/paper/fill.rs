//! The named values a template quotes (`{{name}}`), filling them in, and
//! the premises the template's fixed words rest on: a sentence such as
//! "no period 2 appears" is written once in the template, and
//! [`Values::ensure`] refuses to render it when the record no longer
//! bears it out.

use crate::failure::Failure;
use std::collections::BTreeMap;

/// The values by name, and the premises that failed.
#[derive(Default)]
pub struct Values {
    named: BTreeMap<String, String>,
    failed: Vec<String>,
}

impl Values {
    /// Sets `name` (a second value for the same name is a bug in the
    /// renderer, reported as a failed premise).
    pub fn set(&mut self, name: &str, value: impl Into<String>) {
        if self.named.insert(name.to_string(), value.into()).is_some() {
            self.failed.push(format!("{{{{{name}}}}} is set twice"));
        }
    }

    /// The value of `name`, if set.
    pub fn get(&self, name: &str) -> Option<&str> {
        self.named.get(name).map(String::as_str)
    }

    /// Records a premise of the template's words: `holds` must be true for
    /// the sentence `words` to be rendered.
    pub fn ensure(&mut self, holds: bool, words: &str) {
        if !holds {
            self.failed.push(words.to_string());
        }
    }

    /// Fills every `{{name}}` of `template`; fails on a name without a
    /// value, and on every premise that does not hold.
    pub fn fill(&self, template: &str) -> Result<String, Failure> {
        let mut out = String::with_capacity(template.len() * 2);
        let mut rest = template;
        let mut unknown = Vec::new();
        while let Some(start) = rest.find("{{") {
            out.push_str(&rest[..start]);
            let after = &rest[start + 2..];
            let Some(end) = after.find("}}") else {
                return Err(bug(format!("an unclosed {{{{ in: {}", head(after))));
            };
            let name = &after[..end];
            match self.named.get(name) {
                Some(v) => out.push_str(v),
                None => unknown.push(name.to_string()),
            }
            rest = &after[end + 2..];
        }
        out.push_str(rest);
        if !unknown.is_empty() {
            return Err(bug(format!("no value for {}", unknown.join(", "))));
        }
        Ok(out)
    }

    /// Fails if a premise does not hold.
    pub fn premises(&self) -> Result<(), Failure> {
        if self.failed.is_empty() {
            Ok(())
        } else {
            Err(Failure {
                code: 1,
                message: format!(
                    "the paper's words no longer hold; rewrite them (crates/cli/src/commands/paper/): {}",
                    self.failed.join("; ")
                ),
            })
        }
    }
}

fn head(s: &str) -> &str {
    s.char_indices().nth(40).map_or(s, |(i, _)| &s[..i])
}

fn bug(message: String) -> Failure {
    Failure { code: 1, message }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fills_names_and_refuses_unknown_ones_and_failed_premises() {
        let mut v = Values::default();
        v.set("a.b", "1.5");
        assert_eq!(v.fill("x {{a.b}} y").ok().as_deref(), Some("x 1.5 y"));
        assert!(v.fill("{{nope}}").is_err());
        assert!(v.fill("{{a.b").is_err());
        assert!(v.premises().is_ok());
        v.ensure(false, "no period 2 appears");
        assert!(v.premises().is_err());
    }
}
