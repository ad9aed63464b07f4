//! Every byte the program writes goes through here: stdout (a JSON
//! document, whole or streamed item by item ([`Document`]), JSON lines
//! flushed one by one, text such as CSV), files (written under a temporary
//! name and renamed once complete), notes on stderr, and a merge's scratch
//! file ([`Spill`]).
//!
//! Each write to stdout or a file is flushed and checked. A failure (a full
//! disk, `> /dev/full`) is an error naming stdout or the file, with its own
//! exit code [`EXIT_IO`]; a reader that went away (a closed pipe, `| head`)
//! ends the program at the next write with the same code and no message,
//! so a streamed sweep stops computing at once. Notes and progress on
//! stderr are best effort: a failure to show them is no reason to stop.

use crate::args::Format;
use crate::failure::Failure;
use serde_json::Value;
use std::io::{self, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

/// The exit code of a failed write (1 is a solver failure, 2 bad input):
/// every failure to produce the output, never 1.
pub const EXIT_IO: u8 = 3;

/// The failure of a write to `what` (stdout or a file's path): quiet for a
/// closed pipe, whose reader has gone and wants nothing more.
pub fn failed(what: &str, e: &io::Error) -> Failure {
    let message = if e.kind() == io::ErrorKind::BrokenPipe {
        String::new()
    } else {
        // "No space left on device", without the "(os error 28)" suffix.
        let text = e.to_string();
        let reason = text.split(" (os error ").next().unwrap_or(&text);
        format!("cannot write {what}: {reason}")
    };
    Failure {
        code: EXIT_IO,
        message,
    }
}

/// Checks before any work that stdout is open. Rust's runtime gives a
/// program started with stdout closed (`>&-`) a `/dev/null` opened for
/// reading and writing in its place, so every write would succeed into
/// nothing: the program would compute, lose the output and exit 0. That
/// stand-in is told from a `> /dev/null` of the user's by its access mode
/// (a shell's redirection opens for writing only).
pub fn check_stdout() -> Result<(), Failure> {
    if stdout_was_closed() {
        return Err(Failure {
            code: EXIT_IO,
            message: "cannot write stdout: it is closed".into(),
        });
    }
    Ok(())
}

/// Whether descriptor 1 is the runtime's stand-in for a closed stdout:
/// `/dev/null` open for reading and writing (`O_RDWR`, access mode 2).
#[cfg(target_os = "linux")]
fn stdout_was_closed() -> bool {
    let is_null = std::fs::read_link("/proc/self/fd/1").is_ok_and(|p| p == Path::new("/dev/null"));
    is_null
        && std::fs::read_to_string("/proc/self/fdinfo/1").is_ok_and(|info| {
            info.lines()
                .find_map(|l| l.strip_prefix("flags:"))
                .and_then(|f| u32::from_str_radix(f.trim(), 8).ok())
                .is_some_and(|flags| flags & 3 == 2)
        })
}

/// Elsewhere the stand-in cannot be told from a redirection: trusted.
#[cfg(not(target_os = "linux"))]
fn stdout_was_closed() -> bool {
    false
}

/// Writes `bytes` to stdout and flushes them.
pub fn stdout(bytes: &[u8]) -> Result<(), Failure> {
    let mut out = io::stdout().lock();
    out.write_all(bytes)
        .and_then(|()| out.flush())
        .map_err(|e| failed("stdout", &e))
}

/// Writes a result as JSON, or as the CSV `csv` makes of that JSON.
pub fn output(format: Format, value: &Value, csv: fn(&Value) -> String) -> Result<(), Failure> {
    match format {
        Format::Json => emit(value),
        Format::Jsonl => emit_line(value),
        Format::Csv => emit_text(&csv(value)),
    }
}

/// Writes one pretty-printed JSON document.
pub fn emit(value: &Value) -> Result<(), Failure> {
    let mut text = serde_json::to_string_pretty(value).map_err(|e| Failure {
        code: EXIT_IO,
        message: format!("cannot write JSON: {e}"),
    })?;
    text.push('\n');
    stdout(text.as_bytes())
}

/// Writes one JSON line and flushes it, so a reader (or a killed job's
/// log) has every line written so far.
pub fn emit_line(value: &Value) -> Result<(), Failure> {
    stdout(format!("{value}\n").as_bytes())
}

/// Writes text (CSV, a table) as it is.
pub fn emit_text(text: &str) -> Result<(), Failure> {
    stdout(text.as_bytes())
}

/// One line on stderr, `gearshock: ` first, its control characters
/// escaped (a key or value echoed from the input cannot break the line or
/// reach the terminal raw).
pub fn note(text: &str) {
    let text = crate::flags::escaped(text);
    let _ = writeln!(io::stderr().lock(), "gearshock: {text}");
}

/// Checks before any work that `dir` (`flag`'s value) can take files:
/// creates it if missing and writes and removes a probe file there.
pub fn check_dir(flag: &str, dir: &Path) -> Result<(), Failure> {
    let refused = |e: io::Error| {
        let text = e.to_string();
        let reason = text
            .split(" (os error ")
            .next()
            .unwrap_or(&text)
            .to_string();
        crate::failure::usage(format!("{flag} {}: {reason}", dir.display()))
    };
    std::fs::create_dir_all(dir).map_err(refused)?;
    let probe = dir.join(format!(".gearshock-probe-{}", std::process::id()));
    std::fs::write(&probe, b"probe").map_err(refused)?;
    std::fs::remove_file(&probe).map_err(refused)
}

/// Writes `files` (name, contents) into `dir`: each under a temporary name,
/// flushed to the disk, then all renamed, so that a failed run leaves no
/// empty or cut file behind (the temporary files are removed).
pub fn write_files(dir: &Path, files: &[(String, String)]) -> Result<(), Failure> {
    let mut temps = Vec::with_capacity(files.len());
    let result = write_then_rename(dir, files, &mut temps);
    if result.is_err() {
        for t in &temps {
            let _ = std::fs::remove_file(t);
        }
    }
    result
}

fn write_then_rename(
    dir: &Path,
    files: &[(String, String)],
    temps: &mut Vec<std::path::PathBuf>,
) -> Result<(), Failure> {
    let shown = |name: &str| dir.join(name).display().to_string();
    for (name, text) in files {
        let temp = dir.join(format!(".{name}.part-{}", std::process::id()));
        temps.push(temp.clone());
        std::fs::File::create(&temp)
            .and_then(|mut f| {
                f.write_all(text.as_bytes())?;
                f.sync_data()
            })
            .map_err(|e| failed(&shown(name), &e))?;
    }
    for ((name, _), temp) in files.iter().zip(temps.iter()) {
        std::fs::rename(temp, dir.join(name)).map_err(|e| failed(&shown(name), &e))?;
    }
    temps.clear();
    Ok(())
}

/// A pretty-printed JSON document written to stdout as it is made: its
/// fields before a list (`head`), then the list's items one by one, each
/// serialized when given. The text is that of `serde_json`'s pretty
/// printer for the whole document, byte for byte, but only one item is
/// held at a time, so memory stays that of the largest item however long
/// the list.
pub struct Document {
    out: io::BufWriter<io::StdoutLock<'static>>,
    items: usize,
}

impl Document {
    /// Writes `head`'s fields and opens the list `key` after them.
    pub fn begin(head: &serde_json::Map<String, Value>, key: &str) -> Result<Self, Failure> {
        let mut doc = Document {
            out: io::BufWriter::with_capacity(1 << 16, io::stdout().lock()),
            items: 0,
        };
        let head_text = pretty(&Value::Object(head.clone()))?;
        // `{\n  "a": 1\n}` without its closing `\n}`, or `{` for no field.
        let open = head_text
            .strip_suffix("\n}")
            .map_or_else(|| "{".to_string(), |t| format!("{t},"));
        let key_text = serde_json::to_string(key).map_err(json_failure)?;
        doc.put(format!("{open}\n  {key_text}: [").as_bytes())?;
        Ok(doc)
    }

    /// Writes one item of the list, serialized straight into stdout's
    /// buffer (no copy of its text).
    pub fn item(&mut self, v: &Value) -> Result<(), Failure> {
        let sep = if self.items == 0 { "\n    " } else { ",\n    " };
        self.items += 1;
        self.put(sep.as_bytes())?;
        serde_json::to_writer_pretty(Indented(&mut self.out), v)
            .map_err(|e| failed("stdout", &io::Error::from(e)))
    }

    /// Closes the list and the document and flushes stdout.
    pub fn finish(mut self) -> Result<(), Failure> {
        let close: &[u8] = if self.items == 0 {
            b"]\n}\n"
        } else {
            b"\n  ]\n}\n"
        };
        self.put(close)?;
        self.out.flush().map_err(|e| failed("stdout", &e))
    }

    fn put(&mut self, bytes: &[u8]) -> Result<(), Failure> {
        self.out.write_all(bytes).map_err(|e| failed("stdout", &e))
    }
}

fn json_failure(e: serde_json::Error) -> Failure {
    Failure {
        code: EXIT_IO,
        message: format!("cannot write JSON: {e}"),
    }
}

fn pretty(v: &Value) -> Result<String, Failure> {
    serde_json::to_string_pretty(v).map_err(json_failure)
}

/// Indents by a list item's depth (4 spaces) every line after the first of
/// the text written through it: strings hold no raw line break, so every
/// line break of a JSON text is one of its layout.
struct Indented<'a, W: Write>(&'a mut W);

impl<W: Write> Write for Indented<'_, W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let mut lines = buf.split(|&b| b == b'\n');
        if let Some(first) = lines.next() {
            self.0.write_all(first)?;
        }
        for line in lines {
            self.0.write_all(b"\n    ")?;
            self.0.write_all(line)?;
        }
        Ok(buf.len())
    }
    fn flush(&mut self) -> io::Result<()> {
        self.0.flush()
    }
}

/// The checked items, put aside in a temporary file as compact JSON (which
/// reads back to the same value: serde_json's `float_roundtrip`), with
/// each one's place in the merged output. The file is removed when done.
pub struct Spill {
    path: PathBuf,
    out: io::BufWriter<std::fs::File>,
    at: u64,
    /// Offset and length of each place's item (length 0: not yet given).
    places: Vec<(u64, u32)>,
}

impl Spill {
    /// A temporary file for `places` items.
    pub fn new(places: usize) -> Result<Self, Failure> {
        let path =
            std::env::temp_dir().join(format!(".gearshock-merge-{}.json", std::process::id()));
        let file = std::fs::OpenOptions::new()
            .write(true)
            .read(true)
            .create(true)
            .truncate(true)
            .open(&path)
            .map_err(|e| spill_failed(&path, &e))?;
        Ok(Spill {
            out: io::BufWriter::with_capacity(1 << 16, file),
            path,
            at: 0,
            places: vec![(0, 0); places],
        })
    }

    /// Puts aside the item of place `place`.
    pub fn put(&mut self, place: usize, v: &Value) -> Result<(), Failure> {
        let mut counted = Counted(&mut self.out, 0);
        serde_json::to_writer(&mut counted, v)
            .map_err(|e| spill_failed(&self.path, &io::Error::from(e)))?;
        let len = counted.1;
        // An item is at most a shard file's size (256 MiB), below u32::MAX.
        self.places[place] = (self.at, len as u32);
        self.at += len;
        Ok(())
    }

    /// Hands every item to `f` in the order of their places.
    pub fn replay(
        mut self,
        mut f: impl FnMut(Value) -> Result<(), Failure>,
    ) -> Result<(), Failure> {
        self.out.flush().map_err(|e| spill_failed(&self.path, &e))?;
        let file = self.out.get_mut();
        let mut buf = Vec::new();
        for &(at, len) in &self.places {
            buf.resize(len as usize, 0);
            file.seek(SeekFrom::Start(at))
                .and_then(|_| file.read_exact(&mut buf))
                .map_err(|e| spill_failed(&self.path, &e))?;
            let v = serde_json::from_slice(&buf)
                .map_err(|e| crate::failure::usage(format!("merge: {e}")))?;
            f(v)?;
        }
        Ok(())
    }
}

/// A writer that counts the bytes written through it.
struct Counted<'a, W: Write>(&'a mut W, u64);

impl<W: Write> Write for Counted<'_, W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let n = self.0.write(buf)?;
        self.1 += n as u64;
        Ok(n)
    }
    fn flush(&mut self) -> io::Result<()> {
        self.0.flush()
    }
}

impl Drop for Spill {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// A failure of the temporary file: an I/O failure, naming the file and
/// where to put it instead.
fn spill_failed(path: &Path, e: &io::Error) -> Failure {
    let mut f = failed(&format!("the merge's temporary file {}", path.display()), e);
    f.code = EXIT_IO;
    f.message.push_str(" (TMPDIR chooses its folder)");
    f
}
