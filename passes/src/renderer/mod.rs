//! The frame, assembled in one place: the sandbox, the command line and an embedding game all render
//! through [`Renderer`].
//!
//! ```no_run
//! # fn demo() -> lucid_engine::Result<()> {
//! use lucid_engine::{Context, ContextDesc};
//! use lucid_passes::renderer::{Renderer, Settings};
//! let ctx = Context::new(&ContextDesc::from_env())?;
//! let scene = lucid_engine::scene::builtin::build("cornell-box").expect("built-in scene");
//! let mut renderer = Renderer::new(&ctx, scene, 256, 256, Settings::default())?;
//! for _ in 0..16 {
//!     renderer.render()?;
//! }
//! let image = renderer.render_and_read()?; // the accumulated HDR image
//! # Ok(()) }
//! ```

mod settings;
#[cfg(feature = "clap")]
mod value_enum;

pub use crate::samples_per_pixel::{SamplesPerPixel, ZeroSamplesPerPixel};
pub use settings::{Algorithm, Denoiser, EdgeEmission, Settings};

use crate::denoise::edge_emission;
use crate::denoise::gbuffer::{self, GBuffer};
use crate::denoise::{accumulate, neural, svgf};
use crate::denoise::{DenoiseInputs, Denoised, FrameDenoiser, FrameInfo};
use crate::light_transport::{self, Replay, ReplayParams};
use crate::light_transport::{bdpt, path_trace, wavefront};
use crate::plumbing::frame_constants::{self, FrameConstants};
use crate::plumbing::scene_buffers::{
    specialization, workgroup_scene_words, SceneBuffers, SceneHandles,
};
use crate::post::tonemap;
use lucid_engine::capture::ImageData;
use lucid_engine::graph::{BufferHandle, Executor, FrameId, ImageHandle, ReadbackId, RenderGraph};
use lucid_engine::scene::gpu::{self, apply_flattening, pack_flat, BvhLayout, GpuCamera, GpuScene};
use lucid_engine::scene::{Bvh, Camera, FlatScene, Material, Scene};
use lucid_engine::shader::{ShaderLibrary, Specialization};
use lucid_engine::{Context, EngineError, Result};

/// The images of one frame, for callers that add passes of their own (display, capture).
#[derive(Clone, Copy, Debug)]
pub struct FrameImages {
    /// Noisy radiance of this frame.
    pub radiance: ImageHandle,
    /// Radiance without the first hit's emission, divided by its albedo (see
    /// [`crate::light_transport::SurfaceImages::demodulated`]); traced only when a denoiser runs.
    pub demodulated: Option<ImageHandle>,
    /// SVGF's temporal gradients ([`svgf::add_svgf`]); `None` unless temporal SVGF ran.
    pub gradient: Option<ImageHandle>,
    /// The learned denoiser's per-pixel inputs ([`neural::add_record`]); `None` unless it ran.
    pub neural_record: Option<BufferHandle>,
    /// Accumulated (or this frame's) HDR radiance.
    pub hdr: ImageHandle,
    /// Tone-mapped sRGB RGBA8.
    pub ldr: ImageHandle,
    /// Primary visibility for denoisers and debug views (culled when nothing reads it).
    pub gbuffer: GBuffer,
}

/// Counts from the last completed frame.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FrameStats {
    /// Samples dropped because they were NaN or infinite.
    pub non_finite_samples: u32,
    /// Rays traced (closest-hit and shadow rays).
    pub rays: u32,
    /// GPU time of the frame's passes in milliseconds (their timestamps summed); 0 where the
    /// device has no timestamps.
    pub gpu_ms: f64,
}

/// Renders a scene frame after frame: owns the executor, the scene on the GPU, the camera and
/// accumulation state.
pub struct Renderer {
    ctx: Context,
    executor: Executor,
    scene: Scene,
    flat: FlatScene,
    dynamic: Vec<bool>,
    bvh: Bvh,
    gpu: GpuScene,
    buffers: SceneBuffers,
    spec: Specialization,
    camera: Camera,
    prev_camera: GpuCamera,
    prev_transforms: Vec<[[f32; 4]; 3]>,
    settings: Settings,
    width: u32,
    height: u32,
    accumulated: u32,
    /// The scene or the light transport changed since the last frame was added (the light
    /// transport then replays paths for SVGF's temporal gradients; in a static scene they are
    /// exactly zero).
    scene_changed: bool,
    /// The stratum of the path replay of the last frame added (0: none).
    prev_replay_stratum: u32,
    frame_index: u32,
    pending_stats: Option<(FrameId, ReadbackId)>,
    stats: FrameStats,
    network: neural::Network,
    /// This renderer's number: its denoisers' history keys carry it, so no two renderers'
    /// histories share a key.
    instance: u32,
    denoiser: Option<ActiveDenoiser>,
    /// The BVH layout asked for with [`Renderer::set_bvh_layout`]; `None`: [`automatic_layout`].
    requested_layout: Option<BvhLayout>,
}

/// The denoiser of [`Settings::denoiser`], built when the denoiser changes (the one place that
/// maps the settings' choice to an implementation of [`FrameDenoiser`]).
#[derive(Clone)]
enum ActiveDenoiser {
    Svgf(svgf::SvgfDenoiser),
    Neural(neural::NeuralDenoiser),
}

impl ActiveDenoiser {
    fn new(settings: &Settings, network: &neural::Network, instance: u32) -> Option<Self> {
        match settings.denoiser {
            Denoiser::None => None,
            Denoiser::Svgf => Some(Self::Svgf(svgf::SvgfDenoiser::new(
                settings.svgf,
                &format!("svgf.{instance}"),
            ))),
            Denoiser::Neural => Some(Self::Neural(neural::NeuralDenoiser::new(
                network.clone(),
                settings.neural,
                &format!("neural.{instance}"),
            ))),
        }
    }

    fn get(&mut self) -> &mut dyn FrameDenoiser {
        match self {
            Self::Svgf(d) => d,
            Self::Neural(d) => d,
        }
    }
}

/// Numbers the renderers of this process.
static INSTANCES: std::sync::atomic::AtomicU32 = std::sync::atomic::AtomicU32::new(0);

impl Renderer {
    /// Validates `scene`, builds its BVH, uploads it (in the [`automatic_layout`] for `settings`)
    /// and prepares rendering at `width`×`height`.
    pub fn new(
        ctx: &Context,
        mut scene: Scene,
        width: u32,
        height: u32,
        settings: Settings,
    ) -> Result<Self> {
        check_size(width, height)?;
        scene
            .validate()
            .map_err(|e| EngineError::InvalidArgument(format!("scene {}: {e}", scene.name)))?;
        let flat = FlatScene::new(&scene, &[]);
        let flat_len = scene.instances.len();
        check_scene_fits(ctx, &flat.scene)?;
        let bvh = Bvh::build(&flat.scene);
        let (gpu, triangle_ids) = pack_flat(&flat, &scene, &bvh, BvhLayout::default());
        check_depths(&scene, &gpu)?;
        let buffers = SceneBuffers::upload(ctx, &gpu, &triangle_ids)?;
        let spec = specialization(&gpu);
        let library = ShaderLibrary::new(ctx, None)?;
        let network = neural::Network::new(ctx, &neural::NetworkWeights::builtin())?;
        let instance = INSTANCES.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let camera = scene.camera;
        let mut renderer = Self {
            ctx: ctx.clone(),
            executor: Executor::new(ctx, library)?,
            prev_camera: gpu::camera(&camera),
            prev_transforms: transform_rows(&scene),
            camera,
            scene,
            dynamic: vec![false; flat_len],
            flat,
            bvh,
            gpu,
            buffers,
            spec,
            settings,
            width,
            height,
            accumulated: 0,
            scene_changed: false,
            prev_replay_stratum: 0,
            frame_index: 0,
            pending_stats: None,
            stats: FrameStats::default(),
            denoiser: ActiveDenoiser::new(&settings, &network, instance),
            network,
            instance,
            requested_layout: None,
        };
        renderer.apply_layout()?;
        Ok(renderer)
    }

    /// The scene being rendered.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The specialization constants derived from the scene's features and its GPU packing.
    pub fn specialization(&self) -> &Specialization {
        &self.spec
    }

    /// The executor (pass timings, shader library, history resets).
    pub fn executor(&self) -> &Executor {
        &self.executor
    }

    /// The executor, to run graphs that [`Renderer::add_frame`] was added to.
    pub fn executor_mut(&mut self) -> &mut Executor {
        &mut self.executor
    }

    /// The current settings.
    pub fn settings(&self) -> &Settings {
        &self.settings
    }

    /// Changes settings; anything but display settings restarts accumulation. Without a layout
    /// asked for, an algorithm whose [`automatic_layout`] differs packs the BVH again.
    ///
    /// ```no_run
    /// # fn demo() -> lucid_engine::Result<()> {
    /// # let mut renderer: lucid_passes::renderer::Renderer = unimplemented!();
    /// use lucid_passes::renderer::{Algorithm, Denoiser, Settings};
    /// renderer.set_settings(Settings {
    ///     algorithm: Algorithm::Bidirectional,
    ///     denoiser: Denoiser::Svgf,
    ///     ..*renderer.settings()
    /// })?;
    /// # Ok(()) }
    /// ```
    pub fn set_settings(&mut self, settings: Settings) -> Result<()> {
        if self.settings.restarts_accumulation(&settings) {
            self.accumulated = 0;
            self.scene_changed = true;
        }
        match &mut self.denoiser {
            Some(ActiveDenoiser::Svgf(svgf)) if settings.denoiser == Denoiser::Svgf => {
                svgf.set_params(settings.svgf);
            }
            Some(ActiveDenoiser::Neural(neural)) if settings.denoiser == Denoiser::Neural => {
                neural.set_params(settings.neural);
            }
            _ if settings.denoiser != self.settings.denoiser => {
                self.denoiser = ActiveDenoiser::new(&settings, &self.network, self.instance);
            }
            _ => {}
        }
        self.settings = settings;
        self.apply_layout()
    }

    /// The camera.
    pub fn camera(&self) -> Camera {
        self.camera
    }

    /// Moves the camera; a change restarts accumulation.
    ///
    /// ```no_run
    /// # fn demo() -> lucid_engine::Result<()> {
    /// # let mut renderer: lucid_passes::renderer::Renderer = unimplemented!();
    /// use glam::Vec3;
    /// use lucid_engine::scene::Camera;
    /// let eye = Vec3::new(0.0, 1.0, 4.0);
    /// renderer.set_camera(Camera::look_at(eye, Vec3::ZERO, Vec3::Y, 45.0));
    /// # Ok(()) }
    /// ```
    pub fn set_camera(&mut self, camera: Camera) {
        if camera != self.camera {
            self.accumulated = 0;
        }
        self.camera = camera;
    }

    /// Starts a new shot: the next frame is not a continuation of the last (a camera cut, a
    /// teleport), so accumulation and every temporal history (SVGF's, the learned denoiser's
    /// recurrent state) start afresh instead of reprojecting what no longer applies.
    ///
    /// ```no_run
    /// # fn demo() -> lucid_engine::Result<()> {
    /// # let mut renderer: lucid_passes::renderer::Renderer = unimplemented!();
    /// # let next_shot = renderer.camera();
    /// renderer.set_camera(next_shot);
    /// renderer.cut();
    /// # Ok(()) }
    /// ```
    pub fn cut(&mut self) {
        self.executor.reset_history();
        self.accumulated = 0;
    }

    /// Output size.
    pub fn size(&self) -> (u32, u32) {
        (self.width, self.height)
    }

    /// Changes the output size (zero sizes are rejected; skip rendering while minimised instead).
    ///
    /// ```no_run
    /// # fn demo() -> lucid_engine::Result<()> {
    /// # let mut renderer: lucid_passes::renderer::Renderer = unimplemented!();
    /// let (width, height) = (1280, 720); // the window's new inner size
    /// if width > 0 && height > 0 {
    ///     renderer.resize(width, height)?;
    /// }
    /// # Ok(()) }
    /// ```
    pub fn resize(&mut self, width: u32, height: u32) -> Result<()> {
        check_size(width, height)?;
        if (width, height) != (self.width, self.height) {
            self.width = width;
            self.height = height;
            self.accumulated = 0;
        }
        Ok(())
    }

    /// Places instance `index` of the scene at `transform`. The first move of an instance takes it out
    /// of the flattened static geometry (a full rebuild, once); later moves rebuild only the top level.
    ///
    /// ```no_run
    /// # fn demo() -> lucid_engine::Result<()> {
    /// # let mut renderer: lucid_passes::renderer::Renderer = unimplemented!();
    /// use glam::{Affine3A, Vec3};
    /// renderer.set_instance_transform(0, Affine3A::from_translation(Vec3::new(0.1, 0.0, 0.0)))?;
    /// # Ok(()) }
    /// ```
    pub fn set_instance_transform(
        &mut self,
        index: usize,
        transform: glam::Affine3A,
    ) -> Result<()> {
        let instance = self.scene.instances.get_mut(index).ok_or_else(|| {
            EngineError::InvalidArgument(format!("scene has no instance {index}"))
        })?;
        instance.transform = transform;
        self.accumulated = 0;
        self.scene_changed = true;
        match self.flat.instance_of(index) {
            Some(flat_index) => {
                self.flat.scene.instances[flat_index].transform = transform;
                self.bvh
                    .rebuild_top_level(&self.flat.scene)
                    .map_err(|e| EngineError::InvalidArgument(e.to_string()))?;
                apply_flattening(&mut self.gpu, &self.flat, &self.scene, &self.bvh);
                check_depths(&self.scene, &self.gpu)?;
                self.spec = specialization(&self.gpu);
                self.buffers.update_top_level(&self.ctx, &self.gpu)
            }
            None => {
                self.dynamic[index] = true;
                self.rebuild_gpu_scene()
            }
        }
    }

    /// Replaces material `index` of the scene (e.g. switches a light off); restarts accumulation.
    ///
    /// ```no_run
    /// # fn demo() -> lucid_engine::Result<()> {
    /// # let mut renderer: lucid_passes::renderer::Renderer = unimplemented!();
    /// use glam::Vec3;
    /// use lucid_engine::scene::Material;
    /// renderer.set_material(0, Material::diffuse("light off", Vec3::splat(0.8)))?;
    /// # Ok(()) }
    /// ```
    pub fn set_material(&mut self, index: usize, material: Material) -> Result<()> {
        let slot = self.scene.materials.get_mut(index).ok_or_else(|| {
            EngineError::InvalidArgument(format!("scene has no material {index}"))
        })?;
        *slot = material.clone();
        self.accumulated = 0;
        self.scene_changed = true;
        // Flattening does not depend on materials (emitters are merged too): the geometry stays;
        // the materials, and the light list built from the original scene, are packed again.
        self.flat.scene.materials[index] = material;
        self.gpu.update_materials(&self.flat.scene);
        apply_flattening(&mut self.gpu, &self.flat, &self.scene, &self.bvh);
        self.buffers.update_materials(&self.ctx, &self.gpu)?;
        self.spec = specialization(&self.gpu);
        Ok(())
    }

    /// The layout of the BVH nodes on the GPU.
    pub fn bvh_layout(&self) -> BvhLayout {
        self.gpu.layout()
    }

    /// The scene as packed for the GPU (its buffers' sizes: [`GpuScene::bytes_per_triangle`], ...).
    pub fn gpu_scene(&self) -> &GpuScene {
        &self.gpu
    }

    /// Packs and uploads the BVH in `layout`, or with `None` in the [`automatic_layout`] of each
    /// algorithm from then on (frames in flight keep the old buffers); a new layout restarts
    /// accumulation. The image stays the same up to how rays graze box edges: both layouts find
    /// the same closest hits.
    ///
    /// ```no_run
    /// # fn demo() -> lucid_engine::Result<()> {
    /// # let mut renderer: lucid_passes::renderer::Renderer = unimplemented!();
    /// use lucid_engine::scene::gpu::BvhLayout;
    /// renderer.set_bvh_layout(Some(BvhLayout::Binary))?;
    /// # Ok(()) }
    /// ```
    pub fn set_bvh_layout(&mut self, layout: Option<BvhLayout>) -> Result<()> {
        self.requested_layout = layout;
        self.apply_layout()
    }

    /// Packs the BVH again where the layout asked for, or else the automatic one, is not the
    /// current one.
    fn apply_layout(&mut self) -> Result<()> {
        let layout = self
            .requested_layout
            .unwrap_or_else(|| automatic_layout(self.settings.algorithm, &self.gpu));
        if layout != self.gpu.layout() {
            self.upload_gpu_scene(layout)?;
            self.accumulated = 0;
            self.scene_changed = true;
        }
        Ok(())
    }

    /// Flattens, builds and uploads the scene again (frames in flight keep the old buffers).
    fn rebuild_gpu_scene(&mut self) -> Result<()> {
        let flat = FlatScene::new(&self.scene, &self.dynamic);
        check_scene_fits(&self.ctx, &flat.scene)?;
        self.flat = flat;
        self.bvh = Bvh::build(&self.flat.scene);
        self.upload_gpu_scene(self.gpu.layout())?;
        self.apply_layout()
    }

    /// Packs the flattened scene and its BVH in `layout` and uploads it.
    fn upload_gpu_scene(&mut self, layout: BvhLayout) -> Result<()> {
        let (gpu, triangle_ids) = pack_flat(&self.flat, &self.scene, &self.bvh, layout);
        check_depths(&self.scene, &gpu)?;
        self.buffers = SceneBuffers::upload(&self.ctx, &gpu, &triangle_ids)?;
        self.spec = specialization(&gpu);
        self.gpu = gpu;
        Ok(())
    }

    /// Replaces the learned denoiser's network: `weights` (e.g. `NetworkWeights::load` of a file
    /// that `training/train.py` wrote) run on `path`; its history restarts. An error when the
    /// device cannot run `path`.
    pub fn set_neural_network(
        &mut self,
        weights: &neural::NetworkWeights,
        path: neural::InferencePath,
    ) -> Result<()> {
        self.network = neural::Network::with_path(&self.ctx, weights, path)?;
        if self.settings.denoiser == Denoiser::Neural {
            self.denoiser = ActiveDenoiser::new(&self.settings, &self.network, self.instance);
        }
        self.scene_changed = true;
        Ok(())
    }

    /// The path the learned denoiser's convolutions take.
    pub fn neural_path(&self) -> neural::InferencePath {
        self.network.path()
    }

    /// What the learned denoiser's last layers predict.
    pub fn neural_decoder(&self) -> neural::Decoder {
        self.network.decoder()
    }

    /// Frames averaged into the current output.
    pub fn accumulated_frames(&self) -> u32 {
        self.accumulated
    }

    /// Counts from the last completed frame.
    ///
    /// ```no_run
    /// # fn demo() -> lucid_engine::Result<()> {
    /// # let mut renderer: lucid_passes::renderer::Renderer = unimplemented!();
    /// renderer.render_and_read()?;
    /// let stats = renderer.stats();
    /// println!("{} rays, {} NaN/Inf samples dropped", stats.rays, stats.non_finite_samples);
    /// # Ok(()) }
    /// ```
    pub fn stats(&self) -> FrameStats {
        self.stats
    }

    /// Adds this frame's passes to `g` and advances the frame state; run `g` on
    /// [`Renderer::executor_mut`]. Returns the frame's images and the stats readback.
    ///
    /// ```no_run
    /// # fn demo() -> lucid_engine::Result<()> {
    /// # let mut renderer: lucid_passes::renderer::Renderer = unimplemented!();
    /// use lucid_engine::graph::RenderGraph;
    /// let mut g = RenderGraph::new();
    /// let (images, stats) = renderer.add_frame(&mut g);
    /// let shown = g.readback(images.ldr); // or add passes of your own that read images.hdr
    /// let frame = renderer.executor_mut().execute(g.compile()?)?;
    /// let outputs = renderer.executor_mut().wait(frame)?;
    /// renderer.collect_stats(&outputs, stats)?;
    /// let ldr = outputs.image(shown)?;
    /// # Ok(()) }
    /// ```
    pub fn add_frame(&mut self, g: &mut RenderGraph) -> (FrameImages, ReadbackId) {
        let (w, h) = (self.width, self.height);
        let camera = gpu::camera(&self.camera);
        let scene_changed = std::mem::take(&mut self.scene_changed);
        let accumulated = if self.settings.accumulate {
            self.accumulated
        } else {
            0
        };
        let constants = FrameConstants {
            camera,
            prev_camera: self.prev_camera,
            frame_index: self.frame_index,
            seed: self.settings.seed,
            samples_per_pixel: self.settings.samples_per_pixel.get(),
            max_depth: self.settings.max_depth,
            width: w,
            height: h,
            accumulated,
            rr_depth: self.settings.rr_depth,
            padding: [0; 4],
        };
        let frame = frame_constants::add_frame_constants(g, &constants);
        let scene = self.buffers.import(g);
        let prev_transforms = add_prev_transforms(g, &self.prev_transforms);
        let gbuffer = gbuffer::add_gbuffer(g, &scene, frame, prev_transforms, &self.spec, w, h);
        let info = FrameInfo {
            frame_index: self.frame_index,
            accumulated_frames: accumulated,
            samples_per_pixel: self.settings.samples_per_pixel,
            scene_changed,
            replays_paths: self.settings.algorithm.replays_paths(),
        };
        let planned = self.denoiser.as_mut().and_then(|d| {
            let denoiser = d.get();
            let request = denoiser.plan(&info)?;
            if scene_changed {
                for key in denoiser.reset_on_scene_change() {
                    self.executor.reset_history_key(&key);
                }
            }
            Some(request)
        });
        let replay = ReplayParams {
            stratum: planned.map_or(0, |r| r.replay_stratum),
            prev_stratum: self.prev_replay_stratum,
        };
        // The denoiser's images are traced only for a denoiser.
        let surface = planned.is_some();
        let traced = self.add_transport(g, &scene, frame, (&gbuffer, replay), surface);
        // Without accumulation the frame's radiance is its HDR image: no pass copies it.
        let hdr = if self.settings.accumulate {
            accumulate::add_accumulate(g, traced.radiance, w, h, accumulated)
        } else {
            traced.radiance
        };
        let denoised = match (self.denoiser.as_mut(), traced.surface) {
            (Some(denoiser), Some(surface)) if planned.is_some() => {
                let surface = if self.settings.supersamples_edges() {
                    let spec = &self.spec;
                    let images = (&gbuffer, surface);
                    edge_emission::add_edge_emission(g, &scene, frame, images, spec, (w, h))
                } else {
                    surface
                };
                let inputs = DenoiseInputs {
                    radiance: traced.radiance,
                    surface,
                    accumulated: hdr,
                    accumulated_frames: accumulated,
                    accumulating: self.settings.accumulate,
                    replay,
                    frame_index: self.frame_index,
                    gbuffer,
                    width: w,
                    height: h,
                };
                denoiser.get().add(g, &inputs)
            }
            _ => Denoised::image(hdr),
        };
        let hdr = denoised.image;
        let ldr = tonemap::add_tonemap(g, hdr, w, h, self.settings.display);
        let stats = g.readback(traced.stats);
        self.prev_camera = camera;
        self.prev_replay_stratum = replay.stratum;
        self.prev_transforms = transform_rows(&self.scene);
        self.frame_index = self.frame_index.wrapping_add(1);
        self.accumulated = if self.settings.accumulate {
            accumulated.saturating_add(1)
        } else {
            0
        };
        (
            FrameImages {
                radiance: traced.radiance,
                demodulated: traced.surface.map(|s| s.demodulated),
                gradient: denoised.gradient,
                neural_record: denoised.record,
                hdr,
                ldr,
                gbuffer,
            },
            stats,
        )
    }

    /// Adds this frame's light transport: path tracing, megakernel or wavefront (replaying last
    /// frame's paths as `replay` asks, for the denoiser), or bidirectional path tracing; the
    /// denoiser's images when `surface`.
    fn add_transport(
        &self,
        g: &mut RenderGraph,
        scene: &SceneHandles,
        frame: BufferHandle,
        (gbuffer, replay): (&GBuffer, ReplayParams),
        surface: bool,
    ) -> light_transport::Outputs {
        let sampling = light_transport::Frame {
            width: self.width,
            height: self.height,
            samples_per_pixel: self.settings.samples_per_pixel,
            max_depth: self.settings.max_depth,
            surface,
        };
        // Replay serves the denoiser; without one the path tracers need no G-buffer.
        let replay = (surface && self.settings.algorithm.replays_paths()).then_some(Replay {
            params: replay,
            motion: gbuffer.motion,
        });
        match self.settings.algorithm {
            Algorithm::PathTracing => {
                let config = path_trace::Config {
                    park_depth: self.park_depth(),
                };
                let inputs = (scene, frame, &self.spec);
                path_trace::add_path_trace(g, inputs, replay.as_ref(), sampling, &config)
            }
            Algorithm::PathTracingWavefront | Algorithm::PathTracingWavefrontBinned => {
                let config = wavefront::Config {
                    bin_by_material: self.settings.algorithm
                        == Algorithm::PathTracingWavefrontBinned,
                };
                let inputs = (scene, frame, &self.spec);
                wavefront::add_wavefront(g, inputs, replay.as_ref(), sampling, &config)
            }
            Algorithm::Bidirectional => bdpt::add_bdpt(
                g,
                scene,
                frame,
                &self.spec,
                sampling,
                &bdpt::Config {
                    park_depth: self.park_depth(),
                    connections: self.settings.bdpt_connections,
                    heuristic: self.settings.bdpt_mis,
                    connection_roulette: self.settings.bdpt_connection_roulette,
                    pair_shadow_rays: bdpt::pairs_shadow_rays(&self.gpu.features),
                    ..bdpt::Config::default()
                },
            ),
        }
    }

    /// After how many segments the path tracers park their long paths: Russian roulette's start,
    /// when the settings ask for parking.
    fn park_depth(&self) -> Option<u32> {
        self.settings
            .park_long_paths
            .then_some(self.settings.rr_depth)
    }

    /// The compiled plan of the next frame (passes, barriers, lifetimes, aliasing), without rendering
    /// it or changing any state.
    ///
    /// ```no_run
    /// # fn demo() -> lucid_engine::Result<()> {
    /// # let mut renderer: lucid_passes::renderer::Renderer = unimplemented!();
    /// let plan = renderer.frame_plan()?;
    /// println!("{}", plan.dump());
    /// # Ok(()) }
    /// ```
    pub fn frame_plan(&mut self) -> Result<lucid_engine::graph::Plan> {
        let saved = (
            self.prev_camera,
            self.prev_transforms.clone(),
            self.frame_index,
            self.accumulated,
            self.scene_changed,
            self.prev_replay_stratum,
            self.denoiser.clone(),
        );
        let mut g = RenderGraph::new();
        self.add_frame(&mut g);
        (
            self.prev_camera,
            self.prev_transforms,
            self.frame_index,
            self.accumulated,
            self.scene_changed,
            self.prev_replay_stratum,
            self.denoiser,
        ) = saved;
        Ok(g.compile()?.plan)
    }

    /// Records the stats of a finished frame; fails when the device cut the loops of any pixel
    /// short (its image would be wrong).
    pub fn collect_stats(
        &mut self,
        outputs: &lucid_engine::graph::FrameOutputs,
        stats: ReadbackId,
    ) -> Result<()> {
        let words: Vec<u32> = bytemuck::pod_collect_to_vec(outputs.bytes(stats)?);
        let (dropped, rays, cut_short) = (words[0], words[1], words[2]);
        if cut_short > 0 {
            return Err(EngineError::Shader {
                shader: format!("{:?} light transport", self.settings.algorithm),
                message: format!(
                    "the device ended the loops of {cut_short} pixels early (llvmpipe stops a \
                     shader invocation after 65535 loop iterations), so the frame would be wrong: \
                     lower --max-depth, or use a GPU"
                ),
            });
        }
        if dropped > 0 {
            tracing::warn!("{dropped} non-finite samples dropped this frame");
        }
        self.stats = FrameStats {
            non_finite_samples: dropped,
            rays,
            gpu_ms: outputs.timings.iter().map(|t| t.ms).sum(),
        };
        Ok(())
    }

    /// Renders one frame without waiting for it (frames in flight); stats of finished frames are
    /// collected as they complete.
    ///
    /// ```no_run
    /// # fn demo() -> lucid_engine::Result<()> {
    /// # let mut renderer: lucid_passes::renderer::Renderer = unimplemented!();
    /// for _ in 0..60 {
    ///     renderer.render()?;
    /// }
    /// renderer.finish()?;
    /// # Ok(()) }
    /// ```
    pub fn render(&mut self) -> Result<FrameId> {
        let mut g = RenderGraph::new();
        let (_, stats) = self.add_frame(&mut g);
        let frame = self.executor.execute(g.compile()?)?;
        self.buffers.submitted();
        if let Some((old, old_stats)) = self.pending_stats.replace((frame, stats)) {
            let outputs = self.executor.wait(old)?;
            self.collect_stats(&outputs, old_stats)?;
        }
        Ok(frame)
    }

    /// Renders one frame, waits for it and returns its HDR output (the accumulated image when
    /// accumulation is on).
    ///
    /// ```no_run
    /// # fn demo() -> lucid_engine::Result<()> {
    /// # let mut renderer: lucid_passes::renderer::Renderer = unimplemented!();
    /// let hdr = renderer.render_and_read()?;
    /// println!("{}x{} linear RGBA pixels", hdr.width, hdr.height);
    /// # Ok(()) }
    /// ```
    pub fn render_and_read(&mut self) -> Result<ImageData> {
        Ok(self.render_and_read_with_record(false)?.0)
    }

    /// Renders one frame, waits for it and returns its HDR output and the learned denoiser's
    /// per-pixel record of it (planar float channels, see [`neural::add_record`]): what
    /// `lucid dataset` stores and image denoisers take as albedo and normal. An error unless the
    /// learned denoiser runs.
    pub fn render_and_read_record(&mut self) -> Result<(ImageData, Vec<u8>)> {
        let (hdr, record) = self.render_and_read_with_record(true)?;
        Ok((hdr, record.expect("asked for")))
    }

    /// One frame, waited for: its HDR output and, when `with_record`, its record.
    fn render_and_read_with_record(
        &mut self,
        with_record: bool,
    ) -> Result<(ImageData, Option<Vec<u8>>)> {
        let mut g = RenderGraph::new();
        let (images, stats) = self.add_frame(&mut g);
        let hdr = g.readback(images.hdr);
        let record = match (with_record, images.neural_record) {
            (false, _) => None,
            (true, Some(record)) => Some(g.readback(record)),
            (true, None) => {
                return Err(EngineError::InvalidArgument(
                    "the frame has no record: the learned denoiser does not run".into(),
                ))
            }
        };
        let frame = self.executor.execute(g.compile()?)?;
        self.buffers.submitted();
        self.collect_pending_stats()?;
        let outputs = self.executor.wait(frame)?;
        self.collect_stats(&outputs, stats)?;
        let record = match record {
            Some(id) => Some(outputs.bytes(id)?.to_vec()),
            None => None,
        };
        Ok((outputs.image(hdr)?, record))
    }

    /// Waits for the frame whose stats are pending, if any, and records them.
    fn collect_pending_stats(&mut self) -> Result<()> {
        if let Some((old, old_stats)) = self.pending_stats.take() {
            let outputs = self.executor.wait(old)?;
            self.collect_stats(&outputs, old_stats)?;
        }
        Ok(())
    }

    /// Waits for every frame in flight.
    pub fn finish(&mut self) -> Result<()> {
        self.collect_pending_stats()?;
        self.executor.wait_all()
    }
}

/// Object-to-world rows of every scene instance (what the G-buffer needs of last frame).
fn transform_rows(scene: &Scene) -> Vec<[[f32; 4]; 3]> {
    scene
        .instances
        .iter()
        .map(|i| {
            let m = glam::Mat4::from(i.transform);
            [
                m.row(0).to_array(),
                m.row(1).to_array(),
                m.row(2).to_array(),
            ]
        })
        .collect()
}

/// A pass writing last frame's instance transforms into a transient buffer (culled with the
/// G-buffer when nothing reads it).
fn add_prev_transforms(
    g: &mut RenderGraph,
    rows: &[[[f32; 4]; 3]],
) -> lucid_engine::graph::BufferHandle {
    let data: Vec<u8> = if rows.is_empty() {
        vec![0; 48]
    } else {
        bytemuck::cast_slice(rows).to_vec()
    };
    let mut p = g.add_pass("prev_transforms");
    let buffer = p.create_buffer("prev_transforms", data.len() as u64);
    let buffer = p.write(buffer, lucid_engine::graph::Access::TransferWrite);
    p.execute(move |ctx| ctx.update_buffer(buffer, &data));
    buffer
}

/// An error when `scene` (flattened) cannot fit in the device's memory budget, known from its
/// triangle and vertex counts before its BVH is built (which takes a minute and gigabytes of host
/// memory for tens of millions of triangles).
fn check_scene_fits(ctx: &Context, scene: &Scene) -> Result<()> {
    let what = format!(
        "the geometry of scene {} ({} triangles, at least)",
        scene.name,
        scene.unique_triangle_count()
    );
    ctx.check_fits(&what, GpuScene::least_bytes(scene))
}

/// The BVH layout a renderer without one asked for packs `gpu`'s scene in for `algorithm`: the
/// compressed wide one for path tracing a scene that the tracing kernels walk in workgroup memory
/// ([`workgroup_scene_words`]; the Cornell box's path tracer 6% faster on an H200, its BDPT camera
/// pass 15% slower, `bench/README.md`), the binary one otherwise. A scene that fits in the binary
/// layout fits in the wide one (a quarter smaller), so the choice does not flip back and forth.
pub fn automatic_layout(algorithm: Algorithm, gpu: &GpuScene) -> BvhLayout {
    if algorithm == Algorithm::PathTracing && workgroup_scene_words(gpu) != (0, 0) {
        BvhLayout::Wide
    } else {
        BvhLayout::Binary
    }
}

/// An error when the packed BVH of `scene` is deeper than the GPU traversal can walk.
fn check_depths(scene: &Scene, gpu: &GpuScene) -> Result<()> {
    gpu.check_depths()
        .map_err(|e| EngineError::InvalidArgument(format!("scene {}: {e}", scene.name)))
}

fn check_size(width: u32, height: u32) -> Result<()> {
    if width == 0 || height == 0 {
        return Err(EngineError::InvalidArgument(format!(
            "render size {width}x{height} is empty"
        )));
    }
    Ok(())
}
