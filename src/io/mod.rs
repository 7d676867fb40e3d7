//! Writers (and, with the formats issue, readers) of exchange and viewing formats.

pub mod svg;
