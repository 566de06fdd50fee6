//! The scene being edited: the panel's draft, the last valid scene and the [`World`] built from it.
//!
//! The panel edits [`SceneEditor::draft`] freely; [`SceneEditor::apply`] validates the draft and
//! either commits it (rebuilding the world only when the water changed) or refuses it, keeping the
//! previous valid scene running and the reason in [`SceneEditor::error`]. The draft keeps the
//! refused value, so the user sees what they typed next to why it was refused.

use std::path::Path;

use swell::scene::{Camera, Scene, World};
use swell::Result;

/// Draft scene, committed scene and world; see the [module documentation](self).
pub struct SceneEditor {
    /// What the panel shows and edits. May be invalid; see [`SceneEditor::error`].
    pub draft: Scene,
    world: World,
    error: Option<String>,
    /// Bumped on every commit, so the view knows to render again.
    revision: u64,
}

impl SceneEditor {
    /// Builds the world of `scene` (which must be valid: it was loaded by the CLI or a preset).
    pub fn new(scene: Scene) -> Result<Self> {
        let world = World::new(scene.clone())?;
        Ok(Self { draft: scene, world, error: None, revision: 0 })
    }

    /// The last valid scene: what is simulated, rendered and saved.
    pub fn scene(&self) -> &Scene {
        &self.world.scene
    }

    /// The world built from [`SceneEditor::scene`].
    pub fn world_mut(&mut self) -> &mut World {
        &mut self.world
    }

    /// Why the draft was refused, if it was.
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    /// Increases whenever the committed scene changes.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// Validates the draft and commits it. The world is rebuilt (models and meshes) only when
    /// [`World::needs_rebuild_for`] says so (water or terrain changed); camera, lights, sky and
    /// render settings are swapped in place. On error
    /// the previous scene stays and the error is kept for the panel.
    pub fn apply(&mut self) -> Result<()> {
        let result = self.commit();
        self.error = result.as_ref().err().map(ToString::to_string);
        result
    }

    fn commit(&mut self) -> Result<()> {
        if self.draft == self.world.scene {
            return Ok(());
        }
        if self.world.needs_rebuild_for(&self.draft) {
            let time = self.world.time();
            let mut world = World::new(self.draft.clone())?;
            world.update(time)?;
            self.world = world;
        } else {
            self.draft.validate()?;
            self.world.scene = self.draft.clone();
        }
        self.revision += 1;
        Ok(())
    }

    /// Drops a dent `depth` m deep and `radius` m wide on the water at world (x, z) (a click on the
    /// view) and redisplaces the mesh at the current time. Returns false, changing nothing, when
    /// there is no water or its model has no state to disturb (closed-form models). A turned or
    /// scaled patch gets the dent at the model-frame point under the click, sized so that it is
    /// `depth` x `radius` in the world.
    pub fn disturb_water(&mut self, x: f32, z: f32, depth: f32, radius: f32) -> Result<bool> {
        let time = self.world.time();
        if !self.world.disturb_water(x, z, depth, radius)? {
            return Ok(false);
        }
        self.world.update(if time.is_finite() { time } else { 0.0 })?;
        self.revision += 1;
        Ok(true)
    }

    /// Throws the draft away and shows the last valid scene again.
    pub fn revert(&mut self) {
        self.draft = self.world.scene.clone();
        self.error = None;
    }

    /// Moves the camera of both the draft and the committed scene (mouse controls), keeping the
    /// rest of an invalid draft as it is. Refused if `camera` is invalid.
    pub fn set_camera(&mut self, camera: Camera) -> Result<()> {
        camera.validate("camera")?;
        if camera != self.world.scene.camera {
            self.draft.camera = camera;
            self.world.scene.camera = camera;
            self.revision += 1;
        }
        Ok(())
    }

    /// Replaces everything with `scene` (a loaded file); on error nothing changes.
    pub fn replace(&mut self, scene: Scene) -> Result<()> {
        let time = self.world.time();
        let mut world = World::new(scene.clone())?;
        world.update(if time.is_finite() { time } else { 0.0 })?;
        self.world = world;
        self.draft = scene;
        self.error = None;
        self.revision += 1;
        Ok(())
    }

    /// Reads a scene file and, if it is valid, replaces the current scene with it; otherwise the
    /// current scene stays and the error says why.
    pub fn load(&mut self, path: &Path) -> Result<()> {
        let scene = crate::files::read_scene(path)?;
        self.replace(scene)
    }

    /// Writes the last valid scene to `path` as TOML, atomically.
    pub fn save(&self, path: &Path) -> Result<()> {
        crate::files::write_scene(path, self.scene())
    }
}

#[cfg(test)]
mod tests {
    use swell::render::Renderer;
    use swell::scene::{preset, WaterModelSpec};

    use super::*;

    fn sea() -> SceneEditor {
        SceneEditor::new(preset("sea").unwrap()).unwrap()
    }

    fn first_amplitude(scene: &Scene) -> f32 {
        match &scene.water.as_ref().unwrap().model {
            WaterModelSpec::Gerstner(g) => g.waves[0].amplitude,
            other => panic!("not gerstner: {other:?}"),
        }
    }

    fn set_first_amplitude(scene: &mut Scene, a: f32) {
        match &mut scene.water.as_mut().unwrap().model {
            WaterModelSpec::Gerstner(g) => g.waves[0].amplitude = a,
            other => panic!("not gerstner: {other:?}"),
        }
    }

    #[test]
    fn a_valid_draft_is_committed_and_rebuilds_the_water() {
        let mut e = sea();
        let h0 = e.world_mut().water.as_ref().unwrap().mesh.positions.clone();
        set_first_amplitude(&mut e.draft, 1.5);
        e.apply().unwrap();
        assert_eq!(e.scene(), &e.draft);
        assert_eq!(first_amplitude(e.scene()), 1.5);
        assert_eq!(e.revision(), 1);
        // The rebuilt world really moves differently.
        assert_ne!(e.world_mut().water.as_ref().unwrap().mesh.positions, h0);
    }

    #[test]
    fn an_invalid_draft_is_refused_with_the_reason_and_the_scene_kept() {
        let mut e = sea();
        let before = e.scene().clone();
        set_first_amplitude(&mut e.draft, -2.0);
        let err = e.apply().unwrap_err().to_string();
        assert_eq!(err, "water.waves[0].amplitude = -2 is outside [0, 100000]");
        assert_eq!(e.error(), Some(err.as_str()));
        assert_eq!(e.scene(), &before);
        assert_eq!(first_amplitude(&e.draft), -2.0, "the draft keeps what the user typed");
        // Moving the camera still works while the draft is invalid.
        let mut cam = before.camera;
        cam.eye.y += 1.0;
        e.set_camera(cam).unwrap();
        assert_eq!(e.scene().camera, cam);
        assert_eq!(e.draft.camera, cam);
        e.draft.render.exposure = 0.0;
        set_first_amplitude(&mut e.draft, 0.5);
        assert!(e.apply().unwrap_err().to_string().starts_with("render.exposure = 0"));
        e.revert();
        assert_eq!(e.error(), None);
        assert_eq!(e.draft, *e.scene());
        assert_eq!(first_amplitude(e.scene()), first_amplitude(&before));
    }

    #[test]
    fn non_water_edits_keep_the_world_and_invalid_cameras_are_refused() {
        let mut e = sea();
        e.world_mut().update(3.0).unwrap();
        e.draft.render.exposure = 2.0;
        e.draft.sky.zenith.x = 0.5;
        e.apply().unwrap();
        assert_eq!(e.world_mut().time(), 3.0);
        assert_eq!(e.scene().render.exposure, 2.0);
        let mut bad = e.scene().camera;
        bad.eye = bad.target;
        assert!(e.set_camera(bad).is_err());
        assert_ne!(e.scene().camera.eye, e.scene().camera.target);
    }

    #[test]
    fn save_then_load_reproduces_the_scene_and_the_render() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("edited.toml");
        let mut e = sea();
        set_first_amplitude(&mut e.draft, 1.1);
        e.draft.camera.eye.x = 12.0;
        e.draft.render.gamma = Some(2.2);
        e.apply().unwrap();
        e.save(&path).unwrap();

        let mut loaded = sea();
        loaded.load(&path).unwrap();
        assert_eq!(loaded.scene(), e.scene());
        assert_eq!(loaded.draft, e.draft);

        let pixels = |ed: &mut SceneEditor| {
            ed.world_mut().update(2.5).unwrap();
            let mut r = Renderer::new();
            let mut rgba = Vec::new();
            let s = ed.scene().render;
            r.render_size(ed.world_mut(), 160, 90).encode_rgba8(s.exposure, s.gamma, &mut rgba);
            rgba
        };
        assert_eq!(pixels(&mut e), pixels(&mut loaded));
    }

    #[test]
    fn a_click_disturbs_the_spring_mesh_and_nothing_else() {
        let mut e = SceneEditor::new(preset("springs").unwrap()).unwrap();
        e.world_mut().update(1.0).unwrap();
        let rev = e.revision();
        let before = e.world_mut().water.as_ref().unwrap().model.height_at(2.0, -3.0, 1.0);
        assert!(e.disturb_water(2.0, -3.0, 0.5, 1.0).unwrap());
        assert_eq!(e.revision(), rev + 1);
        let w = e.world_mut().water.as_ref().unwrap();
        let after = w.model.height_at(2.0, -3.0, 1.0);
        assert!((before - after - 0.5).abs() < 1e-3, "{before} -> {after}");
        // The mesh shown moved too: its lowest vertex is at least the dent deep.
        let lowest = w.mesh.positions.iter().map(|p| p.y).fold(f32::INFINITY, f32::min);
        assert!(lowest <= after + 1e-4);
        assert!(e.disturb_water(0.0, 0.0, -1.0, 1.0).is_err());
        let mut sea = sea();
        assert!(!sea.disturb_water(0.0, 0.0, 0.5, 1.0).unwrap());
        assert_eq!(sea.revision(), 0);
    }

    #[test]
    fn a_click_on_a_turned_and_scaled_spring_mesh_dents_the_water_under_it() {
        let mut scene = preset("springs").unwrap();
        let s = &mut scene.water.as_mut().unwrap().surface;
        (s.yaw_deg, s.uniform_scale) = (90.0, 2.0);
        let mut e = SceneEditor::new(scene).unwrap();
        e.world_mut().update(1.0).unwrap();
        let before = e.world_mut().water_height_at(2.0, -3.0).unwrap();
        assert!(e.disturb_water(2.0, -3.0, 0.5, 1.0).unwrap());
        let after = e.world_mut().water_height_at(2.0, -3.0).unwrap();
        assert!((before - after - 0.5).abs() < 2e-3, "{before} -> {after}");
    }

    #[test]
    fn a_bad_file_is_reported_and_the_scene_kept() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("bad.toml");
        std::fs::write(
            &path,
            "version = 1\n[camera]\neye = [0.0, 1.0, 2.0]\ntarget = [0.0, 0.0, 0.0]\n[render]\nwidth = -3\n",
        )
        .unwrap();
        let mut e = sea();
        let before = e.scene().clone();
        let err = e.load(&path).unwrap_err().to_string();
        assert!(err.contains("bad.toml") && err.contains("render.width"), "{err}");
        assert_eq!(e.scene(), &before);
        let missing = e.load(&dir.path().join("missing.toml")).unwrap_err().to_string();
        assert!(missing.contains("missing.toml"), "{missing}");
        assert_eq!(e.scene(), &before);
    }
}
