//! The layering rule of ARCHITECTURE.md, checked on the source text: every `crate::X` path
//! (in `use` lines and inline) names a module of the same or a lower layer. Pipelines
//! (ssi, repair, reparam, curve_on_surface, approx) never import each other; the kernel
//! (scalar, geom, predicates, spline, model, brep, io, tessellate) never imports a pipeline
//! or the command line.

use std::path::Path;

const PIPELINES: [&str; 5] = ["ssi", "repair", "reparam", "curve_on_surface", "approx"];
const TOP: [&str; 5] = ["cli", "demo", "fuzz_entry", "bin", "batch"];

/// The top-level module a source file belongs to (`src/ssi/pair.rs` → `ssi`).
fn module_of(rel: &Path) -> String {
    let first = rel
        .components()
        .next()
        .unwrap()
        .as_os_str()
        .to_string_lossy()
        .to_string();
    first.trim_end_matches(".rs").to_string()
}

fn files(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// Every `crate::name` in `text` outside line comments.
fn crate_refs(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let code = line.split("//").next().unwrap();
        let mut rest = code;
        while let Some(k) = rest.find("crate::") {
            let tail = &rest[k + 7..];
            let name: String = tail
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if !name.is_empty() {
                out.push((i + 1, name));
            }
            rest = tail;
        }
    }
    out
}

#[test]
fn no_upward_or_sideways_imports() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut all = Vec::new();
    files(&src, &mut all);
    assert!(all.len() > 50);
    let mut bad = Vec::new();
    for f in &all {
        let rel = f.strip_prefix(&src).unwrap();
        let from = module_of(rel);
        if from == "lib" || TOP.contains(&from.as_str()) {
            continue;
        }
        let text = std::fs::read_to_string(f).unwrap();
        for (line, to) in crate_refs(&text) {
            if to == from {
                continue;
            }
            let sideways = PIPELINES.contains(&from.as_str()) && PIPELINES.contains(&to.as_str());
            let upward = TOP.contains(&to.as_str())
                || (!PIPELINES.contains(&from.as_str()) && PIPELINES.contains(&to.as_str()));
            if sideways || upward {
                bad.push(format!("{}:{line}: {from} -> {to}", rel.display()));
            }
        }
    }
    assert!(
        bad.is_empty(),
        "imports against the layering:\n{}",
        bad.join("\n")
    );
}

/// The checker itself finds a sideways and an upward import.
#[test]
fn the_checker_sees_imports() {
    let refs = crate_refs("use crate::ssi::pair;\nlet x = crate::repair::run(); // crate::cli\n");
    assert_eq!(
        refs,
        vec![(1, "ssi".to_string()), (2, "repair".to_string())]
    );
}

/// Small files (ARCHITECTURE.md): no source file over 500 lines.
#[test]
fn no_source_file_over_500_lines() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut all = Vec::new();
    files(&src, &mut all);
    let long: Vec<String> = all
        .iter()
        .filter_map(|f| {
            let n = std::fs::read_to_string(f).unwrap().lines().count();
            (n > 500).then(|| format!("{} ({n} lines)", f.display()))
        })
        .collect();
    assert!(long.is_empty(), "{long:?}");
}
