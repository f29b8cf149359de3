//! How long each step of an arrangement took, for profiling a split on a real scene, and the
//! timer that measures such steps.

/// Wall-clock seconds of each step of [`split_polygons_at_intersections`](super::split_polygons_at_intersections),
/// in the order they run. Timings differ from run to run; everything else an
/// [`Arrangement`](super::Arrangement) holds is the same bits on every run and thread count.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ArrangementSeconds {
    /// Each face's plane, bounds and neighbours across its edges.
    pub faces: f64,
    /// The candidate pairs and how each pair meets (the broad phase and the pair tests,
    /// [`IntersectionCounts::candidate_pairs`](super::IntersectionCounts::candidate_pairs) of them).
    pub meetings: f64,
    /// Cutting the faces along the segments where they meet, with the T-junctions.
    pub cutting: f64,
    /// Dropping the hidden copies of coincident faces and marking pieces sealed in solids.
    pub copies_and_sealing: f64,
}

impl ArrangementSeconds {
    /// The sum of the steps.
    pub fn total(&self) -> f64 {
        self.faces + self.meetings + self.cutting + self.copies_and_sealing
    }
}

/// Times consecutive steps: each [`StepTimer::lap`] is the wall-clock seconds since the one
/// before (or since [`StepTimer::start`]).
///
/// ```
/// let mut timer = pm_geom::StepTimer::start();
/// std::thread::sleep(std::time::Duration::from_millis(20));
/// let slept = timer.lap();
/// assert!(slept >= 0.02, "a lap holds the step since the last: {slept} s");
/// ```
#[derive(Clone, Copy, Debug)]
pub struct StepTimer {
    last: std::time::Instant,
}

impl StepTimer {
    /// A timer whose first lap starts now.
    pub fn start() -> Self {
        StepTimer {
            last: std::time::Instant::now(),
        }
    }

    /// Seconds since the last lap, and a new lap begun.
    pub fn lap(&mut self) -> f64 {
        let now = std::time::Instant::now();
        let seconds = (now - self.last).as_secs_f64();
        self.last = now;
        seconds
    }
}
