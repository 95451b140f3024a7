//! The name a typo was meant to be (a subcommand, a man page): a leaf for main.rs, manual.rs.

/// The name of `names` that `typed` was probably meant to be: one at most two edits
/// away (`chek` → `check`), or one it begins (`vol` → `volume`); the nearest first.
pub fn nearest<'a>(typed: &str, names: impl Iterator<Item = &'a str>) -> Option<String> {
    names
        .map(|name| (edits(typed, name), name))
        .filter(|(d, name)| *d <= 2 || (typed.len() >= 3 && name.starts_with(typed)))
        .min()
        .map(|(_, name)| name.to_string())
}

/// Levenshtein distance.
fn edits(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut previous = row[0];
        row[0] = i + 1;
        for (j, &cb) in b.iter().enumerate() {
            let next = (previous + usize::from(ca != cb)).min(row[j] + 1).min(row[j + 1] + 1);
            previous = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}
