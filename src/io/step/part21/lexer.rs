//! The tokens and values of Part 21 text (see the parent module): each value becomes a word
//! of the table's storage ([`super::table`]).

use super::table::{self, tag, tag_of, word};
use super::{MAX_INTERNED, Name, Parser, SyntaxError};

/// The parse of one piece of text.
pub(super) struct Lexer<'a, 'p> {
    pub text: &'a str,
    pub s: &'a [u8],
    pub i: usize,
    pub p: &'p mut Parser,
}

impl Lexer<'_, '_> {
    pub(super) fn err<T>(&self, reason: impl Into<String>) -> Result<T, SyntaxError> {
        Err(SyntaxError {
            line: self.p.line,
            reason: reason.into(),
        })
    }
    fn skip_ws(&mut self) {
        loop {
            while let Some(&c) = self.s.get(self.i)
                && c.is_ascii_whitespace()
            {
                if c == b'\n' {
                    self.p.line += 1;
                }
                self.i += 1;
            }
            if self.s[self.i..].starts_with(b"/*") {
                match self.s[self.i + 2..].windows(2).position(|w| w == b"*/") {
                    Some(p) => {
                        self.p.line += self.s[self.i..self.i + 2 + p]
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
    pub(super) fn peek(&mut self) -> Option<u8> {
        self.skip_ws();
        self.s.get(self.i).copied()
    }
    pub(super) fn eat(&mut self, c: u8) -> Result<(), SyntaxError> {
        match self.peek() {
            Some(x) if x == c => {
                self.i += 1;
                Ok(())
            }
            Some(x) => self.err(format!("expected '{}', found '{}'", c as char, x as char)),
            None => self.err(format!("expected '{}', found end of file", c as char)),
        }
    }
    /// A keyword (letters, digits, `_`, `!`), upper-cased and interned: its name index (the
    /// empty name if there is none).
    pub(super) fn keyword(&mut self) -> u64 {
        self.skip_ws();
        let st = self.i;
        while let Some(&c) = self.s.get(self.i)
            && (c.is_ascii_alphanumeric() || c == b'_' || c == b'!')
        {
            self.i += 1;
        }
        let raw = &self.s[st..self.i];
        if let Some(&n) = self.p.names.get(raw) {
            return n;
        }
        // ASCII only, so the slice is on character boundaries.
        let n: Name = self.text[st..self.i].to_ascii_uppercase().into();
        let k = self.p.store.names.len() as u64;
        self.p.store.names.push(n);
        // Real schemas use a few hundred names; past the cap new names are not kept, so a file
        // made of many names whose hashes collide cannot make the table's probing quadratic.
        if self.p.names.len() < MAX_INTERNED {
            self.p.names.insert(raw.into(), k);
        }
        k
    }
    /// The digits at the cursor as an id or reference; `None` if there are none or too many.
    pub(super) fn digits(&mut self) -> Option<u64> {
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
    /// A quoted string (`'` doubled inside), the cursor after the opening quote: its word.
    fn string(&mut self) -> Result<u64, SyntaxError> {
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
        self.p.line += body.bytes().filter(|&c| c == b'\n').count();
        Ok(if escaped {
            self.p.store.string(&body.replace("''", "'"))
        } else {
            self.p.store.string(body)
        })
    }
    /// The items of a list at `depth` whose `(` was read, through its `)`, onto the stack.
    pub(super) fn items(&mut self, depth: usize) -> Result<(), SyntaxError> {
        if self.peek() == Some(b')') {
            self.i += 1;
            return Ok(());
        }
        loop {
            let v = self.value(depth + 1)?;
            self.p.stack.push(v);
            match self.peek() {
                Some(b',') => self.i += 1,
                Some(b')') => {
                    self.i += 1;
                    return Ok(());
                }
                _ => return self.err("expected ',' or ')' in a list"),
            }
        }
    }
    /// The list whose items are on the stack from `base`, taken off it into the store: its
    /// word. The items go on one stack shared by every open list, and a closed list's items
    /// are copied once into the table's words. Nested lists of reals or of references are
    /// kept as plain numbers (argument lists, `nested` false, stay lists of values).
    fn close(&mut self, base: usize, nested: bool) -> Result<u64, SyntaxError> {
        let p = &mut *self.p;
        let items = &mut p.stack[base..];
        let is_ref = |w: &u64| matches!(tag_of(*w), Some(tag::REF | tag::BIG_REF));
        let t = if !nested || items.is_empty() {
            tag::LIST
        } else if items.iter().all(|w| tag_of(*w).is_none()) {
            tag::REALS
        } else if items.iter().all(is_ref) {
            for w in items.iter_mut() {
                *w = match tag_of(*w) {
                    Some(tag::BIG_REF) => p.store.big.get((*w & table::PAYLOAD) as usize),
                    _ => None,
                }
                .copied()
                .unwrap_or(*w & table::PAYLOAD);
            }
            tag::REFS
        } else {
            tag::LIST
        };
        let w = p.store.list(t, &p.stack[base..]);
        p.stack.truncate(base);
        match w {
            Some(w) => Ok(w),
            None => self.err("file too large"),
        }
    }
    pub(super) fn value(&mut self, depth: usize) -> Result<u64, SyntaxError> {
        if depth > 64 {
            return self.err("lists nested too deeply");
        }
        match self.peek() {
            Some(b'(') => {
                self.i += 1;
                let base = self.p.stack.len();
                self.items(depth)?;
                self.close(base, depth > 0)
            }
            Some(b'#') => {
                self.i += 1;
                match self.digits() {
                    Some(r) => Ok(self.p.store.reference(r)),
                    None => self.err("malformed reference"),
                }
            }
            Some(b'\'') => {
                self.i += 1;
                self.string()
            }
            Some(b'.') => {
                self.i += 1;
                let k = self.keyword();
                self.eat(b'.')?;
                Ok(word(tag::ENUM, k))
            }
            Some(b'$') | Some(b'*') => {
                self.i += 1;
                Ok(word(tag::UNSET, 0))
            }
            Some(b'"') => {
                // Binary: keep as a string of hex digits.
                self.i += 1;
                let st = self.i;
                while self.i < self.s.len() && self.s[self.i] != b'"' {
                    self.i += 1;
                }
                let v = self.p.store.string(&self.text[st..self.i]);
                self.eat(b'"')?;
                Ok(v)
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
                    return Ok(self.p.store.int(i));
                }
                // Rust's float syntax takes the Part 21 forms `1.` and `1.E5` as they are.
                match t.parse::<f64>() {
                    Ok(x) if x.is_finite() => Ok(x.to_bits()),
                    _ => self.err(format!("malformed number '{t}'")),
                }
            }
            Some(c) if c.is_ascii_alphabetic() || c == b'!' => {
                // A typed parameter: its name, then its arguments (a list one level down,
                // kept as values).
                let k = self.keyword();
                self.eat(b'(')?;
                if depth + 1 > 64 {
                    return self.err("lists nested too deeply");
                }
                let base = self.p.stack.len();
                self.p.stack.push(k);
                self.items(depth + 1)?;
                let p = &mut *self.p;
                let w = p.store.list(tag::TYPED, &p.stack[base..]);
                p.stack.truncate(base);
                w.map_or_else(|| self.err("file too large"), Ok)
            }
            Some(c) => self.err(format!("unexpected character '{}'", c as char)),
            None => self.err("unexpected end of file"),
        }
    }
}
