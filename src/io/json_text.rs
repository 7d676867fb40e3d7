//! Readable JSON for results: objects and arrays of objects or arrays are indented one entry
//! per line, as `serde_json`'s pretty printer does, but an array of scalars is written on one
//! line (`[1.5,-2.0,0.25]`). A point list then takes one line per point instead of five, which
//! keeps large results (hundreds of thousands of points) a fraction of the pretty size while
//! they stay readable and diffable. The text is ordinary JSON: any reader parses it.

use serde::Serialize;
use serde_json::ser::{CompactFormatter, Formatter};
use std::io::{self, Write};

/// One open array or object: whether it holds an entry that is itself a container (then its
/// closing bracket goes on its own line).
struct Level {
    nested: bool,
}

/// The formatter; see the module comment.
struct Readable {
    levels: Vec<Level>,
    /// An array entry has begun but it is not known yet whether it is a scalar (written
    /// inline) or a container (written on its own line); `true` for the first entry.
    pending: Option<bool>,
}

impl Readable {
    fn indent<W: ?Sized + Write>(&self, w: &mut W) -> io::Result<()> {
        w.write_all(b"\n")?;
        for _ in 0..self.levels.len() {
            w.write_all(b"  ")?;
        }
        Ok(())
    }
    /// Before a scalar: a pending array entry is written inline.
    fn scalar<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        if let Some(first) = self.pending.take()
            && !first
        {
            w.write_all(b",")?;
        }
        Ok(())
    }
    /// Before a container: a pending array entry goes on its own line.
    fn container<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        if let Some(first) = self.pending.take() {
            if !first {
                w.write_all(b",")?;
            }
            if let Some(l) = self.levels.last_mut() {
                l.nested = true;
            }
            self.indent(w)?;
        }
        Ok(())
    }
    fn close<W: ?Sized + Write>(&mut self, w: &mut W, bracket: &[u8]) -> io::Result<()> {
        let l = self.levels.pop();
        if l.is_some_and(|l| l.nested) {
            self.indent(w)?;
        }
        w.write_all(bracket)
    }
}

macro_rules! scalar {
    ($($name:ident($t:ty)),*) => {$(
        fn $name<W: ?Sized + Write>(&mut self, w: &mut W, v: $t) -> io::Result<()> {
            self.scalar(w)?;
            CompactFormatter.$name(w, v)
        }
    )*};
}

impl Formatter for Readable {
    fn write_null<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.scalar(w)?;
        w.write_all(b"null")
    }
    scalar!(
        write_bool(bool),
        write_i8(i8),
        write_i16(i16),
        write_i32(i32),
        write_i64(i64),
        write_i128(i128),
        write_u8(u8),
        write_u16(u16),
        write_u32(u32),
        write_u64(u64),
        write_u128(u128),
        write_f32(f32),
        write_f64(f64),
        write_number_str(&str)
    );
    fn begin_string<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.scalar(w)?;
        w.write_all(b"\"")
    }
    fn write_raw_fragment<W: ?Sized + Write>(&mut self, w: &mut W, f: &str) -> io::Result<()> {
        self.scalar(w)?;
        w.write_all(f.as_bytes())
    }
    fn begin_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.container(w)?;
        self.levels.push(Level { nested: false });
        w.write_all(b"[")
    }
    fn end_array<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.close(w, b"]")
    }
    fn begin_array_value<W: ?Sized + Write>(&mut self, _w: &mut W, first: bool) -> io::Result<()> {
        self.pending = Some(first);
        Ok(())
    }
    fn end_array_value<W: ?Sized + Write>(&mut self, _w: &mut W) -> io::Result<()> {
        Ok(())
    }
    fn begin_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.container(w)?;
        self.levels.push(Level { nested: false });
        w.write_all(b"{")
    }
    fn end_object<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        self.close(w, b"}")
    }
    fn begin_object_key<W: ?Sized + Write>(&mut self, w: &mut W, first: bool) -> io::Result<()> {
        // An object's entries are always one per line.
        if let Some(l) = self.levels.last_mut() {
            l.nested = true;
        }
        if !first {
            w.write_all(b",")?;
        }
        self.indent(w)
    }
    fn begin_object_value<W: ?Sized + Write>(&mut self, w: &mut W) -> io::Result<()> {
        w.write_all(b": ")
    }
}

/// Whether [`to_text`] indents every value (`serde_json`'s pretty printer) instead.
static PRETTY: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);

/// Indent every value in [`to_text`] from now on (the command line's `--pretty`).
pub fn set_pretty(on: bool) {
    PRETTY.store(on, std::sync::atomic::Ordering::Relaxed);
}

/// `v` as readable JSON text (see the module comment), or fully indented after
/// [`set_pretty`].
pub fn to_text<T: Serialize + ?Sized>(v: &T) -> Result<String, serde_json::Error> {
    let mut buf = Vec::with_capacity(4096);
    to_writer(&mut buf, v)?;
    // The formatter writes only ASCII brackets, commas, spaces and newlines around
    // serde_json's own UTF-8 output.
    String::from_utf8(buf).map_err(|e| serde_json::Error::io(io::Error::other(e)))
}

/// [`to_text`] written to `w` as it is produced: a large result is never held as text in
/// memory (give a buffered writer).
pub fn to_writer<W: Write, T: Serialize + ?Sized>(w: W, v: &T) -> Result<(), serde_json::Error> {
    if PRETTY.load(std::sync::atomic::Ordering::Relaxed) {
        return serde_json::to_writer_pretty(w, v);
    }
    let mut ser = serde_json::Serializer::with_formatter(
        w,
        Readable {
            levels: Vec::new(),
            pending: None,
        },
    );
    v.serialize(&mut ser)
}

/// Write `v` as [`to_text`] would to `path`, streamed through a buffer into a temporary file
/// renamed over `path` at the end ([`super::write_atomic_with`]): a failed write keeps the
/// previous file.
pub fn write_file<T: Serialize + ?Sized>(path: &std::path::Path, v: &T) -> io::Result<()> {
    super::write_atomic_with(path, |f| {
        let mut w = io::BufWriter::with_capacity(1 << 16, f);
        to_writer(&mut w, v).map_err(io::Error::other)?;
        w.flush()
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn scalars_inline_containers_on_their_own_lines() {
        let v =
            json!({"a": [[1.5, -2.0], [0.25, 3]], "b": [], "c": {}, "d": "x", "e": [{"f": null}]});
        let t = to_text(&v).unwrap();
        assert_eq!(
            t,
            "{\n  \"a\": [\n    [1.5,-2.0],\n    [0.25,3]\n  ],\n  \"b\": [],\n  \"c\": {},\n  \"d\": \"x\",\n  \"e\": [\n    {\n      \"f\": null\n    }\n  ]\n}"
        );
        let back: serde_json::Value = serde_json::from_str(&t).unwrap();
        assert_eq!(back, v);
    }

    /// The streamed file holds the same text as [`to_text`].
    #[test]
    fn written_file_equals_the_text() {
        let v = json!({"points": (0..5000).map(|i| [i as f64 * 0.5, -1.0, 2.25]).collect::<Vec<_>>(), "n": 3});
        let dir = std::env::temp_dir().join(format!("vericad-json-text-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("r.json");
        write_file(&p, &v).unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), to_text(&v).unwrap());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn round_trips_what_pretty_round_trips() {
        let v = json!([1, [2, [3, {"k": [4.0, "s", true, false, null]}]], {"z": [[[]]]}, "q\"\n"]);
        let t = to_text(&v).unwrap();
        assert_eq!(serde_json::from_str::<serde_json::Value>(&t).unwrap(), v);
        let top: serde_json::Value = serde_json::from_str(&to_text(&json!(7)).unwrap()).unwrap();
        assert_eq!(top, json!(7));
    }
}
