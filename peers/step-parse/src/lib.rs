//! The parsers being compared, each from bytes already in memory to its entity table, plus the
//! list of input files. Shared by the criterion bench (`benches/parse.rs`) and the one-shot
//! runner (`src/bin/parse_once.rs`) used for peak memory.

use std::path::{Path, PathBuf};

/// vericad's Part 21 parse: text → `Part21` (entity id → record). Returns the entity count.
pub fn vericad_parse(bytes: &[u8]) -> usize {
    let text = std::str::from_utf8(bytes).expect("STEP input is not UTF-8");
    let p = vericad::io::step::part21::parse(text).expect("vericad failed to parse");
    p.entities.len()
}

/// foxtrot's parse: `strip_flatten` (comments and whitespace out, as its own example does
/// before parsing) then `StepFile::parse` into typed AP214 entities. Returns the size of its
/// entity table (one slot per id up to the largest).
pub fn foxtrot_parse(bytes: &[u8]) -> usize {
    let flat = foxtrot_step::step_file::StepFile::strip_flatten(bytes);
    foxtrot_step::step_file::StepFile::parse(&flat).0.len()
}

/// foxtrot's parse, counted (not timed): (instances parsed into a typed record, instances that
/// fell back to `_FailedToParse`).
pub fn foxtrot_counts(bytes: &[u8]) -> (usize, usize) {
    use foxtrot_step::ap214::Entity;
    let flat = foxtrot_step::step_file::StepFile::strip_flatten(bytes);
    let f = foxtrot_step::step_file::StepFile::parse(&flat);
    let failed =
        f.0.iter()
            .filter(|e| matches!(e, Entity::_FailedToParse))
            .count();
    let empty =
        f.0.iter()
            .filter(|e| matches!(e, Entity::_EmptySlot))
            .count();
    (f.0.len() - failed - empty, failed)
}

/// The instance ids that foxtrot parsed only as `_FailedToParse` (it logs and goes on).
pub fn foxtrot_failed_ids(bytes: &[u8]) -> Vec<usize> {
    use foxtrot_step::ap214::Entity;
    let flat = foxtrot_step::step_file::StepFile::strip_flatten(bytes);
    let f = foxtrot_step::step_file::StepFile::parse(&flat);
    (0..f.0.len())
        .filter(|&i| matches!(f.0[i], Entity::_FailedToParse))
        .collect()
}

/// vericad's whole read (file → Model: parse + B-rep build), as the CLI does it.
pub fn vericad_read_model(path: &Path) -> usize {
    let m = vericad::io::read_model(path).expect("vericad failed to read");
    m.surfaces.len()
}

/// The public STEP inputs, relative to the repository root; those that exist are returned.
pub fn inputs() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut v = Vec::new();
    for dir in [
        "tests/data/public",
        "tests/data/public/occt-written",
        "tests/data/large",
    ] {
        let Ok(rd) = std::fs::read_dir(root.join(dir)) else {
            continue;
        };
        let mut files: Vec<PathBuf> = rd
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| {
                p.extension()
                    .and_then(|e| e.to_str())
                    .is_some_and(|e| matches!(e.to_ascii_lowercase().as_str(), "step" | "stp"))
            })
            .collect();
        files.sort();
        v.extend(files);
    }
    v
}

/// A short name for a file: its path under `tests/data/`.
pub fn label(p: &Path) -> String {
    let s = p.to_string_lossy();
    match s.find("tests/data/") {
        Some(i) => s[i + "tests/data/".len()..].to_string(),
        None => s.into_owned(),
    }
}
