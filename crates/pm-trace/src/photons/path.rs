//! Photon paths: one path from its light to its end (`PhotonPath`), and a chunk of paths
//! traced one at a time or, in large scenes, two at a time with their rays cast together.

use super::guide::EmissionGuide;
use super::light_picker::LightPicker;
use super::options::{NEAR_LIGHT_DISTANCE, TraceOptions};
use crate::bsdf::Bsdf;
use crate::bsdf::near_specular::passes_through;
use crate::partition::assignment::MapAssignment;
use crate::ray::Ray;
use crate::rng::Rng;
use crate::scene::{Hit, RayKind, Scene};
use glam::Vec3;
use pm_kdtree::{Photon, PhotonKind};

/// Traces paths `begin..end` into `out`, in path order; with a `guide`, a path its bin drops
/// at the light stores nothing and casts no ray.
///
/// `paired` (chosen by [`Scene::prefers_ray_pairs`]: scenes large enough for memory to
/// dominate) keeps two paths in flight and casts their rays together with
/// [`Scene::intersect_pair`]; when one ends, the next path takes its place at once. Photons of
/// a path that ends before an older one are held back until the older one has ended, so the
/// order (and every photon) is what one path at a time gives.
#[allow(clippy::too_many_arguments)] // the chunk's inputs, then its two outputs
pub(super) fn trace_paths(
    scene: &Scene,
    assignment: &MapAssignment,
    options: &TraceOptions,
    picker: &LightPicker,
    guide: Option<&EmissionGuide>,
    (begin, end): (u32, u32),
    paired: bool,
    out: &mut Vec<(u32, Photon)>,
    near: &mut NearLight,
) {
    if !paired {
        for path in begin..end {
            let mut p = PhotonPath::start(scene, options, picker, guide, path);
            p.run_to_end(scene, assignment, out);
            near.add(&p);
        }
        return;
    }
    /// A path in flight and the photons it has stored so far.
    struct Slot {
        path: PhotonPath,
        index: u32,
        photons: Vec<(u32, Photon)>,
    }
    let mut next = begin;
    // The next path not dropped at its light (a dropped one stores nothing: skipping it keeps
    // the order of every photon).
    let mut start = |photons: Vec<(u32, Photon)>| {
        while next < end {
            next += 1;
            let path = PhotonPath::start(scene, options, picker, guide, next - 1);
            if path.is_live() {
                return Some(Slot {
                    path,
                    index: next - 1,
                    photons,
                });
            }
        }
        None
    };
    let mut slots = [start(Vec::new()), start(Vec::new())];
    // Photons of ended paths newer than the oldest path in flight, in path order.
    let mut waiting = Vec::new();
    loop {
        match &mut slots {
            [Some(a), Some(b)] => {
                let [hit_a, hit_b] = scene.intersect_pair_from(
                    [&a.path.ray, &b.path.ray],
                    [a.path.from.as_ref(), b.path.from.as_ref()],
                    f32::INFINITY,
                );
                a.path.interact(scene, assignment, hit_a, &mut a.photons);
                b.path.interact(scene, assignment, hit_b, &mut b.photons);
            }
            [Some(s), None] | [None, Some(s)] => {
                let hit = match &s.path.from {
                    Some(from) => scene.intersect_from(from, &s.path.ray, f32::INFINITY, RayKind::Other),
                    None => scene.intersect(&s.path.ray, f32::INFINITY, RayKind::Other),
                };
                s.path.interact(scene, assignment, hit, &mut s.photons);
            }
            [None, None] => break,
        }
        for k in 0..2 {
            if slots[k].as_ref().is_none_or(|s| s.path.is_live()) {
                continue;
            }
            let ended = slots[k].take().expect("checked above");
            near.add(&ended.path);
            let mut photons = ended.photons;
            if slots[1 - k].as_ref().is_some_and(|o| o.index < ended.index) {
                waiting.append(&mut photons);
            } else {
                out.append(&mut photons);
                out.append(&mut waiting);
            }
            slots[k] = start(photons);
        }
    }
}

/// Traces pilot path `path` of `options` (uniform emission) to its end, storing its photons
/// in `out`; returns its light and the ray it left that light along.
pub(super) fn pilot_path(
    scene: &Scene,
    assignment: &MapAssignment,
    options: &TraceOptions,
    picker: &LightPicker,
    path: u32,
    out: &mut Vec<(u32, Photon)>,
) -> (usize, Ray) {
    let mut p = PhotonPath::start(scene, options, picker, None, path);
    let left = (
        p.light,
        Ray {
            origin: p.emitted_at,
            direction: p.emitted_dir,
        },
    );
    p.run_to_end(scene, assignment, out);
    left
}

/// The power emitted by a chunk's paths and the part of it whose first hit lay on a surface
/// within [`NEAR_LIGHT_DISTANCE`] of its light (summed over channels).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct NearLight {
    pub(super) emitted: f64,
    pub(super) near: f64,
    /// Paths traced on (not dropped at their light by a guide).
    pub(super) traced: u64,
}

impl NearLight {
    fn add(&mut self, path: &PhotonPath) {
        self.emitted += f64::from(path.emitted);
        self.near += f64::from(path.near_light);
        self.traced += u64::from(!path.dropped);
    }
}

/// One photon path in flight: emitted from a light, then carried from surface to surface
/// until it is absorbed, leaves the scene or reaches `max_bounces` interactions.
struct PhotonPath {
    rng: Rng,
    /// The light it left, and the direction it left along.
    light: usize,
    emitted_dir: Vec3,
    /// True when a guide dropped it at its light (it casts no ray).
    dropped: bool,
    power: Vec3,
    /// The power it started with, summed over channels.
    emitted: f32,
    /// `emitted` when its first hit lay on a surface whose plane passes within
    /// [`NEAR_LIGHT_DISTANCE`] of where it left the light, else 0.
    near_light: f32,
    /// Where it left its light (the first ray starts a step further).
    emitted_at: Vec3,
    /// True until the first ray's hit has been handled.
    first_ray: bool,
    /// The ray to cast next, and the surface point it leaves (none for the first).
    ray: Ray,
    from: Option<Hit>,
    diffuse_bounces: u32,
    specular: bool,
    /// Interactions left before the cut-off; zero once the path has ended.
    bounces_left: u32,
}

impl PhotonPath {
    /// Path `path` of the run, emitted from a light picked in proportion to its power; with a
    /// `guide`, traced on with its bin's keep probability `P` (one more draw from the path's
    /// stream when `P < 1`) and then carrying `1 / P` times the power, or ended at once.
    #[inline]
    fn start(
        scene: &Scene,
        options: &TraceOptions,
        picker: &LightPicker,
        guide: Option<&EmissionGuide>,
        path: u32,
    ) -> Self {
        let mut rng = Rng::for_pass(options.seed, options.pass, path as u64);
        let (li, photon_power) = picker.pick(&mut rng);
        let emitted = scene.lights()[li].emit(&mut rng);
        let mut power = photon_power * emitted.weight;
        let mut bounces_left = options.max_bounces;
        let mut dropped = false;
        if let Some(guide) = guide {
            let keep = guide.keep(li, &emitted.ray);
            if keep < 1.0 {
                if rng.next_f32() < keep {
                    power /= keep;
                } else {
                    power = Vec3::ZERO;
                    bounces_left = 0;
                    dropped = true;
                }
            }
        }
        PhotonPath {
            light: li,
            emitted_dir: emitted.ray.direction,
            dropped,
            rng,
            power,
            emitted: power.element_sum(),
            near_light: 0.0,
            emitted_at: emitted.ray.origin,
            first_ray: true,
            // Step off the emitter's own surface (area lights start on their geometry).
            from: None,
            ray: Ray {
                origin: emitted.ray.at(scene.epsilon()),
                direction: emitted.ray.direction,
            },
            diffuse_bounces: 0,
            specular: false,
            bounces_left,
        }
    }

    #[inline]
    fn is_live(&self) -> bool {
        self.bounces_left > 0
    }

    /// Casts the path's rays one at a time until it ends, storing its photons in `out`.
    fn run_to_end(&mut self, scene: &Scene, assignment: &MapAssignment, out: &mut Vec<(u32, Photon)>) {
        while self.is_live() {
            let hit = match &self.from {
                Some(from) => scene.intersect_from(from, &self.ray, f32::INFINITY, RayKind::Other),
                None => scene.intersect(&self.ray, f32::INFINITY, RayKind::Other),
            };
            self.interact(scene, assignment, hit, out);
        }
    }

    /// What the path does at `hit`, the closest hit of its ray (`None`: it left the scene):
    /// a photon stored in `out` at a diffuse hit, then absorption or the next ray.
    #[inline]
    fn interact(
        &mut self,
        scene: &Scene,
        assignment: &MapAssignment,
        hit: Option<Hit>,
        out: &mut Vec<(u32, Photon)>,
    ) {
        let first = std::mem::replace(&mut self.first_ray, false);
        self.bounces_left -= 1;
        let Some(hit) = hit else {
            self.bounces_left = 0;
            return;
        };
        if first && (hit.position - self.emitted_at).dot(hit.normal).abs() <= NEAR_LIGHT_DISTANCE {
            // The first surface hit lies in a plane within 1 mm of the light: a light facing
            // into the wall or ceiling it sits on.
            self.near_light = self.emitted;
        }
        let material = scene.material(&hit);
        let wo = -self.ray.direction;
        // Where camera paths pass through (mirror, glass, near-specular metal), photon paths
        // bounce as off a mirror: no photon is stored there (none would be read), and the
        // light they carry on stays caustic, read at the next diffuse surface from the
        // caustic map as the camera would find it by sampling through.
        let direction = if !passes_through(material) {
            // Photons scatter about the geometric normal (no shading-normal adjoint to correct).
            let at = scene.shading_point_about(&hit, hit.normal, 0.0);
            let albedo = material.albedo(&at, wo);
            let kind = match (self.diffuse_bounces, self.specular) {
                (0, false) => PhotonKind::Direct,
                (0, true) => PhotonKind::Caustic,
                _ => PhotonKind::Indirect,
            };
            out.push((
                assignment.map_of(hit.part),
                Photon {
                    position: hit.position,
                    power: self.power,
                    direction: self.ray.direction,
                    kind,
                },
            ));
            // Russian roulette on the albedo: survive with q, then carry the sample's weight
            // over q (unbiased for any q, as the weight's mean is the albedo).
            let q = albedo.max_element().min(1.0);
            if self.rng.next_f32() >= q {
                self.bounces_left = 0;
                return;
            }
            let Some(sample) = material.sample_from(&at, wo, &mut self.rng) else {
                self.bounces_left = 0;
                return;
            };
            self.power *= sample.weight / q;
            if sample.lobe.has_delta() {
                self.specular = true;
            } else {
                self.diffuse_bounces += 1;
            }
            sample.wi
        } else {
            let at = scene.shading_point(&hit);
            let Some(sample) = material.sample_from(&at, wo, &mut self.rng) else {
                self.bounces_left = 0;
                return;
            };
            self.power *= sample.weight;
            if self.power.max_element() <= 0.0 {
                self.bounces_left = 0;
                return;
            }
            self.specular = true;
            sample.wi
        };
        self.ray = scene.spawn_ray(&hit, direction);
        self.from = Some(hit);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::partition::Partitioner;
    use crate::partition::crease::CreaseAngle;
    use crate::photons::light_picker::LightPicker;
    use crate::scenes::scale::split_rooms;

    /// Paths traced two at a time store exactly the photons, in exactly the order, of paths
    /// traced one at a time (every path draws from its own stream, and the second path's
    /// photons are held back until the first has ended), on a scene large enough to use pairs
    /// and for an odd number of paths.
    #[test]
    fn paths_traced_in_pairs_store_what_paths_traced_one_at_a_time_store() {
        let scene = split_rooms(60).unwrap();
        assert!(scene.prefers_ray_pairs());
        let assignment = CreaseAngle::default()
            .partition(scene.clone())
            .unwrap()
            .assignment()
            .clone();
        let options = TraceOptions {
            photons: 2_001,
            seed: 7,
            ..TraceOptions::default()
        };
        let picker = LightPicker::new(&scene, options.photons).unwrap();
        // Uniform emission, and a guide that sees only the floors.
        let learnt = EmissionGuide::learn(
            &scene,
            &assignment,
            &options,
            &crate::photons::GuideOptions::default(),
            &|_, p| p.y < 1e-3,
        )
        .unwrap();
        assert!(learnt.keep_rate() < 0.9, "{}", learnt.keep_rate());
        for guide in [None, Some(&learnt)] {
            let trace = |paired: bool, range: (u32, u32)| {
                let mut out = Vec::new();
                let mut near = NearLight::default();
                trace_paths(
                    &scene,
                    &assignment,
                    &options,
                    &picker,
                    guide,
                    range,
                    paired,
                    &mut out,
                    &mut near,
                );
                out
            };
            // The smallest chunks too: one path (no pair), two (one pair), three (a pair and a
            // path left over), and a chunk starting at an odd path.
            for range in [(0, 1), (0, 2), (0, 3), (7, 10)] {
                assert_eq!(trace(true, range), trace(false, range), "paths {range:?}");
            }
            let (one, two) = (
                trace(false, (0, options.photons)),
                trace(true, (0, options.photons)),
            );
            assert!(one.len() > 3_000, "{}", one.len());
            assert_eq!(one.len(), two.len());
            for (k, ((ma, a), (mb, b))) in one.iter().zip(&two).enumerate() {
                assert_eq!(ma, mb, "photon {k}");
                assert_eq!(
                    a.position.to_array().map(f32::to_bits),
                    b.position.to_array().map(f32::to_bits),
                    "photon {k}"
                );
                assert_eq!(
                    a.power.to_array().map(f32::to_bits),
                    b.power.to_array().map(f32::to_bits),
                    "photon {k}"
                );
                assert_eq!(a.direction, b.direction, "photon {k}");
                assert_eq!(a.kind, b.kind, "photon {k}");
            }
        }
    }

    /// The whole run on a scene large enough for paired paths gives the same photons on one thread
    /// and on seven (chunks are paired within themselves, so the thread count never shows).
    #[test]
    fn paired_tracing_is_the_same_on_one_and_seven_threads() {
        let scene = split_rooms(60).unwrap();
        assert!(scene.prefers_ray_pairs());
        let assignment = CreaseAngle::default()
            .partition(scene.clone())
            .unwrap()
            .assignment()
            .clone();
        let options = TraceOptions {
            photons: 3_001,
            seed: 11,
            ..TraceOptions::default()
        };
        let run = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| crate::photons::trace::trace_photons(&scene, &assignment, &options).unwrap())
                .into_parts()
                .0
        };
        let (one, seven) = (run(1), run(7));
        assert!(one.iter().map(Vec::len).sum::<usize>() > 5_000);
        assert_eq!(one, seven);
    }
}
