//! What a reader did with each topology and edge-geometry entity: read and converted,
//! recognised but unsupported, or invalid — counted per entity type with the ids — and the
//! topology faults found, each naming the face and the entity.

use std::collections::BTreeMap;

/// How one entity type fared.
#[derive(Clone, Debug, PartialEq, Default, serde::Serialize)]
pub struct Tally {
    /// Instances read and converted.
    pub converted: usize,
    /// Instances recognised but not converted (ids).
    pub unsupported: Vec<String>,
    /// Instances refused as malformed (ids); the reason is in an issue.
    pub invalid: Vec<String>,
    /// Instances no face, shell or solid reaches (ids): not part of the B-rep.
    pub not_read: Vec<String>,
}

/// A fault of the topology or of an edge's geometry.
#[derive(Clone, Debug, PartialEq, thiserror::Error, serde::Serialize)]
pub enum IssueKind {
    #[error("reference to a missing instance {to}")]
    DanglingReference { to: String },
    #[error("{attribute} is {found}, expected {expected}")]
    WrongType {
        attribute: String,
        expected: String,
        found: String,
    },
    #[error("malformed: {0}")]
    Malformed(String),
    #[error(
        "loop is open: oriented edge {position} ends at vertex {end} but the next begins at vertex {next}"
    )]
    OpenLoop {
        position: usize,
        end: String,
        next: String,
    },
    #[error("edge loop has no edges")]
    EmptyLoop,
    #[error("face has no bounds")]
    NoBounds,
    #[error("{count} bounds are declared outer (FACE_OUTER_BOUND)")]
    SeveralOuterBounds { count: usize },
    #[error("curve of type {0} is not supported; the edge has no 3D curve")]
    UnsupportedCurve(String),
    #[error("parameter-space curve of type {0} is not supported; the edge keeps its 3D curve")]
    UnsupportedPCurve(String),
    #[error("surface of type {0} is not supported; the face has no surface")]
    UnsupportedSurface(String),
    #[error("surface is invalid ({0}); the face was skipped (--skip-invalid) and has no surface")]
    InvalidSurface(String),
    #[error("references nest deeper than {0} levels (a cycle?)")]
    TooDeep(usize),
    #[error("vertex lies {distance:e} from the curve end it bounds (tolerance {tolerance:e})")]
    VertexOffCurve { distance: f64, tolerance: f64 },
    #[error("edge is used {uses} times in shell {shell} (a closed shell uses each edge twice)")]
    EdgeUse { shell: String, uses: usize },
}

/// One fault: the entity it is about, the face it belongs to (when it belongs to one), why.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct TopologyIssue {
    /// Source id of the faulty entity, e.g. `"#57"`.
    pub entity: String,
    /// Source id of the face whose boundary holds it, if any.
    pub face: Option<String>,
    pub kind: IssueKind,
}

impl std::fmt::Display for TopologyIssue {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match &self.face {
            Some(face) if *face != self.entity => {
                write!(f, "face {face}: {}: {}", self.entity, self.kind)
            }
            _ => write!(f, "{}: {}", self.entity, self.kind),
        }
    }
}

/// The reader's account of the topology.
#[derive(Clone, Debug, PartialEq, Default, serde::Serialize)]
pub struct BrepReport {
    /// By entity type name (the source's, e.g. `EDGE_CURVE`).
    pub entities: BTreeMap<String, Tally>,
    pub issues: Vec<TopologyIssue>,
}

impl BrepReport {
    fn tally(&mut self, ty: &str) -> &mut Tally {
        self.entities.entry(ty.to_string()).or_default()
    }
    /// Count one converted instance of `ty`.
    pub fn converted(&mut self, ty: &str) {
        self.tally(ty).converted += 1;
    }
    /// Record an unsupported instance.
    pub fn unsupported(&mut self, ty: &str, id: &str) {
        self.tally(ty).unsupported.push(id.to_string());
    }
    /// Record an invalid instance and why.
    pub fn invalid(&mut self, ty: &str, id: &str, face: Option<&str>, kind: IssueKind) {
        self.tally(ty).invalid.push(id.to_string());
        self.issue(id, face, kind);
    }
    /// Record a fault that does not make an instance invalid by itself.
    pub fn issue(&mut self, id: &str, face: Option<&str>, kind: IssueKind) {
        self.issues.push(TopologyIssue {
            entity: id.to_string(),
            face: face.map(str::to_string),
            kind,
        });
    }
    /// One line per entity type with something not converted.
    pub fn summary_lines(&self) -> Vec<String> {
        let mut out = Vec::new();
        for (ty, t) in &self.entities {
            if !t.unsupported.is_empty() {
                out.push(format!(
                    "{} {ty} not supported: {}",
                    t.unsupported.len(),
                    crate::model::list_ids(t.unsupported.iter().cloned())
                ));
            }
            if !t.not_read.is_empty() {
                out.push(format!(
                    "{} {ty} not read (no face, shell or solid uses them): {}",
                    t.not_read.len(),
                    crate::model::list_ids(t.not_read.iter().cloned())
                ));
            }
            if !t.invalid.is_empty() {
                out.push(format!(
                    "{} {ty} invalid: {}",
                    t.invalid.len(),
                    crate::model::list_ids(t.invalid.iter().cloned())
                ));
            }
        }
        out
    }

    /// The lines a reader adds to the model's warnings: [`Self::summary_lines`], then one line
    /// per topology issue up to [`MAX_LISTED_ISSUES`] and a count of the rest (all stay in the
    /// report).
    pub fn warning_lines(&self) -> Vec<String> {
        let mut out = self.summary_lines();
        let n = self.issues.len();
        for i in self.issues.iter().take(MAX_LISTED_ISSUES) {
            out.push(format!("topology: {i}"));
        }
        if n > MAX_LISTED_ISSUES {
            out.push(format!(
                "topology: {} more issue(s) in the B-rep report",
                n - MAX_LISTED_ISSUES
            ));
        }
        out
    }
}

/// Topology issues listed one per warning; the rest are counted (all are in the B-rep report).
pub const MAX_LISTED_ISSUES: usize = 50;
