//! What an input path may be: a regular file or a directory. A FIFO, a device or a socket is
//! refused before it is opened: reading one blocks until another process writes, or never
//! ends (`/dev/zero`).

use std::path::Path;

/// Refuses `path` when it exists and is neither a regular file nor a directory, with what it
/// is; a path that does not exist is left to the reader's own message.
pub fn check_kind(path: &Path) -> Result<(), String> {
    let Ok(meta) = std::fs::metadata(path) else {
        return Ok(());
    };
    let t = meta.file_type();
    if t.is_file() || t.is_dir() {
        return Ok(());
    }
    #[cfg(unix)]
    let kind = {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            "a FIFO (named pipe)"
        } else if t.is_char_device() || t.is_block_device() {
            "a device"
        } else if t.is_socket() {
            "a socket"
        } else {
            "not a regular file"
        }
    };
    #[cfg(not(unix))]
    let kind = "not a regular file";
    Err(format!(
        "{}: {kind}; reading it could block or never end: give a regular file (save the stream \
         to a file first)",
        path.display()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn files_and_directories_pass_devices_do_not() {
        let tmp = std::env::temp_dir();
        assert!(check_kind(&tmp).is_ok());
        assert!(check_kind(Path::new("/no/such/path")).is_ok());
        #[cfg(unix)]
        {
            let e = check_kind(Path::new("/dev/zero")).unwrap_err();
            assert!(e.contains("a device"), "{e}");
        }
    }
}
