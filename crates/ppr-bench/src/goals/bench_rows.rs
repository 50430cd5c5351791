//! The rows of the bench's own CSV files that the goals read: `runtime.csv` (`ppr-bench
//! runtime`) and `comparison.csv` (`ppr-bench compare`). Columns are found by their header
//! names, so files with columns a session added (`run`, `binary`) read as well.

use std::path::{Path, PathBuf};

use crate::error::BenchError;
use crate::report::compare_report::SKIPPED;

/// A row of `runtime.csv`: one pass (or the whole frame) of one scene, camera and size.
#[derive(Clone, Debug, PartialEq)]
pub struct RuntimeRow {
    /// The scene, with the profile row's name in brackets for a profile row
    /// (`demo [frame span]`).
    pub scene: String,
    pub camera: String,
    pub width: u32,
    pub height: u32,
    /// `projection + reflection`, `projection`, `reflection`, `frame`, …
    pub pass: String,
    pub median_ms: f64,
    /// The pass's time over its bandwidth floor (`NaN` where it has none).
    pub ratio_to_floor: f64,
}

impl RuntimeRow {
    /// The scene without the profile row, and the profile row's name (`None` for the
    /// scene's default frame).
    pub fn scene_and_row(&self) -> (&str, Option<&str>) {
        split_label(&self.scene)
    }
}

/// A row of `comparison.csv`: one technique on one scene, camera and size.
#[derive(Clone, Debug, PartialEq)]
pub struct CompareRow {
    pub scene: String,
    pub camera: String,
    pub width: u32,
    pub height: u32,
    /// The technique with its options (`ppr`, `ssr-low stride=16 refine=4`,
    /// `ppr timing=frame`).
    pub technique: String,
    /// The sum of its passes' medians, or its whole frame's with `timing=frame` (`NaN`
    /// where the adapter gave no times).
    pub gpu_total_median_ms: f64,
    /// PSNR against the reference over the pixels whose reflection is on screen (`inf`
    /// where equal, `NaN` where quality was not measured).
    pub psnr_on_screen_db: f64,
    /// What the run scored against, from its command line (`--reference mirror`): the
    /// flag's value, or `default` where the command gave none or the file has no command.
    pub reference: String,
}

/// A row type read by column name.
pub trait BenchRow: Sized {
    /// Builds a row from one record; `Err` says which column failed and why.
    fn from_record(r: &Record<'_>) -> Result<Self, String>;
}

impl BenchRow for RuntimeRow {
    fn from_record(r: &Record<'_>) -> Result<Self, String> {
        let (scene, camera, width, height) = r.view()?;
        Ok(Self {
            scene,
            camera,
            width,
            height,
            pass: r.text("pass")?,
            median_ms: r.number("median_ms")?,
            ratio_to_floor: r.number_or_nan("ratio_to_floor")?,
        })
    }
}

impl BenchRow for CompareRow {
    fn from_record(r: &Record<'_>) -> Result<Self, String> {
        let (scene, camera, width, height) = r.view()?;
        Ok(Self {
            scene,
            camera,
            width,
            height,
            technique: r.text("technique")?,
            gpu_total_median_ms: r.number("gpu_total_median_ms")?,
            psnr_on_screen_db: r.number("psnr_on_screen_db")?,
            reference: r.optional("command").map_or_else(|| "default".to_owned(), reference_of),
        })
    }
}

/// One record with its file's header.
pub struct Record<'a> {
    header: &'a csv::StringRecord,
    fields: &'a csv::StringRecord,
}

impl Record<'_> {
    fn field(&self, name: &str) -> Result<&str, String> {
        let i = self.header.iter().position(|h| h == name).ok_or_else(|| format!("no column `{name}`"))?;
        self.fields.get(i).ok_or_else(|| format!("column `{name}` is missing from the row"))
    }

    /// The view a row measured: scene, camera, width and height (both files' first columns).
    fn view(&self) -> Result<(String, String, u32, u32), String> {
        Ok((self.text("scene")?, self.text("camera")?, self.whole("width")?, self.whole("height")?))
    }

    /// The field of a column the file may lack.
    fn optional(&self, name: &str) -> Option<&str> {
        self.field(name).ok()
    }

    fn text(&self, name: &str) -> Result<String, String> {
        self.field(name).map(str::to_owned)
    }

    fn whole(&self, name: &str) -> Result<u32, String> {
        let t = self.field(name)?;
        t.trim().parse().map_err(|_| format!("column `{name}`: `{t}` is not a whole number"))
    }

    /// A number as the suites write it: decimals, `NaN`/`nan`, `inf`, or an empty field, a
    /// dash or `skipped` (quality not measured) for no value (`NaN`).
    fn number(&self, name: &str) -> Result<f64, String> {
        let t = self.field(name)?;
        match t.trim() {
            "" | "-" | "–" | SKIPPED => Ok(f64::NAN),
            v => v.parse().map_err(|_| format!("column `{name}`: `{v}` is not a number")),
        }
    }

    /// [`Self::number`], `NaN` where the file has no such column (older files).
    fn number_or_nan(&self, name: &str) -> Result<f64, String> {
        if self.header.iter().any(|h| h == name) { self.number(name) } else { Ok(f64::NAN) }
    }
}

/// The value of `--reference` on a command line (`default` without one).
fn reference_of(command: &str) -> String {
    let mut words = command.split_whitespace();
    while let Some(w) = words.next() {
        if let Some(v) = w.strip_prefix("--reference=") {
            return v.to_owned();
        }
        if w == "--reference" {
            return words.next().unwrap_or("default").to_owned();
        }
    }
    "default".to_owned()
}

/// `scene [row]` → (`scene`, `Some(row)`); a label without brackets → (label, `None`).
pub fn split_label(label: &str) -> (&str, Option<&str>) {
    match label.split_once(" [") {
        Some((scene, rest)) => (scene, Some(rest.strip_suffix(']').unwrap_or(rest))),
        None => (label, None),
    }
}

/// The CSV file a path names: the path itself, or `default_name` inside it if it is a
/// folder (a suite's `--out` folder).
pub fn csv_path(path: &Path, default_name: &str) -> PathBuf {
    if path.is_dir() { path.join(default_name) } else { path.to_path_buf() }
}

/// Every row of a CSV file; an error names the file, the line and the column.
///
/// # Errors
/// The file cannot be read, lacks a column or holds a value that does not parse.
pub fn read_rows<T: BenchRow>(path: &Path) -> Result<Vec<T>, BenchError> {
    let csv_error = |e: csv::Error| match e.kind() {
        csv::ErrorKind::Io(io) => BenchError::io(path, std::io::Error::new(io.kind(), io.to_string())),
        _ => BenchError::Csv { path: path.to_path_buf(), reason: e.to_string() },
    };
    let mut reader = csv::Reader::from_path(path).map_err(csv_error)?;
    let header = reader.headers().map_err(csv_error)?.clone();
    let mut rows = Vec::new();
    for fields in reader.records() {
        let fields = fields.map_err(csv_error)?;
        let line = fields.position().map_or(0, csv::Position::line);
        let row = T::from_record(&Record { header: &header, fields: &fields }).map_err(|reason| {
            BenchError::Csv { path: path.to_path_buf(), reason: format!("line {line}: {reason}") }
        })?;
        rows.push(row);
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_split_into_scene_and_profile_row() {
        assert_eq!(split_label("demo"), ("demo", None));
        assert_eq!(split_label("demo [frame span]"), ("demo", Some("frame span")));
        assert_eq!(
            split_label("stairway-1000 [path blockers off]"),
            ("stairway-1000", Some("path blockers off"))
        );
    }

    #[test]
    fn the_reference_is_read_from_the_command_line() {
        assert_eq!(reference_of("ppr-bench compare --reference mirror --scene demo"), "mirror");
        assert_eq!(reference_of("ppr-bench compare --reference=glossy"), "glossy");
        assert_eq!(reference_of("ppr-bench compare --scene demo"), "default");
    }

    #[test]
    fn rows_read_by_header_with_extra_columns_and_nan() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("runtime.csv");
        std::fs::write(
            &path,
            "run,scene,camera,width,height,pass,median_ms,ratio_to_floor\n\
             call 1,\"demo [frame span]\",cam,3840,2160,frame,0.25,NaN\n",
        )
        .unwrap();
        let rows: Vec<RuntimeRow> = read_rows(&csv_path(dir.path(), "runtime.csv")).unwrap();
        assert_eq!(rows.len(), 1);
        assert_eq!(rows[0].scene_and_row(), ("demo", Some("frame span")));
        assert!((rows[0].median_ms - 0.25).abs() < 1e-12);
        assert!(rows[0].ratio_to_floor.is_nan());
    }

    #[test]
    fn numbers_read_as_the_suites_write_them() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("comparison.csv");
        std::fs::write(
            &path,
            "scene,camera,width,height,technique,gpu_total_median_ms,psnr_on_screen_db\n\
             demo,a,64,36,exact,nan,inf\n\
             demo,b,64,36,ppr,0.5,\n\
             demo,c,64,36,ssr-low,0.25,skipped\n",
        )
        .unwrap();
        let rows: Vec<CompareRow> = read_rows(&path).unwrap();
        assert!(rows[0].gpu_total_median_ms.is_nan() && rows[0].psnr_on_screen_db == f64::INFINITY);
        assert!((rows[1].gpu_total_median_ms - 0.5).abs() < 1e-12 && rows[1].psnr_on_screen_db.is_nan());
        assert!(rows[2].psnr_on_screen_db.is_nan());
        std::fs::write(&path, "scene,camera,width,height,technique,gpu_total_median_ms,psnr_on_screen_db\ndemo,a,64,36,ppr,fast,1\n")
            .unwrap();
        let err = read_rows::<CompareRow>(&path).unwrap_err().to_string();
        assert!(err.contains("line 2: column `gpu_total_median_ms`: `fast` is not a number"), "{err}");
    }

    #[test]
    fn a_missing_column_names_the_file_and_the_column() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("comparison.csv");
        std::fs::write(
            &path,
            "scene,camera,width,height,technique,gpu_total_median_ms\ndemo,c,1,1,ppr,0.1\n",
        )
        .unwrap();
        let err = read_rows::<CompareRow>(&path).unwrap_err().to_string();
        assert!(
            err.contains("comparison.csv") && err.contains("line 2: no column `psnr_on_screen_db`"),
            "{err}"
        );
        let err = read_rows::<CompareRow>(&dir.path().join("absent.csv")).unwrap_err().to_string();
        assert!(err.contains("absent.csv"), "{err}");
    }
}
