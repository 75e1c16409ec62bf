//! Output files: their default names, and a check that they can be written
//! before any time is spent rendering.

use crate::image_io::ImageFormat;
use std::path::{Path, PathBuf};

/// `<stem>.exr` and `<stem>.png`, `<stem>` from the Film's filename or `lumis`.
pub fn default_outputs(film_filename: Option<&str>) -> Vec<PathBuf> {
    let stem = film_filename
        .and_then(|f| Path::new(f).file_stem())
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_else(|| "lumis".to_string());
    vec![
        PathBuf::from(format!("{stem}.exr")),
        PathBuf::from(format!("{stem}.png")),
    ]
}

/// Refuses an output whose format is unknown or whose folder cannot take a
/// new file (missing, not a folder, read-only), by creating and removing a
/// temporary file there.
pub fn check_writable(path: &Path) -> Result<(), String> {
    ImageFormat::from_path(path).map_err(|e| e.to_string())?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    if !dir.is_dir() {
        return Err(format!(
            "cannot write {}: the folder {} does not exist",
            path.display(),
            dir.display()
        ));
    }
    let probe = dir.join(format!(".lumis-write-check-{}", std::process::id()));
    match std::fs::File::create(&probe) {
        Ok(_) => {
            let _ = std::fs::remove_file(&probe);
            Ok(())
        }
        Err(e) => Err(format!("cannot write {}: {e}", path.display())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outputs_are_named_and_checked() {
        assert_eq!(
            default_outputs(Some("renders/glass.exr")),
            vec![PathBuf::from("glass.exr"), PathBuf::from("glass.png")]
        );
        assert_eq!(default_outputs(None)[0], PathBuf::from("lumis.exr"));
        let e = check_writable(Path::new("/no/such/dir/x.exr")).unwrap_err();
        assert!(e.contains("does not exist"), "{e}");
        assert!(check_writable(Path::new("x.bmp")).is_err());
        let dir = std::env::temp_dir();
        assert!(check_writable(&dir.join("ok.exr")).is_ok());
    }
}
