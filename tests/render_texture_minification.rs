//! Textures seen from afar: a floor tiled with a fine black-and-white checkerboard (about 20
//! texels to a pixel) under a straight-down directional light of irradiance π, seen straight
//! down. Each pixel's true value is the checkerboard's mean over its footprint, 0.5 (linear)
//! to within a texel's share. Point lookups (the path tracer, one sample a pixel) alias into
//! a pattern of grey levels (bilinear between black and white texels: rms 1/6 about
//! the mean); ShadowRays averages the texture over the pixel's footprint through
//! the mip chain, so every pixel is close to 0.5.

use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::Partitioner;
use photon_maps::trace::glam::{Vec2, Vec3};
use photon_maps::trace::{
    Camera, DirectionalLight, Sampler, Scene, SingleMap, Surface, Texture, VertexAttributes,
};
use std::f32::consts::PI;
use std::sync::Arc;

fn scene() -> Scene {
    // 8×8 texels of alternating white and black, repeated 64 times per metre: 512 texels/m.
    let texels = (0..64u32)
        .map(|i| {
            if (i % 8 + i / 8).is_multiple_of(2) {
                [255; 3]
            } else {
                [0; 3]
            }
        })
        .collect();
    let texture = Arc::new(Texture::from_srgb8(8, 8, texels).unwrap());
    let floor = [
        Vec3::new(-4.0, 0.0, -4.0),
        Vec3::new(-4.0, 0.0, 4.0),
        Vec3::new(4.0, 0.0, 4.0),
        Vec3::new(4.0, 0.0, -4.0),
    ];
    let uvs = floor.iter().map(|p| Vec2::new(p.x, p.z) * 64.0).collect();
    // 2 m above the floor, 2 m wide view in 48 pixels: 4.2 cm a pixel, about 21 texels.
    let vfov = 2.0 * 0.5f32.atan();
    Scene::builder()
        .attributed_mesh(
            &floor,
            &[[0, 1, 2], [0, 2, 3]],
            Surface::diffuse(Vec3::ONE),
            VertexAttributes {
                uvs: Some(uvs),
                base_color_texture: Some((texture, Sampler::default())),
                ..VertexAttributes::default()
            },
        )
        .light(DirectionalLight::new(Vec3::NEG_Y, Vec3::splat(PI)))
        .camera(Camera::new(
            Vec3::new(0.1, 2.0, 0.05),
            Vec3::new(0.1, 0.0, 0.05),
            Vec3::Z,
            vfov,
        ))
        .build()
        .unwrap()
}

fn render(scene: &Scene, mode: Mode) -> Image {
    let settings = RenderSettings {
        width: 48,
        height: 48,
        photons: 1000,
        mode,
        seed: 4,
        ..RenderSettings::default()
    };
    Renderer::new(EstimatorKind::Disc, settings)
        .render(&SingleMap.partition(scene.clone()).unwrap(), &())
        .unwrap()
        .image
}

/// Mean and root-mean-square deviation from 0.5 of the pixels' red channel.
fn stats(image: &Image) -> (f32, f32) {
    let n = image.pixels().len() as f32;
    let mean = image.pixels().iter().map(|p| p.x).sum::<f32>() / n;
    let rms = (image.pixels().iter().map(|p| (p.x - 0.5).powi(2)).sum::<f32>() / n).sqrt();
    (mean, rms)
}

#[test]
fn distant_checkerboard_pixels_are_its_mean_not_aliases() {
    let scene = scene();
    // Radiance = albedo · E / π = albedo (no other surface: nothing but direct light).
    let (point_mean, point_rms) = stats(&render(&scene, Mode::PathTrace));
    let (filtered_mean, filtered_rms) = stats(&render(&scene, Mode::ShadowRays));
    println!(
        "pixels' deviation from the footprint mean 0.5: point lookups rms {point_rms:.3} (mean {point_mean:.3}), footprint-filtered rms {filtered_rms:.4} (mean {filtered_mean:.4})"
    );
    assert!(
        point_rms > 0.1,
        "the scene must alias without filtering ({point_rms})"
    );
    assert!(filtered_rms < 0.03, "filtered pixels deviate by {filtered_rms}");
    assert!(
        (filtered_mean - 0.5).abs() < 0.01,
        "filtered mean {filtered_mean}"
    );
}
