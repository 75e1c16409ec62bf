//! Reading texture images (PNG, EXR, PFM, TGA) into linear RGB levels.

use super::mipmap::Level;
use super::tga;
use lumis_math::Rgb;
use std::path::Path;

/// How 8- and 16-bit texel values map to linear values (pbrt-v4's `encoding`;
/// float formats are always linear).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Encoding {
    Srgb,
    Linear,
    Gamma(f32),
}

impl Encoding {
    pub fn parse(s: &str) -> Option<Encoding> {
        match s {
            "sRGB" | "srgb" => Some(Encoding::Srgb),
            "linear" => Some(Encoding::Linear),
            _ => {
                let g: f32 = s.strip_prefix("gamma ")?.trim().parse().ok()?;
                (g > 0.0).then_some(Encoding::Gamma(g))
            }
        }
    }

    /// Linear value of an encoded value in [0, 1].
    #[inline]
    pub fn to_linear(self, v: f32) -> f32 {
        match self {
            Encoding::Srgb => lumis_math::rgb::srgb_to_linear(v),
            Encoding::Linear => v,
            Encoding::Gamma(g) => v.powf(g),
        }
    }

    fn table8(self) -> [f32; 256] {
        std::array::from_fn(|i| self.to_linear(i as f32 / 255.0))
    }
}

/// Reads an image file as linear RGB, row 0 at the top.
pub fn read_texture_image(path: &Path, enc: Encoding) -> Result<Level, String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "exr" | "pfm" => {
            let img = crate::image_io::read_image(path).map_err(|e| e.to_string())?;
            let texels = img.data.chunks(3).map(Rgb::from_slice).collect();
            Ok(Level {
                width: img.width,
                height: img.height,
                texels,
            })
        }
        "tga" => {
            let bytes = std::fs::read(path).map_err(|e| e.to_string())?;
            let t = tga::decode(&bytes)?;
            Ok(from_rgb8(t.width, t.height, &t.rgb, enc))
        }
        "png" => {
            let img = image::open(path).map_err(|e| e.to_string())?;
            let sixteen = matches!(
                img.color(),
                image::ColorType::L16
                    | image::ColorType::La16
                    | image::ColorType::Rgb16
                    | image::ColorType::Rgba16
            );
            if sixteen {
                let rgb = img.to_rgb16();
                let texels = rgb
                    .pixels()
                    .map(|p| Rgb::new(p[0] as f32, p[1] as f32, p[2] as f32) / 65535.0)
                    .map(|c| c.map(|v| enc.to_linear(v)))
                    .collect();
                Ok(Level {
                    width: rgb.width(),
                    height: rgb.height(),
                    texels,
                })
            } else {
                let rgb = img.to_rgb8();
                let px: Vec<[u8; 3]> = rgb.pixels().map(|p| p.0).collect();
                Ok(from_rgb8(rgb.width(), rgb.height(), &px, enc))
            }
        }
        _ => Err(format!(
            "unsupported image format `.{ext}` (expected .png, .exr, .pfm or .tga)"
        )),
    }
}

/// 8-bit texels decoded through the encoding.
pub fn from_rgb8(width: u32, height: u32, px: &[[u8; 3]], enc: Encoding) -> Level {
    let t = enc.table8();
    Level {
        width,
        height,
        texels: px
            .iter()
            .map(|p| Rgb::new(t[p[0] as usize], t[p[1] as usize], t[p[2] as usize]))
            .collect(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_decode_of_8_bit() {
        let l = from_rgb8(2, 1, &[[0, 128, 255], [188, 188, 188]], Encoding::Srgb);
        assert_eq!(l.texels[0].r, 0.0);
        assert!(
            (l.texels[0].g - 0.215_861).abs() < 1e-5,
            "{:?}",
            l.texels[0]
        );
        assert!((l.texels[0].b - 1.0).abs() < 1e-6);
        // sRGB 188 is about linear 0.5.
        assert!((l.texels[1].r - 0.502_886).abs() < 1e-4);
        let lin = from_rgb8(1, 1, &[[51, 0, 0]], Encoding::Linear);
        assert!((lin.texels[0].r - 0.2).abs() < 1e-6);
        let g = from_rgb8(1, 1, &[[51, 0, 0]], Encoding::Gamma(2.0));
        assert!((g.texels[0].r - 0.04).abs() < 1e-6);
        assert_eq!(Encoding::parse("gamma 2.2"), Some(Encoding::Gamma(2.2)));
        assert_eq!(Encoding::parse("sRGB"), Some(Encoding::Srgb));
        assert_eq!(Encoding::parse("bogus"), None);
    }

    #[test]
    fn reads_tga_png_and_pfm_files() {
        let dir = std::env::temp_dir().join(format!("lumis-tex-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // TGA: 1x1 RLE, linear encoding.
        let mut b = tga::tests::header(10, 1, 1, 24, 0x20);
        b.extend_from_slice(&[0x80, 0, 0, 255]);
        let p = dir.join("a.tga");
        std::fs::write(&p, &b).unwrap();
        let l = read_texture_image(&p, Encoding::Linear).unwrap();
        assert_eq!(l.texels, vec![Rgb::new(1.0, 0.0, 0.0)]);
        // PNG written by the image writer (sRGB 8-bit) reads back close to linear.
        let img = crate::image_io::RgbImage::new(2, 1, vec![0.5, 0.25, 1.0, 0.0, 0.0, 0.0]);
        let p = dir.join("a.png");
        crate::image_io::write_image(&p, &img, 0.0).unwrap();
        let l = read_texture_image(&p, Encoding::Srgb).unwrap();
        assert!((l.texels[0].r - 0.5).abs() < 0.01 && (l.texels[0].g - 0.25).abs() < 0.01);
        let p = dir.join("a.pfm");
        crate::image_io::write_image(&p, &img, 0.0).unwrap();
        let l = read_texture_image(&p, Encoding::Srgb).unwrap();
        assert_eq!(l.texels[0], Rgb::new(0.5, 0.25, 1.0));
        assert!(read_texture_image(&dir.join("a.jpg"), Encoding::Srgb).is_err());
        std::fs::remove_dir_all(&dir).ok();
    }
}
