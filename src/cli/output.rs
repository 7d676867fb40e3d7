//! Printing a job's report and mapping its error to an exit code.

use super::{EXIT_BAD_INPUT, EXIT_FAILURE, EXIT_UNCERTIFIED};

/// Print a report; a closed pipe (e.g. `| head`) is not an error.
pub(super) fn print<T: serde::Serialize + std::fmt::Display>(r: &T, json: bool) {
    use std::io::Write;
    let mut out = std::io::BufWriter::with_capacity(1 << 16, std::io::stdout().lock());
    let _ = if json {
        // Streamed as it is made: a large result is never held as text in memory. A closed
        // pipe ends the output quietly.
        match crate::io::json_text::to_writer(&mut out, r) {
            Ok(()) => writeln!(out),
            Err(e) if e.io_error_kind() == Some(std::io::ErrorKind::BrokenPipe) => Ok(()),
            Err(e) => {
                let _ = out.flush();
                eprintln!("error: the JSON report could not be written: {e}");
                Ok(())
            }
        }
    } else {
        write!(out, "{r}")
    };
    let _ = out.flush();
}

pub(super) fn bad(msg: impl std::fmt::Display) -> i32 {
    eprintln!("error: {msg}");
    EXIT_BAD_INPUT
}

/// Print a job's report, or its error with the exit code for bad input or failure.
pub(super) fn finish<T: serde::Serialize + std::fmt::Display, E: std::fmt::Display>(
    r: Result<T, E>,
    json: bool,
    is_bad: impl Fn(&E) -> bool,
) -> i32 {
    finish_checked(r, json, |_| true, is_bad)
}

/// [`finish`] for a job whose report carries a verdict: exit 0 when `passed` says so,
/// [`EXIT_UNCERTIFIED`] when it does not (not certified, not within tol).
pub(super) fn finish_checked<T: serde::Serialize + std::fmt::Display, E: std::fmt::Display>(
    r: Result<T, E>,
    json: bool,
    passed: impl Fn(&T) -> bool,
    is_bad: impl Fn(&E) -> bool,
) -> i32 {
    match r {
        Ok(r) => {
            print(&r, json);
            if passed(&r) { 0 } else { EXIT_UNCERTIFIED }
        }
        Err(e) if is_bad(&e) => bad(e),
        Err(e) => {
            eprintln!("error: {e}");
            EXIT_FAILURE
        }
    }
}
