//! The per-tick CSV and the JSON summary.

use super::*;

/// Writes `samples` as a CSV time series to `path`: a header row with the field names of
/// [`Sample`] (the units are in the names, see [`SAMPLE_CSV_FIELDS`]), then one row per
/// sample. Floats are printed in their shortest round-trip form (`NaN`, `inf`, `-inf` for
/// the non-finite ones), `slipping` as `true`/`false`. An empty `samples` still gets the
/// header.
pub fn write_csv(path: &Path, samples: &[Sample]) -> io::Result<()> {
    let mut w = sample_csv(path)?;
    for s in samples {
        w.serialize(s)?;
    }
    w.flush()
}

/// Creates (truncates) a sample CSV at `path` and writes its header, [`SAMPLE_CSV_FIELDS`]
/// (written here, not by `csv` from the first row: its header writer refuses the nested
/// [`Sample::parts`], whose fields its rows write inline).
pub fn sample_csv(path: &Path) -> io::Result<csv::Writer<BufWriter<File>>> {
    let mut w = csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(BufWriter::new(File::create(path)?));
    w.write_record(SAMPLE_CSV_FIELDS)?;
    Ok(w)
}

#[derive(Serialize)]
pub(super) struct SummaryFile<'a> {
    runs: &'a [RunSummary],
}

/// Writes `{"runs": [...]}` with every [`RunSummary`] as pretty-printed JSON to `path`.
/// Non-finite floats become `null` (JSON has no NaN).
pub fn write_summary_json(path: &Path, runs: &[RunSummary]) -> io::Result<()> {
    let mut w = BufWriter::new(File::create(path)?);
    serde_json::to_writer_pretty(&mut w, &SummaryFile { runs })?;
    w.write_all(b"\n")?;
    w.flush()
}
