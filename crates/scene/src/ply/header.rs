//! The PLY header: format, elements and their properties.

use super::{invalid, PlyError};

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Format {
    Ascii,
    BinaryLe,
    BinaryBe,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Scalar {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Scalar {
    fn parse(s: &str) -> Option<Scalar> {
        Some(match s {
            "char" | "int8" => Scalar::I8,
            "uchar" | "uint8" => Scalar::U8,
            "short" | "int16" => Scalar::I16,
            "ushort" | "uint16" => Scalar::U16,
            "int" | "int32" => Scalar::I32,
            "uint" | "uint32" => Scalar::U32,
            "float" | "float32" => Scalar::F32,
            "double" | "float64" => Scalar::F64,
            _ => return None,
        })
    }

    pub(super) fn size(self) -> usize {
        match self {
            Scalar::I8 | Scalar::U8 => 1,
            Scalar::I16 | Scalar::U16 => 2,
            Scalar::I32 | Scalar::U32 | Scalar::F32 => 4,
            Scalar::F64 => 8,
        }
    }

    /// Decodes the first `size()` bytes of `b`, little-endian.
    pub(super) fn decode_le(self, b: &[u8; 8]) -> f64 {
        let b2 = [b[0], b[1]];
        let b4 = [b[0], b[1], b[2], b[3]];
        match self {
            Scalar::I8 => b[0] as i8 as f64,
            Scalar::U8 => b[0] as f64,
            Scalar::I16 => i16::from_le_bytes(b2) as f64,
            Scalar::U16 => u16::from_le_bytes(b2) as f64,
            Scalar::I32 => i32::from_le_bytes(b4) as f64,
            Scalar::U32 => u32::from_le_bytes(b4) as f64,
            Scalar::F32 => f32::from_le_bytes(b4) as f64,
            Scalar::F64 => f64::from_le_bytes(*b),
        }
    }
}

#[derive(Clone, Debug)]
pub(super) enum Prop {
    Scalar(Scalar, String),
    /// Count type, item type, name.
    List(Scalar, Scalar, String),
}

impl Prop {
    pub(super) fn name(&self) -> &str {
        match self {
            Prop::Scalar(_, n) | Prop::List(_, _, n) => n,
        }
    }
}

#[derive(Clone, Debug)]
pub(super) struct Element {
    pub name: String,
    pub count: usize,
    pub props: Vec<Prop>,
}

#[derive(Clone, Debug)]
pub(super) struct Header {
    pub format: Format,
    pub elements: Vec<Element>,
}

/// Parses the header; returns it and the offset where the data starts (just
/// after the newline ending `end_header`).
pub(super) fn parse(bytes: &[u8]) -> Result<(Header, usize), PlyError> {
    let mut pos = 0;
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    let mut first = true;
    loop {
        let Some(nl) = bytes[pos..].iter().position(|&b| b == b'\n') else {
            return Err(invalid(if first {
                "not a PLY file"
            } else {
                "the header has no end_header line"
            }));
        };
        let raw = &bytes[pos..pos + nl];
        pos += nl + 1;
        let line = std::str::from_utf8(raw)
            .map_err(|_| invalid("the header is not text"))?
            .trim_end_matches('\r');
        let words: Vec<&str> = line.split_whitespace().collect();
        if first {
            if words != ["ply"] {
                return Err(invalid("not a PLY file (the first line is not `ply`)"));
            }
            first = false;
            continue;
        }
        match words.as_slice() {
            [] => {}
            ["comment" | "obj_info", ..] => {}
            ["format", f, _version] => {
                format = Some(match *f {
                    "ascii" => Format::Ascii,
                    "binary_little_endian" => Format::BinaryLe,
                    "binary_big_endian" => Format::BinaryBe,
                    other => return Err(invalid(format!("unknown PLY format `{other}`"))),
                })
            }
            ["element", name, count] => {
                let count = count
                    .parse::<usize>()
                    .map_err(|_| invalid(format!("bad element count `{count}` for `{name}`")))?;
                elements.push(Element {
                    name: name.to_string(),
                    count,
                    props: Vec::new(),
                });
            }
            ["property", rest @ ..] => {
                let el = elements
                    .last_mut()
                    .ok_or_else(|| invalid("a property appears before any element"))?;
                let ty = |s: &str| {
                    Scalar::parse(s).ok_or_else(|| invalid(format!("unknown property type `{s}`")))
                };
                let prop = match rest {
                    ["list", c, item, name] => Prop::List(ty(c)?, ty(item)?, name.to_string()),
                    [t, name] => Prop::Scalar(ty(t)?, name.to_string()),
                    _ => return Err(invalid(format!("malformed property line `{line}`"))),
                };
                el.props.push(prop);
            }
            ["end_header"] => break,
            _ => return Err(invalid(format!("unexpected header line `{line}`"))),
        }
    }
    let format = format.ok_or_else(|| invalid("the header has no format line"))?;
    Ok((Header { format, elements }, pos))
}

impl Header {
    /// Refuses element counts that cannot fit in `data_len` bytes.
    pub(super) fn check_sizes(&self, data_len: usize) -> Result<(), PlyError> {
        let mut total: usize = 0;
        for el in &self.elements {
            let min: usize = match self.format {
                // Every ascii value takes at least one character.
                Format::Ascii => el.props.len(),
                _ => el
                    .props
                    .iter()
                    .map(|p| match p {
                        Prop::Scalar(s, _) | Prop::List(s, _, _) => s.size(),
                    })
                    .sum(),
            };
            let need = el.count.checked_mul(min).and_then(|n| n.checked_add(total));
            match need {
                Some(n) if n <= data_len => total = n,
                _ => {
                    let what = match el.name.as_str() {
                        "vertex" => "vertices".to_string(),
                        "face" => "faces".to_string(),
                        other => format!("`{other}` elements"),
                    };
                    return Err(invalid(format!(
                        "PLY header declares {} {what} but the file has only {data_len} bytes of data",
                        el.count
                    )));
                }
            }
        }
        Ok(())
    }
}
