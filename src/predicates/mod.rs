//! Exact geometric predicates on `f64` (adaptive, via Shewchuk's filters in `robust`) and on
//! every other backend (plain formulas in exact arithmetic). Never a tolerance where a sign
//! is asked.
//!
//! * [`orient`] — orient2d / orient3d;
//! * [`segment_plane`] — where a segment meets a triangle's plane;
//! * [`point_in_triangle`] — exact location of a point relative to a triangle;
//! * [`fn@tri_tri`] — triangle–triangle intersection, classified exactly, with the crossing
//!   segment's endpoints and a rigorous bound on their rounding error;
//! * [`fn@single_sided`] — a planar Bézier curve against its chord (Yang et al. §3);
//! * [`poly`] — exact polynomials, Sturm sequences, root isolation.

pub mod descartes;
pub mod orient;
pub mod point_in_triangle;
pub mod poly;
pub mod segment_plane;
pub mod single_sided;
pub mod tri_tri;

pub use orient::{orient2d, orient3d};
pub use single_sided::{Sidedness, single_sided};
pub use tri_tri::{TriTriContact, tri_tri};
