//! The instances of a Part 21 table by id, stored compactly: every value is one 64-bit word
//! of one array per table (a real as its own bits; anything else tagged in the bit patterns
//! no finite real has, see [`word`]), a list's items are consecutive words of the same array,
//! strings are slices of one text and names indices into one list. An instance is its id and
//! a row word: for most, the name, the number and the position of the arguments, for the
//! others the position of header words and arguments ([`Store::record`]). The ids are kept
//! sorted (an id is read by binary search). No allocation is made per instance or per list,
//! so the table takes about as many bytes as the file has numbers, references and names
//! (the hammer of `BENCHMARKS.md`: 0.96 MB for its 1.16 MB of text).
//!
//! The readers see instances through [`Inst`]; the typed form ([`Entity`], [`Value`]) is
//! made for an instance the first time [`Table::get`] (or an iterator of them) asks for it.
//!
//! [`Value`]: super::Value

use super::view::Inst;
use super::{Entity, Name};
use std::sync::OnceLock;

/// A word whose top twelve bits are all set (a negative sign and an exponent of all ones:
/// an infinity or NaN, never a parsed real, which is finite) holds a tag in bits 48–51 and a
/// 48-bit payload; any other word is a real.
const SPECIAL: u64 = 0xFFF0 << 48;
/// The payload bits of a tagged word.
pub(super) const PAYLOAD: u64 = (1 << 48) - 1;
/// A list of this many items or more keeps its length in the word before its items.
pub(super) const LONG: u64 = 0xFF;
/// Complex instance: the header's top bit; the low bits count its partial entities.
pub(super) const COMPLEX: u64 = 1 << 63;
/// A row's instance is a record of header words and arguments ([`Store::record`]).
pub(super) const INDIRECT: u64 = 1 << 63;
/// Names from this index on are not written in a row.
const ROW_NAMES: u64 = 0x7FFF;

/// The tags of [`word`]. Lists (`LIST` … `TYPED`) have the position of their items in the
/// table's words as payload bits 8–47 and their length in bits 0–7 ([`LONG`]: see there).
pub(super) mod tag {
    /// `$` or `*`.
    pub const UNSET: u64 = 0;
    /// An integer in the 48-bit two's complement range.
    pub const INT: u64 = 1;
    /// An integer outside it: the payload indexes [`super::Store::big`].
    pub const BIG_INT: u64 = 2;
    /// A reference below 2⁴⁸.
    pub const REF: u64 = 3;
    /// A larger reference: the payload indexes [`super::Store::big`].
    pub const BIG_REF: u64 = 4;
    /// A string: its start in the text (bits 16–47) and length (bits 0–15).
    pub const STR: u64 = 5;
    /// A longer or later string: the payload indexes [`super::Store::spans`].
    pub const LONG_STR: u64 = 6;
    /// An enumeration: the payload indexes the names.
    pub const ENUM: u64 = 7;
    /// A list of values.
    pub const LIST: u64 = 8;
    /// A nested list of reals: the items are the reals.
    pub const REALS: u64 = 9;
    /// A nested list of references: the items are the ids.
    pub const REFS: u64 = 10;
    /// A typed parameter: the first item is its name's index, the others its arguments.
    pub const TYPED: u64 = 11;
    /// A real that is not finite (only in tables made from typed instances): the payload
    /// indexes [`super::Store::big`], which holds its bits.
    pub const BIG_REAL: u64 = 12;
}

/// The word of tag `tag` and payload `payload` (below 2⁴⁸).
pub(super) fn word(tag: u64, payload: u64) -> u64 {
    SPECIAL | tag << 48 | (payload & PAYLOAD)
}

/// The tag of a word, `None` for a real.
pub(super) fn tag_of(w: u64) -> Option<u64> {
    (w >> 52 == 0xFFF).then_some((w >> 48) & 0xF)
}

/// A record's header word: the (partial) entity's name index and its number of arguments;
/// `None` when either is too large for its bits (31 and 32).
pub(super) fn header(name: usize, args: usize) -> Option<u64> {
    let (name, args) = (u32::try_from(name).ok()?, u32::try_from(args).ok()?);
    (args < 1 << 31).then_some(u64::from(name) | u64::from(args) << 32)
}

/// The storage of a table's values (see the module comment).
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct Store {
    pub words: Vec<u64>,
    /// Entity, partial-entity, typed-parameter and enumeration names.
    pub names: Vec<Name>,
    /// Every string's characters, one after the other.
    pub text: String,
    /// `(start, length)` in `text` of the strings [`tag::STR`] cannot place.
    pub spans: Vec<(usize, usize)>,
    /// Integers (as two's complement) and references too large for a payload.
    pub big: Vec<u64>,
}

/// The store of a view that has no table (an empty argument list).
pub(super) static EMPTY: Store = Store {
    words: Vec::new(),
    names: Vec::new(),
    text: String::new(),
    spans: Vec::new(),
    big: Vec::new(),
};

impl Store {
    /// The items of the list whose word has payload `payload`.
    pub fn items(&self, payload: u64) -> &[u64] {
        let pos = (payload >> 8) as usize;
        let (from, n) = match payload & LONG {
            LONG => (pos + 1, self.words.get(pos).map_or(0, |&n| n as usize)),
            n => (pos, n as usize),
        };
        self.words.get(from..from.saturating_add(n)).unwrap_or(&[])
    }
    /// The name of index `i`.
    #[inline]
    pub fn name(&self, i: u64) -> &str {
        self.names.get(i as usize).map_or("", |n| n)
    }
    /// The string of a [`tag::STR`] or [`tag::LONG_STR`] word's payload.
    pub fn str(&self, t: u64, payload: u64) -> &str {
        let (start, len) = if t == tag::STR {
            ((payload >> 16) as usize, (payload & 0xFFFF) as usize)
        } else {
            self.spans.get(payload as usize).copied().unwrap_or((0, 0))
        };
        self.text.get(start..start + len).unwrap_or("")
    }
    /// A value that is too large for a payload: its index in `big`.
    fn big(&mut self, t: u64, x: u64) -> u64 {
        self.big.push(x);
        word(t, self.big.len() as u64 - 1)
    }
    /// The word of an integer.
    pub fn int(&mut self, i: i64) -> u64 {
        if (-(1 << 47)..1 << 47).contains(&i) {
            word(tag::INT, i as u64)
        } else {
            self.big(tag::BIG_INT, i as u64)
        }
    }
    /// The word of a reference.
    pub fn reference(&mut self, r: u64) -> u64 {
        if r <= PAYLOAD {
            word(tag::REF, r)
        } else {
            self.big(tag::BIG_REF, r)
        }
    }
    /// The word of a string (its characters appended to the text).
    pub fn string(&mut self, s: &str) -> u64 {
        let start = self.text.len();
        self.text.push_str(s);
        if start < 1 << 32 && s.len() < 1 << 16 {
            word(tag::STR, (start as u64) << 16 | s.len() as u64)
        } else {
            self.spans.push((start, s.len()));
            word(tag::LONG_STR, self.spans.len() as u64 - 1)
        }
    }
    /// The word of a list of tag `t` whose items are `items` (appended to the words); `None`
    /// past 2⁴⁰ words.
    pub fn list(&mut self, t: u64, items: &[u64]) -> Option<u64> {
        let pos = self.words.len() as u64;
        if pos >= 1 << 40 {
            return None;
        }
        let n = items.len() as u64;
        if n >= LONG {
            self.words.push(n);
        }
        self.words.extend_from_slice(items);
        Some(word(t, pos << 8 | n.min(LONG)))
    }
    /// The record of an instance whose partial entities (each a [`header`] word and its
    /// arguments) are `parts`, appended to the words: its row word. A simple instance of up
    /// to 254 arguments whose name index is below 32767 is its arguments alone, the row
    /// holding their position (bits 0–39), number (40–47) and the name (48–62); any other
    /// has [`INDIRECT`] set and the position of its header words (a complex one's first
    /// counting its partial entities with [`COMPLEX`] set). `None` past 2⁴⁰ words.
    pub fn record(&mut self, parts: &[u64], complex: bool, count: u64) -> Option<u64> {
        let pos = self.words.len() as u64;
        if pos >= 1 << 40 {
            return None;
        }
        if !complex
            && let Some((&h, args)) = parts.split_first()
            && h & 0xFFFF_FFFF < ROW_NAMES
            && (args.len() as u64) < LONG
        {
            self.words.extend_from_slice(args);
            return Some(pos | (args.len() as u64) << 40 | (h & 0xFFFF_FFFF) << 48);
        }
        if complex {
            self.words.push(COMPLEX | count);
        }
        self.words.extend_from_slice(parts);
        Some(pos | INDIRECT)
    }
    /// Lengths of the growing parts, to undo what a failed instance added ([`Store::cut`]).
    pub fn mark(&self) -> [usize; 4] {
        [
            self.words.len(),
            self.text.len(),
            self.spans.len(),
            self.big.len(),
        ]
    }
    /// Back to the lengths of `mark` (names stay: a retry finds them again).
    pub fn cut(&mut self, [w, t, s, b]: [usize; 4]) {
        self.words.truncate(w);
        self.text.truncate(t);
        self.spans.truncate(s);
        self.big.truncate(b);
    }
}

/// The instances of a STEP file, sorted by id (ids are unique).
#[derive(Default)]
pub struct Table {
    /// `(id, row word of the instance (see [`Store::record`]))`, by id.
    rows: Vec<(u64, u64)>,
    store: Store,
    /// The typed form of each instance, made when first asked for.
    typed: OnceLock<Box<[OnceLock<Entity>]>>,
}

impl Table {
    /// The table of `items` (any order; ids unique — a later duplicate is dropped).
    pub fn new(mut items: Vec<(u64, Entity)>) -> Table {
        if !items.is_sorted_by(|a, b| a.0 < b.0) {
            items.sort_by_key(|x| x.0);
            items.dedup_by_key(|x| x.0);
        }
        let mut store = Store::default();
        let rows = items
            .iter()
            .map(|(id, e)| (*id, super::values::encode(&mut store, e)))
            .collect();
        Table::from_parts(rows, store)
    }
    /// The table of the records `rows` (`(id, row word)`, ids unique) in `store`.
    pub(super) fn from_parts(mut rows: Vec<(u64, u64)>, mut store: Store) -> Table {
        if !rows.is_sorted_by(|a, b| a.0 < b.0) {
            rows.sort_by_key(|x| x.0);
        }
        rows.shrink_to_fit();
        store.words.shrink_to_fit();
        store.text.shrink_to_fit();
        store.names.shrink_to_fit();
        Table {
            rows,
            store,
            typed: OnceLock::new(),
        }
    }
    /// The position of instance `id` in the table's (ascending id) order.
    pub fn index_of(&self, id: u64) -> Option<usize> {
        self.rows.binary_search_by_key(&id, |x| x.0).ok()
    }
    /// The instance with id `id`.
    pub fn inst(&self, id: u64) -> Option<Inst<'_>> {
        let i = self.index_of(id)?;
        Some(Inst::new(&self.store, self.rows[i].1))
    }
    /// Ids and instances in ascending id order.
    pub fn insts(&self) -> impl Iterator<Item = (u64, Inst<'_>)> + '_ {
        self.rows
            .iter()
            .map(|&(id, at)| (id, Inst::new(&self.store, at)))
    }
    /// The typed form of the instance in row `i`.
    fn typed(&self, i: usize) -> &Entity {
        let all = self
            .typed
            .get_or_init(|| (0..self.rows.len()).map(|_| OnceLock::new()).collect());
        all[i].get_or_init(|| Inst::new(&self.store, self.rows[i].1).to_entity())
    }
    /// The instance with id `id`, typed (see [`Table::inst`] for the instance as stored).
    pub fn get(&self, id: &u64) -> Option<&Entity> {
        Some(self.typed(self.index_of(*id)?))
    }
    /// Whether instance `id` is in the table.
    pub fn contains_key(&self, id: &u64) -> bool {
        self.index_of(*id).is_some()
    }
    /// The number of instances.
    pub fn len(&self) -> usize {
        self.rows.len()
    }
    /// Whether there are no instances.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }
    /// Ids and typed instances in ascending id order.
    pub fn iter(&self) -> Iter<'_> {
        Iter { t: self, i: 0 }
    }
    /// Ids in ascending order.
    pub fn keys(&self) -> impl Iterator<Item = &u64> {
        self.rows.iter().map(|x| &x.0)
    }
    /// Typed instances in ascending id order.
    pub fn values(&self) -> impl Iterator<Item = &Entity> {
        self.iter().map(|x| x.1)
    }
}

/// Iterator over a [`Table`]'s ids and typed instances.
#[derive(Clone)]
pub struct Iter<'a> {
    t: &'a Table,
    i: usize,
}

impl<'a> Iterator for Iter<'a> {
    type Item = (&'a u64, &'a Entity);
    fn next(&mut self) -> Option<Self::Item> {
        let row = self.t.rows.get(self.i)?;
        self.i += 1;
        Some((&row.0, self.t.typed(self.i - 1)))
    }
    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.t.rows.len() - self.i;
        (n, Some(n))
    }
}

impl ExactSizeIterator for Iter<'_> {}

impl<'a> IntoIterator for &'a Table {
    type Item = (&'a u64, &'a Entity);
    type IntoIter = Iter<'a>;
    fn into_iter(self) -> Iter<'a> {
        self.iter()
    }
}

impl FromIterator<(u64, Entity)> for Table {
    fn from_iter<I: IntoIterator<Item = (u64, Entity)>>(it: I) -> Table {
        Table::new(it.into_iter().collect())
    }
}

impl Clone for Table {
    /// The same instances (their typed forms made again when asked for).
    fn clone(&self) -> Table {
        Table {
            rows: self.rows.clone(),
            store: self.store.clone(),
            typed: OnceLock::new(),
        }
    }
}

impl PartialEq for Table {
    /// The same ids with equal instances.
    fn eq(&self, other: &Table) -> bool {
        self.len() == other.len()
            && self
                .insts()
                .zip(other.insts())
                .all(|((a, x), (b, y))| a == b && x.to_entity() == y.to_entity())
    }
}

impl std::fmt::Debug for Table {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_map()
            .entries(self.insts().map(|(id, e)| (id, e.to_entity())))
            .finish()
    }
}
