//! Image folders as recordings: the ffmpeg concat list that feeds the folder's images to the
//! same decoder as a video (one time unit per image, so ffmpeg keeps every frame in order),
//! and, when decoding fails, the first image that does not decode, to name it.

use super::{bad, VideoError};
use crate::interrupt::{Kind, Registered};
use std::path::{Path, PathBuf};

/// A concat list for `files`, written to a temporary file removed when dropped (a fresh random
/// name created exclusively in the temporary folder, private to this user: no name another
/// user could plant a link at).
pub(super) fn concat_list(files: &[PathBuf]) -> Result<TempFile, VideoError> {
    let mut text = String::from("ffconcat version 1.0\n");
    for f in files {
        let abs = std::fs::canonicalize(f).map_err(|e| bad(f, e.to_string()))?;
        // The list is lines of UTF-8 text: a name that is not, or that breaks a line, cannot
        // be written into it (ffmpeg would look for another file), so the image is named.
        let name = abs
            .to_str()
            .filter(|n| !n.contains(['\n', '\r']))
            .ok_or_else(|| {
                bad(
                    f,
                    "its name holds a line break or bytes that are not UTF-8, which the list of \
                     images handed to ffmpeg cannot carry; rename it",
                )
            })?;
        text += &format!("file '{}'\nduration 1\n", name.replace('\'', "'\\''"));
    }
    let scratch = |source| VideoError::Scratch {
        path: std::env::temp_dir(),
        source,
    };
    let mut file = tempfile::Builder::new()
        .prefix("physvid-frames-")
        .suffix(".ffconcat")
        .tempfile()
        .map_err(scratch)?;
    let registered = Registered::new(Kind::File, file.path());
    use std::io::Write;
    file.write_all(text.as_bytes())
        .and_then(|()| file.flush())
        .map_err(scratch)?;
    Ok(TempFile {
        file,
        _registered: registered,
    })
}

/// The images' numbers as times, in frames from the first (the last run of digits in each name,
/// their common step one frame: frame_0002, frame_0004, … count as consecutive): a number that
/// is skipped is a frame missing. None where a name has no number or the numbers do not rise.
pub(super) fn numbered(files: &[PathBuf]) -> Option<Vec<f64>> {
    let numbers: Vec<u64> = files
        .iter()
        .map(|f| {
            let stem = f.file_stem()?.to_str()?;
            let end = stem.rfind(|c: char| c.is_ascii_digit())? + 1;
            let start = stem[..end]
                .rfind(|c: char| !c.is_ascii_digit())
                .map_or(0, |i| i + 1);
            stem[start..end].parse().ok()
        })
        .collect::<Option<_>>()?;
    if numbers.windows(2).any(|w| w[1] <= w[0]) {
        return None;
    }
    let gcd = |mut a: u64, mut b: u64| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a
    };
    let step = numbers.windows(2).map(|w| w[1] - w[0]).fold(0, gcd).max(1);
    Some(
        numbers
            .iter()
            .map(|n| ((n - numbers[0]) / step) as f64)
            .collect(),
    )
}

/// Refuses a folder whose images differ in format or size from its first (ffmpeg decodes a
/// folder as one stream of one codec and size), naming the first that differs.
pub(super) fn check_alike(files: &[PathBuf]) -> Result<(), VideoError> {
    let header = |f: &Path| -> Result<(image::ImageFormat, (u32, u32)), String> {
        if std::fs::metadata(f).is_ok_and(|m| m.len() == 0) {
            return Err("an empty file".into());
        }
        let reader = image::ImageReader::open(f)
            .and_then(|r| r.with_guessed_format())
            .map_err(|e| e.to_string())?;
        let format = reader.format().ok_or("not a PNG or JPEG image")?;
        let size = reader.into_dimensions().map_err(|e| e.to_string())?;
        Ok((format, size))
    };
    let Some(first) = files.first() else {
        return Ok(());
    };
    let (format, size) = header(first).map_err(|why| undecodable(0, first, files.len(), &why))?;
    for (i, f) in files.iter().enumerate().skip(1) {
        let (fmt, sz) = header(f).map_err(|why| undecodable(i, f, files.len(), &why))?;
        if fmt != format || sz != size {
            let name = |f: image::ImageFormat| {
                f.extensions_str()
                    .first()
                    .copied()
                    .unwrap_or("?")
                    .to_uppercase()
            };
            return Err(bad(
                f,
                format!(
                    "image {} of {} is a {}×{} {} among {}×{} {} images ({} first); the \
                     folder's images must share one format and size: convert it or remove it",
                    i + 1,
                    files.len(),
                    sz.0,
                    sz.1,
                    name(fmt),
                    size.0,
                    size.1,
                    name(format),
                    first.display()
                ),
            ));
        }
    }
    Ok(())
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

/// Image `i` (from 0) of `n`, `file`, does not decode, for `why`.
fn undecodable(i: usize, file: &Path, n: usize, why: &str) -> VideoError {
    bad(
        file,
        format!(
            "image {} of {n} in the folder does not decode ({why}); replace or remove it (a \
             numbered image removed is a frame missing, filled in from its neighbours)",
            i + 1
        ),
    )
}

/// The error for an image folder that did not decode whole: names the first bad image.
pub(super) fn damaged_folder(
    input: &Path,
    files: &[PathBuf],
    decoded: usize,
    ffmpeg_said: &str,
) -> VideoError {
    match first_unreadable(files) {
        Some((i, f, why)) => undecodable(i, f, files.len(), &why),
        None => bad(
            input,
            format!("{decoded} of {} images decoded: {ffmpeg_said}", files.len()),
        ),
    }
}

/// A temporary file, removed when dropped (and on a signal, while it is registered).
pub(super) struct TempFile {
    file: tempfile::NamedTempFile,
    _registered: Registered,
}

impl TempFile {
    pub(super) fn path(&self) -> &Path {
        self.file.path()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_image_whose_name_the_list_cannot_carry_is_named() {
        use std::os::unix::ffi::OsStrExt;
        let dir = tempfile::tempdir().unwrap();
        let img = image::GrayImage::from_pixel(4, 3, image::Luma([90u8]));
        for name in [
            std::ffi::OsStr::new("f1\nx.png"),
            std::ffi::OsStr::from_bytes(b"f2\xff.png"),
        ] {
            let good = dir.path().join("f0.png");
            let odd = dir.path().join(name);
            img.save(&good).unwrap();
            img.save_with_format(&odd, image::ImageFormat::Png).unwrap();
            let e = concat_list(&[good, odd.clone()])
                .err()
                .expect("refused")
                .to_string();
            assert!(
                e.contains(&odd.display().to_string()) && e.contains("rename it"),
                "{e}"
            );
            std::fs::remove_file(&odd).unwrap();
        }
        // A quote in a name is escaped, not refused.
        let quoted = dir.path().join("it's.png");
        img.save(&quoted).unwrap();
        assert!(concat_list(&[quoted]).is_ok());
    }

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

    #[test]
    fn image_numbers_are_the_clock_and_a_stranger_among_them_is_named() {
        let p = |names: &[&str]| names.iter().map(PathBuf::from).collect::<Vec<_>>();
        assert_eq!(
            numbered(&p(&["f1.png", "f2.png", "f4.png"])),
            Some(vec![0.0, 1.0, 3.0])
        );
        assert_eq!(
            numbered(&p(&["a_0010.png", "a_0012.png", "a_0016.png"])),
            Some(vec![0.0, 1.0, 3.0])
        );
        assert_eq!(numbered(&p(&["x.png", "y2.png"])), None);
        let dir = tempfile::tempdir().unwrap();
        let img = image::GrayImage::from_pixel(4, 3, image::Luma([90u8]));
        let mut files = Vec::new();
        for (i, ext) in ["png", "png", "jpg", "png"].iter().enumerate() {
            let f = dir.path().join(format!("f{i}.{ext}"));
            img.save(&f).unwrap();
            files.push(f);
        }
        let e = check_alike(&files).unwrap_err().to_string();
        assert!(
            e.contains("f2.jpg") && e.contains("image 3 of 4") && e.contains("JPG"),
            "{e}"
        );
    }
}
