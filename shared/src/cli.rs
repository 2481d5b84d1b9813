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

/// Parses `NAME=VALUE[,NAME=VALUE...]` (as `--init` and `--set` take) into pairs, in order. A
/// name given twice (which value would win?), an empty name and a value that is not a finite
/// number are refused.
pub fn parse_name_values(text: &str) -> Result<Vec<(String, f64)>, String> {
    let mut out: Vec<(String, f64)> = Vec::new();
    for pair in text.split(',').filter(|s| !s.trim().is_empty()) {
        let (k, v) = pair
            .split_once('=')
            .ok_or_else(|| format!("'{pair}' is not NAME=VALUE"))?;
        let k = k.trim();
        if k.is_empty() {
            return Err(format!("'{pair}' has no name before '='"));
        }
        let v: f64 = v
            .trim()
            .parse()
            .map_err(|_| format!("'{}' in '{pair}' is not a number", v.trim()))?;
        if !v.is_finite() {
            return Err(format!("'{pair}': the value must be a finite number"));
        }
        if out.iter().any(|(name, _)| name == k) {
            return Err(format!("'{k}' is given twice; give each name once"));
        }
        out.push((k.to_string(), v));
    }
    Ok(out)
}

/// A number for a message: plain when moderate, in scientific notation when huge or tiny
/// (1e300 is not printed as 301 digits).
pub fn num(v: f64) -> String {
    if v != 0.0 && v.is_finite() && !(1e-4..1e6).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// A computed number for a message, to four significant digits (1234, 0.1235, 1.235e-7).
pub fn approx(v: f64) -> String {
    if v == 0.0 {
        return "0".to_string();
    }
    if v.is_finite() && !(1e-3..1e5).contains(&v.abs()) {
        format!("{v:.3e}")
    } else {
        let s = format!(
            "{:.*}",
            (3 - v.abs().log10().floor() as i64).clamp(0, 6) as usize,
            v
        );
        if s.contains('.') {
            s.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            s
        }
    }
}

/// The most worker threads `--threads` takes: beyond a few per core threads only add
/// overhead, and tens of thousands exhaust the stack and the OpenMP runtime.
pub const MAX_THREADS: usize = 256;

/// `--threads`' parser: a whole number from 1 to [`MAX_THREADS`].
pub fn thread_count(text: &str) -> Result<usize, String> {
    let n: usize = text
        .trim()
        .parse()
        .map_err(|_| format!("'{text}' is not a whole number"))?;
    if (1..=MAX_THREADS).contains(&n) {
        Ok(n)
    } else {
        Err(format!("{n}: must be from 1 to {MAX_THREADS}"))
    }
}

/// Prints help or version (exit 0), or the parse error as one line (exit 2).
pub fn exit_on_clap_error(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => match e.print() {
            Ok(()) => ExitCode::SUCCESS,
            Err(io) => {
                crate::term::eprint_line(&format!("error: cannot write to standard output ({io})"));
                ExitCode::FAILURE
            }
        },
        _ => {
            crate::term::eprint_line(&one_line(&e.render().to_string()));
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
        assert!(super::parse_name_values("a=1,a=2")
            .unwrap_err()
            .contains("given twice"));
        assert!(super::parse_name_values("a=nan")
            .unwrap_err()
            .contains("finite"));
        assert!(super::parse_name_values("=3")
            .unwrap_err()
            .contains("no name"));
    }

    #[test]
    fn numbers_in_messages_stay_short() {
        assert_eq!(super::num(0.2), "0.2");
        assert_eq!(super::num(1e300), "1e300");
        assert_eq!(super::num(-1e-30), "-1e-30");
        assert_eq!(super::num(f64::NAN), "NaN");
        assert_eq!(super::approx(9904.544411531508), "9905");
        assert_eq!(super::approx(0.67295), "0.673");
        assert_eq!(super::approx(3.17e-5), "3.170e-5");
        assert_eq!(super::approx(2.0), "2");
        assert_eq!(super::approx(0.0), "0");
    }

    #[test]
    fn thread_counts_are_bounded() {
        assert_eq!(super::thread_count("3"), Ok(3));
        for bad in ["0", "257", "100000", "-1", "x"] {
            assert!(super::thread_count(bad).is_err(), "{bad}");
        }
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
