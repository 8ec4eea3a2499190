//! Where `simulate` sends a run's ticks as they are produced: one CSV row each (the same
//! rows [`crate::sim::report::write_csv`] writes) and a bounded [`PlotTrace`] for the
//! plots. Memory: the CSV writer's buffer and the trace, a constant whatever the run's
//! length.

use super::record::Sample;
use super::report::sample_csv;
use super::run::SampleSink;
use super::trace::PlotTrace;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// A run's CSV, written as the run goes, and its plot trace.
#[derive(Debug)]
pub struct RunStream {
    path: PathBuf,
    csv: csv::Writer<BufWriter<File>>,
    /// What the plots get.
    pub trace: PlotTrace,
}

impl RunStream {
    /// Creates (truncates) the CSV at `path`.
    pub fn create(path: &Path) -> std::io::Result<Self> {
        Ok(Self {
            path: path.to_path_buf(),
            csv: sample_csv(path)?,
            trace: PlotTrace::new(),
        })
    }

    /// Flushes the CSV (a run without ticks still gets the header) and gives the trace.
    pub fn finish(mut self) -> std::io::Result<PlotTrace> {
        self.csv.flush()?;
        Ok(self.trace)
    }
}

impl SampleSink for RunStream {
    fn sample(&mut self, s: &Sample) -> Result<(), String> {
        self.csv
            .serialize(s)
            .map_err(|e| format!("--out: {}: {e}", self.path.display()))?;
        self.trace.push(s);
        Ok(())
    }
}
