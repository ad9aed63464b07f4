//! Input files read through a size limit, so that no input (`/dev/zero`,
//! a forged file) can grow memory without bound, and with every key of an
//! object once.

use crate::failure::{usage, Failure};
use serde::de::{self, Deserialize, Deserializer, MapAccess, SeqAccess, Visitor};
use serde_json::Value;
use std::io::Read;

/// Largest `--params` file (bytes): a parameter set is a few kB.
pub const MAX_PARAMS_BYTES: u64 = 1 << 20;
/// Largest shard file `merge` reads (bytes).
pub const MAX_SHARD_BYTES: u64 = 256 << 20;
/// Largest total of the files `merge` reads (bytes): parsed JSON takes
/// several times its text in memory.
pub const MAX_MERGE_BYTES: u64 = 1 << 30;

/// A reader that fails once more than its limit has been read, so that no
/// input (`/dev/zero`, a forged file) can grow memory without bound.
struct Limited<R> {
    inner: R,
    left: u64,
}

impl<R: Read> Read for Limited<R> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        // Read one byte past the limit to tell "exactly the limit" from "more".
        let want = buf
            .len()
            .min(usize::try_from(self.left.saturating_add(1)).unwrap_or(usize::MAX));
        let n = self.inner.read(&mut buf[..want])?;
        if n as u64 > self.left {
            return Err(std::io::Error::other("over the size limit"));
        }
        self.left -= n as u64;
        Ok(n)
    }
}

/// Describes a size in words (e.g. "1 MiB").
pub fn bytes_text(n: u64) -> String {
    if n >= 1 << 30 && n.is_multiple_of(1 << 30) {
        format!("{} GiB", n >> 30)
    } else if n >= 1 << 20 && n.is_multiple_of(1 << 20) {
        format!("{} MiB", n >> 20)
    } else {
        format!("{n} bytes")
    }
}

/// A file opened for reading through a limit of `limit` bytes; the
/// failure names `what` (the flag or command), the file and `limit_text`
/// (what the limit is).
pub struct LimitedFile {
    reader: Limited<std::io::BufReader<std::fs::File>>,
    limit: u64,
    too_large: String,
    what: String,
}

impl LimitedFile {
    /// Opens `path`, refusing at once a file larger than `limit`.
    pub fn open(
        path: &std::path::Path,
        limit: u64,
        what: &str,
        limit_text: &str,
    ) -> Result<Self, Failure> {
        let shown = path.display();
        let too_large = format!("{what} {shown}: larger than {limit_text}");
        let file = std::fs::File::open(path).map_err(|e| usage(format!("{what} {shown}: {e}")))?;
        if file
            .metadata()
            .is_ok_and(|m| m.is_file() && m.len() > limit)
        {
            return Err(usage(too_large));
        }
        Ok(LimitedFile {
            reader: Limited {
                inner: std::io::BufReader::with_capacity(1 << 16, file),
                left: limit,
            },
            limit,
            too_large,
            what: format!("{what} {shown}"),
        })
    }

    /// The reader.
    pub fn reader(&mut self) -> &mut impl Read {
        &mut self.reader
    }

    /// The bytes read so far.
    pub fn read_bytes(&self) -> u64 {
        self.limit - self.reader.left
    }

    /// A JSON reader's failure in words: over the limit, unreadable, or
    /// not JSON.
    pub fn failure(&self, e: &serde_json::Error) -> Failure {
        if e.is_io() && e.to_string().contains("over the size limit") {
            usage(self.too_large.clone())
        } else if e.is_io() || e.is_data() {
            usage(format!("{}: {e}", self.what))
        } else {
            usage(format!("{}: not JSON: {e}", self.what))
        }
    }
}

/// Reads and parses a JSON file of at most `limit` bytes, returning the
/// value and the bytes read; the failure names `what` (the flag or
/// command), the file and `limit_text` (what the limit is).
pub fn read_json(
    path: &std::path::Path,
    limit: u64,
    what: &str,
    limit_text: &str,
) -> Result<(Value, u64), Failure> {
    let mut file = LimitedFile::open(path, limit, what, limit_text)?;
    let Unique(value) = serde_json::from_reader(file.reader()).map_err(|e| file.failure(&e))?;
    Ok((value, file.read_bytes()))
}

/// A JSON value whose objects hold each key once: a key given twice (which
/// a plain reader would settle silently, the last one winning) is refused
/// naming it.
pub(crate) struct Unique(pub(crate) Value);

impl<'de> Deserialize<'de> for Unique {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(UniqueVisitor)
    }
}

struct UniqueVisitor;

impl<'de> Visitor<'de> for UniqueVisitor {
    type Value = Unique;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a JSON value")
    }
    fn visit_bool<E: de::Error>(self, v: bool) -> Result<Unique, E> {
        Ok(Unique(Value::Bool(v)))
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<Unique, E> {
        Ok(Unique(Value::from(v)))
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<Unique, E> {
        Ok(Unique(Value::from(v)))
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<Unique, E> {
        Ok(Unique(Value::from(v)))
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<Unique, E> {
        Ok(Unique(Value::from(v)))
    }
    fn visit_string<E: de::Error>(self, v: String) -> Result<Unique, E> {
        Ok(Unique(Value::String(v)))
    }
    fn visit_unit<E: de::Error>(self) -> Result<Unique, E> {
        Ok(Unique(Value::Null))
    }
    fn visit_none<E: de::Error>(self) -> Result<Unique, E> {
        Ok(Unique(Value::Null))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut s: A) -> Result<Unique, A::Error> {
        let mut items = Vec::new();
        while let Some(Unique(v)) = s.next_element()? {
            items.push(v);
        }
        Ok(Unique(Value::Array(items)))
    }
    fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> Result<Unique, A::Error> {
        let mut map = serde_json::Map::new();
        while let Some(key) = m.next_key::<String>()? {
            if map.contains_key(&key) {
                return Err(de::Error::custom(format!(
                    "key \"{}\" is given twice",
                    crate::flags::shown(&key, 40)
                )));
            }
            let Unique(v) = m.next_value()?;
            map.insert(key, v);
        }
        Ok(Unique(Value::Object(map)))
    }
}
