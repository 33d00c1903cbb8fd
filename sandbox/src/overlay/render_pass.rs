//! The render pass the UI draws in: one colour attachment that keeps its contents (the tone-mapped
//! frame) and stays in `COLOR_ATTACHMENT_OPTIMAL`, so the render graph's tracked layout holds.

use ash::vk;
use lucid_engine::error::VkResultExt as _;
use lucid_engine::Context;

/// Creates the UI render pass for attachments of `format`.
pub fn create(ctx: &Context, format: vk::Format) -> anyhow::Result<vk::RenderPass> {
    let layout = vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL;
    let attachments = [vk::AttachmentDescription::default()
        .format(format)
        .samples(vk::SampleCountFlags::TYPE_1)
        .load_op(vk::AttachmentLoadOp::LOAD)
        .store_op(vk::AttachmentStoreOp::STORE)
        .stencil_load_op(vk::AttachmentLoadOp::DONT_CARE)
        .stencil_store_op(vk::AttachmentStoreOp::DONT_CARE)
        .initial_layout(layout)
        .final_layout(layout)];
    let color = [vk::AttachmentReference::default()
        .attachment(0)
        .layout(layout)];
    let subpasses = [vk::SubpassDescription::default()
        .pipeline_bind_point(vk::PipelineBindPoint::GRAPHICS)
        .color_attachments(&color)];
    let info = vk::RenderPassCreateInfo::default()
        .attachments(&attachments)
        .subpasses(&subpasses);
    // SAFETY: device valid; info references locals that outlive the call.
    let render_pass =
        unsafe { ctx.device().create_render_pass(&info, None) }.vk("vkCreateRenderPass")?;
    ctx.set_name(render_pass, "sandbox ui");
    Ok(render_pass)
}
