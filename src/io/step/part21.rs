//! ISO 10303-21 ("Part 21", STEP physical file) tokenizer and parser: the DATA section as a
//! map from instance id to entity — simple `TYPE(args)` or complex `(TYPE1(args) TYPE2(…))`.
//! Comments `/* … */`, multi-line instances, strings with `''`, enumerations, typed
//! parameters and `$`/`*` are handled; any syntax fault is a typed error with its line.
//!
//! The parse writes each instance straight into the table's compact storage
//! ([`table`](Table)); a file can be parsed from its whole text ([`parse`]) or read piece by
//! piece, without holding its text (`stream`).

use std::collections::HashMap;
use std::sync::Arc;

/// An entity, partial entity, typed-parameter or enumeration name: upper case, shared by every
/// instance that uses it (one allocation per distinct name in a file).
pub type Name = Arc<str>;

mod lexer;
mod lines;
mod stream;
mod table;
mod values;
mod view;

use lexer::Lexer;
use lines::Lines;
pub(super) use stream::{ReadFault, read};
pub use table::{Iter, Table};
use table::{Store, header};
pub use values::{Entity, Value};
pub use view::{Args, ArgsIter, Inst, ListRefs, Parts, Val};

/// A parsed STEP file.
#[derive(Clone, Debug, Default)]
pub struct Part21 {
    pub schema: Vec<String>,
    pub entities: Table,
}

/// A syntax fault.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("line {line}: {reason}")]
pub struct SyntaxError {
    pub line: usize,
    pub reason: String,
}

/// Distinct names kept for sharing (see [`Lexer::keyword`]).
const MAX_INTERNED: usize = 4096;

/// What the parse keeps from one instance to the next (and from one piece of the text to the
/// next, see `stream`).
struct Parser {
    line: usize,
    /// Names met so far, by their spelling in the file: their index in the store.
    /// (Fx hashing: names are short and come from the file itself; the default SipHash
    /// would cost more than the parse of the instance around them.)
    names: rustc_hash::FxHashMap<Box<[u8]>, u64>,
    /// Items of the lists being read (see [`Lexer::close`]).
    stack: Vec<u64>,
    store: Store,
    /// `(id, row word)` of the instances read, in file order.
    rows: Vec<(u64, u64)>,
    /// The line of each instance, in file order. Ids usually ascend, and only once they do
    /// not is a map of every id's line built, to name both places when an id is defined twice.
    lines: Lines,
    defined: Option<HashMap<u64, usize>>,
}

/// How a piece of text ended ([`Parser::statements`]).
enum Step {
    /// At `ENDSEC`.
    Done,
    /// Out of text at byte `.0` (an instance's start, or where the text ends): the next
    /// piece continues from there.
    More(usize),
}

impl Parser {
    fn new(line: usize) -> Parser {
        Parser {
            line,
            names: HashMap::default(),
            stack: Vec::new(),
            store: Store::default(),
            rows: Vec::new(),
            lines: Lines::default(),
            defined: None,
        }
    }
    /// Read the instances of `text` up to `ENDSEC`. `last`: whether `text` holds the rest of
    /// the file. Otherwise an instance that cannot be read is reported as [`Step::More`] at
    /// its start, with what it added undone: it may be cut off by the end of the text (its
    /// fault, if it has one, is found again with more text). An instance read, or `ENDSEC`,
    /// never looked at the end of the text (every scan that meets it leaves the cursor
    /// there, and an instance ends with a `;` read after it), so it reads as in the whole
    /// text.
    fn statements(&mut self, text: &str, last: bool) -> Result<Step, SyntaxError> {
        let mut lx = Lexer {
            text,
            s: text.as_bytes(),
            i: 0,
            p: self,
        };
        loop {
            let (start, line) = (lx.i, lx.p.line);
            let (mark, lines) = (lx.p.store.mark(), lx.p.lines.mark());
            let mut undo = None;
            let fault = match lx.peek() {
                None if !last => {
                    lx.p.line = line;
                    return Ok(Step::More(start));
                }
                None => lx.err("missing ENDSEC"),
                Some(b'#') => lx.statement(&mut undo),
                Some(_) => {
                    let k = lx.keyword();
                    let k = lx.p.store.name(k);
                    if k == "ENDSEC" && (last || lx.i < lx.s.len()) {
                        return Ok(Step::Done);
                    }
                    lx.err(format!("unexpected '{k}' in DATA section"))
                }
            };
            if let Err(e) = fault {
                if last {
                    return Err(e);
                }
                let p = &mut *lx.p;
                p.line = line;
                p.store.cut(mark);
                p.lines.truncate(lines);
                p.stack.clear();
                if let (Some((id, was)), Some(map)) = (undo, p.defined.as_mut()) {
                    match was {
                        Some(l) => map.insert(id, l),
                        None => map.remove(&id),
                    };
                }
                return Ok(Step::More(start));
            }
        }
    }
    /// The table of the instances read.
    fn finish(self) -> Table {
        Table::from_parts(self.rows, self.store)
    }
}

impl Lexer<'_, '_> {
    /// An argument list (its items onto the stack).
    fn args(&mut self) -> Result<(), SyntaxError> {
        if self.peek() == Some(b'(') {
            self.i += 1;
            self.items(0)
        } else {
            self.value(0)?;
            self.err("expected an argument list")
        }
    }
    /// A (partial) entity `k` of instance `id`: its header and arguments onto the stack.
    fn part(&mut self, id: u64, k: u64) -> Result<(), SyntaxError> {
        let at = self.p.stack.len();
        self.p.stack.push(0);
        self.args()?;
        match header(k as usize, self.p.stack.len() - at - 1) {
            Some(h) => self.p.stack[at] = h,
            None => return self.err(format!("#{id}: too many attributes")),
        }
        Ok(())
    }
    /// One instance after its `#id=`: simple `NAME(args)` or complex `(NAME(args) …)`, and
    /// `;`. Its row word ([`Store::record`]).
    fn instance(&mut self, id: u64) -> Result<u64, SyntaxError> {
        let complex = self.peek() == Some(b'(');
        let mut parts = 0;
        if complex {
            self.i += 1;
            while self.peek() != Some(b')') {
                let k = self.keyword();
                if self.p.store.name(k).is_empty() {
                    return self.err(format!("#{id}: expected a partial entity name"));
                }
                self.part(id, k)?;
                parts += 1;
            }
            self.i += 1;
        } else {
            let k = self.keyword();
            if self.p.store.name(k).is_empty() {
                return self.err(format!("#{id}: expected an entity name"));
            }
            self.part(id, k)?;
        }
        self.eat(b';')?;
        let p = &mut *self.p;
        let row = p.store.record(&p.stack, complex, parts);
        p.stack.clear();
        row.map_or_else(|| self.err("file too large"), Ok)
    }
    /// An instance from its `#`; `undo`: the id entered in the map of ids and the line it
    /// replaced there, if any.
    fn statement(&mut self, undo: &mut Option<(u64, Option<usize>)>) -> Result<(), SyntaxError> {
        self.i += 1;
        let Some(id) = self.digits() else {
            return self.err("malformed instance id");
        };
        let p = &mut *self.p;
        let ascending = p.defined.is_none() && p.rows.last().is_none_or(|l| l.0 < id);
        if !ascending {
            let (rows, lines) = (&p.rows, &p.lines);
            let map = p
                .defined
                .get_or_insert_with(|| rows.iter().map(|x| x.0).zip(lines.iter()).collect());
            let first = map.insert(id, p.line);
            *undo = Some((id, first));
            if let Some(first) = first {
                // A second `#N=` would silently replace the first instance and every
                // reference to it: the file is ambiguous.
                return self.err(format!(
                    "#{id} is defined twice (first on line {first}); instance ids must be unique"
                ));
            }
        }
        p.lines.push(p.line);
        self.eat(b'=')?;
        let at = self.instance(id)?;
        self.p.rows.push((id, at));
        Ok(())
    }
}

/// The schema names of the text from `FILE_SCHEMA` on: its quoted strings up to the first
/// `;`.
fn schema_of(from_file_schema: &str) -> Vec<String> {
    let end = from_file_schema.find(';').unwrap_or(from_file_schema.len());
    from_file_schema[..end]
        .split('\'')
        .skip(1)
        .step_by(2)
        .map(|s| s.to_string())
        .collect()
}

/// The fault of a text without a DATA section.
fn no_data() -> SyntaxError {
    SyntaxError {
        line: 1,
        reason: "no DATA section (not an ISO 10303-21 file?)".into(),
    }
}

/// Parse a whole STEP file.
pub fn parse(text: &str) -> Result<Part21, SyntaxError> {
    // Header: find FILE_SCHEMA's strings, then DATA;
    let schema = text
        .find("FILE_SCHEMA")
        .map_or(vec![], |p| schema_of(&text[p..]));
    let Some(d) = text.find("DATA;") else {
        return Err(no_data());
    };
    let mut p = Parser::new(1 + text[..d].matches('\n').count());
    match p.statements(&text[d + 5..], true)? {
        Step::Done => Ok(Part21 {
            schema,
            entities: p.finish(),
        }),
        // Not returned for the last piece of a text.
        Step::More(_) => Err(SyntaxError {
            line: p.line,
            reason: "missing ENDSEC".into(),
        }),
    }
}
