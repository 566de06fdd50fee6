//! Issue 21: every member of every closed set round-trips through its name and the scene format,
//! and the documentation lists it. The lists come from the sets' own declarations, so a member
//! added to a set is checked here without an edit.

use swell::body::BodyShape;
use swell::closed_set::ClosedSet;
use swell::export::{ExrCompression, NormalSpace};
use swell::math::ToneCurve;
use swell::scene::{GlitterModel, Scene, Shading, SkyModel, WaterModelSpec, TERRAIN_GENERATORS, WATER_MODELS};
use swell::spectrum::{SpectrumKind, SpreadingFunction};

fn scene_format_doc() -> String {
    std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../../docs/scene-format.md")).unwrap()
}

/// Each member parses from its name, prints as it, and survives TOML both ways; the names are
/// unique and an unknown name is refused naming the key and listing every valid name.
fn round_trips<T: ClosedSet + serde::Serialize + serde::de::DeserializeOwned>() {
    #[derive(serde::Serialize, serde::Deserialize)]
    struct Holder<T> {
        value: T,
    }
    assert_eq!(T::ALL.len(), T::NAMES.len());
    for (&member, &name) in T::ALL.iter().zip(T::NAMES) {
        assert_eq!(member.name(), name);
        assert_eq!(T::parse("key", name).unwrap(), member);
        let text = toml::to_string(&Holder { value: member }).unwrap();
        assert_eq!(text.trim(), format!("value = \"{name}\""));
        assert_eq!(toml::from_str::<Holder<T>>(&text).unwrap().value, member);
        assert_eq!(T::NAMES.iter().filter(|n| **n == name).count(), 1, "{name} twice");
    }
    let e = T::parse("a.key", "no-such-member").unwrap_err().to_string();
    assert!(e.starts_with("a.key: `no-such-member` is not") && e.contains(&T::NAMES.join(", ")), "{e}");
}

#[test]
fn every_closed_set_round_trips_through_its_names() {
    round_trips::<Shading>();
    round_trips::<SpectrumKind>();
    round_trips::<SpreadingFunction>();
    round_trips::<ExrCompression>();
    round_trips::<NormalSpace>();
    round_trips::<SkyModel>();
    round_trips::<GlitterModel>();
    round_trips::<ToneCurve>();
    round_trips::<BodyShape>();
}

#[test]
fn the_scene_format_documents_every_member() {
    let doc = scene_format_doc();
    let names = Shading::NAMES
        .iter()
        .chain(SpectrumKind::NAMES)
        .chain(SpreadingFunction::NAMES)
        .chain(SkyModel::NAMES)
        .chain(GlitterModel::NAMES)
        .chain(ToneCurve::NAMES)
        .chain(BodyShape::NAMES)
        .chain(WATER_MODELS)
        .chain(TERRAIN_GENERATORS);
    for name in names {
        let listed = doc.contains(&format!("`{name}`")) || doc.contains(&format!("\"{name}\""));
        assert!(listed, "docs/scene-format.md does not list `{name}`");
    }
}

#[test]
fn every_sky_model_renders_finite_and_round_trips() {
    for &model in SkyModel::ALL {
        let text = format!(
            "[camera]\neye = [0.0, 20.0, 60.0]\ntarget = [0.0, 0.0, 0.0]\n\
             [[light]]\ntype = 'directional'\ndirection = [0.3, -1.0, 0.2]\n\
             [sky]\nmodel = '{}'\nhaze_distance = 80.0\nsun_drives_light = true\n\
             [water]\nmodel = 'sines'\nsize = [40.0, 40.0]\ncells = [16, 16]\n[render]\nwidth = 64\nheight = 36\n",
            model.name()
        );
        let scene = Scene::from_toml(&text, "t").unwrap_or_else(|e| panic!("{model}: {e}"));
        assert_eq!(Scene::from_toml(&scene.to_toml(), "again").unwrap(), scene, "{model}");
        let world = swell::world::World::new(scene).unwrap();
        let image = swell::render::Renderer::new().render(&world).color.clone();
        assert!(image.iter().all(|c| c.is_finite()), "{model}");
    }
}

#[test]
fn every_shading_model_renders_water_and_terrain() {
    for &shading in Shading::ALL {
        let text = format!(
            "[camera]\neye = [0.0, 20.0, 60.0]\ntarget = [0.0, 0.0, 0.0]\n\
             [water]\nmodel = 'sines'\nsize = [40.0, 40.0]\ncells = [16, 16]\n[water.material]\nshading = '{0}'\n\
             [terrain]\ngenerator = 'hills'\nsize = 33\nextent = [80.0, 80.0]\n[terrain.material]\nshading = '{0}'\n\
             [render]\nwidth = 64\nheight = 36\n",
            shading.name()
        );
        let scene = Scene::from_toml(&text, "t").unwrap_or_else(|e| panic!("{shading}: {e}"));
        assert_eq!(Scene::from_toml(&scene.to_toml(), "again").unwrap(), scene, "{shading}");
        let world = swell::world::World::new(scene).unwrap();
        let image = swell::render::Renderer::new().render(&world).color.clone();
        assert!(image.iter().all(|c| c.is_finite()), "{shading}");
    }
}

#[test]
fn every_water_model_validates_builds_and_round_trips_by_name() {
    for &name in WATER_MODELS {
        let model = WaterModelSpec::default_for(name).unwrap();
        assert_eq!(model.name(), name);
        model.validate().unwrap_or_else(|e| panic!("{name}: {e}"));
        model.build().unwrap_or_else(|e| panic!("{name}: {e}"));
        let scene = Scene::from_toml(&format!("[water]\nmodel = '{name}'\n"), "t").unwrap();
        assert_eq!(scene.water.as_ref().unwrap().model, model, "{name}: the scene's defaults are the model's");
        assert_eq!(Scene::from_toml(&scene.to_toml(), "again").unwrap(), scene, "{name}");
    }
    assert!(WaterModelSpec::default_for("lava").is_none());
}

/// docs/scene-format.md's `extent` row names each model once, among the models defined everywhere
/// or among those that cannot be unbounded, as the model's own `ModelParams::defined_everywhere`
/// says (issue 33: the fact lives in the model contract; the docs row cannot drift from it).
#[test]
fn the_extent_row_sorts_every_model_as_its_contract_says() {
    let doc = scene_format_doc();
    let row = doc.lines().find(|l| l.starts_with("| `extent` | string")).expect("the extent row");
    // The backticked names inside the parentheses after each phrase.
    let names_after = |phrase: &str| -> Vec<String> {
        let at = row.find(phrase).unwrap_or_else(|| panic!("the extent row lacks \"{phrase}\""));
        let list = &row[at + phrase.len()..];
        let list = &list[list.find('(').expect("a list") + 1..list.find(')').expect("a closed list")];
        list.split('`').skip(1).step_by(2).map(str::to_string).collect()
    };
    let everywhere = names_after("the models defined everywhere");
    let finite = names_after("patch` otherwise");
    for &name in WATER_MODELS {
        let defined = WaterModelSpec::default_for(name).unwrap().params().defined_everywhere();
        let (listed, other) = if defined { (&everywhere, &finite) } else { (&finite, &everywhere) };
        assert!(listed.iter().any(|n| n == name), "extent row: `{name}` belongs in {listed:?}");
        assert!(!other.iter().any(|n| n == name), "extent row: `{name}` is listed in {other:?}");
    }
    assert_eq!(everywhere.len() + finite.len(), WATER_MODELS.len(), "{everywhere:?} {finite:?}");
}

#[test]
fn every_generator_but_the_file_validates_builds_and_round_trips_by_name() {
    for &name in TERRAIN_GENERATORS.iter().filter(|g| **g != "heightmap") {
        let size = if name == "diamond-square" { 33 } else { 20 };
        let scene = Scene::from_toml(&format!("[terrain]\ngenerator = '{name}'\nsize = {size}\n"), "t")
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let terrain = scene.terrain.as_ref().unwrap();
        assert_eq!(terrain.generator.name(), name);
        let field = terrain.build().unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!((field.cols(), field.rows()), (size as usize, size as usize), "{name}");
        assert_eq!(Scene::from_toml(&scene.to_toml(), "again").unwrap(), scene, "{name}");
    }
}
