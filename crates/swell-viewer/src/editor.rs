//! The scene being edited: the panel's draft, the last valid scene, and the last scene the view
//! has shown.
//!
//! The panel edits [`SceneEditor::draft`] freely; [`SceneEditor::apply`] validates the draft and
//! either commits it or refuses it, keeping the previous valid scene running and the reason in
//! [`SceneEditor::error`]. The draft keeps the refused value, so the user sees what they typed next
//! to why it was refused.
//!
//! The editor builds no world of its own: the render thread's world is the one simulated and
//! shown, and a second one here would be rebuilt on every water or terrain edit (a slider drag
//! rebuilds every frame) for nothing but a check. Validation ([`Scene::validate`]) catches every
//! bad value; what only building finds (a heightmap or texture file that cannot be read, a
//! model that goes unstable at once) comes back from the render thread as a failed frame, and
//! [`SceneEditor::frame_failed`] then puts back the last scene that was shown, as a refusal.
//! Whole scenes (the start, a loaded file) are still built here once, so that a bad file is
//! refused before anything changes.

use std::path::Path;

use swell::scene::{Camera, Scene};
use swell::world::{TerrainBody, World};
use swell::{Error, Result};

/// What [`SceneEditor::frame_failed`] made of a failed frame.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FrameFailure {
    /// The failure was about an older revision than the current one: ignored.
    Stale,
    /// The current commit could not be shown and was undone; the error is in the panel.
    Refused,
    /// The scene already shown failed (a model went unstable): the caller reports the error.
    Unrecoverable,
}

/// Draft, committed and last shown scene; see the [module documentation](self).
pub struct SceneEditor {
    /// What the panel shows and edits. May be invalid; see [`SceneEditor::error`].
    pub draft: Scene,
    /// The last valid scene: what the view renders and what is saved.
    scene: Scene,
    /// The last committed scene a frame was rendered from, and its revision: where a commit
    /// that fails to build falls back to.
    shown: Scene,
    shown_revision: u64,
    error: Option<String>,
    /// Bumped on every commit, so the view knows to render again.
    revision: u64,
}

impl SceneEditor {
    /// Starts editing `scene`, refused if it does not build (a file that cannot be read).
    pub fn new(scene: Scene) -> Result<Self> {
        World::new(scene.clone())?;
        Ok(Self { draft: scene.clone(), shown: scene.clone(), scene, shown_revision: 0, error: None, revision: 0 })
    }

    /// The last valid scene: what is simulated, rendered and saved.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Why the draft was refused, if it was.
    pub fn error(&self) -> Option<&str> {
        self.error.as_deref()
    }

    /// Increases whenever the committed scene changes.
    pub fn revision(&self) -> u64 {
        self.revision
    }

    /// Validates the draft and commits it. On error the previous scene stays and the error is
    /// kept for the panel.
    pub fn apply(&mut self) -> Result<()> {
        let result = self.commit();
        self.error = result.as_ref().err().map(ToString::to_string);
        result
    }

    fn commit(&mut self) -> Result<()> {
        if self.draft == self.scene {
            return Ok(());
        }
        self.draft.validate()?;
        self.scene = self.draft.clone();
        self.revision += 1;
        Ok(())
    }

    /// The view rendered a frame of `revision`: if it is the current one, its scene becomes the
    /// fallback of a later commit that fails to build.
    pub fn frame_shown(&mut self, revision: u64) {
        if revision == self.revision && self.shown_revision != revision {
            self.shown = self.scene.clone();
            self.shown_revision = revision;
        }
    }

    /// The view failed to build or step the scene of `revision` with `error`.
    ///
    /// - An older revision than the current one: [`FrameFailure::Stale`], nothing changes. The
    ///   current revision's frame answers for itself (fails again, or builds, after a camera drag
    ///   or a further edit).
    /// - The current scene, differing from the last one shown: the commit is undone as a
    ///   refusal ([`FrameFailure::Refused`]): the last shown scene comes back (with a new
    ///   revision), the draft keeps what was typed, and the error is kept for the panel.
    /// - The shown scene itself (e.g. a spring mesh that went unstable later on): there is
    ///   nothing to go back to, [`FrameFailure::Unrecoverable`], and the caller reports it.
    pub fn frame_failed(&mut self, revision: u64, error: &Error) -> FrameFailure {
        if revision != self.revision {
            return FrameFailure::Stale;
        }
        if self.scene == self.shown {
            return FrameFailure::Unrecoverable;
        }
        self.scene = self.shown.clone();
        self.error = Some(swell::error::printable(&error.to_string()));
        self.revision += 1;
        self.shown_revision = self.revision;
        FrameFailure::Refused
    }

    /// A click at world (x, z) wants to drop a dent on the water. True, with a new revision so
    /// that a paused view renders again, when the water's model takes disturbances (the spring
    /// mesh); the caller hands the dent to the render thread, whose world is the one shown.
    /// False, changing nothing, without water or for closed-form models.
    pub fn disturb_water(&mut self) -> bool {
        let takes = self.scene.water.as_ref().is_some_and(|w| w.model.takes_disturbances());
        if takes {
            self.revision += 1;
        }
        takes
    }

    /// The render thread's world added `spec` (a body dropped by a click, [`World::add_body`]):
    /// the same spec is appended to the scene, the draft and the fallback scene, so that the next
    /// scene sent holds the bodies that world holds (it is then not rebuilt) and a saved scene
    /// replays the drop. Returns the body's index; a new revision, so the view gets the scene.
    pub fn body_dropped(&mut self, spec: swell::body::BodySpec) -> usize {
        self.scene.bodies.push(spec.clone());
        self.shown.bodies.push(spec.clone());
        self.draft.bodies.push(spec);
        self.revision += 1;
        self.scene.bodies.len() - 1
    }

    /// Throws the draft away and shows the last valid scene again.
    pub fn revert(&mut self) {
        self.draft = self.scene.clone();
        self.error = None;
    }

    /// Moves the camera of both the draft and the committed scene (mouse controls), keeping the
    /// rest of an invalid draft as it is. Refused if `camera` is invalid.
    pub fn set_camera(&mut self, camera: Camera) -> Result<()> {
        camera.validate("camera")?;
        if camera != self.scene.camera {
            self.draft.camera = camera;
            self.scene.camera = camera;
            self.shown.camera = camera;
            self.revision += 1;
        }
        Ok(())
    }

    /// Replaces everything with `scene` (a loaded file); on error (it does not build) nothing
    /// changes.
    pub fn replace(&mut self, scene: Scene) -> Result<()> {
        World::new(scene.clone())?;
        self.draft = scene.clone();
        self.shown = scene.clone();
        self.scene = scene;
        self.error = None;
        self.revision += 1;
        self.shown_revision = self.revision;
        Ok(())
    }

    /// Reads a scene file and, if it is valid, replaces the current scene with it; otherwise the
    /// current scene stays and the error says why.
    pub fn load(&mut self, path: &Path) -> Result<()> {
        let scene = crate::files::read_scene(path)?;
        self.replace(scene)
    }

    /// Reads the heightmap PNG at `path` (with its `.toml` sidecar) and makes it the terrain,
    /// keeping the terrain's placement and look, committed at once; returns the field's vertices
    /// per side [x, z]. On error (the file cannot be read, or the draft is refused) nothing
    /// changes.
    pub fn load_heightmap(&mut self, path: &Path) -> Result<[usize; 2]> {
        let spec = crate::panels::terrain::use_heightmap(self.draft.terrain.as_ref(), path.to_path_buf());
        let body = TerrainBody::new(&spec)?;
        let before = self.draft.terrain.replace(spec);
        if let Err(e) = self.apply() {
            // Refused (another value of the draft, or the size limit): the draft goes back.
            self.draft.terrain = before;
            let _ = self.apply();
            return Err(e);
        }
        Ok([body.field.cols(), body.field.rows()])
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

    fn positions_at(scene: &Scene, t: f64) -> Vec<glam::Vec3> {
        let mut w = World::new(scene.clone()).unwrap();
        w.update(t).unwrap();
        w.water.unwrap().surface.positions().to_vec()
    }

    #[test]
    fn a_valid_draft_is_committed() {
        let mut e = sea();
        let before = e.scene().clone();
        set_first_amplitude(&mut e.draft, 1.5);
        e.apply().unwrap();
        assert_eq!(e.scene(), &e.draft);
        assert_eq!(first_amplitude(e.scene()), 1.5);
        assert_eq!(e.revision(), 1);
        // The committed scene really moves differently.
        assert_ne!(positions_at(e.scene(), 1.0), positions_at(&before, 1.0));
        // Committing the same draft again changes nothing.
        e.apply().unwrap();
        assert_eq!(e.revision(), 1);
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
    fn non_water_edits_commit_and_invalid_cameras_are_refused() {
        let mut e = sea();
        e.draft.render.exposure = 2.0;
        e.draft.sky.zenith.x = 0.5;
        e.apply().unwrap();
        assert_eq!(e.scene().render.exposure, 2.0);
        let mut bad = e.scene().camera;
        bad.eye = bad.target;
        assert!(e.set_camera(bad).is_err());
        assert_ne!(e.scene().camera.eye, e.scene().camera.target);
    }

    #[test]
    fn a_commit_the_view_cannot_build_is_undone_as_a_refusal() {
        let mut e = sea();
        e.frame_shown(0);
        let good = e.scene().clone();
        // Valid by its values; only reading the file finds that it is missing.
        e.draft.water.as_mut().unwrap().material.texture = Some("/no/such/texture.png".into());
        e.apply().unwrap();
        assert_eq!(e.revision(), 1);
        let err = World::new(e.scene().clone()).err().expect("the texture file is missing");
        // A late answer about an older revision changes nothing.
        let committed = e.scene().clone();
        assert_eq!(e.frame_failed(0, &err), FrameFailure::Stale);
        assert_eq!((e.scene(), e.revision(), e.error()), (&committed, 1, None), "a stale failure changes nothing");
        assert_eq!(e.frame_failed(1, &err), FrameFailure::Refused);
        assert_eq!(e.scene(), &good);
        assert_eq!(e.revision(), 2, "a new revision, so the view follows the restored scene");
        assert_eq!(e.error(), Some(err.to_string().as_str()));
        assert!(e.draft.water.as_ref().unwrap().material.texture.is_some(), "the draft keeps what was typed");
        // The shown scene failing (a model going unstable later) has nothing to go back to.
        assert_eq!(e.frame_failed(2, &err), FrameFailure::Unrecoverable);
        // Nor does a late answer about a revision before it.
        assert_eq!(e.frame_failed(1, &err), FrameFailure::Stale);
        // Once a frame of a commit is shown, that commit is the fallback.
        e.draft = good.clone();
        e.draft.render.exposure = 1.5;
        e.apply().unwrap();
        e.frame_shown(3);
        set_first_amplitude(&mut e.draft, 0.7);
        e.apply().unwrap();
        assert_eq!(e.frame_failed(4, &err), FrameFailure::Refused);
        assert_eq!(e.scene().render.exposure, 1.5);
        assert_eq!(first_amplitude(e.scene()), first_amplitude(&good));
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

        let pixels = |ed: &SceneEditor| {
            let mut world = World::new(ed.scene().clone()).unwrap();
            world.update(2.5).unwrap();
            let mut rgba = Vec::new();
            let s = ed.scene().render;
            Renderer::new().render_size(&world, 160, 90).encode_rgba8(&s.display_encoding(), &mut rgba);
            rgba
        };
        assert_eq!(pixels(&e), pixels(&loaded));
    }

    #[test]
    fn a_loaded_heightmap_becomes_the_terrain_and_a_bad_one_changes_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let png = dir.path().join("hills.png");
        let mut hills = crate::panels::terrain::switch_generator(None, Some("hills")).unwrap().unwrap();
        hills.size = Some(33);
        swell::terrain::write_heightmap(&png, &hills.build().unwrap()).unwrap();
        let mut e = sea();
        assert_eq!(e.load_heightmap(&png).unwrap(), [33, 33]);
        let t = e.scene().terrain.as_ref().expect("the terrain is the file");
        assert!(matches!(t.generator, swell::scene::TerrainGenerator::Heightmap(_)), "{t:?}");
        assert!(!crate::panels::terrain::has_seed(&t.generator), "a file has nothing to regenerate");
        assert_eq!((e.revision(), e.error()), (1, None));
        let before = e.scene().clone();
        let err = e.load_heightmap(&dir.path().join("missing.png")).unwrap_err().to_string();
        assert!(err.contains("missing.png"), "{err}");
        assert_eq!((e.scene(), &e.draft, e.revision()), (&before, &before, 1));
    }

    #[test]
    fn a_click_dents_only_models_with_state() {
        let mut e = SceneEditor::new(preset("springs").unwrap()).unwrap();
        let rev = e.revision();
        assert!(e.disturb_water());
        assert_eq!(e.revision(), rev + 1, "a paused view renders the dent");
        let mut sea = sea();
        assert!(!sea.disturb_water());
        assert_eq!(sea.revision(), 0);
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

    #[test]
    fn a_dropped_body_joins_every_scene_and_survives_refusals_and_saving() {
        let mut e = sea();
        e.frame_shown(0);
        let mut spec =
            swell::body::BodySpec::new(swell::body::BodyShape::Box, &[1.0; 3], glam::Vec3::new(0.0, 2.0, 0.0));
        spec.name = "crate1".into();
        spec.release_time = 3.5;
        assert_eq!(e.body_dropped(spec.clone()), 0);
        assert_eq!(e.revision(), 1);
        assert_eq!((&e.scene().bodies, &e.draft.bodies), (&vec![spec.clone()], &vec![spec.clone()]));
        // A pending refused draft keeps its own value and gets the body too.
        set_first_amplitude(&mut e.draft, -1.0);
        assert!(e.apply().is_err());
        let second = swell::body::BodySpec { name: "crate2".into(), ..spec.clone() };
        assert_eq!(e.body_dropped(second), 1);
        assert_eq!(e.draft.bodies.len(), 2);
        assert_eq!(first_amplitude(&e.draft), -1.0);
        // A later commit the view cannot build falls back to a scene that still holds the bodies.
        e.revert();
        e.draft.bodies.pop();
        e.apply().unwrap();
        let err = swell::Error::invalid("test", "does not build");
        assert_eq!(e.frame_failed(e.revision(), &err), FrameFailure::Refused);
        assert_eq!(e.scene().bodies.len(), 2, "the fallback lost the dropped bodies");
        // Saved, the drop is in the file with its release time.
        let back = Scene::from_toml(&e.scene().to_toml(), "saved").unwrap();
        assert_eq!(back.bodies[0], spec);
    }
}
