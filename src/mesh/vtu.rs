//! ParaView output: VTK XML UnstructuredGrid (`.vtu`, ASCII) with optional nodal and element
//! fields, and `.pvd` collections for time series.
//!
//! Hexahedra are VTK_HEXAHEDRON (type 12), whose node order is gmsh's. Symmetric tensors
//! (stress, strain) are written as 6 components in ParaView's order xx, yy, zz, xy, yz, xz.

use super::Mesh;
use crate::atomic::write_atomic;
use crate::error::{Error, Result};
use std::fmt::Write as _;
use std::path::Path;

/// A named field with `components` values per node or element, stored flat
/// (`values.len() == components * count`).
#[derive(Debug, Clone, Copy)]
pub struct Field<'a> {
    /// Name shown in ParaView, e.g. `displacement`.
    pub name: &'a str,
    /// Values per entity: 1 (scalar), 3 (vector) or 6 (symmetric tensor xx yy zz xy yz xz).
    pub components: usize,
    /// The values, entity by entity.
    pub values: &'a [f64],
}

impl<'a> Field<'a> {
    /// One value per entity (e.g. equivalent plastic strain, dimensionless).
    pub fn scalars(name: &'a str, values: &'a [f64]) -> Self {
        Field {
            name,
            components: 1,
            values,
        }
    }

    /// A 3-vector per entity (e.g. displacement in m, velocity in m/s).
    pub fn vectors(name: &'a str, values: &'a [[f64; 3]]) -> Self {
        Field {
            name,
            components: 3,
            values: values.as_flattened(),
        }
    }

    /// A symmetric tensor per entity as xx, yy, zz, xy, yz, xz (e.g. Cauchy stress in Pa).
    pub fn sym_tensors(name: &'a str, values: &'a [[f64; 6]]) -> Self {
        Field {
            name,
            components: 6,
            values: values.as_flattened(),
        }
    }

    fn check(&self, count: usize, kind: &str) -> Result<()> {
        if self.name.is_empty() || self.name.contains(['"', '<', '>', '&']) {
            return Err(Error::invalid(
                format!("{kind} field name"),
                format!("{:?}", self.name),
                "non-empty, without quotes, <, > or &",
            ));
        }
        if ![1, 3, 6].contains(&self.components) {
            return Err(Error::invalid(
                format!("{kind} field {}.components", self.name),
                self.components,
                "1, 3 or 6",
            ));
        }
        if self.values.len() != self.components * count {
            return Err(Error::invalid(
                format!("{kind} field {} length", self.name),
                self.values.len(),
                format!("{} x {count} values", self.components),
            ));
        }
        if let Some(k) = self.values.iter().position(|v| !v.is_finite()) {
            return Err(Error::Numerical(format!(
                "{kind} field {} has the non-finite value {} at {kind} {}; not written",
                self.name,
                self.values[k],
                k / self.components
            )));
        }
        Ok(())
    }
}

fn data_array(s: &mut String, f: &Field) {
    let _ = writeln!(
        s,
        "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">",
        f.name, f.components
    );
    for chunk in f.values.chunks(f.components) {
        s.push_str("          ");
        for (k, v) in chunk.iter().enumerate() {
            if k > 0 {
                s.push(' ');
            }
            let _ = write!(s, "{v:e}");
        }
        s.push('\n');
    }
    s.push_str("        </DataArray>\n");
}

/// The mesh and fields as VTU text. Fails (and writes nothing) if a field has the wrong
/// length, an unsupported component count, a bad name or a non-finite value, or a node is
/// not finite.
pub fn to_vtu(mesh: &Mesh, point_fields: &[Field], cell_fields: &[Field]) -> Result<String> {
    for f in point_fields {
        f.check(mesh.nodes.len(), "point")?;
    }
    for f in cell_fields {
        f.check(mesh.hexes.len(), "cell")?;
    }
    if let Some(i) = mesh
        .nodes
        .iter()
        .position(|p| !p.iter().all(|v| v.is_finite()))
    {
        return Err(Error::Numerical(format!(
            "mesh node {i} is not finite; not written"
        )));
    }
    let mut s = String::with_capacity(80 * (mesh.nodes.len() + mesh.hexes.len()));
    s.push_str("<?xml version=\"1.0\"?>\n");
    s.push_str(
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\">\n  <UnstructuredGrid>\n",
    );
    let _ = writeln!(
        s,
        "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        mesh.nodes.len(),
        mesh.hexes.len()
    );
    s.push_str("      <PointData>\n");
    for f in point_fields {
        data_array(&mut s, f);
    }
    s.push_str("      </PointData>\n      <CellData>\n");
    for f in cell_fields {
        data_array(&mut s, f);
    }
    s.push_str("      </CellData>\n      <Points>\n");
    data_array(&mut s, &Field::vectors("Points", &mesh.nodes));
    s.push_str("      </Points>\n      <Cells>\n");
    s.push_str("        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
    for h in &mesh.hexes {
        let _ = writeln!(
            s,
            "          {} {} {} {} {} {} {} {}",
            h[0], h[1], h[2], h[3], h[4], h[5], h[6], h[7]
        );
    }
    s.push_str("        </DataArray>\n");
    s.push_str("        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
    for e in 0..mesh.hexes.len() {
        let _ = writeln!(s, "          {}", 8 * (e + 1));
    }
    s.push_str("        </DataArray>\n");
    s.push_str("        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
    for _ in &mesh.hexes {
        s.push_str("          12\n");
    }
    s.push_str(
        "        </DataArray>\n      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n",
    );
    Ok(s)
}

/// Writes the mesh with nodal fields (`point_fields`, one entry per node) and element fields
/// (`cell_fields`, one entry per hexahedron) to a `.vtu` file, atomically.
///
/// Errors: see [`to_vtu`]; I/O errors name the path.
pub fn write(
    path: impl AsRef<Path>,
    mesh: &Mesh,
    point_fields: &[Field],
    cell_fields: &[Field],
) -> Result<()> {
    write_atomic(path, to_vtu(mesh, point_fields, cell_fields)?.as_bytes())
}

/// Writes a ParaView collection (`.pvd`) listing `(time in s, .vtu file name)` steps, so
/// ParaView plays them as a time series. File names are written as given (make them
/// relative to the `.pvd`'s directory).
pub fn write_pvd(path: impl AsRef<Path>, steps: &[(f64, String)]) -> Result<()> {
    let mut s = String::from(
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n  <Collection>\n",
    );
    for (t, file) in steps {
        if !t.is_finite() {
            return Err(Error::Numerical(format!(
                "time {t} of {file} is not finite"
            )));
        }
        if file.contains(['"', '<', '>', '&']) {
            return Err(Error::invalid(
                "pvd file name",
                file,
                "without quotes, <, > or &",
            ));
        }
        let _ = writeln!(s, "    <DataSet timestep=\"{t:e}\" file=\"{file}\"/>");
    }
    s.push_str("  </Collection>\n</VTKFile>\n");
    write_atomic(path, s.as_bytes())
}
