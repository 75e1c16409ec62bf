//! Truevision TGA reader: uncompressed and run-length encoded true-colour
//! (24/32 bits, BGR(A)) and greyscale (8 bits) images, either origin.

/// Decoded 8-bit image: RGB rows, row 0 at the top.
#[derive(Debug)]
pub struct Tga {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<[u8; 3]>,
}

pub fn decode(bytes: &[u8]) -> Result<Tga, String> {
    if bytes.len() < 18 {
        return Err("file shorter than the 18-byte TGA header".into());
    }
    let id_len = bytes[0] as usize;
    let cmap_type = bytes[1];
    let ty = bytes[2];
    let cmap_len = u16::from_le_bytes([bytes[5], bytes[6]]) as usize;
    let cmap_bits = bytes[7] as usize;
    let width = u16::from_le_bytes([bytes[12], bytes[13]]) as usize;
    let height = u16::from_le_bytes([bytes[14], bytes[15]]) as usize;
    let bpp = bytes[16] as usize;
    let desc = bytes[17];
    let (rle, grey) = match ty {
        2 => (false, false),
        3 => (false, true),
        10 => (true, false),
        11 => (true, true),
        _ => {
            return Err(format!(
                "TGA image type {ty} is not supported (only true-colour and greyscale, raw or RLE)"
            ))
        }
    };
    let bytes_pp = match (grey, bpp) {
        (true, 8) => 1,
        (false, 24) => 3,
        (false, 32) => 4,
        _ => {
            return Err(format!(
                "{bpp} bits per pixel is not supported for this TGA type"
            ))
        }
    };
    if width == 0 || height == 0 {
        return Err("TGA image has zero size".into());
    }
    let skip = if cmap_type == 1 {
        cmap_len * cmap_bits.div_ceil(8)
    } else {
        0
    };
    let mut pos = 18 + id_len + skip;
    let n = width * height;
    let mut pixels: Vec<[u8; 3]> = Vec::with_capacity(n);
    let read_px = |pos: &mut usize| -> Result<[u8; 3], String> {
        let p = bytes
            .get(*pos..*pos + bytes_pp)
            .ok_or("TGA pixel data is truncated")?;
        *pos += bytes_pp;
        Ok(if grey { [p[0]; 3] } else { [p[2], p[1], p[0]] })
    };
    if rle {
        while pixels.len() < n {
            let head = *bytes.get(pos).ok_or("TGA pixel data is truncated")?;
            pos += 1;
            let count = (head & 0x7f) as usize + 1;
            if count > n - pixels.len() {
                return Err("TGA run-length packet runs past the image".into());
            }
            if head & 0x80 != 0 {
                let px = read_px(&mut pos)?;
                pixels.extend(std::iter::repeat_n(px, count));
            } else {
                for _ in 0..count {
                    pixels.push(read_px(&mut pos)?);
                }
            }
        }
    } else {
        for _ in 0..n {
            pixels.push(read_px(&mut pos)?);
        }
    }
    // Stored bottom-up unless bit 5 of the descriptor is set; right-to-left if bit 4.
    let top_down = desc & 0x20 != 0;
    let right_to_left = desc & 0x10 != 0;
    let mut rgb = vec![[0u8; 3]; n];
    for y in 0..height {
        let dy = if top_down { y } else { height - 1 - y };
        for x in 0..width {
            let dx = if right_to_left { width - 1 - x } else { x };
            rgb[dy * width + dx] = pixels[y * width + x];
        }
    }
    Ok(Tga {
        width: width as u32,
        height: height as u32,
        rgb,
    })
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    pub(crate) fn header(ty: u8, w: u16, h: u16, bpp: u8, desc: u8) -> Vec<u8> {
        let mut b = vec![0u8; 18];
        b[2] = ty;
        b[12..14].copy_from_slice(&w.to_le_bytes());
        b[14..16].copy_from_slice(&h.to_le_bytes());
        b[16] = bpp;
        b[17] = desc;
        b
    }

    #[test]
    fn raw_bottom_up_bgr() {
        // 2x2, bottom row first: (blue, green) then (red, white).
        let mut b = header(2, 2, 2, 24, 0);
        b.extend_from_slice(&[255, 0, 0, 0, 255, 0, 0, 0, 255, 255, 255, 255]);
        let t = decode(&b).unwrap();
        assert_eq!(
            t.rgb,
            vec![[255, 0, 0], [255, 255, 255], [0, 0, 255], [0, 255, 0]]
        );
    }

    #[test]
    fn rle_top_down_with_alpha_and_raw_packets() {
        // 3x2 top-down 32-bit: a run of 4 red pixels, then a raw packet of 2.
        let mut b = header(10, 3, 2, 32, 0x20);
        b.push(0x80 | 3);
        b.extend_from_slice(&[0, 0, 255, 128]);
        b.push(1);
        b.extend_from_slice(&[10, 20, 30, 255, 40, 50, 60, 255]);
        let t = decode(&b).unwrap();
        assert_eq!(t.rgb[..4], [[255, 0, 0]; 4]);
        assert_eq!(t.rgb[4], [30, 20, 10]);
        assert_eq!(t.rgb[5], [60, 50, 40]);
    }

    #[test]
    fn rle_greyscale_and_errors() {
        let mut b = header(11, 2, 1, 8, 0x20);
        b.extend_from_slice(&[0x81, 77]);
        assert_eq!(decode(&b).unwrap().rgb, vec![[77; 3]; 2]);
        // A run longer than the image, truncated data, unsupported type.
        let mut b = header(11, 2, 1, 8, 0x20);
        b.extend_from_slice(&[0x85, 77]);
        assert!(decode(&b).is_err());
        let mut b = header(2, 2, 2, 24, 0);
        b.extend_from_slice(&[1, 2, 3]);
        assert!(decode(&b).is_err());
        assert!(decode(&header(1, 2, 2, 8, 0)).is_err());
        assert!(decode(&[0u8; 5]).is_err());
    }
}
