//! The contact partition is the default, so where nothing meets it must change nothing: on the
//! report's four scenes and the scale scenes it finds no meeting and renders bit for bit the
//! crease maps' image, with every estimator.

use photon_maps::render::{EstimatorKind, Mode, RenderSettings, Renderer};
use photon_maps::trace::{Contact, CreaseAngle, Partitioner, scenes};

#[test]
fn scenes_where_nothing_meets_render_exactly_the_crease_maps_image() {
    let settings = RenderSettings {
        width: 40,
        height: 30,
        photons: 10_000,
        mode: Mode::PhotonMap,
        seed: 2,
        ..RenderSettings::default()
    };
    let names = [
        "cornell-box",
        "lit-unlit-rooms",
        "colored-rooms",
        "accordion",
        "split-rooms-3",
        "cube-field-8",
    ];
    for name in names {
        let contact = Contact::default()
            .partition(scenes::build(name).unwrap())
            .unwrap();
        let counts = contact.record().unwrap().counts();
        assert_eq!(counts.meetings(), 0, "{name}: {counts:?}");
        let crease = CreaseAngle::default()
            .partition(scenes::build(name).unwrap())
            .unwrap();
        for kind in EstimatorKind::ALL {
            let a = Renderer::new(kind, settings).render(&contact, &()).unwrap().image;
            let b = Renderer::new(kind, settings).render(&crease, &()).unwrap().image;
            let bits = |i: &photon_maps::render::Image| {
                i.pixels()
                    .iter()
                    .flat_map(|p| p.to_array().map(f32::to_bits))
                    .collect::<Vec<_>>()
            };
            assert_eq!(
                bits(&a),
                bits(&b),
                "{name} {kind}: contact and crease maps differ"
            );
        }
    }
}
