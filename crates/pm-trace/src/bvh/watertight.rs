//! The watertight ray–triangle test (Woop, Benthin & Wald 2013): no ray slips between the
//! triangles of a closed mesh, which obvhs's own Möller–Trumbore test allows.

use glam::Vec3;

/// A ray prepared for the watertight test: the axis permutation and shear folded into three
/// row vectors, so a vertex `a` maps to `(a·x_row, a·y_row, a·z_row)` without indexing by a
/// per-ray axis (which compiled to unpredictable branches). Each row has one or two non-zero
/// entries (1 and −shear, or the z scale), so the dot products round exactly like the
/// permute-then-shear formulation.
pub(crate) struct WatertightRay {
    pub(super) origin: Vec3,
    /// The permuted axes `(kx, ky, kz)`: `kz` is the direction's dominant axis.
    pub(super) axes: (usize, usize, usize),
    /// The shear `(d[kx] / d[kz], d[ky] / d[kz], 1 / d[kz])` (each as `d · (1 / d[kz])`).
    pub(super) shear: Vec3,
    x_row: Vec3,
    y_row: Vec3,
    z_row: Vec3,
}

impl WatertightRay {
    pub(crate) fn new(origin: Vec3, direction: Vec3) -> Self {
        /// Unit vectors by axis, so a per-ray axis becomes a table load rather than a branch
        /// or a store-then-load through a stack array (which stalls store forwarding).
        const AXES: [Vec3; 3] = [Vec3::X, Vec3::Y, Vec3::Z];
        /// `(kx, ky)` by `2·kz + (d[kz] < 0)`: the next two axes in cyclic order, swapped
        /// for a negative `d[kz]` to keep the triangles' winding.
        const OTHER_AXES: [(usize, usize); 6] = [(1, 2), (2, 1), (2, 0), (0, 2), (0, 1), (1, 0)];
        let abs = direction.abs();
        // The dominant axis without branches (ray directions are random, so branches here
        // mispredict): x when it beats both, else y when it beats z, else z.
        let x_major = (abs.x > abs.y) & (abs.x > abs.z);
        let y_major = (abs.x <= abs.y) & (abs.y > abs.z);
        let kz = 2 - 2 * x_major as usize - y_major as usize;
        let ez = AXES[kz];
        // Dot products with unit vectors select a component exactly (the direction is finite).
        let dz = direction.dot(ez);
        let (kx, ky) = OTHER_AXES[2 * kz + (dz < 0.0) as usize];
        let (ex, ey) = (AXES[kx], AXES[ky]);
        // One division: the shear only has to be the same for every triangle of a ray.
        let sz = 1.0 / dz;
        let (sx, sy) = (direction.dot(ex) * sz, direction.dot(ey) * sz);
        WatertightRay {
            origin,
            axes: (kx, ky, kz),
            shear: Vec3::new(sx, sy, sz),
            x_row: ex - sx * ez,
            y_row: ey - sy * ez,
            z_row: sz * ez,
        }
    }

    /// Woop–Benthin–Wald watertight ray–triangle intersection (no backface culling).
    #[inline]
    pub(crate) fn intersect_triangle(&self, v: &[Vec3; 3], t_min: f32, t_max: f32) -> f32 {
        let a = v[0] - self.origin;
        let b = v[1] - self.origin;
        let c = v[2] - self.origin;
        let (ax, ay) = (a.dot(self.x_row), a.dot(self.y_row));
        let (bx, by) = (b.dot(self.x_row), b.dot(self.y_row));
        let (cx, cy) = (c.dot(self.x_row), c.dot(self.y_row));
        let mut u = cx * by - cy * bx;
        let mut vv = ax * cy - ay * cx;
        let mut w = bx * ay - by * ax;
        if u == 0.0 || vv == 0.0 || w == 0.0 {
            // Exactly on an edge in single precision: decide in double precision.
            u = (cx as f64 * by as f64 - cy as f64 * bx as f64) as f32;
            vv = (ax as f64 * cy as f64 - ay as f64 * cx as f64) as f32;
            w = (bx as f64 * ay as f64 - by as f64 * ax as f64) as f32;
        }
        if (u < 0.0 || vv < 0.0 || w < 0.0) && (u > 0.0 || vv > 0.0 || w > 0.0) {
            return f32::INFINITY;
        }
        let det = u + vv + w;
        if det == 0.0 {
            return f32::INFINITY;
        }
        let az = a.dot(self.z_row);
        let bz = b.dot(self.z_row);
        let cz = c.dot(self.z_row);
        let t = (u * az + vv * bz + w * cz) / det;
        if t > t_min && t < t_max { t } else { f32::INFINITY }
    }
}
