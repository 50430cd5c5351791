//! Pretty JSON that keeps arrays of numbers (vectors, extents) on one line, for readable ground truth.

/// `serde_json`'s pretty output with every array that holds only numbers joined onto its
/// opening line: `"center": [\n 1.0,\n 2.0\n]` becomes `"center": [1.0, 2.0]`.
pub fn inline_number_arrays(pretty: &str) -> String {
    let lines: Vec<&str> = pretty.lines().collect();
    let mut out = String::with_capacity(pretty.len());
    let mut i = 0;
    while i < lines.len() {
        let line = lines[i];
        if line.ends_with('[') {
            let mut numbers = Vec::new();
            let mut j = i + 1;
            while let Some(item) = lines.get(j).map(|l| l.trim()) {
                let value = item.strip_suffix(',').unwrap_or(item);
                if item.starts_with(']') || value.parse::<f64>().is_err() {
                    break;
                }
                numbers.push(value);
                j += 1;
            }
            if let Some(closing) = lines.get(j).map(|l| l.trim()).filter(|l| l.starts_with(']'))
                && !numbers.is_empty()
            {
                out.push_str(line);
                out.push_str(&numbers.join(", "));
                out.push_str(closing);
                out.push('\n');
                i = j + 1;
                continue;
            }
        }
        out.push_str(line);
        out.push('\n');
        i += 1;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn number_arrays_go_on_one_line_and_others_stay() {
        let value = serde_json::json!({"a": [1.0, -2.5e-7], "b": [[1, 2], [3]], "c": ["x", 1], "d": []});
        let pretty = serde_json::to_string_pretty(&value).expect("serialisable");
        let compact = inline_number_arrays(&pretty);
        assert!(compact.contains("\"a\": [1.0, -2.5e-7],"), "{compact}");
        assert!(compact.contains("    [1, 2],\n    [3]\n"), "{compact}");
        assert!(compact.contains("\"c\": [\n    \"x\",\n    1\n  ],"), "{compact}");
        let reparsed: serde_json::Value = serde_json::from_str(&compact).expect("still JSON");
        assert_eq!(reparsed, value);
    }
}
