//! Radiance estimators, render modes, a deterministic tiled renderer, and images.
//!
//! (Crate docs to be completed by the pm-render issue.)
