//! Shard files against crafted and hostile input: headers whose pass ranges wrap, NaN and
//! infinite sums, a FIFO named as a shard, a shard given twice; and the bytes and memory of
//! writing and merging them.
//!
//! Crafted files are written here with the exr crate from the format's description (the mean
//! as R, G, B; the sums' f64 bits in `pmSum{Hi,Lo}{0,1}{R,G,B}`, high word first; one
//! `photonMapsShard` text attribute of five lines), independently of the library's writer.

#[path = "../../../tests/support/tracking_allocator.rs"]
mod tracking_allocator;

use exr::meta::attribute::{AttributeValue, Text};
use exr::prelude::{Encoding, LayerAttributes, SpecificChannels, Vec2, WritableImage};
use glam::{DVec3, Vec3};
use pm_render::Image;
use pm_render::progressive::{MAX_PASS, PassSums, Shard, ShardError};
use std::path::{Path, PathBuf};

/// Held for writing by the memory measurement and for reading by every other test.
static ALONE: std::sync::RwLock<()> = std::sync::RwLock::new(());

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("pm-shard-files-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn words(x: f64) -> (u32, u32) {
    ((x.to_bits() >> 32) as u32, x.to_bits() as u32)
}

/// Writes a shard file by hand: header lines `lines`, size `w × h`, every pixel's sums
/// `sum(x, y)` as (hi, lo).
fn write_raw(
    path: &Path,
    lines: &[&str],
    w: usize,
    h: usize,
    sum: impl Fn(usize, usize) -> (DVec3, DVec3) + Sync,
) {
    let pixel = |Vec2(x, y): Vec2<usize>| {
        let (hi, lo) = sum(x, y);
        let (rh, gh, bh) = (words(hi.x), words(hi.y), words(hi.z));
        let (rl, gl, bl) = (words(lo.x), words(lo.y), words(lo.z));
        (
            hi.x as f32,
            hi.y as f32,
            hi.z as f32,
            rh.0,
            rh.1,
            rl.0,
            rl.1,
            gh.0,
            gh.1,
            gl.0,
            gl.1,
            bh.0,
            bh.1,
            bl.0,
            bl.1,
        )
    };
    let channels = SpecificChannels::build()
        .with_channel::<f32>("R")
        .with_channel::<f32>("G")
        .with_channel::<f32>("B")
        .with_channel::<u32>("pmSumHi0R")
        .with_channel::<u32>("pmSumHi1R")
        .with_channel::<u32>("pmSumLo0R")
        .with_channel::<u32>("pmSumLo1R")
        .with_channel::<u32>("pmSumHi0G")
        .with_channel::<u32>("pmSumHi1G")
        .with_channel::<u32>("pmSumLo0G")
        .with_channel::<u32>("pmSumLo1G")
        .with_channel::<u32>("pmSumHi0B")
        .with_channel::<u32>("pmSumHi1B")
        .with_channel::<u32>("pmSumLo0B")
        .with_channel::<u32>("pmSumLo1B")
        .with_pixel_fn(pixel);
    let mut attributes = LayerAttributes::default();
    let text = Text::new_or_none(lines.join("\n").as_str()).unwrap();
    attributes
        .other
        .insert(Text::from("photonMapsShard"), AttributeValue::Text(text));
    let layer = exr::prelude::Layer::new((w, h), attributes, Encoding::SMALL_LOSSLESS, channels);
    exr::prelude::Image::from_layer(layer)
        .write()
        .to_file(path)
        .unwrap();
}

/// A valid crafted shard of `passes` passes from `first`, every sum `value`.
fn write_plain(path: &Path, first: &str, passes: &str, value: f64) {
    let lines = ["photon-maps shard v2", first, passes, "scene", "settings"];
    write_raw(path, &lines, 4, 3, |_, _| (DVec3::splat(value), DVec3::ZERO));
}

#[test]
fn the_format_read_here_is_the_format_written() {
    let _shared = ALONE.read().unwrap_or_else(|e| e.into_inner());
    let dir = scratch("format");
    let path = dir.join("a.exr");
    write_plain(&path, "3", "2", 5.0);
    let shard = Shard::read_exr(&path).unwrap();
    assert_eq!(shard.pass_range(), 3..5);
    assert!(shard.mean().pixels().iter().all(|p| *p == Vec3::splat(2.5)));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn pass_ranges_that_wrap_or_reach_the_pilot_are_refused_naming_the_shard() {
    let _shared = ALONE.read().unwrap_or_else(|e| e.into_inner());
    let dir = scratch("wrap");
    let max = MAX_PASS.to_string();
    let cases: [(&str, &str); 4] = [
        ("18446744073709551615", "2"),
        ("18446744073709551614", "18446744073709551615"),
        (&max, "2"),
        ("0", "0"),
    ];
    for (first, passes) in cases {
        let path = dir.join(format!("s{first}-{passes}.exr"));
        write_plain(&path, first, passes, 1.0);
        let err = Shard::read_exr(&path).unwrap_err();
        assert!(
            matches!(err, ShardError::BadPassRange { .. } | ShardError::NoPasses),
            "{first}+{passes}: {err}"
        );
        if passes != "0" {
            assert!(err.to_string().contains(&path.display().to_string()), "{err}");
        }
    }
    // Passes 0..u64::MAX and a shard at u64::MAX: in the old code the total pass count
    // wrapped to 0 and every merged pixel came out NaN with exit 0.
    let (a, b) = (dir.join("a.exr"), dir.join("b.exr"));
    write_plain(&a, "0", "18446744073709551615", 1.0);
    write_plain(&b, "18446744073709551615", "1", 1.0);
    let merged = Shard::merge_files(&[&a, &b]);
    match merged {
        Err(ShardError::BadPassRange { shard, .. }) => assert_eq!(shard, b.display().to_string()),
        other => panic!("{other:?}"),
    }
    // The whole range there is, in two shards, merges.
    write_plain(&a, "0", "18446744073709551613", 1.0);
    write_plain(&b, "18446744073709551613", "1", 1.0);
    let merged = Shard::merge_files(&[&a, &b]).unwrap();
    assert_eq!(merged.pass_range(), 0..MAX_PASS);
    assert!(merged.mean().pixels().iter().all(|p| p.is_finite()));
    // The last pass there is, alone, is a valid shard.
    write_plain(&b, &max, "1", 1.0);
    assert_eq!(Shard::read_exr(&b).unwrap().pass_range(), MAX_PASS..MAX_PASS + 1);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn non_finite_sums_are_refused_naming_the_shard_and_pixel() {
    let _shared = ALONE.read().unwrap_or_else(|e| e.into_inner());
    let dir = scratch("nan");
    let good = dir.join("good.exr");
    write_plain(&good, "0", "1", 1.0);
    for (name, bad) in [
        ("nan", DVec3::new(0.0, f64::NAN, 0.0)),
        ("inf", DVec3::new(f64::INFINITY, 0.0, 0.0)),
        // Finite in f64, infinite as an f32 mean.
        ("huge", DVec3::new(0.0, 0.0, 1e300)),
    ] {
        let path = dir.join(format!("{name}.exr"));
        let lines = ["photon-maps shard v2", "1", "1", "scene", "settings"];
        write_raw(&path, &lines, 4, 3, |x, y| {
            let v = if (x, y) == (2, 1) { bad } else { DVec3::ONE };
            (v, DVec3::ZERO)
        });
        for result in [Shard::read_exr(&path), Shard::merge_files(&[&good, &path])] {
            match result {
                Err(ShardError::NonFinite { shard, x: 2, y: 1 }) => {
                    assert_eq!(shard, path.display().to_string())
                }
                other => panic!("{name}: {other:?}"),
            }
        }
    }
    // A NaN in the remainder part as well.
    let path = dir.join("lo.exr");
    let lines = ["photon-maps shard v2", "1", "1", "scene", "settings"];
    write_raw(&path, &lines, 4, 3, |_, _| (DVec3::ONE, DVec3::splat(f64::NAN)));
    assert!(matches!(
        Shard::read_exr(&path),
        Err(ShardError::NonFinite { .. })
    ));
    // And in memory: a mean with an infinite pixel is no shard.
    let mut mean = Image::new(2, 2).unwrap();
    mean.set(1, 0, Vec3::new(f32::INFINITY, 0.0, 0.0));
    assert!(matches!(
        Shard::new(mean, 0, 1, "s", "t"),
        Err(ShardError::NonFinite { x: 1, y: 0, .. })
    ));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_shard_given_twice_is_named_as_the_duplicate_not_as_a_gap() {
    let _shared = ALONE.read().unwrap_or_else(|e| e.into_inner());
    let dir = scratch("twice");
    let (a, c) = (dir.join("a.exr"), dir.join("c.exr"));
    write_plain(&a, "0", "2", 1.0);
    write_plain(&c, "4", "2", 1.0);
    let spelled_again = dir.join(".").join("c.exr");
    for list in [vec![&c, &a, &c], vec![&c, &a, &spelled_again]] {
        match Shard::merge_files(&list) {
            Err(ShardError::Duplicate { shard }) => assert!(shard.ends_with("c.exr"), "{shard}"),
            other => panic!("{other:?}"),
        }
    }
    // Two files with one range: an overlap naming both.
    let c2 = dir.join("c2.exr");
    write_plain(&c2, "4", "2", 1.0);
    let err = Shard::merge_files(&[&c, &a, &c2]).unwrap_err();
    assert!(matches!(err, ShardError::Overlap { .. }), "{err}");
    assert!(err.to_string().contains("c2.exr"), "{err}");
    // Without the duplicate, the gap is what is wrong.
    assert!(matches!(Shard::merge_files(&[&c, &a]), Err(ShardError::Gap { missing }) if missing == (2..4)));
    std::fs::remove_dir_all(&dir).ok();
}

#[cfg(unix)]
#[test]
fn a_fifo_named_as_a_shard_is_refused_without_blocking() {
    let _shared = ALONE.read().unwrap_or_else(|e| e.into_inner());
    let dir = scratch("fifo");
    let fifo = dir.join("f.exr");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        eprintln!("mkfifo not available; skipping");
        return;
    }
    let good = dir.join("good.exr");
    write_plain(&good, "0", "1", 1.0);
    let (send, receive) = std::sync::mpsc::channel();
    let paths = [good.clone(), fifo.clone()];
    std::thread::spawn(move || {
        let _ = send.send(Shard::merge_files(&paths).map(|_| ()));
    });
    let result = receive
        .recv_timeout(std::time::Duration::from_secs(20))
        .expect("merging a FIFO blocked for 20 s");
    assert!(matches!(result, Err(ShardError::NotAFile { .. })), "{result:?}");
    std::fs::remove_dir_all(&dir).ok();
}

fn shard_of(value: f32, first: u64, passes: u64, w: u32, h: u32) -> Shard {
    let mean = Image::from_fn(w, h, |x, y| Vec3::new(value, x as f32, y as f32)).unwrap();
    Shard::new(mean, first, passes, "scene", "settings").unwrap()
}

#[test]
fn a_shard_file_has_the_same_bytes_every_time_it_is_written() {
    let _shared = ALONE.read().unwrap_or_else(|e| e.into_inner());
    let dir = scratch("bytes");
    let shard = shard_of(0.3, 7, 3, 16, 8);
    let first = dir.join("first.exr");
    shard.write_exr(&first).unwrap();
    let bytes = std::fs::read(&first).unwrap();
    // Four attributes in a hash map came out in a different order from write to write.
    for i in 0..8 {
        let again = dir.join(format!("again{i}.exr"));
        shard.write_exr(&again).unwrap();
        assert_eq!(std::fs::read(&again).unwrap(), bytes, "write {i} differs");
    }
    assert_eq!(Shard::read_exr(&first).unwrap(), shard);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn merging_files_holds_one_running_sum_not_every_shard() {
    // The peak counts every thread's allocations: run alone among this file's tests.
    let _alone = ALONE.write().unwrap_or_else(|e| e.into_inner());
    let dir = scratch("stream");
    let (w, h) = (256u32, 256u32);
    let paths: Vec<PathBuf> = (0..6)
        .map(|i| {
            let path = dir.join(format!("s{i}.exr"));
            shard_of(i as f32, i, 1, w, h).write_exr(&path).unwrap();
            path
        })
        .collect();
    let sums = w as usize * h as usize * PassSums::BYTES_PER_PIXEL as usize;
    let before = tracking_allocator::reset_peak();
    let merged = Shard::merge_files(&paths).unwrap();
    let peak = tracking_allocator::peak() - before;
    assert_eq!(merged.pass_range(), 0..6);
    assert_eq!(merged.mean().pixels()[0], Vec3::new(2.5, 0.0, 0.0));
    // The running sum, the result's copy and the decoder's buffers: well below six shards.
    assert!(peak < 3 * sums, "peak {peak} B for sums of {sums} B");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn pixel_state_is_counted_against_its_limit_at_both_ends() {
    let _shared = ALONE.read().unwrap_or_else(|e| e.into_inner());
    use pm_render::image::{MAX_PIXEL_STATE_BYTES, check_pixel_state};
    use pm_render::progressive::{ProgressiveSettings, SppmSettings};
    use pm_render::{RenderError, RenderSettings};
    let settings = |side: u32| RenderSettings {
        width: side,
        height: side,
        ..RenderSettings::default()
    };
    // 6688² × 48 B is just under 2 GiB, 6689² just over.
    for (side, fits) in [(6688u32, true), (6689, false), (8192, false)] {
        let sppm = SppmSettings::new(settings(side), 1).validate();
        let progressive = ProgressiveSettings::new(settings(side), 1).validate();
        for result in [sppm, progressive] {
            assert_eq!(result.is_ok(), fits, "{side}: {result:?}");
            if !fits {
                assert!(matches!(result, Err(RenderError::PixelStateTooLarge { .. })));
            }
        }
    }
    assert!(
        check_pixel_state(1 << 13, 1 << 13, 12).is_ok(),
        "the film at the pixel limit fits"
    );
    assert_eq!(MAX_PIXEL_STATE_BYTES, 1 << 31);
    assert!(matches!(
        PassSums::new(8192, 8192),
        Err(RenderError::PixelStateTooLarge { .. })
    ));
}
