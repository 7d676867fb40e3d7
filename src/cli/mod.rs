//! Command-line interface: parses arguments, calls one library job, prints its report.
//! Exit codes: 0 success (for `ssi` and `certify-ssi`: everything reported is proven),
//! 3 finished but not certified (uncertified regions, points or curves not within tol,
//! uncertified singular points, missing branches, partial run), 2 bad input (unreadable or invalid file, bad arguments),
//! 1 failure of the computation or of writing outputs (a computation budget exhausted
//! included: `--max-memory`, see [`memory`]).

pub mod approximate;
pub mod batch;
mod commands;
mod convert;
pub mod coons;
pub mod memory;
mod output;
pub mod reparam;
pub mod shell;
pub use commands::Command;
pub use memory::set_memory_probe;

use clap::Parser;
use output::{bad, finish, finish_checked, print};

/// Exit code for bad input.
pub const EXIT_BAD_INPUT: i32 = 2;
/// Exit code for a failed computation or output.
pub const EXIT_FAILURE: i32 = 1;
/// The run finished but not everything it reports is proven: `ssi` with uncertified
/// coverage regions, points not proven within tol, singular points of unproven kind, or a
/// partial run; `certify-ssi` with
/// foreign curves not within tol, or vericad branches missing or partly missing from them.
pub const EXIT_UNCERTIFIED: i32 = 3;
pub use crate::budget::MAX_THREADS;

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
            face,
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
            use crate::curve_on_surface::{Bound, Params, job};
            let Some(bound) = Bound::from_name(&bound) else {
                return bad(format!("--bound must be `local` or `paper`, not `{bound}`"));
            };
            let params = Params::from_options(tol, angle, bound, exact, evidence.unwrap_or(0));
            let outputs = job::Outputs {
                progress: crate::progress::Progress::stderr(),
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
            match (face, curve) {
                (Some(face), _) => finish_checked(
                    crate::curve_on_surface::face_job::run(
                        &surface,
                        &face,
                        &params,
                        (out.as_deref(), iges.as_deref()),
                        crate::progress::Progress::stderr(),
                    ),
                    json,
                    |r| r.all_certified(),
                    |e| e.is_bad_input(),
                ),
                (None, Some(curve)) => {
                    finish(job::run(&surface, &curve, &params, outputs), json, |e| {
                        e.is_bad_input()
                    })
                }
                (None, None) => bad("give --curve or --face"),
            }
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
            pieces,
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
                pieces,
                control: crate::ssi::control::Control {
                    memory: memory.clone(),
                    ..Default::default()
                },
                ..Default::default()
            };
            let outputs = job::Outputs {
                progress: crate::progress::Progress::stderr(),
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
                (out.as_deref(), crate::progress::Progress::stderr()),
            );
            if let Some(code) = memory::exhausted(&memory) {
                return code;
            }
            finish_checked(r, json, |r| r.certified, |e| e.is_bad_input())
        }
        Command::Repair {
            input,
            patches,
            faces,
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
                progress: crate::progress::Progress::stderr(),
                model: out.as_deref(),
                report: report.as_deref(),
                vtk: vtk.as_deref(),
                svg: svg.as_deref(),
                view,
            };
            use crate::repair::faces::job::{Mode, run};
            let mode = match (patches, faces) {
                (true, _) => Mode::Patches,
                (_, true) => Mode::Faces,
                _ => Mode::Auto,
            };
            finish(
                run(&input, &prm, features.as_deref(), outputs, mode).map(|r| r.report()),
                json,
                |e| e.is_bad_input(),
            )
        }
        Command::Reparam(args) => reparam::run(args),
        Command::Convert {
            input,
            output,
            format,
            chordal,
            prove_chordal,
            memory,
        } => convert::run(
            &input,
            &output,
            format.as_deref(),
            (chordal, prove_chordal),
            &memory,
        ),
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
                    print(&crate::tessellate::model_info(&m), json);
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
