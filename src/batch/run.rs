//! Running a job over models: the jobs, the parallel loop that isolates every model and
//! appends its record as it finishes, progress, and the closing summary.

use super::BatchError;
use super::record::{ErrorInfo, InfoFigures, Outcome, Record, RepairFigures, SsiFigures, Status};
use rayon::prelude::*;
use std::collections::BTreeMap;
use std::fmt;
use std::io::Write;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

/// The job run on every model.
#[derive(Clone, Debug)]
pub enum Job {
    /// Read the model and count what it holds.
    Info,
    /// Intersect all distinct face pairs of the model ([`crate::ssi::intersect_models`]).
    Ssi {
        tol: f64,
        /// Per-model limit in seconds: the run stops starting new pairs and is `timeout`.
        time_limit: Option<f64>,
    },
    /// Repair the model: its faces as one patch set ([`crate::repair::repair`]) or, by the
    /// mode ([`crate::repair::faces::job::faces_chosen`]), its B-rep's faces with their trims
    /// ([`crate::repair::faces::repair_faces`]).
    Repair(crate::repair::RepairParams, crate::repair::faces::job::Mode),
}

impl Job {
    /// Check the job's parameters before any model runs.
    pub fn validate(&self) -> Result<(), BatchError> {
        match self {
            Job::Info | Job::Repair(..) => Ok(()),
            Job::Ssi { .. } => self
                .ssi_params()
                .validate()
                .map_err(|e| BatchError::Argument(e.to_string())),
        }
    }

    fn ssi_params(&self) -> crate::ssi::SsiParams {
        let (tol, time_limit) = match self {
            Job::Ssi { tol, time_limit } => (*tol, *time_limit),
            _ => (crate::ssi::SsiParams::default().tol, None),
        };
        // The batch report counts branches; it holds no fit.
        crate::ssi::SsiParams {
            tol,
            time_limit,
            fits: false,
            ..Default::default()
        }
    }

    /// Run the job on one model. Every fault is returned as an outcome (a panic is not caught
    /// here but by [`execute`]).
    pub fn run(&self, path: &Path) -> Outcome {
        if !path.exists() {
            let msg = format!("{}: no such file or directory", path.display());
            return error(Status::BadInput, "read", msg);
        }
        let m = match crate::io::read_model(path) {
            Ok(m) => m,
            Err(e) => return error(Status::BadInput, "read", e),
        };
        match self {
            Job::Info => Outcome::Info(InfoFigures {
                faces: m.surfaces.len(),
                curves: m.curves.len(),
                triangulations: m.triangulations.len(),
                brep_faces: m.brep.as_ref().map(|b| b.faces.len()),
                brep_edges: m.brep.as_ref().map(|b| b.edges.len()),
                unit: m.unit.clone(),
                warnings: m.warnings.len(),
            }),
            Job::Ssi { .. } => {
                use crate::ssi::SsiError;
                match crate::ssi::intersect_models(&m, None, &self.ssi_params(), &|_, _| {}) {
                    Ok(r) => {
                        let s = &r.summary;
                        Outcome::Ssi(SsiFigures {
                            certified: s.certified,
                            partial: s.partial,
                            faces: s.faces_a,
                            pairs_intersected: s.pairs_intersected,
                            branches: s.branches,
                            points: s.points,
                            points_curve_uncertified: s.points_curve_uncertified,
                            uncertified_box_pairs: s.uncertified_box_pairs,
                            singular_points_uncertified: s.singular_points_uncertified,
                            pairs_not_run: s.pairs_not_run,
                            seconds: s.seconds,
                        })
                    }
                    Err(
                        e @ (SsiError::Topology(_)
                        | SsiError::InvalidMesh { .. }
                        | SsiError::MeshStopped),
                    ) => error(Status::Failed, "ssi", e),
                    Err(e) => error(Status::BadInput, "ssi", e),
                }
            }
            Job::Repair(prm, mode) => repair(&m, prm, *mode),
        }
    }
}

/// The `repair` job on the model `m`: the figures of the repair `mode` chooses.
fn repair(
    m: &crate::model::Model,
    prm: &crate::repair::RepairParams,
    mode: crate::repair::faces::job::Mode,
) -> Outcome {
    if crate::repair::faces::job::faces_chosen(m, mode) {
        return match crate::repair::faces::repair_faces(m, prm, &|_| {}) {
            Ok(r) => {
                let r = r.report;
                Outcome::Repair(RepairFigures {
                    mode: "faces".into(),
                    patches_in: r.faces,
                    patches_out: r.faces,
                    pairs_left: r.gaps_left.len(),
                    edges_connected: r.sewing.edges_sewn.len(),
                    gap_max_after: r.gap_max_proven.unwrap_or(r.gap_max_evidence),
                    gap_proven: Some(r.gap_max_proven.is_some()),
                    free_edges_after: Some(r.free_edges_after),
                    trims_ignored: 0,
                })
            }
            Err(e) => error(Status::BadInput, "repair", e),
        };
    }
    let patches = m.surfaces.iter().map(|s| s.nurbs.clone()).collect();
    let overrides = crate::repair::features::FeatureOverrides::default();
    match crate::repair::repair(patches, prm, &overrides, &|_| {}) {
        Ok(r) => Outcome::Repair(RepairFigures {
            mode: "patches".into(),
            patches_in: r.report.patches_in,
            patches_out: r.report.patches_out,
            pairs_left: r.report.gaps_left.len(),
            edges_connected: r.report.edges_connected,
            gap_max_after: r.report.gap_max_after,
            gap_proven: None,
            free_edges_after: None,
            trims_ignored: crate::repair::job::trims_ignored(m).len(),
        }),
        Err(e) => error(Status::BadInput, "repair", e),
    }
}

fn error(status: Status, kind: &str, e: impl fmt::Display) -> Outcome {
    Outcome::Error(
        status,
        ErrorInfo {
            message: e.to_string(),
            kind: kind.to_string(),
        },
    )
}

/// The text of a panic's payload.
fn panic_message(p: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = p.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = p.downcast_ref::<String>() {
        s.clone()
    } else {
        "panic with a non-text payload".to_string()
    }
}

/// The record of `job` on one model, as [`execute`] writes it: the job timed (`seconds`,
/// reading included) and a panic caught and turned into a `panic` record.
pub fn isolated_record(job: &(dyn Fn(&Path) -> Outcome + Sync), path: &Path) -> Record {
    let t = Instant::now();
    let outcome = catch_unwind(AssertUnwindSafe(|| job(path)))
        .unwrap_or_else(|payload| error(Status::Panic, "panic", panic_message(payload.as_ref())));
    Record::new(
        path.display().to_string(),
        t.elapsed().as_secs_f64(),
        outcome,
    )
}

impl Job {
    /// The record of this job on one model, exactly as a batch writes it (see
    /// [`isolated_record`]); for callers that schedule the models themselves.
    pub fn record(&self, path: &Path) -> Record {
        isolated_record(&|p: &Path| self.run(p), path)
    }
}

/// The records of one [`execute`] call.
#[derive(Clone, Debug)]
pub struct Executed {
    /// In the order they finished (and were written).
    pub records: Vec<Record>,
    /// Wall time of the whole call.
    pub seconds: f64,
}

struct Shared<W> {
    out: W,
    records: Vec<Record>,
    error: Option<String>,
    last_progress: Instant,
}

/// Run `job` on every model in parallel (`threads` workers, default all cores) and append each
/// model's record to `out` as one JSON line, flushed, as soon as it finishes. A panic in `job`
/// is caught and becomes a `panic` record; the other models go on. After a failed write no
/// further model starts, and the error is returned. Done/total, rate and ETA go to
/// `progress` at most once per second.
pub fn execute<W: Write + Send>(
    models: &[PathBuf],
    job: &(dyn Fn(&Path) -> Outcome + Sync),
    out: W,
    threads: Option<usize>,
    progress: crate::progress::Progress,
) -> Result<Executed, BatchError> {
    let t0 = Instant::now();
    let mut builder = rayon::ThreadPoolBuilder::new();
    if let Some(n) = threads {
        builder = builder.num_threads(n);
    }
    let pool = builder
        .build()
        .map_err(|e| BatchError::Argument(format!("thread pool: {e}")))?;
    let shared = Mutex::new(Shared {
        out,
        records: Vec::with_capacity(models.len()),
        error: None,
        last_progress: t0,
    });
    let stop = AtomicBool::new(false);
    let total = models.len();
    pool.install(|| {
        models.par_iter().with_max_len(1).for_each(|p| {
            if stop.load(Ordering::Relaxed) {
                return;
            }
            let r = isolated_record(job, p);
            // A poisoned lock only means another worker panicked while holding it, which the
            // writes below do not do; the data is still consistent.
            let mut s = shared.lock().unwrap_or_else(|e| e.into_inner());
            // One write per line: with an append-mode file the line lands whole.
            let written = r.to_line().map_err(|e| e.to_string()).and_then(|line| {
                s.out
                    .write_all(format!("{line}\n").as_bytes())
                    .and_then(|_| s.out.flush())
                    .map_err(|e| e.to_string())
            });
            if let Err(e) = written {
                stop.store(true, Ordering::Relaxed);
                s.error.get_or_insert(e);
                return;
            }
            s.records.push(r);
            let done = s.records.len();
            if progress.0.is_some()
                && (s.last_progress.elapsed().as_secs_f64() >= 1.0 || done == total)
            {
                s.last_progress = Instant::now();
                let el = t0.elapsed().as_secs_f64();
                let rate = done as f64 / el.max(1e-9);
                let eta = (total - done) as f64 / rate.max(1e-9);
                progress.say(|| {
                    format!("batch: {done}/{total} done, {rate:.2} models/s, ETA {eta:.0} s")
                });
            }
        });
    });
    let s = shared.into_inner().unwrap_or_else(|e| e.into_inner());
    if let Some(e) = s.error {
        return Err(BatchError::OutWrite("the output".into(), e));
    }
    Ok(Executed {
        records: s.records,
        seconds: t0.elapsed().as_secs_f64(),
    })
}

/// The end of a batch: counts by status over every model of the run (resumed records
/// included), the wall time of this run, and the slowest models.
#[derive(Clone, Debug)]
pub struct Summary {
    pub models: usize,
    /// Models whose records were already in the output.
    pub resumed: usize,
    pub counts: BTreeMap<Status, usize>,
    /// Wall time of this run (resumed models not included).
    pub seconds: f64,
    /// The five slowest models `(path, seconds)`, slowest first.
    pub slowest: Vec<(String, f64)>,
}

impl Summary {
    /// The summary of `resumed` records found in the output and `new` ones from this run.
    pub fn new(resumed: &[Record], new: &[Record], seconds: f64) -> Summary {
        let mut counts = BTreeMap::new();
        for r in resumed.iter().chain(new) {
            *counts.entry(r.status).or_insert(0) += 1;
        }
        let mut slowest: Vec<(String, f64)> = resumed
            .iter()
            .chain(new)
            .map(|r| (r.path.clone(), r.seconds))
            .collect();
        slowest.sort_by(|a, b| b.1.total_cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
        slowest.truncate(5);
        Summary {
            models: resumed.len() + new.len(),
            resumed: resumed.len(),
            counts,
            seconds,
            slowest,
        }
    }

    /// Models with `status`.
    pub fn count(&self, status: Status) -> usize {
        self.counts.get(&status).copied().unwrap_or(0)
    }

    /// Whether every model is `ok`.
    pub fn all_ok(&self) -> bool {
        self.count(Status::Ok) == self.models
    }
}

impl fmt::Display for Summary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "batch: {} models ({} from earlier records), {:.2} s",
            self.models, self.resumed, self.seconds
        )?;
        for s in Status::ALL {
            writeln!(f, "  {:<12} {:>6}", s.name(), self.count(s))?;
        }
        if !self.slowest.is_empty() {
            writeln!(f, "slowest:")?;
            for (p, t) in &self.slowest {
                writeln!(f, "  {t:>9.3} s  {p}")?;
            }
        }
        Ok(())
    }
}
