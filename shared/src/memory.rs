//! How much memory this machine can give (Linux's `MemAvailable`), for refusing an input that
//! would not fit before allocating it: a header that claims 40 GB is a clear refusal, not an
//! abort or the OOM killer.

/// Bytes the kernel says can be allocated without swapping, where it says (Linux).
pub fn available() -> Option<u64> {
    let text = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = text.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kib: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    kib.checked_mul(1024)
}

/// Whether `bytes` held `copies` times over fit in the memory available (true where it is
/// not known).
pub fn fits(bytes: u64, copies: u64) -> bool {
    available().is_none_or(|free| bytes.saturating_mul(copies) <= free)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_available_memory_is_read_and_a_terabyte_does_not_fit() {
        if cfg!(target_os = "linux") {
            assert!(available().is_some_and(|b| b > 1 << 20));
            assert!(!fits(1 << 40, 3));
        }
        assert!(fits(1024, 3));
    }
}
