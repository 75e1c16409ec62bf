//! A PLY triangle-mesh reader (ascii and binary, either endianness).

use lumis_math::{Vec2, Vec3};
use std::path::Path;

mod header;
use header::{Element, Format, Prop, Scalar};

#[derive(Clone, Debug, Default, PartialEq)]
pub struct PlyMesh {
    pub positions: Vec<Vec3>,
    pub normals: Option<Vec<Vec3>>,
    pub uvs: Option<Vec<Vec2>>,
    /// Triangles; quads and larger polygons are fan-triangulated.
    pub indices: Vec<u32>,
}

#[derive(Debug, thiserror::Error)]
pub enum PlyError {
    #[error("cannot read PLY file `{path}`: {source}")]
    Io {
        path: String,
        source: std::io::Error,
    },
    #[error("{}: corrupt gzip data: {message}", path.as_deref().unwrap_or("PLY data"))]
    Gzip {
        path: Option<String>,
        message: String,
    },
    #[error("{}: {message}", path.as_deref().unwrap_or("PLY data"))]
    Invalid {
        path: Option<String>,
        message: String,
    },
}

fn invalid(message: impl Into<String>) -> PlyError {
    PlyError::Invalid {
        path: None,
        message: message.into(),
    }
}

pub fn read_ply(path: &Path) -> Result<PlyMesh, PlyError> {
    let shown = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|source| PlyError::Io {
        path: shown.clone(),
        source,
    })?;
    parse_ply(&bytes).map_err(|e| match e {
        PlyError::Invalid { message, .. } => PlyError::Invalid {
            path: Some(shown),
            message,
        },
        PlyError::Gzip { message, .. } => PlyError::Gzip {
            path: Some(shown),
            message,
        },
        other => other,
    })
}

/// Largest decompressed size of a gzipped PLY file.
const MAX_GUNZIPPED: u64 = 8 << 30;

/// Parses PLY data, gzip-compressed (`.ply.gz`) or not.
pub fn parse_ply(bytes: &[u8]) -> Result<PlyMesh, PlyError> {
    if bytes.starts_with(&[0x1f, 0x8b]) {
        use std::io::Read;
        let mut out = Vec::new();
        let gz = |message: String| PlyError::Gzip {
            path: None,
            message,
        };
        flate2::read::MultiGzDecoder::new(bytes)
            .take(MAX_GUNZIPPED + 1)
            .read_to_end(&mut out)
            .map_err(|e| gz(e.to_string()))?;
        if out.len() as u64 > MAX_GUNZIPPED {
            return Err(gz(format!(
                "decompresses to more than {} GiB",
                MAX_GUNZIPPED >> 30
            )));
        }
        if out.starts_with(&[0x1f, 0x8b]) {
            return Err(gz("gzip inside gzip".into()));
        }
        return parse_ply(&out);
    }
    let (header, data_start) = header::parse(bytes)?;
    let data = &bytes[data_start..];
    header.check_sizes(data.len())?;
    let mut reader = Reader {
        format: header.format,
        data,
        pos: 0,
    };
    let mut mesh = PlyMesh::default();
    for el in &header.elements {
        match el.name.as_str() {
            "vertex" => read_vertices(&mut reader, el, &mut mesh)?,
            "face" => read_faces(&mut reader, el, &mut mesh)?,
            _ => {
                for _ in 0..el.count {
                    for p in &el.props {
                        reader.skip_prop(p)?;
                    }
                }
            }
        }
    }
    let n = mesh.positions.len();
    if let Some(&bad) = mesh.indices.iter().find(|&&i| i as usize >= n) {
        return Err(invalid(format!(
            "vertex index {bad} is out of range (the mesh has {n} vertices)"
        )));
    }
    Ok(mesh)
}

fn read_vertices(r: &mut Reader, el: &Element, mesh: &mut PlyMesh) -> Result<(), PlyError> {
    let find = |names: &[&str]| el.props.iter().position(|p| names.contains(&p.name()));
    let (Some(x), Some(y), Some(z)) = (find(&["x"]), find(&["y"]), find(&["z"])) else {
        return Err(invalid("the vertex element lacks x, y or z"));
    };
    let normal = match (find(&["nx"]), find(&["ny"]), find(&["nz"])) {
        (Some(a), Some(b), Some(c)) => Some([a, b, c]),
        _ => None,
    };
    let uv = match (
        find(&["u", "s", "texture_u", "texture_s"]),
        find(&["v", "t", "texture_v", "texture_t"]),
    ) {
        (Some(a), Some(b)) => Some([a, b]),
        _ => None,
    };
    let mut vals = vec![0.0f64; el.props.len()];
    let mut normals = Vec::new();
    let mut uvs = Vec::new();
    mesh.positions.reserve(el.count);
    for _ in 0..el.count {
        for (k, p) in el.props.iter().enumerate() {
            vals[k] = match p {
                Prop::Scalar(s, _) => r.read(*s)?,
                Prop::List(..) => {
                    r.skip_prop(p)?;
                    0.0
                }
            };
        }
        let f = |k: usize| vals[k] as f32;
        mesh.positions.push(Vec3::new(f(x), f(y), f(z)));
        if let Some([a, b, c]) = normal {
            normals.push(Vec3::new(f(a), f(b), f(c)));
        }
        if let Some([a, b]) = uv {
            uvs.push(Vec2::new(f(a), f(b)));
        }
    }
    if normal.is_some() {
        mesh.normals = Some(normals);
    }
    if uv.is_some() {
        mesh.uvs = Some(uvs);
    }
    Ok(())
}

fn read_faces(r: &mut Reader, el: &Element, mesh: &mut PlyMesh) -> Result<(), PlyError> {
    let idx = el
        .props
        .iter()
        .position(
            |p| matches!(p, Prop::List(_, _, n) if n == "vertex_indices" || n == "vertex_index"),
        )
        .ok_or_else(|| invalid("the face element has no vertex_indices list"))?;
    let mut poly = Vec::new();
    mesh.indices.reserve(el.count * 3);
    for face in 0..el.count {
        for (k, p) in el.props.iter().enumerate() {
            match p {
                Prop::List(count_ty, item_ty, _) if k == idx => {
                    let n = r.read_count(*count_ty)?;
                    poly.clear();
                    for _ in 0..n {
                        let v = r.read(*item_ty)?;
                        if v < 0.0 || v > u32::MAX as f64 || v.fract() != 0.0 {
                            return Err(invalid(format!(
                                "face {face} has an invalid vertex index {v}"
                            )));
                        }
                        poly.push(v as u32);
                    }
                    if n < 3 {
                        return Err(invalid(format!("face {face} has only {n} vertices")));
                    }
                    for j in 1..n - 1 {
                        mesh.indices
                            .extend_from_slice(&[poly[0], poly[j], poly[j + 1]]);
                    }
                }
                _ => r.skip_prop(p)?,
            }
        }
    }
    Ok(())
}

/// Reads values from the data section in the file's format.
struct Reader<'a> {
    format: Format,
    data: &'a [u8],
    pos: usize,
}

impl Reader<'_> {
    fn read(&mut self, s: Scalar) -> Result<f64, PlyError> {
        match self.format {
            Format::Ascii => self.read_ascii(),
            Format::BinaryLe | Format::BinaryBe => {
                let n = s.size();
                let end = self.pos + n;
                let Some(b) = self.data.get(self.pos..end) else {
                    return Err(invalid("unexpected end of binary data"));
                };
                self.pos = end;
                let mut buf = [0u8; 8];
                buf[..n].copy_from_slice(b);
                if self.format == Format::BinaryBe {
                    buf[..n].reverse();
                }
                Ok(s.decode_le(&buf))
            }
        }
    }

    fn read_ascii(&mut self) -> Result<f64, PlyError> {
        while self
            .data
            .get(self.pos)
            .is_some_and(|b| b.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        let start = self.pos;
        while self
            .data
            .get(self.pos)
            .is_some_and(|b| !b.is_ascii_whitespace())
        {
            self.pos += 1;
        }
        if start == self.pos {
            return Err(invalid("unexpected end of ascii data"));
        }
        let word = std::str::from_utf8(&self.data[start..self.pos]).unwrap_or("?");
        word.parse::<f64>()
            .map_err(|_| invalid(format!("`{word}` is not a number")))
    }

    fn read_count(&mut self, s: Scalar) -> Result<usize, PlyError> {
        let n = self.read(s)?;
        if n < 0.0 || n.fract() != 0.0 || n > 1e6 {
            return Err(invalid(format!("invalid list length {n}")));
        }
        Ok(n as usize)
    }

    fn skip_prop(&mut self, p: &Prop) -> Result<(), PlyError> {
        match p {
            Prop::Scalar(s, _) => {
                self.read(*s)?;
            }
            Prop::List(c, item, _) => {
                let n = self.read_count(*c)?;
                for _ in 0..n {
                    self.read(*item)?;
                }
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests;
