//! SPIR-V reflection with rspirv: descriptor bindings by name, push-constant size, workgroup size and
//! specialization constants of a compute shader.

use rspirv::dr::{Instruction, Module, Operand};
use rspirv::spirv::{BuiltIn, Decoration, ExecutionMode, Op, StorageClass};
use std::collections::HashMap;

/// The kind of resource a binding expects.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum DescriptorKind {
    /// `image2D` etc. with a format: read and written with imageLoad/imageStore.
    StorageImage,
    /// `sampler2D`: a combined image sampler, read with texture().
    SampledImage,
    /// A `buffer` block.
    StorageBuffer,
    /// A `uniform` block.
    UniformBuffer,
}

/// One descriptor binding of a shader.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BindingInfo {
    /// The GLSL name of the variable (or of its block type when the variable has no name).
    pub name: String,
    /// The block type's name for buffers (`Data` in `buffer Data { ... } b_data;`).
    pub block_name: Option<String>,
    /// Descriptor set.
    pub set: u32,
    /// Binding number.
    pub binding: u32,
    /// The resource kind.
    pub kind: DescriptorKind,
    /// Array length (1 when not an array).
    pub count: u32,
    /// Whether the shader never writes through it (`readonly` storage, samplers, uniforms).
    pub read_only: bool,
}

/// The value type of a specialization constant.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpecType {
    /// `const bool`.
    Bool,
    /// `const int`.
    I32,
    /// `const uint`.
    U32,
    /// `const float`.
    F32,
}

/// One specialization constant.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SpecConstantInfo {
    /// The GLSL name.
    pub name: String,
    /// The `constant_id`.
    pub id: u32,
    /// Value type.
    pub ty: SpecType,
    /// Default value as 32 raw bits.
    pub default_bits: u32,
}

/// Everything Lucid needs to know about a compute shader's interface.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Reflection {
    /// Descriptor bindings, sorted by (set, binding).
    pub bindings: Vec<BindingInfo>,
    /// Bytes of push constants the shader reads (0 when none).
    pub push_constant_size: u32,
    /// The workgroup size with default specialization values.
    pub workgroup_size: [u32; 3],
    /// The specialization-constant id that sets each workgroup dimension, if any (`local_size_x_id`).
    pub workgroup_size_ids: [Option<u32>; 3],
    /// Specialization constants.
    pub spec_constants: Vec<SpecConstantInfo>,
}

impl Reflection {
    /// The binding named `name` (variable name, or buffer block type name).
    pub fn binding(&self, name: &str) -> Option<&BindingInfo> {
        self.bindings.iter().find(|b| b.name == name).or_else(|| {
            self.bindings
                .iter()
                .find(|b| b.block_name.as_deref() == Some(name))
        })
    }

    /// The specialization constant named `name`.
    pub fn spec_constant(&self, name: &str) -> Option<&SpecConstantInfo> {
        self.spec_constants.iter().find(|s| s.name == name)
    }

    /// The names of all bindings, for error messages.
    pub fn binding_names(&self) -> Vec<&str> {
        self.bindings.iter().map(|b| b.name.as_str()).collect()
    }
}

/// Converts SPIR-V bytes into words, checking size and magic number.
pub fn spirv_words(bytes: &[u8]) -> Result<Vec<u32>, String> {
    if bytes.len() % 4 != 0 || bytes.len() < 20 {
        return Err(format!("{} bytes is not a SPIR-V module", bytes.len()));
    }
    let words: Vec<u32> = bytes
        .chunks_exact(4)
        .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    if words[0] != rspirv::spirv::MAGIC_NUMBER {
        return Err("bad SPIR-V magic number".into());
    }
    Ok(words)
}

/// Reflects a compute shader's SPIR-V words.
pub fn reflect(words: &[u32]) -> Result<Reflection, String> {
    let module = rspirv::dr::load_words(words).map_err(|e| format!("SPIR-V parse error: {e}"))?;
    Reflector::new(&module).run()
}

fn id(op: Option<&Operand>) -> Option<u32> {
    match op? {
        Operand::IdRef(id) => Some(*id),
        _ => None,
    }
}

fn literal(op: Option<&Operand>) -> Option<u32> {
    match op? {
        Operand::LiteralBit32(v) => Some(*v),
        _ => None,
    }
}

struct Reflector<'m> {
    module: &'m Module,
    names: HashMap<u32, String>,
    decorations: HashMap<u32, Vec<(Decoration, Option<u32>)>>,
    member_offsets: HashMap<(u32, u32), u32>,
    member_matrix_strides: HashMap<(u32, u32), u32>,
    member_non_writable: HashMap<u32, Vec<u32>>,
    defs: HashMap<u32, &'m Instruction>,
}

impl<'m> Reflector<'m> {
    fn new(module: &'m Module) -> Self {
        let mut names = HashMap::new();
        for inst in &module.debug_names {
            if inst.class.opcode == Op::Name {
                if let (Some(target), Some(Operand::LiteralString(name))) =
                    (id(inst.operands.first()), inst.operands.get(1))
                {
                    names.insert(target, name.clone());
                }
            }
        }
        let mut decorations: HashMap<u32, Vec<(Decoration, Option<u32>)>> = HashMap::new();
        let mut member_offsets = HashMap::new();
        let mut member_matrix_strides = HashMap::new();
        let mut member_non_writable: HashMap<u32, Vec<u32>> = HashMap::new();
        for inst in &module.annotations {
            match inst.class.opcode {
                Op::Decorate => {
                    if let (Some(target), Some(Operand::Decoration(d))) =
                        (id(inst.operands.first()), inst.operands.get(1))
                    {
                        let value = match inst.operands.get(2) {
                            Some(Operand::LiteralBit32(v)) => Some(*v),
                            Some(Operand::BuiltIn(b)) => Some(*b as u32),
                            _ => None,
                        };
                        decorations.entry(target).or_default().push((*d, value));
                    }
                }
                Op::MemberDecorate => {
                    if let (Some(target), Some(member), Some(Operand::Decoration(d))) = (
                        id(inst.operands.first()),
                        literal(inst.operands.get(1)),
                        inst.operands.get(2),
                    ) {
                        let value = literal(inst.operands.get(3));
                        match (d, value) {
                            (Decoration::Offset, Some(v)) => {
                                member_offsets.insert((target, member), v);
                            }
                            (Decoration::MatrixStride, Some(v)) => {
                                member_matrix_strides.insert((target, member), v);
                            }
                            (Decoration::NonWritable, _) => {
                                member_non_writable.entry(target).or_default().push(member);
                            }
                            _ => {}
                        }
                    }
                }
                _ => {}
            }
        }
        let defs = module
            .types_global_values
            .iter()
            .filter_map(|i| i.result_id.map(|id| (id, i)))
            .collect();
        Self {
            module,
            names,
            decorations,
            member_offsets,
            member_matrix_strides,
            member_non_writable,
            defs,
        }
    }

    fn decoration(&self, target: u32, d: Decoration) -> Option<Option<u32>> {
        self.decorations
            .get(&target)?
            .iter()
            .find(|(dd, _)| *dd == d)
            .map(|(_, v)| *v)
    }

    fn constant_u32(&self, id: u32) -> Option<u32> {
        let def = self.defs.get(&id)?;
        match def.class.opcode {
            Op::Constant | Op::SpecConstant => literal(def.operands.first()),
            _ => None,
        }
    }

    fn run(self) -> Result<Reflection, String> {
        let mut bindings = Vec::new();
        let mut push_constant_size = 0;
        for inst in &self.module.types_global_values {
            if inst.class.opcode != Op::Variable {
                continue;
            }
            let (Some(var), Some(ptr_type)) = (inst.result_id, inst.result_type) else {
                continue;
            };
            let Some(Operand::StorageClass(class)) = inst.operands.first() else {
                continue;
            };
            let pointee = self
                .defs
                .get(&ptr_type)
                .and_then(|p| id(p.operands.get(1)))
                .ok_or("variable with a malformed pointer type")?;
            match class {
                StorageClass::PushConstant => {
                    push_constant_size = push_constant_size.max(self.type_size(pointee, 0)?);
                }
                StorageClass::UniformConstant
                | StorageClass::Uniform
                | StorageClass::StorageBuffer => {
                    if let Some(b) = self.binding(var, pointee, *class)? {
                        bindings.push(b);
                    }
                }
                _ => {}
            }
        }
        bindings.sort_by_key(|b| (b.set, b.binding));
        let (workgroup_size, workgroup_size_ids) = self.workgroup_size()?;
        Ok(Reflection {
            bindings,
            push_constant_size,
            workgroup_size,
            workgroup_size_ids,
            spec_constants: self.spec_constants(&workgroup_size_ids),
        })
    }

    fn binding(
        &self,
        var: u32,
        pointee: u32,
        class: StorageClass,
    ) -> Result<Option<BindingInfo>, String> {
        let (Some(Some(set)), Some(Some(binding))) = (
            self.decoration(var, Decoration::DescriptorSet),
            self.decoration(var, Decoration::Binding),
        ) else {
            return Ok(None);
        };
        let mut ty = pointee;
        let mut count = 1;
        let def = self.defs.get(&ty).ok_or("binding of unknown type")?;
        if def.class.opcode == Op::TypeArray {
            count = id(def.operands.get(1))
                .and_then(|len| self.constant_u32(len))
                .ok_or("descriptor array with a non-constant length")?;
            ty = id(def.operands.first()).ok_or("malformed array type")?;
        } else if def.class.opcode == Op::TypeRuntimeArray {
            count = 0;
            ty = id(def.operands.first()).ok_or("malformed runtime array type")?;
        }
        let def = self.defs.get(&ty).ok_or("binding of unknown type")?;
        let var_non_writable = self.decoration(var, Decoration::NonWritable).is_some();
        let (kind, read_only) = match def.class.opcode {
            Op::TypeImage => {
                // Operand 5 is "Sampled": 2 means a storage image.
                if literal(def.operands.get(5)) == Some(2) {
                    (DescriptorKind::StorageImage, var_non_writable)
                } else {
                    return Err("separate sampled images are not supported: use sampler2D".into());
                }
            }
            Op::TypeSampledImage => (DescriptorKind::SampledImage, true),
            Op::TypeStruct => {
                let buffer_block = self.decoration(ty, Decoration::BufferBlock).is_some();
                let members = def.operands.len() as u32;
                let all_members_readonly = self
                    .member_non_writable
                    .get(&ty)
                    .is_some_and(|m| m.len() as u32 == members);
                if class == StorageClass::StorageBuffer || buffer_block {
                    (
                        DescriptorKind::StorageBuffer,
                        var_non_writable || all_members_readonly,
                    )
                } else {
                    (DescriptorKind::UniformBuffer, true)
                }
            }
            _ => return Ok(None),
        };
        let block_name = (def.class.opcode == Op::TypeStruct)
            .then(|| self.names.get(&ty).cloned())
            .flatten();
        let name = self
            .names
            .get(&var)
            .filter(|n| !n.is_empty())
            .cloned()
            .or_else(|| block_name.clone())
            .unwrap_or_else(|| format!("set{set}_binding{binding}"));
        Ok(Some(BindingInfo {
            name,
            block_name,
            set,
            binding,
            kind,
            count,
            read_only,
        }))
    }

    /// Byte size of a type in a block (struct member `member_matrix_stride` applies to matrices).
    fn type_size(&self, ty: u32, matrix_stride: u32) -> Result<u32, String> {
        let def = self.defs.get(&ty).ok_or("unknown type in a block")?;
        Ok(match def.class.opcode {
            Op::TypeInt | Op::TypeFloat => literal(def.operands.first()).unwrap_or(32) / 8,
            Op::TypeBool => 4,
            Op::TypeVector => {
                let component = self.type_size(id(def.operands.first()).ok_or("bad vector")?, 0)?;
                component * literal(def.operands.get(1)).unwrap_or(4)
            }
            Op::TypeMatrix => {
                let column = id(def.operands.first()).ok_or("bad matrix")?;
                let columns = literal(def.operands.get(1)).unwrap_or(4);
                let stride = if matrix_stride > 0 {
                    matrix_stride
                } else {
                    self.type_size(column, 0)?
                };
                stride * columns
            }
            Op::TypeArray => {
                let element = id(def.operands.first()).ok_or("bad array")?;
                let len = id(def.operands.get(1))
                    .and_then(|l| self.constant_u32(l))
                    .ok_or("array with a non-constant length in a block")?;
                let stride = match self.decoration(ty, Decoration::ArrayStride) {
                    Some(Some(stride)) => stride,
                    _ => self.type_size(element, 0)?,
                };
                stride * len
            }
            Op::TypeRuntimeArray => 0,
            Op::TypeStruct => {
                let mut size = 0;
                for (i, member) in def.operands.iter().enumerate() {
                    let member_ty = id(Some(member)).ok_or("bad struct member")?;
                    let key = (ty, i as u32);
                    let offset = self.member_offsets.get(&key).copied().unwrap_or(size);
                    let stride = self.member_matrix_strides.get(&key).copied().unwrap_or(0);
                    size = size.max(offset + self.type_size(member_ty, stride)?);
                }
                size
            }
            other => return Err(format!("unsupported type {other:?} in a block")),
        })
    }

    fn workgroup_size(&self) -> Result<([u32; 3], [Option<u32>; 3]), String> {
        let mut size = None;
        let mut ids = [None; 3];
        for inst in &self.module.execution_modes {
            let Some(Operand::ExecutionMode(mode)) = inst.operands.get(1) else {
                continue;
            };
            let values: Vec<Option<u32>> = (2..5).map(|i| literal(inst.operands.get(i))).collect();
            match mode {
                ExecutionMode::LocalSize => {
                    size = Some([
                        values[0].unwrap_or(1),
                        values[1].unwrap_or(1),
                        values[2].unwrap_or(1),
                    ]);
                }
                ExecutionMode::LocalSizeId => {
                    let mut s = [1; 3];
                    for (axis, slot) in s.iter_mut().enumerate() {
                        let cid = id(inst.operands.get(axis + 2)).ok_or("bad LocalSizeId")?;
                        *slot = self
                            .constant_u32(cid)
                            .ok_or("LocalSizeId is not a constant")?;
                        ids[axis] = self.spec_id(cid);
                    }
                    size = Some(s);
                }
                _ => {}
            }
        }
        // A constant decorated BuiltIn WorkgroupSize overrides the execution mode.
        for (&target, decos) in &self.decorations {
            let is_wg = decos.iter().any(|(d, v)| {
                *d == Decoration::BuiltIn && *v == Some(BuiltIn::WorkgroupSize as u32)
            });
            let Some(def) = self.defs.get(&target).filter(|_| is_wg) else {
                continue;
            };
            let mut s = [1; 3];
            for (axis, slot) in s.iter_mut().enumerate() {
                let cid = id(def.operands.get(axis)).ok_or("bad WorkgroupSize constant")?;
                *slot = self
                    .constant_u32(cid)
                    .ok_or("WorkgroupSize is not constant")?;
                ids[axis] = self.spec_id(cid);
            }
            size = Some(s);
        }
        size.map(|s| (s, ids))
            .ok_or_else(|| "no workgroup size: is this a compute shader?".to_string())
    }

    fn spec_id(&self, constant: u32) -> Option<u32> {
        self.decoration(constant, Decoration::SpecId).flatten()
    }

    /// Specialization constants; unnamed ones that set the workgroup size (`local_size_x_id = N`)
    /// are named `local_size_x`, `local_size_y`, `local_size_z`.
    fn spec_constants(&self, workgroup_ids: &[Option<u32>; 3]) -> Vec<SpecConstantInfo> {
        const AXES: [&str; 3] = ["local_size_x", "local_size_y", "local_size_z"];
        let mut out = Vec::new();
        for inst in &self.module.types_global_values {
            let Some(result) = inst.result_id else {
                continue;
            };
            let Some(spec_id) = self.spec_id(result) else {
                continue;
            };
            let ty = inst.result_type.and_then(|t| self.defs.get(&t));
            let (ty, default_bits) = match inst.class.opcode {
                Op::SpecConstantTrue => (SpecType::Bool, 1),
                Op::SpecConstantFalse => (SpecType::Bool, 0),
                Op::SpecConstant => {
                    let bits = literal(inst.operands.first()).unwrap_or(0);
                    let ty = match ty.map(|t| (t.class.opcode, literal(t.operands.get(1)))) {
                        Some((Op::TypeFloat, _)) => SpecType::F32,
                        Some((Op::TypeInt, Some(1))) => SpecType::I32,
                        _ => SpecType::U32,
                    };
                    (ty, bits)
                }
                _ => continue,
            };
            let axis = workgroup_ids.iter().position(|&id| id == Some(spec_id));
            let name = match (self.names.get(&result).filter(|n| !n.is_empty()), axis) {
                (Some(name), _) => name.clone(),
                (None, Some(axis)) => AXES[axis].to_string(),
                (None, None) => format!("constant_{spec_id}"),
            };
            out.push(SpecConstantInfo {
                name,
                id: spec_id,
                ty,
                default_bits,
            });
        }
        out.sort_by_key(|s| s.id);
        out
    }
}
