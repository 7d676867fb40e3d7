//! ISO 10303-21 ("Part 21", STEP physical file) tokenizer and parser: the DATA section as a
//! map from instance id to entity — simple `TYPE(args)` or complex `(TYPE1(args) TYPE2(…))`.
//! Comments `/* … */`, multi-line instances, strings with `''`, enumerations, typed
//! parameters and `$`/`*` are handled; any syntax fault is a typed error with its line.

use std::collections::HashMap;
use std::hash::{BuildHasherDefault, Hasher};
use std::sync::Arc;

/// An entity, partial entity, typed-parameter or enumeration name: upper case, shared by every
/// instance that uses it (one allocation per distinct name in a file).
pub type Name = Arc<str>;

mod table;
mod values;

pub use table::Table;
pub use values::{Entity, ListRefs, Value};

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

/// FNV-1a: names are short and come from the file itself; the default SipHash would cost more
/// than the parse of the instance around them.
#[derive(Default)]
struct Fnv(u64);

impl Hasher for Fnv {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        let mut h = if self.0 == 0 {
            0xcbf2_9ce4_8422_2325
        } else {
            self.0
        };
        for &b in bytes {
            h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
        self.0 = h;
    }
}

struct Lexer<'a> {
    text: &'a str,
    s: &'a [u8],
    i: usize,
    line: usize,
    /// Names met so far, by their spelling in the file.
    names: HashMap<&'a [u8], Name, BuildHasherDefault<Fnv>>,
    /// Items of the lists being read (see [`Lexer::value`]).
    stack: Vec<Value>,
}

impl<'a> Lexer<'a> {
    fn err<T>(&self, reason: impl Into<String>) -> Result<T, SyntaxError> {
        Err(SyntaxError {
            line: self.line,
            reason: reason.into(),
        })
    }
    fn skip_ws(&mut self) {
        loop {
            while let Some(&c) = self.s.get(self.i)
                && c.is_ascii_whitespace()
            {
                if c == b'\n' {
                    self.line += 1;
                }
                self.i += 1;
            }
            if self.s[self.i..].starts_with(b"/*") {
                match self.s[self.i + 2..].windows(2).position(|w| w == b"*/") {
                    Some(p) => {
                        self.line += self.s[self.i..self.i + 2 + p]
                            .iter()
                            .filter(|&&c| c == b'\n')
                            .count();
                        self.i += p + 4;
                    }
                    None => self.i = self.s.len(),
                }
            } else {
                return;
            }
        }
    }
    fn peek(&mut self) -> Option<u8> {
        self.skip_ws();
        self.s.get(self.i).copied()
    }
    fn eat(&mut self, c: u8) -> Result<(), SyntaxError> {
        match self.peek() {
            Some(x) if x == c => {
                self.i += 1;
                Ok(())
            }
            Some(x) => self.err(format!("expected '{}', found '{}'", c as char, x as char)),
            None => self.err(format!("expected '{}', found end of file", c as char)),
        }
    }
    /// A keyword (letters, digits, `_`, `!`), upper-cased and interned; empty if none.
    fn keyword(&mut self) -> Name {
        self.skip_ws();
        let st = self.i;
        while let Some(&c) = self.s.get(self.i)
            && (c.is_ascii_alphanumeric() || c == b'_' || c == b'!')
        {
            self.i += 1;
        }
        let raw = &self.s[st..self.i];
        if let Some(n) = self.names.get(raw) {
            return n.clone();
        }
        // ASCII only, so the slice is on character boundaries.
        let n: Name = self.text[st..self.i].to_ascii_uppercase().into();
        // Real schemas use a few hundred names; past the cap new names are not kept, so a file
        // made of many names whose hashes collide cannot make the table's probing quadratic.
        if self.names.len() < MAX_INTERNED {
            self.names.insert(raw, n.clone());
        }
        n
    }
    /// The digits at the cursor as an id or reference; `None` if there are none or too many.
    fn digits(&mut self) -> Option<u64> {
        let st = self.i;
        let mut v: u64 = 0;
        while let Some(&c) = self.s.get(self.i)
            && c.is_ascii_digit()
        {
            v = v.checked_mul(10)?.checked_add(u64::from(c - b'0'))?;
            self.i += 1;
        }
        (self.i > st).then_some(v)
    }
    /// A quoted string (`'` doubled inside), the cursor after the opening quote.
    fn string(&mut self) -> Result<String, SyntaxError> {
        let st = self.i;
        let mut escaped = false;
        loop {
            let Some(p) = self.s[self.i..].iter().position(|&c| c == b'\'') else {
                return self.err("unterminated string");
            };
            self.i += p + 1;
            if self.s.get(self.i) == Some(&b'\'') {
                escaped = true;
                self.i += 1;
            } else {
                break;
            }
        }
        let body = &self.text[st..self.i - 1];
        self.line += body.bytes().filter(|&c| c == b'\n').count();
        Ok(if escaped {
            body.replace("''", "'")
        } else {
            body.to_owned()
        })
    }
    fn value(&mut self, depth: usize) -> Result<Value, SyntaxError> {
        if depth > 64 {
            return self.err("lists nested too deeply");
        }
        match self.peek() {
            Some(b'(') => {
                self.i += 1;
                if self.peek() == Some(b')') {
                    self.i += 1;
                    return Ok(Value::List(Box::default()));
                }
                // The items go on one stack shared by every open list, and a closed list takes
                // its own items off it in one allocation of their exact number (no growing
                // vector per list: most lists are short and kept for the whole read). A fault
                // ends the parse, so items left on the stack then are never read.
                let base = self.stack.len();
                loop {
                    let v = self.value(depth + 1)?;
                    self.stack.push(v);
                    match self.peek() {
                        Some(b',') => self.i += 1,
                        Some(b')') => {
                            self.i += 1;
                            // Nested lists of reals or of references are kept as plain
                            // numbers (argument lists stay lists of values).
                            if depth > 0 {
                                let items = &self.stack[base..];
                                let reals: Option<Vec<f64>> = items
                                    .iter()
                                    .map(|v| match v {
                                        Value::Real(x) => Some(*x),
                                        _ => None,
                                    })
                                    .collect();
                                if let Some(r) = reals {
                                    self.stack.truncate(base);
                                    return Ok(Value::Reals(r.into_boxed_slice()));
                                }
                                let refs: Option<Vec<u64>> =
                                    items.iter().map(Value::reference).collect();
                                if let Some(r) = refs {
                                    self.stack.truncate(base);
                                    return Ok(Value::Refs(r.into_boxed_slice()));
                                }
                            }
                            let items: Vec<Value> = self.stack.drain(base..).collect();
                            return Ok(Value::List(items.into_boxed_slice()));
                        }
                        _ => return self.err("expected ',' or ')' in a list"),
                    }
                }
            }
            Some(b'#') => {
                self.i += 1;
                match self.digits() {
                    Some(r) => Ok(Value::Ref(r)),
                    None => self.err("malformed reference"),
                }
            }
            Some(b'\'') => {
                self.i += 1;
                Ok(Value::Str(self.string()?.into_boxed_str()))
            }
            Some(b'.') => {
                self.i += 1;
                let k = self.keyword();
                self.eat(b'.')?;
                Ok(Value::Enum(k))
            }
            Some(b'$') | Some(b'*') => {
                self.i += 1;
                Ok(Value::Unset)
            }
            Some(b'"') => {
                // Binary: keep as a string of hex digits.
                self.i += 1;
                let st = self.i;
                while self.i < self.s.len() && self.s[self.i] != b'"' {
                    self.i += 1;
                }
                let v: Box<str> = self.text[st..self.i].into();
                self.eat(b'"')?;
                Ok(Value::Str(v))
            }
            Some(c) if c == b'-' || c == b'+' || c.is_ascii_digit() => {
                let st = self.i;
                self.i += 1;
                let mut real = false;
                while let Some(&c) = self.s.get(self.i) {
                    match c {
                        b'0'..=b'9' | b'-' | b'+' => {}
                        b'.' | b'E' | b'e' => real = true,
                        _ => break,
                    }
                    self.i += 1;
                }
                let t = &self.text[st..self.i];
                if !real && let Ok(i) = t.parse::<i64>() {
                    return Ok(Value::Int(i));
                }
                // Rust's float syntax takes the Part 21 forms `1.` and `1.E5` as they are.
                match t.parse::<f64>() {
                    Ok(x) if x.is_finite() => Ok(Value::Real(x)),
                    _ => self.err(format!("malformed number '{t}'")),
                }
            }
            Some(c) if c.is_ascii_alphabetic() || c == b'!' => {
                let k = self.keyword();
                self.eat(b'(')?;
                self.i -= 1;
                match self.value(depth + 1)? {
                    Value::List(v) => Ok(Value::Typed(Box::new((k, v)))),
                    Value::Reals(v) => Ok(Value::Typed(Box::new((
                        k,
                        v.iter().map(|x| Value::Real(*x)).collect(),
                    )))),
                    Value::Refs(v) => Ok(Value::Typed(Box::new((
                        k,
                        v.iter().map(|x| Value::Ref(*x)).collect(),
                    )))),
                    _ => self.err("expected arguments"),
                }
            }
            Some(c) => self.err(format!("unexpected character '{}'", c as char)),
            None => self.err("unexpected end of file"),
        }
    }
    fn args(&mut self) -> Result<Box<[Value]>, SyntaxError> {
        match self.value(0)? {
            Value::List(v) => Ok(v),
            _ => self.err("expected an argument list"),
        }
    }
    /// One instance after its `#id=`: simple `NAME(args)` or complex `(NAME(args) …)`, and `;`.
    fn instance(&mut self, id: u64) -> Result<Entity, SyntaxError> {
        let e = if self.peek() == Some(b'(') {
            self.i += 1;
            let mut parts = Vec::new();
            while self.peek() != Some(b')') {
                let k = self.keyword();
                if k.is_empty() {
                    return self.err(format!("#{id}: expected a partial entity name"));
                }
                parts.push((k, self.args()?));
            }
            self.i += 1;
            Entity::Complex(parts.into_boxed_slice())
        } else {
            let k = self.keyword();
            if k.is_empty() {
                return self.err(format!("#{id}: expected an entity name"));
            }
            Entity::Simple(k, self.args()?)
        };
        self.eat(b';')?;
        Ok(e)
    }
}

/// Parse a whole STEP file.
pub fn parse(text: &str) -> Result<Part21, SyntaxError> {
    let mut lx = Lexer {
        text,
        s: text.as_bytes(),
        i: 0,
        line: 1,
        names: HashMap::default(),
        stack: Vec::new(),
    };
    let mut out = Part21::default();
    // Header: find FILE_SCHEMA's strings, then DATA;
    if let Some(p) = text.find("FILE_SCHEMA") {
        let rest = &text[p..];
        let end = rest.find(';').unwrap_or(rest.len());
        out.schema = rest[..end]
            .split('\'')
            .skip(1)
            .step_by(2)
            .map(|s| s.to_string())
            .collect();
    }
    let Some(d) = text.find("DATA;") else {
        return Err(SyntaxError {
            line: 1,
            reason: "no DATA section (not an ISO 10303-21 file?)".into(),
        });
    };
    lx.line += text[..d].matches('\n').count();
    lx.i = d + 5;
    // Instances with their lines, in file order; ids usually ascend, and only once they do not
    // is a map of every id's line built, to name both places when an id is defined twice.
    let mut found: Vec<(u64, Entity)> = Vec::new();
    let mut lines: Vec<usize> = Vec::new();
    let mut defined: Option<HashMap<u64, usize>> = None;
    loop {
        match lx.peek() {
            None => return lx.err("missing ENDSEC"),
            Some(b'#') => {
                lx.i += 1;
                let Some(id) = lx.digits() else {
                    return lx.err("malformed instance id");
                };
                let ascending = defined.is_none() && found.last().is_none_or(|l| l.0 < id);
                if !ascending {
                    let map = defined.get_or_insert_with(|| {
                        found
                            .iter()
                            .map(|x| x.0)
                            .zip(lines.iter().copied())
                            .collect()
                    });
                    if let Some(first) = map.insert(id, lx.line) {
                        // A second `#N=` would silently replace the first instance and every
                        // reference to it: the file is ambiguous.
                        return lx.err(format!(
                            "#{id} is defined twice (first on line {first}); instance ids must be unique"
                        ));
                    }
                }
                lines.push(lx.line);
                lx.eat(b'=')?;
                let e = lx.instance(id)?;
                found.push((id, e));
            }
            Some(_) => {
                let k = lx.keyword();
                if &*k == "ENDSEC" {
                    out.entities = Table::new(found);
                    return Ok(out);
                }
                return lx.err(format!("unexpected '{k}' in DATA section"));
            }
        }
    }
}
