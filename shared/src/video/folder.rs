//! Image folders as recordings: the ffmpeg concat list that feeds the folder's images to the
//! same decoder as a video (one time unit per image, so ffmpeg keeps every frame in order),
//! and, when decoding fails, the first image that does not decode, to name it.

use super::{bad, VideoError};
use std::path::{Path, PathBuf};

/// A concat list for `files`, written to a temporary file removed when dropped.
pub(super) fn concat_list(files: &[PathBuf]) -> Result<TempFile, VideoError> {
    let mut text = String::from("ffconcat version 1.0\n");
    for f in files {
        let abs = std::fs::canonicalize(f).map_err(|e| bad(f, e.to_string()))?;
        text += &format!(
            "file '{}'\nduration 1\n",
            abs.to_string_lossy().replace('\'', "'\\''")
        );
    }
    let tmp = tempfile_path();
    std::fs::write(&tmp, text).map_err(|e| bad(&tmp, e.to_string()))?;
    Ok(TempFile(tmp))
}

/// The first of `files` that does not decode as an image: its index, path and why.
pub(super) fn first_unreadable(files: &[PathBuf]) -> Option<(usize, &Path, String)> {
    files.iter().enumerate().find_map(|(i, f)| {
        let why = match std::fs::metadata(f) {
            Ok(m) if m.len() == 0 => Some("an empty file".to_string()),
            Ok(_) => image::open(f).err().map(|e| e.to_string()),
            Err(e) => Some(e.to_string()),
        };
        why.map(|w| (i, f.as_path(), w))
    })
}

/// The error for an image folder that did not decode whole: names the first bad image.
pub(super) fn damaged_folder(
    input: &Path,
    files: &[PathBuf],
    decoded: usize,
    ffmpeg_said: &str,
) -> VideoError {
    match first_unreadable(files) {
        Some((i, f, why)) => bad(
            f,
            format!(
                "image {} of {} in the folder does not decode ({why}); replace or remove it \
                 (the frames after a removed image shift by one frame interval)",
                i + 1,
                files.len()
            ),
        ),
        None => bad(
            input,
            format!("{decoded} of {} images decoded: {ffmpeg_said}", files.len()),
        ),
    }
}

/// A file removed when dropped.
pub(super) struct TempFile(pub PathBuf);

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.0);
    }
}

fn tempfile_path() -> PathBuf {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static COUNTER: AtomicUsize = AtomicUsize::new(0);
    std::env::temp_dir().join(format!(
        "physvid-frames-{}-{}.ffconcat",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_first_image_that_does_not_decode_is_named() {
        let dir = tempfile::tempdir().unwrap();
        let img = image::GrayImage::from_pixel(4, 3, image::Luma([90u8]));
        let mut files = Vec::new();
        for i in 0..4 {
            let p = dir.path().join(format!("f{i}.png"));
            img.save(&p).unwrap();
            files.push(p);
        }
        assert!(first_unreadable(&files).is_none());
        let bytes = std::fs::read(&files[2]).unwrap();
        std::fs::write(&files[2], &bytes[..bytes.len() / 2]).unwrap();
        std::fs::write(&files[3], b"").unwrap();
        let (i, f, _) = first_unreadable(&files).unwrap();
        assert_eq!((i, f), (2, files[2].as_path()));
        std::fs::write(&files[2], &bytes).unwrap();
        let (i, _, why) = first_unreadable(&files).unwrap();
        assert_eq!((i, why.as_str()), (3, "an empty file"));
    }
}
