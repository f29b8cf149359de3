//! The render example (filled in by the pm-render issue).

fn main() {}
