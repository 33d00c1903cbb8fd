//! Compile: cull, order, derive barriers, compute transient lifetimes and alias their memory.
//! Plain data: no Vulkan calls, testable without a GPU.

use super::handle::ResourceId;
use super::plan::{AliasSlot, Barrier, BarrierSrc, Plan, PlannedPass, PlannedResource};
use super::render_graph::{PassWork, RenderGraph, ResourceDesc, ResourceKind};
use super::GraphError;
use crate::access::Access;
use crate::memory::ResourceState;
use ash::vk;
use std::collections::HashMap;

/// Which passes must run: roots (side effects, writes to imported or temporal resources) and,
/// transitively, the producers of every version a kept pass reads.
fn cull(graph: &RenderGraph) -> Vec<bool> {
    let mut producer: HashMap<(ResourceId, u32), usize> = HashMap::new();
    for (i, pass) in graph.passes.iter().enumerate() {
        for &(id, version, _) in &pass.writes {
            producer.insert((id, version), i);
        }
    }
    let mut keep = vec![false; graph.passes.len()];
    let mut stack: Vec<usize> = graph
        .passes
        .iter()
        .enumerate()
        .filter(|(_, p)| {
            p.side_effect
                || p.writes.iter().any(|&(id, _, _)| {
                    !matches!(graph.resources[id.0 as usize].kind, ResourceKind::Transient)
                })
        })
        .map(|(i, _)| i)
        .collect();
    while let Some(i) = stack.pop() {
        if std::mem::replace(&mut keep[i], true) {
            continue;
        }
        for &(id, version, _) in &graph.passes[i].reads {
            if let Some(&p) = producer.get(&(id, version)) {
                if !keep[p] {
                    stack.push(p);
                }
            }
        }
    }
    keep
}

/// Tracks one resource's hazards while walking the kept passes.
#[derive(Clone, Copy)]
struct Track {
    layout: vk::ImageLayout,
    /// Stages and accesses of the last write (empty when none this frame).
    write_stage: vk::PipelineStageFlags2,
    write_access: vk::AccessFlags2,
    /// Stages and accesses the last write was made visible to.
    visible_stage: vk::PipelineStageFlags2,
    visible_access: vk::AccessFlags2,
    /// Stages of reads since the last write (write-after-read needs them).
    read_stage: vk::PipelineStageFlags2,
}

impl Track {
    fn state(&self) -> ResourceState {
        ResourceState {
            layout: self.layout,
            stage: self.write_stage | self.read_stage,
            access: self.write_access,
        }
    }
}

fn first_use_barrier(
    id: ResourceId,
    kind: &ResourceKind,
    access: Access,
    aliased_after: Option<ResourceState>,
) -> (Barrier, Track) {
    let info = access.info();
    let discard = matches!(kind, ResourceKind::Transient);
    let barrier = Barrier {
        resource: id,
        src: match aliased_after {
            Some(prev) => BarrierSrc::Earlier {
                stage: prev.stage,
                access: prev.access,
            },
            None => BarrierSrc::FrameStart,
        },
        dst_stage: info.stage,
        dst_access: info.access,
        old_layout: discard.then_some(vk::ImageLayout::UNDEFINED),
        new_layout: info.layout,
    };
    let track = Track {
        layout: info.layout,
        write_stage: if info.writes {
            info.stage
        } else {
            vk::PipelineStageFlags2::NONE
        },
        write_access: if info.writes {
            info.access
        } else {
            vk::AccessFlags2::NONE
        },
        visible_stage: if info.writes {
            vk::PipelineStageFlags2::NONE
        } else {
            info.stage
        },
        visible_access: if info.writes {
            vk::AccessFlags2::NONE
        } else {
            info.access
        },
        read_stage: if info.writes {
            vk::PipelineStageFlags2::NONE
        } else {
            info.stage
        },
    };
    (barrier, track)
}

/// The barrier (if any) that access `access` needs after the accesses in `track`, and the new track.
fn next_barrier(
    id: ResourceId,
    track: &mut Track,
    access: Access,
    is_image: bool,
) -> Option<Barrier> {
    let info = access.info();
    let layout_change = is_image && track.layout != info.layout;
    // Whether a barrier is needed, and the earlier stages it waits for.
    let (needed, stage) = if info.writes {
        // Write after write (memory dependency) and write after read (execution dependency).
        let stage = track.write_stage | track.read_stage;
        (layout_change || !stage.is_empty(), stage)
    } else {
        let covered = track.write_stage.is_empty()
            || (track.visible_stage.contains(info.stage)
                && track.visible_access.contains(info.access));
        // A layout transition writes the image: it must also wait for the reads since the last write.
        let stage = if layout_change {
            track.write_stage | track.read_stage
        } else {
            track.write_stage
        };
        (layout_change || !covered, stage)
    };
    let barrier = needed.then(|| Barrier {
        resource: id,
        src: BarrierSrc::Earlier {
            stage: if stage.is_empty() { info.stage } else { stage },
            access: track.write_access,
        },
        dst_stage: info.stage,
        dst_access: info.access,
        old_layout: Some(track.layout),
        new_layout: info.layout,
    });
    if info.writes {
        track.write_stage = info.stage;
        track.write_access = info.access;
        track.visible_stage = vk::PipelineStageFlags2::NONE;
        track.visible_access = vk::AccessFlags2::NONE;
        track.read_stage = vk::PipelineStageFlags2::NONE;
    } else {
        if needed {
            track.visible_stage |= info.stage;
            track.visible_access |= info.access;
        }
        if layout_change {
            track.read_stage = vk::PipelineStageFlags2::NONE;
        }
        track.read_stage |= info.stage;
    }
    track.layout = info.layout;
    barrier
}

/// Assigns transients to memory slots: greedy in order of first use, reusing the best-fitting slot
/// whose last member's lifetime ended before this one begins. Images and buffers never share.
fn alias(resources: &mut [PlannedResource]) -> Vec<AliasSlot> {
    let mut order: Vec<usize> = (0..resources.len())
        .filter(|&i| {
            resources[i].kind == ResourceKind::Transient && resources[i].lifetime.is_some()
        })
        .collect();
    order.sort_by_key(|&i| resources[i].lifetime.map(|l| l.0));
    let mut slots: Vec<AliasSlot> = Vec::new();
    let mut slot_end: Vec<usize> = Vec::new();
    for i in order {
        let (first, last) = resources[i].lifetime.unwrap_or_default();
        let images = matches!(resources[i].desc, ResourceDesc::Image(_));
        let size = resources[i].desc.byte_size();
        let best = (0..slots.len())
            .filter(|&s| slots[s].images == images && slot_end[s] < first)
            .min_by_key(|&s| slots[s].size_estimate.abs_diff(size));
        let s = match best {
            Some(s) => s,
            None => {
                slots.push(AliasSlot {
                    images,
                    size_estimate: 0,
                    members: Vec::new(),
                });
                slot_end.push(0);
                slots.len() - 1
            }
        };
        slots[s].size_estimate = slots[s].size_estimate.max(size);
        slots[s].members.push(ResourceId(i as u32));
        slot_end[s] = last;
        resources[i].slot = Some(s);
    }
    slots
}

impl RenderGraph {
    /// Compiles the graph: the plan (plain data) and the work of the kept passes.
    pub fn compile(self) -> Result<super::CompiledGraph, GraphError> {
        if let Some(e) = self.errors.first() {
            return Err(e.clone());
        }
        for pass in &self.passes {
            if matches!(pass.work, PassWork::Missing) {
                return Err(GraphError::NoWork(pass.name.clone()));
            }
        }
        let keep = cull(&self);
        let mut resources: Vec<PlannedResource> = self
            .resources
            .iter()
            .map(|r| PlannedResource {
                name: r.name.clone(),
                kind: r.kind.clone(),
                desc: r.desc,
                image_usage: vk::ImageUsageFlags::empty(),
                buffer_usage: vk::BufferUsageFlags::empty(),
                lifetime: None,
                slot: None,
            })
            .collect();

        // Order: declaration order of kept passes. Versioned handles make it a valid topological
        // order (a pass can only read versions declared before it, and cannot read overwritten ones).
        let kept: Vec<usize> = (0..self.passes.len()).filter(|&i| keep[i]).collect();
        let mut accesses_per_pass = Vec::with_capacity(kept.len());
        for (position, &i) in kept.iter().enumerate() {
            let pass = &self.passes[i];
            let mut accesses: Vec<(ResourceId, u32, Access)> = Vec::new();
            for &(id, version, access) in &pass.reads {
                if !pass.writes.iter().any(|&(w, _, a)| w == id && a == access) {
                    accesses.push((id, version, access));
                }
            }
            accesses.extend(pass.writes.iter().copied());
            for &(id, _, access) in &accesses {
                let r = &mut resources[id.0 as usize];
                r.image_usage |= access.image_usage();
                r.buffer_usage |= access.buffer_usage();
                r.lifetime = Some(match r.lifetime {
                    None => (position, position),
                    Some((first, _)) => (first, position),
                });
            }
            accesses_per_pass.push(accesses);
        }
        let slots = alias(&mut resources);

        let mut tracks: HashMap<ResourceId, Track> = HashMap::new();
        let mut slot_state: Vec<Option<ResourceState>> = vec![None; slots.len()];
        let mut passes = Vec::with_capacity(kept.len());
        for (&i, accesses) in kept.iter().zip(accesses_per_pass) {
            let mut barriers = Vec::new();
            for &(id, _, access) in &accesses {
                let res = &resources[id.0 as usize];
                let is_image = matches!(res.desc, ResourceDesc::Image(_));
                match tracks.get_mut(&id) {
                    Some(track) => barriers.extend(next_barrier(id, track, access, is_image)),
                    None => {
                        let aliased_after = res.slot.and_then(|s| slot_state[s]);
                        let (b, t) = first_use_barrier(id, &res.kind, access, aliased_after);
                        barriers.push(b);
                        tracks.insert(id, t);
                    }
                }
                if let (Some(s), Some(t)) = (res.slot, tracks.get(&id)) {
                    slot_state[s] = Some(t.state());
                }
            }
            passes.push(PlannedPass {
                name: self.passes[i].name.clone(),
                decl_index: i,
                barriers,
                accesses,
            });
        }
        let mut final_states: Vec<(ResourceId, ResourceState)> = tracks
            .iter()
            .filter(|(id, _)| resources[id.0 as usize].kind != ResourceKind::Transient)
            .map(|(&id, t)| (id, t.state()))
            .collect();
        final_states.sort_by_key(|(id, _)| *id);
        let culled = (0..self.passes.len())
            .filter(|&i| !keep[i])
            .map(|i| self.passes[i].name.clone())
            .collect();
        let plan = Plan {
            resources,
            passes,
            culled,
            slot_final_states: slot_state
                .into_iter()
                .map(Option::unwrap_or_default)
                .collect(),
            slots,
            final_states,
        };
        let mut work: Vec<Option<PassWork>> =
            self.passes.into_iter().map(|p| Some(p.work)).collect();
        let work = kept
            .iter()
            .map(|&i| work[i].take().unwrap_or(PassWork::Missing))
            .collect();
        Ok(super::CompiledGraph {
            plan,
            work,
            externals: self.externals,
            readbacks: self.readbacks,
        })
    }
}
