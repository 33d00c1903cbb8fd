//! `lucid info`: the device and what the engine would run with.

use clap::Args;
use lucid_engine::{Context, ContextDesc};

/// Options of `lucid info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// Print as JSON.
    #[arg(long)]
    json: bool,
}

/// Prints the chosen device.
pub fn run(args: &InfoArgs) -> anyhow::Result<()> {
    let ctx = Context::new(&ContextDesc::from_env())?;
    let info = ctx.info();
    let budget = ctx.memory_budget();
    let mib = |bytes: u64| bytes / (1024 * 1024);
    if args.json {
        let value = serde_json::json!({
            "device": info.name,
            "kind": format!("{:?}", info.kind),
            "vulkan": format!("{}.{}.{}", info.api_version.0, info.api_version.1, info.api_version.2),
            "subgroup_size": info.subgroup_size,
            "shared_memory_bytes": info.max_shared_memory,
            "timestamps": info.timestamps,
            "timestamp_period_ns": info.timestamp_period_ns,
            "shader_float16": info.shader_float16,
            "validation": format!("{:?}", ctx.validation()),
            "device_local_heap_mib": mib(budget.heap_bytes),
            "memory_budget_mib": mib(budget.bytes()),
            "max_allocation_mib": mib(budget.max_allocation_bytes),
        });
        println!("{}", serde_json::to_string_pretty(&value)?);
    } else {
        println!("device:        {} ({:?})", info.name, info.kind);
        println!(
            "vulkan:        {}.{}.{}",
            info.api_version.0, info.api_version.1, info.api_version.2
        );
        println!("subgroup size: {}", info.subgroup_size);
        println!(
            "shared memory: {} bytes per workgroup",
            info.max_shared_memory
        );
        println!(
            "timestamps:    {} ({} ns per tick)",
            info.timestamps, info.timestamp_period_ns
        );
        println!("float16:       {}", info.shader_float16);
        println!("validation:    {:?}", ctx.validation());
        println!(
            "memory:        {} MiB device-local heap, budget {} MiB, at most {} MiB per allocation",
            mib(budget.heap_bytes),
            mib(budget.bytes()),
            mib(budget.max_allocation_bytes)
        );
    }
    Ok(())
}
