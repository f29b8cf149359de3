//! The progressive renderer: leak-free at every pass (crease maps in lit-unlit-rooms, contact
//! maps in touching-rooms) for every estimator, while SPPM's one map leaks; bit-identical for
//! 1, 2 and 3 threads; shards merge into the single run and mismatched shards are refused.

use photon_maps::render::progressive::{
    ProgressiveRenderer, ProgressiveSettings, Shard, ShardError, SppmRenderer, SppmSettings,
};
use photon_maps::render::{EstimatorKind, Image, Mode, RenderSettings};
use photon_maps::trace::{Contact, CreaseAngle, Partitioned, Partitioner, Scene, scenes};

#[path = "support/dark_room.rs"]
mod dark_room;

const W: u32 = 48;
const H: u32 = 24;
/// Pixels of the image (`W × H`) that show only the dark room.
fn dark_room_pixels(scene: &Scene) -> Vec<usize> {
    dark_room::dark_room_pixels(scene, W, H)
}

fn render_settings(photons: u32, threads: usize) -> RenderSettings {
    RenderSettings {
        width: W,
        height: H,
        photons,
        mode: Mode::PhotonMap,
        seed: 5,
        threads,
        tile_size: 7,
        ..RenderSettings::default()
    }
}

fn progressive(first_pass: u64, passes: u64, threads: usize) -> ProgressiveSettings {
    ProgressiveSettings {
        first_pass,
        ..ProgressiveSettings::new(render_settings(6_000, threads), passes)
    }
}

/// Renders passes 0..4 one at a time and checks the dark room in each pass's own image.
fn assert_dark_at_every_pass(partitioned: &Partitioned, label: &str) {
    let dark = dark_room_pixels(partitioned.scene());
    assert!(
        dark.len() > (W * H / 20) as usize,
        "{label}: {} dark pixels",
        dark.len()
    );
    for kind in EstimatorKind::ALL {
        for pass in [0, 1, 2, 7] {
            let out = ProgressiveRenderer::new(kind, progressive(pass, 1, 0))
                .render(partitioned, &())
                .unwrap();
            let image = out.accumulation.mean();
            for &i in &dark {
                assert_eq!(
                    image.pixels()[i].to_array(),
                    [0.0; 3],
                    "{label} {kind}: pixel {i} leaks in pass {pass}"
                );
            }
            assert!(image.mean().x > 0.0, "{label} {kind}: the lit room must be lit");
        }
    }
}

#[test]
fn crease_maps_keep_the_dark_room_black_at_every_pass() {
    let scene = scenes::build("lit-unlit-rooms").unwrap();
    let crease = CreaseAngle::default().partition(scene).unwrap();
    assert_dark_at_every_pass(&crease, "lit-unlit-rooms");
}

#[test]
fn contact_maps_keep_the_touching_dark_room_black_at_every_pass() {
    let contact = Contact::default()
        .partition(scenes::build("touching-rooms").unwrap())
        .unwrap();
    assert_dark_at_every_pass(&contact, "touching-rooms");
}

#[test]
fn sppm_with_one_map_leaks_into_the_dark_room() {
    let scene = scenes::build("lit-unlit-rooms").unwrap();
    let dark = dark_room_pixels(&scene);
    let out = SppmRenderer::new(SppmSettings::new(render_settings(6_000, 0), 4))
        .render(&scene, &())
        .unwrap();
    let lit = dark.iter().filter(|&&i| out.image.pixels()[i].x > 0.0).count();
    assert!(lit > 0, "SPPM's global map should gather through the shared wall");
    assert!(out.image.mean().x > 0.0);
    assert_eq!(out.stats.passes, 4);
}

fn bits(image: &Image) -> Vec<u32> {
    image
        .pixels()
        .iter()
        .flat_map(|p| p.to_array().map(f32::to_bits))
        .collect()
}

#[test]
fn one_two_and_three_threads_give_bit_identical_images() {
    let scene = scenes::build("cornell-box").unwrap();
    for kind in EstimatorKind::ALL {
        let render = |threads| {
            let out = ProgressiveRenderer::new(kind, progressive(0, 3, threads))
                .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
                .unwrap();
            bits(&out.accumulation.mean())
        };
        let one = render(1);
        assert_eq!(one, render(2), "{kind}: 1 and 2 threads differ");
        assert_eq!(one, render(3), "{kind}: 1 and 3 threads differ");
        // Many threads asking for the same pilot sites and map polygons at once (each is
        // computed by whichever asks first).
        if kind == EstimatorKind::GeometryCube {
            assert_eq!(one, render(64), "{kind}: 1 and 64 threads differ");
        }
    }
    let sppm = |threads| {
        let s = SppmSettings::new(render_settings(6_000, threads), 3);
        bits(&SppmRenderer::new(s).render(&scene, &()).unwrap().image)
    };
    let one = sppm(1);
    assert_eq!(one, sppm(2), "SPPM: 1 and 2 threads differ");
    assert_eq!(one, sppm(3), "SPPM: 1 and 3 threads differ");
}

#[test]
fn merged_shards_equal_the_single_run() {
    let scene = scenes::build("cornell-box").unwrap();
    let kind = EstimatorKind::GeometryCube;
    let run = |first, passes| {
        let settings = progressive(first, passes, 0);
        let out = ProgressiveRenderer::new(kind, settings)
            .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
            .unwrap();
        let a = &out.accumulation;
        assert_eq!(a.pass_range(), first..first + passes);
        Shard::from_accumulation(a, "cornell-box", &settings.identity()).unwrap()
    };
    let single = run(0, 5);
    // Shards given out of order, as a scheduler may finish them.
    let shards = [run(3, 2), run(0, 1), run(1, 2)];
    let dir = std::env::temp_dir().join(format!("pm-shards-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let read: Vec<Shard> = shards
        .iter()
        .enumerate()
        .map(|(i, s)| {
            let path = dir.join(format!("shard{i}.exr"));
            s.write_exr(&path).unwrap();
            Shard::read_exr(&path).unwrap()
        })
        .collect();
    assert_eq!(read, shards, "shards read back as written");
    let merged = Shard::merge(&read).unwrap();
    assert_eq!(merged.pass_range(), 0..5);
    // Bit for bit: the shards carry exact sums, so the grouping of passes does not matter.
    assert_eq!(
        bits(&merged.mean()),
        bits(&single.mean()),
        "merged shards differ from the single run"
    );
    let paths: Vec<_> = [2, 0, 1].map(|i| dir.join(format!("shard{i}.exr"))).to_vec();
    let streamed = Shard::merge_files(&paths).unwrap();
    assert_eq!(
        bits(&streamed.mean()),
        bits(&single.mean()),
        "merged files differ from the single run"
    );
    // The naive merge of rounded means (what shards held before) is not bit-identical here,
    // so the test can tell.
    let rounded: Vec<Shard> = shards
        .iter()
        .map(|s| {
            Shard::new(
                s.mean(),
                s.pass_range().start,
                s.passes(),
                s.scene(),
                s.settings(),
            )
            .unwrap()
        })
        .collect();
    assert_ne!(
        bits(&Shard::merge(&rounded).unwrap().mean()),
        bits(&single.mean())
    );

    // Refusals.
    assert!(matches!(
        Shard::merge(&[shards[1].clone(), shards[1].clone()]),
        Err(ShardError::Overlap { .. })
    ));
    assert!(matches!(
        Shard::merge(&[shards[1].clone(), shards[0].clone()]),
        Err(ShardError::Gap { .. })
    ));
    let other_scene = Shard::new(shards[0].mean().clone(), 3, 2, "accordion", shards[0].settings()).unwrap();
    assert!(matches!(
        Shard::merge(&[shards[1].clone(), shards[2].clone(), other_scene]),
        Err(ShardError::SceneMismatch { .. })
    ));
    let other_settings = Shard::new(shards[0].mean().clone(), 3, 2, "cornell-box", "k=7").unwrap();
    assert!(matches!(
        Shard::merge(&[shards[1].clone(), shards[2].clone(), other_settings]),
        Err(ShardError::SettingsMismatch { .. })
    ));
    let plain = dir.join("plain.exr");
    single.mean().write_exr(&plain).unwrap();
    assert!(matches!(
        Shard::read_exr(&plain),
        Err(ShardError::NotAShard { .. })
    ));
    assert!(matches!(Shard::merge(&[]), Err(ShardError::Empty)));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_time_budget_stops_after_the_pass_that_spends_it() {
    let scene = scenes::build("accordion").unwrap();
    let settings = ProgressiveSettings {
        passes: None,
        time_budget: Some(std::time::Duration::ZERO),
        ..progressive(0, 1, 0)
    };
    let out = ProgressiveRenderer::new(EstimatorKind::Disc, settings)
        .render(&CreaseAngle::default().partition(scene.clone()).unwrap(), &())
        .unwrap();
    assert_eq!(out.stats.passes, 1);
    assert_eq!(out.accumulation.passes(), 1);
}
