//! Numbers as the text reports print them: plain notation where it reads well, else
//! scientific (`-2.73e-16`, not `-0.000000000000000273`), trailing zeros trimmed. JSON
//! keeps every bit (serde_json prints the shortest string that reads back the same).

/// `x` to `digits` significant digits: plain for magnitudes from 1e-4 to 1e12, scientific
/// otherwise, trailing zeros trimmed in both.
///
/// ```
/// use meshvol_report::number::num;
/// assert_eq!(num(-2.7318e-16, 3), "-2.73e-16");
/// assert_eq!(num(12345.678901234567, 10), "12345.6789");
/// assert_eq!(num(2.5e13, 3), "2.5e13");
/// ```
pub fn num(x: f64, digits: usize) -> String {
    if x == 0.0 {
        return "0".into();
    }
    if !x.is_finite() {
        return x.to_string();
    }
    let digits = digits.max(1);
    let magnitude = x.abs().log10().floor() as i32;
    if (-4..12).contains(&magnitude) {
        let decimals = (digits as i32 - 1 - magnitude).max(0) as usize;
        trim(&format!("{x:.decimals$}"))
    } else {
        let s = format!("{x:.*e}", digits - 1);
        match s.split_once('e') {
            Some((mantissa, exponent)) => format!("{}e{exponent}", trim(mantissa)),
            None => s,
        }
    }
}

/// Trailing zeros (and a bare point) removed from a decimal number.
fn trim(s: &str) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s.to_string()
    }
}

/// `(x, y, z)` with `digits` significant digits each.
pub fn vector(v: [f64; 3], digits: usize) -> String {
    format!("({}, {}, {})", num(v[0], digits), num(v[1], digits), num(v[2], digits))
}

/// `n thing` or `n things`.
///
/// ```
/// use meshvol_report::number::count;
/// assert_eq!(count(1, "polygon", "polygons"), "1 polygon");
/// assert_eq!(count(0, "hole", "holes"), "0 holes");
/// ```
pub fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

#[cfg(test)]
mod tests {
    use super::num;

    #[test]
    fn numbers_read_well() {
        assert_eq!(num(1.0, 15), "1");
        assert_eq!(num(12345.678901234567, 10), "12345.6789"); // trailing zeros trimmed
        assert_eq!(num(-0.5, 10), "-0.5");
        assert_eq!(num(1.5e-9, 2), "1.5e-9");
        assert_eq!(num(2.5e13, 3), "2.5e13");
        assert_eq!(num(-2.7318e-16, 15), "-2.7318e-16");
        assert_eq!(num(1e-4, 3), "0.0001");
        assert_eq!(num(f64::NAN, 3), "NaN");
        // Round-trips at 17 digits.
        let x = 0.1 + 0.2;
        assert_eq!(num(x, 17).parse::<f64>().unwrap(), x);
    }
}
