//! Non-geometric lights: punctual lights, the sun and the environment.
//!
//! Area lights are not listed here: every triangle or sphere whose
//! material emits is an area light (see [`super::LightDistribution`]).
//!
//! Point and spot lights are delta lights: a path can never hit them, so
//! they contribute only through next-event estimation. NEE picks them from
//! the light distribution like any area light and evaluates
//! `intensity / distance²` (times the spot falloff) with a pdf of the
//! selection probability alone.
//!
//! Units are radiometric (W/sr, W/m², W/(m²·sr)) per RGB channel. glTF's
//! photometric units convert with [`LUMENS_PER_WATT`]: an RGB value of 1 on
//! every channel is 683 lumens per watt's worth, so a white point light of
//! `I` candela has a radiant intensity of `I / 683` W/sr per channel, and a
//! coloured one `colour × I / 683` (the convention of Blender's glTF
//! exporter and of three.js and Filament, which multiply the colour by the
//! intensity; its luminous intensity is then `I × luminance(colour)`).

use glam::Vec3;

/// Luminous efficacy (lm/W) that turns photometric light units into Lucid's radiometric RGB:
/// the maximum efficacy, that of 555 nm light, which the SI's definition of the candela uses.
pub const LUMENS_PER_WATT: f32 = 683.0;

/// A point or spot light (from `KHR_lights_punctual`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PunctualLight {
    /// Isotropic point light.
    Point {
        /// World position.
        position: Vec3,
        /// Radiant intensity per channel (W/sr).
        intensity: Vec3,
    },
    /// Spot light with a smooth falloff between the cone angles.
    Spot {
        /// World position.
        position: Vec3,
        /// Unit direction the spot points to.
        direction: Vec3,
        /// Radiant intensity per channel on the axis (W/sr).
        intensity: Vec3,
        /// Angle (radians) within which intensity is full.
        inner_angle: f32,
        /// Angle (radians) beyond which intensity is zero.
        outer_angle: f32,
    },
}

impl PunctualLight {
    /// Total emitted power (W) on the strongest channel (see
    /// [`super::light_list::selection_power`]).
    pub fn power(&self) -> f32 {
        let strength = super::light_list::selection_power;
        match *self {
            PunctualLight::Point { intensity, .. } => {
                4.0 * std::f32::consts::PI * strength(intensity)
            }
            PunctualLight::Spot {
                intensity,
                inner_angle,
                outer_angle,
                ..
            } => {
                // Solid angle of the cone at the mean of the two angles.
                let cos_mid = (0.5 * (inner_angle + outer_angle)).cos();
                2.0 * std::f32::consts::PI * (1.0 - cos_mid) * strength(intensity)
            }
        }
    }
}

/// A distant directional light with a small angular radius.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sun {
    /// Unit direction from the scene towards the sun.
    pub direction: Vec3,
    /// Irradiance per channel on a surface facing the sun (W/m²).
    pub irradiance: Vec3,
    /// Angular radius of the sun disc in radians (0.00465 for the real sun).
    pub angular_radius: f32,
}

impl Sun {
    /// Radiance of the sun disc: irradiance over the disc's solid angle
    /// (projected, small-angle).
    pub fn radiance(&self) -> Vec3 {
        let s = self.angular_radius.sin();
        self.irradiance / (std::f32::consts::PI * s * s).max(f32::MIN_POSITIVE)
    }
}

/// Light arriving from infinitely far away in every direction.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Environment {
    /// Uniform radiance from all directions (black = no environment).
    Constant(Vec3),
    /// A simple sky: radiance blends from `horizon` to `zenith` over the
    /// upper hemisphere (`y > 0`, by `sqrt(y)`) and is `ground` below.
    Sky {
        /// Radiance straight up.
        zenith: Vec3,
        /// Radiance at the horizon.
        horizon: Vec3,
        /// Radiance of every downward direction.
        ground: Vec3,
    },
    /// An equirectangular map of radiance ([`super::environment_map`]): scene texture `texture`
    /// (linear), importance sampled by next-event estimation.
    Map {
        /// The scene texture holding the map.
        texture: u32,
    },
}

impl Environment {
    /// The neutral sky a scene without any light gets (glTF import): a pale, nearly white
    /// gradient of radiance about 1 above the horizon and a grey ground, so that a white
    /// Lambertian surface facing up comes out at about its albedo.
    pub const NEUTRAL_SKY: Environment = Environment::Sky {
        zenith: Vec3::new(0.8, 0.85, 0.95),
        horizon: Vec3::new(1.0, 1.0, 1.0),
        ground: Vec3::new(0.3, 0.28, 0.25),
    };

    /// Whether any direction has non-zero radiance.
    pub fn is_black(&self) -> bool {
        match *self {
            Environment::Constant(c) => c.max_element() <= 0.0,
            Environment::Sky {
                zenith,
                horizon,
                ground,
            } => zenith.max(horizon).max(ground).max_element() <= 0.0,
            Environment::Map { .. } => false,
        }
    }
}

/// Rec. 709 luminance of a linear RGB value.
pub fn luminance(c: Vec3) -> f32 {
    c.dot(Vec3::new(0.2126, 0.7152, 0.0722))
}
