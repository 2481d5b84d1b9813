//! Text on a terminal: control characters from file names, model files or data (an escape
//! sequence, a carriage return, a newline that splits a one-line refusal, a bidirectional
//! override) are shown escaped, never sent raw; and standard output that cannot be written (a
//! full disk, a closed pipe) is an error to report, not a panic.

use std::borrow::Cow;
use std::io::Write;

/// Whether `c` must not reach a terminal raw: C0 and C1 controls and the bidirectional
/// overrides and isolates. `keep_newlines` lets `\n` through (multi-line tables).
fn unsafe_char(c: char, keep_newlines: bool) -> bool {
    (c.is_control() && !(keep_newlines && c == '\n'))
        || ('\u{202a}'..='\u{202e}').contains(&c)
        || ('\u{2066}'..='\u{2069}').contains(&c)
}

fn escaped(text: &str, keep_newlines: bool) -> Cow<'_, str> {
    if !text.chars().any(|c| unsafe_char(c, keep_newlines)) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if !unsafe_char(c, keep_newlines) {
            out.push(c);
            continue;
        }
        match c {
            '\n' => out.push_str("\\n"),
            '\r' => out.push_str("\\r"),
            '\t' => out.push_str("\\t"),
            c if (c as u32) < 0x100 => out.push_str(&format!("\\x{:02x}", c as u32)),
            c => out.push_str(&format!("\\u{{{:x}}}", c as u32)),
        }
    }
    Cow::Owned(out)
}

/// `text` with every control character escaped but the newline (a table, a verdict's lines).
pub fn clean(text: &str) -> Cow<'_, str> {
    escaped(text, true)
}

/// `text` as one line: every control character escaped, the newline too (a refusal, a
/// warning, a progress line).
pub fn one_line(text: &str) -> Cow<'_, str> {
    escaped(text, false)
}

/// Writes `text` (cleaned) and a newline to standard output and flushes it. A write that
/// fails (a full disk, a closed pipe) is returned as an error naming standard output.
pub fn print(text: &str) -> Result<(), StdoutError> {
    write_to(&mut std::io::stdout().lock(), text)
}

fn write_to(w: &mut impl Write, text: &str) -> Result<(), StdoutError> {
    let cleaned = clean(text);
    w.write_all(cleaned.as_bytes())
        .and_then(|()| {
            if cleaned.ends_with('\n') {
                Ok(())
            } else {
                w.write_all(b"\n")
            }
        })
        .and_then(|()| w.flush())
        .map_err(StdoutError)
}

/// Writes `text` as one line (escaped) to standard error, ignoring a failure: there is
/// nowhere left to report it.
pub fn eprint_line(text: &str) {
    let mut err = std::io::stderr().lock();
    let _ = err
        .write_all(one_line(text).as_bytes())
        .and_then(|()| err.write_all(b"\n"));
}

/// Writes `text` with its newlines kept (every other control escaped) to standard error,
/// ignoring a failure.
pub fn eprint(text: &str) {
    let mut err = std::io::stderr().lock();
    let cleaned = clean(text);
    let _ = err.write_all(cleaned.as_bytes()).and_then(|()| {
        if cleaned.ends_with('\n') {
            Ok(())
        } else {
            err.write_all(b"\n")
        }
    });
}

/// Standard output could not be written.
#[derive(Debug, thiserror::Error)]
#[error("cannot write to standard output ({0})")]
pub struct StdoutError(#[source] pub std::io::Error);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn control_characters_are_shown_escaped() {
        assert_eq!(clean("plain\ntext"), "plain\ntext");
        assert!(matches!(clean("plain"), Cow::Borrowed(_)));
        assert_eq!(clean("a\u{1b}[31mred"), "a\\x1b[31mred");
        assert_eq!(one_line("two\nlines\r"), "two\\nlines\\r");
        assert_eq!(one_line("x\u{202e}y\u{9b}"), "x\\u{202e}y\\x9b");
        assert_eq!(one_line("Größe °C"), "Größe °C");
    }

    #[test]
    fn a_failing_stdout_is_an_error_not_a_panic() {
        struct Full;
        impl Write for Full {
            fn write(&mut self, _: &[u8]) -> std::io::Result<usize> {
                Err(std::io::Error::from_raw_os_error(libc::ENOSPC))
            }
            fn flush(&mut self) -> std::io::Result<()> {
                Ok(())
            }
        }
        let e = write_to(&mut Full, "table").unwrap_err();
        assert!(e.to_string().contains("standard output"), "{e}");
        let mut v = Vec::new();
        write_to(&mut v, "a\u{7}b").unwrap();
        assert_eq!(v, b"a\\x07b\n");
    }
}
