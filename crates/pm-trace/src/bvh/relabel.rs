//! A ray search taken over with new parts. The contact partition's rebuilt scene searches the
//! faces as the user gave them ([`crate::scene`]'s faces as given), which the scene as loaded
//! searched already: it takes that hierarchy over, each triangle's part replaced, instead of
//! building the same one again (on a 57,000-triangle interior, 40 ms of a 0.5 s split).

use super::pieces::PieceIndex;
use super::{SceneBvh, Search};
use crate::part::PartSurface;
use glam::Vec3;
use std::sync::Arc;

impl SceneBvh {
    /// `loaded`'s triangle search with this search's shapes: triangle `i` of those `loaded`
    /// was built from (`triangle(i)`, for `i` below `parts.len()`) takes part `parts[i]` (a
    /// piece list in `pieces`, as [`SceneBvh::with_triangles`] takes them), or, when `None`, is
    /// never met: its record shrinks to one corner, which the watertight test never hits
    /// (every edge function is exactly zero, so is the determinant).
    ///
    /// The same hits as a search built over the kept triangles alone, but for which of two
    /// triangles met at exactly the same distance comes first (the trees differ). `Err` gives
    /// `pieces` back when `loaded` is not a hierarchy over exactly those triangles in that
    /// order (a small scene's flat scan, or another scene): build the search instead.
    pub(crate) fn with_parts_of(
        &self,
        loaded: Arc<SceneBvh>,
        triangle: impl Fn(usize) -> [Vec3; 3],
        parts: &[Option<PartSurface>],
        pieces: PieceIndex,
    ) -> Result<Self, PieceIndex> {
        let same_triangles = matches!(loaded.triangle_search, Search::Bvh(_))
            && loaded.input_index.len() == parts.len()
            && loaded.triangles.len() == parts.len()
            && loaded
                .triangles
                .iter()
                .zip(&loaded.input_index)
                .all(|(record, &i)| record.v == triangle(i as usize));
        if !same_triangles {
            return Err(pieces);
        }
        // The scene as loaded is gone by now, so the hierarchy is usually taken, not copied.
        let SceneBvh {
            mut triangles,
            triangle_search,
            input_index,
            ..
        } = Arc::try_unwrap(loaded).unwrap_or_else(|shared| shared.duplicate_triangle_search());
        let mut dropped = 0;
        for (record, &i) in triangles.iter_mut().zip(&input_index) {
            match parts[i as usize] {
                Some(part) => {
                    record.part = part.part;
                    record.surface = part.surface;
                }
                None => {
                    record.v = [record.v[0]; 3];
                    dropped += 1;
                }
            }
        }
        let shapes = Self::build(Vec::new(), Vec::new(), self.shapes.clone());
        Ok(SceneBvh {
            triangles,
            triangle_search,
            input_index,
            dropped,
            shapes: shapes.shapes,
            shape_search: shapes.shape_search,
            pieces,
        })
    }

    /// A copy of this search's triangle side (for a search still shared).
    fn duplicate_triangle_search(&self) -> SceneBvh {
        let triangle_search = match &self.triangle_search {
            Search::Bvh(bvh) => Search::Bvh(bvh.clone()),
            Search::Empty | Search::Scan(_) => Search::Empty,
        };
        SceneBvh {
            triangles: self.triangles.clone(),
            triangle_search,
            input_index: self.input_index.clone(),
            dropped: self.dropped,
            shapes: Vec::new(),
            shape_search: Search::Empty,
            pieces: PieceIndex::default(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Rng;
    use crate::bvh::HitPrimitive;
    use crate::part::PartId;
    use crate::ray::Ray;
    use crate::sampling::uniform_sphere;
    use glam::Vec2;

    fn part(i: usize) -> PartSurface {
        PartSurface {
            part: PartId(i as u32),
            surface: (i % 7) as u32,
        }
    }

    /// A hierarchy taken over with new parts finds what a flat scan (brute force) of the kept
    /// triangles alone finds: the same distance bit for bit, the same new part, the same
    /// any-hit answer. Half the triangles have a coincident copy (the hidden copies the
    /// contact partition drops), and every copy and every fifth other triangle is dropped.
    #[test]
    fn a_search_taken_over_meets_exactly_the_kept_triangles() {
        let mut rng = Rng::new(41, 2);
        let mut u = || rng.next_f32();
        let mut triangles = Vec::new();
        for _ in 0..3000 {
            let centre = Vec3::new(u(), u(), u());
            let v = [0, 1, 2].map(|_| centre + (Vec3::new(u(), u(), u()) - 0.5) * 0.1);
            triangles.push(v);
            if u() < 0.5 {
                triangles.push(v);
            }
        }
        let loaded_parts: Vec<PartSurface> = (0..triangles.len()).map(part).collect();
        let loaded = SceneBvh::build(triangles.clone(), loaded_parts, Vec::new());
        assert!(matches!(loaded.triangle_search, Search::Bvh(_)));
        let parts: Vec<Option<PartSurface>> = (0..triangles.len())
            .map(|i| {
                let copy = i > 0 && triangles[i] == triangles[i - 1];
                (!copy && i % 5 != 0).then(|| part(10_000 + i))
            })
            .collect();
        let kept: Vec<usize> = (0..triangles.len()).filter(|&i| parts[i].is_some()).collect();
        let scan = SceneBvh::build_with(
            kept.iter().map(|&i| triangles[i]).collect(),
            kept.iter().map(|&i| parts[i].unwrap()).collect(),
            Vec::new(),
            usize::MAX,
        );
        let no_shapes = SceneBvh::build(Vec::new(), Vec::new(), Vec::new());
        let taken = no_shapes
            .with_parts_of(Arc::new(loaded), |i| triangles[i], &parts, PieceIndex::default())
            .expect("the hierarchy was built from these triangles");
        assert_eq!(taken.triangle_count(), kept.len());
        let mut hits = 0;
        for _ in 0..20_000 {
            let origin = Vec3::new(u(), u(), u()) * 1.2 - 0.1;
            let ray = Ray {
                origin,
                direction: uniform_sphere(Vec2::new(u(), u())),
            };
            let want = scan.closest(&ray, 0.0, f32::INFINITY, |_| true);
            let got = taken.closest(&ray, 0.0, f32::INFINITY, |_| true);
            let part_at = |search: &SceneBvh, (t, hit): (f32, HitPrimitive)| {
                (t, search.part_and_normal(hit, ray.at(t)).map(|(p, _)| p))
            };
            assert_eq!(got.map(|h| part_at(&taken, h)), want.map(|h| part_at(&scan, h)));
            assert_eq!(taken.any_hit(&ray, 0.0, 0.3), scan.any_hit(&ray, 0.0, 0.3));
            hits += usize::from(want.is_some());
        }
        assert!(hits > 5_000, "too few hits to test: {hits}");
    }

    /// The contact partition does take the scene's hierarchy over: a tessellated floor, its
    /// coincident copy (the hidden copy the split drops, all 200 of its triangles) and a wall
    /// standing on it (which cuts the floor). The split scene searches the loaded scene's very
    /// nodes, its dropped records are the copy's, and rays meet what they met before the split.
    /// At a metre, a micrometre, and ten kilometres ten thousand kilometres from the origin.
    #[test]
    fn the_contact_split_takes_the_loaded_hierarchy_over() {
        for (scale, origin) in [
            (1.0, Vec3::ZERO),
            (1e-6, Vec3::ZERO),
            (1e4, Vec3::new(1e7, -6e6, 3e6)),
        ] {
            contact_split_takes_the_loaded_hierarchy_over_at(scale, origin);
        }
    }

    fn contact_split_takes_the_loaded_hierarchy_over_at(scale: f32, origin: Vec3) {
        use crate::partition::{Contact, Partitioner};
        use crate::{PointLight, Scene, Surface};
        let at = |p: Vec3| origin + p * scale;
        let n = 10u32;
        let grid: Vec<Vec3> = (0..=n)
            .flat_map(|z| (0..=n).map(move |x| Vec3::new(x as f32, 0.0, z as f32) / n as f32))
            .map(at)
            .collect();
        let quads: Vec<[u32; 4]> = (0..n)
            .flat_map(|z| (0..n).map(move |x| z * (n + 1) + x))
            .map(|i| [i, i + n + 1, i + n + 2, i + 1])
            .collect();
        let wall = [
            Vec3::new(0.45, 0.0, 0.0),
            Vec3::new(0.45, 0.0, 1.0),
            Vec3::new(0.45, 0.5, 1.0),
            Vec3::new(0.45, 0.5, 0.0),
        ]
        .map(at);
        let grey = Surface::diffuse(Vec3::splat(0.5));
        let scene = Scene::builder()
            .mesh(&grid, &quads, grey)
            .mesh(&grid, &quads, grey)
            .mesh(&wall, &[[0u32, 1, 2, 3]], grey)
            .light(PointLight::new(at(Vec3::new(0.2, 1.0, 0.5)), Vec3::splat(1.0)))
            .build()
            .unwrap();
        let loaded_nodes = match &scene.search().triangle_search {
            Search::Bvh(bvh) => bvh.nodes.clone(),
            _ => panic!("402 triangles are searched by a hierarchy"),
        };
        let split = Contact::default().partition(scene.clone()).unwrap();
        let search = split.scene().search();
        let Search::Bvh(bvh) = &search.triangle_search else {
            panic!("the split scene's triangles are searched by a hierarchy");
        };
        let case = format!("scale {scale}, origin {origin}");
        assert_eq!(
            bvh.nodes, loaded_nodes,
            "{case}: the loaded hierarchy, not a new one"
        );
        assert_eq!(
            search.dropped, 200,
            "{case}: the copy's triangles are the dropped ones"
        );
        assert_eq!(search.triangle_count(), 202, "{case}");
        // Rays in the scene's own coordinates (it may be re-centred): from above the floor.
        let bounds = scene.bounds();
        let mut rng = Rng::new(5, 1);
        let mut u = || rng.next_f32();
        for _ in 0..2_000 {
            let ray = Ray {
                origin: bounds.min + (bounds.max - bounds.min) * Vec3::new(u(), 0.05 + 0.9 * u(), u()),
                direction: uniform_sphere(Vec2::new(u(), u())),
            };
            let t = |s: &Scene| {
                s.search()
                    .closest(&ray, 0.0, f32::INFINITY, |_| true)
                    .map(|h| h.0)
            };
            assert_eq!(t(split.scene()), t(&scene), "{case}");
        }
    }

    /// Only a hierarchy over exactly the given triangles, in their order, is taken over.
    #[test]
    fn other_triangles_or_a_scan_are_refused() {
        let triangle = |k: usize| {
            let o = Vec3::new(k as f32, 0.0, 0.0);
            [o, o + Vec3::X, o + Vec3::Y]
        };
        let build = |n: usize| {
            SceneBvh::build(
                (0..n).map(triangle).collect(),
                (0..n).map(part).collect(),
                Vec::new(),
            )
        };
        let none = SceneBvh::build(Vec::new(), Vec::new(), Vec::new());
        let parts = |n: usize| vec![Some(part(0)); n];
        let take = |loaded: SceneBvh, n: usize, of: &dyn Fn(usize) -> [Vec3; 3]| {
            none.with_parts_of(Arc::new(loaded), of, &parts(n), PieceIndex::default())
                .is_ok()
        };
        assert!(take(build(200), 200, &triangle));
        assert!(!take(build(200), 199, &triangle), "fewer triangles");
        assert!(!take(build(200), 200, &|k| triangle(199 - k)), "another order");
        assert!(!take(build(10), 10, &triangle), "a scan");
    }
}
