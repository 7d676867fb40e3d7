//! VTK XML PolyData (`.vtp`, viewable in ParaView) writer: surfaces tessellated on a regular
//! parameter grid, polylines, and per-point / per-cell arrays (patch id, error bound,
//! certified flag, …).

use std::fmt::Write;

/// A named scalar array attached to points or cells.
#[derive(Clone, Debug)]
pub struct Array {
    pub name: String,
    pub values: Vec<f64>,
}

/// Geometry to write: points, triangles and/or quads (`polys`), polylines (`lines`), and
/// data arrays (`point_data` has one value per point, `cell_data` one per poly then line).
#[derive(Clone, Debug, Default)]
pub struct PolyData {
    pub points: Vec<[f64; 3]>,
    pub polys: Vec<Vec<u32>>,
    pub lines: Vec<Vec<u32>>,
    pub point_data: Vec<Array>,
    pub cell_data: Vec<Array>,
}

impl PolyData {
    /// Add a surface sampled on an `n × n` grid of its domain as quads; returns the number
    /// of cells added.
    pub fn add_surface(&mut self, s: &crate::spline::NurbsSurface<f64, 3>, n: usize) -> usize {
        let base = self.points.len() as u32;
        self.points.extend(super::surface_grid(s, n));
        let id = |i: usize, j: usize| base + (i * (n + 1) + j) as u32;
        for i in 0..n {
            for j in 0..n {
                self.polys
                    .push(vec![id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)]);
            }
        }
        n * n
    }
    /// Add a polyline; returns its cell index among lines.
    pub fn add_polyline(&mut self, pts: &[[f64; 3]]) -> usize {
        let base = self.points.len() as u32;
        self.points.extend_from_slice(pts);
        self.lines
            .push((0..pts.len() as u32).map(|k| base + k).collect());
        self.lines.len() - 1
    }
}

fn data_array(s: &mut String, a: &Array) {
    let _ = write!(
        s,
        "        <DataArray type=\"Float64\" Name=\"{}\" format=\"ascii\">",
        a.name.replace(['"', '<', '>', '&'], "_")
    );
    for v in &a.values {
        let _ = write!(s, "{v:?} ");
    }
    s.push_str("</DataArray>\n");
}

fn connectivity(s: &mut String, cells: &[Vec<u32>]) {
    s.push_str("        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">");
    for c in cells {
        for v in c {
            let _ = write!(s, "{v} ");
        }
    }
    s.push_str(
        "</DataArray>\n        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">",
    );
    let mut o = 0;
    for c in cells {
        o += c.len();
        let _ = write!(s, "{o} ");
    }
    s.push_str("</DataArray>\n");
}

/// Render as a `.vtp` document.
pub fn render(p: &PolyData) -> String {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\">\n  <PolyData>\n",
    );
    let _ = writeln!(
        s,
        "    <Piece NumberOfPoints=\"{}\" NumberOfVerts=\"0\" NumberOfLines=\"{}\" NumberOfStrips=\"0\" NumberOfPolys=\"{}\">",
        p.points.len(),
        p.lines.len(),
        p.polys.len()
    );
    s.push_str("      <Points>\n        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">");
    for q in &p.points {
        let _ = write!(s, "{:?} {:?} {:?} ", q[0], q[1], q[2]);
    }
    s.push_str("</DataArray>\n      </Points>\n");
    s.push_str("      <PointData>\n");
    for a in &p.point_data {
        data_array(&mut s, a);
    }
    s.push_str("      </PointData>\n      <CellData>\n");
    for a in &p.cell_data {
        data_array(&mut s, a);
    }
    s.push_str("      </CellData>\n      <Lines>\n");
    connectivity(&mut s, &p.lines);
    s.push_str("      </Lines>\n      <Polys>\n");
    connectivity(&mut s, &p.polys);
    s.push_str("      </Polys>\n    </Piece>\n  </PolyData>\n</VTKFile>\n");
    s
}

/// A model's surfaces as one `.vtp` with a per-cell `patch_id` array.
pub fn model_to_vtp(m: &crate::model::Model, grid: usize) -> String {
    let mut p = PolyData::default();
    let mut ids = Vec::new();
    for (k, s) in m.surfaces.iter().enumerate() {
        let n = p.add_surface(&s.nurbs, grid);
        ids.extend(std::iter::repeat_n(k as f64, n));
    }
    for t in &m.triangulations {
        let base = p.points.len() as u32;
        p.points.extend_from_slice(&t.vertices);
        for tri in &t.triangles {
            p.polys.push(tri.iter().map(|v| base + v).collect());
            ids.push(-1.0);
        }
    }
    p.cell_data.push(Array {
        name: "patch_id".into(),
        values: ids,
    });
    render(&p)
}
