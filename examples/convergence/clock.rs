//! A clock that leaves out the study's own bookkeeping (reading an image's error after a pass),
//! so that each method is timed on its rendering alone; wall time, or the process's CPU time
//! over the thread count (steadier when other work shares the machine).

use std::time::{Duration, Instant};

/// What the clock counts.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ClockKind {
    /// Wall time.
    Wall,
    /// CPU time of all the process's threads divided by the worker threads (Linux
    /// `/proc/self/stat`, 10 ms ticks): what a quiet machine's wall time would be, when
    /// the workers are busy, whatever else runs.
    Cpu,
}

/// Seconds since the start, less the time spent in [`Clock::exclude`].
pub struct Clock {
    kind: ClockKind,
    threads: f64,
    start: Duration,
    excluded: Duration,
}

impl Clock {
    /// Starts now; `threads` divides CPU time.
    pub fn start(kind: ClockKind, threads: usize) -> Self {
        let mut clock = Clock {
            kind,
            threads: threads.max(1) as f64,
            start: Duration::ZERO,
            excluded: Duration::ZERO,
        };
        clock.start = clock.now();
        clock
    }

    fn now(&self) -> Duration {
        match self.kind {
            ClockKind::Wall => epoch().elapsed(),
            ClockKind::Cpu => process_cpu_time().div_f64(self.threads),
        }
    }

    /// Rendering seconds so far.
    pub fn seconds(&self) -> f64 {
        self.now()
            .saturating_sub(self.start)
            .saturating_sub(self.excluded)
            .as_secs_f64()
    }

    /// Runs `f` off the clock.
    pub fn exclude<T>(&mut self, f: impl FnOnce() -> T) -> T {
        let t = self.now();
        let out = f();
        self.excluded += self.now().saturating_sub(t);
        out
    }
}

/// A fixed instant wall times are measured from.
fn epoch() -> Instant {
    static EPOCH: std::sync::OnceLock<Instant> = std::sync::OnceLock::new();
    *EPOCH.get_or_init(Instant::now)
}

/// User plus system CPU time of every thread of this process (zero where `/proc` is absent).
fn process_cpu_time() -> Duration {
    // Fields 14 and 15 of /proc/self/stat, after the parenthesised command name, in clock
    // ticks of 1/100 s (USER_HZ, 100 on every Linux architecture).
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return Duration::ZERO;
    };
    let Some(rest) = stat.rsplit_once(')').map(|(_, r)| r) else {
        return Duration::ZERO;
    };
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // `rest` starts at field 3 (state), so field n is at index n − 3.
    let ticks: u64 = [11, 12]
        .iter()
        .filter_map(|&i| fields.get(i).and_then(|f| f.parse::<u64>().ok()))
        .sum();
    Duration::from_millis(ticks * 10)
}
