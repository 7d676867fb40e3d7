//! No `unwrap`, `expect`, `panic!`, `unreachable!`, `todo!` or `unimplemented!` in the
//! library's non-test code, except the few listed below, each on a value that does not come
//! from input (an invariant of the code itself), with the reason. Bad input must end in a
//! typed error; a new panic path fails this test until it is removed or argued here.
//!
//! `src/fuzz_entry.rs` is excluded as a whole: its panics are the fuzz targets' invariant
//! checks, which must panic when an invariant breaks.

use std::path::{Path, PathBuf};

/// `(file, code on the line, why it cannot fire on any input)`.
const ALLOWED: &[(&str, &str, &str)] = &[
    (
        "src/scalar/mod.rs",
        r#"S::from_f64(x).expect("lift: caller guarantees a finite value")"#,
        "lift is called on finite values only: readers and spline constructors refuse non-finite data, pipelines re-check models built in code (ssi: Model::validate and the coordinate range; eval: finite parameters)",
    ),
    (
        "src/predicates/poly.rs",
        r#"d.degree().expect("division by the zero polynomial")"#,
        "the divisors are Sturm-sequence and square-free-part polynomials, non-zero by the loop conditions of their callers",
    ),
    (
        "src/curve_on_surface/float/cells.rs",
        r#"*self.u_breaks.last().expect("two breaks"),"#,
        "breakpoints of a validated knot vector: at least two (a non-empty domain)",
    ),
    (
        "src/curve_on_surface/float/cells.rs",
        r#"*self.v_breaks.last().expect("two breaks"),"#,
        "breakpoints of a validated knot vector: at least two (a non-empty domain)",
    ),
    (
        "src/curve_on_surface/float/midpatch.rs",
        r#".expect("binomial coefficients are positive");"#,
        "division by a binomial coefficient C(p+q, k), k <= p+q, which is at least 1",
    ),
    (
        "src/curve_on_surface/examples.rs",
        r#"json::from_str(crate::model::YANG_TABLE2, "embedded").expect("embedded model");"#,
        "the model compiled into the binary (tested by the demo tests)",
    ),
    (
        "src/curve_on_surface/examples.rs",
        r#"unreachable!("the embedded model's first curve is a domain curve")"#,
        "the model compiled into the binary",
    ),
    (
        "src/curve_on_surface/examples.rs",
        r#"NurbsSurface::new(k.clone(), 3, k, 3, n, n, pts, vec![1.0; n * n]).expect("valid surface")"#,
        "fixed example data built in code",
    ),
    (
        "src/curve_on_surface/examples.rs",
        r#"NurbsCurve::new(knots, 3, p, vec![1.0; 13]).expect("valid curve")"#,
        "fixed example data built in code",
    ),
    (
        "src/curve_on_surface/examples.rs",
        r#"NurbsCurve::new(clamped_cubic(n), 3, p, vec![1.0; n]).expect("valid curve")"#,
        "fixed example data built in code",
    ),
];

const PATTERNS: &[&str] = &[
    ".unwrap()",
    ".expect(",
    "panic!(",
    "unreachable!(",
    "todo!(",
    "unimplemented!(",
    "unwrap_unchecked",
];

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// `line` without a trailing `//` comment (one outside a string literal).
fn strip_comment(line: &str) -> &str {
    let b = line.as_bytes();
    let mut in_str = false;
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'\\' if in_str => i += 1,
            b'"' => in_str = !in_str,
            b'/' if !in_str && b.get(i + 1) == Some(&b'/') => return &line[..i],
            _ => {}
        }
        i += 1;
    }
    line
}

/// The lines of `text` outside `#[cfg(test)]` items and outside comments, with their
/// numbers.
fn non_test_lines(text: &str) -> Vec<(usize, String)> {
    let mut out = Vec::new();
    let mut skip_item = false;
    let mut depth: i64 = 0;
    let mut opened = false;
    for (k, line) in text.lines().enumerate() {
        let code = strip_comment(line);
        if code.trim_start().starts_with("#[cfg(test)]") {
            skip_item = true;
            depth = 0;
            opened = false;
            continue;
        }
        if skip_item {
            for c in code.chars() {
                match c {
                    '{' => {
                        depth += 1;
                        opened = true;
                    }
                    '}' => depth -= 1,
                    _ => {}
                }
            }
            // An item without a body (`use`, `mod x;`) ends at its semicolon.
            if (opened && depth <= 0) || (!opened && code.trim_end().ends_with(';')) {
                skip_item = false;
            }
            continue;
        }
        out.push((k + 1, code.to_string()));
    }
    out
}

#[test]
fn no_panic_paths_on_input_in_the_library() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    rust_files(&root.join("src"), &mut files);
    files.sort();
    assert!(files.len() > 50, "the source tree was not found");
    let mut found = Vec::new();
    let mut used = vec![false; ALLOWED.len()];
    for f in &files {
        let rel = f
            .strip_prefix(root)
            .unwrap()
            .to_string_lossy()
            .replace('\\', "/");
        if rel == "src/fuzz_entry.rs" {
            continue;
        }
        // A module's tests in a file of their own: skipped only when the parent declares
        // them test-only (`#[cfg(test)] mod tests;`).
        if f.file_name().is_some_and(|n| n == "tests.rs") {
            let dir = f.parent().unwrap();
            let parent = [
                dir.with_extension("rs"),
                dir.join("mod.rs"),
                dir.join("lib.rs"),
            ]
            .into_iter()
            .find(|p| p.is_file())
            .unwrap_or_else(|| panic!("{rel}: no parent module file"));
            let ptext = std::fs::read_to_string(&parent).unwrap();
            assert!(
                ptext.contains("#[cfg(test)]\nmod tests;"),
                "{rel}: not declared as `#[cfg(test)] mod tests;` in {}",
                parent.display()
            );
            continue;
        }
        let text = std::fs::read_to_string(f).unwrap();
        for (n, code) in non_test_lines(&text) {
            if !PATTERNS.iter().any(|p| code.contains(p)) {
                continue;
            }
            match ALLOWED
                .iter()
                .position(|(file, snippet, _)| *file == rel && code.contains(snippet))
            {
                Some(i) => used[i] = true,
                None => found.push(format!("{rel}:{n}: {}", code.trim())),
            }
        }
    }
    assert!(
        found.is_empty(),
        "panic paths in library code (return a typed error instead, or argue the invariant in ALLOWED):\n{}",
        found.join("\n")
    );
    let stale: Vec<_> = ALLOWED
        .iter()
        .zip(&used)
        .filter(|(_, u)| !**u)
        .map(|((f, s, _), _)| format!("{f}: {s}"))
        .collect();
    assert!(
        stale.is_empty(),
        "allowed entries that match nothing: {stale:?}"
    );
}

/// The scanner itself: test items are skipped, code around them is not.
#[test]
fn the_scanner_skips_test_items_only() {
    let text = "fn a() { x.unwrap(); }\n#[cfg(test)]\nmod tests {\n    fn b() { y.unwrap(); }\n}\nfn c() { z.expect(\"w\"); } // q.unwrap()\n#[cfg(test)]\nuse foo::bar;\nfn d() { panic!(\"p\") }\n";
    let lines: Vec<String> = non_test_lines(text)
        .into_iter()
        .filter(|(_, c)| PATTERNS.iter().any(|p| c.contains(p)))
        .map(|(n, c)| format!("{n}:{}", c.trim()))
        .collect();
    assert_eq!(
        lines,
        vec![
            "1:fn a() { x.unwrap(); }",
            "6:fn c() { z.expect(\"w\"); }",
            "9:fn d() { panic!(\"p\") }"
        ]
    );
}
