//! The flags' number parsers (clap value parsers): a leaf the command modules import.

/// Parses a flag's value that must be a finite number, zero or more.
pub fn non_negative_finite(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 0.0 => Ok(x),
        _ => Err(format!("must be zero or a positive number; got {s}")),
    }
}

/// Parses a flag's value that must be a finite number above zero.
pub fn positive_finite(s: &str) -> Result<f64, String> {
    match s.parse::<f64>() {
        Ok(x) if x.is_finite() && x > 0.0 => Ok(x),
        _ => Err(format!("must be a positive number; got {s}")),
    }
}
