//! Where a contact partition's photon maps come from: for a glTF scene, the number of crease
//! and contact maps, how many contact maps are smaller than 1 mm², 1 cm², … (and the area they
//! cover), how many contact maps each crease surface is split into, and the surfaces split the
//! most, with their size and place, so that a fragmented scene shows what fragments it (text
//! floating in front of a control panel, a box bottom tessellated into strips).
//!
//! `cargo run --release --example map_census -- SCENE.gltf [--contact-gap G]` (G a fraction of
//! the scene's bounding-box diagonal, as the render example's `--contact-gap`). Prints a
//! report; writes nothing.

use clap::Parser;
use photon_maps::trace::glam::Vec3;
use photon_maps::trace::{Contact, CreaseAngle, PartId, Partitioner, SourceFace};
use std::collections::HashMap;
use std::io::Write;
use std::path::PathBuf;

/// The contact maps of a glTF scene against its crease-angle maps. Prints a report; writes
/// nothing.
#[derive(Parser, Debug)]
struct Args {
    /// The glTF scene.
    scene: PathBuf,
    /// Widest gap that counts as touching, as a fraction of the bounding-box diagonal.
    #[arg(long, default_value_t = Contact::default().relative_gap)]
    contact_gap: f32,
    /// How many of the most split crease surfaces to list.
    #[arg(long, default_value_t = 8)]
    worst: usize,
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args = Args::parse();
    // Written through a locked handle so that a closed pipe (`| head`) ends the report with
    // an error instead of a panic.
    let mut out = std::io::stdout().lock();
    if !(args.contact_gap.is_finite() && args.contact_gap >= 0.0) {
        return Err(format!("--contact-gap {} is not a finite fraction ≥ 0", args.contact_gap).into());
    }
    let scene = photon_maps::trace::gltf::load_scene(&args.scene)?;
    let crease_start = std::time::Instant::now();
    let crease = CreaseAngle::default().partition(scene.clone())?;
    let crease_seconds = crease_start.elapsed().as_secs_f64();
    let crease_of: HashMap<SourceFace, u32> = (0..crease.scene().part_count() as u32)
        .filter_map(|p| {
            let face = crease.scene().source_face(PartId(p))?;
            Some((face, crease.assignment().map_of(PartId(p))))
        })
        .collect();
    let start = std::time::Instant::now();
    let contact = Contact {
        relative_gap: args.contact_gap,
        ..Contact::default()
    }
    .partition(scene)?;
    let seconds = start.elapsed().as_secs_f64();
    let (split, assignment) = (contact.scene(), contact.assignment());
    let maps = assignment.map_count() as usize;
    let mut map_area = vec![0.0f64; maps];
    let mut map_surfaces: Vec<Vec<u32>> = vec![Vec::new(); maps];
    for p in 0..split.part_count() as u32 {
        let m = assignment.map_of(PartId(p)) as usize;
        split.for_each_part_polygon(PartId(p), |polygon| map_area[m] += area(polygon));
        if let Some(surface) = contact.source_face(PartId(p)).and_then(|f| crease_of.get(&f))
            && !map_surfaces[m].contains(surface)
        {
            map_surfaces[m].push(*surface);
        }
    }
    writeln!(
        out,
        "{}: {} crease maps ({crease_seconds:.2} s); contact maps at gap {} of the diagonal: {maps} \
         (split {seconds:.2} s)",
        args.scene.display(),
        crease.assignment().map_count(),
        args.contact_gap
    )?;
    if let Some(record) = contact.record() {
        writeln!(out, "meetings: {:?}", record.counts())?;
    }
    let total: f64 = map_area.iter().sum();
    writeln!(
        out,
        "contact maps smaller than (count, their share of the {total:.3} m² of surface):"
    )?;
    for limit in [1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1] {
        let small: Vec<f64> = map_area.iter().copied().filter(|&a| a < limit).collect();
        let share = small.iter().sum::<f64>() / total.max(f64::MIN_POSITIVE);
        writeln!(
            out,
            "  {limit:>7.0e} m²: {:>7} ({:.3} %)",
            small.len(),
            100.0 * share
        )?;
    }
    let spanning = map_surfaces.iter().filter(|s| s.len() > 1).count();
    writeln!(
        out,
        "contact maps spanning more than one crease surface: {spanning}"
    )?;

    let mut per_surface: HashMap<u32, Vec<usize>> = HashMap::new();
    for (m, surfaces) in map_surfaces.iter().enumerate() {
        for &s in surfaces {
            per_surface.entry(s).or_default().push(m);
        }
    }
    let mut counts: Vec<usize> = per_surface.values().map(Vec::len).collect();
    counts.sort_unstable();
    if let Some(&most) = counts.last() {
        let at = |q: f64| counts[((counts.len() - 1) as f64 * q) as usize];
        writeln!(
            out,
            "contact maps per crease surface: median {}, 90th percentile {}, 99th {}, most {most}",
            at(0.5),
            at(0.9),
            at(0.99)
        )?;
    }
    let mut worst: Vec<(usize, u32)> = per_surface.iter().map(|(&s, m)| (m.len(), s)).collect();
    worst.sort_unstable_by(|a, b| b.cmp(a));
    for &(count, surface) in worst.iter().take(args.worst) {
        let mut lo = Vec3::splat(f32::INFINITY);
        let mut hi = Vec3::splat(f32::NEG_INFINITY);
        let mut surface_area = 0.0;
        for p in 0..crease.scene().part_count() as u32 {
            if crease.assignment().map_of(PartId(p)) == surface {
                crease.scene().for_each_part_polygon(PartId(p), |polygon| {
                    surface_area += area(polygon);
                    for &v in polygon {
                        lo = lo.min(v);
                        hi = hi.max(v);
                    }
                });
            }
        }
        let mut areas: Vec<f64> = per_surface[&surface].iter().map(|&m| map_area[m]).collect();
        areas.sort_by(f64::total_cmp);
        writeln!(
            out,
            "  crease surface {surface}: {count} contact maps (median {:.2e} m²) over {surface_area:.2e} m², \
             from {lo} to {hi}",
            areas[areas.len() / 2]
        )?;
    }
    Ok(())
}

/// Area of a planar polygon.
fn area(polygon: &[Vec3]) -> f64 {
    let mut sum = Vec3::ZERO;
    for i in 1..polygon.len().saturating_sub(1) {
        sum += (polygon[i] - polygon[0]).cross(polygon[i + 1] - polygon[0]);
    }
    0.5 * f64::from(sum.length())
}
