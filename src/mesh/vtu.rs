//! ParaView output: VTK XML UnstructuredGrid (`.vtu`) with optional nodal and element
//! fields, and `.pvd` collections for time series.
//!
//! Files are binary by default, as ParaView writes them: the arrays follow the XML header as
//! appended raw data, each zlib-compressed in 32 KiB blocks (`compressor=
//! "vtkZLibDataCompressor"`, UInt64 block headers); [`VtuFormat::Ascii`] writes plain text.
//! Hexahedra are VTK_HEXAHEDRON (type 12), whose node order is gmsh's. Components are named:
//! vectors `x`, `y`, `z`; symmetric tensors (stress, strain) are 6 components in ParaView's
//! order `xx`, `yy`, `zz`, `xy`, `yz`, `zx`. A time value (s) can be stored as the field
//! `TimeValue`, which ParaView shows as the data set's time.

use super::Mesh;
use crate::atomic::write_atomic;
use crate::error::{Error, Result};
use flate2::{write::ZlibEncoder, Compression};
use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

/// How the arrays of a `.vtu` file are stored.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum VtuFormat {
    /// Appended raw binary, zlib-compressed (ParaView's own choice; about a tenth of ASCII).
    #[default]
    Binary,
    /// Plain text, one entity per line.
    Ascii,
}

/// Uncompressed size of one compressed block, bytes (VTK's default).
const BLOCK: usize = 32 * 1024;

/// Names of the components of a field with `n` components (none for scalars).
fn component_names(n: usize) -> &'static [&'static str] {
    match n {
        3 => &["x", "y", "z"],
        6 => &["xx", "yy", "zz", "xy", "yz", "zx"],
        _ => &[],
    }
}

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

/// One array of the file, whatever its element type.
enum Values<'a> {
    F64(&'a [f64]),
    I64(Vec<i64>),
    U8(Vec<u8>),
}

impl Values<'_> {
    fn vtk_type(&self) -> &'static str {
        match self {
            Values::F64(_) => "Float64",
            Values::I64(_) => "Int64",
            Values::U8(_) => "UInt8",
        }
    }

    /// Little-endian bytes.
    fn bytes(&self) -> Vec<u8> {
        match self {
            Values::F64(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            Values::I64(v) => v.iter().flat_map(|x| x.to_le_bytes()).collect(),
            Values::U8(v) => v.clone(),
        }
    }

    /// Text, `per_line` values a line.
    fn text(&self, per_line: usize) -> String {
        let items: Vec<String> = match self {
            Values::F64(v) => v.iter().map(|x| format!("{x:e}")).collect(),
            Values::I64(v) => v.iter().map(|x| x.to_string()).collect(),
            Values::U8(v) => v.iter().map(|x| x.to_string()).collect(),
        };
        let mut s = String::new();
        for line in items.chunks(per_line.max(1)) {
            s.push_str("          ");
            s.push_str(&line.join(" "));
            s.push('\n');
        }
        s
    }
}

/// The `<DataArray>` attributes and values of one array.
struct Array<'a> {
    name: &'a str,
    components: usize,
    tuples: Option<usize>,
    /// Values a line in ASCII.
    per_line: usize,
    values: Values<'a>,
}

/// zlib-compressed `bytes` with VTK's block header (block count, block size, size of a
/// partial last block, compressed sizes; all UInt64).
fn compressed(bytes: &[u8]) -> Result<Vec<u8>> {
    let blocks: Vec<Vec<u8>> = bytes
        .chunks(BLOCK)
        .map(|chunk| {
            let mut z = ZlibEncoder::new(Vec::new(), Compression::default());
            z.write_all(chunk)?;
            z.finish()
        })
        .collect::<std::io::Result<_>>()
        .map_err(|e| Error::External(format!("vtu compression: {e}")))?;
    let mut out = Vec::new();
    for h in [blocks.len(), BLOCK, bytes.len() % BLOCK] {
        out.extend((h as u64).to_le_bytes());
    }
    for b in &blocks {
        out.extend((b.len() as u64).to_le_bytes());
    }
    for b in blocks {
        out.extend(b);
    }
    Ok(out)
}

/// Writes the array's `<DataArray>` element into `xml`; binary values go to `appended`.
fn data_array(
    xml: &mut String,
    appended: &mut Vec<u8>,
    a: &Array,
    format: VtuFormat,
) -> Result<()> {
    let _ = write!(
        xml,
        "        <DataArray type=\"{}\" Name=\"{}\"",
        a.values.vtk_type(),
        a.name
    );
    if a.components > 1 {
        let _ = write!(xml, " NumberOfComponents=\"{}\"", a.components);
    }
    for (k, c) in component_names(a.components).iter().enumerate() {
        let _ = write!(xml, " ComponentName{k}=\"{c}\"");
    }
    if let Some(n) = a.tuples {
        let _ = write!(xml, " NumberOfTuples=\"{n}\"");
    }
    match format {
        VtuFormat::Ascii => {
            xml.push_str(" format=\"ascii\">\n");
            xml.push_str(&a.values.text(a.per_line));
            xml.push_str("        </DataArray>\n");
        }
        VtuFormat::Binary => {
            let _ = writeln!(xml, " format=\"appended\" offset=\"{}\"/>", appended.len());
            appended.extend(compressed(&a.values.bytes())?);
        }
    }
    Ok(())
}

fn field_array<'a>(f: &Field<'a>) -> Array<'a> {
    Array {
        name: f.name,
        components: f.components,
        tuples: None,
        per_line: f.components,
        values: Values::F64(f.values),
    }
}

/// An unstructured grid as the VTU writer takes it: points (m) and cells of one VTK type.
pub(crate) struct Grid<'a> {
    /// Point coordinates (x, y, z), m.
    pub(crate) points: &'a [[f64; 3]],
    /// Node indices of every cell, cell after cell.
    pub(crate) connectivity: Vec<i64>,
    /// Nodes per cell.
    pub(crate) per_cell: usize,
    /// VTK cell type (9 quad, 12 hexahedron).
    pub(crate) cell_type: u8,
}

impl Grid<'_> {
    fn cells(&self) -> usize {
        self.connectivity.len() / self.per_cell
    }
}

/// Checks the fields and the grid for [`grid_bytes`].
fn check_all(grid: &Grid, point_fields: &[Field], cell_fields: &[Field]) -> Result<()> {
    for f in point_fields {
        f.check(grid.points.len(), "point")?;
    }
    for f in cell_fields {
        f.check(grid.cells(), "cell")?;
    }
    super::check_finite_nodes(grid.points)
}

/// The mesh and fields as a `.vtu` file in `format`, with the data set's time `time` (s)
/// as the field `TimeValue` when given. Fails (and writes nothing) if a field has the wrong
/// length, an unsupported component count, a bad name or a non-finite value, or a node or
/// the time is not finite.
pub fn to_vtu_bytes(
    mesh: &Mesh,
    point_fields: &[Field],
    cell_fields: &[Field],
    time: Option<f64>,
    format: VtuFormat,
) -> Result<Vec<u8>> {
    let grid = Grid {
        points: &mesh.nodes,
        connectivity: mesh.hexes.iter().flatten().map(|&n| n as i64).collect(),
        per_cell: 8,
        cell_type: 12,
    };
    grid_bytes(&grid, point_fields, cell_fields, time, format)
}

/// [`to_vtu_bytes`] for any [`Grid`].
pub(crate) fn grid_bytes(
    grid: &Grid,
    point_fields: &[Field],
    cell_fields: &[Field],
    time: Option<f64>,
    format: VtuFormat,
) -> Result<Vec<u8>> {
    check_all(grid, point_fields, cell_fields)?;
    if let Some(t) = time.filter(|t| !t.is_finite()) {
        return Err(Error::Numerical(format!(
            "time {t} is not finite; not written"
        )));
    }
    let mut s = String::with_capacity(4096);
    let mut appended = Vec::new();
    s.push_str("<?xml version=\"1.0\"?>\n");
    s.push_str(
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\"",
    );
    if format == VtuFormat::Binary {
        s.push_str(" compressor=\"vtkZLibDataCompressor\"");
    }
    s.push_str(">\n  <UnstructuredGrid>\n");
    let time_value = time.map(|t| [t]);
    if let Some(t) = &time_value {
        s.push_str("    <FieldData>\n");
        let a = Array {
            name: "TimeValue",
            components: 1,
            tuples: Some(1),
            per_line: 1,
            values: Values::F64(t),
        };
        data_array(&mut s, &mut appended, &a, format)?;
        s.push_str("    </FieldData>\n");
    }
    let _ = writeln!(
        s,
        "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        grid.points.len(),
        grid.cells()
    );
    s.push_str("      <PointData>\n");
    for f in point_fields {
        data_array(&mut s, &mut appended, &field_array(f), format)?;
    }
    s.push_str("      </PointData>\n      <CellData>\n");
    for f in cell_fields {
        data_array(&mut s, &mut appended, &field_array(f), format)?;
    }
    s.push_str("      </CellData>\n      <Points>\n");
    data_array(
        &mut s,
        &mut appended,
        &field_array(&Field::vectors("Points", grid.points)),
        format,
    )?;
    s.push_str("      </Points>\n      <Cells>\n");
    let cells = [
        Array {
            name: "connectivity",
            components: 1,
            tuples: None,
            per_line: grid.per_cell,
            values: Values::I64(grid.connectivity.clone()),
        },
        Array {
            name: "offsets",
            components: 1,
            tuples: None,
            per_line: 1,
            values: Values::I64(
                (1..=grid.cells())
                    .map(|e| (grid.per_cell * e) as i64)
                    .collect(),
            ),
        },
        Array {
            name: "types",
            components: 1,
            tuples: None,
            per_line: 1,
            values: Values::U8(vec![grid.cell_type; grid.cells()]),
        },
    ];
    for a in &cells {
        data_array(&mut s, &mut appended, a, format)?;
    }
    s.push_str("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n");
    let mut out = s.into_bytes();
    if format == VtuFormat::Binary {
        out.extend_from_slice(b"  <AppendedData encoding=\"raw\">\n   _");
        out.extend(appended);
        out.extend_from_slice(b"\n  </AppendedData>\n");
    }
    out.extend_from_slice(b"</VTKFile>\n");
    Ok(out)
}

/// The mesh and fields as ASCII VTU text; see [`to_vtu_bytes`] for the failure modes.
pub fn to_vtu(mesh: &Mesh, point_fields: &[Field], cell_fields: &[Field]) -> Result<String> {
    let bytes = to_vtu_bytes(mesh, point_fields, cell_fields, None, VtuFormat::Ascii)?;
    String::from_utf8(bytes).map_err(|e| Error::Parse(format!("vtu text: {e}")))
}

/// Writes the mesh with nodal fields (`point_fields`, one entry per node) and element fields
/// (`cell_fields`, one entry per hexahedron) to a binary `.vtu` file, atomically.
///
/// Errors: see [`to_vtu_bytes`]; I/O errors name the path.
pub fn write(
    path: impl AsRef<Path>,
    mesh: &Mesh,
    point_fields: &[Field],
    cell_fields: &[Field],
) -> Result<()> {
    write_with(
        path,
        mesh,
        point_fields,
        cell_fields,
        None,
        VtuFormat::Binary,
    )
}

/// [`write`] in `format`, with the data set's time `time` (s) when given.
///
/// Errors: see [`to_vtu_bytes`]; I/O errors name the path.
pub fn write_with(
    path: impl AsRef<Path>,
    mesh: &Mesh,
    point_fields: &[Field],
    cell_fields: &[Field],
    time: Option<f64>,
    format: VtuFormat,
) -> Result<()> {
    write_atomic(
        path,
        &to_vtu_bytes(mesh, point_fields, cell_fields, time, format)?,
    )
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
