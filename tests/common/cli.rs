//! Running the command-line tool from the integration tests.

use std::process::Command;

/// Run the `vericad` binary built for the tests: exit code (-1 when killed by a signal),
/// standard output, standard error.
pub fn vericad(args: &[&str]) -> (i32, String, String) {
    let o = Command::new(env!("CARGO_BIN_EXE_vericad"))
        .args(args)
        .output()
        .unwrap();
    (
        o.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}
