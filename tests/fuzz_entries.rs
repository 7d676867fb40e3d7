//! The fuzz targets' bodies run as ordinary tests: over the malformed-model corpus, the
//! valid models, byte-level mutations of them, and random byte strings.

mod common;
use common::Rng;
use vericad::fuzz_entry;

fn corpus() -> Vec<Vec<u8>> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/malformed");
    let mut v: Vec<Vec<u8>> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| std::fs::read(e.unwrap().path()).unwrap())
        .collect();
    v.push(vericad::demo::DEFAULT_MODEL.as_bytes().to_vec());
    v.sort();
    v
}

#[test]
fn model_json_survives_corpus_and_mutations() {
    let mut r = Rng(11);
    let base = corpus();
    for seed in &base {
        fuzz_entry::model_json(seed);
    }
    for k in 0..20_000 {
        let mut s = base[k % base.len()].clone();
        for _ in 0..1 + r.below(4) {
            if s.is_empty() {
                break;
            }
            let i = r.below(s.len());
            match r.below(4) {
                0 => s[i] = b"0123456789-.eE,[]{}\":"[r.below(21)],
                1 => {
                    s.remove(i);
                }
                2 => s.insert(i, s[i]),
                _ => s.truncate(i),
            }
        }
        fuzz_entry::model_json(&s);
    }
}

#[test]
fn geometry_targets_survive_random_and_structured_bytes() {
    let mut r = Rng(12);
    for k in 0..20_000 {
        let n = 8 * (2 + r.below(18));
        let bytes: Vec<u8> = if k % 5 == 0 {
            (0..n).map(|_| r.next_u64() as u8).collect()
        } else {
            // Small integers as f64: many exact degeneracies.
            (0..n / 8)
                .flat_map(|_| (r.int(-2, 2) as f64).to_le_bytes())
                .collect()
        };
        fuzz_entry::single_sided_test(&bytes);
        fuzz_entry::tri_tri_test(&bytes);
    }
}

#[test]
fn curve_on_surface_target_survives_random_bytes() {
    let mut r = Rng(13);
    for k in 0..60 {
        let bytes: Vec<u8> = if k % 3 == 0 {
            (0..56).map(|_| r.next_u64() as u8).collect()
        } else {
            (0..7)
                .flat_map(|_| r.range(-0.3, 1.3).to_le_bytes())
                .collect()
        };
        fuzz_entry::curve_on_surface(&bytes);
    }
}

/// The readers on byte-level mutations of every real file in tests/data/public.
#[test]
fn readers_survive_mutated_real_files() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/public");
    let mut files: Vec<Vec<u8>> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x != "md"))
        .map(|p| std::fs::read(p).unwrap())
        .collect();
    files.sort();
    let mut r = Rng(14);
    for f in &files {
        fuzz_entry::readers(f);
    }
    for k in 0..300 {
        let mut s = files[k % files.len()].clone();
        for _ in 0..1 + r.below(6) {
            let i = r.below(s.len());
            match r.below(5) {
                0 => s[i] = b"0123456789-.,;()#'HDE\n "[r.below(23)],
                1 => {
                    s.remove(i);
                }
                2 => s.insert(i, s[i]),
                3 => s.truncate(i.max(1)),
                _ => {
                    let j = r.below(s.len());
                    s.swap(i, j);
                }
            }
        }
        fuzz_entry::readers(&s);
    }
}

#[test]
fn ssi_meshes_on_random_degenerate_grids() {
    let mut r = Rng(29);
    let (mut segments, mut with) = (0, 0);
    for _ in 0..3_000 {
        let data: Vec<u8> = (0..64).map(|_| r.below(256) as u8).collect();
        let s = fuzz_entry::ssi_meshes(&data);
        segments += s;
        with += usize::from(s > 0);
    }
    // The grids do cross (the test exercises the tracer, not only the culling).
    assert!(
        with > 1_000 && segments > 10_000,
        "{with} runs with segments, {segments} in all"
    );
    fuzz_entry::ssi_meshes(&[]);
    fuzz_entry::ssi_meshes(&[2; 64]);
}

#[test]
fn ssi_surfaces_on_random_patches() {
    let mut r = Rng(31);
    let mut with = 0;
    for _ in 0..40 {
        let data: Vec<u8> = (0..41).map(|_| r.below(256) as u8).collect();
        with += usize::from(fuzz_entry::ssi_surfaces(&data) > 0);
    }
    // The patches do cross (the test reaches the certificates, not only the culling).
    assert!(with > 10, "{with} runs with branches");
    fuzz_entry::ssi_surfaces(&[]);
    fuzz_entry::ssi_surfaces(&[255; 41]);
}

#[test]
fn repair_on_random_patch_soups() {
    let mut r = Rng(31);
    let mut connected = 0;
    for _ in 0..150 {
        let len = r.below(150);
        let data: Vec<u8> = (0..len).map(|_| r.below(256) as u8).collect();
        connected += fuzz_entry::repair_soup(&data);
    }
    assert!(connected > 0, "the soups do connect somewhere");
}

/// Every file under `dir` (recursively), sorted.
fn files_under(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            files_under(&p, out);
        } else {
            out.push(p);
        }
    }
}

/// Every fuzz target over its committed seed corpus (`fuzz/seeds/<target>`, plus the test
/// data each target is run with: `fuzz/README.md`), each input on a thread of its own with
/// a time limit, so a hang fails the test as well as a panic.
#[test]
fn every_fuzz_target_survives_its_seed_corpus() {
    use std::time::Duration;
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    type Entry = fn(&[u8]);
    let targets: [(&str, Entry, &[&str]); 9] = [
        (
            "readers",
            fuzz_entry::readers,
            &["tests/data/faulty", "tests/data/public"],
        ),
        (
            "model_json",
            fuzz_entry::model_json,
            &["tests/data/malformed", "src/models"],
        ),
        (
            "curve_on_surface",
            fuzz_entry::curve_on_surface,
            &["tests/data/faulty/fuzz-artifacts/curve_on_surface"],
        ),
        ("single_sided", fuzz_entry::single_sided_test, &[]),
        ("tri_tri", fuzz_entry::tri_tri_test, &[]),
        (
            "ssi_meshes",
            |d| {
                fuzz_entry::ssi_meshes(d);
            },
            &[],
        ),
        (
            "ssi_surfaces",
            |d| {
                fuzz_entry::ssi_surfaces(d);
            },
            &[],
        ),
        (
            "repair_soup",
            |d| {
                fuzz_entry::repair_soup(d);
            },
            &[],
        ),
        ("coons_boundary", fuzz_entry::coons_boundary, &[]),
    ];
    // Every cargo-fuzz target has an entry here.
    let declared = std::fs::read_to_string(root.join("fuzz/Cargo.toml")).unwrap();
    let n_bins = declared.matches("[[bin]]").count();
    assert_eq!(
        n_bins,
        targets.len(),
        "a fuzz target without its corpus test"
    );
    for (name, entry, extra) in targets {
        assert!(declared.contains(&format!("name = \"{name}\"")), "{name}");
        let mut files = Vec::new();
        let seeds = root.join("fuzz/seeds").join(name);
        if seeds.is_dir() {
            files_under(&seeds, &mut files);
        }
        for d in extra {
            files_under(&root.join(d), &mut files);
        }
        files.sort();
        assert!(files.len() >= 4, "{name}: {} seeds", files.len());
        for f in files {
            let bytes = std::fs::read(&f).unwrap();
            let (tx, rx) = std::sync::mpsc::channel();
            std::thread::spawn(move || {
                let ok = std::panic::catch_unwind(|| entry(&bytes)).is_ok();
                let _ = tx.send(ok);
            });
            let r = rx.recv_timeout(Duration::from_secs(120));
            assert_eq!(r, Ok(true), "{name}: {} panicked or hung", f.display());
        }
    }
}
