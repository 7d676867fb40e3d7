//! Batch runs: one job (`info`, `ssi`, `repair`) over many model files, one JSON record per
//! model (docs/batch.md).
//!
//! This module finds the models ([`discover`]), takes a shard of them ([`shard`]), skips the
//! ones the output already has records for ([`read_done`]), and hands the rest to
//! [`run::execute`], which runs them in parallel, isolates every model (errors and panics
//! become records) and appends each record as it finishes. The batch layer sits beside the
//! command line on top of the pipelines: it calls their library entry points only.

pub mod record;
pub mod run;

pub use record::{Outcome, Record, Status};
pub use run::{Job, Summary};

use std::collections::HashSet;
use std::io::{Seek, SeekFrom};
use std::path::{Path, PathBuf};

/// File extensions (case-insensitive) taken as models when a directory is searched.
pub const MODEL_EXTENSIONS: [&str; 6] = ["step", "stp", "igs", "iges", "json", "stl"];

/// A fault that stops a batch before or while it runs (never a fault of one model).
#[derive(Debug, thiserror::Error)]
pub enum BatchError {
    #[error("{0}: cannot read the list of inputs: {1}")]
    Manifest(String, String),
    #[error("{0}: cannot read the directory: {1}")]
    Directory(String, String),
    #[error("{0}: cannot read the existing records: {1}")]
    OutRead(String, String),
    #[error("{0}: line {1} is not a batch record: {2}")]
    OutRecord(String, usize, String),
    #[error("cannot write the records to {0}: {1}")]
    OutWrite(String, String),
    #[error("{0}")]
    Argument(String),
}

impl BatchError {
    /// Bad arguments or an unreadable inputs list or output (exit code 2), as opposed to a
    /// failure to write the records (1).
    pub fn is_bad_input(&self) -> bool {
        !matches!(self, BatchError::OutWrite(..))
    }
}

/// Whether `p` has one of the [`MODEL_EXTENSIONS`].
pub fn is_model_file(p: &Path) -> bool {
    p.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| MODEL_EXTENSIONS.contains(&e.to_ascii_lowercase().as_str()))
}

fn walk(dir: &Path, out: &mut Vec<PathBuf>) -> Result<(), BatchError> {
    let err = |e: std::io::Error| BatchError::Directory(dir.display().to_string(), e.to_string());
    let mut entries = Vec::new();
    for e in std::fs::read_dir(dir).map_err(err)? {
        entries.push(e.map_err(err)?.path());
    }
    for p in entries {
        if p.is_dir() {
            walk(&p, out)?;
        } else if is_model_file(&p) {
            out.push(p);
        }
    }
    Ok(())
}

fn add_input(p: &Path, out: &mut Vec<PathBuf>) -> Result<(), BatchError> {
    if p.is_dir() {
        walk(p, out)
    } else {
        // A file named explicitly is a model whatever its name: a missing or unreadable one
        // becomes a `bad_input` record, not the end of the batch.
        out.push(p.to_path_buf());
        Ok(())
    }
}

/// The models named by `inputs`, sorted and without repeats: a directory stands for the model
/// files under it (recursively, by [`MODEL_EXTENSIONS`]), `@FILE` for the paths listed in FILE
/// (one per line; blank lines and lines starting with `#` are skipped; relative paths are
/// relative to FILE's directory; a listed directory is searched too), and anything else for
/// itself.
pub fn discover(inputs: &[String]) -> Result<Vec<PathBuf>, BatchError> {
    let mut out = Vec::new();
    for i in inputs {
        if let Some(list) = i.strip_prefix('@') {
            let text = std::fs::read_to_string(list)
                .map_err(|e| BatchError::Manifest(list.to_string(), e.to_string()))?;
            let base = Path::new(list).parent().unwrap_or(Path::new(""));
            for line in text.lines().map(str::trim) {
                if line.is_empty() || line.starts_with('#') {
                    continue;
                }
                add_input(&base.join(line), &mut out)?;
            }
        } else {
            add_input(Path::new(i), &mut out)?;
        }
    }
    out.sort();
    out.dedup();
    Ok(out)
}

/// Shard `i` of `n`: the models whose index in `models` (sorted) is `i` modulo `n`. The `n`
/// shards partition the list.
pub fn shard(models: Vec<PathBuf>, i: usize, n: usize) -> Vec<PathBuf> {
    models
        .into_iter()
        .enumerate()
        .filter(|(k, _)| n > 0 && k % n == i)
        .map(|(_, p)| p)
        .collect()
}

/// Parse `--shard I/N` (0 ≤ I < N).
pub fn parse_shard(s: &str) -> Result<(usize, usize), BatchError> {
    let bad = || BatchError::Argument(format!("--shard must be I/N with 0 <= I < N, not `{s}`"));
    let (a, b) = s.split_once('/').ok_or_else(bad)?;
    let i: usize = a.trim().parse().map_err(|_| bad())?;
    let n: usize = b.trim().parse().map_err(|_| bad())?;
    if n == 0 || i >= n {
        return Err(bad());
    }
    Ok((i, n))
}

/// The records already in `out` (none when it does not exist). A last line cut short (a run
/// killed while writing it) is removed from the file so that appending starts on a fresh
/// line; its model runs again. Any other line that is not a record is an error.
pub fn read_done(out: &Path) -> Result<Vec<Record>, BatchError> {
    let name = || out.display().to_string();
    let text = match std::fs::read(out) {
        Ok(t) => t,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(BatchError::OutRead(name(), e.to_string())),
    };
    let complete = match text.iter().rposition(|&b| b == b'\n') {
        Some(k) => k + 1,
        None => 0,
    };
    if complete < text.len() {
        let f = std::fs::OpenOptions::new()
            .write(true)
            .open(out)
            .map_err(|e| BatchError::OutWrite(name(), e.to_string()))?;
        f.set_len(complete as u64)
            .map_err(|e| BatchError::OutWrite(name(), e.to_string()))?;
    }
    let text = String::from_utf8_lossy(&text[..complete]);
    let mut records = Vec::new();
    for (k, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            continue;
        }
        let r: Record = serde_json::from_str(line)
            .map_err(|e| BatchError::OutRecord(name(), k + 1, e.to_string()))?;
        records.push(r);
    }
    Ok(records)
}

/// What a batch runs on and where its records go.
#[derive(Clone, Debug)]
pub struct Options {
    /// Directories, files and `@FILE` lists (see [`discover`]).
    pub inputs: Vec<String>,
    pub job: Job,
    /// The JSONL output: appended to, and read first to skip models it has records for.
    pub out: PathBuf,
    /// `(i, n)`: run shard i of n.
    pub shard: Option<(usize, usize)>,
    /// Worker threads (default: all cores).
    pub threads: Option<usize>,
    /// Where progress lines go (at most once per second; default: nowhere).
    pub progress: crate::progress::Progress,
}

/// Run a batch: discover, shard, skip what `out` already holds, run the rest (each record
/// appended as it finishes). The summary covers every model of the shard, those whose
/// records were already in `out` included, so a resumed run ends with the same summary
/// counts as an uninterrupted one.
pub fn run(opts: &Options) -> Result<Summary, BatchError> {
    opts.job.validate()?;
    let mut models = discover(&opts.inputs)?;
    if let Some((i, n)) = opts.shard {
        models = shard(models, i, n);
    }
    let existing = read_done(&opts.out)?;
    let wanted: HashSet<String> = models.iter().map(|p| p.display().to_string()).collect();
    let mut done: Vec<Record> = Vec::new();
    let mut seen = HashSet::new();
    for r in existing {
        if wanted.contains(&r.path) && seen.insert(r.path.clone()) {
            done.push(r);
        }
    }
    let todo: Vec<PathBuf> = models
        .into_iter()
        .filter(|p| !seen.contains(&p.display().to_string()))
        .collect();
    let mut file = std::fs::OpenOptions::new()
        .create(true)
        .append(true)
        .open(&opts.out)
        .map_err(|e| BatchError::OutWrite(opts.out.display().to_string(), e.to_string()))?;
    file.seek(SeekFrom::End(0))
        .map_err(|e| BatchError::OutWrite(opts.out.display().to_string(), e.to_string()))?;
    let job = opts.job.clone();
    let new = run::execute(
        &todo,
        &|p: &Path| job.run(p),
        file,
        opts.threads,
        opts.progress,
    )
    .map_err(|e| match e {
        BatchError::OutWrite(_, m) => BatchError::OutWrite(opts.out.display().to_string(), m),
        e => e,
    })?;
    Ok(Summary::new(&done, &new.records, new.seconds))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_list() {
        let all: Vec<PathBuf> = (0..7)
            .map(|k| PathBuf::from(format!("m{k}.json")))
            .collect();
        let mut union: Vec<PathBuf> = (0..3).flat_map(|i| shard(all.clone(), i, 3)).collect();
        union.sort();
        assert_eq!(union, all);
        assert_eq!(shard(all.clone(), 1, 3).len(), 2);
    }

    #[test]
    fn shard_arguments_are_checked() {
        assert_eq!(parse_shard("1/2").unwrap(), (1, 2));
        for bad in ["2/2", "0/0", "-1/2", "1", "a/b"] {
            assert!(parse_shard(bad).is_err(), "{bad}");
        }
    }
}
