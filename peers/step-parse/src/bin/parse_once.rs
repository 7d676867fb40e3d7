//! Parse one file once with one parser and exit: for peak memory under `/usr/bin/time -v`.
//! `parse_once none FILE` only reads the file (the process's baseline).

use std::path::Path;
use step_parse_peers::{foxtrot_counts, foxtrot_failed_ids, vericad_parse, vericad_read_model};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let [_, which, file] = &args[..] else {
        eprintln!("usage: parse_once none|vericad|foxtrot|foxtrot_failed|read_model FILE");
        std::process::exit(2);
    };
    let bytes = std::fs::read(file).expect("read input");
    match which.as_str() {
        "none" => println!("{} bytes", bytes.len()),
        "vericad" => println!("{} entities", vericad_parse(&bytes)),
        "foxtrot" => {
            let (ok, failed) = foxtrot_counts(&bytes);
            println!("{ok} typed entities, {failed} failed");
        }
        "foxtrot_failed" => {
            for id in foxtrot_failed_ids(&bytes) {
                println!("#{id}");
            }
        }
        "read_model" => println!("{} surfaces", vericad_read_model(Path::new(file))),
        _ => {
            eprintln!("unknown parser {which}");
            std::process::exit(2);
        }
    }
}
