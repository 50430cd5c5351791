//! A CSV writer by hand: a header, then rows of the same length, fields quoted when needed.

use std::path::Path;

use crate::error::BenchError;

/// A table being built, written at the end.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct CsvTable {
    pub header: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

impl CsvTable {
    pub fn new(header: &[&str]) -> Self {
        Self { header: header.iter().map(|s| (*s).to_owned()).collect(), rows: Vec::new() }
    }

    /// Adds a row.
    ///
    /// # Panics
    /// If its length differs from the header's (a bug in the caller).
    pub fn push(&mut self, row: Vec<String>) {
        assert_eq!(row.len(), self.header.len(), "CSV row length differs from the header");
        self.rows.push(row);
    }

    /// The table as CSV text (RFC 4180 quoting, `\n` line ends).
    pub fn to_text(&self) -> String {
        let mut out = String::new();
        for row in std::iter::once(&self.header).chain(&self.rows) {
            let fields: Vec<String> = row.iter().map(|f| quote(f)).collect();
            out.push_str(&fields.join(","));
            out.push('\n');
        }
        out
    }

    /// Writes the table.
    ///
    /// # Errors
    /// The file cannot be written.
    pub fn write(&self, path: &Path) -> Result<(), BenchError> {
        std::fs::write(path, self.to_text()).map_err(|e| BenchError::io(path, e))
    }
}

fn quote(field: &str) -> String {
    if field.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", field.replace('"', "\"\""))
    } else {
        field.to_owned()
    }
}

/// Splits one CSV line into fields (the inverse of the writer, for tests and readers).
pub fn split_line(line: &str) -> Vec<String> {
    let mut fields = Vec::new();
    let mut field = String::new();
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                field.push('"');
                chars.next();
            }
            ('"', _) => quoted = !quoted,
            (',', false) => fields.push(std::mem::take(&mut field)),
            _ => field.push(c),
        }
    }
    fields.push(field);
    fields
}

/// A number for a CSV cell: fixed decimals, `inf` for infinity.
pub fn num(v: f64, decimals: usize) -> String {
    if v.is_infinite() { "inf".into() } else { format!("{v:.decimals$}") }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quoting_round_trips() {
        let mut t = CsvTable::new(&["a", "b"]);
        t.push(vec!["x, y".into(), "say \"hi\"".into()]);
        let text = t.to_text();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "a,b");
        assert_eq!(split_line(lines[1]), ["x, y", "say \"hi\""]);
        assert_eq!(num(f64::INFINITY, 2), "inf");
        assert_eq!(num(1.23456, 3), "1.235");
    }
}
