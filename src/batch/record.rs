//! One line of a batch's JSONL output: the model, its status, its figures or its error.

use serde::{Deserialize, Serialize};
use std::fmt;

/// How one model's job ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// The job finished and everything it reports holds (for `ssi`: certified).
    Ok,
    /// The job finished but not everything is proven (`ssi`: `certified` is false).
    Uncertified,
    /// The model could not be read or is not valid input for the job.
    BadInput,
    /// The computation itself failed (an internal check).
    Failed,
    /// The per-model time limit stopped the job; the figures are those of a partial run.
    Timeout,
    /// The job panicked; the panic was caught and the batch went on.
    Panic,
}

impl Status {
    /// Every status, in the order of the summary table.
    pub const ALL: [Status; 6] = [
        Status::Ok,
        Status::Uncertified,
        Status::Timeout,
        Status::BadInput,
        Status::Failed,
        Status::Panic,
    ];

    /// The name used in the records (`bad_input`, ...).
    pub fn name(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Uncertified => "uncertified",
            Status::BadInput => "bad_input",
            Status::Failed => "failed",
            Status::Timeout => "timeout",
            Status::Panic => "panic",
        }
    }
}

impl fmt::Display for Status {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Why a model has no figures.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ErrorInfo {
    /// The error as the reader or the pipeline gives it (with entity ids, JSON paths or line
    /// numbers where the reader has them).
    pub message: String,
    /// Where it came from: `read` (the file reader), `ssi`, `repair`, or `panic`.
    pub kind: String,
}

/// `--job info`: what the model holds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct InfoFigures {
    /// Faces (surfaces) of the model.
    pub faces: usize,
    pub curves: usize,
    pub triangulations: usize,
    /// Faces and distinct edges of the B-rep, when the file has topology.
    pub brep_faces: Option<usize>,
    pub brep_edges: Option<usize>,
    pub unit: Option<String>,
    /// Reader warnings (what was skipped or approximated).
    pub warnings: usize,
}

/// `--job ssi`: the one-file intersection's summary.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SsiFigures {
    /// Everything the run reports is proven (see the `ssi` command).
    pub certified: bool,
    /// The time limit stopped the run before every face pair was intersected.
    pub partial: bool,
    pub faces: usize,
    pub pairs_intersected: usize,
    pub branches: usize,
    pub points: usize,
    /// Points without a proven distance to the intersection curve.
    pub points_curve_uncertified: usize,
    /// Box pairs neither proven free nor loop-free.
    pub uncertified_box_pairs: usize,
    pub singular_points_uncertified: usize,
    pub pairs_not_run: usize,
    /// The intersection's own time (the record's `seconds` includes reading the file).
    pub seconds: f64,
}

/// `--job repair`: the repair report's headline figures.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RepairFigures {
    /// Which repair ran: `patches` (the paper's patch-set repair on the untrimmed surfaces)
    /// or `faces` (the B-rep's faces with their trims; then patches in and out are the faces).
    #[serde(default = "patches")]
    pub mode: String,
    pub patches_in: usize,
    pub patches_out: usize,
    /// Patches: candidate edge pairs left disconnected (gap of at least u2). Faces: shared
    /// edges whose gap (proven, else evidence) is at least u2.
    pub pairs_left: usize,
    /// Patches: edges connected. Faces: free edges sewn into shared ones.
    pub edges_connected: usize,
    /// The largest gap after the repair (faces: proven when `gap_proven`, else evidence).
    pub gap_max_after: f64,
    /// Faces: whether `gap_max_after` is a proven bound (every shared edge has one).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub gap_proven: Option<bool>,
    /// Faces: edges still used by one face.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub free_edges_after: Option<usize>,
    /// Trimmed faces whose trims the patch-set repair ignored (it works on the untrimmed
    /// surfaces; `vericad repair` repairs such models' faces instead).
    #[serde(default)]
    pub trims_ignored: usize,
}

fn patches() -> String {
    "patches".into()
}

/// One model's line in the output.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Record {
    /// The model's path as the batch found it (the key for resuming).
    pub path: String,
    pub status: Status,
    /// Wall time of the job on this model, reading included.
    pub seconds: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub info: Option<InfoFigures>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ssi: Option<SsiFigures>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub repair: Option<RepairFigures>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<ErrorInfo>,
}

/// A job's outcome on one model, before timing and path are attached.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    Info(InfoFigures),
    /// Status `ok`, `uncertified` or `timeout` from the figures.
    Ssi(SsiFigures),
    Repair(RepairFigures),
    /// A typed error: status `bad_input` or `failed`.
    Error(Status, ErrorInfo),
}

impl Record {
    /// The record of `outcome` on the model at `path`.
    pub fn new(path: String, seconds: f64, outcome: Outcome) -> Record {
        let mut r = Record {
            path,
            status: Status::Ok,
            seconds,
            info: None,
            ssi: None,
            repair: None,
            error: None,
        };
        match outcome {
            Outcome::Info(f) => r.info = Some(f),
            Outcome::Ssi(f) => {
                r.status = if f.partial {
                    Status::Timeout
                } else if f.certified {
                    Status::Ok
                } else {
                    Status::Uncertified
                };
                r.ssi = Some(f);
            }
            Outcome::Repair(f) => r.repair = Some(f),
            Outcome::Error(s, e) => {
                r.status = s;
                r.error = Some(e);
            }
        }
        r
    }

    /// The record as one JSON line (without the newline).
    pub fn to_line(&self) -> Result<String, serde_json::Error> {
        serde_json::to_string(self)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_round_trips_through_its_line() {
        let r = Record::new(
            "a.step".into(),
            0.5,
            Outcome::Error(
                Status::BadInput,
                ErrorInfo {
                    message: "#12: bad".into(),
                    kind: "read".into(),
                },
            ),
        );
        let line = r.to_line().unwrap();
        assert!(line.contains("\"status\":\"bad_input\""), "{line}");
        assert!(!line.contains('\n'));
        let back: Record = serde_json::from_str(&line).unwrap();
        assert_eq!(back, r);
    }
}
