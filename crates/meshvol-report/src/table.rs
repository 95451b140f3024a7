//! Reports as rows of a table (`--format csv`): one row per report, its JSON keys as
//! columns.
//!
//! The rule is `pandas.json_normalize(report, sep=".")`'s: an object's keys are columns,
//! in the order the report writes them; a nested object's keys become `parent.child`
//! (recursively, `bounds.min`, `a.b.c`; an empty object gives no column); every other
//! value is one cell, lists included (a list of numbers or of objects is not spread over
//! columns). [`flatten`] applies it to one report. A [`Table`] of several reports has the
//! union of their columns, in the order first seen, and a row leaves a column it lacks
//! empty.
//!
//! As text ([`cell`]), a string is itself, `null` is an empty cell, and a number, a
//! boolean or a list is its compact JSON text (`26183.29623547592`, `true`,
//! `[-30.0,-30.0,0.0]`): the same digits as the `--json` line, so a cell parsed as JSON
//! is the JSON value. [`Table::write_csv`] quotes cells per RFC 4180 (the `csv` crate)
//! where they hold a comma, a quote or a line break.

use serde_json::{Map, Value};
use std::collections::HashMap;

/// The columns of one report, `pandas.json_normalize(report, sep=".")`'s: nested objects
/// spread into `parent.child` columns; lists and scalars one cell each. A report that is
/// not an object is one column named by the empty string.
///
/// ```
/// use serde_json::json;
/// let row = meshvol_report::table::flatten(&json!({
///     "file": "a.stl", "volume": 1.5,
///     "bounds": {"min": [0, 0, 0], "max": [1, 1, 1.5]}, "units": {}, "warnings": []
/// }));
/// let names: Vec<&str> = row.iter().map(|(k, _)| k.as_str()).collect();
/// assert_eq!(names, ["file", "volume", "bounds.min", "bounds.max", "warnings"]);
/// assert_eq!(row[2].1, json!([0, 0, 0]));
/// ```
pub fn flatten(report: &Value) -> Vec<(String, Value)> {
    let mut columns = Vec::new();
    match report {
        Value::Object(map) => spread("", map, &mut columns),
        other => columns.push((String::new(), other.clone())),
    }
    columns
}

fn spread(prefix: &str, map: &Map<String, Value>, columns: &mut Vec<(String, Value)>) {
    for (key, value) in map {
        let name = if prefix.is_empty() { key.clone() } else { format!("{prefix}.{key}") };
        match value {
            Value::Object(inner) => spread(&name, inner, columns),
            other => columns.push((name, other.clone())),
        }
    }
}

/// A value as the text of its cell: a string as itself, `null` empty, anything else its
/// compact JSON text.
pub fn cell(value: &Value) -> String {
    match value {
        Value::Null => String::new(),
        Value::String(s) => s.clone(),
        other => other.to_string(),
    }
}

/// Rows of reports under the union of their columns (in the order first seen).
#[derive(Debug, Default)]
pub struct Table {
    columns: Vec<String>,
    index: HashMap<String, usize>,
    rows: Vec<Vec<(usize, Value)>>,
}

impl Table {
    /// An empty table.
    pub fn new() -> Table {
        Table::default()
    }

    /// Adds `report` (a JSON object) as a row, its new columns after the others.
    pub fn push(&mut self, report: &Value) {
        let row = flatten(report)
            .into_iter()
            .map(|(name, value)| {
                let next = self.columns.len();
                let i = *self.index.entry(name.clone()).or_insert(next);
                if i == next {
                    self.columns.push(name);
                }
                (i, value)
            })
            .collect();
        self.rows.push(row);
    }

    /// The columns, in the order first seen.
    pub fn columns(&self) -> &[String] {
        &self.columns
    }

    /// How many rows.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    /// Whether there are no rows.
    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The rows as text cells, one per column (empty where a row has no such key).
    pub fn cells(&self) -> impl Iterator<Item = Vec<String>> + '_ {
        self.rows.iter().map(|row| {
            let mut cells = vec![String::new(); self.columns.len()];
            for (i, value) in row {
                cells[*i] = cell(value);
            }
            cells
        })
    }

    /// The table as CSV: a header line of the columns, then one line per row (RFC 4180
    /// quoting, `\n` line ends). No rows: nothing.
    pub fn write_csv(&self, out: impl std::io::Write) -> std::io::Result<()> {
        if self.rows.is_empty() {
            return Ok(());
        }
        let mut w =
            csv::WriterBuilder::new().terminator(csv::Terminator::Any(b'\n')).from_writer(out);
        w.write_record(&self.columns)?;
        for row in self.cells() {
            w.write_record(&row)?;
        }
        w.flush()
    }

    /// [`write_csv`](Self::write_csv) into a string.
    pub fn to_csv(&self) -> String {
        let mut out = Vec::new();
        // Writing to memory does not fail, and every cell is UTF-8.
        let _ = self.write_csv(&mut out);
        String::from_utf8(out).unwrap_or_default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn nested_objects_spread_and_lists_stay_one_cell() {
        let row = flatten(&json!({"a": {"b": {"c": 1}, "d": [1, {"e": 2}]}, "f": null}));
        assert_eq!(
            row,
            vec![
                ("a.b.c".to_string(), json!(1)),
                ("a.d".to_string(), json!([1, {"e": 2}])),
                ("f".to_string(), Value::Null)
            ]
        );
        assert_eq!(cell(&json!([1.5, true, "x"])), r#"[1.5,true,"x"]"#);
        assert_eq!(cell(&json!("a,b")), "a,b");
        assert_eq!(cell(&Value::Null), "");
    }

    #[test]
    fn rows_share_the_union_of_their_columns_in_the_order_first_seen() {
        let mut t = Table::new();
        t.push(&json!({"file": "a", "volume": 1.0, "bounds": {"min": [0, 0]}}));
        t.push(&json!({"file": "b, c", "error": "b: \"bad\"\nline"}));
        t.push(&json!({"file": "d", "mass": 2, "volume": 3}));
        assert_eq!(t.columns(), ["file", "volume", "bounds.min", "error", "mass"]);
        let csv = t.to_csv();
        let mut r = csv::Reader::from_reader(csv.as_bytes());
        let rows: Vec<Vec<String>> =
            r.records().map(|rec| rec.unwrap().iter().map(str::to_string).collect()).collect();
        assert_eq!(rows[0], ["a", "1.0", "[0,0]", "", ""]);
        assert_eq!(rows[1], ["b, c", "", "", "b: \"bad\"\nline", ""]);
        assert_eq!(rows[2], ["d", "3", "", "", "2"]);
    }
}
