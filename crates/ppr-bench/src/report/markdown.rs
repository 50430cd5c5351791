//! Markdown tables.

/// A markdown table: header, alignment (right for numbers), rows.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MarkdownTable {
    header: Vec<String>,
    numeric: Vec<bool>,
    rows: Vec<Vec<String>>,
}

impl MarkdownTable {
    /// Columns named in `header`; a name starting with `#` is right-aligned (numbers) and
    /// printed without the `#`.
    pub fn new(header: &[&str]) -> Self {
        Self {
            header: header.iter().map(|h| h.trim_start_matches('#').to_owned()).collect(),
            numeric: header.iter().map(|h| h.starts_with('#')).collect(),
            rows: Vec::new(),
        }
    }

    pub fn push(&mut self, row: Vec<String>) {
        self.rows.push(row);
    }

    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The table as markdown text, ending with a newline.
    pub fn render(&self) -> String {
        let line = |cells: &[String]| format!("| {} |\n", cells.join(" | "));
        let mut out = line(&self.header);
        let rule: Vec<String> =
            self.numeric.iter().map(|n| if *n { "---:".into() } else { "---".into() }).collect();
        out.push_str(&line(&rule));
        for r in &self.rows {
            out.push_str(&line(&r.iter().map(|c| c.replace('|', "\\|")).collect::<Vec<_>>()));
        }
        out
    }
}

/// Milliseconds with three decimals (`–` for NaN).
pub fn ms(v: f64) -> String {
    if v.is_nan() { "–".into() } else { format!("{v:.3}") }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_aligned_columns() {
        let mut t = MarkdownTable::new(&["name", "#ms"]);
        t.push(vec!["a|b".into(), ms(1.0)]);
        assert_eq!(t.render(), "| name | ms |\n| --- | ---: |\n| a\\|b | 1.000 |\n");
    }
}
