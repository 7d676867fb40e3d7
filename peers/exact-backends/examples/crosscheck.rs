//! Prints, per backend and kernel, how many exact results equal num-rational's, and the
//! size of those results (the bits of the largest numerator and denominator).
//! `cargo run --release --example crosscheck`

use exact_backends::backends::{BigRational, MalachiteRational, RBig, Ratio05, RugRational};
use exact_backends::{Exact, Inputs};

type Res = Vec<(&'static str, Vec<(String, String)>)>;

fn bits(decimal: &str) -> usize {
    let d = BigRational::from_integer(decimal.parse().expect("decimal"));
    d.numer().bits() as usize
}

fn row<T: Exact>(reference: &Res) {
    let got = Inputs::<T>::new().results();
    let cells: Vec<String> = reference
        .iter()
        .zip(&got)
        .map(|((_, r), (_, g))| {
            let same = r.iter().zip(g).filter(|(x, y)| x == y).count();
            format!("{same}/{}", r.len())
        })
        .collect();
    println!("| {} | {} |", T::NAME, cells.join(" | "));
}

fn main() {
    let reference = Inputs::<BigRational>::new().results();
    let signs = Inputs::<BigRational>::new().run_orient3d();
    let count = |s: i8| signs.iter().filter(|&&x| x == s).count();
    println!(
        "orient3d signs (num-rational): {} positive, {} negative, {} zero",
        count(1),
        count(-1),
        count(0)
    );
    println!("\nresult sizes (largest numerator / denominator, bits):");
    for (k, vals) in &reference {
        let n = vals
            .iter()
            .map(|(n, _)| bits(n.trim_start_matches('-')))
            .max()
            .unwrap_or(0);
        let d = vals.iter().map(|(_, d)| bits(d)).max().unwrap_or(0);
        println!(
            "  {k}: {} values, numerator ≤ {n} bits, denominator ≤ {d} bits",
            vals.len()
        );
    }
    let names: Vec<&str> = reference.iter().map(|(k, _)| *k).collect();
    println!("\nexact results equal to num-rational's:\n");
    println!("| backend | {} |", names.join(" | "));
    println!("|---|{}", "---|".repeat(names.len()));
    row::<BigRational>(&reference);
    row::<Ratio05>(&reference);
    row::<RugRational>(&reference);
    row::<RBig>(&reference);
    row::<MalachiteRational>(&reference);
}
