//! Stage timings (`--timings`): how long each stage of a run took, in wall seconds and
//! in CPU seconds of the whole process, so that anyone can see on any machine which
//! stage runs on one thread (CPU ≈ wall) or waits (CPU ≪ wall × threads).
//!
//! The stages of one input are contiguous: each ends where the next starts, the first
//! starts when the input is read and the last ends when its report is printed, so
//! their wall seconds add up to the run's time for that input.
//!
//! Each stage also gives the process's peak resident memory at its end (the high-water
//! mark the system keeps, files mapped into memory included), so that the stage which
//! raises the peak is the first one whose figure is the run's largest.

use crate::number::num;
use serde::Serialize;
use std::fmt::Write;
use std::time::Instant;

/// One stage. Field names are the JSON keys of the `timings` list.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StageTiming {
    /// What the stage does (`reading`, `welding`, `finding edges`, `finding crossings`).
    pub stage: String,
    pub wall_s: f64,
    /// CPU seconds (user + system) of the process during the stage: up to the thread
    /// count times `wall_s` when every thread works.
    pub cpu_s: f64,
    /// The process's peak resident memory so far, in MB (10⁶ bytes), at the stage's end;
    /// absent where the system does not say.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub peak_mb: Option<f64>,
}

/// A stage under way: its name and the clocks at its start.
pub struct Running {
    stage: String,
    start: Instant,
    cpu_s: f64,
}

impl Running {
    pub fn start(stage: &str) -> Running {
        Running { stage: stage.to_string(), start: Instant::now(), cpu_s: process_cpu_seconds() }
    }

    /// The stage, ending now.
    pub fn finish(self) -> StageTiming {
        StageTiming {
            wall_s: self.start.elapsed().as_secs_f64(),
            cpu_s: (process_cpu_seconds() - self.cpu_s).max(0.0),
            peak_mb: peak_resident_bytes().map(|b| b as f64 / 1e6),
            stage: self.stage,
        }
    }
}

/// User and system CPU seconds of this process so far (the `cpu_s` of a stage is the
/// difference across it).
#[cfg(unix)]
pub fn process_cpu_seconds() -> f64 {
    let mut usage = std::mem::MaybeUninit::<libc::rusage>::zeroed();
    // SAFETY: getrusage writes the struct it is given; RUSAGE_SELF is always valid.
    if unsafe { libc::getrusage(libc::RUSAGE_SELF, usage.as_mut_ptr()) } != 0 {
        return 0.0;
    }
    // SAFETY: initialised above (zeroed, then written by a successful call).
    let usage = unsafe { usage.assume_init() };
    let seconds = |t: libc::timeval| t.tv_sec as f64 + t.tv_usec as f64 * 1e-6;
    seconds(usage.ru_utime) + seconds(usage.ru_stime)
}

/// The process's peak resident memory so far (`ru_maxrss`), in bytes.
#[cfg(unix)]
pub fn peak_resident_bytes() -> Option<u64> {
    let mut usage = std::mem::MaybeUninit::<libc::rusage>::zeroed();
    // SAFETY: as in process_cpu_seconds.
    if unsafe { libc::getrusage(libc::RUSAGE_SELF, usage.as_mut_ptr()) } != 0 {
        return None;
    }
    // SAFETY: initialised above (zeroed, then written by a successful call).
    let peak = unsafe { usage.assume_init() }.ru_maxrss as u64;
    // Linux counts kibibytes, macOS bytes.
    Some(if cfg!(target_os = "macos") { peak } else { peak * 1024 })
}

/// Peak memory is not read on this system.
#[cfg(not(unix))]
pub fn peak_resident_bytes() -> Option<u64> {
    None
}

/// CPU time is not read on this system: timings give wall seconds only.
#[cfg(not(unix))]
pub fn process_cpu_seconds() -> f64 {
    0.0
}

/// `line` (one JSON object and its newline, as [`crate::json_line`] writes it) with a
/// `timings` list added as its last key.
pub fn with_timings(line: &str, timings: &[StageTiming]) -> Result<String, String> {
    let list = serde_json::to_string(timings).map_err(|e| e.to_string())?;
    let object = line.trim_end();
    let Some(open) = object.strip_suffix('}') else {
        return Err(format!("not a JSON object: {object}"));
    };
    let comma = if open.trim_end().ends_with('{') { "" } else { "," };
    Ok(format!("{open}{comma}\"timings\":{list}}}\n"))
}

/// The timings as text: one line a stage, then the total (and the peak memory: the
/// largest at any stage's end).
pub fn text(name: &str, timings: &[StageTiming]) -> String {
    let mut s = format!("{name}: timings (wall s, cpu s, peak MB)\n");
    let (mut wall, mut cpu) = (0.0, 0.0);
    let peak_mb = |p: Option<f64>| p.map_or(String::new(), |p| format!("{p:.0}"));
    for t in timings {
        let (w, c, p) = (num(t.wall_s, 4), num(t.cpu_s, 4), peak_mb(t.peak_mb));
        let _ = writeln!(s, "  {:<44} {w:>10} {c:>10} {p:>9}", t.stage);
        wall += t.wall_s;
        cpu += t.cpu_s;
    }
    let peak = timings.iter().filter_map(|t| t.peak_mb).reduce(f64::max);
    let (w, c, p) = (num(wall, 4), num(cpu, 4), peak_mb(peak));
    let _ = writeln!(s, "  {:<44} {w:>10} {c:>10} {p:>9}", "total");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_list_is_the_last_key() {
        let t =
            [StageTiming { stage: "reading".into(), wall_s: 0.5, cpu_s: 0.25, peak_mb: Some(7.0) }];
        let line = with_timings("{\"file\":\"a\",\"warnings\":[]}\n", &t).unwrap();
        let v: serde_json::Value = serde_json::from_str(&line).unwrap();
        assert_eq!(v["timings"][0]["stage"], "reading");
        assert_eq!(v["timings"][0]["wall_s"], 0.5);
        assert_eq!(v["timings"][0]["cpu_s"], 0.25);
        assert_eq!(v["timings"][0]["peak_mb"], 7.0);
        assert!(line.ends_with("]}\n"));
        let empty = with_timings("{}\n", &t).unwrap();
        assert!(serde_json::from_str::<serde_json::Value>(&empty).is_ok(), "{empty}");
        assert!(with_timings("[1]\n", &t).is_err());
    }
}
