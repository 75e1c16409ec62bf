//! The hash of a scene's inputs: its top-level text when given as text and
//! the contents of every file read to build it (scene files, meshes, images,
//! spectra), so that a checkpoint can tell whether a scene is still the same.

use crate::checkpoint::Fnv;
use lumis_scene::Inputs;
use std::io::Read;

/// Hashes `inputs`: the text, then each file's contents in first-read order
/// (length-prefixed, so the boundaries count). Paths are not hashed: the same
/// files reached by another path are the same scene. A file that cannot be
/// read any more hashes as such, unlike any contents.
pub fn inputs_hash(inputs: &Inputs) -> u64 {
    let mut h = Fnv::default();
    match &inputs.text {
        Some(t) => h.write(b"text").write_str(t),
        None => h.write(b"file"),
    };
    h.write(&(inputs.files.len() as u64).to_le_bytes());
    for f in &inputs.files {
        if hash_file(&mut h, f).is_err() {
            h.write(b"unreadable");
        }
    }
    h.0
}

/// The file's contents, then their length.
fn hash_file(h: &mut Fnv, path: &std::path::Path) -> std::io::Result<()> {
    let mut file = std::fs::File::open(path)?;
    let mut buf = vec![0u8; 1 << 16];
    let mut len = 0u64;
    loop {
        let n = file.read(&mut buf)?;
        if n == 0 {
            break;
        }
        h.write(&buf[..n]);
        len += n as u64;
    }
    h.write(&len.to_le_bytes());
    Ok(())
}
