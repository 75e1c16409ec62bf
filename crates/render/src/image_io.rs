//! Image files: EXR (32-bit float, linear), PFM, PNG (sRGB, 8-bit).
//! Writes go to a temporary file in the same folder, then a rename, so an
//! output is never left half-written.

use lumis_math::rgb::linear_to_srgb;
use std::path::{Path, PathBuf};

/// A linear RGB image, row-major, top row first.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RgbImage {
    pub width: u32,
    pub height: u32,
    pub data: Vec<f32>,
    /// Text metadata (EXR header attributes; ignored by PFM and PNG).
    pub metadata: Vec<(String, String)>,
}

impl RgbImage {
    pub fn new(width: u32, height: u32, data: Vec<f32>) -> RgbImage {
        assert_eq!(data.len(), width as usize * height as usize * 3);
        RgbImage {
            width,
            height,
            data,
            metadata: Vec::new(),
        }
    }

    pub fn pixel(&self, x: u32, y: u32) -> [f32; 3] {
        let i = 3 * (y as usize * self.width as usize + x as usize);
        [self.data[i], self.data[i + 1], self.data[i + 2]]
    }

    /// Mean of each channel.
    pub fn channel_means(&self) -> [f64; 3] {
        let mut s = [0.0f64; 3];
        for px in self.data.chunks_exact(3) {
            for c in 0..3 {
                s[c] += px[c] as f64;
            }
        }
        let n = (self.width as f64 * self.height as f64).max(1.0);
        [s[0] / n, s[1] / n, s[2] / n]
    }

    pub fn meta(&self, key: &str) -> Option<&str> {
        self.metadata
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.as_str())
    }
}

#[derive(Debug, thiserror::Error)]
pub enum ImageError {
    #[error("{path}: unsupported image extension (use .exr, .pfm or .png)")]
    Extension { path: String },
    #[error("{path}: {msg}")]
    Io { path: String, msg: String },
    #[error("{path}: not a valid {format} file: {msg}")]
    Format {
        path: String,
        format: &'static str,
        msg: String,
    },
}

fn io_err(path: &Path, e: impl std::fmt::Display) -> ImageError {
    ImageError::Io {
        path: path.display().to_string(),
        msg: e.to_string(),
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    Exr,
    Pfm,
    Png,
}

impl ImageFormat {
    pub fn from_path(path: &Path) -> Result<ImageFormat, ImageError> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .as_deref()
        {
            Some("exr") => Ok(ImageFormat::Exr),
            Some("pfm") => Ok(ImageFormat::Pfm),
            Some("png") => Ok(ImageFormat::Png),
            _ => Err(ImageError::Extension {
                path: path.display().to_string(),
            }),
        }
    }
}

fn temp_path(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_default();
    // Unique per process and per write: two threads writing one name each
    // rename a whole file of their own (the last one wins).
    static WRITES: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let k = WRITES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    path.with_file_name(format!(".{name}.tmp{}-{k}", std::process::id()))
}

/// Writes by extension; `exposure` (stops) applies to PNG only.
pub fn write_image(path: &Path, img: &RgbImage, exposure: f32) -> Result<(), ImageError> {
    let format = ImageFormat::from_path(path)?;
    let tmp = temp_path(path);
    let result = match format {
        ImageFormat::Exr => write_exr(&tmp, img),
        ImageFormat::Pfm => write_pfm(&tmp, img),
        ImageFormat::Png => write_png(&tmp, img, exposure),
    };
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(e);
    }
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        io_err(path, e)
    })
}

fn write_exr(path: &Path, img: &RgbImage) -> Result<(), ImageError> {
    use exr::meta::attribute::{AttributeValue, Text};
    use exr::prelude::*;
    let (w, h) = (img.width as usize, img.height as usize);
    let data = &img.data;
    let pixels = SpecificChannels::rgb(|p: Vec2<usize>| {
        let i = 3 * (p.y() * w + p.x());
        (data[i], data[i + 1], data[i + 2])
    });
    let mut attrs = LayerAttributes::named("");
    attrs.software_name = Some(Text::from("lumis"));
    for (k, v) in &img.metadata {
        attrs.other.insert(
            Text::from(k.as_str()),
            AttributeValue::Text(Text::from(v.as_str())),
        );
    }
    let layer = Layer::new((w, h), attrs, Encoding::SMALL_LOSSLESS, pixels);
    Image::from_layer(layer)
        .write()
        .to_file(path)
        .map_err(|e| io_err(path, e))
}

fn write_pfm(path: &Path, img: &RgbImage) -> Result<(), ImageError> {
    let mut out = format!("PF\n{} {}\n-1.0\n", img.width, img.height).into_bytes();
    let w = img.width as usize;
    // PFM stores the bottom row first.
    for y in (0..img.height as usize).rev() {
        for v in &img.data[3 * y * w..3 * (y + 1) * w] {
            out.extend_from_slice(&v.to_le_bytes());
        }
    }
    std::fs::write(path, out).map_err(|e| io_err(path, e))
}

/// 8-bit sRGB with `2^exposure` scaling, clamped.
pub fn to_srgb8(img: &RgbImage, exposure: f32) -> Vec<u8> {
    let scale = 2f32.powf(exposure);
    img.data
        .iter()
        .map(|&v| {
            let v = if v.is_finite() { v * scale } else { 0.0 };
            (linear_to_srgb(v.clamp(0.0, 1.0)) * 255.0 + 0.5) as u8
        })
        .collect()
}

fn write_png(path: &Path, img: &RgbImage, exposure: f32) -> Result<(), ImageError> {
    let bytes = to_srgb8(img, exposure);
    image::save_buffer_with_format(
        path,
        &bytes,
        img.width,
        img.height,
        image::ColorType::Rgb8,
        image::ImageFormat::Png,
    )
    .map_err(|e| io_err(path, e))
}

/// Writes 8-bit sRGB bytes (`width * height * 3`, row-major) as a PNG,
/// atomically (temporary file, then rename): for false-colour images.
pub fn write_srgb8_png(
    path: &Path,
    width: u32,
    height: u32,
    bytes: &[u8],
) -> Result<(), ImageError> {
    let tmp = temp_path(path);
    image::save_buffer_with_format(
        &tmp,
        bytes,
        width,
        height,
        image::ColorType::Rgb8,
        image::ImageFormat::Png,
    )
    .map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        io_err(path, e)
    })?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        io_err(path, e)
    })
}

/// Reads EXR, PFM or PNG (8-bit sRGB decoded to linear).
pub fn read_image(path: &Path) -> Result<RgbImage, ImageError> {
    let format = ImageFormat::from_path(path)?;
    let bytes = std::fs::read(path).map_err(|e| io_err(path, e))?;
    decode_image(&bytes, format, &path.display().to_string())
}

/// Decodes an image held in memory; `name` labels errors. Sizes in headers
/// are checked against the data before anything is allocated.
pub fn decode_image(bytes: &[u8], format: ImageFormat, name: &str) -> Result<RgbImage, ImageError> {
    match format {
        ImageFormat::Exr => read_exr(bytes, name),
        ImageFormat::Pfm => read_pfm(bytes, name),
        ImageFormat::Png => read_png(bytes, name),
    }
}

/// Most pixels an image file may declare: the film's limit, and at most
/// 4096 per byte of file beyond the first million (generous for compressed
/// flat images, small enough that a tiny hostile header cannot claim gigabytes).
fn pixel_limit(file_len: usize) -> u64 {
    crate::film::MAX_PIXELS.min((1u64 << 20) + 4096 * file_len as u64)
}

fn read_exr(bytes: &[u8], name: &str) -> Result<RgbImage, ImageError> {
    use exr::meta::attribute::AttributeValue;
    use exr::prelude::*;
    let bad = |msg: String| ImageError::Format {
        path: name.to_string(),
        format: "EXR",
        msg,
    };
    let meta = exr::meta::MetaData::read_from_buffered(std::io::Cursor::new(bytes), false)
        .map_err(|e| bad(e.to_string()))?;
    let limit = pixel_limit(bytes.len());
    for h in &meta.headers {
        let px = h.layer_size.width() as u64 * h.layer_size.height() as u64;
        if px > limit {
            return Err(bad(format!(
                "declares {}x{} pixels, more than {limit} for a file of {} bytes",
                h.layer_size.width(),
                h.layer_size.height(),
                bytes.len()
            )));
        }
    }
    let img = read()
        .no_deep_data()
        .largest_resolution_level()
        .rgba_channels(
            |res, _| (res.width(), vec![0f32; res.width() * res.height() * 3]),
            |(w, buf): &mut (usize, Vec<f32>), p, (r, g, b, _a): (f32, f32, f32, f32)| {
                let i = 3 * (p.y() * *w + p.x());
                buf[i] = r;
                buf[i + 1] = g;
                buf[i + 2] = b;
            },
        )
        .first_valid_layer()
        .all_attributes()
        .from_buffered(std::io::Cursor::new(bytes))
        .map_err(|e| bad(e.to_string()))?;
    let layer = &img.layer_data;
    let size = layer.size;
    let mut metadata = Vec::new();
    for (k, v) in layer
        .attributes
        .other
        .iter()
        .chain(img.attributes.other.iter())
    {
        if let AttributeValue::Text(t) = v {
            metadata.push((k.to_string(), t.to_string()));
        }
    }
    Ok(RgbImage {
        width: size.width() as u32,
        height: size.height() as u32,
        data: layer.channel_data.pixels.1.clone(),
        metadata,
    })
}

fn read_pfm(bytes: &[u8], name: &str) -> Result<RgbImage, ImageError> {
    let bad = |msg: &str| ImageError::Format {
        path: name.to_string(),
        format: "PFM",
        msg: msg.to_string(),
    };
    // Header: three whitespace-separated tokens after the magic, then one whitespace byte.
    let mut pos = 0;
    let mut tokens = Vec::new();
    while tokens.len() < 4 {
        while pos < bytes.len() && bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        let start = pos;
        while pos < bytes.len() && !bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        if start == pos {
            return Err(bad("truncated header"));
        }
        tokens.push(String::from_utf8_lossy(&bytes[start..pos]).to_string());
    }
    pos += 1;
    let channels = match tokens[0].as_str() {
        "PF" => 3,
        "Pf" => 1,
        _ => return Err(bad("missing PF/Pf magic")),
    };
    let w: usize = tokens[1].parse().map_err(|_| bad("bad width"))?;
    let h: usize = tokens[2].parse().map_err(|_| bad("bad height"))?;
    let scale: f32 = tokens[3].parse().map_err(|_| bad("bad scale"))?;
    let need = w
        .checked_mul(h)
        .and_then(|n| n.checked_mul(4 * channels))
        .ok_or_else(|| bad("size overflows"))?;
    if bytes.len() < pos + need {
        return Err(bad("file shorter than its header says"));
    }
    let little = scale < 0.0;
    let mut data = vec![0f32; w * h * 3];
    for y in 0..h {
        for x in 0..w {
            for c in 0..3 {
                let src_c = if channels == 1 { 0 } else { c };
                let o = pos + 4 * (channels * (y * w + x) + src_c);
                let b = [bytes[o], bytes[o + 1], bytes[o + 2], bytes[o + 3]];
                let v = if little {
                    f32::from_le_bytes(b)
                } else {
                    f32::from_be_bytes(b)
                };
                data[3 * ((h - 1 - y) * w + x) + c] = v;
            }
        }
    }
    Ok(RgbImage {
        width: w as u32,
        height: h as u32,
        data,
        metadata: Vec::new(),
    })
}

fn read_png(bytes: &[u8], name: &str) -> Result<RgbImage, ImageError> {
    let bad = |e: image::ImageError| ImageError::Format {
        path: name.to_string(),
        format: "PNG",
        msg: e.to_string(),
    };
    // The decoder's default limits (512 MiB per allocation) apply.
    let img = image::ImageReader::with_format(std::io::Cursor::new(bytes), image::ImageFormat::Png)
        .decode()
        .map_err(bad)?;
    let rgb = img.to_rgb8();
    let data = rgb
        .as_raw()
        .iter()
        .map(|&v| lumis_math::rgb::srgb_to_linear(v as f32 / 255.0))
        .collect();
    Ok(RgbImage {
        width: rgb.width(),
        height: rgb.height(),
        data,
        metadata: Vec::new(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample_image() -> RgbImage {
        let data = (0..4 * 3 * 3).map(|i| i as f32 * 0.25).collect();
        let mut img = RgbImage::new(4, 3, data);
        img.metadata.push(("lumis:spp".into(), "16".into()));
        img
    }

    #[test]
    fn exr_and_pfm_round_trip_exactly() {
        let dir = std::env::temp_dir().join(format!("lumis-img-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let img = sample_image();
        for name in ["a.exr", "a.pfm"] {
            let p = dir.join(name);
            write_image(&p, &img, 0.0).unwrap();
            let back = read_image(&p).unwrap();
            assert_eq!((back.width, back.height), (4, 3));
            assert_eq!(back.data, img.data, "{name}");
            if name.ends_with("exr") {
                assert_eq!(back.meta("lumis:spp"), Some("16"));
            }
        }
        let p = dir.join("a.png");
        write_image(&p, &img, 0.0).unwrap();
        assert_eq!(read_image(&p).unwrap().width, 4);
        assert!(write_image(&dir.join("a.jpg"), &img, 0.0).is_err());
        // No temporary files left behind.
        let left: Vec<_> = std::fs::read_dir(&dir)
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().contains(".tmp"))
            .collect();
        assert!(left.is_empty());
        std::fs::remove_dir_all(&dir).ok();
    }
}
