//! Exact geometric predicates.
