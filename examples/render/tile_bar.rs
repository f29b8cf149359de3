//! The render example's progress bar: an indicatif bar fed by the renderer's progress
//! callbacks, one tile at a time.

use indicatif::{ProgressBar, ProgressStyle};
use photon_maps::render::Progress;

/// An indicatif bar fed by the renderer's progress callbacks (hidden when stderr is no TTY).
pub(crate) struct TileBar(pub(crate) ProgressBar);

impl TileBar {
    pub(crate) fn new(label: &str) -> Self {
        let bar = ProgressBar::new(0);
        if let Ok(style) = ProgressStyle::with_template("{msg:>24} [{bar:40}] {pos}/{len} tiles {elapsed}") {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_message(label.to_owned());
        TileBar(bar)
    }
}

impl Progress for TileBar {
    fn phase(&self, name: &'static str) {
        self.0.set_message(name);
    }
    fn tiles_done(&self, _done: usize, total: usize) {
        if self.0.length() != Some(total as u64) {
            self.0.set_length(total as u64);
        }
        self.0.inc(1);
    }
}
