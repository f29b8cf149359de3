//! How a scene's photons fill its maps: how many maps hold none, how many hold fewer than
//! an estimate's k (there a k-nearest search runs out of the map and its radius grows to the
//! map's edge or the maximum distance), and how much of the surface those maps cover. The
//! measure of a partition's fragmentation: a split into many small maps leaves most of them
//! with few photons, and every estimate there wide or noisy.

use super::maps::PhotonMaps;

/// Photons per map, and the surface in maps that hold fewer than k: see [`PhotonMaps::occupancy`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct MapOccupancy {
    /// The k the counts below are taken against.
    pub k: usize,
    /// Maps.
    pub maps: usize,
    /// Maps that hold no photon.
    pub empty: usize,
    /// Maps that hold at least one photon and fewer than `k`.
    pub below_k: usize,
    /// Photons stored, over all maps.
    pub photons: u64,
    /// Photons stored in maps of fewer than `k`.
    pub photons_below_k: u64,
    /// Photons per map at the 10th, 50th and 90th percentiles, and the most in one map.
    pub photons_per_map: [u64; 4],
    /// The maps' surface, square metres (their faces' area).
    pub area: f64,
    /// The surface of maps that hold fewer than `k` photons (empty ones included).
    pub area_below_k: f64,
}

impl MapOccupancy {
    /// The share of the surface whose map holds fewer than `k` photons, in `[0, 1]`.
    pub fn area_share_below_k(&self) -> f64 {
        if self.area > 0.0 {
            self.area_below_k / self.area
        } else {
            0.0
        }
    }
}

impl PhotonMaps {
    /// How the photons fill the maps, counted against an estimate's `k` (see
    /// [`MapOccupancy`]). Linear in the maps' faces; the photons are not visited, and no
    /// map's polygons are built.
    pub fn occupancy(&self, k: usize) -> MapOccupancy {
        let mut counts: Vec<u64> = Vec::with_capacity(self.len());
        let mut out = MapOccupancy {
            k,
            maps: self.len(),
            ..MapOccupancy::default()
        };
        for (id, map) in self.iter().enumerate() {
            let n = map.tree().len() as u64;
            // The faces' area: the polygons' up to rounding, and no map's polygons built.
            let area = self.face_area(id as u32).unwrap_or(0.0);
            out.photons += n;
            out.area += area;
            if n < k as u64 {
                out.area_below_k += area;
                if n == 0 {
                    out.empty += 1;
                } else {
                    out.below_k += 1;
                    out.photons_below_k += n;
                }
            }
            counts.push(n);
        }
        counts.sort_unstable();
        if let Some(&most) = counts.last() {
            let at = |q: usize| counts[(counts.len() - 1) * q / 100];
            out.photons_per_map = [at(10), at(50), at(90), most];
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use crate::partition::Partitioner;
    use crate::partition::crease::CreaseAngle;
    use crate::photons::maps::PhotonMaps;
    use crate::photons::options::TraceOptions;
    use crate::photons::trace::trace_photons;

    /// Counted by hand on the Cornell box's crease maps: the counts add up to the maps and
    /// photons, the area to the scene's, and a k above every map's count puts all the surface
    /// below it.
    #[test]
    fn occupancy_adds_up_to_the_maps() {
        let scene = crate::scenes::build("cornell-box").unwrap();
        let partitioned = CreaseAngle::default().partition(scene).unwrap();
        let (scene, assignment) = (partitioned.scene(), partitioned.assignment());
        let options = TraceOptions {
            photons: 2_000,
            ..TraceOptions::default()
        };
        let traced = trace_photons(scene, assignment, &options).unwrap();
        let maps = PhotonMaps::build(scene, assignment, traced).unwrap();
        let stored: u64 = maps.iter().map(|m| m.tree().len() as u64).sum();
        let by_hand_below = |k: u64| maps.iter().filter(|m| (m.tree().len() as u64) < k).count();
        for k in [1, 50, 1_000_000] {
            let o = maps.occupancy(k);
            assert_eq!(o.maps, maps.len());
            assert_eq!(o.photons, stored);
            assert_eq!(o.empty + o.below_k, by_hand_below(k as u64), "k {k}");
            assert!(o.photons_per_map[0] <= o.photons_per_map[1]);
            assert!(o.photons_per_map[2] <= o.photons_per_map[3]);
        }
        let all = maps.occupancy(1_000_000);
        assert_eq!(all.area_share_below_k(), 1.0);
        assert_eq!(all.photons_below_k, stored);
        assert_eq!(maps.occupancy(1).area_below_k > 0.0, maps.occupancy(1).empty > 0);
    }
}
