use super::*;

const HEADER_TAIL: &str = "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n\
property float nx\nproperty float ny\nproperty float nz\nproperty float u\nproperty float v\n\
property uchar flags\nelement face 2\nproperty list uchar int vertex_indices\n\
property list uchar float extra\nelement junk 1\nproperty list uint short data\nproperty double w\nend_header\n";

/// Vertex rows: position, normal, uv, flags.
fn verts() -> Vec<[f32; 9]> {
    vec![
        [0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 7.0],
        [1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 0.0, 7.0],
        [1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 7.0],
        [0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.0, 7.0],
    ]
}

fn ascii() -> Vec<u8> {
    let mut s = format!("ply\r\nformat ascii 1.0\r\ncomment made by hand\n{HEADER_TAIL}");
    for v in verts() {
        let row: Vec<String> = v.iter().map(|x| x.to_string()).collect();
        s += &row.join(" ");
        s += "\n";
    }
    s += "3 0 1 2 1 0.5\n3 0 2 3 0\n2 -1 1 2.5\n";
    s.into_bytes()
}

fn binary(big: bool) -> Vec<u8> {
    let fmt = if big {
        "binary_big_endian"
    } else {
        "binary_little_endian"
    };
    let mut b = format!("ply\nformat {fmt} 1.0\n{HEADER_TAIL}").into_bytes();
    let f = |b: &mut Vec<u8>, x: f32| {
        b.extend(if big {
            x.to_be_bytes()
        } else {
            x.to_le_bytes()
        })
    };
    let i = |b: &mut Vec<u8>, x: i32| {
        b.extend(if big {
            x.to_be_bytes()
        } else {
            x.to_le_bytes()
        })
    };
    for v in verts() {
        for x in &v[..8] {
            f(&mut b, *x);
        }
        b.push(v[8] as u8);
    }
    for tri in [[0, 1, 2], [0, 2, 3]] {
        b.push(3);
        for x in tri {
            i(&mut b, x);
        }
        b.push(0);
    }
    b.extend(if big {
        2u32.to_be_bytes()
    } else {
        2u32.to_le_bytes()
    });
    b.extend([0u8; 4]);
    b.extend(if big {
        2.5f64.to_be_bytes()
    } else {
        2.5f64.to_le_bytes()
    });
    b
}

fn check_square(m: &PlyMesh) {
    assert_eq!(m.positions.len(), 4);
    assert_eq!(m.positions[2], Vec3::new(1.0, 1.0, 0.0));
    assert_eq!(m.normals.as_ref().unwrap()[3], Vec3::Z);
    assert_eq!(m.uvs.as_ref().unwrap()[1], Vec2::new(1.0, 0.0));
    assert_eq!(m.indices, vec![0, 1, 2, 0, 2, 3]);
}

#[test]
fn ascii_with_crlf_header_and_skipped_properties() {
    check_square(&parse_ply(&ascii()).unwrap());
}

#[test]
fn binary_both_endiannesses() {
    check_square(&parse_ply(&binary(false)).unwrap());
    check_square(&parse_ply(&binary(true)).unwrap());
}

#[test]
fn data_may_start_with_a_newline_byte() {
    let mut b = b"ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty uchar x\n\
property uchar y\nproperty uchar z\nend_header\n"
        .to_vec();
    b.extend([0x0A, 0x0B, 0x0C]);
    let m = parse_ply(&b).unwrap();
    assert_eq!(m.positions, vec![Vec3::new(10.0, 11.0, 12.0)]);
    assert!(m.normals.is_none() && m.uvs.is_none());
}

#[test]
fn quads_and_pentagons_are_fan_triangulated() {
    let s = "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\nproperty float z\n\
element face 2\nproperty list uchar uint vertex_index\nend_header\n\
0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 2 0\n4 0 1 2 3\n5 0 1 2 3 4\n";
    let m = parse_ply(s.as_bytes()).unwrap();
    assert_eq!(m.indices, vec![0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 2, 3, 0, 3, 4]);
}

#[test]
fn out_of_range_index_is_an_error() {
    let s = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n3 0 1 3\n";
    let e = parse_ply(s.as_bytes()).unwrap_err().to_string();
    assert!(e.contains("vertex index 3 is out of range"), "{e}");
}

#[test]
fn absurd_counts_are_refused_before_allocating() {
    let s = "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\n\
property float y\nproperty float z\nend_header\n\0\0\0\0";
    let e = parse_ply(s.as_bytes()).unwrap_err().to_string();
    assert!(
        e.contains("PLY header declares 4000000000 vertices but the file has only 4 bytes of data"),
        "{e}"
    );
}

#[test]
fn truncated_and_malformed_inputs_are_errors() {
    let mut b = binary(false);
    b.truncate(b.len() - 10);
    assert!(parse_ply(&b).is_err());
    assert!(parse_ply(b"not a ply\n")
        .unwrap_err()
        .to_string()
        .contains("not a PLY file"));
    assert!(parse_ply(b"ply\nformat ascii 1.0\nelement vertex 1\n").is_err());
    let e = parse_ply(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n1\n");
    assert!(e
        .unwrap_err()
        .to_string()
        .contains("unknown property type `quad`"));
    let e = parse_ply(b"ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nend_header\n1 2 zz\n");
    assert!(e.unwrap_err().to_string().contains("`zz` is not a number"));
    assert!(matches!(
        parse_ply(&[0x1f, 0x8b, 8, 0]),
        Err(PlyError::Gzip { .. })
    ));
    // A valid gzip stream of garbage is a PLY error, not a panic.
    let junk = gzip(b"not a ply\n");
    assert!(parse_ply(&junk)
        .unwrap_err()
        .to_string()
        .contains("not a PLY file"));
}

#[test]
fn read_ply_names_the_file() {
    let e = read_ply(Path::new("/nonexistent/mesh.ply"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("/nonexistent/mesh.ply"), "{e}");
    let dir = std::env::temp_dir().join(format!("lumis-ply-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("bad.ply");
    std::fs::write(&p, b"ply\nformat ascii 1.0\nelement vertex 1\nend_header\n").unwrap();
    let e = read_ply(&p).unwrap_err().to_string();
    assert!(e.contains("bad.ply") && e.contains("lacks x"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}

fn gzip(data: &[u8]) -> Vec<u8> {
    use std::io::Write;
    let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::default());
    enc.write_all(data).unwrap();
    enc.finish().unwrap()
}

#[test]
fn gzipped_ply_reads_like_the_plain_file() {
    let text = b"ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let plain = parse_ply(text).unwrap();
    let dir = std::env::temp_dir().join(format!("lumis-plygz-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("tri.ply.gz");
    std::fs::write(&p, gzip(text)).unwrap();
    let gz = read_ply(&p).unwrap();
    assert_eq!(gz.positions, plain.positions);
    assert_eq!(gz.indices, plain.indices);
    let bad = dir.join("cut.ply.gz");
    let g = gzip(text);
    std::fs::write(&bad, &g[..g.len() / 2]).unwrap();
    let e = read_ply(&bad).unwrap_err().to_string();
    assert!(e.contains("cut.ply.gz") && e.contains("gzip"), "{e}");
    std::fs::remove_dir_all(&dir).ok();
}
