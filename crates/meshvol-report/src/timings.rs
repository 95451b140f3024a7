//! Stage timings (`--timings`): how long each stage of a run took, in wall seconds and
//! in CPU seconds of the whole process, so that anyone can see on any machine which
//! stage runs on one thread (CPU ≈ wall) or waits (CPU ≪ wall × threads).
//!
//! The stages of one input are contiguous: each ends where the next starts, the first
//! starts when the input is read and the last ends when its report is printed, so
//! their wall seconds add up to the run's time for that input.

use crate::number::num;
use serde::Serialize;
use std::fmt::Write;

/// One stage. Field names are the JSON keys of the `timings` list.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StageTiming {
    /// What the stage does (`reading`, `welding`, `finding edges`, `finding crossings`).
    pub stage: String,
    pub wall_s: f64,
    /// CPU seconds (user + system) of the process during the stage: up to the thread
    /// count times `wall_s` when every thread works.
    pub cpu_s: f64,
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

/// The timings as text: one line a stage, then the total.
pub fn text(name: &str, timings: &[StageTiming]) -> String {
    let mut s = format!("{name}: timings (wall s, cpu s)\n");
    let (mut wall, mut cpu) = (0.0, 0.0);
    for t in timings {
        let _ = writeln!(s, "  {:<44} {:>10} {:>10}", t.stage, num(t.wall_s, 4), num(t.cpu_s, 4));
        wall += t.wall_s;
        cpu += t.cpu_s;
    }
    let _ = writeln!(s, "  {:<44} {:>10} {:>10}", "total", num(wall, 4), num(cpu, 4));
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_list_is_the_last_key() {
        let t = [StageTiming { stage: "reading".into(), wall_s: 0.5, cpu_s: 0.25 }];
        let line = with_timings("{\"file\":\"a\",\"warnings\":[]}\n", &t).unwrap();
        let v: serde_json::Value = serde_json::from_str(&line).unwrap();
        assert_eq!(v["timings"][0]["stage"], "reading");
        assert_eq!(v["timings"][0]["wall_s"], 0.5);
        assert_eq!(v["timings"][0]["cpu_s"], 0.25);
        assert!(line.ends_with("]}\n"));
        let empty = with_timings("{}\n", &t).unwrap();
        assert!(serde_json::from_str::<serde_json::Value>(&empty).is_ok(), "{empty}");
        assert!(with_timings("[1]\n", &t).is_err());
    }
}
