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

/// A number as the shortest text that reads back to the same `f64`, in
/// plain decimal notation (`12`, `0.5`, `-0.0025`) for magnitudes from
/// 1e-5 to 1e15 and zero, in exponent form outside them (`1e-9`,
/// `2.5e20`, which every CSV reader parses), non-finite values as `NaN`,
/// `inf`, `-inf`.
pub fn format_number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-5..1e15).contains(&v.abs()) {
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
            vec![0.5, -0.0025, 2.5e20],
        ];
        let text = csv_text(&["time", "node", "value"], &rows);
        assert_eq!(
            text,
            "time,node,value\n0,12,0.1\n1,-3,1e-9\n2,5,NaN\n0.5,-0.0025,2.5e20\n"
        );
        for (line, row) in text
            .lines()
            .skip(1)
            .zip(&rows)
            .filter(|(_, r)| !r[2].is_nan())
        {
            let back: Vec<f64> = line.split(',').map(|v| v.parse().unwrap()).collect();
            assert_eq!(&back, row);
        }
    }
}
