//! Command-line interface: parses arguments, calls one library job, prints its report.
//! Exit codes: 0 success (for `ssi` and `certify-ssi`: everything reported is proven),
//! 3 finished but not certified (uncertified regions, points or curves not within tol,
//! uncertified singular points, missing branches, partial run), 2 bad input (unreadable or invalid file, bad arguments),
//! 1 failure of the computation or of writing outputs (a computation budget exhausted
//! included: `--max-memory`, see [`memory`]).

pub mod approximate;
pub mod batch;
mod convert;
pub mod coons;
pub mod memory;
mod output;
pub mod reparam;
pub mod shell;
pub use memory::set_memory_probe;

use clap::{Parser, Subcommand};
use output::{bad, finish, finish_checked, print};
use std::path::PathBuf;

/// Exit code for bad input.
pub const EXIT_BAD_INPUT: i32 = 2;
/// Exit code for a failed computation or output.
pub const EXIT_FAILURE: i32 = 1;
/// The run finished but not everything it reports is proven: `ssi` with uncertified
/// coverage regions, points not proven within tol, singular points of unproven kind, or a
/// partial run; `certify-ssi` with
/// foreign curves not within tol, or vericad branches missing or partly missing from them.
pub const EXIT_UNCERTIFIED: i32 = 3;
/// Largest `--threads` accepted (each worker has its own stack).
pub const MAX_THREADS: usize = 1024;

#[derive(Parser, Debug)]
#[command(
    name = "vericad",
    version,
    about = "Verification-first CAGD for surface grid generation: exact predicates, certified curves on surfaces, SSI, repair."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
    /// Indent every JSON value in written files and `--json` output (by default arrays of
    /// numbers, such as points, stay on one line).
    #[arg(long, global = true)]
    pub pretty: bool,
    /// Read STEP and IGES files whose faces are partly invalid (non-finite or malformed
    /// surface or trims) by skipping those faces, each counted `invalid` with its id and
    /// reason in the accounts and named in a warning (by default such a file is refused).
    #[arg(long, global = true)]
    pub skip_invalid: bool,
}

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
        /// Output format, overriding the extension: json, step, iges, stl, stl-binary, vtp, obj.
        #[arg(long)]
        format: Option<String>,
        #[command(flatten)]
        memory: memory::MemoryArg,
    },
    /// Approximate the image of a domain curve on a B-spline surface by Bézier curves of degree
    /// p+q lying exactly on it, with a proven Hausdorff bound (Yang et al. 2008).
    CurveOnSurface {
        /// Surface: model file, optionally `:INDEX` (default 0).
        #[arg(long)]
        surface: String,
        /// Domain curve: model file with a 2D curve, optionally `:INDEX` (default 0).
        #[arg(long)]
        curve: String,
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
    /// accepted). A vericad branch is reported missing only with a certified witness point
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
    Repair {
        /// Patch set: native JSON, STEP, IGES (faces as patches) or Plot3D.
        input: PathBuf,
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
    /// Evaluate a surface at (u,v) or a curve at t, in f64 and exactly (BigRational).
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

/// Run a parsed command; returns the process exit code.
pub fn run(cli: Cli) -> i32 {
    crate::io::json_text::set_pretty(cli.pretty);
    crate::io::set_skip_invalid_faces(cli.skip_invalid);
    match cli.command {
        Command::Demo { out, json } => match crate::demo::run(crate::demo::DEFAULT_MODEL, &out) {
            Ok(r) => {
                print(&r, json);
                0
            }
            Err(e) => {
                eprintln!("error: {e}");
                EXIT_FAILURE
            }
        },
        Command::CurveOnSurface {
            surface,
            curve,
            tol,
            angle,
            bound,
            exact,
            evidence,
            out,
            svg,
            iges,
            vtk,
            svg_3d,
            view,
            max_memory,
            json,
        } => {
            use crate::curve_on_surface::{Arithmetic, Bound, Params, job};
            let Some(bound) = Bound::from_name(&bound) else {
                return bad(format!("--bound must be `local` or `paper`, not `{bound}`"));
            };
            let params = Params {
                eps_d: tol,
                eps_t_deg: angle,
                bound,
                arithmetic: if exact {
                    Arithmetic::Exact
                } else {
                    Arithmetic::Float
                },
                evidence_samples: evidence.unwrap_or(0),
                ..Params::default()
            };
            let outputs = job::Outputs {
                json: out.as_deref(),
                svg: svg.as_deref(),
                iges: iges.as_deref(),
                vtk: vtk.as_deref(),
                svg_3d: svg_3d.as_deref(),
                view,
            };
            let memory = match memory::budget(max_memory) {
                Ok(m) => m,
                Err(e) => return bad(e),
            };
            memory::watch(&memory, "curve-on-surface");
            finish(job::run(&surface, &curve, &params, outputs), json, |e| {
                e.is_bad_input()
            })
        }
        Command::Ssi {
            file,
            file2,
            tol,
            flatness,
            time_limit,
            untrimmed,
            threads,
            out,
            vtk,
            iges,
            svg,
            view,
            fits,
            max_memory,
            no_certify,
            json,
        } => {
            use crate::ssi::job;
            if let Some(n) = threads
                && !(1..=MAX_THREADS).contains(&n)
            {
                return bad(format!("--threads must be in 1..={MAX_THREADS}, not {n}"));
            }
            let memory = match memory::budget(max_memory) {
                Ok(m) => m,
                Err(e) => return bad(e),
            };
            let prm = crate::ssi::SsiParams {
                tol,
                flatness,
                time_limit,
                respect_trims: !untrimmed,
                certify: !no_certify,
                control: crate::ssi::control::Control {
                    memory: memory.clone(),
                    ..Default::default()
                },
                ..Default::default()
            };
            let outputs = job::Outputs {
                json: out.as_deref(),
                vtk: vtk.as_deref(),
                iges: iges.as_deref(),
                fits,
                svg: svg.as_deref(),
                view,
            };
            let r = job::run(&file, file2.as_deref(), &prm, threads, outputs);
            if let Some(code) = memory::exhausted(&memory) {
                return code;
            }
            finish_checked(r, json, |r| r.summary.certified, |e| e.is_bad_input())
        }
        Command::CertifySsi {
            a,
            b,
            curves,
            tol,
            match_distance,
            out,
            max_memory,
            json,
        } => {
            let memory = match memory::budget(max_memory) {
                Ok(m) => m,
                Err(e) => return bad(e),
            };
            let prm = crate::ssi::SsiParams {
                tol,
                control: crate::ssi::control::Control {
                    memory: memory.clone(),
                    ..Default::default()
                },
                ..Default::default()
            };
            let r = crate::ssi::job::run_certify(
                &a,
                b.as_deref(),
                &curves,
                &prm,
                match_distance,
                out.as_deref(),
            );
            if let Some(code) = memory::exhausted(&memory) {
                return code;
            }
            finish_checked(r, json, |r| r.certified, |e| e.is_bad_input())
        }
        Command::Repair {
            input,
            u1,
            u2,
            feature_angle,
            features,
            out,
            report,
            vtk,
            svg,
            view,
            max_memory,
            json,
        } => {
            let prm = crate::repair::RepairParams {
                u1,
                u2,
                feature_angle_deg: feature_angle,
                ..Default::default()
            };
            let memory = match memory::budget(max_memory) {
                Ok(m) => m,
                Err(e) => return bad(e),
            };
            memory::watch(&memory, "repair");
            let outputs = crate::repair::job::Outputs {
                model: out.as_deref(),
                report: report.as_deref(),
                vtk: vtk.as_deref(),
                svg: svg.as_deref(),
                view,
            };
            finish(
                crate::repair::job::run(&input, &prm, features.as_deref(), outputs),
                json,
                |e| e.is_bad_input(),
            )
        }
        Command::Reparam(args) => reparam::run(args),
        Command::Convert {
            input,
            output,
            format,
            memory,
        } => convert::run(&input, &output, format.as_deref(), &memory),
        Command::Coons(args) => coons::run(args),
        Command::Approximate(args) => approximate::run(args),
        Command::Batch(args) => batch::run(args),
        Command::Completions(args) => shell::completions(args),
        Command::Man(args) => shell::man(args),
        Command::Info { file, memory, json } => {
            if let Err(e) = memory.watch("info") {
                return bad(e);
            }
            match crate::io::read_model(&file) {
                Ok(m) => {
                    let mut info = crate::model::info::summarize(&m);
                    if let Some(b) = &m.brep {
                        info.face_areas = crate::tessellate::face_areas(&m, b);
                    }
                    print(&info, json);
                    0
                }
                Err(e) => bad(e),
            }
        }
        Command::Eval {
            file,
            surface,
            curve,
            uv,
            t,
            json,
        } => {
            let m = match crate::io::read_model(&file) {
                Ok(m) => m,
                Err(e) => return bad(e),
            };
            let r = match (surface, curve) {
                (Some(i), None) => crate::model::eval::eval_surface(&m, i, &uv),
                (None, Some(i)) => match t {
                    Some(t) => crate::model::eval::eval_curve(&m, i, &[t]),
                    None => return bad("--curve needs --t"),
                },
                _ => return bad("give either --surface I --uv U,V or --curve I --t T"),
            };
            match r {
                Ok(r) => {
                    print(&r, json);
                    0
                }
                Err(e) => bad(e),
            }
        }
    }
}
