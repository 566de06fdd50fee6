//! The files panel: save the scene to TOML, load one, save a screenshot of the view or the whole
//! window. The viewer does the work ([`FileRequest`]) and reports back in [`FilesForm::message`].

use std::path::PathBuf;

use eframe::egui::{TextEdit, Ui};

use super::fields;

/// What the user asked to do with a file.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FileRequest {
    /// Write the current (valid) scene as TOML.
    SaveScene(PathBuf),
    /// Read a scene file and replace the current scene if it is valid.
    LoadScene(PathBuf),
    /// Write the rendered view (without the panel) as PNG, at the view's pixel size.
    SaveView(PathBuf),
    /// Write the whole window, panel included, as PNG.
    SaveWindow(PathBuf),
    /// Write the terrain's height field as a 16-bit grey PNG with its sidecar.
    SaveHeightmap(PathBuf),
    /// Read a heightmap PNG (and its sidecar) and make it the terrain, if it reads.
    LoadHeightmap(PathBuf),
}

/// The outcome of the last file operation, as shown under the buttons.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum FileMessage {
    /// It worked: what was written or read.
    Done(String),
    /// It failed: why (the scene is unchanged).
    Failed(String),
}

/// The paths typed in the panel and the last outcome.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct FilesForm {
    /// Scene file to save to or load from.
    pub scene_path: String,
    /// PNG file for screenshots.
    pub image_path: String,
    /// Outcome of the last operation.
    pub message: Option<FileMessage>,
}

impl Default for FilesForm {
    fn default() -> Self {
        Self { scene_path: "scene.toml".into(), image_path: "swell-view.png".into(), message: None }
    }
}

/// Shows the file controls; returns what was clicked, if anything.
pub fn show(ui: &mut Ui, form: &mut FilesForm) -> Option<FileRequest> {
    let mut request = None;
    fields::grid("files").show(ui, |ui| {
        ui.label("scene file");
        ui.add(TextEdit::singleline(&mut form.scene_path).desired_width(220.0));
        ui.end_row();
        ui.label("");
        ui.horizontal(|ui| {
            if ui.button("Save scene").clicked() {
                request = Some(FileRequest::SaveScene(PathBuf::from(&form.scene_path)));
            }
            if ui.button("Load scene").clicked() {
                request = Some(FileRequest::LoadScene(PathBuf::from(&form.scene_path)));
            }
        });
        ui.end_row();
        ui.label("image file");
        ui.add(TextEdit::singleline(&mut form.image_path).desired_width(220.0));
        ui.end_row();
        ui.label("");
        ui.horizontal(|ui| {
            if ui.button("Save view PNG").clicked() {
                request = Some(FileRequest::SaveView(PathBuf::from(&form.image_path)));
            }
            if ui.button("Save window PNG").clicked() {
                request = Some(FileRequest::SaveWindow(PathBuf::from(&form.image_path)));
            }
        });
        ui.end_row();
    });
    match &form.message {
        Some(FileMessage::Done(m)) => {
            ui.label(m);
        }
        Some(FileMessage::Failed(m)) => {
            ui.colored_label(ui.visuals().error_fg_color, m);
        }
        None => {}
    }
    request
}
