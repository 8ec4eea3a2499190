//! The per-tick CSV and the JSON summary.

use super::*;

/// Writes `samples` as a CSV time series to `path`: a header row with the field names of
/// [`Sample`] (the units are in the names, see [`SAMPLE_CSV_FIELDS`]), then one row per
/// sample. Floats are printed in their shortest round-trip form (`NaN`, `inf`, `-inf` for
/// the non-finite ones), `slipping` as `true`/`false`. An empty `samples` still gets the
/// header.
pub fn write_csv(path: &Path, samples: &[Sample]) -> io::Result<()> {
    let mut w = csv::Writer::from_writer(BufWriter::new(File::create(path)?));
    if samples.is_empty() {
        w.write_record(SAMPLE_CSV_FIELDS)?;
    }
    for s in samples {
        w.serialize(s)?;
    }
    w.flush()
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
