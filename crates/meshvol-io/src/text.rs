//! Byte-level helpers shared by the text readers: whitespace classes, numbers, and
//! showing a piece of the input in a message.

/// The UTF-8 byte order mark.
const BOM: &[u8] = b"\xEF\xBB\xBF";

/// Whitespace inside a line: space, tab, CR, vertical tab, form feed.
#[inline]
pub fn is_blank(b: u8) -> bool {
    matches!(b, b' ' | b'\t' | b'\r' | 0x0b | 0x0c)
}

/// Any ASCII whitespace, newline included.
#[inline]
pub fn is_space(b: u8) -> bool {
    b == b'\n' || is_blank(b)
}

/// The length of a UTF-8 byte order mark at the start of `bytes` (0 or 3).
pub fn bom_len(bytes: &[u8]) -> usize {
    if bytes.starts_with(BOM) {
        BOM.len()
    } else {
        0
    }
}

/// For a file whose lines end with CR alone (classic Mac OS): a copy with LF line ends,
/// which every text reader splits at. `None` for any other file: its first line end is
/// LF or CRLF, or it has no line end, or an LF comes later (mixed line ends are not
/// guessed at). The copy has the same length, so byte offsets and line numbers agree.
pub fn lf_line_ends(bytes: &[u8]) -> Option<Vec<u8>> {
    let first = memchr::memchr2(b'\n', b'\r', bytes)?;
    if bytes[first] != b'\r'
        || bytes.get(first + 1) == Some(&b'\n')
        || memchr::memchr(b'\n', &bytes[first..]).is_some()
    {
        return None;
    }
    Some(bytes.iter().map(|&b| if b == b'\r' { b'\n' } else { b }).collect())
}

/// The offset of the first byte after `start` that is not whitespace (newlines included),
/// or `bytes.len()`.
#[inline]
pub fn skip_space(bytes: &[u8], mut pos: usize) -> usize {
    while pos < bytes.len() && is_space(bytes[pos]) {
        pos += 1;
    }
    pos
}

/// The offset of the first byte at or after `pos` that is not blank (newlines stop it),
/// or `bytes.len()`.
#[inline]
pub fn skip_blank(bytes: &[u8], mut pos: usize) -> usize {
    while pos < bytes.len() && is_blank(bytes[pos]) {
        pos += 1;
    }
    pos
}

/// The end of the token that starts at `pos`: the first whitespace byte or the end.
#[inline]
pub fn token_end(bytes: &[u8], mut pos: usize) -> usize {
    while pos < bytes.len() && !is_space(bytes[pos]) {
        pos += 1;
    }
    pos
}

/// Why a number could not be read.
pub enum NumberError {
    /// No number starts here (a word, or the end of the input).
    Missing,
    /// Something that starts like a number but is not one (`1.5x`, `-`).
    Invalid,
    /// A number that is NaN or infinite (`nan`, `inf`, `1e999`).
    NonFinite,
}

/// Parses the number that starts at `pos` and must end at whitespace or at the end of
/// `bytes`; returns it and the offset just after it.
#[inline]
pub fn parse_f64(bytes: &[u8], pos: usize) -> Result<(f64, usize), NumberError> {
    let rest = bytes.get(pos..).unwrap_or_default();
    match fast_float2::parse_partial::<f64, _>(rest) {
        Ok((value, used)) => {
            let end = pos + used;
            if end < bytes.len() && !is_space(bytes[end]) {
                Err(NumberError::Invalid)
            } else if !value.is_finite() {
                Err(NumberError::NonFinite)
            } else {
                Ok((value, end))
            }
        }
        Err(_) => match rest.first() {
            Some(b) if b.is_ascii_alphabetic() || is_space(*b) => Err(NumberError::Missing),
            None => Err(NumberError::Missing),
            Some(_) => Err(NumberError::Invalid),
        },
    }
}

/// Chunk boundaries for parsing in parallel: `start`, then line starts about `target`
/// bytes apart, then `bytes.len()`. A chunk may start after the newline at `nl` only
/// when `can_cut(nl)` (an OBJ line continued with `\` must stay whole); else the next
/// newline is tried.
pub fn line_boundaries(
    bytes: &[u8],
    start: usize,
    target: usize,
    can_cut: impl Fn(usize) -> bool,
) -> Vec<usize> {
    let mut bounds = vec![start];
    let mut from = start.saturating_add(target);
    while from < bytes.len() {
        match memchr::memchr(b'\n', &bytes[from..]) {
            Some(i) if from + i + 1 < bytes.len() => {
                let nl = from + i;
                if !can_cut(nl) {
                    from = nl + 1;
                    continue;
                }
                bounds.push(nl + 1);
                from = (nl + 1).saturating_add(target);
            }
            _ => break,
        }
    }
    bounds.push(bytes.len());
    bounds
}

/// A piece of input for an error message: lossy UTF-8, shortened to 40 characters.
pub fn show(token: &[u8]) -> String {
    const MAX: usize = 40;
    let text = String::from_utf8_lossy(token);
    if text.chars().count() > MAX {
        let cut: String = text.chars().take(MAX).collect();
        format!("{cut}…")
    } else {
        text.into_owned()
    }
}

/// A name as the file writes it (an STL solid's, an OBJ group's): lossy UTF-8, trimmed,
/// not shortened.
pub fn lossy_name(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).trim().to_string()
}

/// The token that starts at `pos`, for messages.
pub fn show_token(bytes: &[u8], pos: usize) -> String {
    let pos = pos.min(bytes.len());
    show(&bytes[pos..token_end(bytes, pos)])
}

/// Whether the bytes look like text: no control bytes other than whitespace. Bytes of
/// 0x80 and above are allowed (UTF-8 names).
pub fn looks_like_text(bytes: &[u8]) -> bool {
    bytes.iter().all(|&b| b >= 0x20 && b != 0x7f || is_space(b))
}

/// Whether `bytes` starts with the keyword `word` (ASCII, any case) followed by
/// whitespace or the end.
#[inline]
pub fn starts_with_word(bytes: &[u8], word: &[u8]) -> bool {
    bytes.len() >= word.len()
        && bytes[..word.len()].eq_ignore_ascii_case(word)
        && bytes.get(word.len()).is_none_or(|&b| is_space(b))
}

/// Deterministic mutations of test inputs (xorshift64*), for the readers' unit tests.
#[cfg(test)]
pub(crate) mod mutate {
    use crate::error::{Location, ParseError};

    /// A read's value or its error's place and message, and its warnings.
    pub type Outcome<T> = (Result<T, (Option<Location>, String)>, Vec<String>);

    /// What a read gave, in a form two reads can be compared in.
    pub fn outcome<T>(read: impl FnOnce(&mut Vec<String>) -> Result<T, ParseError>) -> Outcome<T> {
        let mut warnings = vec![];
        let result = read(&mut warnings).map_err(|e| (e.location, e.message));
        (result, warnings)
    }

    pub struct Rng(pub u64);

    impl Rng {
        pub fn next(&mut self) -> u64 {
            self.0 ^= self.0 >> 12;
            self.0 ^= self.0 << 25;
            self.0 ^= self.0 >> 27;
            self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
        }

        pub fn below(&mut self, n: usize) -> usize {
            (self.next() % n.max(1) as u64) as usize
        }
    }

    /// One to four edits: delete, insert one of `pieces`, duplicate a span, flip a byte.
    pub fn mutate(rng: &mut Rng, input: &[u8], pieces: &[&[u8]]) -> Vec<u8> {
        let mut out = input.to_vec();
        for _ in 0..1 + rng.below(4) {
            let at = rng.below(out.len() + 1);
            match rng.below(4) {
                0 => {
                    let end = (at + 1 + rng.below(40)).min(out.len());
                    out.drain(at.min(end)..end);
                }
                1 => {
                    let piece = pieces[rng.below(pieces.len())];
                    out.splice(at..at, piece.iter().copied());
                }
                2 => {
                    let end = (at + rng.below(200)).min(out.len());
                    let copy = out[at..end].to_vec();
                    let to = rng.below(out.len() + 1);
                    out.splice(to..to, copy);
                }
                _ if !out.is_empty() => {
                    let i = rng.below(out.len());
                    out[i] = rng.next() as u8;
                }
                _ => {}
            }
        }
        out
    }

    /// Reads `file` and `rounds − 1` mutants of it whole and in chunks of each size in
    /// `chunks`, and asserts every chunked read equals the whole one: parallel chunking
    /// must be invisible. Returns how many inputs were (read, refused), so callers can
    /// check that both paths ran.
    pub fn assert_chunking_invisible<T, E, W>(
        file: &[u8],
        pieces: &[&[u8]],
        seed: u64,
        rounds: usize,
        chunks: &[usize],
        run: impl Fn(&[u8], usize) -> (Result<T, E>, W),
    ) -> (usize, usize)
    where
        (Result<T, E>, W): PartialEq + std::fmt::Debug,
    {
        let mut rng = Rng(seed);
        let (mut ok, mut err) = (0, 0);
        for round in 0..rounds {
            let input = if round == 0 { file.to_vec() } else { mutate(&mut rng, file, pieces) };
            let whole = run(&input, usize::MAX / 2);
            if whole.0.is_ok() {
                ok += 1
            } else {
                err += 1
            }
            for &chunk in chunks {
                let chunked = run(&input, chunk);
                assert_eq!(chunked, whole, "chunk {chunk}: {}", String::from_utf8_lossy(&input));
            }
        }
        (ok, err)
    }
}
