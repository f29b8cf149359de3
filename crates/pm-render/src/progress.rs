//! Progress reporting: a small observer the renderer calls as tiles finish (`()` ignores it).

/// Receives progress from the renderer. Called from worker threads, without locks on the
/// renderer's side; keep implementations cheap.
pub trait Progress: Sync {
    /// A phase begins: `"guide"` (camera-driven emission learning), `"trace"`, `"build"` or
    /// `"render"` (and `"pilot"` in progressive renders).
    fn phase(&self, name: &'static str) {
        let _ = name;
    }
    /// `done` of `total` tiles are finished.
    fn tiles_done(&self, done: usize, total: usize);
    /// A progressive render finished its `passes`-th pass, having emitted `photons` photon
    /// paths in all.
    fn pass_done(&self, passes: u64, photons: u64) {
        let _ = (passes, photons);
    }
}

impl Progress for () {
    fn tiles_done(&self, _done: usize, _total: usize) {}
}

impl<P: Progress + ?Sized> Progress for &P {
    fn phase(&self, name: &'static str) {
        (**self).phase(name)
    }
    fn tiles_done(&self, done: usize, total: usize) {
        (**self).tiles_done(done, total)
    }
    fn pass_done(&self, passes: u64, photons: u64) {
        (**self).pass_done(passes, photons)
    }
}
