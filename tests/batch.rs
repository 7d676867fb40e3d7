//! `vericad batch` end to end over the test data (public, faulty and malformed models): one
//! record per model, bad files as `bad_input` records with the reader's message, resume,
//! shards, the `ssi` job under a time limit, argument checks, and panic isolation in the
//! library's executor.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};
use std::process::Command;
use vericad::batch::record::{InfoFigures, Outcome};
use vericad::batch::{Record, Status};

fn data(dir: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/data")
        .join(dir)
        .display()
        .to_string()
}

fn all_dirs() -> Vec<String> {
    ["public", "faulty", "malformed"].map(data).to_vec()
}

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("vericad-batch-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Run `vericad batch ARGS --out OUT` (with `--threads 2` unless ARGS set it); returns the
/// exit code and stderr.
fn batch(args: &[String], out: &Path) -> (i32, String) {
    let mut c = Command::new(env!("CARGO_BIN_EXE_vericad"));
    c.arg("batch").args(args).arg("--out").arg(out);
    if !args.iter().any(|a| a == "--threads") {
        c.args(["--threads", "2"]);
    }
    let o = c.output().unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stderr).into(),
    )
}

fn info_args(inputs: &[String]) -> Vec<String> {
    let mut a = inputs.to_vec();
    a.extend(["--job".to_string(), "info".to_string()]);
    a
}

fn records(out: &Path) -> Vec<Record> {
    std::fs::read_to_string(out)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{l}: {e}")))
        .collect()
}

fn path_status(rs: &[Record]) -> BTreeSet<(String, Status)> {
    rs.iter().map(|r| (r.path.clone(), r.status)).collect()
}

/// The model files under `dir`, found independently of the library's discovery.
fn model_files(dir: &Path, out: &mut Vec<String>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            model_files(&p, out);
        } else if let Some(x) = p.extension().and_then(|x| x.to_str())
            && ["step", "stp", "igs", "iges", "json", "stl"].contains(&x.to_lowercase().as_str())
        {
            out.push(p.display().to_string());
        }
    }
}

#[test]
fn every_model_gets_exactly_one_record_and_bad_files_say_why() {
    let out = tmp("all").join("r.jsonl");
    let (code, stderr) = batch(&info_args(&all_dirs()), &out);
    assert_eq!(code, 3, "bad files make the run not all ok: {stderr}");
    assert!(stderr.contains("bad_input"), "summary table: {stderr}");
    let rs = records(&out);
    let mut expected = Vec::new();
    for d in all_dirs() {
        model_files(Path::new(&d), &mut expected);
    }
    expected.sort();
    let mut got: Vec<String> = rs.iter().map(|r| r.path.clone()).collect();
    got.sort();
    assert_eq!(got, expected, "one record per model file, none twice");
    for r in &rs {
        match r.status {
            Status::Ok => assert!(r.info.is_some() && r.error.is_none(), "{r:?}"),
            Status::BadInput => {
                let e = r.error.as_ref().expect("a bad_input record has an error");
                assert!(!e.message.is_empty(), "{r:?}");
                assert_eq!(e.kind, "read", "{r:?}");
            }
            s => panic!("info gives ok or bad_input, not {s}: {r:?}"),
        }
    }
    let neg = rs
        .iter()
        .find(|r| r.path.ends_with("negative-weight.json"))
        .unwrap();
    assert_eq!(neg.status, Status::BadInput);
    assert!(
        neg.error
            .as_ref()
            .unwrap()
            .message
            .contains("surfaces[0].weights[1][1]"),
        "{neg:?}"
    );
    // A well-formed B-rep reports its topology counts.
    let cube = rs
        .iter()
        .find(|r| r.path.ends_with("gmsh-cube1000.igs"))
        .unwrap();
    let info = cube.info.as_ref().unwrap();
    assert!(info.faces >= 6, "{info:?}");
}

#[test]
fn a_resumed_run_adds_only_the_missing_records() {
    let d = tmp("resume");
    let fresh = d.join("fresh.jsonl");
    batch(&info_args(&all_dirs()), &fresh);
    let fresh = records(&fresh);

    // First a subset, then the full run on the same output.
    let out = d.join("r.jsonl");
    batch(&info_args(&[data("public")]), &out);
    let first = records(&out);
    assert!(!first.is_empty());
    // A run killed while writing leaves a cut-off last line: it is dropped and rerun.
    let mut text = std::fs::read_to_string(&out).unwrap();
    text.push_str("{\"path\":\"cut off");
    std::fs::write(&out, text).unwrap();
    let (_, stderr) = batch(&info_args(&all_dirs()), &out);
    assert!(
        stderr.contains(&format!("({} from earlier records)", first.len())),
        "{stderr}"
    );
    let all = records(&out);
    assert_eq!(&all[..first.len()], &first[..], "earlier records are kept");
    assert_eq!(all.len(), fresh.len(), "no model twice");
    assert_eq!(path_status(&all), path_status(&fresh));

    // Nothing left to do: a third run writes nothing.
    batch(&info_args(&all_dirs()), &out);
    assert_eq!(records(&out).len(), fresh.len());
}

/// A run killed part way and started again with the same command ends with one record per
/// model, the records written before the kill kept as they were.
#[test]
fn a_killed_run_resumed_completes_the_records() {
    let d = tmp("kill");
    let out = d.join("r.jsonl");
    let args = [
        &data("public"),
        "--job",
        "ssi",
        "--time-limit-per-model",
        "1",
        "--threads",
        "2",
        "--quiet",
    ];
    let mut child = Command::new(env!("CARGO_BIN_EXE_vericad"))
        .arg("batch")
        .args(args)
        .arg("--out")
        .arg(&out)
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(1500));
    let _ = child.kill();
    child.wait().unwrap();
    let before = std::fs::read_to_string(&out).unwrap_or_default();
    // Complete lines only: a line cut by the kill is dropped and its model runs again.
    let kept = before.matches('\n').count();
    let args: Vec<String> = args.map(String::from).to_vec();
    batch(&args, &out);
    let rs = records(&out);
    let mut expected = Vec::new();
    model_files(Path::new(&data("public")), &mut expected);
    expected.sort();
    let mut got: Vec<String> = rs.iter().map(|r| r.path.clone()).collect();
    got.sort();
    assert_eq!(got, expected, "one record per model after the resume");
    assert!(kept < expected.len(), "the kill came before the end");
    let after = std::fs::read_to_string(&out).unwrap();
    let first: Vec<&str> = before.lines().take(kept).collect();
    let again: Vec<&str> = after.lines().take(kept).collect();
    assert_eq!(first, again, "records from before the kill are kept");
}

#[test]
fn two_shards_make_one_run() {
    let d = tmp("shard");
    let full = d.join("full.jsonl");
    batch(&info_args(&all_dirs()), &full);
    let full = records(&full);
    let mut union = BTreeSet::new();
    let mut sizes = Vec::new();
    for i in 0..2 {
        let out = d.join(format!("s{i}.jsonl"));
        let mut a = info_args(&all_dirs());
        a.extend(["--shard".to_string(), format!("{i}/2")]);
        batch(&a, &out);
        let rs = records(&out);
        sizes.push(rs.len());
        union.extend(path_status(&rs));
    }
    assert_eq!(
        sizes.iter().sum::<usize>(),
        full.len(),
        "shards are disjoint"
    );
    assert!(sizes[0].abs_diff(sizes[1]) <= 1, "{sizes:?}");
    assert_eq!(union, path_status(&full));
}

#[test]
fn ssi_job_gives_verdicts_within_the_time_limit() {
    let d = tmp("ssi");
    let list = d.join("list.txt");
    let p = data("public");
    std::fs::write(
        &list,
        format!(
            "# three small models\n{p}/gmsh-cube1000.igs\n\n{p}/gmsh-sphere_Rhino3D_default.igs\n{p}/occt-bad_header.igs\n"
        ),
    )
    .unwrap();
    let out = d.join("r.jsonl");
    let args: Vec<String> = [
        &format!("@{}", list.display()),
        "missing-model",
        "--job",
        "ssi",
        "--time-limit-per-model",
        "2",
        "--tol",
        "1e-6",
    ]
    .map(String::from)
    .to_vec();
    let (code, stderr) = batch(&args, &out);
    let rs = records(&out);
    assert_eq!(rs.len(), 4, "{stderr}");
    // A path that names nothing is a bad model, not the end of the batch.
    let missing = rs.iter().find(|r| r.path == "missing-model").unwrap();
    assert_eq!(missing.status, Status::BadInput);
    let message = &missing.error.as_ref().unwrap().message;
    assert!(message.contains("no such file"), "{missing:?}");
    let rs: Vec<Record> = rs.into_iter().filter(|r| r.ssi.is_some()).collect();
    assert_eq!(rs.len(), 3, "{stderr}");
    let by: BTreeMap<&str, &Record> = rs
        .iter()
        .map(|r| (Path::new(&r.path).file_name().unwrap().to_str().unwrap(), r))
        .collect();
    for r in &rs {
        let f = r.ssi.as_ref().expect("ssi figures");
        assert_eq!(r.status == Status::Ok, f.certified && !f.partial, "{r:?}");
        assert_eq!(r.status == Status::Timeout, f.partial, "{r:?}");
    }
    // The cube is a closed shell (sewn from its trimmed faces): its faces meet only along
    // shared edges, which are listed as such, not as branches.
    let cube = by["gmsh-cube1000.igs"].ssi.as_ref().unwrap();
    assert_eq!(cube.branches, 0, "{cube:?}");
    assert_eq!(cube.faces, 6, "{cube:?}");
    // One face alone has no pair to intersect: certified, nothing found.
    let one = by["occt-bad_header.igs"];
    assert_eq!(one.status, Status::Ok);
    assert_eq!(one.ssi.as_ref().unwrap().branches, 0);
    assert_eq!(code, 3, "a bad model makes the run not all ok: {stderr}");
}

/// `--job repair`: a model read as faces gets the repair figures, its patch count the one
/// `--job info` gives; a file without faces (STL) a `bad_input` record from the repair.
#[test]
fn repair_job_reports_patches_in_and_out() {
    let d = tmp("repair");
    let (info, repair) = (d.join("info.jsonl"), d.join("repair.jsonl"));
    batch(&info_args(&[data("public")]), &info);
    let args: Vec<String> = [data("public"), "--job".into(), "repair".into()].to_vec();
    batch(&args, &repair);
    let faces: BTreeMap<String, usize> = records(&info)
        .into_iter()
        .filter_map(|r| Some((r.path, r.info?.faces)))
        .collect();
    let rs = records(&repair);
    assert_eq!(
        rs.len(),
        faces.len(),
        "every model read by info is repaired or refused"
    );
    let mut repaired = 0;
    for r in &rs {
        match (&r.repair, &r.error) {
            (Some(f), None) => {
                assert_eq!(r.status, Status::Ok);
                assert_eq!(f.patches_in, faces[&r.path], "{r:?}");
                assert!(f.patches_out >= 1, "{r:?}");
                repaired += 1;
            }
            (None, Some(e)) => {
                assert_eq!(r.status, Status::BadInput);
                assert!(r.path.ends_with(".stl"), "{r:?}");
                assert_eq!(e.kind, "repair", "{r:?}");
            }
            _ => panic!("figures or an error: {r:?}"),
        }
    }
    assert!(repaired >= 5, "{rs:?}");
}

/// The `repair` job picks the repair as `vericad repair` does: gmsh-t20 (15 of its 21 faces
/// cut out of larger surfaces) gets the faces repair, with its trims; the fuselage (8 natural
/// B-spline faces) the patch-set repair. `--repair-mode patches` forces the patch-set repair
/// on t20, which then counts the trims it ignored.
#[test]
fn repair_job_picks_the_faces_repair_for_trimmed_faces() {
    let d = tmp("repair-mode");
    let t20 = format!("{}/gmsh-t20_data.step", data("public"));
    let fuselage = format!("{}/occt-bug28366_fuselage.stp", data("public"));
    let run = |extra: &[&str], name: &str| {
        let out = d.join(name);
        let mut args = vec![
            t20.clone(),
            fuselage.clone(),
            "--job".into(),
            "repair".into(),
        ];
        args.extend(extra.iter().map(|s| s.to_string()));
        let (code, stderr) = batch(&args, &out);
        let rs = records(&out);
        let get = |p: &str| {
            rs.iter()
                .find(|r| r.path.ends_with(p))
                .cloned()
                .unwrap_or_else(|| panic!("{p}: {rs:?}"))
        };
        (
            code,
            stderr,
            get("gmsh-t20_data.step"),
            get("occt-bug28366_fuselage.stp"),
        )
    };
    let (code, stderr, t, f) = run(&[], "auto.jsonl");
    assert_eq!(code, 0, "{stderr}");
    let (t, f) = (t.repair.unwrap(), f.repair.unwrap());
    assert_eq!(t.mode, "faces", "{t:?}");
    assert_eq!((t.patches_in, t.patches_out, t.trims_ignored), (21, 21, 0));
    assert_eq!(t.free_edges_after, Some(0), "t20 is a closed solid: {t:?}");
    assert_eq!(t.gap_proven, Some(true), "{t:?}");
    assert_eq!(f.mode, "patches", "{f:?}");
    assert_eq!((f.free_edges_after, f.gap_proven), (None, None));
    let (code, stderr, t, _) = run(&["--repair-mode", "patches"], "patches.jsonl");
    assert_eq!(code, 0, "{stderr}");
    let t = t.repair.unwrap();
    assert_eq!(t.mode, "patches", "{t:?}");
    assert_eq!(t.trims_ignored, 15, "{t:?}");
    // Forced faces: the fuselage's bare surfaces have no B-rep, which its record says.
    let (code, _, t, f) = run(&["--repair-mode", "faces"], "faces.jsonl");
    assert_eq!(code, 3);
    assert_eq!(t.repair.map(|r| r.mode).as_deref(), Some("faces"));
    assert_eq!(f.status, Status::BadInput);
    assert!(f.error.unwrap().message.contains("no B-rep"));
}

#[test]
fn bad_arguments_exit_2_with_a_clear_message() {
    let d = tmp("args");
    let out = d.join("r.jsonl");
    let p = data("public");
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (vec![&p, "--job", "frobnicate"], "--job"),
        (vec![&p, "--job", "info", "--shard", "2/2"], "--shard"),
        (vec![&p, "--job", "info", "--shard", "-1/2"], "--shard"),
        (vec![&p, "--job", "info", "--threads", "-1"], "--threads"),
        (
            vec![&p, "--job", "ssi", "--time-limit-per-model", "-5"],
            "--time-limit-per-model",
        ),
        (vec![&p, "--job", "ssi", "--tol", "-1"], "--tol"),
        (
            vec![&p, "--job", "repair", "--repair-mode", "trims"],
            "--repair-mode",
        ),
        (vec!["@/nonexistent/list.txt", "--job", "info"], "list"),
    ];
    for (args, word) in cases {
        let args: Vec<String> = args.into_iter().map(String::from).collect();
        let (code, stderr) = batch(&args, &out);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stderr.contains(word), "{args:?}: {stderr}");
        assert!(
            !stderr.contains("unexpected argument"),
            "{args:?}: {stderr}"
        );
    }
    // An output that holds something other than records is not appended to.
    std::fs::write(&out, "not a record\n").unwrap();
    let (code, stderr) = batch(&info_args(&[p]), &out);
    assert_eq!(code, 2, "{stderr}");
    assert!(stderr.contains("line 1"), "{stderr}");
    assert_eq!(std::fs::read_to_string(&out).unwrap(), "not a record\n");
}

#[test]
fn a_panicking_job_becomes_a_panic_record() {
    let d = tmp("panic");
    let models: Vec<PathBuf> = ["a.json", "b.json", "c.json"]
        .iter()
        .map(|n| d.join(n))
        .collect();
    let out = d.join("r.jsonl");
    let file = std::fs::File::create(&out).unwrap();
    let job = |p: &Path| -> Outcome {
        if p.ends_with("b.json") {
            panic!("the job broke on b");
        }
        Outcome::Info(InfoFigures {
            faces: 1,
            curves: 0,
            triangulations: 0,
            brep_faces: None,
            brep_edges: None,
            unit: None,
            warnings: 0,
        })
    };
    let done =
        vericad::batch::run::execute(&models, &job, file, Some(2), Default::default()).unwrap();
    assert_eq!(done.records.len(), 3);
    let rs = records(&out);
    assert_eq!(path_status(&rs), path_status(&done.records));
    let b = rs.iter().find(|r| r.path.ends_with("b.json")).unwrap();
    assert_eq!(b.status, Status::Panic);
    assert!(
        b.error
            .as_ref()
            .unwrap()
            .message
            .contains("the job broke on b")
    );
    assert_eq!(
        rs.iter().filter(|r| r.status == Status::Ok).count(),
        2,
        "the other models ran"
    );
}
