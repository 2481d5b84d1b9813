//! Minimal `.npy` (NumPy format 1.0–3.0) reader and writer for little-endian float32 arrays
//! in C order, with a reader that validates every header field and names what is wrong.

use crate::error::DatasetError;
use std::io::{Read, Write};
use std::path::Path;

/// The first bytes of every `.npy` file.
pub const MAGIC: &[u8; 6] = b"\x93NUMPY";

/// An n-dimensional float32 array in C order.
#[derive(Debug, Clone, PartialEq)]
pub struct NpyArray {
    pub shape: Vec<usize>,
    pub data: Vec<f32>,
}

/// The header text NumPy writes for a `<f4` C-order array, padded so the data starts on a
/// 64-byte boundary (what `numpy.save` does).
pub fn header_bytes(shape: &[usize]) -> Vec<u8> {
    let dims: Vec<String> = shape.iter().map(|d| d.to_string()).collect();
    let shape_text = if dims.len() == 1 {
        format!("({},)", dims[0])
    } else {
        format!("({})", dims.join(", "))
    };
    let mut dict = format!("{{'descr': '<f4', 'fortran_order': False, 'shape': {shape_text}, }}");
    let unpadded = MAGIC.len() + 2 + 2 + dict.len() + 1;
    let pad = (64 - unpadded % 64) % 64;
    dict.push_str(&" ".repeat(pad));
    dict.push('\n');
    let mut out = Vec::with_capacity(10 + dict.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&[1, 0]);
    out.extend_from_slice(&(dict.len() as u16).to_le_bytes());
    out.extend_from_slice(dict.as_bytes());
    out
}

/// Writes `data` with `shape` as a `.npy` stream. The caller owns buffering and atomicity.
pub fn write_npy<W: Write>(mut w: W, shape: &[usize], data: &[f32]) -> std::io::Result<()> {
    assert_eq!(
        shape.iter().product::<usize>(),
        data.len(),
        "shape and data length disagree"
    );
    w.write_all(&header_bytes(shape))?;
    write_f32_le(&mut w, data)?;
    w.flush()
}

/// Writes float32 values little-endian (the `.npy` body after the header).
pub fn write_f32_le<W: Write>(w: &mut W, data: &[f32]) -> std::io::Result<()> {
    if cfg!(target_endian = "little") {
        // Write in 8 MiB pieces so a failing sink fails early.
        for chunk in data.chunks(2 << 20) {
            w.write_all(bytemuck::cast_slice(chunk))?;
        }
    } else {
        for v in data {
            w.write_all(&v.to_le_bytes())?;
        }
    }
    Ok(())
}

/// Parsed header fields.
#[derive(Debug, PartialEq)]
struct Header {
    descr: String,
    fortran_order: bool,
    shape: Vec<usize>,
}

fn malformed(path: &Path, reason: impl Into<String>) -> DatasetError {
    DatasetError::MalformedNpy {
        path: path.to_path_buf(),
        reason: reason.into(),
    }
}

/// Extracts the value text after `'key':` up to the next top-level comma or closing brace.
fn dict_value<'a>(dict: &'a str, key: &str) -> Option<&'a str> {
    let pat_single = format!("'{key}'");
    let pat_double = format!("\"{key}\"");
    let start = dict
        .find(&pat_single)
        .map(|i| i + pat_single.len())
        .or_else(|| dict.find(&pat_double).map(|i| i + pat_double.len()))?;
    let rest = dict[start..].trim_start().strip_prefix(':')?.trim_start();
    let mut depth = 0i32;
    for (i, c) in rest.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            ',' | '}' if depth == 0 => return Some(rest[..i].trim()),
            _ => {}
        }
    }
    None
}

fn parse_header(path: &Path, dict: &str) -> Result<Header, DatasetError> {
    let dict = dict.trim();
    if !dict.starts_with('{') || !dict.ends_with('}') {
        return Err(malformed(path, "header is not a Python dict literal"));
    }
    let descr = dict_value(dict, "descr")
        .ok_or_else(|| malformed(path, "header has no 'descr'"))?
        .trim_matches(|c| c == '\'' || c == '"')
        .to_string();
    let fortran_order = match dict_value(dict, "fortran_order") {
        Some("False") => false,
        Some("True") => true,
        Some(other) => return Err(malformed(path, format!("fortran_order is '{other}'"))),
        None => return Err(malformed(path, "header has no 'fortran_order'")),
    };
    let shape_text =
        dict_value(dict, "shape").ok_or_else(|| malformed(path, "header has no 'shape'"))?;
    let inner = shape_text
        .strip_prefix('(')
        .and_then(|s| s.strip_suffix(')'))
        .ok_or_else(|| malformed(path, format!("shape '{shape_text}' is not a tuple")))?;
    let shape = inner
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .map(|s| {
            s.trim_end_matches('L').parse::<usize>().map_err(|_| {
                let why = if s.starts_with('-') && s[1..].parse::<u64>().is_ok() {
                    "is negative"
                } else {
                    "is not an integer"
                };
                malformed(path, format!("shape entry '{s}' {why}"))
            })
        })
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Header {
        descr,
        fortran_order,
        shape,
    })
}

/// Reads a little-endian float32 C-order `.npy` file, validating magic, version, header,
/// dtype, order and the data length.
pub fn read_npy(path: &Path) -> Result<NpyArray, DatasetError> {
    let (mut r, shape, count) = open_npy(path)?;
    let mut data = vec![0f32; count];
    r.read_exact(bytemuck::cast_slice_mut(&mut data))
        .map_err(|source| DatasetError::Read {
            path: path.to_path_buf(),
            source,
        })?;
    if cfg!(target_endian = "big") {
        for v in &mut data {
            *v = f32::from_le_bytes(v.to_ne_bytes());
        }
    }
    Ok(NpyArray { shape, data })
}

/// The shape of a `.npy` file, validated as `read_npy` validates it (the data's length
/// included), without reading its data.
pub fn read_npy_shape(path: &Path) -> Result<Vec<usize>, DatasetError> {
    open_npy(path).map(|(_, shape, _)| shape)
}

/// Opens a `.npy` file and checks everything but its values: a reader at its data, its shape
/// and its number of values.
fn open_npy(
    path: &Path,
) -> Result<(std::io::BufReader<std::fs::File>, Vec<usize>, usize), DatasetError> {
    let read_err = |source| DatasetError::Read {
        path: path.to_path_buf(),
        source,
    };
    if path.is_dir() {
        return Err(malformed(path, "it is a directory"));
    }
    crate::input::check_kind(path).map_err(|e| malformed(path, e))?;
    let file = std::fs::File::open(path).map_err(read_err)?;
    let file_len = file.metadata().map_err(read_err)?.len();
    let mut r = std::io::BufReader::new(file);
    let mut preamble = [0u8; 8];
    r.read_exact(&mut preamble)
        .map_err(|_| malformed(path, "file is shorter than the .npy preamble"))?;
    if &preamble[..6] != MAGIC {
        return Err(malformed(path, "missing the \\x93NUMPY magic string"));
    }
    let major = preamble[6];
    let header_len = match major {
        1 => {
            let mut b = [0u8; 2];
            r.read_exact(&mut b)
                .map_err(|_| malformed(path, "truncated header length"))?;
            u16::from_le_bytes(b) as usize
        }
        2 | 3 => {
            let mut b = [0u8; 4];
            r.read_exact(&mut b)
                .map_err(|_| malformed(path, "truncated header length"))?;
            u32::from_le_bytes(b) as usize
        }
        v => return Err(malformed(path, format!("unsupported format version {v}"))),
    };
    let prefix = if major == 1 { 10 } else { 12 };
    if (prefix + header_len) as u64 > file_len {
        return Err(malformed(path, "header runs past the end of the file"));
    }
    let mut header = vec![0u8; header_len];
    r.read_exact(&mut header)
        .map_err(|_| malformed(path, "truncated header"))?;
    let header = String::from_utf8(header).map_err(|_| malformed(path, "header is not text"))?;
    let h = parse_header(path, &header)?;
    if h.descr != "<f4" && !(cfg!(target_endian = "little") && h.descr == "=f4") {
        return Err(DatasetError::WrongDtype {
            path: path.to_path_buf(),
            found: h.descr,
        });
    }
    if h.fortran_order && h.shape.iter().filter(|&&d| d > 1).count() > 1 {
        return Err(DatasetError::FortranOrder {
            path: path.to_path_buf(),
        });
    }
    let count = h
        .shape
        .iter()
        .try_fold(1usize, |acc, &d| acc.checked_mul(d))
        .ok_or_else(|| malformed(path, "shape overflows"))?;
    let expected_bytes = (count as u64).saturating_mul(4);
    let data_bytes = file_len - (prefix + header_len) as u64;
    // Checked before anything is allocated: a sparse file can back a header of any size.
    if data_bytes == expected_bytes && !crate::memory::fits(expected_bytes, 3) {
        return Err(DatasetError::TooLarge {
            path: path.to_path_buf(),
            bytes: expected_bytes,
            available: crate::memory::available().unwrap_or(0),
        });
    }
    if data_bytes != expected_bytes {
        return Err(malformed(
            path,
            format!(
                "shape {:?} needs {expected_bytes} data bytes but the file holds {data_bytes} (truncated or padded)",
                h.shape
            ),
        ));
    }
    Ok((r, h.shape, count))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn write_tmp(bytes: &[u8]) -> (tempfile::TempDir, std::path::PathBuf) {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("a.npy");
        std::fs::write(&p, bytes).unwrap();
        (dir, p)
    }

    #[test]
    fn header_is_64_byte_aligned_and_numpy_shaped() {
        for shape in [vec![3usize], vec![500, 20, 1, 50, 50], vec![]] {
            let h = header_bytes(&shape);
            assert_eq!(h.len() % 64, 0);
            assert_eq!(*h.last().unwrap(), b'\n');
        }
        let h = String::from_utf8_lossy(&header_bytes(&[7])).to_string();
        assert!(h.contains("'shape': (7,)"));
    }

    #[test]
    fn round_trip() {
        let data: Vec<f32> = (0..24).map(|i| i as f32 * 0.5 - 3.0).collect();
        let mut bytes = Vec::new();
        write_npy(&mut bytes, &[2, 3, 4], &data).unwrap();
        let (_d, p) = write_tmp(&bytes);
        let a = read_npy(&p).unwrap();
        assert_eq!(a.shape, vec![2, 3, 4]);
        assert_eq!(a.data, data);
    }

    #[test]
    fn rejects_float64_with_the_fix() {
        let mut bytes = header_bytes(&[2]);
        let pos = bytes.windows(3).position(|w| w == b"<f4").unwrap();
        bytes[pos + 2] = b'8';
        bytes.extend_from_slice(&[0u8; 16]);
        let (_d, p) = write_tmp(&bytes);
        let e = read_npy(&p).unwrap_err().to_string();
        assert!(e.contains("'<f8'") && e.contains("astype"), "{e}");
    }

    #[test]
    fn rejects_truncated_data_and_bad_magic_and_bad_header() {
        let mut bytes = Vec::new();
        write_npy(&mut bytes, &[4], &[1.0, 2.0, 3.0, 4.0]).unwrap();
        bytes.truncate(bytes.len() - 3);
        let (_d, p) = write_tmp(&bytes);
        assert!(read_npy(&p).unwrap_err().to_string().contains("truncated"));

        let (_d, p) = write_tmp(b"not an npy file at all");
        assert!(read_npy(&p).unwrap_err().to_string().contains("magic"));

        let mut bytes = header_bytes(&[4]);
        let pos = bytes.windows(5).position(|w| w == b"shape").unwrap();
        bytes[pos] = b'x';
        let (_d, p) = write_tmp(&bytes);
        assert!(read_npy(&p).unwrap_err().to_string().contains("no 'shape'"));
    }

    #[test]
    fn parses_numpy_variants() {
        let h = parse_header(
            Path::new("x"),
            "{'descr': '<f4', 'fortran_order': False, 'shape': (2, 3), }",
        )
        .unwrap();
        assert_eq!(h.shape, vec![2, 3]);
        let h = parse_header(
            Path::new("x"),
            "{'shape': (), 'fortran_order': True, 'descr': '<f8'}",
        )
        .unwrap();
        assert!(h.shape.is_empty() && h.fortran_order && h.descr == "<f8");
    }
}
