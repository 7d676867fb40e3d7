//! The typed form of a Part 21 table's values and instances ([`Value`], [`Entity`]): what
//! [`super::Table::get`] gives, and what [`super::Table::new`] stores.

use super::table::{Store, header, tag, word};
use super::{ListRefs, Name};

/// A parameter value.
#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Int(i64),
    Real(f64),
    Str(Box<str>),
    Enum(Name),
    Ref(u64),
    List(Box<[Value]>),
    /// A nested list whose items are all reals (coordinates, weights, knots), stored as
    /// numbers: a third of the size of [`Value::List`]'s values. Argument lists and a typed
    /// parameter's arguments are always [`Value::List`].
    Reals(Box<[f64]>),
    /// A nested list whose items are all references (control points, a loop's edges, a
    /// shell's faces), stored as ids: a third of the size of [`Value::List`]'s values. Read
    /// through [`Value::list_refs`].
    Refs(Box<[u64]>),
    /// A typed parameter such as `LENGTH_MEASURE(1.0)`: its name and arguments, boxed (they are
    /// rare, and inline they would make every value larger).
    Typed(Box<(Name, Box<[Value]>)>),
    /// `$` (unset) or `*` (derived).
    Unset,
}

impl Value {
    /// A number (integers widen to reals).
    pub fn num(&self) -> Option<f64> {
        match self {
            Value::Real(x) => Some(*x),
            Value::Int(i) => Some(*i as f64),
            Value::Typed(t) if t.1.len() == 1 => t.1[0].num(),
            _ => None,
        }
    }
    pub fn int(&self) -> Option<i64> {
        match self {
            Value::Int(i) => Some(*i),
            _ => None,
        }
    }
    pub fn reference(&self) -> Option<u64> {
        match self {
            Value::Ref(r) => Some(*r),
            _ => None,
        }
    }
    /// The numbers of a list of numbers ([`Value::Reals`], or a [`Value::List`] of
    /// numbers: integers widen to reals); `None` for anything else.
    pub fn numbers(&self) -> Option<Vec<f64>> {
        match self {
            Value::Reals(v) => Some(v.to_vec()),
            Value::List(v) => v.iter().map(Value::num).collect(),
            _ => None,
        }
    }
    /// Per item of a list, its number if it is one ([`Value::num`]); `None` for a value that
    /// is not a list.
    pub fn list_numbers(&self) -> Option<Vec<Option<f64>>> {
        match self {
            Value::Reals(v) => Some(v.iter().map(|x| Some(*x)).collect()),
            Value::List(v) => Some(v.iter().map(Value::num).collect()),
            _ => None,
        }
    }
    /// Per item of a list, its reference if it is one ([`Value::Refs`], or a [`Value::List`]:
    /// `None` for an item that is not a reference); `None` for a value that is not a list.
    pub fn list_refs(&self) -> Option<ListRefs<'_>> {
        match self {
            Value::Refs(v) => Some(ListRefs::Ids(v.iter())),
            Value::List(v) => Some(ListRefs::Values(v.iter())),
            _ => None,
        }
    }
    /// The items of a list that is not a [`Value::Reals`] or [`Value::Refs`] (see
    /// [`Value::numbers`] and [`Value::list_refs`]).
    pub fn list(&self) -> Option<&[Value]> {
        match self {
            Value::List(v) => Some(v),
            _ => None,
        }
    }
    pub fn enumeration(&self) -> Option<&str> {
        match self {
            Value::Enum(e) => Some(e),
            _ => None,
        }
    }
    /// Every reference inside this value (recursively).
    pub fn refs(&self, out: &mut Vec<u64>) {
        match self {
            Value::Ref(r) => out.push(*r),
            Value::Refs(v) => out.extend_from_slice(v),
            Value::List(v) => v.iter().for_each(|x| x.refs(out)),
            Value::Typed(t) => t.1.iter().for_each(|x| x.refs(out)),
            _ => {}
        }
    }
}

/// One entity instance.
#[derive(Clone, Debug, PartialEq)]
pub enum Entity {
    Simple(Name, Box<[Value]>),
    /// A complex instance: its partial entities by name, in file order.
    Complex(Box<[(Name, Box<[Value]>)]>),
}

impl Entity {
    /// The entity's type name (the first partial entity's for complex instances).
    pub fn name(&self) -> &str {
        match self {
            Entity::Simple(n, _) => n,
            Entity::Complex(p) => p.first().map(|x| &*x.0).unwrap_or(""),
        }
    }
    /// Arguments of the (partial) entity called `name`.
    pub fn part(&self, name: &str) -> Option<&[Value]> {
        match self {
            Entity::Simple(n, a) if **n == *name => Some(a),
            Entity::Complex(p) => p.iter().find(|x| *x.0 == *name).map(|x| &*x.1),
            _ => None,
        }
    }
    /// Every (partial) entity's name and arguments, in file order.
    pub fn parts(&self) -> impl Iterator<Item = (&str, &[Value])> {
        let (one, many) = match self {
            Entity::Simple(n, a) => (Some((&**n, &**a)), &[][..]),
            Entity::Complex(p) => (None, &**p),
        };
        one.into_iter()
            .chain(many.iter().map(|(n, a)| (&**n, &**a)))
    }
    /// Whether the instance is, or contains, `name`.
    pub fn is(&self, name: &str) -> bool {
        self.part(name).is_some()
    }
    /// Every reference in the instance.
    pub fn refs(&self) -> Vec<u64> {
        let mut out = Vec::new();
        match self {
            Entity::Simple(_, a) => a.iter().for_each(|v| v.refs(&mut out)),
            Entity::Complex(p) => p
                .iter()
                .for_each(|(_, a)| a.iter().for_each(|v| v.refs(&mut out))),
        }
        out
    }
}

/// The word of `v` in `s` (its lists' items appended to the words).
fn encode_value(s: &mut Store, v: &Value) -> u64 {
    let list = |s: &mut Store, t, items: &[u64]| s.list(t, items).unwrap_or(word(tag::UNSET, 0));
    match v {
        Value::Int(i) => s.int(*i),
        Value::Real(x) if x.is_finite() => x.to_bits(),
        // Not a parsed value (those are finite): its bits could be a tagged word's.
        Value::Real(x) => {
            s.big.push(x.to_bits());
            word(tag::BIG_REAL, s.big.len() as u64 - 1)
        }
        Value::Str(x) => s.string(x),
        Value::Enum(n) => word(tag::ENUM, name(s, n)),
        Value::Ref(r) => s.reference(*r),
        Value::List(v) => {
            let items: Vec<u64> = v.iter().map(|x| encode_value(s, x)).collect();
            list(s, tag::LIST, &items)
        }
        Value::Reals(v) => {
            let items: Vec<u64> = v.iter().map(|x| x.to_bits()).collect();
            list(s, tag::REALS, &items)
        }
        Value::Refs(v) => list(s, tag::REFS, v),
        Value::Typed(t) => {
            let mut items = vec![name(s, &t.0)];
            items.extend(t.1.iter().map(|x| encode_value(s, x)));
            list(s, tag::TYPED, &items)
        }
        Value::Unset => word(tag::UNSET, 0),
    }
}

/// The index of a new name `n` in `s`.
fn name(s: &mut Store, n: &Name) -> u64 {
    s.names.push(n.clone());
    s.names.len() as u64 - 1
}

/// The record of `e` in `s`: its row word ([`Store::record`]).
pub(super) fn encode(s: &mut Store, e: &Entity) -> u64 {
    let mut parts = Vec::new();
    let mut count = 0;
    for (n, a) in e.parts() {
        let n = name(s, &n.into());
        let args: Vec<u64> = a.iter().map(|v| encode_value(s, v)).collect();
        // Past 2³¹ arguments (beyond any memory) the instance is kept without them.
        match header(n as usize, args.len()) {
            Some(h) => {
                parts.push(h);
                parts.extend(args);
            }
            None => parts.push(header(n as usize, 0).unwrap_or(0)),
        }
        count += 1;
    }
    let complex = matches!(e, Entity::Complex(_));
    s.record(&parts, complex, count).unwrap_or(0)
}
