//! vericad — verification-first computer-aided geometric design for surface grid generation.
//!
//! Layers (nothing below imports from above), see `ARCHITECTURE.md`:
//! `cli` → pipelines → `io`/`model` → `spline` → `predicates` → `scalar`, `geom`.
//!
//! # Where to start
//!
//! Every pipeline takes a [`model::Model`] (surfaces, curves, patch sets and, from STEP or
//! IGES, the B-rep with its faces, loops and edges) and returns a result that carries its
//! certificate: what is proven, and what is only measured or left uncertified. The entry
//! points, re-exported here:
//!
//! | step | entry point | result |
//! |---|---|---|
//! | read a file (STEP, IGES, native JSON, Plot3D, STL) | [`read_model`] | [`Model`] |
//! | surface–surface intersection (certified points, coverage) | [`intersect_models`] with [`SsiParams`] | [`SsiResult`] |
//! | curves on B-spline surfaces (Yang et al.) | [`approximate`] with [`CurveOnSurfaceParams`] | [`CurveOnSurface`] |
//! | repair of a faulty patch set (Uva, Monno & Hamann) | [`repair()`] with [`RepairParams`] | [`RepairResult`] |
//! | repair of a B-rep's trimmed faces | [`repair::faces::repair_faces`] | [`repair::faces::FacesResult`] |
//! | chord-length reparametrization, Coons approximation | [`reparam`], [`approx::coons`] | |
//!
//! The `vericad` command line (feature `cli`) parses arguments, calls these and prints; the
//! `*::job` modules add file output (JSON, SVG, VTK, IGES) around them.
//!
//! Reading a part and asking what it holds:
//!
//! ```
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/public/gmsh-t20_data.step");
//! let model = vericad::read_model(std::path::Path::new(path)).unwrap();
//! let brep = model.brep.as_ref().expect("STEP faces come with their B-rep");
//! assert_eq!(brep.faces.len(), 21);
//! // Faces bounded by their surface's whole parameter rectangle (the rest are trimmed).
//! let natural = vericad::brep::natural::natural_faces(brep, &model);
//! assert_eq!(natural.iter().filter(|n| **n).count(), 6);
//! ```
//!
//! A sphere of radius 2 cut by the plane `z = 1`: one closed loop of radius `√3`, every
//! point proven within `tol` of both surfaces and within its `curve_radius` of the true
//! curve, and the coverage certificate proving that no other branch exists:
//!
//! ```
//! use vericad::model::{Model, Surface};
//! use vericad::spline::construct::{Frame, bilinear, sphere};
//! use vericad::{SsiParams, intersect_models};
//!
//! let ball = sphere(&Frame::WORLD, 2.0).unwrap();
//! let plane = bilinear([-3., -3., 1.], [3., -3., 1.], [-3., 3., 1.], [3., 3., 1.]).unwrap();
//! let a = Model { surfaces: vec![Surface::new("ball", ball)], ..Default::default() };
//! let b = Model { surfaces: vec![Surface::new("plane", plane)], ..Default::default() };
//! let prm = SsiParams { tol: 1e-7, ..Default::default() };
//! let r = intersect_models(&a, Some(&b), &prm, &|_, _| {}).unwrap();
//! assert_eq!((r.summary.branches, r.summary.closed_branches), (1, 1));
//! assert!(r.summary.certified && r.summary.no_missed_branches);
//! assert!(r.summary.all_points_within_tol && r.summary.dist_max <= prm.tol);
//! assert!(r.summary.dist_curve_max.is_some_and(|d| d <= prm.tol));
//! for p in &r.pairs[0].branches[0].points {
//!     let radius = (p[0] * p[0] + p[1] * p[1]).sqrt();
//!     assert!((radius - 3f64.sqrt()).abs() < 1e-6 && (p[2] - 1.0).abs() < 1e-6);
//! }
//! ```
//!
//! Yang et al.'s Table 2 (a domain curve on a biquadratic surface): Bézier segments of degree
//! `p + q` lying on the surface, with a proven Hausdorff bound below `eps_d`:
//!
//! ```
//! use vericad::model::CurveGeometry;
//! use vericad::{CurveOnSurfaceParams, approximate};
//!
//! let m = vericad::model::json::from_str(vericad::model::YANG_TABLE2, "table2").unwrap();
//! let CurveGeometry::Domain(curve) = &m.curves[0].geometry else { panic!("a domain curve") };
//! let prm = CurveOnSurfaceParams { eps_d: 1e-3, ..Default::default() };
//! let r = approximate(&m.surfaces[0].nurbs, curve, &prm).unwrap();
//! assert!(r.certificate.hausdorff_bound <= 1e-3);
//! assert!(r.segments.iter().all(|s| s.degree == 4));
//! ```
//!
//! Two unit squares meant to share an edge, 1e-4 apart there: the repair connects them,
//! makes the shared edge identical on both sides and, as they meet without a feature edge,
//! merges them into one patch:
//!
//! ```
//! use vericad::repair::features::FeatureOverrides;
//! use vericad::spline::construct::bilinear;
//! use vericad::{RepairParams, repair};
//!
//! let left = bilinear([0., 0., 0.], [1., 0., 0.], [0., 1., 0.], [1., 1., 0.]).unwrap();
//! let right = bilinear([1., 0., 1e-4], [2., 0., 0.], [1., 1., 1e-4], [2., 1., 0.]).unwrap();
//! let prm = RepairParams { u1: 1e-3, u2: 1e-3, ..Default::default() };
//! let r = repair(vec![left, right], &prm, &FeatureOverrides::default(), &|_| {}).unwrap();
//! assert_eq!((r.report.edges_connected, r.report.shared_edges_identical), (1, 1));
//! assert!(r.report.gap_max_before > 9e-5 && r.report.gap_max_after < 1e-12);
//! assert_eq!(r.report.patches_out, 1);
//! ```

// Index loops mirror the published algorithms (The NURBS Book, de Casteljau); keep them.
#![allow(clippy::needless_range_loop)]

pub mod approx;
pub mod batch;
pub mod brep;
pub mod budget;
#[cfg(feature = "cli")]
pub mod cli;
pub mod curve_on_surface;
pub mod demo;
#[doc(hidden)]
pub mod fuzz_entry;
pub mod geom;
pub mod io;
pub mod model;
pub mod predicates;
pub mod progress;
pub mod repair;
pub mod reparam;
pub mod scalar;
pub mod spline;
pub mod ssi;
pub mod tessellate;

pub use curve_on_surface::{CurveOnSurface, Params as CurveOnSurfaceParams, approximate};
pub use io::{read_model, write_model};
pub use model::Model;
pub use repair::{RepairParams, RepairResult, repair};
pub use scalar::{RealScalar, Scalar, Sign};
pub use ssi::{SsiParams, SsiResult, intersect_models};
