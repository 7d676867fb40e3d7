//! The subcommands of the command line and their arguments, with the help text clap prints
//! for each.

use super::{approximate, batch, coons, memory, reparam, shell};
use clap::Subcommand;
use std::path::PathBuf;

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Run the main job on the embedded default model (Yang et al. Table 2 data) and write
    /// its outputs.
    Demo {
        /// Directory for the outputs.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// Print the report as JSON instead of the human summary.
        #[arg(long)]
        json: bool,
    },
    /// Summarize a model file: surfaces, curves, degrees, rational or not, bounding box.
    Info {
        /// Model file: native JSON, STEP (.step/.stp), IGES (.igs/.iges), STL or Plot3D
        /// (.xyz/.p3d).
        file: PathBuf,
        #[command(flatten)]
        memory: memory::MemoryArg,
        /// Print the result as JSON instead of the human summary.
        #[arg(long)]
        json: bool,
    },
    /// Convert a model between formats (from the extensions). Reads native JSON, STEP, IGES,
    /// STL and Plot3D; writes JSON, STEP, IGES, STL (ASCII or binary), VTK PolyData (.vtp)
    /// and OBJ. Analytic surfaces are written as their exact NURBS forms; a B-rep's faces
    /// are tessellated inside their trims for STL, OBJ and VTP; what the target format
    /// cannot hold is reported.
    Convert {
        /// Model to read (.json, .step/.stp, .igs/.iges, .stl, .xyz/.p3d).
        input: PathBuf,
        /// File to write (.json, .step/.stp, .igs/.iges, .stl, .vtp, .obj).
        output: PathBuf,
        /// Output format, overriding the extension: json, step, iges, iges-faces, stl,
        /// stl-binary, vtp, obj. A B-rep is written to IGES as B-rep entities
        /// (186/514/510/508/504/502); `iges-faces` writes trimmed surfaces (144/142) instead.
        #[arg(long)]
        format: Option<String>,
        /// For STL, OBJ and VTP output of a B-rep: triangulate finer until the measured
        /// chordal deviation (surface to triangles, edge curves to segments, sampled at seven
        /// points per triangle and at edge midpoints: evidence, not a bound) is at most this
        /// (model units). Exit 3 when it is not reached.
        #[arg(long)]
        chordal: Option<f64>,
        /// With --chordal: also prove a bound on the final mesh's deviation (every triangle
        /// within it of its face's surface over its parameter triangle, and back), from
        /// interval enclosures of the second derivatives and of the corners; several interval
        /// evaluations per triangle, so far slower than the meshing itself
        #[arg(long, requires = "chordal")]
        prove_chordal: bool,
        #[command(flatten)]
        memory: memory::MemoryArg,
    },
    /// Approximate the image of a domain curve on a B-spline surface by Bézier curves of degree
    /// p+q lying exactly on it, with a proven Hausdorff bound (Yang et al. 2008).
    CurveOnSurface {
        /// Surface: model file, optionally `:INDEX` (default 0). With `--face`: the STEP or
        /// IGES file whose B-rep faces are taken.
        #[arg(long)]
        surface: String,
        /// Domain curve: model file with a 2D curve, optionally `:INDEX` (default 0).
        #[arg(long, required_unless_present = "face", conflicts_with = "face")]
        curve: Option<String>,
        /// Instead of one domain curve: every edge of every loop of these B-rep faces of the
        /// `--surface` file — `all`, or a comma-separated list of indices and source ids
        /// (`#12`) — each edge's pcurve as the domain curve (the source's, a plane's, or one
        /// projected from the edge), reported with its proven distance to the edge. Exit 0
        /// when every edge is certified, 3 otherwise.
        #[arg(long, conflicts_with_all = ["svg", "vtk", "svg_3d"])]
        face: Option<String>,
        /// Distance tolerance ε_D (model units).
        #[arg(long, default_value_t = 1e-3, allow_hyphen_values = true)]
        tol: f64,
        /// Angle tolerance ε_T (degrees).
        #[arg(long, default_value_t = 10.0, allow_hyphen_values = true)]
        angle: f64,
        /// Lipschitz bound: `local` (tighter, proven) or `paper` (eq. 12 per patch).
        #[arg(long, default_value = "local")]
        bound: String,
        /// Run every step in exact rational arithmetic (the reference; slower) instead of
        /// f64 with interval enclosures (which reruns exactly by itself when undecided).
        #[arg(long)]
        exact: bool,
        /// Also measure the distance between the segments and the true image at N samples per
        /// segment, both ways (evidence, not proof; timed apart). Default: not measured.
        #[arg(long, value_name = "N", num_args = 0..=1, default_missing_value = "32")]
        evidence: Option<usize>,
        /// Write the JSON result here.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Write an SVG plot of the parameter domain here.
        #[arg(long)]
        svg: Option<PathBuf>,
        /// Write the result curve (126) and the surface (128) as IGES here.
        #[arg(long)]
        iges: Option<PathBuf>,
        /// Write the segments (with per-segment bound and certified flag) and the surface as
        /// VTK PolyData (.vtp) here.
        #[arg(long)]
        vtk: Option<PathBuf>,
        /// Write a 3D picture here (SVG): the surface shaded, the segments over it (green
        /// within ε_d by their proven bound, red above), their joints marked, with a legend
        /// and a scale.
        #[arg(long = "svg-3d")]
        svg_3d: Option<PathBuf>,
        /// The 3D picture's view direction: azimuth and elevation in degrees, as `AZ,EL`
        /// (orthographic; default -60,25).
        #[arg(long, allow_hyphen_values = true, default_value = "-60,25", value_parser = crate::io::picture::View::parse)]
        view: crate::io::picture::View,
        /// Memory budget in megabytes (10⁶ bytes) of heap: past it the job stops with
        /// `budget exhausted: memory ...` and exit code 1.
        #[arg(long, allow_hyphen_values = true)]
        max_memory: Option<f64>,
        /// Print the result as JSON instead of the human summary.
        #[arg(long)]
        json: bool,
    },
    /// Intersect surfaces (all face pairs of FILE, or faces of FILE against faces of FILE2;
    /// triangulations such as STL when the files hold no faces), with exactly traced topology
    /// and two proven figures per output point: its distance to each surface at its own
    /// parameters (dist_a, dist_b) and its distance to the intersection curve itself
    /// (curve_radius: a true common point lies within it; near tangency the first can be
    /// small while the second is large or unproven). Exit 0 certified, 3 finished but not
    /// certified, 2 bad input.
    Ssi {
        /// Model: native JSON, STEP, IGES, or STL (intersected as triangulations).
        file: PathBuf,
        /// Second model: every face of FILE against every face of FILE2 (omitted: all
        /// distinct face pairs of FILE).
        file2: Option<PathBuf>,
        /// Tolerance: refined points agree on both surfaces, and chords follow the true curve,
        /// within it (model units).
        #[arg(long, default_value_t = 1e-6, allow_hyphen_values = true)]
        tol: f64,
        /// Triangulation flatness (default: 0.2% of the pair's control-net diagonal).
        #[arg(long, allow_hyphen_values = true)]
        flatness: Option<f64>,
        /// Stop starting new work after this many seconds (the result is marked partial).
        #[arg(long, allow_hyphen_values = true)]
        time_limit: Option<f64>,
        /// Intersect the faces' whole surfaces, ignoring trim loops (IGES 144/142, JSON trim
        /// loops, STEP B-rep loops) and shared edges. By default the curves are restricted
        /// to the faces, and in a one-file run on a B-rep the intersection along edges two
        /// faces share is listed as shared edges, not as branches.
        #[arg(long)]
        untrimmed: bool,
        /// Worker threads (default: all cores; at most 1024). Results do not depend on it.
        #[arg(long, allow_hyphen_values = true)]
        threads: Option<usize>,
        /// Write the JSON result here.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Write branches, tangential points and faces as VTK PolyData (.vtp) here.
        #[arg(long)]
        vtk: Option<PathBuf>,
        /// Write the fitted cubic of every branch as IGES 126 curves here.
        #[arg(long)]
        iges: Option<PathBuf>,
        /// Write a picture here (SVG): the faces shaded, the branches over them coloured by
        /// what is proven (green within tol of the curve, amber above tol, red not proven),
        /// singular points and uncertified coverage regions marked, with a legend and a scale.
        #[arg(long)]
        svg: Option<PathBuf>,
        /// The picture's view direction: azimuth and elevation in degrees, as `AZ,EL`
        /// (orthographic; default -60,25).
        #[arg(long, allow_hyphen_values = true, default_value = "-60,25", value_parser = crate::io::picture::View::parse)]
        view: crate::io::picture::View,
        /// Keep every branch's fitted cubic (knots, control points in 3D and in both domains)
        /// in the JSON result; off by default (about four times the size of the points).
        #[arg(long)]
        fits: bool,
        /// Memory budget in megabytes (10⁶ bytes) of heap: past it the job stops with
        /// `budget exhausted: memory ...` and exit code 1.
        #[arg(long, allow_hyphen_values = true)]
        max_memory: Option<f64>,
        /// How each branch runs between its points: `chords` (split until every midpoint is
        /// within tol of the curve) or `cubic` (Hermite pieces with the curve's tangents at
        /// the ends, in `tangents`; split until each is within tol of the curve where
        /// measured): far fewer points, each certified as with chords.
        #[arg(long, default_value = "chords")]
        pieces: crate::ssi::Pieces,
        /// Skip the certificates: no curve radius per point and no coverage (a faster preview;
        /// the run is reported as not certified, exit 3). Distances to each surface are still
        /// bounded.
        #[arg(long)]
        no_certify: bool,
        /// Print the result as JSON instead of the human summary.
        #[arg(long)]
        json: bool,
    },
    /// Check another system's intersection curves between the faces of A and B (or, with B
    /// omitted, between every two distinct faces of A). Per curve point: proven bounds on its
    /// distance to each face set (global branch and bound, not a local search), and a proven
    /// radius to a true intersection point (Krawczyk test; tangent contacts are never
    /// accepted) whose parameters lie inside both faces' trim loops (points whose true curve
    /// point is outside a face are reported `outside_faces`). A vericad branch is reported missing only with a certified witness point
    /// far from every foreign curve. Exit 0 only when every curve is within tol of the
    /// intersection, no branch is missing, partial or unverified, and vericad's own coverage
    /// is certified; 3 otherwise.
    CertifySsi {
        /// Faces of the first model.
        a: PathBuf,
        /// Faces of the second model; omitted: one-file mode (every pair of distinct faces of
        /// A; points on edges shared by two faces are reported as such).
        b: Option<PathBuf>,
        /// Foreign curves: IGES/STEP/JSON model curves (e.g. IGES 126), JSON polylines
        /// (`[[[x,y,z],...],...]` or `{"curves": [...]}`), or a vericad `ssi` result.
        #[arg(long)]
        curves: PathBuf,
        #[arg(long, default_value_t = 1e-6, allow_hyphen_values = true)]
        tol: f64,
        /// A vericad branch point counts as found within this distance of a foreign curve
        /// (default 100 × tol).
        #[arg(long = "match", allow_hyphen_values = true)]
        match_distance: Option<f64>,
        /// Write the JSON verdict (per curve, per point, missing branches) here.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Memory budget in megabytes (10⁶ bytes) of heap: past it the job stops with
        /// `budget exhausted: memory ...` and exit code 1.
        #[arg(long, allow_hyphen_values = true)]
        max_memory: Option<f64>,
        /// Print the result as JSON instead of the human summary.
        #[arg(long)]
        json: bool,
    },
    /// Repair a faulty patch set (Uva, Monno & Hamann): connectivity with T-junction splits,
    /// edge verification, corner and boundary averaging, feature lines, group growing and
    /// merging of control nets, and a report (which lists what is left open and why).
    /// A B-rep with trimmed faces gets the faces repair instead: trims kept, free edges
    /// sewn within u1, gaps along shared edges (proven where the pcurves' bounds are) and
    /// feature edges reported (`--patches` forces the patch-set repair).
    Repair {
        /// Patch set: native JSON, STEP, IGES (faces as patches) or Plot3D.
        input: PathBuf,
        /// Repair the untrimmed surfaces as a patch set even where faces are trimmed (the
        /// trims are ignored, which the report says).
        #[arg(long, conflicts_with = "faces")]
        patches: bool,
        /// Repair the B-rep's faces (trims kept) even where every face is bounded by its
        /// surface's rectangle.
        #[arg(long)]
        faces: bool,
        /// Corner distance threshold (Algorithm 1).
        #[arg(long, default_value_t = 1e-3, allow_hyphen_values = true)]
        u1: f64,
        /// Largest gap along a shared edge.
        #[arg(long, default_value_t = 1e-3, allow_hyphen_values = true)]
        u2: f64,
        /// Normal angle above which a shared edge is a feature edge (degrees).
        #[arg(long, default_value_t = 30.0, allow_hyphen_values = true)]
        feature_angle: f64,
        /// Feature overrides: `{"add": [[patch, edge], ...], "remove": [...]}`.
        #[arg(long)]
        features: Option<PathBuf>,
        /// Repaired patches (format from the extension: .igs, .step, .json).
        #[arg(long)]
        out: Option<PathBuf>,
        /// JSON report.
        #[arg(long)]
        report: Option<PathBuf>,
        /// VTK view: patches, feature edges, gaps left.
        #[arg(long)]
        vtk: Option<PathBuf>,
        /// Write a picture here (SVG): the output patches shaded, one colour each, with the
        /// feature edges and the gaps left above u2 drawn over them, a legend and a scale.
        #[arg(long)]
        svg: Option<PathBuf>,
        /// The picture's view direction: azimuth and elevation in degrees, as `AZ,EL`
        /// (orthographic; default -60,25).
        #[arg(long, allow_hyphen_values = true, default_value = "-60,25", value_parser = crate::io::picture::View::parse)]
        view: crate::io::picture::View,
        /// Memory budget in megabytes (10⁶ bytes) of heap: past it the job stops with
        /// `budget exhausted: memory ...` and exit code 1.
        #[arg(long, allow_hyphen_values = true)]
        max_memory: Option<f64>,
        /// Print the result as JSON instead of the human summary.
        #[arg(long)]
        json: bool,
    },
    /// Reparametrize NURBS faces to chord length within a tolerance (RCA, Razdan): boundary
    /// points by arc length and curvature, reconciled opposite boundaries, relaxed interior
    /// points, a C2 bicubic, and parameter lines inserted until the measured E_max ≤ tol; a
    /// proven Hausdorff bound decides where it is ≤ tol, the measured E_max (evidence) elsewhere.
    /// Exit 0 when every face is within tol, 3 when some face is not.
    Reparam(reparam::ReparamArgs),
    /// Approximate faulty geometry by one bicubic C1 B-spline surface over four boundary
    /// curves (projected Coons patch, multiquadric gap filling; Hamann & Jean).
    Coons(coons::CoonsArgs),
    /// Many Coons approximants over a layout of curves; shared rows identical (checked).
    Approximate(approximate::ApproximateArgs),
    /// One job (info, ssi, repair) over many models: a JSONL record each, resumable, sharded.
    Batch(batch::BatchArgs),
    /// Print a shell completion script (bash, zsh, fish, elvish, powershell) for vericad.
    Completions(shell::CompletionsArgs),
    /// Print the man page, or write one page per command with `--out DIR`.
    Man(shell::ManArgs),
    /// Evaluate a surface at (u,v) or a curve at t, in f64 and exactly (Rational).
    Eval {
        /// Model file: native JSON, STEP or IGES.
        file: PathBuf,
        /// Index of the surface to evaluate (use with --uv).
        #[arg(long, conflicts_with = "curve")]
        surface: Option<usize>,
        /// Index of the curve to evaluate (use with --t).
        #[arg(long)]
        curve: Option<usize>,
        /// Surface parameters `u,v`.
        #[arg(long, value_delimiter = ',', allow_hyphen_values = true)]
        uv: Vec<f64>,
        /// Curve parameter.
        #[arg(long, allow_hyphen_values = true)]
        t: Option<f64>,
        /// Print the result as JSON instead of the human summary.
        #[arg(long)]
        json: bool,
    },
}
