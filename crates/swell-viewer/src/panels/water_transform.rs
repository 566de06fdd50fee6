//! The water's object transform (paper 000's transforms, as far as water at rest on y = 0 allows):
//! move the patch centre in x and z, turn it about +Y (`yaw_deg`) and scale it uniformly
//! (`uniform_scale`), by typed values or step buttons. Steps are paper 000's (5 units per move,
//! 5 degrees per turn, the same defaults as the terrain panel's) and swell's scale factor 1.1.
//!
//! There are no X or Z rotations or Y moves: they would lift or tilt the water at rest off
//! y = 0, which the water optics (reflection plane, depth) rely on (see
//! [`swell::scene::WaterPlacement`]).

use eframe::egui::Ui;
use swell::scene::WaterSurface;

use super::terrain::{PAPER_MOVE_STEP_M, PAPER_ROTATE_STEP_DEG, SCALE_STEP};
use super::{fields, keys};

/// The step sizes (the panel's, not the scene's).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WaterTransformForm {
    /// Move step, metres.
    pub move_step: f32,
    /// Turn step, degrees.
    pub rotate_step: f32,
    /// Scale step, factor > 1.
    pub scale_step: f32,
}

impl Default for WaterTransformForm {
    fn default() -> Self {
        Self { move_step: PAPER_MOVE_STEP_M, rotate_step: PAPER_ROTATE_STEP_DEG, scale_step: SCALE_STEP }
    }
}

/// One press of a step button.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum WaterStep {
    /// Move the centre along x (`0`) or z (`1`) by `sign` steps.
    Move(usize, f32),
    /// Turn about +Y by `sign` steps.
    Yaw(f32),
    /// Scale up (`1.0`) or down (`-1.0`) one step.
    Scale(f32),
}

/// Applies one press to `s`. Turns wrap into [-360, 360] so repeated presses stay valid.
pub fn apply_step(s: &mut WaterSurface, step: WaterStep, form: &WaterTransformForm) {
    match step {
        WaterStep::Move(axis, sign) => s.center[axis] += sign * form.move_step,
        WaterStep::Yaw(sign) => {
            let a = s.yaw_deg + sign * form.rotate_step;
            s.yaw_deg = if a.abs() > 360.0 { a % 360.0 } else { a };
        }
        WaterStep::Scale(sign) => s.uniform_scale *= form.scale_step.powf(sign),
    }
}

/// Shows the transform rows and buttons; returns whether `s` changed.
pub fn show(ui: &mut Ui, s: &mut WaterSurface, form: &mut WaterTransformForm) -> bool {
    let mut changed = false;
    ui.label("Transform (about the patch centre; turn about +Y only)");
    fields::grid("water-transform").show(ui, |ui| {
        changed |= fields::number(ui, "yaw [-360, 360]", &mut s.yaw_deg, 0.5, " deg");
        changed |= fields::number(ui, "uniform scale (0, 10000]", &mut s.uniform_scale, 0.01, " x");
        keys::edits("water", &["yaw_deg", "uniform_scale"]);
        fields::number(ui, "move step", &mut form.move_step, 0.1, " m");
        fields::number(ui, "rotate step", &mut form.rotate_step, 0.1, " deg");
        fields::number(ui, "scale step", &mut form.scale_step, 0.01, " x");
    });
    let mut step = None;
    ui.horizontal(|ui| {
        for (label, st) in [
            ("x -", WaterStep::Move(0, -1.0)),
            ("x +", WaterStep::Move(0, 1.0)),
            ("z -", WaterStep::Move(1, -1.0)),
            ("z +", WaterStep::Move(1, 1.0)),
            ("yaw -", WaterStep::Yaw(-1.0)),
            ("yaw +", WaterStep::Yaw(1.0)),
            ("scale /", WaterStep::Scale(-1.0)),
            ("scale x", WaterStep::Scale(1.0)),
        ] {
            if ui.small_button(label).clicked() {
                step = Some(st);
            }
        }
        if ui.small_button("identity").on_hover_text("yaw 0, scale 1 (the centre stays)").clicked()
            && (s.yaw_deg, s.uniform_scale) != (0.0, 1.0)
        {
            s.yaw_deg = 0.0;
            s.uniform_scale = 1.0;
            changed = true;
        }
    });
    if let Some(st) = step {
        apply_step(s, st, form);
        changed = true;
    }
    changed
}

#[cfg(test)]
mod tests {
    use glam::Vec2;
    use swell::scene::{preset, Scene};
    use swell::world::World;

    use super::*;

    #[test]
    fn steps_are_paper_000_s_stay_valid_and_the_scene_renders_them() {
        let form = WaterTransformForm::default();
        let mut scene = preset("sea").unwrap();
        scene.water.as_mut().unwrap().surface.cells = [16, 16];
        let s = &mut scene.water.as_mut().unwrap().surface;
        let c0 = s.center;
        apply_step(s, WaterStep::Move(0, 1.0), &form);
        apply_step(s, WaterStep::Move(1, -1.0), &form);
        assert_eq!(s.center - c0, Vec2::new(5.0, -5.0));
        for _ in 0..80 {
            apply_step(s, WaterStep::Yaw(1.0), &form);
        }
        // 80 presses of 5 degrees = 400 degrees, wrapped back into the valid range.
        assert!((s.yaw_deg - 40.0).abs() < 1e-3, "{}", s.yaw_deg);
        apply_step(s, WaterStep::Scale(1.0), &form);
        apply_step(s, WaterStep::Scale(1.0), &form);
        apply_step(s, WaterStep::Scale(-1.0), &form);
        assert!((s.uniform_scale - 1.1).abs() < 1e-5);
        // The edited scene saves, loads back, validates and places the mesh.
        let back = Scene::from_toml(&scene.to_toml(), "t").unwrap();
        assert_eq!(back, scene);
        let world = World::new(back).unwrap();
        let w = world.water.as_ref().unwrap();
        assert_eq!(w.placement.scale, scene.water.as_ref().unwrap().surface.uniform_scale);
        assert!((w.placement.yaw - 40f32.to_radians()).abs() < 1e-6);
    }
}
