//! The path tracer reads no photon map, so no partition may change the scene it sees: the
//! render example's path-trace mode renders a scene of piercing solids as given, bit for bit
//! the library's path tracer on the unsplit scene, although the example's default partition
//! (contact) would split it; and the split scene itself path traces to the same bits, since
//! its rays meet the faces as given.

#[path = "support/example.rs"]
mod example;
#[path = "support/scratch.rs"]
mod scratch;

use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings, Renderer};
use photon_maps::trace::{Contact, Partitioner, SingleMap, scenes};

#[test]
fn the_path_tracer_sees_the_scene_as_given() {
    let dir = scratch::Scratch::new("path-trace-unsplit");
    let out = dir.path("pt.exr");
    let args = [
        "--mode",
        "path-trace",
        "--scene",
        "solid-rooms-pierce",
        "--size",
        "24x12",
        "--spp",
        "2",
        "--out",
        &out,
    ];
    let Some(output) = example::run(&args) else { return };
    example::assert_ok(&args, &output);
    let by_cli = Image::read_exr(&out).unwrap();

    let scene = scenes::build("solid-rooms-pierce").unwrap();
    let settings = RenderSettings {
        width: 24,
        height: 12,
        samples_per_pixel: 2,
        mode: Mode::PathTrace,
        ..RenderSettings::default()
    };
    let render = |partitioned| {
        Renderer::new(EstimatorKind::GeometryCube, settings)
            .render(&partitioned, &())
            .unwrap()
            .image
    };
    let as_given = render(SingleMap.partition(scene.clone()).unwrap());
    assert_eq!(
        by_cli.pixels(),
        as_given.pixels(),
        "the example path-traced another scene"
    );
    // The contact split does re-mesh this scene, but its rays meet the faces as given (the
    // split decides maps, never visibility): even the split scene path traces to the same
    // bits (its lamp is a point light, so light sampling does not see the re-meshing either).
    let split = Contact::default().partition(scene.clone()).unwrap();
    assert_ne!(split.scene().part_count(), scene.part_count());
    assert_eq!(
        render(split).pixels(),
        as_given.pixels(),
        "the split scene's rays met the pieces, not the faces as given"
    );
}
