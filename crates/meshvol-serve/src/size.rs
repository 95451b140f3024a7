//! Sizes in bytes, read (`256MiB`) and written in words: a leaf for flags and messages.

/// Parses a size: bytes, or a number with `KiB`, `MiB`, `GiB` (powers of 1024) or `KB`,
/// `MB`, `GB` (powers of 1000); `256MiB`, `1.5GB`, `1000000`.
pub fn parse_size(s: &str) -> Result<usize, String> {
    let t = s.trim();
    let split = t.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(t.len());
    let (number, unit) = t.split_at(split);
    let factor: f64 = match unit.trim().to_ascii_lowercase().as_str() {
        "" | "b" => 1.0,
        "k" | "kb" => 1e3,
        "m" | "mb" => 1e6,
        "g" | "gb" => 1e9,
        "kib" => 1024.0,
        "mib" => 1024.0 * 1024.0,
        "gib" => 1024.0 * 1024.0 * 1024.0,
        _ => return Err(format!("'{s}' is not a size: use bytes, or KiB, MiB, GiB, KB, MB, GB")),
    };
    match number.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 1.0 && x * factor <= usize::MAX as f64 => {
            Ok((x * factor) as usize)
        }
        _ => Err(format!("'{s}' is not a size of at least one byte")),
    }
}

/// A size in words for messages: `256 MiB`, `1000 bytes`.
pub fn size_words(bytes: usize) -> String {
    const MIB: usize = 1024 * 1024;
    match bytes {
        b if b >= MIB && b % MIB == 0 => format!("{} MiB", b / MIB),
        b if b >= 1024 && b % 1024 == 0 => format!("{} KiB", b / 1024),
        b => format!("{b} bytes"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_are_read_in_binary_and_decimal_units() {
        assert_eq!(parse_size("256MiB"), Ok(256 * 1024 * 1024));
        assert_eq!(parse_size("1.5 GB"), Ok(1_500_000_000));
        assert_eq!(parse_size("1000"), Ok(1000));
        assert_eq!(parse_size("2kib"), Ok(2048));
        assert!(parse_size("0").is_err());
        assert!(parse_size("-5MB").is_err());
        assert!(parse_size("5 parsecs").is_err());
        assert!(parse_size("nan").is_err());
        assert_eq!(size_words(256 * 1024 * 1024), "256 MiB");
        assert_eq!(size_words(1000), "1000 bytes");
    }
}
