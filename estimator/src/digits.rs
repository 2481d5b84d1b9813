//! How numbers are written for people: six significant digits for values, two for
//! standard errors (the table, report.html, the batch summaries and the model choice's lines).

/// Six significant digits.
pub fn sig(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    if v != 0.0 && v.is_finite() && !(1e-3..1e6).contains(&v.abs()) {
        format!("{v:.5e}")
    } else {
        let digits = (5 - v.abs().log10().floor() as i64).clamp(0, 9) as usize;
        format!("{v:.digits$}")
    }
}

/// A standard error to two significant digits.
pub fn significant(e: f64) -> String {
    if !e.is_finite() || e == 0.0 {
        return format!("{e}");
    }
    let digits = (1 - e.abs().log10().floor() as i32).max(0) as usize;
    if digits > 8 || e.abs() >= 1e6 {
        format!("{e:.1e}")
    } else {
        format!("{e:.digits$}")
    }
}
