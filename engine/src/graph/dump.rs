//! Human-readable dumps of a compiled plan: text, and Graphviz for `dot -Tsvg`.

use super::plan::{BarrierSrc, Plan};
use super::render_graph::{ResourceDesc, ResourceKind};
use std::collections::HashMap;
use std::fmt::Write;

impl Plan {
    /// A text listing: passes in order with their accesses and barriers, culled passes, resources
    /// with lifetimes and memory slots.
    pub fn dump(&self) -> String {
        let mut out = String::new();
        let name = |id: super::ResourceId| self.resources[id.0 as usize].name.as_str();
        let _ = writeln!(
            out,
            "passes ({} kept, {} culled):",
            self.passes.len(),
            self.culled.len()
        );
        for (i, pass) in self.passes.iter().enumerate() {
            let _ = writeln!(out, "  {i}: {}", pass.name);
            for b in &pass.barriers {
                let src = match b.src {
                    BarrierSrc::FrameStart => "frame start".to_string(),
                    BarrierSrc::Earlier { stage, access } => format!("{stage:?}/{access:?}"),
                };
                let layout = match b.old_layout {
                    Some(old) if old != b.new_layout => format!(" {old:?} -> {:?}", b.new_layout),
                    None => format!(" (current) -> {:?}", b.new_layout),
                    _ => String::new(),
                };
                let _ = writeln!(
                    out,
                    "     barrier {}: {src} => {:?}/{:?}{layout}",
                    name(b.resource),
                    b.dst_stage,
                    b.dst_access
                );
            }
            for &(id, version, access) in &pass.accesses {
                let _ = writeln!(out, "     {access:?} {}@v{version}", name(id));
            }
        }
        for culled in &self.culled {
            let _ = writeln!(out, "  culled: {culled}");
        }
        let _ = writeln!(out, "resources:");
        for r in &self.resources {
            let desc = match r.desc {
                ResourceDesc::Image(d) => format!("{}x{} {:?}", d.width, d.height, d.format),
                ResourceDesc::Buffer(size) => format!("{size} bytes"),
            };
            let life = r
                .lifetime
                .map_or("unused".to_string(), |(a, b)| format!("passes {a}..={b}"));
            let slot = r.slot.map_or(String::new(), |s| format!(", slot {s}"));
            let _ = writeln!(out, "  {} [{:?}] {desc}, {life}{slot}", r.name, r.kind);
        }
        let (aliased, unaliased) = self.transient_bytes();
        let _ = writeln!(
            out,
            "transient memory: {aliased} bytes in {} slots ({unaliased} bytes without aliasing)",
            self.slots.len()
        );
        out
    }

    /// A Graphviz digraph: passes as boxes, resources as ellipses, edges for reads and writes.
    pub fn to_dot(&self) -> String {
        let mut out = String::from("digraph render_graph {\n  rankdir=LR;\n");
        let mut declared: HashMap<(u32, u32), String> = HashMap::new();
        for (i, pass) in self.passes.iter().enumerate() {
            let _ = writeln!(out, "  p{i} [shape=box, label={:?}];", pass.name);
            for &(id, version, access) in &pass.accesses {
                let node = format!("r{}_{}", id.0, version);
                declared.entry((id.0, version)).or_insert_with(|| {
                    let r = &self.resources[id.0 as usize];
                    let style = match r.kind {
                        ResourceKind::Transient => "",
                        _ => ", style=bold",
                    };
                    let _ = writeln!(
                        out,
                        "  {node} [shape=ellipse, label=\"{} v{version}\"{style}];",
                        r.name.replace('"', "'")
                    );
                    node.clone()
                });
                if access.info().writes {
                    let _ = writeln!(out, "  p{i} -> {node};");
                } else {
                    let _ = writeln!(out, "  {node} -> p{i};");
                }
            }
        }
        out.push_str("}\n");
        out
    }
}
