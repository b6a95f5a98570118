//! Comma-separated tables (`.csv`) of numbers, for the time histories and
//! contact profiles: one header line, one line per row.

use std::path::Path;

use super::write_atomically;

/// The CSV text of `rows` under `header`, each number as [`format_number`]
/// writes it.
pub fn csv_text(header: &[&str], rows: &[Vec<f64>]) -> String {
    let mut text = header.join(",");
    text.push('\n');
    for row in rows {
        for (i, v) in row.iter().enumerate() {
            if i > 0 {
                text.push(',');
            }
            text.push_str(&format_number(*v));
        }
        text.push('\n');
    }
    text
}

/// A number as the shortest text that reads back to the same `f64`:
/// integers (node ids, statuses) plainly (`12`), anything else in exponent
/// form (`1e-1`, `-2.5e-9`), non-finite values as `NaN`, `inf`, `-inf`.
pub fn format_number(v: f64) -> String {
    if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

/// Writes `rows` under `header` to `path` as CSV, atomically.
pub fn write_csv(path: &Path, header: &[&str], rows: &[Vec<f64>]) -> crate::Result<()> {
    let text = csv_text(header, rows);
    write_atomically(path, |w| w.write_all(text.as_bytes()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_and_rows_read_back() {
        let rows = vec![
            vec![0.0, 12.0, 0.1],
            vec![1.0, -3.0, 1e-9],
            vec![2.0, 5.0, f64::NAN],
        ];
        let text = csv_text(&["time", "node", "value"], &rows);
        assert_eq!(text, "time,node,value\n0,12,1e-1\n1,-3,1e-9\n2,5,NaN\n");
        let back: Vec<f64> = text
            .lines()
            .nth(2)
            .unwrap()
            .split(',')
            .map(|v| v.parse().unwrap())
            .collect();
        assert_eq!(back, rows[1]);
    }
}
