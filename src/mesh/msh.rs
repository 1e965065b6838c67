//! gmsh MSH files: a reader for versions 4.1 and 2.2 (ASCII and binary) and a 4.1 ASCII writer.
//!
//! The reader is our own rather than the mshio crate's: mshio parses only version 4.1 and
//! skips `$PhysicalNames`, and we need 2.2 and named physical groups. It is written for
//! hostile input: every declared count is checked against the bytes left in the file before
//! anything is allocated, every node reference is checked, and nothing panics.
//!
//! What becomes what: 8-node hexahedra (type 5) are the solid; 4-node quadrangles (type 3) in
//! a physical group become the face set of that group's name (and the node set of their
//! nodes); points (type 15) in a physical group add their node to the node set of that name;
//! 2-node lines (type 1) are ignored (the section reader `section::msh` keeps them);
//! any other element type is an error. Hexahedra whose corners are all inverted (a mirrored node order) are reoriented with a warning; partly
//! inverted or degenerate ones are an error naming the element.

use super::{quality::corner_scaled_jacobians, topology::boundary_faces, Mesh};
use crate::atomic::write_atomic;
use crate::error::{Error, Result};
use std::collections::{BTreeMap, HashMap};
use std::fmt::Write as _;
use std::path::Path;

/// A mesh read from a file, with the warnings the reader raised (e.g. reoriented elements).
#[derive(Debug, Clone)]
pub struct Loaded {
    /// The mesh.
    pub mesh: Mesh,
    /// Human-readable warnings; empty for a clean file.
    pub warnings: Vec<String>,
}

/// Reads a gmsh MSH file (4.1 or 2.2, ASCII or binary). See the module documentation for
/// what is kept. Errors name the file, the byte offset or element/node tag, and the problem.
pub fn read(path: impl AsRef<Path>) -> Result<Loaded> {
    let path = path.as_ref();
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    parse(&bytes, &path.display().to_string())
}

/// Parses the bytes of a MSH file; `name` is used in error messages.
pub fn parse(bytes: &[u8], name: &str) -> Result<Loaded> {
    assemble(parse_raw(bytes, name)?, name)
}

/// Reads the sections of a MSH file into [`Raw`], checking counts and references.
pub(super) fn parse_raw(bytes: &[u8], name: &str) -> Result<Raw> {
    let mut c = Cur {
        b: bytes,
        pos: 0,
        name,
        swap: false,
        size_t: 8,
    };
    let mut raw = Raw::default();
    let mut version = None;
    let mut binary = false;
    loop {
        c.skip_ws();
        if c.pos >= c.b.len() {
            break;
        }
        let section = c.token("section header")?;
        let Some(sec) = section.strip_prefix('$') else {
            return Err(c.err(format!(
                "expected a $Section header, found {:?}",
                clip(section)
            )));
        };
        if binary && version == Some(41) && matches!(sec, "Entities" | "Nodes" | "Elements") {
            c.skip_line(); // binary data starts right after the header line
        }
        match sec {
            "MeshFormat" => {
                let v = c.token("format version")?;
                let ft: u32 = c.ascii("file type")?;
                let ds: usize = c.ascii("data size")?;
                version = Some(match v {
                    "4.1" => 41,
                    "2.2" | "2.1" | "2" | "2.0" => 22,
                    _ => {
                        return Err(c.err(format!(
                            "unsupported MSH version {:?} (twoball reads 4.1 and 2.2)",
                            clip(v)
                        )))
                    }
                });
                if ds != 4 && ds != 8 {
                    return Err(c.err(format!("data size {ds} (allowed 4 or 8)")));
                }
                c.size_t = ds;
                binary = ft == 1;
                if binary {
                    c.skip_line();
                    let one = c.bytes(4, "endianness marker")?;
                    let le = i32::from_le_bytes([one[0], one[1], one[2], one[3]]);
                    let be = i32::from_be_bytes([one[0], one[1], one[2], one[3]]);
                    c.swap = match (le, be) {
                        (1, _) => cfg!(target_endian = "big"),
                        (_, 1) => cfg!(target_endian = "little"),
                        _ => return Err(c.err("binary endianness marker is not 1")),
                    };
                }
            }
            "PhysicalNames" => {
                let n: u64 = c.ascii("number of physical names")?;
                let n = c.cap(n, 8, "physical names")?;
                for _ in 0..n {
                    let dim: i32 = c.ascii("physical dimension")?;
                    let tag: i32 = c.ascii("physical tag")?;
                    let name = c.quoted()?;
                    raw.names.insert((dim, tag), name);
                }
            }
            "Entities" if version == Some(41) => read_entities(&mut c, binary, &mut raw)?,
            "Nodes" => match version {
                Some(41) => read_nodes41(&mut c, binary, &mut raw)?,
                Some(_) => read_nodes22(&mut c, binary, &mut raw)?,
                None => return Err(c.err("$Nodes before $MeshFormat")),
            },
            "Elements" => match version {
                Some(41) => read_elements41(&mut c, binary, &mut raw)?,
                Some(_) => read_elements22(&mut c, binary, &mut raw)?,
                None => return Err(c.err("$Elements before $MeshFormat")),
            },
            _ => {
                // Unknown or unused section: skip to its end marker.
                let end = format!("$End{sec}");
                c.skip_past(&end)?;
                continue;
            }
        }
        c.expect(&format!("$End{sec}"))?;
    }
    if version.is_none() {
        return Err(Error::Parse(format!(
            "{name}: no $MeshFormat section (not a MSH file?)"
        )));
    }
    Ok(raw)
}

/// Everything read from the file, before it is checked and turned into a [`Mesh`].
#[derive(Default)]
pub(crate) struct Raw {
    pub(super) names: HashMap<(i32, i32), String>,
    /// Physical tags of each (dim, entity tag) (version 4.1).
    entity_phys: HashMap<(i32, i32), Vec<i32>>,
    pub(super) nodes: Vec<(u64, [f64; 3])>,
    pub(super) hexes: Vec<(u64, [u64; 8])>,
    /// Quads, lines and points with the physical groups they belong to.
    pub(super) quads: Vec<(u64, [u64; 4], Vec<i32>)>,
    pub(super) lines: Vec<(u64, [u64; 2], Vec<i32>)>,
    points: Vec<(u64, u64, Vec<i32>)>,
}

/// A byte cursor that reads ASCII tokens or binary numbers and never reads past the end.
struct Cur<'a> {
    b: &'a [u8],
    pos: usize,
    name: &'a str,
    /// Binary data is in the other byte order than this machine's.
    swap: bool,
    size_t: usize,
}

fn clip(s: &str) -> String {
    s.chars().take(40).collect()
}

impl<'a> Cur<'a> {
    fn err(&self, what: impl std::fmt::Display) -> Error {
        Error::Parse(format!("{}: at byte {}: {what}", self.name, self.pos))
    }

    fn remaining(&self) -> usize {
        self.b.len() - self.pos
    }

    fn skip_ws(&mut self) {
        while self.pos < self.b.len() && self.b[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
    }

    fn skip_line(&mut self) {
        while self.pos < self.b.len() && self.b[self.pos] != b'\n' {
            self.pos += 1;
        }
        if self.pos < self.b.len() {
            self.pos += 1;
        }
    }

    fn token(&mut self, what: &str) -> Result<&'a str> {
        self.skip_ws();
        let start = self.pos;
        while self.pos < self.b.len() && !self.b[self.pos].is_ascii_whitespace() {
            self.pos += 1;
        }
        if start == self.pos {
            return Err(self.err(format!("unexpected end of file reading {what}")));
        }
        std::str::from_utf8(&self.b[start..self.pos])
            .map_err(|_| self.err(format!("non-text bytes where {what} was expected")))
    }

    fn ascii<T: std::str::FromStr>(&mut self, what: &str) -> Result<T> {
        let t = self.token(what)?;
        t.parse()
            .map_err(|_| self.err(format!("cannot read {what} from {:?}", clip(t))))
    }

    fn quoted(&mut self) -> Result<String> {
        self.skip_ws();
        if self.pos >= self.b.len() || self.b[self.pos] != b'"' {
            return Err(self.err("expected a quoted physical name"));
        }
        let start = self.pos + 1;
        let Some(len) = self.b[start..].iter().take(4096).position(|&c| c == b'"') else {
            return Err(self.err("unterminated physical name (or longer than 4096 bytes)"));
        };
        self.pos = start + len + 1;
        Ok(String::from_utf8_lossy(&self.b[start..start + len]).into_owned())
    }

    fn expect(&mut self, lit: &str) -> Result<()> {
        self.skip_ws();
        if self.b[self.pos..].starts_with(lit.as_bytes()) {
            self.pos += lit.len();
            Ok(())
        } else {
            Err(self.err(format!(
                "expected {lit} (wrong count or truncated section?)"
            )))
        }
    }

    fn skip_past(&mut self, lit: &str) -> Result<()> {
        let needle = lit.as_bytes();
        match self.b[self.pos..]
            .windows(needle.len())
            .position(|w| w == needle)
        {
            Some(i) => {
                self.pos += i + needle.len();
                Ok(())
            }
            None => Err(self.err(format!("missing {lit}"))),
        }
    }

    fn bytes(&mut self, n: usize, what: &str) -> Result<&'a [u8]> {
        if self.remaining() < n {
            return Err(self.err(format!("file ends inside {what}")));
        }
        let s = &self.b[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }

    fn bin<const N: usize>(&mut self, what: &str) -> Result<[u8; N]> {
        let mut a = [0u8; N];
        a.copy_from_slice(self.bytes(N, what)?);
        if self.swap {
            a.reverse();
        }
        Ok(a)
    }

    /// A `size_t` count or tag (4.1 headers and tags; ASCII or binary).
    fn size(&mut self, binary: bool, what: &str) -> Result<u64> {
        if !binary {
            return self.ascii(what);
        }
        Ok(if self.size_t == 8 {
            u64::from_ne_bytes(self.bin::<8>(what)?)
        } else {
            u32::from_ne_bytes(self.bin::<4>(what)?) as u64
        })
    }

    fn int(&mut self, binary: bool, what: &str) -> Result<i32> {
        if !binary {
            return self.ascii(what);
        }
        Ok(i32::from_ne_bytes(self.bin::<4>(what)?))
    }

    fn float(&mut self, binary: bool, what: &str) -> Result<f64> {
        if !binary {
            return self.ascii(what);
        }
        Ok(f64::from_ne_bytes(self.bin::<8>(what)?))
    }

    /// Checks a declared count against the bytes left (each item needs at least
    /// `min_bytes`), so a huge declared size is an error instead of a huge allocation.
    fn cap(&self, n: u64, min_bytes: usize, what: &str) -> Result<usize> {
        let most = self.remaining() / min_bytes.max(1);
        if n > most as u64 {
            return Err(self.err(format!(
                "declares {n} {what} but only {} bytes remain (wrong count or truncated file)",
                self.remaining()
            )));
        }
        Ok(n as usize)
    }

    fn item_bytes(&self, binary: bool, binary_size: usize) -> usize {
        if binary {
            binary_size
        } else {
            2
        }
    }
}

fn read_entities(c: &mut Cur, binary: bool, raw: &mut Raw) -> Result<()> {
    let counts = [
        c.size(binary, "number of points")?,
        c.size(binary, "number of curves")?,
        c.size(binary, "number of surfaces")?,
        c.size(binary, "number of volumes")?,
    ];
    for (dim, &count) in counts.iter().enumerate() {
        let n = c.cap(count, c.item_bytes(binary, 4 + 24), "entities")?;
        for _ in 0..n {
            let tag = c.int(binary, "entity tag")?;
            let n_coords = if dim == 0 { 3 } else { 6 };
            for _ in 0..n_coords {
                c.float(binary, "entity bounding box")?;
            }
            let np = c.size(binary, "number of physical tags")?;
            let np = c.cap(np, c.item_bytes(binary, 4), "physical tags")?;
            let mut phys = Vec::with_capacity(np);
            for _ in 0..np {
                phys.push(c.int(binary, "physical tag")?);
            }
            if dim > 0 {
                let nb = c.size(binary, "number of bounding entities")?;
                let nb = c.cap(nb, c.item_bytes(binary, 4), "bounding entities")?;
                for _ in 0..nb {
                    c.int(binary, "bounding entity tag")?;
                }
            }
            raw.entity_phys.insert((dim as i32, tag), phys);
        }
    }
    Ok(())
}

fn read_nodes41(c: &mut Cur, binary: bool, raw: &mut Raw) -> Result<()> {
    let blocks = c.size(binary, "number of node blocks")?;
    let _total = c.size(binary, "number of nodes")?;
    c.size(binary, "minimum node tag")?;
    c.size(binary, "maximum node tag")?;
    let st = c.size_t;
    let blocks = c.cap(blocks, c.item_bytes(binary, 8 + st), "node blocks")?;
    for _ in 0..blocks {
        let dim = c.int(binary, "node block dimension")?;
        c.int(binary, "node block entity tag")?;
        let parametric = c.int(binary, "node block parametric flag")?;
        let n = c.size(binary, "nodes in block")?;
        let params = if parametric == 1 {
            dim.clamp(0, 3) as usize
        } else {
            0
        };
        let n = c.cap(
            n,
            c.item_bytes(binary, st + 24) * if binary { 1 } else { 4 },
            "nodes",
        )?;
        let first = raw.nodes.len();
        for _ in 0..n {
            let tag = c.size(binary, "node tag")?;
            raw.nodes.push((tag, [0.0; 3]));
        }
        for k in 0..n {
            let mut x = [0.0; 3];
            for v in &mut x {
                *v = c.float(binary, "node coordinate")?;
            }
            for _ in 0..params {
                c.float(binary, "parametric coordinate")?;
            }
            raw.nodes[first + k].1 = x;
        }
    }
    Ok(())
}

fn read_nodes22(c: &mut Cur, binary: bool, raw: &mut Raw) -> Result<()> {
    let n: u64 = c.ascii("number of nodes")?;
    if binary {
        c.skip_line();
    }
    let n = c.cap(n, if binary { 28 } else { 8 }, "nodes")?;
    raw.nodes.reserve(n);
    for _ in 0..n {
        let tag = if binary {
            c.int(true, "node tag")? as i64
        } else {
            c.ascii::<i64>("node tag")?
        };
        let tag = u64::try_from(tag).map_err(|_| c.err(format!("negative node tag {tag}")))?;
        let mut x = [0.0; 3];
        for v in &mut x {
            *v = c.float(binary, "node coordinate")?;
        }
        raw.nodes.push((tag, x));
    }
    Ok(())
}

/// Number of nodes of the element types we read or skip; `None` for unsupported types.
fn nodes_of_type(t: i32) -> Option<usize> {
    match t {
        5 => Some(8),
        3 => Some(4),
        15 => Some(1),
        1 => Some(2),
        _ => None,
    }
}

fn unsupported(c: &Cur, elem: u64, t: i32) -> Error {
    let name = match t {
        2 => "3-node triangle",
        4 => "4-node tetrahedron",
        6 => "6-node prism",
        7 => "5-node pyramid",
        8 => "3-node line",
        9 => "6-node triangle",
        10 => "9-node quadrangle",
        11 => "10-node tetrahedron",
        12 => "27-node hexahedron",
        16 => "8-node quadrangle",
        17 => "20-node hexahedron",
        _ => "unknown type",
    };
    c.err(format!(
        "element {elem}: unsupported element type {t} ({name}); twoball reads 8-node \
         hexahedra (5) and 4-node quadrangles (3), and skips points (15) and lines (1)"
    ))
}

fn store(raw: &mut Raw, t: i32, tag: u64, nodes: &[u64], phys: Vec<i32>) {
    match t {
        5 => raw
            .hexes
            .push((tag, [0, 1, 2, 3, 4, 5, 6, 7].map(|i| nodes[i]))),
        3 => raw
            .quads
            .push((tag, [nodes[0], nodes[1], nodes[2], nodes[3]], phys)),
        15 => raw.points.push((tag, nodes[0], phys)),
        1 => raw.lines.push((tag, [nodes[0], nodes[1]], phys)),
        _ => {}
    }
}

fn read_elements41(c: &mut Cur, binary: bool, raw: &mut Raw) -> Result<()> {
    let blocks = c.size(binary, "number of element blocks")?;
    c.size(binary, "number of elements")?;
    c.size(binary, "minimum element tag")?;
    c.size(binary, "maximum element tag")?;
    let st = c.size_t;
    let blocks = c.cap(blocks, c.item_bytes(binary, 12 + st), "element blocks")?;
    let mut nodes = [0u64; 8];
    for _ in 0..blocks {
        let dim = c.int(binary, "element block dimension")?;
        let entity = c.int(binary, "element block entity tag")?;
        let t = c.int(binary, "element type")?;
        let n = c.size(binary, "elements in block")?;
        let Some(nn) = nodes_of_type(t) else {
            let first = if n > 0 {
                c.size(binary, "element tag").unwrap_or(0)
            } else {
                0
            };
            return Err(unsupported(c, first, t));
        };
        let n = c.cap(n, c.item_bytes(binary, st) * (1 + nn), "elements")?;
        let phys = raw
            .entity_phys
            .get(&(dim, entity))
            .cloned()
            .unwrap_or_default();
        for _ in 0..n {
            let tag = c.size(binary, "element tag")?;
            for v in nodes.iter_mut().take(nn) {
                *v = c.size(binary, "element node tag")?;
            }
            store(raw, t, tag, &nodes[..nn], phys.clone());
        }
    }
    Ok(())
}

fn read_elements22(c: &mut Cur, binary: bool, raw: &mut Raw) -> Result<()> {
    let total: u64 = c.ascii("number of elements")?;
    let total = c.cap(total, if binary { 12 } else { 8 }, "elements")?;
    let mut nodes = [0u64; 8];
    let to_u64 = |c: &Cur, v: i64, what: &str| {
        u64::try_from(v).map_err(|_| c.err(format!("negative {what} {v}")))
    };
    if !binary {
        for _ in 0..total {
            let tag = c.ascii::<i64>("element tag")?;
            let tag = to_u64(c, tag, "element tag")?;
            let t: i32 = c.ascii("element type")?;
            let ntags: u64 = c.ascii("number of element tags")?;
            let ntags = c.cap(ntags, 2, "element tags")?;
            let Some(nn) = nodes_of_type(t) else {
                return Err(unsupported(c, tag, t));
            };
            let mut phys = Vec::new();
            for k in 0..ntags {
                let v: i32 = c.ascii("element tag value")?;
                if k == 0 && v != 0 {
                    phys.push(v);
                }
            }
            for v in nodes.iter_mut().take(nn) {
                let x = c.ascii::<i64>("element node tag")?;
                *v = to_u64(c, x, "node tag")?;
            }
            store(raw, t, tag, &nodes[..nn], phys);
        }
        return Ok(());
    }
    c.skip_line();
    let mut done = 0usize;
    while done < total {
        let t = c.int(true, "element type")?;
        let n = c.int(true, "elements following")?;
        let ntags = c.int(true, "number of element tags")?;
        if n <= 0 || !(0..=64).contains(&ntags) {
            return Err(c.err(format!(
                "bad binary element header ({n} elements, {ntags} tags)"
            )));
        }
        let Some(nn) = nodes_of_type(t) else {
            let first = c.int(true, "element tag").unwrap_or(0);
            return Err(unsupported(c, first.max(0) as u64, t));
        };
        let n = c.cap(n as u64, 4 * (1 + ntags as usize + nn), "elements")?;
        if done + n > total {
            return Err(c.err(format!(
                "binary element blocks hold more than the declared {total}"
            )));
        }
        for _ in 0..n {
            let tag = c.int(true, "element tag")? as i64;
            let tag = to_u64(c, tag, "element tag")?;
            let mut phys = Vec::new();
            for k in 0..ntags {
                let v = c.int(true, "element tag value")?;
                if k == 0 && v != 0 {
                    phys.push(v);
                }
            }
            for v in nodes.iter_mut().take(nn) {
                let x = c.int(true, "element node tag")? as i64;
                *v = to_u64(c, x, "node tag")?;
            }
            store(raw, t, tag, &nodes[..nn], phys);
        }
        done += n;
    }
    Ok(())
}

/// The position of each node tag in `raw.nodes`; fails (naming file `name`) on a
/// non-finite coordinate or a tag defined twice.
pub(crate) fn node_index(raw: &Raw, name: &str) -> Result<HashMap<u64, usize>> {
    let fail = |m: String| Error::Parse(format!("{name}: {m}"));
    let mut index: HashMap<u64, usize> = HashMap::with_capacity(raw.nodes.len());
    for (k, (tag, x)) in raw.nodes.iter().enumerate() {
        if !x.iter().all(|v| v.is_finite()) {
            return Err(fail(format!(
                "node {tag} has a non-finite coordinate {x:?}"
            )));
        }
        if index.insert(*tag, k).is_some() {
            return Err(fail(format!("node {tag} is defined twice")));
        }
    }
    Ok(index)
}

/// Checks what was read and builds the mesh.
fn assemble(raw: Raw, name: &str) -> Result<Loaded> {
    let fail = |m: String| Error::Parse(format!("{name}: {m}"));
    if raw.hexes.is_empty() {
        return Err(fail(
            "no volume elements: twoball needs 8-node hexahedra (gmsh: Recombine + transfinite \
             volumes, and a physical volume group)"
                .into(),
        ));
    }
    let index = node_index(&raw, name)?;
    // Keep only nodes used by hexahedra, in file order.
    let mut new_id = vec![u32::MAX; raw.nodes.len()];
    for (tag, h) in &raw.hexes {
        for t in h {
            let Some(&k) = index.get(t) else {
                return Err(fail(format!(
                    "element {tag} refers to node {t}, which is not defined"
                )));
            };
            new_id[k] = 0;
        }
    }
    let mut nodes = Vec::new();
    for (k, id) in new_id.iter_mut().enumerate() {
        if *id == 0 {
            if nodes.len() >= u32::MAX as usize {
                return Err(fail("more than 2^32 - 1 nodes".into()));
            }
            *id = nodes.len() as u32;
            nodes.push(raw.nodes[k].1);
        }
    }
    let map = |tag: u64, t: u64| -> Result<u32> {
        match index.get(&t).map(|&k| new_id[k]) {
            Some(i) if i != u32::MAX => Ok(i),
            Some(_) => Err(fail(format!(
                "element {tag} uses node {t}, which is on no hexahedron"
            ))),
            None => Err(fail(format!(
                "element {tag} refers to node {t}, which is not defined"
            ))),
        }
    };
    let mut hexes = Vec::with_capacity(raw.hexes.len());
    let mut flipped = Vec::new();
    for (tag, h) in &raw.hexes {
        let mut e = [0u32; 8];
        for (v, &t) in e.iter_mut().zip(h) {
            *v = map(*tag, t)?;
        }
        let sj = corner_scaled_jacobians(&e.map(|i| nodes[i as usize]));
        if sj.iter().all(|&s| s > 0.0) {
            hexes.push(e);
        } else if sj.iter().all(|&s| s < 0.0) {
            flipped.push(*tag);
            hexes.push([e[0], e[3], e[2], e[1], e[4], e[7], e[6], e[5]]);
        } else {
            let lo = sj.iter().cloned().fold(f64::INFINITY, f64::min);
            let hi = sj.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
            return Err(fail(format!(
                "element {tag} is inverted or degenerate (corner scaled Jacobians from {lo:.3} \
                 to {hi:.3})"
            )));
        }
    }
    let mut warnings = Vec::new();
    if !flipped.is_empty() {
        warnings.push(format!(
            "{name}: reoriented {} mirrored hexahedra (first: element {})",
            flipped.len(),
            flipped[0]
        ));
    }
    let boundary = boundary_faces(&hexes);
    let mut outward: HashMap<[u32; 4], [u32; 4]> = HashMap::with_capacity(boundary.len());
    for q in &boundary {
        let mut k = *q;
        k.sort_unstable();
        outward.insert(k, *q);
    }
    let group = |dim: i32, p: i32| {
        raw.names
            .get(&(dim, p))
            .cloned()
            .unwrap_or_else(|| format!("physical_{p}"))
    };
    let mut face_sets: BTreeMap<String, Vec<[u32; 4]>> = BTreeMap::new();
    let mut node_sets: BTreeMap<String, Vec<u32>> = BTreeMap::new();
    for (tag, q, phys) in &raw.quads {
        let mut f = [0u32; 4];
        for (v, &t) in f.iter_mut().zip(q) {
            *v = map(*tag, t)?;
        }
        let mut k = f;
        k.sort_unstable();
        let f = outward.get(&k).copied().unwrap_or(f);
        for &p in phys {
            let name = group(2, p);
            face_sets.entry(name.clone()).or_default().push(f);
            node_sets.entry(name).or_default().extend_from_slice(&f);
        }
    }
    for (tag, t, phys) in &raw.points {
        let i = map(*tag, *t)?;
        for &p in phys {
            node_sets.entry(group(0, p)).or_default().push(i);
        }
    }
    for v in node_sets.values_mut() {
        v.sort_unstable();
        v.dedup();
    }
    Ok(Loaded {
        mesh: Mesh {
            nodes,
            hexes,
            boundary,
            node_sets,
            face_sets,
        },
        warnings,
    })
}

/// The mesh as MSH 4.1 ASCII text. Hexahedra form one volume entity in the physical group
/// `volume`. Each face set becomes a physical surface group of its name; every distinct quad
/// is written once, on a surface entity carrying all the groups it belongs to (gmsh rejects
/// duplicate elements). A node set that is not exactly the nodes of the face set of the same
/// name becomes a physical point group of its name, one point element per node, grouped the
/// same way. Reading the text back with [`parse`] gives the same mesh.
pub fn to_msh41(mesh: &Mesh) -> Result<String> {
    super::check_finite_nodes(&mesh.nodes)?;
    let face_names: Vec<&String> = mesh
        .face_sets
        .iter()
        .filter(|(_, v)| !v.is_empty())
        .map(|(k, _)| k)
        .collect();
    let point_names: Vec<&String> = mesh
        .node_sets
        .iter()
        .filter(|(k, v)| {
            let mut from_faces: Vec<u32> = mesh
                .face_sets
                .get(*k)
                .map(|f| f.iter().flatten().copied().collect())
                .unwrap_or_default();
            from_faces.sort_unstable();
            from_faces.dedup();
            !v.is_empty() && from_faces != **v
        })
        .map(|(k, _)| k)
        .collect();
    // Physical tags: 1 = volume, then face sets, then node sets.
    let face_tag = |k: usize| (k + 2) as i32;
    let point_tag = |k: usize| (k + 2 + face_names.len()) as i32;
    // Group distinct quads (and nodes) by the sets they belong to: one entity per group.
    let mut quad_groups: BTreeMap<[u32; 4], (Vec<i32>, [u32; 4])> = BTreeMap::new();
    for (k, name) in face_names.iter().enumerate() {
        for q in &mesh.face_sets[*name] {
            let mut key = *q;
            key.sort_unstable();
            let e = quad_groups.entry(key).or_insert((Vec::new(), *q));
            if !e.0.contains(&face_tag(k)) {
                e.0.push(face_tag(k));
            }
        }
    }
    let mut surfaces: BTreeMap<Vec<i32>, Vec<[u32; 4]>> = BTreeMap::new();
    for (tags, q) in quad_groups.into_values() {
        surfaces.entry(tags).or_default().push(q);
    }
    let mut node_groups: BTreeMap<u32, Vec<i32>> = BTreeMap::new();
    for (k, name) in point_names.iter().enumerate() {
        for &i in &mesh.node_sets[*name] {
            node_groups.entry(i).or_default().push(point_tag(k));
        }
    }
    let mut points: BTreeMap<Vec<i32>, Vec<u32>> = BTreeMap::new();
    for (i, tags) in node_groups {
        points.entry(tags).or_default().push(i);
    }
    let bbox = |ids: &mut dyn Iterator<Item = u32>| {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for i in ids {
            let p = mesh.nodes[i as usize];
            for a in 0..3 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
        format!(
            "{:e} {:e} {:e} {:e} {:e} {:e}",
            lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]
        )
    };
    let tag_list = |t: &[i32]| {
        let mut s = t.len().to_string();
        for x in t {
            let _ = write!(s, " {x}");
        }
        s
    };
    let mut s = String::with_capacity(64 * mesh.nodes.len() + 80 * mesh.hexes.len());
    s.push_str("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    let n_phys = 1 + face_names.len() + point_names.len();
    let _ = writeln!(s, "$PhysicalNames\n{n_phys}\n3 1 \"volume\"");
    for (k, name) in face_names.iter().enumerate() {
        let _ = writeln!(s, "2 {} \"{}\"", face_tag(k), name.replace('"', "'"));
    }
    for (k, name) in point_names.iter().enumerate() {
        let _ = writeln!(s, "0 {} \"{}\"", point_tag(k), name.replace('"', "'"));
    }
    s.push_str("$EndPhysicalNames\n$Entities\n");
    let _ = writeln!(s, "{} 0 {} 1", points.len(), surfaces.len());
    for (k, (tags, v)) in points.iter().enumerate() {
        let p = mesh.nodes[v[0] as usize];
        let _ = writeln!(
            s,
            "{} {:e} {:e} {:e} {}",
            k + 1,
            p[0],
            p[1],
            p[2],
            tag_list(tags)
        );
    }
    for (k, (tags, f)) in surfaces.iter().enumerate() {
        let b = bbox(&mut f.iter().flatten().copied());
        let _ = writeln!(s, "{} {b} {} 0", k + 1, tag_list(tags));
    }
    let b = bbox(&mut (0..mesh.nodes.len() as u32));
    let surface_tags: Vec<i32> = (1..=surfaces.len() as i32).collect();
    let _ = writeln!(s, "1 {b} 1 1 {}", tag_list(&surface_tags));
    s.push_str("$EndEntities\n$Nodes\n");
    let n = mesh.nodes.len();
    let _ = writeln!(s, "1 {n} 1 {n}\n3 1 0 {n}");
    for i in 1..=n {
        let _ = writeln!(s, "{i}");
    }
    for p in &mesh.nodes {
        let _ = writeln!(s, "{:.17e} {:.17e} {:.17e}", p[0], p[1], p[2]);
    }
    s.push_str("$EndNodes\n$Elements\n");
    let n_quads: usize = surfaces.values().map(Vec::len).sum();
    let n_points: usize = points.values().map(Vec::len).sum();
    let total = mesh.hexes.len() + n_quads + n_points;
    let _ = writeln!(s, "{} {total} 1 {total}", 1 + surfaces.len() + points.len());
    let mut tag = 1;
    let _ = writeln!(s, "3 1 5 {}", mesh.hexes.len());
    for h in &mesh.hexes {
        let _ = write!(s, "{tag}");
        for v in h {
            let _ = write!(s, " {}", v + 1);
        }
        s.push('\n');
        tag += 1;
    }
    for (k, f) in surfaces.values().enumerate() {
        let _ = writeln!(s, "2 {} 3 {}", k + 1, f.len());
        for q in f {
            let _ = writeln!(
                s,
                "{tag} {} {} {} {}",
                q[0] + 1,
                q[1] + 1,
                q[2] + 1,
                q[3] + 1
            );
            tag += 1;
        }
    }
    for (k, v) in points.values().enumerate() {
        let _ = writeln!(s, "0 {} 15 {}", k + 1, v.len());
        for i in v {
            let _ = writeln!(s, "{tag} {}", i + 1);
            tag += 1;
        }
    }
    s.push_str("$EndElements\n");
    Ok(s)
}

/// Writes `mesh` as MSH 4.1 ASCII (see [`to_msh41`]), atomically.
pub fn write(path: impl AsRef<Path>, mesh: &Mesh) -> Result<()> {
    write_atomic(path, to_msh41(mesh)?.as_bytes())
}
