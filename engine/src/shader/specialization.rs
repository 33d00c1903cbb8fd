//! Specialization constants set by name, turned into Vulkan specialization info through reflection.

use super::reflect::{Reflection, SpecType};
use ash::vk;

/// A specialization-constant value.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SpecValue {
    /// A `bool` constant.
    Bool(bool),
    /// An `int` constant.
    I32(i32),
    /// A `uint` constant.
    U32(u32),
    /// A `float` constant.
    F32(f32),
}

impl SpecValue {
    fn bits(self) -> u32 {
        match self {
            Self::Bool(b) => b as u32,
            Self::I32(v) => v as u32,
            Self::U32(v) => v,
            Self::F32(v) => v.to_bits(),
        }
    }

    fn matches(self, ty: SpecType) -> bool {
        matches!(
            (self, ty),
            (Self::Bool(_), SpecType::Bool)
                | (Self::I32(_), SpecType::I32)
                | (Self::U32(_), SpecType::U32)
                | (Self::F32(_), SpecType::F32)
        )
    }
}

impl From<bool> for SpecValue {
    fn from(v: bool) -> Self {
        Self::Bool(v)
    }
}
impl From<u32> for SpecValue {
    fn from(v: u32) -> Self {
        Self::U32(v)
    }
}
impl From<i32> for SpecValue {
    fn from(v: i32) -> Self {
        Self::I32(v)
    }
}
impl From<f32> for SpecValue {
    fn from(v: f32) -> Self {
        Self::F32(v)
    }
}

/// A set of specialization constants by name (e.g. `HAS_DIELECTRIC = false`).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Specialization {
    values: Vec<(String, SpecValue)>,
}

impl Specialization {
    /// No specialization: every constant keeps its default.
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets `name` to `value` (replacing an earlier value).
    pub fn set(mut self, name: &str, value: impl Into<SpecValue>) -> Self {
        let value = value.into();
        match self.values.iter_mut().find(|(n, _)| n == name) {
            Some(slot) => slot.1 = value,
            None => self.values.push((name.to_string(), value)),
        }
        self
    }

    /// The value set for `name`, if any.
    pub fn get(&self, name: &str) -> Option<SpecValue> {
        self.values.iter().find(|(n, _)| n == name).map(|(_, v)| *v)
    }

    /// The values set, in the order they were set.
    pub fn values(&self) -> &[(String, SpecValue)] {
        &self.values
    }

    /// Resolves names against `reflection`: (constant id, bits), sorted by id. Unknown names and
    /// values of the wrong type are errors naming the constants the shader has.
    pub fn resolve(&self, reflection: &Reflection) -> Result<Vec<(u32, u32)>, String> {
        let mut out = Vec::with_capacity(self.values.len());
        for (name, value) in &self.values {
            let info = reflection.spec_constant(name).ok_or_else(|| {
                let known: Vec<&str> = reflection
                    .spec_constants
                    .iter()
                    .map(|s| s.name.as_str())
                    .collect();
                format!("has no specialization constant {name:?} (it has: {known:?})")
            })?;
            if !value.matches(info.ty) {
                return Err(format!(
                    "specialization constant {name:?} is {:?}, not {value:?}",
                    info.ty
                ));
            }
            out.push((info.id, value.bits()));
        }
        out.sort_by_key(|&(id, _)| id);
        Ok(out)
    }

    /// The workgroup size after applying resolved constants to the reflected defaults.
    pub fn workgroup_size(reflection: &Reflection, resolved: &[(u32, u32)]) -> [u32; 3] {
        let mut size = reflection.workgroup_size;
        for (axis, id) in reflection.workgroup_size_ids.iter().enumerate() {
            if let Some(&(_, bits)) = id.and_then(|id| resolved.iter().find(|(i, _)| *i == id)) {
                size[axis] = bits.max(1);
            }
        }
        size
    }
}

/// Map entries and data for `resolved` constants (4 bytes each).
pub(crate) fn map_entries(resolved: &[(u32, u32)]) -> (Vec<vk::SpecializationMapEntry>, Vec<u8>) {
    let entries = resolved
        .iter()
        .enumerate()
        .map(|(i, &(id, _))| vk::SpecializationMapEntry {
            constant_id: id,
            offset: (i * 4) as u32,
            size: 4,
        })
        .collect();
    let data = resolved
        .iter()
        .flat_map(|&(_, bits)| bits.to_le_bytes())
        .collect();
    (entries, data)
}
