//! RECTANGULAR_TRIMMED_SURFACE: the basis surface restricted to the parameter rectangle,
//! checked against the basis surface's analytic parametrization (ISO 10303-42) and, for a
//! B-spline basis, against the basis itself at the same parameters.

use vericad::geom::dist;
use vericad::io::step;

fn read(data: &str, angle_unit_degree: bool) -> vericad::model::Model {
    let units = if angle_unit_degree {
        "#90=(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.));
#91=PLANE_ANGLE_MEASURE_WITH_UNIT(PLANE_ANGLE_MEASURE(0.0174532925199433),#90);
#92=(CONVERSION_BASED_UNIT('DEGREE',#91)NAMED_UNIT(#93)PLANE_ANGLE_UNIT());
#93=DIMENSIONAL_EXPONENTS(0.,0.,0.,0.,0.,0.,0.);"
    } else {
        ""
    };
    let text = format!(
        "ISO-10303-21;\nHEADER;\nFILE_SCHEMA(('AUTOMOTIVE_DESIGN'));\nENDSEC;\nDATA;
#1=CARTESIAN_POINT('',(1.,2.,3.));
#2=DIRECTION('',(0.,0.,1.));
#3=DIRECTION('',(1.,0.,0.));
#4=AXIS2_PLACEMENT_3D('',#1,#2,#3);
{units}
{data}
ENDSEC;\nEND-ISO-10303-21;\n"
    );
    step::from_str(&text, "rts.step").unwrap_or_else(|e| panic!("{e}"))
}

/// Every point of the converted surface on a 17×17 grid, mapped back through `inverse` to
/// the basis parameters `(u, v)` and re-evaluated with `sigma`: equal within 1e-14 relative,
/// and inside the rectangle; the rectangle's corners are reached.
fn check(
    m: &vericad::model::Model,
    sigma: impl Fn(f64, f64) -> [f64; 3],
    inverse: impl Fn(&[f64; 3]) -> (f64, f64),
    rect: [f64; 4],
) {
    assert_eq!(m.surfaces.len(), 1, "{:?}", m.warnings);
    let s = &m.surfaces[0].nurbs;
    let (u0, u1, v0, v1) = s.hom.domain();
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for i in 0..=16 {
        for j in 0..=16 {
            let p = s.eval(
                &(u0 + (u1 - u0) * i as f64 / 16.0),
                &(v0 + (v1 - v0) * j as f64 / 16.0),
            );
            let (u, v) = inverse(&p);
            let q = sigma(u, v);
            assert!(dist(&p, &q) < 1e-13, "{p:?} vs {q:?}");
            lo = [lo[0].min(u), lo[1].min(v)];
            hi = [hi[0].max(u), hi[1].max(v)];
        }
    }
    for (x, y) in lo
        .iter()
        .chain(&hi)
        .zip([rect[0], rect[2], rect[1], rect[3]])
    {
        assert!((x - y).abs() < 1e-12, "{lo:?} {hi:?} vs {rect:?}");
    }
}

#[test]
fn a_cylinder_piece() {
    let m = read(
        "#5=CYLINDRICAL_SURFACE('',#4,2.);\n#6=RECTANGULAR_TRIMMED_SURFACE('',#5,0.5,2.5,-1.,3.,.T.,.T.);",
        false,
    );
    let sigma = |u: f64, v: f64| [1.0 + 2.0 * u.cos(), 2.0 + 2.0 * u.sin(), 3.0 + v];
    let inverse = |p: &[f64; 3]| ((p[1] - 2.0).atan2(p[0] - 1.0), p[2] - 3.0);
    check(&m, sigma, inverse, [0.5, 2.5, -1.0, 3.0]);
}

#[test]
fn a_sphere_piece_in_degrees() {
    let m = read(
        "#5=SPHERICAL_SURFACE('',#4,3.);\n#6=RECTANGULAR_TRIMMED_SURFACE('',#5,10.,130.,-20.,60.,.T.,.T.);",
        true,
    );
    let sigma = |u: f64, v: f64| {
        [
            1.0 + 3.0 * v.cos() * u.cos(),
            2.0 + 3.0 * v.cos() * u.sin(),
            3.0 + 3.0 * v.sin(),
        ]
    };
    let inverse = |p: &[f64; 3]| {
        let (x, y, z) = (p[0] - 1.0, p[1] - 2.0, p[2] - 3.0);
        (y.atan2(x), z.atan2((x * x + y * y).sqrt()))
    };
    let d = std::f64::consts::PI / 180.0;
    check(
        &m,
        sigma,
        inverse,
        [10.0 * d, 130.0 * d, -20.0 * d, 60.0 * d],
    );
}

#[test]
fn a_torus_and_a_cone_piece() {
    let m = read(
        "#5=TOROIDAL_SURFACE('',#4,5.,1.5);\n#6=RECTANGULAR_TRIMMED_SURFACE('',#5,-1.,1.,0.25,2.,.T.,.T.);",
        false,
    );
    let sigma = |u: f64, v: f64| {
        let r = 5.0 + 1.5 * v.cos();
        [1.0 + r * u.cos(), 2.0 + r * u.sin(), 3.0 + 1.5 * v.sin()]
    };
    let inverse = |p: &[f64; 3]| {
        let (x, y, z) = (p[0] - 1.0, p[1] - 2.0, p[2] - 3.0);
        (y.atan2(x), z.atan2((x * x + y * y).sqrt() - 5.0))
    };
    check(&m, sigma, inverse, [-1.0, 1.0, 0.25, 2.0]);

    let m = read(
        "#5=CONICAL_SURFACE('',#4,1.,0.3);\n#6=RECTANGULAR_TRIMMED_SURFACE('',#5,0.,1.,0.5,2.,.T.,.T.);",
        false,
    );
    let t = 0.3f64.tan();
    let sigma = |u: f64, v: f64| {
        let r = 1.0 + v * t;
        [1.0 + r * u.cos(), 2.0 + r * u.sin(), 3.0 + v]
    };
    let inverse = |p: &[f64; 3]| ((p[1] - 2.0).atan2(p[0] - 1.0), p[2] - 3.0);
    check(&m, sigma, inverse, [0.0, 1.0, 0.5, 2.0]);
}

#[test]
fn a_plane_piece_and_a_bspline_piece() {
    let m = read(
        "#5=PLANE('',#4);\n#6=RECTANGULAR_TRIMMED_SURFACE('',#5,-2.,1.,0.5,4.,.T.,.T.);",
        false,
    );
    check(
        &m,
        |u, v| [1.0 + u, 2.0 + v, 3.0],
        |p| (p[0] - 1.0, p[1] - 2.0),
        [-2.0, 1.0, 0.5, 4.0],
    );

    // A bicubic-by-quadratic B-spline basis: the piece equals the basis at the same
    // parameters (knot insertion keeps the parametrization).
    let mut pts = String::new();
    let mut rows = Vec::new();
    for i in 0..5 {
        let mut row = Vec::new();
        for j in 0..3 {
            let id = 100 + i * 3 + j;
            let z = ((i * 7 + j * 3) % 5) as f64 * 0.3;
            pts += &format!("#{id}=CARTESIAN_POINT('',({}.,{}.,{z}));\n", i, j);
            row.push(format!("#{id}"));
        }
        rows.push(format!("({})", row.join(",")));
    }
    let data = format!(
        "{pts}#5=B_SPLINE_SURFACE_WITH_KNOTS('',3,2,({}),.UNSPECIFIED.,.F.,.F.,.F.,(4,1,4),(3,3),(0.,0.5,2.),(0.,1.),.UNSPECIFIED.);\n#6=RECTANGULAR_TRIMMED_SURFACE('',#5,0.25,1.5,0.2,0.7,.T.,.T.);",
        rows.join(",")
    );
    let basis = read(
        &format!(
            "{pts}#5=B_SPLINE_SURFACE_WITH_KNOTS('',3,2,({}),.UNSPECIFIED.,.F.,.F.,.F.,(4,1,4),(3,3),(0.,0.5,2.),(0.,1.),.UNSPECIFIED.);",
            rows.join(",")
        ),
        false,
    );
    let m = read(&data, false);
    assert_eq!(m.surfaces.len(), 1, "{:?}", m.warnings);
    let (s, b) = (&m.surfaces[0].nurbs, &basis.surfaces[0].nurbs);
    assert_eq!(s.hom.domain(), (0.25, 1.5, 0.2, 0.7));
    for i in 0..=10 {
        for j in 0..=10 {
            let (u, v) = (0.25 + 1.25 * i as f64 / 10.0, 0.2 + 0.5 * j as f64 / 10.0);
            assert!(dist(&s.eval(&u, &v), &b.eval(&u, &v)) < 1e-14);
        }
    }
}
