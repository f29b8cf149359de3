//! A wall clock that leaves out the study's own bookkeeping (reading an image's error after a
//! pass), so that each method is timed on its rendering alone.

use std::time::{Duration, Instant};

/// Seconds since the start, less the time spent in [`Clock::exclude`].
pub struct Clock {
    start: Instant,
    excluded: Duration,
}

impl Clock {
    /// Starts now.
    pub fn start() -> Self {
        Clock {
            start: Instant::now(),
            excluded: Duration::ZERO,
        }
    }

    /// Rendering seconds so far.
    pub fn seconds(&self) -> f64 {
        self.start.elapsed().saturating_sub(self.excluded).as_secs_f64()
    }

    /// Runs `f` off the clock.
    pub fn exclude<T>(&mut self, f: impl FnOnce() -> T) -> T {
        let t = Instant::now();
        let out = f();
        self.excluded += t.elapsed();
        out
    }
}
