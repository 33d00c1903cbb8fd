//! What a file uses that Lucid does not render, collected while importing and reported once per
//! feature per file: the feature, what is done instead, how many of the file's materials,
//! primitives, nodes, ... use it, and the first of them.

use std::collections::BTreeMap;

/// A glTF feature the importer ignores or approximates.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Feature {
    /// `pbrMetallicRoughness.metallicRoughnessTexture` on a transmissive material.
    MetallicRoughnessTexture,
    /// A `KHR_materials_transmission` factor strictly between 0 and 1, or its texture.
    PartialTransmission,
    /// `KHR_materials_specular`'s textures.
    SpecularTextures,
    /// A texture read through `TEXCOORD_n`, n > 0 (by its `texCoord` or its
    /// `KHR_texture_transform`'s).
    OtherTexCoords,
    /// Point and line primitives.
    PointsAndLines,
    /// Morph targets.
    MorphTargets,
    /// Skins.
    Skins,
    /// Animations.
    Animations,
    /// Orthographic cameras.
    OrthographicCamera,
    /// A directional light after the first.
    ExtraDirectionalLight,
    /// A punctual light's `range`.
    LightRange,
}

impl Feature {
    /// The feature and what happens instead.
    fn describe(self) -> &'static str {
        match self {
            Feature::MetallicRoughnessTexture => {
                "metallic-roughness textures on transmissive materials are not supported: their \
                 roughness factor alone is used"
            }
            Feature::PartialTransmission => {
                "partial transmission (a transmission factor below 1, or a transmission texture) \
                 is not supported: the material is fully transmissive"
            }
            Feature::SpecularTextures => {
                "KHR_materials_specular textures are not supported: its factors alone are used"
            }
            Feature::OtherTexCoords => {
                "texture coordinates other than TEXCOORD_0 are not supported: TEXCOORD_0 is used"
            }
            Feature::PointsAndLines => {
                "point and line primitives are not supported (only triangles, triangle strips \
                 and triangle fans): they are skipped"
            }
            Feature::MorphTargets => {
                "morph targets are not supported: meshes keep their base shape"
            }
            Feature::Skins => "skins are not supported: skinned meshes keep their bind pose",
            Feature::Animations => "animations are not supported: the scene is shown at rest",
            Feature::OrthographicCamera => {
                "orthographic cameras are not supported: they are ignored"
            }
            Feature::ExtraDirectionalLight => {
                "only one directional light is supported: the others are ignored"
            }
            Feature::LightRange => {
                "light ranges are not supported: lights fall off with the inverse square of the \
                 distance without a cut-off"
            }
        }
    }
}

/// The unsupported features one file uses.
#[derive(Debug, Default)]
pub struct Unsupported {
    /// Per feature: how many users, the first and the last user, and what kind of thing users
    /// are.
    seen: BTreeMap<Feature, Users>,
}

#[derive(Debug)]
struct Users {
    count: usize,
    first: String,
    last: String,
    kind: &'static str,
}

impl Unsupported {
    /// Records that `user` (e.g. "material `brick`"), one of the file's `kind` (plural, e.g.
    /// "materials"), uses `feature` (a user noted twice in a row counts once).
    pub fn note(&mut self, feature: Feature, kind: &'static str, user: impl FnOnce() -> String) {
        let user = user();
        match self.seen.get_mut(&feature) {
            Some(u) if u.last == user => {}
            Some(u) => {
                u.count += 1;
                u.last = user;
            }
            None => {
                self.seen.insert(
                    feature,
                    Users {
                        count: 1,
                        first: user.clone(),
                        last: user,
                        kind,
                    },
                );
            }
        }
    }

    /// One warning per feature, naming the file `label`.
    pub fn warnings(&self, label: &str) -> Vec<String> {
        self.seen
            .iter()
            .map(|(feature, u)| {
                let users = if u.count == 1 {
                    u.first.clone()
                } else {
                    format!("{} {}, the first {}", u.count, u.kind, u.first)
                };
                format!("{label}: {} ({users})", feature.describe())
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_warning_per_feature_with_a_count() {
        let mut u = Unsupported::default();
        for name in ["a", "b", "b", "c"] {
            u.note(Feature::PartialTransmission, "materials", || {
                format!("material `{name}`")
            });
        }
        u.note(Feature::Animations, "animations", || "animation 0".into());
        let w = u.warnings("f.gltf");
        assert_eq!(w.len(), 2);
        assert!(w[0].starts_with("f.gltf: partial transmission"), "{w:?}");
        assert!(
            w[0].ends_with("(3 materials, the first material `a`)"),
            "{w:?}"
        );
        assert!(w[1].ends_with("(animation 0)"), "{w:?}");
    }
}
