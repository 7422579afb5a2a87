//! The CSV files of an output folder as the report reads them: a header the
//! writer's own (checked), rows of as many fields, numbers read on demand
//! with the file and line of a field that is not one.

use crate::error::{Error, Result};

/// A CSV file of the output folder: its header and rows of fields.
pub(super) struct Table {
    /// The file (its path), for messages.
    pub place: String,
    pub columns: Vec<String>,
    /// Each row with its line number in the file (from 1, the header's).
    pub rows: Vec<(usize, Vec<String>)>,
}

impl Table {
    /// Parses `text`; its header must begin with the columns of `expected`
    /// (the writer's header, comma-separated; later columns are allowed:
    /// a twisting model's, or ones a later version adds).
    pub fn parse(place: &str, text: &str, expected: &str) -> Result<Table> {
        let bad = |line: usize, m: String| Error::input(format!("{place}:{line}"), m);
        let mut records = records(text).map_err(|(line, m)| bad(line, m))?;
        if records.is_empty() {
            return Err(bad(1, "empty: no header".into()));
        }
        let (_, columns) = records.remove(0);
        let want: Vec<&str> = expected.trim_end().split(',').collect();
        let differs = want
            .iter()
            .enumerate()
            .find(|(k, w)| columns.get(*k).map(String::as_str) != Some(**w));
        if let Some((k, w)) = differs {
            let found = columns
                .get(k)
                .map_or("nothing".to_string(), |c| format!("\"{c}\""));
            return Err(bad(
                1,
                format!(
                    "not the header this program writes: column {} is {found}, not \"{w}\"",
                    k + 1
                ),
            ));
        }
        for (line, row) in &records {
            if row.len() != columns.len() {
                return Err(bad(
                    *line,
                    format!("{} fields, the header has {}", row.len(), columns.len()),
                ));
            }
        }
        Ok(Table {
            place: place.to_string(),
            columns,
            rows: records,
        })
    }

    /// The index of column `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }

    /// Column `name` of every row as numbers (an empty field is NaN); a
    /// missing column is an empty list.
    pub fn numbers(&self, name: &str) -> Result<Vec<f64>> {
        let Some(k) = self.column(name) else {
            return Ok(Vec::new());
        };
        self.rows
            .iter()
            .map(|(line, row)| self.number(*line, name, &row[k]))
            .collect()
    }

    /// One field as a number: empty is NaN, anything else must parse.
    pub fn number(&self, line: usize, column: &str, field: &str) -> Result<f64> {
        if field.is_empty() {
            return Ok(f64::NAN);
        }
        field.parse().map_err(|_| {
            Error::input(
                format!("{}:{line}", self.place),
                format!("{column}: \"{field}\" is not a number"),
            )
        })
    }

    /// The rows whose field `column` is `value`, as a table of their own.
    pub fn select(&self, column: &str, value: &str) -> Table {
        let k = self.column(column);
        Table {
            place: self.place.clone(),
            columns: self.columns.clone(),
            rows: self
                .rows
                .iter()
                .filter(|(_, r)| k.is_some_and(|k| r[k] == value))
                .cloned()
                .collect(),
        }
    }

    /// The distinct values of `column`, in the order they first appear.
    pub fn distinct(&self, column: &str) -> Vec<String> {
        let Some(k) = self.column(column) else {
            return Vec::new();
        };
        let mut out: Vec<String> = Vec::new();
        for (_, r) in &self.rows {
            if !out.contains(&r[k]) {
                out.push(r[k].clone());
            }
        }
        out
    }
}

/// A record: the line it starts on, its fields.
type Record = (usize, Vec<String>);

/// The records of a CSV text with the line each starts on: fields split at
/// commas, a field in double quotes may hold commas, line breaks and
/// doubled quotes (as the writer quotes a name). Blank lines are skipped.
fn records(text: &str) -> std::result::Result<Vec<Record>, (usize, String)> {
    let mut out = Vec::new();
    let mut chars = text.chars().peekable();
    let mut line = 1;
    while chars.peek().is_some() {
        let start = line;
        let mut fields = Vec::new();
        let mut field = String::new();
        let mut quoted = false;
        while let Some(c) = chars.next() {
            match c {
                '"' if quoted && chars.peek() == Some(&'"') => {
                    chars.next();
                    field.push('"');
                }
                '"' if quoted => quoted = false,
                '"' if field.is_empty() => quoted = true,
                ',' if !quoted => fields.push(std::mem::take(&mut field)),
                '\n' if !quoted => {
                    line += 1;
                    break;
                }
                '\r' if !quoted && chars.peek() == Some(&'\n') => {}
                c => {
                    line += usize::from(c == '\n');
                    field.push(c);
                }
            }
        }
        if quoted {
            return Err((start, "a quoted field is not closed".into()));
        }
        fields.push(field);
        if !(fields.len() == 1 && fields[0].is_empty()) {
            out.push((start, fields));
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quoted_names_and_bad_headers() {
        let t = Table::parse(
            "x.csv",
            "a,b,name\n1,2,plain\n3,,\"a, \"\"b\"\"\nc\"\n",
            "a,b",
        )
        .unwrap();
        assert_eq!(t.rows.len(), 2);
        assert_eq!(t.rows[1].1[2], "a, \"b\"\nc");
        assert!(t.numbers("b").unwrap()[1].is_nan());
        assert_eq!(t.distinct("name"), ["plain", "a, \"b\"\nc"]);
        let e = Table::parse("x.csv", "a,c\n1,2\n", "a,b").err().unwrap();
        assert_eq!(
            e.to_string(),
            "x.csv:1: not the header this program writes: column 2 is \"c\", not \"b\""
        );
        let e = Table::parse("x.csv", "a,b\n1,2\n3\n", "a,b").err().unwrap();
        assert_eq!(e.to_string(), "x.csv:3: 1 fields, the header has 2");
        let e = t.numbers("a").map(|_| ()).and_then(|_| {
            Table::parse("x.csv", "a,b\nx,2\n", "a,b")?
                .numbers("a")
                .map(|_| ())
        });
        assert_eq!(
            e.err().unwrap().to_string(),
            "x.csv:2: a: \"x\" is not a number"
        );
        let e = Table::parse("x.csv", "a,b\n\"1,2\n", "a,b").err().unwrap();
        assert_eq!(e.to_string(), "x.csv:2: a quoted field is not closed");
    }
}
