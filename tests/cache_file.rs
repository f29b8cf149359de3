//! The persistent photon cache (issue 36 item 1): a render from a loaded cache file is
//! bit-identical to the render that built it, in every mode that reads photons; a cache for
//! another scene or other settings is refused by name; and thousands of mutated or truncated
//! files (seeded) never panic, always give an error or a valid cache, and allocate bounded.

#[path = "support/tracking_allocator.rs"]
mod tracking_allocator;

use photon_maps::render::cache_file::{
    CacheFileError, HEADER_BYTES, load_cache, payload_checksum, save_cache,
};
use photon_maps::render::glam::{Vec2, Vec3};
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, RenderStats, Renderer};
use photon_maps::trace::{Camera, CreaseAngle, Partitioned, Partitioner, PointLight, Scene, Surface, scenes};

/// A closed box with a glass ball in it, lit by a point light: photons of every kind
/// (direct, indirect and caustic, so the caustic trees are exercised).
fn glass_box() -> Scene {
    glass_box_with(60.0, 0.35)
}

/// The glass box with a light of `power` watts and a ball of `radius`.
fn glass_box_with(power: f32, radius: f32) -> Scene {
    let p = [
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(1.0, 0.0, -1.0),
        Vec3::new(1.0, 2.0, -1.0),
        Vec3::new(-1.0, 2.0, -1.0),
        Vec3::new(-1.0, 0.0, 1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(1.0, 2.0, 1.0),
        Vec3::new(-1.0, 2.0, 1.0),
    ];
    // Inward-facing quads.
    let faces = [
        [0u32, 1, 2, 3],
        [5, 4, 7, 6],
        [4, 0, 3, 7],
        [1, 5, 6, 2],
        [4, 5, 1, 0],
        [3, 2, 6, 7],
    ];
    Scene::builder()
        .mesh(&p, &faces, Surface::diffuse(Vec3::new(0.7, 0.6, 0.5)))
        .sphere(Vec3::new(0.0, 0.5, 0.0), radius, Surface::glass(1.5))
        .light(PointLight::new(Vec3::new(0.2, 1.7, 0.1), Vec3::splat(power)))
        .camera(Camera::new(Vec3::new(0.0, 1.0, 0.95), Vec3::NEG_Z, Vec3::Y, 1.2))
        .build()
        .unwrap()
}

/// The tests of this file run one at a time: the allocation bound reads a global counter.
static ONE_AT_A_TIME: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn settings(mode: Mode) -> RenderSettings {
    RenderSettings {
        width: 32,
        height: 32,
        samples_per_pixel: 1,
        photons: 20_000,
        mode,
        seed: 5,
        ..RenderSettings::default()
    }
}

fn bits(image: &Image) -> Vec<u32> {
    image
        .pixels()
        .iter()
        .flat_map(|p| p.to_array().map(f32::to_bits))
        .collect()
}

/// The bytes of the cache `renderer` builds for `partitioned`, and the image it renders.
fn saved(renderer: &Renderer<EstimatorKind>, partitioned: &Partitioned) -> (Vec<u8>, Image) {
    let cache = renderer
        .build_photon_cache(partitioned, &(), &mut RenderStats::default())
        .unwrap();
    let mut bytes = Vec::new();
    save_cache(&mut bytes, renderer, partitioned, &cache).unwrap();
    let image = renderer
        .render_from_cache(partitioned.scene(), &cache, &(), &mut RenderStats::default())
        .unwrap();
    (bytes, image)
}

#[test]
fn loaded_cache_renders_the_bits_of_the_render_that_built_it() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let partitioned = CreaseAngle::default().partition(glass_box()).unwrap();
    for (mode, kind) in [
        (Mode::PhotonMap, EstimatorKind::Disc),
        (Mode::PhotonMap, EstimatorKind::GeometryCube),
        (Mode::PhotonMap, EstimatorKind::GeometryBall),
        (Mode::ShadowRays, EstimatorKind::GeometryCube),
        (Mode::FinalGather, EstimatorKind::GeometryCube),
        (Mode::FinalGather, EstimatorKind::Disc),
    ] {
        let renderer = Renderer::new(kind, settings(mode));
        // The one-shot render (trace, build, render) is the reference.
        let reference = renderer.render(&partitioned, &()).unwrap().image;
        let (bytes, built) = saved(&renderer, &partitioned);
        assert_eq!(bits(&reference), bits(&built), "{mode} {kind}: built cache");
        let loaded = load_cache(&bytes[..], &renderer, &partitioned).unwrap();
        if mode == Mode::FinalGather {
            assert!(loaded.radiance.as_ref().is_some_and(|c| !c.is_empty()));
            let caustic = (0..loaded.maps.len() as u32)
                .filter_map(|m| loaded.radiance.as_ref().unwrap().caustic_tree(m))
                .count();
            assert!(caustic > 0, "the scene stores caustic photons");
        }
        let image = renderer
            .render_from_cache(partitioned.scene(), &loaded, &(), &mut RenderStats::default())
            .unwrap();
        assert!(image.mean().x > 0.0);
        assert_eq!(bits(&reference), bits(&image), "{mode} {kind}: loaded cache");
    }
}

#[test]
fn cache_for_another_scene_or_other_settings_is_refused_by_name() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let partitioned = CreaseAngle::default().partition(glass_box()).unwrap();
    let renderer = Renderer::new(EstimatorKind::GeometryCube, settings(Mode::FinalGather));
    let (bytes, _) = saved(&renderer, &partitioned);
    let refused = |renderer: &Renderer<EstimatorKind>, partitioned: &Partitioned| match load_cache(
        &bytes[..],
        renderer,
        partitioned,
    ) {
        Err(CacheFileError::IdentityMismatch { key, file, run }) => (key, file, run),
        other => panic!("expected an identity mismatch, got {other:?}"),
    };
    let with = |f: &dyn Fn(&mut RenderSettings)| {
        let mut s = settings(Mode::FinalGather);
        f(&mut s);
        Renderer::new(EstimatorKind::GeometryCube, s)
    };
    assert_eq!(
        refused(&with(&|s| s.photons = 20_001), &partitioned),
        ("photons".into(), "20000".into(), "20001".into())
    );
    assert_eq!(refused(&with(&|s| s.seed = 6), &partitioned).0, "seed");
    assert_eq!(refused(&with(&|s| s.k = 50), &partitioned).0, "k");
    assert_eq!(
        refused(&with(&|s| s.final_gather.cache_every = 8), &partitioned).0,
        "cache_every"
    );
    assert_eq!(
        refused(&with(&|s| s.max_distance = Some(0.3)), &partitioned).0,
        "max_distance"
    );
    assert_eq!(
        refused(&with(&|s| s.mode = Mode::PhotonMap), &partitioned).0,
        "radiance_cache"
    );
    let disc = Renderer::new(EstimatorKind::Disc, settings(Mode::FinalGather));
    assert_eq!(refused(&disc, &partitioned).0, "estimator");
    // The camera, size and samples are not part of it: one cache renders any view.
    let other_view = with(&|s| {
        s.width = 20;
        s.samples_per_pixel = 2;
    });
    let moved = glass_box()
        .with_camera(Camera::new(Vec3::new(0.5, 1.0, 0.9), Vec3::NEG_Z, Vec3::Y, 1.0))
        .unwrap();
    let moved = CreaseAngle::default().partition(moved).unwrap();
    assert!(load_cache(&bytes[..], &other_view, &moved).is_ok());
    // Another scene: another partition, other geometry, another light.
    let cornell = CreaseAngle::default()
        .partition(scenes::build("cornell-box").unwrap())
        .unwrap();
    let key = refused(&renderer, &cornell).0;
    assert!(["parts", "maps", "assignment"].contains(&key.as_str()), "{key}");
    let relit = CreaseAngle::default()
        .partition(glass_box_with(61.0, 0.35))
        .unwrap();
    assert_eq!(refused(&renderer, &relit).0, "lights");
    let reshaped = CreaseAngle::default()
        .partition(glass_box_with(60.0, 0.36))
        .unwrap();
    assert_eq!(refused(&renderer, &reshaped).0, "geometry");
    // The same geometry with a texture: refused for the untextured box, and for the same
    // texture with one texel changed.
    let textured = |texel: u8| {
        let partitioned = CreaseAngle::default().partition(textured_floor(texel)).unwrap();
        let renderer = Renderer::new(EstimatorKind::GeometryCube, settings(Mode::PhotonMap));
        (renderer, partitioned)
    };
    let (renderer, partitioned) = textured(200);
    let (bytes, _) = saved(&renderer, &partitioned);
    assert!(load_cache(&bytes[..], &renderer, &partitioned).is_ok());
    let (other_renderer, retextured) = textured(201);
    match load_cache(&bytes[..], &other_renderer, &retextured) {
        Err(CacheFileError::IdentityMismatch { key, .. }) => assert_eq!(key, "appearance"),
        other => panic!("expected an appearance mismatch, got {other:?}"),
    }
}

/// A lit square floor with a 2×2 base-colour texture whose first texel is `texel` (grey).
fn textured_floor(texel: u8) -> Scene {
    use photon_maps::trace::{Sampler, Texture, VertexAttributes};
    use std::sync::Arc;
    let p = [
        Vec3::new(-1.0, 0.0, -1.0),
        Vec3::new(1.0, 0.0, -1.0),
        Vec3::new(1.0, 0.0, 1.0),
        Vec3::new(-1.0, 0.0, 1.0),
    ];
    let texels = vec![[texel; 3], [90; 3], [90; 3], [160; 3]];
    let attributes = VertexAttributes {
        uvs: Some(vec![
            Vec2::new(0.0, 0.0),
            Vec2::new(1.0, 0.0),
            Vec2::new(1.0, 1.0),
            Vec2::new(0.0, 1.0),
        ]),
        base_color_texture: Some((
            Arc::new(Texture::from_srgb8(2, 2, texels).unwrap()),
            Sampler::default(),
        )),
        ..VertexAttributes::default()
    };
    Scene::builder()
        .attributed_mesh(
            &p,
            &[[0, 2, 1], [0, 3, 2]],
            Surface::diffuse(Vec3::splat(0.8)),
            attributes,
        )
        .light(PointLight::new(Vec3::new(0.0, 1.0, 0.0), Vec3::splat(20.0)))
        .camera(Camera::new(Vec3::new(0.0, 1.5, 0.5), Vec3::NEG_Y, Vec3::Z, 1.2))
        .build()
        .unwrap()
}

/// A small generator (SplitMix64), seeded: the mutations are the same every run.
struct Mix(u64);

impl Mix {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

/// One mutation of `bytes`: a byte flip, a truncation, a length field set huge, bytes
/// inserted or removed; half of them re-sealed (the header's length and checksum rewritten
/// to match), so that the parser behind the checksum meets hostile structure too.
fn mutate(bytes: &[u8], rng: &mut Mix) -> Vec<u8> {
    let mut out = bytes.to_vec();
    let at = |rng: &mut Mix, len: usize| rng.below(len);
    match rng.below(6) {
        0 => {
            let i = at(rng, out.len());
            out[i] ^= 1 << rng.below(8);
        }
        1 => out.truncate(at(rng, out.len())),
        2 => {
            // A count field (u32 or u64) somewhere set huge.
            let i = at(rng, out.len().saturating_sub(8));
            let huge = [u64::MAX, u64::from(u32::MAX), 1 << 40, (out.len() as u64) / 19];
            out[i..i + 8].copy_from_slice(&huge[rng.below(4)].to_le_bytes());
        }
        3 => {
            let i = at(rng, out.len());
            for _ in 0..1 + rng.below(9) {
                out.insert(i, rng.next() as u8);
            }
        }
        4 => {
            let i = at(rng, out.len());
            let n = (1 + rng.below(9)).min(out.len() - i);
            out.drain(i..i + n);
        }
        _ => {
            for _ in 0..1 + rng.below(4) {
                let i = at(rng, out.len());
                out[i] = rng.next() as u8;
            }
        }
    }
    if rng.below(2) == 0 && out.len() >= HEADER_BYTES {
        let payload_len = (out.len() - HEADER_BYTES) as u64;
        let checksum = payload_checksum(&out[HEADER_BYTES..]);
        out[12..20].copy_from_slice(&payload_len.to_le_bytes());
        out[20..28].copy_from_slice(&checksum.to_le_bytes());
    }
    out
}

#[test]
fn mutated_cache_files_are_refused_without_panic_or_unbounded_allocation() {
    let _one = ONE_AT_A_TIME.lock().unwrap_or_else(|e| e.into_inner());
    let partitioned = CreaseAngle::default().partition(glass_box()).unwrap();
    let renderer = Renderer::new(
        EstimatorKind::GeometryCube,
        RenderSettings {
            photons: 1_500,
            ..settings(Mode::FinalGather)
        },
    );
    let (bytes, _) = saved(&renderer, &partitioned);
    // What a valid load allocates beyond its file: the maps' polygons (from the scene) and
    // the caustic trees; a mutated file may add at most a small multiple of its own size.
    let base = tracking_allocator::reset_peak();
    load_cache(&bytes[..], &renderer, &partitioned).unwrap();
    let valid_peak = tracking_allocator::peak() - base;
    let mut rng = Mix(0x36_0001);
    let (mut refused, mut loaded) = (0, 0);
    for case in 0..3_000 {
        let mutated = mutate(&bytes, &mut rng);
        let base = tracking_allocator::reset_peak();
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            load_cache(&mutated[..], &renderer, &partitioned)
        }));
        let peak = tracking_allocator::peak() - base;
        let result = result.unwrap_or_else(|_| panic!("case {case}: load panicked"));
        assert!(
            peak <= valid_peak + 4 * mutated.len() + 4096,
            "case {case}: {peak} bytes allocated for a file of {} (a valid load: {valid_peak})",
            mutated.len()
        );
        match result {
            Ok(cache) => {
                cache.maps.validate().unwrap();
                loaded += 1;
            }
            Err(e) => {
                assert!(!e.to_string().is_empty());
                refused += 1;
            }
        }
    }
    assert!(refused > 2_000, "{refused} refused, {loaded} loaded");
}
