//! Ray offsets that survive rounding (after pbrt-v4's *Managing Rounding Error*): a hit point
//! computed as `origin + t · direction` lies within a bound of its surface that scales with
//! the magnitudes involved, never with a scene-relative epsilon; a secondary ray starts that
//! far off the surface along the normal, then one more float step away on each axis, so it
//! neither re-hits its own surface nor jumps through a thin wall, from 1 µm scenes to
//! kilometres from the origin.

use glam::Vec3;

/// Relative rounding error of a hit point: `ERROR_ULPS` units of f32 precision times the
/// magnitudes the point was computed from. The watertight triangle test translates the
/// vertices to the ray origin and divides two sums of three products (a few roundings each,
/// relative to `|v − origin| ≈ t`); `origin + t · direction` adds two more, relative to
/// `|origin|` and `t`. pbrt-v4's bound for the barycentric point is γ₇ ≈ 7ε; the ray-parametric
/// point carries t's error too, so this takes 16ε, and the sphere's quadratic stays within it
/// away from tangent rays (which carry no light there).
pub const ERROR_ULPS: f32 = 16.0;

/// The largest coordinate magnitude of `p`.
#[inline]
fn reach(p: Vec3) -> f32 {
    p.abs().max_element()
}

/// A bound on the distance of `position`, computed at distance `t` along a unit ray from
/// `origin`, from the true surface point.
#[inline]
pub fn point_error(origin: Vec3, position: Vec3, t: f32) -> f32 {
    ERROR_ULPS * f32::EPSILON * (reach(origin) + reach(position) + t.abs())
}

/// A bound on the distance of a point written in a triangle's coordinates, `v₀ + b₁ e₁ + b₂ e₂`,
/// from the triangle's plane, `magnitude` being the largest coordinate of `Σ |bᵢ vᵢ|`
/// (after pbrt-v4, taken at [`ERROR_ULPS`] like the ray-parametric one). It does not
/// grow with the triangle's thinness, as the error of `origin + t · direction` does.
#[inline]
pub fn interpolated_point_error(magnitude: f32) -> f32 {
    ERROR_ULPS * f32::EPSILON * magnitude
}

/// `point` moved `error` along unit `normal` (the side a new ray leaves to), then one float
/// step further away on each axis the normal has a component in: past the surface whatever
/// the rounding of the move.
#[inline]
pub fn offset_point(point: Vec3, normal: Vec3, error: f32) -> Vec3 {
    let moved = point + normal * error;
    let away = |x: f32, n: f32| {
        if n > 0.0 {
            x.next_up()
        } else if n < 0.0 {
            x.next_down()
        } else {
            x
        }
    };
    Vec3::new(
        away(moved.x, normal.x),
        away(moved.y, normal.y),
        away(moved.z, normal.z),
    )
}
