//! `ConfigError`: a flag or scene parameter outside its valid range, naming the flag, the value
//! and what is expected.

/// A flag outside its valid range; the message names the flag, the value and the range.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{flag} {value}: {expected}")]
pub struct ConfigError {
    pub flag: &'static str,
    pub value: String,
    pub expected: String,
}

/// A [`ConfigError`] for `flag`.
pub fn invalid(
    flag: &'static str,
    value: impl ToString,
    expected: impl Into<String>,
) -> ConfigError {
    ConfigError {
        flag,
        value: value.to_string(),
        expected: expected.into(),
    }
}
