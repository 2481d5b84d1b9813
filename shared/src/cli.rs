//! Command-line helpers shared by the binaries: clap errors as one line with exit code 2.

use std::process::ExitCode;

/// Folds clap's multi-line error text into one line, dropping the usage and "try --help" hints.
pub fn one_line(text: &str) -> String {
    text.lines()
        .map(str::trim)
        .filter(|l| {
            !l.is_empty() && !l.starts_with("For more information") && !l.starts_with("Usage:")
        })
        .collect::<Vec<_>>()
        .join(" ")
}

/// Prints help or version (exit 0), or the parse error as one line (exit 2).
pub fn exit_on_clap_error(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let _ = e.print();
            ExitCode::SUCCESS
        }
        _ => {
            eprintln!("{}", one_line(&e.render().to_string()));
            ExitCode::from(2)
        }
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn folds_clap_text() {
        let t = "error: invalid value 'x' for '--scenario <SCENARIO>'\n  [possible values: a, b]\n\nFor more information, try '--help'.\n";
        assert_eq!(
            super::one_line(t),
            "error: invalid value 'x' for '--scenario <SCENARIO>' [possible values: a, b]"
        );
    }
}
