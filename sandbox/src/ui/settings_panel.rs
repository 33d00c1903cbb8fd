//! The editable sections: scene, renderer, auto configuration, split view, display and camera.

use super::Requests;
use crate::settings::{
    Algorithm, Denoiser, EdgeEmission, RenderSettings, SamplesPerPixel, ToneCurve,
};
use crate::state::{AppState, PathMode};
use lucid_engine::scene::SceneFeatures;
use lucid_passes::light_transport::bdpt::MisHeuristic;
use std::num::NonZeroU32;

/// Shows the sections.
pub fn show(ui: &mut egui::Ui, state: &mut AppState, requests: &mut Requests) {
    egui::CollapsingHeader::new("Scene")
        .default_open(true)
        .show(ui, |ui| scene(ui, state, requests));
    egui::CollapsingHeader::new("Renderer")
        .default_open(true)
        .show(ui, |ui| {
            if state.split.is_some() {
                ui.label("left half");
            }
            renderer(ui, &mut state.render)
        });
    egui::CollapsingHeader::new("Auto configuration")
        .default_open(state.auto.last.is_some())
        .show(ui, |ui| {
            super::auto_panel::show(ui, &mut state.auto, requests)
        });
    egui::CollapsingHeader::new("Split view")
        .default_open(true)
        .show(ui, |ui| split(ui, state));
    egui::CollapsingHeader::new("Display")
        .default_open(true)
        .show(ui, |ui| display(ui, state, requests));
    egui::CollapsingHeader::new("Camera")
        .default_open(false)
        .show(ui, |ui| camera(ui, state, requests));
}

fn scene(ui: &mut egui::Ui, state: &mut AppState, requests: &mut Requests) {
    ui.horizontal(|ui| {
        let field = ui.text_edit_singleline(&mut state.scene_field);
        let enter = field.lost_focus() && ui.input(|i| i.key_pressed(egui::Key::Enter));
        if ui.button("Load").clicked() || enter {
            requests.load_scene = Some(state.scene_field.trim().to_string());
        }
    });
    match &state.scene {
        Ok(info) => {
            ui.label(format!("{} ({})", info.name, info.source));
            ui.label(format!(
                "{} triangles, {} materials",
                info.triangles, info.materials
            ));
            for warning in &info.warnings {
                ui.colored_label(egui::Color32::YELLOW, warning);
            }
            for note in &info.notes {
                ui.label(note);
            }
            let used: Vec<&str> = feature_list(&info.features)
                .into_iter()
                .filter_map(|(name, used)| used.then_some(name))
                .collect();
            let used = if used.is_empty() {
                "none".to_string()
            } else {
                used.join(", ")
            };
            ui.label(format!("Features: {used}"));
        }
        Err(e) => {
            ui.colored_label(egui::Color32::LIGHT_RED, e);
        }
    }
}

/// The scene features with their names, in a fixed order.
fn feature_list(f: &SceneFeatures) -> [(&'static str, bool); 18] {
    [
        ("diffuse", f.diffuse),
        ("conductor", f.conductor),
        ("smooth dielectric", f.dielectric_smooth),
        ("rough dielectric", f.dielectric_rough),
        ("glTF metal-roughness", f.metal_rough),
        ("emissive", f.emissive),
        ("spheres", f.spheres),
        ("textures", f.textures),
        ("vertex colours", f.vertex_colors),
        ("normal maps", f.normal_maps),
        ("emissive textures", f.emissive_textures),
        ("alpha cut-outs", f.alpha_test),
        ("occlusion", f.occlusion),
        ("texture transforms", f.texture_transforms),
        ("environment", f.environment),
        ("environment map", f.environment_map),
        ("sun", f.sun),
        ("point/spot lights", f.delta_lights),
    ]
}

fn renderer(ui: &mut egui::Ui, r: &mut RenderSettings) {
    egui::ComboBox::from_label("algorithm")
        .selected_text(r.algorithm.label())
        .show_ui(ui, |ui| {
            for a in Algorithm::ALL {
                ui.selectable_value(&mut r.algorithm, a, a.label());
            }
        });
    let mut spp = r.spp.get();
    ui.add(
        egui::DragValue::new(&mut spp)
            .range(1..=1024)
            .prefix("samples per pixel: "),
    );
    r.spp = SamplesPerPixel::new(spp).unwrap_or(r.spp);
    ui.add(
        egui::DragValue::new(&mut r.max_depth)
            .range(1..=64)
            .prefix("max path length: "),
    );
    if r.algorithm == Algorithm::Bidirectional {
        let mut connections = r.bdpt_connections.get();
        ui.add(
            egui::DragValue::new(&mut connections)
                .range(1..=16)
                .prefix("connections per vertex: "),
        )
        .on_hover_text(
            "Cached light vertices each camera vertex connects to: more cost time and lower the \
             noise of the light that only connections find",
        );
        r.bdpt_connections = NonZeroU32::new(connections).unwrap_or(r.bdpt_connections);
        egui::ComboBox::from_label("MIS")
            .selected_text(r.bdpt_mis.label())
            .show_ui(ui, |ui| {
                for h in MisHeuristic::ALL {
                    ui.selectable_value(&mut r.bdpt_mis, h, h.label());
                }
            });
        ui.add(
            egui::DragValue::new(&mut r.bdpt_connection_roulette)
                .range(0.0..=100.0)
                .speed(0.01)
                .prefix("connection roulette: "),
        )
        .on_hover_text(
            "A connection that would add less than this share of what its camera subpath has \
             gathered, or a light-tracing one whose MIS weight is under it (at most 1), is traced \
             with probability in proportion (unbiased: fewer shadow rays, a little more noise); 0 \
             traces every connection",
        );
    }
    egui::ComboBox::from_label("denoiser")
        .selected_text(r.denoiser.label())
        .show_ui(ui, |ui| {
            for d in Denoiser::ALL {
                ui.selectable_value(&mut r.denoiser, d, d.label());
            }
        });
    if r.denoiser != Denoiser::None {
        egui::ComboBox::from_label("supersample emitters' edges")
            .selected_text(r.edge_emission.label())
            .show_ui(ui, |ui| {
                for e in EdgeEmission::ALL {
                    ui.selectable_value(&mut r.edge_emission, e, e.label());
                }
            });
    }
    if r.denoiser == Denoiser::Svgf {
        super::svgf_panel::svgf(ui, &mut r.svgf, r.algorithm.replays_paths());
    }
    if r.denoiser == Denoiser::Neural {
        ui.checkbox(&mut r.neural.gated_filter, "gated filter over the output")
            .on_hover_text(
                "The weights' edge-aware a-trous filter, blended in where the network's gate \
                 says (weights without one have nothing to turn off): off, the first frames \
                 after a cut are filtered less, for 0.20 ms less at 1080p on an H200",
            );
    }
    ui.checkbox(&mut r.accumulate, "accumulate");
    egui::ComboBox::from_label("view")
        .selected_text(r.view.label())
        .show_ui(ui, |ui| {
            for v in lucid_passes::debug::debug_view::View::ALL {
                ui.selectable_value(&mut r.view, v, v.label());
            }
        });
}

/// The toggle of the split view and the right half's settings (a copy of the left half's with the
/// other algorithm when it is turned on).
fn split(ui: &mut egui::Ui, state: &mut AppState) {
    let mut on = state.split.is_some();
    if ui
        .checkbox(&mut on, "compare two configurations side by side")
        .changed()
    {
        state.split = on.then(|| state.render.compared());
    }
    if let Some(right) = &mut state.split {
        ui.label("right half");
        ui.push_id("split", |ui| renderer(ui, right));
    }
}

fn display(ui: &mut egui::Ui, state: &mut AppState, requests: &mut Requests) {
    let d = &mut state.display;
    ui.add(egui::Slider::new(&mut d.exposure, -10.0..=10.0).text("exposure (EV)"));
    egui::ComboBox::from_label("tone mapper")
        .selected_text(d.tone_curve.label())
        .show_ui(ui, |ui| {
            for t in ToneCurve::ALL {
                ui.selectable_value(&mut d.tone_curve, t, t.label());
            }
        });
    if ui.button("Capture EXR + PNG (F12)").clicked() {
        requests.capture = true;
    }
}

fn camera(ui: &mut egui::Ui, state: &mut AppState, requests: &mut Requests) {
    let pose = state.camera.pose;
    ui.label(format!(
        "position {:.2} {:.2} {:.2}",
        pose.position.x, pose.position.y, pose.position.z
    ));
    ui.label(format!(
        "yaw {:.1}°, pitch {:.1}°, fov {:.1}°",
        pose.yaw.to_degrees(),
        pose.pitch.to_degrees(),
        pose.vfov_degrees
    ));
    ui.add(
        egui::DragValue::new(&mut state.camera.speed)
            .range(1e-3..=1e4)
            .speed(0.05)
            .prefix("speed: ")
            .suffix(" /s"),
    );
    ui.label("WASD move, Q/E down/up, right mouse look, wheel speed, F frames the scene");
    let stored = state.bookmarks.stored_keys();
    ui.label(if stored.is_empty() {
        "bookmarks: Shift+1..9 stores, 1..9 recalls".to_string()
    } else {
        format!("bookmarks: {stored:?}")
    });
    ui.horizontal(|ui| {
        ui.label("path file");
        ui.text_edit_singleline(&mut state.path_file);
    });
    ui.horizontal(|ui| match &state.path {
        PathMode::Idle => {
            requests.record = ui.button("Record").clicked();
            requests.replay = ui.button("Replay").clicked();
        }
        PathMode::Recording(recorder, _) => {
            ui.label(format!("recording ({} keys)", recorder.len()));
            requests.stop = ui.button("Stop and save").clicked();
        }
        PathMode::Replaying(..) => {
            ui.label("replaying");
            requests.stop = ui.button("Stop").clicked();
        }
    });
}
