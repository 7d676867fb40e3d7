//! `--max-memory`: a job whose heap genuinely exceeds the budget stops with the typed error
//! `budget exhausted: memory (limit X MB, in use Y MB) at <step>` and exit code 1; a job
//! that stays under it gives exactly the result it gives without the option; a limit that
//! is not a positive number is bad input (exit 2).
//!
//! The large model is known by construction to need more than the limit: two bilinear
//! patches of 710 × 710 control points hold 2 · 710² · 3 f64 coordinates = 24.2 MB of
//! heap, over a 20 MB budget, before any work starts.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn vericad(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_vericad"))
        .args(args)
        .output()
        .unwrap()
}

fn public(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data/public")
        .join(name)
        .display()
        .to_string()
}

/// A flat bilinear patch of `n × n` control points: the unit square of the plane z = 0
/// (`vertical`: the plane x = 0.5, spanning y, z in [-0.5, 0.5] + 0.5).
fn patch(n: usize, vertical: bool) -> String {
    let knots: Vec<String> = std::iter::once("0".to_string())
        .chain((0..n).map(|i| format!("{}", i as f64 / (n - 1) as f64)))
        .chain(std::iter::once("1".to_string()))
        .collect();
    let knots = knots.join(",");
    let mut rows = Vec::with_capacity(n);
    for i in 0..n {
        let a = i as f64 / (n - 1) as f64;
        let row: Vec<String> = (0..n)
            .map(|j| {
                let b = j as f64 / (n - 1) as f64;
                if vertical {
                    format!("[0.5,{a},{}]", b - 0.5)
                } else {
                    format!("[{a},{b},0]")
                }
            })
            .collect();
        rows.push(format!("[{}]", row.join(",")));
    }
    format!(
        "{{\"degree_u\":1,\"degree_v\":1,\"knots_u\":[{knots}],\"knots_v\":[{knots}],\"control_points\":[{}]}}",
        rows.join(",")
    )
}

/// The large model in a directory of its own (`tag`: the test's).
fn large_model(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("vericad-memory-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("large.json");
    let text = format!(
        "{{\"surfaces\":[{},{}]}}",
        patch(710, false),
        patch(710, true)
    );
    std::fs::write(&p, text).unwrap();
    p
}

/// The `(limit, in use)` megabytes and the step of a budget error line.
fn budget_error(stderr: &str) -> (f64, f64, String) {
    let l = stderr
        .lines()
        .find(|l| l.contains("budget exhausted: memory"))
        .unwrap_or_else(|| panic!("no budget error in: {stderr}"));
    let num = |after: &str| -> f64 {
        let r = &l[l.find(after).unwrap() + after.len()..];
        r[..r.find(' ').unwrap()].parse().unwrap()
    };
    let step = l[l.find(") at ").unwrap() + 5..].to_string();
    (num("(limit "), num("in use "), step)
}

#[test]
fn ssi_over_its_memory_budget_stops_with_the_typed_error() {
    let p = large_model("ssi");
    let f = p.to_str().unwrap();
    let o = vericad(&["ssi", f, "--max-memory", "20"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    let (limit, in_use, step) = budget_error(&err);
    assert_eq!(limit, 20.0);
    // At least the control points' 24.2 MB are in use.
    assert!(in_use >= 24.0, "{in_use}");
    assert!(!step.is_empty());
    assert!(o.stdout.is_empty(), "no result is printed");
    let _ = std::fs::remove_dir_all(p.parent().unwrap());
}

#[test]
fn ssi_under_its_memory_budget_gives_the_same_result() {
    let f = public("gmsh-t20_data.step");
    let free = vericad(&["ssi", &f, "--json"]);
    let bounded = vericad(&["ssi", &f, "--json", "--max-memory", "1000"]);
    assert_eq!(bounded.status.code(), free.status.code());
    let err = String::from_utf8_lossy(&bounded.stderr);
    assert!(!err.contains("budget exhausted"), "{err}");
    let strip = |o: &Output| {
        let mut v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        // Timings differ between runs.
        strip_seconds(&mut v);
        v
    };
    assert_eq!(strip(&bounded), strip(&free));
}

fn strip_seconds(v: &mut serde_json::Value) {
    match v {
        serde_json::Value::Object(m) => {
            m.retain(|k, _| !k.contains("seconds") && !k.contains("time"));
            m.values_mut().for_each(strip_seconds);
        }
        serde_json::Value::Array(a) => a.iter_mut().for_each(strip_seconds),
        _ => {}
    }
}

#[test]
fn repair_over_its_memory_budget_stops_with_the_typed_error() {
    // The same 24.2 MB of control points, read as a patch set to repair.
    let p = large_model("repair");
    let o = vericad(&["repair", p.to_str().unwrap(), "--max-memory", "20"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    let (limit, in_use, step) = budget_error(&err);
    assert_eq!((limit, step.as_str()), (20.0, "repair"));
    assert!(in_use > 20.0);
    let _ = std::fs::remove_dir_all(p.parent().unwrap());
}

#[test]
fn a_limit_that_is_not_a_positive_number_is_bad_input() {
    for m in ["0", "-5", "nan", "inf"] {
        let o = vericad(&["ssi", &public("gmsh-t20_data.step"), "--max-memory", m]);
        assert_eq!(o.status.code(), Some(2), "{m}");
        assert!(String::from_utf8_lossy(&o.stderr).contains("--max-memory"));
    }
}

/// The commands without checkpoints that read a model first (watched from a second thread):
/// the 24.2 MB model ends each of them with the typed error naming the command, exit 1, and
/// no output file is left behind.
#[test]
fn reading_commands_over_their_memory_budget_stop_with_the_typed_error() {
    let p = large_model("readers");
    let f = p.to_str().unwrap();
    let out = p.parent().unwrap().join("out.json");
    let o_str = out.to_str().unwrap();
    for (cmd, args) in [
        ("info", vec!["info", f]),
        ("convert", vec!["convert", f, o_str]),
        ("reparam", vec!["reparam", f, "--out", o_str]),
    ] {
        let mut a = args.clone();
        a.extend(["--max-memory", "20"]);
        let o = vericad(&a);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{cmd}: {err}");
        let (limit, in_use, step) = budget_error(&err);
        assert_eq!((limit, step.as_str()), (20.0, cmd));
        assert!(in_use > 20.0, "{cmd}: {in_use}");
        assert!(!out.exists(), "{cmd} left an output");
    }
    let _ = std::fs::remove_dir_all(p.parent().unwrap());
}

#[test]
fn reparam_under_its_memory_budget_gives_the_same_result() {
    let f = format!("{}:1", public("gmsh-t20_data.step"));
    let free = vericad(&["reparam", &f, "--json", "--no-bound"]);
    let bounded = vericad(&[
        "reparam",
        &f,
        "--json",
        "--no-bound",
        "--max-memory",
        "1000",
    ]);
    assert_eq!(free.status.code(), Some(0));
    assert_eq!(bounded.status.code(), free.status.code());
    let strip = |o: &Output| {
        let mut v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        strip_seconds(&mut v);
        v
    };
    assert_eq!(strip(&bounded), strip(&free));
}

#[test]
fn every_command_refuses_a_limit_that_is_not_a_positive_number() {
    let t20 = public("gmsh-t20_data.step");
    let dir = std::env::temp_dir();
    let out = dir.join(format!("vericad-memory-bad-{}.json", std::process::id()));
    let o_str = out.to_str().unwrap();
    let commands: [Vec<&str>; 6] = [
        vec!["info", &t20],
        vec!["convert", &t20, o_str],
        vec!["reparam", &t20],
        vec!["coons", &t20, "--boundary", o_str],
        vec!["approximate", &t20, "--layout", o_str],
        vec!["curve-on-surface", "--surface", &t20, "--curve", &t20],
    ];
    for args in commands {
        for m in ["0", "-5", "nan"] {
            let mut a = args.clone();
            a.extend(["--max-memory", m]);
            let o = vericad(&a);
            let err = String::from_utf8_lossy(&o.stderr);
            assert_eq!(o.status.code(), Some(2), "{args:?} {m}: {err}");
            assert!(err.contains("--max-memory"), "{args:?} {m}: {err}");
        }
    }
    assert!(!out.exists());
}
