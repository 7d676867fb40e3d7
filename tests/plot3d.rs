//! Plot3D reader: every layout variant reads, faults are refused.

use vericad::io::plot3d::from_bytes;
use vericad::model::Model;

fn grid(ni: usize, nj: usize, o: f64) -> Vec<f64> {
    let mut v = Vec::new();
    for c in 0..3 {
        for j in 0..nj {
            for i in 0..ni {
                v.push(match c {
                    0 => i as f64 + o,
                    1 => j as f64 * 0.5,
                    _ => (i * j) as f64 * 0.25,
                });
            }
        }
    }
    v
}

fn check(m: &Model, blocks: &[(usize, usize, f64)]) {
    assert_eq!(m.surfaces.len(), blocks.len());
    for (s, &(ni, nj, o)) in m.surfaces.iter().zip(blocks) {
        // The surface interpolates the grid at integer parameters.
        for i in 0..ni {
            for j in 0..nj {
                let p = s.nurbs.eval(&(i as f64), &(j as f64));
                assert_eq!(p, [i as f64 + o, j as f64 * 0.5, (i * j) as f64 * 0.25]);
            }
        }
    }
}

#[test]
fn every_variant_reads() {
    let blocks = [(3usize, 4usize, 0.0), (2, 2, 10.0)];
    // ASCII multi-block, 3 dims, with iblank.
    let mut t = String::from("2\n3 4 1\n2 2 1\n");
    for &(ni, nj, o) in &blocks {
        for x in grid(ni, nj, o) {
            t += &format!("{x} ");
        }
        t += &"1 ".repeat(ni * nj);
    }
    check(&from_bytes(t.as_bytes(), "a").unwrap(), &blocks);
    // ASCII single block, 2 dims.
    let mut t = String::from("3 4\n");
    for x in grid(3, 4, 0.0) {
        t += &format!("{x:e} ");
    }
    check(&from_bytes(t.as_bytes(), "a").unwrap(), &blocks[..1]);
    // Binary, multi-block, double, with record markers.
    let rec = |p: Vec<u8>| {
        let mut r = (p.len() as i32).to_le_bytes().to_vec();
        r.extend(&p);
        r.extend((p.len() as i32).to_le_bytes());
        r
    };
    let mut b = rec(2i32.to_le_bytes().to_vec());
    b.extend(rec([3i32, 4, 1, 2, 2, 1]
        .iter()
        .flat_map(|x| x.to_le_bytes())
        .collect()));
    for &(ni, nj, o) in &blocks {
        b.extend(rec(grid(ni, nj, o)
            .iter()
            .flat_map(|x| x.to_le_bytes())
            .collect()));
    }
    check(&from_bytes(&b, "b").unwrap(), &blocks);
    // Binary, single block, single precision, no markers.
    let mut b: Vec<u8> = [3i32, 4, 1].iter().flat_map(|x| x.to_le_bytes()).collect();
    b.extend(
        grid(3, 4, 0.0)
            .iter()
            .flat_map(|x| (*x as f32).to_le_bytes()),
    );
    check(&from_bytes(&b, "c").unwrap(), &blocks[..1]);
    // Faults.
    assert!(from_bytes(b"2\n3 4 1\n", "d").is_err());
    assert!(from_bytes(&[1, 2, 3], "e").is_err());
}
