//! 3D pictures as SVG: shaded triangles, polylines and point markers seen along a chosen
//! direction (orthographic), with a title, a legend and a scale bar in model units.
//!
//! Triangles are drawn far to near (painter's algorithm on their centroids' depth), shaded by
//! the angle between their normal and the view direction (two-sided, so reversed faces look
//! the same); polylines and markers are drawn on top of every triangle, so curves behind a
//! face stay visible. The drawing keeps the model's true aspect.

use super::svg::xml_escape;
use std::fmt::Write;

/// The view: looking from azimuth `azimuth_deg` (about +z, from +x towards +y) and elevation
/// `elevation_deg` (above the xy plane) towards the scene; +z points up on the page unless the
/// view is straight along it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    pub azimuth_deg: f64,
    pub elevation_deg: f64,
}

impl Default for View {
    fn default() -> Self {
        View {
            azimuth_deg: -60.0,
            elevation_deg: 25.0,
        }
    }
}

impl View {
    /// Parse `"AZ,EL"` in degrees; the elevation within [−90, 90].
    pub fn parse(s: &str) -> Result<View, String> {
        let parts: Vec<&str> = s.split(',').map(str::trim).collect();
        let nums: Vec<f64> = parts.iter().filter_map(|p| p.parse().ok()).collect();
        match nums[..] {
            [a, e] if parts.len() == 2 && a.is_finite() && (-90.0..=90.0).contains(&e) => {
                Ok(View {
                    azimuth_deg: a,
                    elevation_deg: e,
                })
            }
            _ => Err(format!(
                "view must be AZIMUTH,ELEVATION in degrees with the elevation in [-90, 90], not {s:?}"
            )),
        }
    }

    /// Unit vectors: towards the viewer, page right, page up.
    pub fn frame(&self) -> [[f64; 3]; 3] {
        let (a, e) = (
            self.azimuth_deg.to_radians(),
            self.elevation_deg.to_radians(),
        );
        let v = [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()];
        let r = [-a.sin(), a.cos(), 0.0];
        let u = [
            v[1] * r[2] - v[2] * r[1],
            v[2] * r[0] - v[0] * r[2],
            v[0] * r[1] - v[1] * r[0],
        ];
        [v, r, u]
    }
}

/// An RGB colour.
pub type Rgb = [u8; 3];

/// The colours every picture uses for what is proven (within its tolerance), what is not
/// proven (or left open), and face borders; and the page size.
pub const PROVEN: Rgb = [0, 150, 70];
pub const NOT_PROVEN: Rgb = [215, 30, 30];
pub const BORDER: Rgb = [90, 90, 90];
pub const PAGE: [f64; 2] = [1100.0, 800.0];

/// What to draw.
#[derive(Clone, Debug, Default)]
pub struct Scene {
    pub title: String,
    /// Triangles with their base colour (shaded by orientation).
    pub triangles: Vec<([[f64; 3]; 3], Rgb)>,
    /// Thin lines drawn over the triangles (face borders).
    pub outlines: Vec<(Vec<[f64; 3]>, Rgb)>,
    /// Curves, drawn over everything else.
    pub polylines: Vec<(Vec<[f64; 3]>, Rgb)>,
    pub markers: Vec<([f64; 3], Rgb)>,
    /// Small dots (joints along a curve), drawn with the curves.
    pub dots: Vec<([f64; 3], Rgb)>,
    /// Legend rows: swatch colour and text.
    pub legend: Vec<(Rgb, String)>,
    /// The length unit for the scale bar (`None`: "model units").
    pub unit: Option<String>,
}

impl Scene {
    /// A surface sampled on a `grid × grid` lattice of its domain as triangles of `colour`,
    /// and its border curve (through the lattice's border points) in `border`.
    pub fn add_surface(
        &mut self,
        s: &crate::spline::NurbsSurface<f64, 3>,
        grid: usize,
        colour: Rgb,
        border: Rgb,
    ) {
        let n = grid.max(1);
        let g: Vec<Vec<[f64; 3]>> = super::surface_grid(s, n)
            .chunks(n + 1)
            .map(<[_]>::to_vec)
            .collect();
        for i in 0..n {
            for j in 0..n {
                let (a, b, c, d) = (g[i][j], g[i + 1][j], g[i + 1][j + 1], g[i][j + 1]);
                self.triangles.push(([a, b, c], colour));
                self.triangles.push(([a, c, d], colour));
            }
        }
        let ring: Vec<[f64; 3]> = (0..=n)
            .map(|i| g[i][0])
            .chain((0..=n).map(|j| g[n][j]))
            .chain((0..=n).rev().map(|i| g[i][n]))
            .chain((0..=n).rev().map(|j| g[0][j]))
            .collect();
        self.outlines.push((ring, border));
    }
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn hex(c: Rgb) -> String {
    format!("#{:02x}{:02x}{:02x}", c[0], c[1], c[2])
}

/// The largest of 1, 2, 5 × 10^k not above `x` (`x > 0`).
pub fn nice_length(x: f64) -> f64 {
    let p = 10f64.powf(x.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * p)
        .find(|l| *l <= x)
        .unwrap_or(p)
}

/// The page mapping: model point → page coordinates (x right, y down) and depth.
pub struct Projection {
    frame: [[f64; 3]; 3],
    scale: f64,
    offset: [f64; 2],
    height: f64,
}

impl Projection {
    /// Fit every finite point of `pts` into a `width × height` page with `margin` around
    /// (the legend's band on the right included in `margin_right`).
    pub fn fit(
        view: &View,
        pts: &[[f64; 3]],
        width: f64,
        height: f64,
        margin: f64,
        margin_right: f64,
    ) -> Projection {
        let frame = view.frame();
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for p in pts.iter().filter(|p| p.iter().all(|c| c.is_finite())) {
            let s = [dot(p, &frame[1]), dot(p, &frame[2])];
            for k in 0..2 {
                lo[k] = lo[k].min(s[k]);
                hi[k] = hi[k].max(s[k]);
            }
        }
        if lo[0] > hi[0] {
            (lo, hi) = ([-1.0; 2], [1.0; 2]);
        }
        let span = [(hi[0] - lo[0]).max(1e-300), (hi[1] - lo[1]).max(1e-300)];
        let room = [width - margin - margin_right, height - 2.0 * margin];
        let scale = (room[0] / span[0]).min(room[1] / span[1]);
        // Centre the drawing in its room.
        let offset = [
            margin + 0.5 * (room[0] - scale * span[0]) - scale * lo[0],
            margin + 0.5 * (room[1] - scale * span[1]) - scale * lo[1],
        ];
        Projection {
            frame,
            scale,
            offset,
            height,
        }
    }
    /// Page coordinates of `p`.
    pub fn page(&self, p: &[f64; 3]) -> [f64; 2] {
        let (x, y) = (dot(p, &self.frame[1]), dot(p, &self.frame[2]));
        [
            self.offset[0] + self.scale * x,
            self.height - (self.offset[1] + self.scale * y),
        ]
    }
    /// Distance towards the viewer.
    pub fn depth(&self, p: &[f64; 3]) -> f64 {
        dot(p, &self.frame[0])
    }
    /// Page units per model unit.
    pub fn scale(&self) -> f64 {
        self.scale
    }
}

/// Lambert shade of `base` for a triangle facing the viewer at `|cos|`.
fn shade(base: Rgb, cos: f64) -> Rgb {
    let f = 0.35 + 0.65 * cos.abs().min(1.0);
    base.map(|c| (c as f64 * f).round().clamp(0.0, 255.0) as u8)
}

fn points_attr(pr: &Projection, pts: &[[f64; 3]]) -> String {
    let mut s = String::new();
    for p in pts {
        let q = pr.page(p);
        let _ = write!(s, "{:.2},{:.2} ", q[0], q[1]);
    }
    s.trim_end().to_string()
}

/// Render `scene` seen along `view` as an SVG document of `width × height`.
pub fn render(scene: &Scene, view: &View, width: f64, height: f64) -> String {
    let all: Vec<[f64; 3]> = scene
        .triangles
        .iter()
        .flat_map(|t| t.0)
        .chain(scene.outlines.iter().flat_map(|l| l.0.iter().copied()))
        .chain(scene.polylines.iter().flat_map(|l| l.0.iter().copied()))
        .chain(scene.markers.iter().map(|m| m.0))
        .chain(scene.dots.iter().map(|m| m.0))
        .collect();
    let (margin, legend_w) = (40.0, 340.0);
    let pr = Projection::fit(view, &all, width, height, margin, legend_w);
    let v = pr.frame[0];
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    // Triangles, far to near.
    let finite = |t: &[[f64; 3]; 3]| t.iter().flatten().all(|c| c.is_finite());
    let mut order: Vec<(f64, usize)> = scene
        .triangles
        .iter()
        .enumerate()
        .filter(|(_, t)| finite(&t.0))
        .map(|(i, t)| {
            let c: [f64; 3] = std::array::from_fn(|k| (t.0[0][k] + t.0[1][k] + t.0[2][k]) / 3.0);
            (pr.depth(&c), i)
        })
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let _ = writeln!(s, r#"<g id="faces" stroke-linejoin="round">"#);
    for (_, i) in order {
        let (t, base) = &scene.triangles[i];
        let e1: [f64; 3] = std::array::from_fn(|k| t[1][k] - t[0][k]);
        let e2: [f64; 3] = std::array::from_fn(|k| t[2][k] - t[0][k]);
        let n = [
            e1[1] * e2[2] - e1[2] * e2[1],
            e1[2] * e2[0] - e1[0] * e2[2],
            e1[0] * e2[1] - e1[1] * e2[0],
        ];
        let len = dot(&n, &n).sqrt();
        let cos = if len > 0.0 { dot(&n, &v) / len } else { 1.0 };
        let c = hex(shade(*base, cos));
        let _ = writeln!(
            s,
            r#"<polygon points="{}" fill="{c}" stroke="{c}" stroke-width="0.6"/>"#,
            points_attr(&pr, t)
        );
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(s, r#"<g id="outlines" fill="none" stroke-width="0.8">"#);
    for (pts, c) in &scene.outlines {
        let _ = writeln!(
            s,
            r#"<polyline points="{}" stroke="{}"/>"#,
            points_attr(&pr, pts),
            hex(*c)
        );
    }
    let _ = writeln!(s, "</g>");
    let _ = writeln!(
        s,
        r#"<g id="curves" fill="none" stroke-width="2.2" stroke-linejoin="round" stroke-linecap="round">"#
    );
    for (pts, c) in &scene.polylines {
        let _ = writeln!(
            s,
            r#"<polyline points="{}" stroke="{}"/>"#,
            points_attr(&pr, pts),
            hex(*c)
        );
    }
    let _ = writeln!(s, "</g>");
    for (id, list, r) in [("dots", &scene.dots, 2.0), ("markers", &scene.markers, 4.5)] {
        let _ = writeln!(s, r#"<g id="{id}" stroke="black" stroke-width="0.6">"#);
        for (p, c) in list {
            let q = pr.page(p);
            if q.iter().all(|x| x.is_finite()) {
                let _ = writeln!(
                    s,
                    r#"<circle cx="{:.2}" cy="{:.2}" r="{r}" fill="{}"/>"#,
                    q[0],
                    q[1],
                    hex(*c)
                );
            }
        }
        let _ = writeln!(s, "</g>");
    }
    // Title, legend, scale bar, view.
    let _ = writeln!(
        s,
        r#"<text x="{margin}" y="26" font-family="sans-serif" font-size="15">{}</text>"#,
        xml_escape(&scene.title)
    );
    let lx = width - legend_w + 10.0;
    let _ = writeln!(
        s,
        r#"<g id="legend" font-family="sans-serif" font-size="12">"#
    );
    for (k, (c, text)) in scene.legend.iter().enumerate() {
        let y = margin + 22.0 * k as f64;
        let _ = writeln!(
            s,
            r#"<rect x="{lx}" y="{:.1}" width="16" height="10" fill="{}" stroke="black" stroke-width="0.5"/><text x="{:.1}" y="{:.1}">{}</text>"#,
            y,
            hex(*c),
            lx + 24.0,
            y + 10.0,
            xml_escape(text)
        );
    }
    let _ = writeln!(s, "</g>");
    let room = 0.3 * (width - margin - legend_w);
    if pr.scale > 0.0 && pr.scale.is_finite() {
        let len = nice_length(room / pr.scale);
        let px = len * pr.scale;
        let y = height - 18.0;
        let unit = scene.unit.as_deref().unwrap_or("(model units)");
        let _ = writeln!(
            s,
            r#"<g id="scale" font-family="sans-serif" font-size="12"><line x1="{margin}" y1="{y}" x2="{:.2}" y2="{y}" stroke="black" stroke-width="2"/><text x="{margin}" y="{:.1}">{} {}</text></g>"#,
            margin + px,
            y - 6.0,
            len,
            xml_escape(unit)
        );
    }
    let _ = writeln!(
        s,
        r##"<text x="{margin}" y="44" font-family="sans-serif" font-size="11" fill="#555">view: azimuth {}°, elevation {}° (orthographic; curves drawn over the faces)</text>"##,
        view.azimuth_deg, view.elevation_deg
    );
    let _ = writeln!(s, "</svg>");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// From azimuth 0, elevation 0 the viewer is on +x: +y is to the right, +z up.
    #[test]
    fn the_frame_follows_the_angles() {
        let f = View {
            azimuth_deg: 0.0,
            elevation_deg: 0.0,
        }
        .frame();
        let close = |a: &[f64; 3], b: [f64; 3]| (0..3).all(|k| (a[k] - b[k]).abs() < 1e-15);
        assert!(close(&f[0], [1.0, 0.0, 0.0]) && close(&f[1], [0.0, 1.0, 0.0]));
        assert!(close(&f[2], [0.0, 0.0, 1.0]));
        // From straight above (elevation 90), azimuth 90: x runs to the left, so y runs down
        // the page (the view stays right-handed: right × up = towards the viewer).
        let f = View {
            azimuth_deg: 90.0,
            elevation_deg: 90.0,
        }
        .frame();
        assert!(close(&f[0], [0.0, 0.0, 1.0]) && close(&f[1], [-1.0, 0.0, 0.0]));
        assert!(close(&f[2], [0.0, -1.0, 0.0]));
    }

    /// The fit keeps the true aspect and puts the extreme points on the margins.
    #[test]
    fn the_fit_keeps_the_aspect() {
        let v = View {
            azimuth_deg: 0.0,
            elevation_deg: 0.0,
        };
        // A 2 × 1 rectangle in the yz plane on a 400 × 400 page, 40 margin: scale 160.
        let pts = [[0.0, 0.0, 0.0], [0.0, 2.0, 1.0]];
        let pr = Projection::fit(&v, &pts, 400.0, 400.0, 40.0, 40.0);
        assert_eq!(pr.scale(), 160.0);
        assert_eq!(pr.page(&pts[0]), [40.0, 280.0]);
        assert_eq!(pr.page(&pts[1]), [360.0, 120.0]);
        assert_eq!(pr.depth(&[3.0, 0.0, 0.0]), 3.0);
    }

    #[test]
    fn nice_lengths() {
        assert_eq!(nice_length(7.3), 5.0);
        assert_eq!(nice_length(0.0031), 0.002);
        assert_eq!(nice_length(100.0), 100.0);
        assert_eq!(nice_length(19.9), 10.0);
    }

    #[test]
    fn views_parse() {
        assert_eq!(
            View::parse("30, -10"),
            Ok(View {
                azimuth_deg: 30.0,
                elevation_deg: -10.0
            })
        );
        for bad in ["30", "a,b", "1,2,3", "0,91", "nan,0", ""] {
            assert!(View::parse(bad).is_err(), "{bad}");
        }
    }

    /// Triangles come out far to near: the nearer one is drawn last; curves after faces.
    #[test]
    fn painter_order_and_layers() {
        let tri = |x: f64| [[x, 0.0, 0.0], [x, 1.0, 0.0], [x, 0.0, 1.0]];
        let scene = Scene {
            title: "t <&>".into(),
            triangles: vec![(tri(1.0), [200, 0, 0]), (tri(-1.0), [0, 0, 200])],
            polylines: vec![(vec![[0.0, 0.0, 0.0], [0.0, 1.0, 1.0]], [0, 160, 0])],
            legend: vec![([0, 160, 0], "certified".into())],
            ..Default::default()
        };
        let v = View {
            azimuth_deg: 0.0,
            elevation_deg: 0.0,
        };
        let s = render(&scene, &v, 600.0, 400.0);
        // Viewer on +x: the triangle at x = −1 is farther, drawn first; both face the viewer
        // (full shade).
        let blue = s.find("#0000c8").unwrap();
        let red = s.find("#c80000").unwrap();
        assert!(blue < red);
        assert!(s.find("<g id=\"curves\"").unwrap() > red);
        assert!(s.contains("t &lt;&amp;&gt;") && s.contains(">certified</text>"));
        assert!(s.starts_with("<svg") && s.trim_end().ends_with("</svg>"));
    }
}
