//! Memory per triangle, counted: a global allocator that tracks the bytes live on the heap
//! shows what a built scene holds (mesh, triangles, BVH, per-part tables) per triangle, on a
//! tessellated room (coplanar quads) and on a sphere of triangles (nothing coplanar), and the
//! peak while building. `Scene::heap_bytes` must agree with the count.

use photon_maps::trace::glam::Vec3;
use photon_maps::trace::scenes::scale::split_rooms;
use photon_maps::trace::{PointLight, Scene, Surface};

#[path = "support/tracking_allocator.rs"]
mod tracking_allocator;

/// A UV sphere of `stacks × 2·stacks` cells, each two triangles: no two faces coplanar.
fn sphere_mesh(stacks: u32) -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let slices = 2 * stacks;
    let mut positions = Vec::new();
    for i in 0..=stacks {
        let theta = std::f32::consts::PI * i as f32 / stacks as f32;
        for j in 0..slices {
            let phi = std::f32::consts::TAU * j as f32 / slices as f32;
            positions.push(Vec3::new(
                theta.sin() * phi.cos(),
                theta.cos(),
                theta.sin() * phi.sin(),
            ));
        }
    }
    let mut faces = Vec::new();
    for i in 0..stacks {
        for j in 0..slices {
            let v = |a: u32, b: u32| a * slices + b % slices;
            let (a, b, c, d) = (v(i, j), v(i, j + 1), v(i + 1, j + 1), v(i + 1, j));
            // The poles' degenerate halves are dropped by the mesh builder.
            faces.push([a, c, b]);
            faces.push([a, d, c]);
        }
    }
    (positions, faces)
}

/// (live bytes per triangle after building, peak bytes per triangle while building, and
/// the scene's own report per triangle), for a scene made by `make`.
fn measure(make: impl FnOnce() -> Scene) -> (f64, f64, f64, usize) {
    let base = tracking_allocator::reset_peak();
    let scene = make();
    let live = tracking_allocator::live() - base;
    let peak = tracking_allocator::peak() - base;
    let triangles: usize = scene
        .meshes()
        .iter()
        .map(|m| {
            let mesh = m.half_edge_mesh();
            mesh.faces()
                .map(|f| mesh.face_vertices(f).len() - 2)
                .sum::<usize>()
        })
        .sum();
    let per = |bytes: usize| bytes as f64 / triangles as f64;
    (per(live), per(peak), per(scene.heap_bytes()), triangles)
}

#[test]
fn a_built_scene_holds_at_most_100_bytes_per_triangle() {
    let (sphere_positions, sphere_faces) = sphere_mesh(100);
    let rooms = measure(|| split_rooms(40).expect("scene"));
    // The top of the range: a million triangles.
    let million = measure(|| split_rooms(205).expect("scene"));
    let sphere = measure(|| {
        Scene::builder()
            .mesh(
                &sphere_positions,
                &sphere_faces,
                Surface::diffuse(Vec3::splat(0.5)),
            )
            .light(PointLight::new(Vec3::ZERO, Vec3::ONE))
            .build()
            .expect("scene")
    });
    for (name, (live, peak, reported, triangles)) in [
        ("split-rooms-40", rooms),
        ("split-rooms-205", million),
        ("sphere", sphere),
    ] {
        eprintln!(
            "{name}: {triangles} triangles, {live:.1} B/triangle live, {peak:.1} at the peak, reported {reported:.1}"
        );
        assert!(triangles > 35_000, "{name}: {triangles}");
        assert!(live <= 100.0, "{name}: {live:.1} bytes per triangle");
        // The scene's own report counts everything but a few small fixed-size values.
        assert!(
            (reported - live).abs() <= 0.02 * live,
            "{name}: reported {reported:.1}, counted {live:.1}"
        );
        // Building needs more (the binary BVH and its conversion), but within a bound.
        assert!(peak <= 400.0, "{name}: peak {peak:.1} bytes per triangle");
    }
}
