//! The instances of a Part 21 table by id: one vector sorted by id (an id is read by binary
//! search). Files list their instances mostly in ascending id order, so the parse's vector is
//! the table itself: no second structure is built beside it, and a tree's per-node overhead is
//! not paid.

use super::Entity;

/// The instances of a STEP file, sorted by id (ids are unique).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Table {
    items: Vec<(u64, Entity)>,
}

impl Table {
    /// The table of `items` (any order; ids unique — a later duplicate is dropped).
    pub fn new(mut items: Vec<(u64, Entity)>) -> Table {
        if !items.is_sorted_by(|a, b| a.0 < b.0) {
            items.sort_by_key(|x| x.0);
            items.dedup_by_key(|x| x.0);
        }
        items.shrink_to_fit();
        Table { items }
    }
    /// The instance with id `id`.
    pub fn get(&self, id: &u64) -> Option<&Entity> {
        let i = self.items.binary_search_by_key(id, |x| x.0).ok()?;
        Some(&self.items[i].1)
    }
    pub fn contains_key(&self, id: &u64) -> bool {
        self.get(id).is_some()
    }
    pub fn len(&self) -> usize {
        self.items.len()
    }
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }
    /// Ids and instances in ascending id order.
    pub fn iter(&self) -> Iter<'_> {
        self.items.iter().map(pair)
    }
    /// Ids in ascending order.
    pub fn keys(&self) -> impl Iterator<Item = &u64> {
        self.items.iter().map(|x| &x.0)
    }
    /// Instances in ascending id order.
    pub fn values(&self) -> impl Iterator<Item = &Entity> {
        self.items.iter().map(|x| &x.1)
    }
}

/// An id and its instance, as a map's iterator gives them.
fn pair(x: &(u64, Entity)) -> (&u64, &Entity) {
    (&x.0, &x.1)
}

/// Iterator over a [`Table`]'s ids and instances.
pub type Iter<'a> = std::iter::Map<std::slice::Iter<'a, (u64, Entity)>, PairFn<'a>>;
/// The function [`Iter`] maps with.
pub type PairFn<'a> = fn(&'a (u64, Entity)) -> (&'a u64, &'a Entity);

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
