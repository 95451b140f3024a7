//! `timings=True`: the stages of one call with their wall and CPU seconds, as the
//! command's `--timings` lists them (`meshvol_report::timings`): the check's stages
//! (the core's progress hook names them), then the measuring.

use meshvol_report::timings::{Running, StageTiming};
use pyo3::prelude::*;
use std::sync::Mutex;

/// The stages done, and the current one.
type Stages = (Vec<StageTiming>, Option<Running>);

/// The stages of one call as they pass: each stage named ends the one before it.
pub struct Clock {
    state: Mutex<Stages>,
}

impl Clock {
    pub fn new() -> Clock {
        Clock { state: Mutex::new((Vec::new(), None)) }
    }

    /// Ends the current stage and starts `stage`.
    pub fn start(&self, stage: &str) {
        let mut state = self.state.lock().unwrap_or_else(|e| e.into_inner());
        close(&mut state);
        state.1 = Some(Running::start(stage));
    }

    /// The stages, the last ending now.
    pub fn finish(&self) -> Vec<StageTiming> {
        let mut state = self.state.lock().unwrap_or_else(|e| e.into_inner());
        close(&mut state);
        std::mem::take(&mut state.0)
    }
}

fn close(state: &mut Stages) {
    if let Some(stage) = state.1.take() {
        state.0.push(stage.finish());
    }
}

impl meshvol::progress::Progress for Clock {
    fn stage(&self, name: &'static str) {
        self.start(name);
    }
}

/// Starts `stage` on `clock` when timing.
pub fn stage(clock: Option<&Clock>, stage: &str) {
    if let Some(c) = clock {
        c.start(stage);
    }
}

/// The stages as Python sees them in every report: a list of {stage, wall_s, cpu_s}.
pub fn to_python<'py>(py: Python<'py>, stages: &[StageTiming]) -> PyResult<Bound<'py, PyAny>> {
    let value = serde_json::to_value(stages).map_err(crate::errors::mesh_error)?;
    crate::dict::to_python(py, &value)
}
