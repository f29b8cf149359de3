//! How cost grows with the work: times per phase and peak heap memory as the triangle count
//! grows (the rooms with every face split N × N, 24 → 240k triangles; a field of separate
//! cubes) and as the photon count grows (the Cornell box, 10⁴ → 10⁷ photons). Prints markdown
//! tables (the "How cost grows" section of `docs/results.md` is this output).
//!
//! `cargo run --release --example scale` (about a minute on 2 cores; `--quick` for a smaller
//! sweep).

use photon_maps::render::{EstimatorKind, Mode, RenderSettings, Renderer};
use photon_maps::trace::{CreaseAngle, Scene, scenes};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering::Relaxed};
use std::time::Instant;

/// The system allocator, keeping the bytes live and their peak.
struct Tracking;

static LIVE: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

fn grow(bytes: usize) {
    let live = LIVE.fetch_add(bytes, Relaxed) + bytes;
    PEAK.fetch_max(live, Relaxed);
}

// SAFETY: every call is forwarded unchanged to the system allocator; the counters are atomics
// and never allocate.
unsafe impl GlobalAlloc for Tracking {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        grow(layout.size());
        // SAFETY: the caller's contract is passed on as is.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        grow(layout.size());
        // SAFETY: as above.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size >= layout.size() {
            grow(new_size - layout.size());
        } else {
            LIVE.fetch_sub(layout.size() - new_size, Relaxed);
        }
        // SAFETY: as above.
        unsafe { System.realloc(ptr, layout, new_size) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        LIVE.fetch_sub(layout.size(), Relaxed);
        // SAFETY: as above.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static ALLOCATOR: Tracking = Tracking;

/// Starts a peak measurement; returns the bytes live now.
fn reset_peak() -> usize {
    let live = LIVE.load(Relaxed);
    PEAK.store(live, Relaxed);
    live
}

fn mib(bytes: usize) -> f64 {
    bytes as f64 / (1024.0 * 1024.0)
}

/// One row of the triangle sweep.
fn triangle_row(name: &str) -> Result<String, String> {
    let base = reset_peak();
    let start = Instant::now();
    let scene = scenes::build(name).map_err(|e| e.to_string())?;
    let build_scene = start.elapsed().as_secs_f64();
    let scene_peak = PEAK.load(Relaxed) - base;
    let triangles = triangle_count(&scene);
    let scene_bytes = scene.heap_bytes();
    let settings = RenderSettings {
        width: 128,
        height: 128,
        photons: 1_000_000,
        ..RenderSettings::default()
    };
    reset_peak();
    let cube = Renderer::new(EstimatorKind::GeometryCube, settings)
        .render(&scene, &CreaseAngle::default(), &())
        .map_err(|e| e.to_string())?;
    let render_peak = PEAK.load(Relaxed) - base;
    let disc = Renderer::new(EstimatorKind::Disc, settings)
        .render(&scene, &CreaseAngle::default(), &())
        .map_err(|e| e.to_string())?;
    let path_traced = Renderer::new(
        EstimatorKind::Disc,
        RenderSettings {
            mode: Mode::PathTrace,
            samples_per_pixel: 16,
            ..settings
        },
    )
    .render(&scene, &CreaseAngle::default(), &())
    .map_err(|e| e.to_string())?;
    let s = &cube.stats;
    Ok(format!(
        "| {name} | {triangles} | {build_scene:.3} | {:.0} | {:.2} | {:.3} | {:.3} | {:.3} | {:.2} | {:.3} | {:.1} | {:.1} |",
        scene_bytes as f64 / triangles as f64,
        s.photons_emitted as f64 / s.trace.as_secs_f64() / 1e6,
        s.trace.as_secs_f64(),
        s.build.as_secs_f64(),
        s.render.as_secs_f64(),
        s.render.as_secs_f64() / disc.stats.render.as_secs_f64(),
        path_traced.stats.render.as_secs_f64(),
        mib(scene_peak),
        mib(render_peak),
    ))
}

/// One row of the photon sweep.
fn photon_row(photons: u32) -> Result<String, String> {
    let scene = scenes::build("cornell-box").map_err(|e| e.to_string())?;
    let settings = RenderSettings {
        width: 128,
        height: 128,
        photons,
        ..RenderSettings::default()
    };
    let base = reset_peak();
    let out = Renderer::new(EstimatorKind::GeometryCube, settings)
        .render(&scene, &CreaseAngle::default(), &())
        .map_err(|e| e.to_string())?;
    let peak = PEAK.load(Relaxed) - base;
    let s = &out.stats;
    let mean = out.image.mean();
    Ok(format!(
        "| {photons} | {} | {:.3} | {:.2} | {:.3} | {:.3} | {:.1} | {:.0} | ({:.4}, {:.4}, {:.4}) | {} |",
        s.photons_stored,
        s.trace.as_secs_f64(),
        s.photons_emitted as f64 / s.trace.as_secs_f64() / 1e6,
        s.build.as_secs_f64(),
        s.render.as_secs_f64(),
        mib(peak),
        peak as f64 / s.photons_stored.max(1) as f64,
        mean.x,
        mean.y,
        mean.z,
        s.photon_channels_below_range,
    ))
}

fn triangle_count(scene: &Scene) -> usize {
    scene
        .meshes()
        .iter()
        .map(|m| {
            let mesh = m.half_edge_mesh();
            mesh.faces()
                .map(|f| mesh.face_vertices(f).len() - 2)
                .sum::<usize>()
        })
        .sum()
}

fn main() -> Result<(), String> {
    let quick = std::env::args().any(|a| a == "--quick");
    let threads = rayon::current_num_threads();
    println!("Measured with `cargo run --release --example scale` on {threads} threads.\n");
    println!(
        "Triangles: crease maps, 1,000,000 photons, 128×128. Scene bytes are what the built scene holds \
         (`Scene::heap_bytes`); peaks are heap bytes at the highest point while building the scene, \
         and while tracing, building maps and rendering with the cube estimator. \
         Path traced: 16 samples per pixel, render phase.\n"
    );
    println!(
        "| scene | triangles | scene build s | scene B/triangle | trace M paths/s | trace s | map build s | cube render s | cube / disc render | path-traced render s | scene peak MiB | render peak MiB |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|---|---|");
    let splits: &[u32] = if quick { &[1, 10, 30] } else { &[1, 10, 30, 100] };
    for n in splits {
        println!("{}", triangle_row(&format!("split-rooms-{n}"))?);
    }
    let cubes: &[u32] = if quick { &[1_000] } else { &[1_000, 10_000] };
    for n in cubes {
        println!("{}", triangle_row(&format!("cube-field-{n}"))?);
    }
    println!(
        "\nPhotons: the Cornell box, crease maps, cube estimator (k = 100), 128×128. The peak is \
         the heap's highest point during the render (photons traced in full precision, then \
         encoded into the maps); per stored photon.\n"
    );
    println!(
        "| photons | stored | trace s | trace M paths/s | map build s | render s | peak MiB | peak B/stored photon | mean RGB | channels below range |"
    );
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let counts: &[u32] = if quick {
        &[10_000, 100_000, 1_000_000]
    } else {
        &[10_000, 100_000, 1_000_000, 10_000_000]
    };
    for &n in counts {
        println!("{}", photon_row(n)?);
    }
    Ok(())
}
