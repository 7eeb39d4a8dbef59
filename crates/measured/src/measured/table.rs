//! A table of CEINMS's trials (`emg.txt`, `lmt.txt`, `<dof>Ma.txt`, `<dof>Torque.txt`): two
//! count lines, a header, then rows, fields separated by tabs:
//!
//! ```text
//! datacolumns 3        the columns, time included
//! datarows 2           the rows after the header
//! time→a→b             (→ a tab)
//! 2.32→0.1→0.2
//! 2.324→0.1→0.3
//! ```
//!
//! CEINMS reads it so (lib/FileIO/DataFromFile.cpp of the toolbox); here everything is checked:
//! the declared counts against the header and the rows, every value a finite number, the times
//! strictly increasing, the column names non-empty and unique. Lines may end in CR LF; blank
//! lines may follow the last row.

use crate::measured::{read_bytes, shown, utf8_text, MeasuredError};
use muscle_actuator_core::text::excerpt;
use std::path::Path;

/// Largest table file read, bytes (32 MiB: two minutes of 16 EMG channels at 2 kHz).
pub(crate) const MAX_TABLE_BYTES: u64 = 32 << 20;

/// A table as read: named columns of values over strictly increasing times.
#[derive(Debug, Clone, PartialEq)]
pub struct Table {
    /// The columns' names, after `time`, in the file's order; non-empty and unique.
    columns: Vec<String>,
    /// The rows' times, s, strictly increasing; at least one.
    times: Vec<f64>,
    /// The values, column-major: column `j` is `values[j * rows..(j + 1) * rows]`; all finite.
    values: Vec<f64>,
}

impl Table {
    /// Reads and checks the table in `path` (a regular file of at most `MAX_TABLE_BYTES`).
    pub fn read(path: &Path) -> Result<Table, MeasuredError> {
        let error = |error| MeasuredError::Table {
            path: shown(path),
            error,
        };
        let text = utf8_text(read_bytes(path, MAX_TABLE_BYTES)?)
            .map_err(|line| error(TableError::NotText { line }))?;
        Table::parse(&text).map_err(error)
    }

    /// Parses and checks a table's text.
    pub fn parse(text: &str) -> Result<Table, TableError> {
        let mut lines = text
            .split('\n')
            .map(|l| l.strip_suffix('\r').unwrap_or(l))
            .enumerate()
            .map(|(i, l)| (i + 1, l));
        let declared_columns = count_line(lines.next(), "datacolumns")?;
        let declared_rows = count_line(lines.next(), "datarows")?;
        if declared_columns < 2 {
            return Err(TableError::TooFewColumns {
                declared: declared_columns,
            });
        }
        if declared_rows == 0 {
            return Err(TableError::NoRows);
        }
        let (line, header) = lines
            .next()
            .filter(|(_, h)| !h.trim().is_empty())
            .ok_or(TableError::NoHeader)?;
        let columns = header_names(line, header, declared_columns)?;
        let mut rows = Rows::new(columns.len());
        let mut blank: Option<usize> = None;
        for (line, text) in lines {
            if text.trim().is_empty() {
                blank.get_or_insert(line);
                continue;
            }
            if let Some(blank) = blank {
                return Err(TableError::BlankLine { line: blank });
            }
            if rows.times.len() == declared_rows {
                return Err(TableError::ExtraRow {
                    line,
                    declared: declared_rows,
                });
            }
            rows.push(line, text, &columns)?;
        }
        if rows.times.len() < declared_rows {
            return Err(TableError::MissingRows {
                found: rows.times.len(),
                declared: declared_rows,
            });
        }
        Ok(rows.into_table(columns))
    }

    /// A table of `columns` over `times` from column-major `values` (column `j` is
    /// `values[j * times.len()..]`); the caller guarantees the shape and the rules of the
    /// fields.
    pub(crate) fn from_columns(columns: Vec<String>, times: Vec<f64>, values: Vec<f64>) -> Table {
        debug_assert_eq!(values.len(), columns.len() * times.len());
        Table {
            columns,
            times,
            values,
        }
    }

    /// The columns' names (after `time`), in the file's order.
    pub fn columns(&self) -> &[String] {
        &self.columns
    }

    /// The rows' times, s, strictly increasing.
    pub fn times(&self) -> &[f64] {
        &self.times
    }

    /// The number of rows.
    pub fn rows(&self) -> usize {
        self.times.len()
    }

    /// The first row's time, s.
    pub fn start(&self) -> f64 {
        self.times.first().copied().unwrap_or(f64::NAN)
    }

    /// The last row's time, s.
    pub fn end(&self) -> f64 {
        self.times.last().copied().unwrap_or(f64::NAN)
    }

    /// The index of the column named `name`.
    pub(crate) fn column_index(&self, name: &str) -> Option<usize> {
        self.columns.iter().position(|c| c == name)
    }

    /// Column `index`'s values, one per row.
    pub fn column(&self, index: usize) -> Option<&[f64]> {
        let rows = self.rows();
        self.values.get(index * rows..(index + 1) * rows)
    }

    /// The values of the column named `name`, one per row.
    pub fn column_named(&self, name: &str) -> Option<&[f64]> {
        self.column(self.column_index(name)?)
    }

    /// The value of column `column` at row `row`.
    pub fn value(&self, row: usize, column: usize) -> Option<f64> {
        self.column(column)?.get(row).copied()
    }
}

/// The rows read so far, row-major.
struct Rows {
    width: usize,
    times: Vec<f64>,
    values: Vec<f64>,
}

impl Rows {
    fn new(width: usize) -> Rows {
        Rows {
            width,
            times: Vec::new(),
            values: Vec::new(),
        }
    }

    /// Reads one row (`line` its number, `text` its text): as many fields as the header, every
    /// one a finite number, the time after the previous row's.
    fn push(&mut self, line: usize, text: &str, columns: &[String]) -> Result<(), TableError> {
        let expected = self.width + 1;
        let found = text.split('\t').count();
        if found != expected {
            return Err(TableError::FieldCount {
                line,
                found,
                expected,
            });
        }
        for (i, field) in text.split('\t').enumerate() {
            let name = i.checked_sub(1).map_or("time", |j| columns[j].as_str());
            let value = number(field, line, i + 1, name)?;
            if i == 0 {
                if let Some(&previous) = self.times.last() {
                    if value <= previous {
                        return Err(TableError::TimeNotIncreasing {
                            line,
                            time: value,
                            previous,
                        });
                    }
                }
                self.times.push(value);
            } else {
                self.values.push(value);
            }
        }
        Ok(())
    }

    /// The table, its values made column-major.
    fn into_table(self, columns: Vec<String>) -> Table {
        let rows = self.times.len();
        let mut values = Vec::with_capacity(self.values.len());
        for j in 0..self.width {
            values.extend((0..rows).map(|i| self.values[i * self.width + j]));
        }
        Table::from_columns(columns, self.times, values)
    }
}

/// The count of a line `KEY N` (`line` the line, if any).
fn count_line(line: Option<(usize, &str)>, key: &'static str) -> Result<usize, TableError> {
    let (number, text) = line.unwrap_or((0, ""));
    let mut words = text.split_ascii_whitespace();
    match (
        words.next(),
        words.next().map(str::parse::<usize>),
        words.next(),
    ) {
        (Some(k), Some(Ok(n)), None) if k == key => Ok(n),
        _ => Err(TableError::CountLine {
            line: number.max(1),
            key,
            found: text.to_string(),
        }),
    }
}

/// The column names of the header `text` on line `line`: `time`, then `declared - 1` names,
/// non-empty and unique.
fn header_names(line: usize, text: &str, declared: usize) -> Result<Vec<String>, TableError> {
    let fields: Vec<&str> = text.split('\t').map(str::trim).collect();
    if fields[0] != "time" {
        return Err(TableError::HeaderNotTime {
            line,
            found: fields[0].to_string(),
        });
    }
    if fields.len() != declared {
        return Err(TableError::HeaderCount {
            line,
            found: fields.len(),
            declared,
        });
    }
    for (i, name) in fields.iter().enumerate() {
        if name.is_empty() {
            return Err(TableError::EmptyName {
                line,
                column: i + 1,
            });
        }
        if let Some(first) = fields[..i].iter().position(|n| n == name) {
            return Err(TableError::DuplicateName {
                line,
                column: i + 1,
                name: name.to_string(),
                first: first + 1,
            });
        }
    }
    Ok(fields[1..].iter().map(|s| s.to_string()).collect())
}

/// The finite number in `field` (column `column`, named `name`, of line `line`).
fn number(field: &str, line: usize, column: usize, name: &str) -> Result<f64, TableError> {
    let field = field.trim();
    let at = |found: &str| (line, column, name.to_string(), found.to_string());
    match field.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        Ok(_) => {
            let (line, column, name, found) = at(field);
            Err(TableError::NotFinite {
                line,
                column,
                name,
                found,
            })
        }
        Err(_) => {
            let (line, column, name, found) = at(field);
            Err(TableError::NotANumber {
                line,
                column,
                name,
                found,
            })
        }
    }
}

/// What is wrong with a table's text; lines and columns count from 1 (column 1 is `time`).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TableError {
    /// A byte that is not UTF-8.
    #[error("line {line}: not UTF-8 text")]
    NotText {
        /// The line of the first such byte.
        line: usize,
    },
    /// Line 1 is not `datacolumns N`, or line 2 not `datarows M`.
    #[error("line {line}: expected `{key} N` (N a whole number), found {:?}", excerpt(.found))]
    CountLine {
        /// The line.
        line: usize,
        /// The key expected there.
        key: &'static str,
        /// The line's text.
        found: String,
    },
    /// Fewer than two declared columns (time and one of values).
    #[error(
        "datacolumns {declared}: a table has the time column and at least one more \
         (datacolumns counts the time column)"
    )]
    TooFewColumns {
        /// The declared count.
        declared: usize,
    },
    /// `datarows 0`.
    #[error("datarows 0: a table has at least one row")]
    NoRows,
    /// The text ends before the header.
    #[error("line 3: no header (expected `time` and the columns' names)")]
    NoHeader,
    /// The header's first name is not `time`.
    #[error(
        "line {line}, column 1: the header starts with {:?}, expected `time` (then the \
         columns' names, separated by tabs)",
        excerpt(.found)
    )]
    HeaderNotTime {
        /// The header's line.
        line: usize,
        /// Its first name.
        found: String,
    },
    /// The header has another count of names than `datacolumns` declares.
    #[error(
        "line {line}: the header has {found} tab-separated names, datacolumns declares \
         {declared}"
    )]
    HeaderCount {
        /// The header's line.
        line: usize,
        /// Its names, `time` included.
        found: usize,
        /// The declared count.
        declared: usize,
    },
    /// An empty name in the header (two tabs in a row, or a tab at an end).
    #[error("line {line}, column {column}: empty column name")]
    EmptyName {
        /// The header's line.
        line: usize,
        /// The column.
        column: usize,
    },
    /// A name given twice in the header.
    #[error("line {line}, column {column}: column name {:?} repeats column {first}", excerpt(.name))]
    DuplicateName {
        /// The header's line.
        line: usize,
        /// The column.
        column: usize,
        /// The name.
        name: String,
        /// The column that has it first.
        first: usize,
    },
    /// A row with another count of fields than the header.
    #[error(
        "line {line}: {found} tab-separated fields, expected {expected} (time and the \
         header's columns)"
    )]
    FieldCount {
        /// The row's line.
        line: usize,
        /// Its fields.
        found: usize,
        /// The header's, `time` included.
        expected: usize,
    },
    /// A field that is not a number.
    #[error("line {line}, column {column} ({}): {:?} is not a number", excerpt(.name), excerpt(.found))]
    NotANumber {
        /// The row's line.
        line: usize,
        /// The column.
        column: usize,
        /// The column's name.
        name: String,
        /// The field.
        found: String,
    },
    /// A field that is infinite or not a number (`inf`, `NaN`, or beyond the doubles).
    #[error("line {line}, column {column} ({}): {:?} is not finite", excerpt(.name), excerpt(.found))]
    NotFinite {
        /// The row's line.
        line: usize,
        /// The column.
        column: usize,
        /// The column's name.
        name: String,
        /// The field.
        found: String,
    },
    /// A row's time not after the previous row's.
    #[error("line {line}, column 1 (time): {time} s is not after the previous row's {previous} s")]
    TimeNotIncreasing {
        /// The row's line.
        line: usize,
        /// Its time, s.
        time: f64,
        /// The previous row's time, s.
        previous: f64,
    },
    /// A row after the declared count.
    #[error("line {line}: a row beyond the {declared} that datarows declares")]
    ExtraRow {
        /// The row's line.
        line: usize,
        /// The declared count.
        declared: usize,
    },
    /// Fewer rows than declared.
    #[error("{found} rows, datarows declares {declared}")]
    MissingRows {
        /// The rows found.
        found: usize,
        /// The declared count.
        declared: usize,
    },
    /// A blank line with rows after it.
    #[error("line {line}: a blank line between rows")]
    BlankLine {
        /// The blank line.
        line: usize,
    },
}

#[cfg(test)]
mod tests;
