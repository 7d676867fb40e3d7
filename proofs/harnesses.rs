//! Proof harnesses: properties that certified outputs rest on, each written once as a plain
//! function and driven two ways:
//! * `#[test]` — `cargo test --test proofs` runs it exhaustively over a bounded domain or
//!   over deterministic random and adversarial inputs, with exact rational arithmetic as the
//!   oracle (`VERICAD_LARGE=1` enlarges the runs);
//! * `#[cfg(kani)] #[kani::proof]` — where Kani is installed, `cargo kani --tests` proves the
//!   integer and bounded ones for every input allowed by `kani::assume`.
//!
//! See `proofs/README.md` for what each harness establishes, over which domain, what it does
//! not establish, and the mutation of the code under test it was checked to catch.

mod common;

mod along;
mod bezier_jet;
mod cones;
mod coverage;
mod curve_on_surface;
mod hermite;
mod hull;
mod interval;
mod sign_change;
mod trace;
mod trims;
