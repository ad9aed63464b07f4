//! Shard files read as a stream: the fields of a file's top-level object
//! are kept up to its list of items (a sweep's `points`, a map's `cells`),
//! whose items are then handed over one at a time, so that `merge` never
//! holds a whole shard, let alone all of them. A key given twice in any
//! object is refused, named, as in every JSON file gearshock reads.

use crate::failure::Failure;
use crate::input::Unique;
use serde::de::{self, DeserializeSeed, IgnoredAny, MapAccess, SeqAccess, Visitor};
use serde_json::{Map, Value};
use std::fmt;

/// What a streamed file's list is handed to.
pub trait Sink {
    /// The list `key` starts; `head` holds the fields read before it.
    fn head(&mut self, key: &str, head: &Map<String, Value>) -> Result<(), Failure>;
    /// One item of the list.
    fn item(&mut self, v: Value) -> Result<(), Failure>;
}

/// A file's top-level fields before its list, and whether it had a list.
pub struct Read {
    /// The fields before the list (all of them if it had none).
    pub head: Map<String, Value>,
    /// Whether one of the list keys was found (and streamed to the sink).
    pub listed: bool,
}

/// Reads the JSON object in `reader`, handing the first field named one of
/// `keys` to `sink` item by item (fields after it are read and dropped).
/// A sink's failure stops the reading and is returned as it is; other
/// failures are a JSON error for the caller to word.
pub fn read(
    reader: impl std::io::Read,
    keys: &[&str],
    sink: &mut dyn Sink,
) -> Result<Read, Result<Failure, serde_json::Error>> {
    let mut stopped = None;
    let mut de = serde_json::Deserializer::from_reader(reader);
    let top = Top {
        keys,
        sink,
        stopped: &mut stopped,
    };
    let read = top.deserialize(&mut de).and_then(|r| de.end().map(|()| r));
    match (read, stopped) {
        (_, Some(f)) => Err(Ok(f)),
        (Ok(r), None) => Ok(r),
        (Err(e), None) => Err(Err(e)),
    }
}

/// Says that a sink stopped the reading (its failure is kept aside).
fn stop<E: de::Error>(stopped: &mut Option<Failure>, f: Failure) -> E {
    *stopped = Some(f);
    E::custom("stopped")
}

struct Top<'a> {
    keys: &'a [&'a str],
    sink: &'a mut dyn Sink,
    stopped: &'a mut Option<Failure>,
}

impl<'de> DeserializeSeed<'de> for Top<'_> {
    type Value = Read;
    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<Read, D::Error> {
        d.deserialize_map(self)
    }
}

impl<'de> Visitor<'de> for Top<'_> {
    type Value = Read;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a JSON object")
    }
    fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> Result<Read, A::Error> {
        let Top {
            keys,
            sink,
            stopped,
        } = self;
        let mut head = Map::new();
        let mut listed = false;
        let mut seen = std::collections::HashSet::new();
        while let Some(key) = m.next_key::<String>()? {
            if !seen.insert(key.clone()) {
                return Err(de::Error::custom(format!(
                    "key \"{}\" is given twice",
                    crate::flags::shown(&key, 40)
                )));
            }
            if listed {
                m.next_value::<IgnoredAny>()?;
            } else if keys.contains(&key.as_str()) {
                if let Err(f) = sink.head(&key, &head) {
                    return Err(stop(stopped, f));
                }
                m.next_value_seed(Items {
                    sink: &mut *sink,
                    stopped: &mut *stopped,
                })?;
                listed = true;
            } else {
                let Unique(v) = m.next_value()?;
                head.insert(key, v);
            }
        }
        Ok(Read { head, listed })
    }
}

struct Items<'a> {
    sink: &'a mut dyn Sink,
    stopped: &'a mut Option<Failure>,
}

impl<'de> DeserializeSeed<'de> for Items<'_> {
    type Value = ();
    fn deserialize<D: de::Deserializer<'de>>(self, d: D) -> Result<(), D::Error> {
        d.deserialize_seq(self)
    }
}

impl<'de> Visitor<'de> for Items<'_> {
    type Value = ();
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("an array of points or cells")
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut s: A) -> Result<(), A::Error> {
        while let Some(Unique(v)) = s.next_element()? {
            if let Err(f) = self.sink.item(v) {
                return Err(stop(self.stopped, f));
            }
        }
        Ok(())
    }
}
