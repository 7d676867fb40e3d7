//! Borrowed views of a [`Table`](super::Table)'s instances as stored: an instance
//! ([`Inst`]), an argument list ([`Args`]) and a value ([`Val`]), each a reference into the
//! table and a position, copied freely. They answer what [`Entity`] and [`Value`] answer,
//! without making either.

use super::table::{COMPLEX, EMPTY, INDIRECT, PAYLOAD, Store, tag, tag_of, word};
use super::{Entity, Name, Value};

/// An instance of a table (simple or complex), as stored.
#[derive(Clone, Copy)]
pub struct Inst<'a> {
    s: &'a Store,
    /// Its row word ([`Store::record`]).
    row: u64,
}

impl<'a> Inst<'a> {
    pub(super) fn new(s: &'a Store, row: u64) -> Self {
        Inst { s, row }
    }
    /// Where its words start.
    fn at(&self) -> usize {
        (self.row & ((1 << 40) - 1)) as usize
    }
    /// Whether the instance is complex (`(A(…) B(…))`, even of one partial entity).
    pub fn is_complex(&self) -> bool {
        self.row & INDIRECT != 0
            && self
                .s
                .words
                .get(self.at())
                .is_some_and(|h| h & COMPLEX != 0)
    }
    /// Every (partial) entity's name and arguments, in file order.
    pub fn parts(&self) -> Parts<'a> {
        let at = self.at();
        if self.row & INDIRECT == 0 {
            let n = (self.row >> 40) as usize & 0xFF;
            let direct = (self.row >> 48, self.s.words.get(at..at + n).unwrap_or(&[]));
            return Parts {
                s: self.s,
                at,
                left: 0,
                direct: Some(direct),
            };
        }
        let (at, left) = match self.s.words.get(at) {
            Some(&h) if h & COMPLEX != 0 => (at + 1, (h & !COMPLEX) as usize),
            _ => (at, 1),
        };
        Parts {
            s: self.s,
            at,
            left,
            direct: None,
        }
    }
    /// The name of a simple instance written in its row (most are).
    #[inline]
    fn row_name(&self) -> Option<&'a str> {
        (self.row & INDIRECT == 0).then(|| self.s.name(self.row >> 48))
    }
    /// The entity's type name (the first partial entity's for complex instances).
    #[inline]
    pub fn name(&self) -> &'a str {
        match self.row_name() {
            Some(n) => n,
            None => self.parts().next().map_or("", |p| p.0),
        }
    }
    /// The arguments of a simple instance (`None` for a complex one).
    pub fn simple_args(&self) -> Option<Args<'a>> {
        (!self.is_complex()).then(|| self.parts().next().map(|p| p.1))?
    }
    /// Arguments of the (partial) entity called `name`.
    #[inline]
    pub fn part(&self, name: &str) -> Option<Args<'a>> {
        match self.row_name() {
            Some(n) if n != name => None,
            _ => self.find(name),
        }
    }
    /// [`Inst::part`] by a walk over the partial entities.
    fn find(&self, name: &str) -> Option<Args<'a>> {
        self.parts().find(|p| p.0 == name).map(|p| p.1)
    }
    /// Whether the instance is, or contains, `name`.
    #[inline]
    pub fn is(&self, name: &str) -> bool {
        match self.row_name() {
            Some(n) => n == name,
            None => self.find(name).is_some(),
        }
    }
    /// Every reference in the instance.
    pub fn refs(&self) -> Vec<u64> {
        let mut out = Vec::new();
        for (_, a) in self.parts() {
            a.iter().for_each(|v| v.refs(&mut out));
        }
        out
    }
    /// The typed form of the instance.
    pub fn to_entity(&self) -> Entity {
        let name = |n: &str| -> Name { n.into() };
        if self.is_complex() {
            Entity::Complex(
                self.parts()
                    .map(|(n, a)| (name(n), a.to_values()))
                    .collect(),
            )
        } else {
            let (n, a) = self.parts().next().unwrap_or_default();
            Entity::Simple(name(n), a.to_values())
        }
    }
}

impl std::fmt::Debug for Inst<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.to_entity().fmt(f)
    }
}

/// The partial entities of an instance ([`Inst::parts`]).
#[derive(Clone)]
pub struct Parts<'a> {
    s: &'a Store,
    /// The next header word.
    at: usize,
    /// Header words left.
    left: usize,
    /// A simple instance written in its row: name index and arguments.
    direct: Option<(u64, &'a [u64])>,
}

impl<'a> Iterator for Parts<'a> {
    type Item = (&'a str, Args<'a>);
    fn next(&mut self) -> Option<Self::Item> {
        if let Some((name, items)) = self.direct.take() {
            return Some((self.s.name(name), Args { s: self.s, items }));
        }
        if self.left == 0 {
            return None;
        }
        self.left -= 1;
        let h = *self.s.words.get(self.at)?;
        let n = (h >> 32) as usize & 0x7FFF_FFFF;
        let items = self.s.words.get(self.at + 1..self.at + 1 + n)?;
        self.at += 1 + n;
        Some((self.s.name(h & 0xFFFF_FFFF), Args { s: self.s, items }))
    }
}

/// The values of an argument list (or of a list of values), as stored.
#[derive(Clone, Copy)]
pub struct Args<'a> {
    s: &'a Store,
    items: &'a [u64],
}

impl Default for Args<'_> {
    /// No values.
    fn default() -> Self {
        Args {
            s: &EMPTY,
            items: &[],
        }
    }
}

impl<'a> Args<'a> {
    /// The number of values.
    pub fn len(&self) -> usize {
        self.items.len()
    }
    /// Whether there are no values.
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }
    /// Value `i`.
    pub fn get(&self, i: usize) -> Option<Val<'a>> {
        let w = *self.items.get(i)?;
        Some(Val { s: self.s, w })
    }
    /// Value 0.
    pub fn first(&self) -> Option<Val<'a>> {
        self.get(0)
    }
    /// The last value.
    pub fn last(&self) -> Option<Val<'a>> {
        self.get(self.len().checked_sub(1)?)
    }
    /// The values from `i` on (none when `i` is past the end).
    pub fn from(&self, i: usize) -> Args<'a> {
        Args {
            s: self.s,
            items: self.items.get(i..).unwrap_or(&[]),
        }
    }
    /// The values in order.
    pub fn iter(&self) -> ArgsIter<'a> {
        ArgsIter {
            s: self.s,
            items: self.items.iter(),
        }
    }
    /// The typed form of the values.
    pub fn to_values(&self) -> Box<[Value]> {
        self.iter().map(|v| v.to_value()).collect()
    }
}

impl<'a> IntoIterator for Args<'a> {
    type Item = Val<'a>;
    type IntoIter = ArgsIter<'a>;
    fn into_iter(self) -> ArgsIter<'a> {
        self.iter()
    }
}

impl std::fmt::Debug for Args<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// Iterator over the values of [`Args`].
#[derive(Clone)]
pub struct ArgsIter<'a> {
    s: &'a Store,
    items: std::slice::Iter<'a, u64>,
}

impl<'a> Iterator for ArgsIter<'a> {
    type Item = Val<'a>;
    fn next(&mut self) -> Option<Val<'a>> {
        let w = *self.items.next()?;
        Some(Val { s: self.s, w })
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        self.items.size_hint()
    }
}

impl ExactSizeIterator for ArgsIter<'_> {}

/// A parameter value, as stored.
#[derive(Clone, Copy)]
pub struct Val<'a> {
    s: &'a Store,
    w: u64,
}

impl Default for Val<'_> {
    /// `$`.
    fn default() -> Self {
        Val {
            s: &EMPTY,
            w: word(tag::UNSET, 0),
        }
    }
}

impl<'a> Val<'a> {
    /// The value's tag and payload (`None` for a real).
    fn tagged(&self) -> Option<(u64, u64)> {
        Some((tag_of(self.w)?, self.w & PAYLOAD))
    }
    /// The items of a list of tag `t`.
    fn items(&self, t: u64) -> Option<&'a [u64]> {
        match self.tagged()? {
            (x, p) if x == t => Some(self.s.items(p)),
            _ => None,
        }
    }
    /// A number (integers widen to reals).
    pub fn num(&self) -> Option<f64> {
        match self.tagged() {
            None | Some((tag::BIG_REAL, _)) => self.real(),
            Some((tag::INT | tag::BIG_INT, _)) => self.int().map(|i| i as f64),
            Some((tag::TYPED, _)) => match self.typed()?.1 {
                a if a.len() == 1 => a.first()?.num(),
                _ => None,
            },
            _ => None,
        }
    }
    /// An integer.
    pub fn int(&self) -> Option<i64> {
        match self.tagged()? {
            (tag::INT, p) => Some(((p << 16) as i64) >> 16),
            (tag::BIG_INT, p) => self.s.big.get(p as usize).map(|&x| x as i64),
            _ => None,
        }
    }
    /// A reference (`#id`): the id.
    pub fn reference(&self) -> Option<u64> {
        match self.tagged()? {
            (tag::REF, p) => Some(p),
            (tag::BIG_REF, p) => self.s.big.get(p as usize).copied(),
            _ => None,
        }
    }
    /// A real (not an integer).
    pub fn real(&self) -> Option<f64> {
        match self.tagged() {
            None => Some(f64::from_bits(self.w)),
            Some((tag::BIG_REAL, p)) => self.s.big.get(p as usize).map(|x| f64::from_bits(*x)),
            _ => None,
        }
    }
    /// `$` or `*`.
    pub fn is_unset(&self) -> bool {
        self.tagged() == Some((tag::UNSET, 0))
    }
    /// A string's characters.
    pub fn str(&self) -> Option<&'a str> {
        match self.tagged()? {
            (t @ (tag::STR | tag::LONG_STR), p) => Some(self.s.str(t, p)),
            _ => None,
        }
    }
    /// An enumeration's name (`.F.`: `F`).
    pub fn enumeration(&self) -> Option<&'a str> {
        match self.tagged()? {
            (tag::ENUM, p) => Some(self.s.name(p)),
            _ => None,
        }
    }
    /// A typed parameter's name and arguments.
    pub fn typed(&self) -> Option<(&'a str, Args<'a>)> {
        let (name, items) = self.items(tag::TYPED)?.split_first()?;
        Some((self.s.name(*name), Args { s: self.s, items }))
    }
    /// The items of a list that is not of reals or of references alone (see
    /// [`Val::numbers`] and [`Val::list_refs`]).
    pub fn list(&self) -> Option<Args<'a>> {
        let items = self.items(tag::LIST)?;
        Some(Args { s: self.s, items })
    }
    /// The numbers of a list of numbers (of reals, or of numbers: integers widen to reals);
    /// `None` for anything else.
    pub fn numbers(&self) -> Option<Vec<f64>> {
        match self.items(tag::REALS) {
            Some(v) => Some(v.iter().map(|x| f64::from_bits(*x)).collect()),
            None => self.list()?.iter().map(|v| v.num()).collect(),
        }
    }
    /// Per item of a list, its number if it is one ([`Val::num`]); `None` for a value that
    /// is not a list.
    pub fn list_numbers(&self) -> Option<Vec<Option<f64>>> {
        match self.items(tag::REALS) {
            Some(v) => Some(v.iter().map(|x| Some(f64::from_bits(*x))).collect()),
            None => Some(self.list()?.iter().map(|v| v.num()).collect()),
        }
    }
    /// Per item of a list, its reference if it is one (`None` for an item that is not a
    /// reference); `None` for a value that is not a list.
    pub fn list_refs(&self) -> Option<ListRefs<'a>> {
        match self.items(tag::REFS) {
            Some(v) => Some(ListRefs::Ids(v.iter())),
            None => Some(ListRefs::Vals(self.list()?.iter())),
        }
    }
    /// Every reference inside this value (recursively).
    pub fn refs(&self, out: &mut Vec<u64>) {
        match self.tagged() {
            Some((tag::REF | tag::BIG_REF, _)) => out.extend(self.reference()),
            Some((tag::REFS, p)) => out.extend_from_slice(self.s.items(p)),
            Some((tag::LIST, _)) => self.list().into_iter().flatten().for_each(|x| x.refs(out)),
            Some((tag::TYPED, _)) => {
                if let Some((_, a)) = self.typed() {
                    a.iter().for_each(|x| x.refs(out))
                }
            }
            _ => {}
        }
    }
    /// The typed form of the value.
    pub fn to_value(&self) -> Value {
        let Some((t, p)) = self.tagged() else {
            return Value::Real(f64::from_bits(self.w));
        };
        let items = || self.s.items(p);
        match t {
            tag::BIG_REAL => Value::Real(self.real().unwrap_or(0.0)),
            tag::INT | tag::BIG_INT => Value::Int(self.int().unwrap_or(0)),
            tag::REF | tag::BIG_REF => Value::Ref(self.reference().unwrap_or(0)),
            tag::STR | tag::LONG_STR => Value::Str(self.s.str(t, p).into()),
            tag::ENUM => Value::Enum(self.s.name(p).into()),
            tag::LIST => Value::List(
                Args {
                    s: self.s,
                    items: items(),
                }
                .to_values(),
            ),
            tag::REALS => Value::Reals(items().iter().map(|x| f64::from_bits(*x)).collect()),
            tag::REFS => Value::Refs(items().into()),
            tag::TYPED => {
                let (n, a) = self.typed().unwrap_or_default();
                Value::Typed(Box::new((n.into(), a.to_values())))
            }
            _ => Value::Unset,
        }
    }
}

impl std::fmt::Debug for Val<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        self.to_value().fmt(f)
    }
}

/// The items of a list as references ([`Val::list_refs`], [`Value::list_refs`]).
#[derive(Clone, Debug)]
pub enum ListRefs<'a> {
    /// The ids of a list of references alone ([`Value::Refs`], or its stored form).
    Ids(std::slice::Iter<'a, u64>),
    /// The items of a [`Value::List`].
    Values(std::slice::Iter<'a, Value>),
    /// The items of a stored list of values ([`Val::list`]).
    Vals(ArgsIter<'a>),
}

impl std::fmt::Debug for ArgsIter<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.clone()).finish()
    }
}

impl Iterator for ListRefs<'_> {
    type Item = Option<u64>;
    fn next(&mut self) -> Option<Option<u64>> {
        match self {
            ListRefs::Ids(i) => i.next().map(|r| Some(*r)),
            ListRefs::Values(i) => i.next().map(Value::reference),
            ListRefs::Vals(i) => i.next().map(|v| v.reference()),
        }
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        match self {
            ListRefs::Ids(i) => i.size_hint(),
            ListRefs::Values(i) => i.size_hint(),
            ListRefs::Vals(i) => i.size_hint(),
        }
    }
}

impl ExactSizeIterator for ListRefs<'_> {}

impl Default for ListRefs<'_> {
    /// No items.
    fn default() -> Self {
        ListRefs::Ids([].iter())
    }
}
