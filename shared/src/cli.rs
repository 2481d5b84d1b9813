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

/// Parses `NAME=VALUE[,NAME=VALUE...]` (as `--init` and `--set` take) into pairs, in order.
pub fn parse_name_values(text: &str) -> Result<Vec<(String, f64)>, String> {
    text.split(',')
        .filter(|s| !s.trim().is_empty())
        .map(|pair| {
            let (k, v) = pair
                .split_once('=')
                .ok_or_else(|| format!("'{pair}' is not NAME=VALUE"))?;
            let v: f64 = v
                .trim()
                .parse()
                .map_err(|_| format!("'{}' in '{pair}' is not a number", v.trim()))?;
            Ok((k.trim().to_string(), v))
        })
        .collect()
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
    fn name_value_pairs_parse_and_name_the_bad_part() {
        assert_eq!(
            super::parse_name_values("a=1, b = 2.5,").unwrap(),
            vec![("a".to_string(), 1.0), ("b".to_string(), 2.5)]
        );
        assert!(super::parse_name_values("a")
            .unwrap_err()
            .contains("NAME=VALUE"));
        assert!(super::parse_name_values("a=x").unwrap_err().contains("'x'"));
    }

    #[test]
    fn folds_clap_text() {
        let t = "error: invalid value 'x' for '--scenario <SCENARIO>'\n  [possible values: a, b]\n\nFor more information, try '--help'.\n";
        assert_eq!(
            super::one_line(t),
            "error: invalid value 'x' for '--scenario <SCENARIO>' [possible values: a, b]"
        );
    }
}
