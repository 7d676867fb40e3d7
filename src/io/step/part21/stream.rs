//! A Part 21 file read piece by piece: the text is decoded and parsed as it is read, and
//! only the part not parsed yet is kept, so reading a file does not hold its whole text
//! beside its table. The result is the one [`super::parse`] gives for the text
//! `String::from_utf8_lossy` makes of the whole file.
//!
//! The parser reads the instances of the text held; one cut off by its end (or any it cannot
//! read) is read again from its start once more text is held (see `Parser::statements`:
//! an instance read never looked past its `;`, so it reads as in the whole text). A fault is
//! reported only when the rest of the file is held, so it is the one the whole-text parse
//! reports. An instance longer than the text held doubles what is read next, so a long one
//! is read again only a few times.

use super::{Parser, Part21, Step, SyntaxError, no_data, schema_of};
use std::io::Read;

/// Bytes read at a time.
const CHUNK: usize = 64 * 1024;

/// Why a file could not be read.
#[derive(Debug)]
pub(in crate::io::step) enum ReadFault {
    /// Reading it failed.
    Io(std::io::Error),
    /// Its text is not Part 21.
    Syntax(SyntaxError),
}

impl From<std::io::Error> for ReadFault {
    fn from(e: std::io::Error) -> Self {
        ReadFault::Io(e)
    }
}

/// The `FILE_SCHEMA` search over the whole text (see [`super::parse`]): the text from its
/// first occurrence up to the next `;`.
enum Schema {
    /// Not found yet: the last bytes seen (a match may start there).
    Search(String),
    /// Found: the text from it on, no `;` yet.
    Capture(String),
    Done(Vec<String>),
}

impl Schema {
    fn feed(&mut self, s: &str) {
        match self {
            Schema::Search(tail) => {
                tail.push_str(s);
                if let Some(p) = tail.find("FILE_SCHEMA") {
                    let found = tail.split_off(p);
                    *self = Schema::Capture(String::new());
                    self.feed(&found);
                } else {
                    let mut cut = tail.len().saturating_sub(10);
                    while !tail.is_char_boundary(cut) {
                        cut -= 1;
                    }
                    tail.drain(..cut);
                }
            }
            Schema::Capture(c) => {
                let from = c.len();
                c.push_str(s);
                if c[from..].contains(';') {
                    *self = Schema::Done(schema_of(c));
                }
            }
            Schema::Done(_) => {}
        }
    }
    fn finish(self) -> Vec<String> {
        match self {
            Schema::Search(_) => vec![],
            Schema::Capture(c) => schema_of(&c),
            Schema::Done(v) => v,
        }
    }
}

/// The file being read.
struct Input<R> {
    r: R,
    /// Bytes read at a time.
    chunk: usize,
    /// Bytes read and not yet decoded: the start of a character the next read completes.
    raw: Vec<u8>,
    eof: bool,
    schema: Schema,
}

impl<R: Read> Input<R> {
    /// Append the text of the next piece of the file (up to `want` bytes) to `buf`.
    fn more(&mut self, buf: &mut String, want: usize) -> std::io::Result<()> {
        let keep = self.raw.len();
        self.raw.resize(keep + want, 0);
        let n = loop {
            match self.r.read(&mut self.raw[keep..]) {
                Ok(n) => break n,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        };
        self.raw.truncate(keep + n);
        self.eof = n == 0;
        let from = buf.len();
        decode(&mut self.raw, buf, self.eof);
        self.raw.shrink_to(self.chunk);
        self.schema.feed(&buf[from..]);
        Ok(())
    }
    /// Read the rest of the file, for its read faults and its schema, keeping no text.
    fn drain(&mut self) -> std::io::Result<()> {
        let mut sink = String::new();
        while !self.eof {
            sink.clear();
            self.more(&mut sink, self.chunk)?;
        }
        Ok(())
    }
}

/// Append the text of `raw` to `buf` as `String::from_utf8_lossy` decodes it (each invalid
/// sequence one U+FFFD), keeping in `raw` an incomplete character at its end unless `eof`.
fn decode(raw: &mut Vec<u8>, buf: &mut String, eof: bool) {
    let mut rest: &[u8] = raw;
    let keep = loop {
        match std::str::from_utf8(rest) {
            Ok(s) => {
                buf.push_str(s);
                break 0;
            }
            Err(e) => {
                let (good, bad) = rest.split_at(e.valid_up_to());
                buf.push_str(std::str::from_utf8(good).unwrap_or_default());
                match e.error_len() {
                    Some(n) => {
                        buf.push(char::REPLACEMENT_CHARACTER);
                        rest = &bad[n..];
                    }
                    None if eof => {
                        buf.push(char::REPLACEMENT_CHARACTER);
                        break 0;
                    }
                    None => break bad.len(),
                }
            }
        }
    };
    let n = raw.len();
    raw.copy_within(n - keep.., 0);
    raw.truncate(keep);
}

/// Read and parse a STEP file from `r`.
pub(in crate::io::step) fn read(r: impl Read) -> Result<Part21, ReadFault> {
    read_by(r, CHUNK)
}

/// [`read`], `chunk` bytes at a time.
fn read_by(r: impl Read, chunk: usize) -> Result<Part21, ReadFault> {
    let mut inp = Input {
        r,
        chunk,
        raw: Vec::new(),
        eof: false,
        schema: Schema::Search(String::new()),
    };
    let mut buf = String::new();
    // The header, up to the first `DATA;`.
    let mut from = 0;
    let d = loop {
        if let Some(p) = buf[from..].find("DATA;") {
            break from + p;
        }
        if inp.eof {
            return Err(ReadFault::Syntax(no_data()));
        }
        from = buf.len().saturating_sub(4);
        while !buf.is_char_boundary(from) {
            from -= 1;
        }
        inp.more(&mut buf, chunk)?;
    };
    let mut p = Parser::new(1 + buf[..d].matches('\n').count());
    buf.drain(..d + 5);
    loop {
        match p.statements(&buf, inp.eof) {
            Ok(Step::Done) => break,
            Ok(Step::More(at)) => {
                buf.drain(..at);
                // Nothing read from what was held: as much again as is held.
                let want = if at == 0 { buf.len().max(chunk) } else { chunk };
                inp.more(&mut buf, want)?;
            }
            Err(e) => return Err(ReadFault::Syntax(e)),
        }
    }
    drop(buf);
    inp.drain()?;
    Ok(Part21 {
        schema: inp.schema.finish(),
        entities: p.finish(),
    })
}

#[cfg(test)]
mod tests {
    use super::{ReadFault, decode, read_by};
    use crate::io::step::part21::{Part21, parse};

    /// The piecewise read of `bytes` (`chunk` at a time) agrees with the parse of their whole
    /// text: the same schema and instances, or the same fault.
    fn agree(bytes: &[u8], chunk: usize) {
        let whole = parse(&String::from_utf8_lossy(bytes));
        let read = read_by(bytes, chunk);
        let same = match (&whole, &read) {
            (Ok(a), Ok(b)) => a.schema == b.schema && a.entities == b.entities,
            (Err(a), Err(ReadFault::Syntax(b))) => a == b,
            _ => false,
        };
        let show = |r: &Result<Part21, _>| format!("{:?}", r.as_ref().map(|p| p.entities.len()));
        assert!(
            same,
            "chunk {chunk}: {} / {:?} for {:?}",
            show(&whole),
            read.as_ref().map(|p| p.entities.len()),
            String::from_utf8_lossy(bytes)
        );
    }

    /// Pieces cut anywhere (in strings holding `;`, comments, doubled quotes, binary values,
    /// numbers, names, `ENDSEC`, characters of several bytes) read as the whole text does,
    /// faults included.
    #[test]
    fn pieces_read_as_the_whole_text() {
        let texts: [&[u8]; 14] = [
            b"ISO-10303-21;HEADER;FILE_SCHEMA(('A;B','C'));ENDSEC;\nDATA;\n#1=P('x;y',(1.,2.5E-3,-3));\n/* c; */#2=(A(1)B(#1,.T.,$,*));\n#3=Q('it''s',\"0F;\",T(1.5),((#1,#2),(#3)));\nENDSEC;END-ISO-10303-21;",
            b"DATA;#5=A(1);#2=B('a\nb');#5=C(2);ENDSEC;",
            b"DATA;#1=A(1);#1=A(2);ENDSEC;",
            b"DATA;#1=A(1);ENDSECX;#2=B(2);ENDSEC;",
            b"DATA;#1=A(1);ENDSEC",
            b"DATA;#1=A(1);#2=B('open);ENDSEC;",
            b"DATA;#1=A(1);/* open ; ENDSEC;",
            b"DATA;#1=A((1,2);ENDSEC;",
            b"DATA;#10=A(#99999999999999999999999);ENDSEC;",
            b"no data section;",
            b"DATA;#1=A(1);ENDSEC;FILE_SCHEMA(('LATE'));",
            b"DATA;#1=NAME('\xC3\xA9\xE2\x82\xAC\xF0\x9F\x98\x80',\xFF\xC3);ENDSEC;",
            b"DATA;#1=NAME('\xE2\x82\xAC');#2=X(1.e5,+2,-0.,1E+300);ENDSEC;\xE2\x82",
            b"DATA;#3=A(1);#2=B(2);#1=C((((((1.))))));ENDSEC;",
        ];
        for t in texts {
            for chunk in [1, 2, 3, 5, 8, 13, 64] {
                agree(t, chunk);
            }
        }
    }

    /// The data files, whole and cut short or with a byte changed, read in small pieces as
    /// their whole text parses.
    #[test]
    fn data_files_read_as_their_whole_text() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
        let mut files = vec![];
        let mut stack = vec![dir];
        while let Some(d) = stack.pop() {
            for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
                let p = e.path();
                if p.is_dir() {
                    stack.push(p);
                } else if p.extension().is_some_and(|x| x == "step" || x == "stp") {
                    files.push(p);
                }
            }
        }
        files.sort();
        assert!(!files.is_empty());
        for f in files {
            let Ok(bytes) = std::fs::read(&f) else {
                continue;
            };
            if bytes.len() > 300_000 {
                agree(&bytes, 4096);
                continue;
            }
            for chunk in [7, 100, 4096] {
                agree(&bytes, chunk);
            }
            let n = bytes.len();
            for k in 1..8 {
                let at = n * k / 8;
                agree(&bytes[..at], 61);
                for c in [b'\'', b';', b'(', b'"', 0xE2] {
                    let mut b = bytes.clone();
                    b[at] = c;
                    agree(&b, 61);
                }
            }
        }
    }

    /// Decoding in pieces, an incomplete character carried to the next, gives what
    /// `from_utf8_lossy` gives for the whole.
    #[test]
    fn pieces_decode_as_the_whole() {
        let mut seed = 0x2545_f491_4f6c_dd1du64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            seed
        };
        let alphabet: [u8; 12] = [
            b'a', b';', 0xC3, 0xA9, 0xE2, 0x82, 0xAC, 0xF0, 0x9F, 0x98, 0x80, 0xFF,
        ];
        for _ in 0..2000 {
            let n = (next() % 24) as usize;
            let bytes: Vec<u8> = (0..n)
                .map(|_| alphabet[(next() % alphabet.len() as u64) as usize])
                .collect();
            let want = String::from_utf8_lossy(&bytes).into_owned();
            let (mut raw, mut got, mut i) = (Vec::new(), String::new(), 0);
            while i < bytes.len() {
                let k = 1 + (next() % 4) as usize;
                let j = (i + k).min(bytes.len());
                raw.extend_from_slice(&bytes[i..j]);
                decode(&mut raw, &mut got, false);
                i = j;
            }
            decode(&mut raw, &mut got, true);
            assert_eq!(got, want, "{bytes:x?}");
        }
    }
}
