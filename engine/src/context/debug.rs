//! The validation-layer messenger: every warning and error is logged and collected so tests can fail on any.

use ash::vk;
use std::ffi::CStr;
use std::sync::{Arc, Mutex};

/// One message from the validation layers.
#[derive(Clone, Debug)]
pub struct ValidationMessage {
    /// `WARNING` or `ERROR`.
    pub severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    /// The message ID name (e.g. `SYNC-HAZARD-READ-AFTER-WRITE`).
    pub id: String,
    /// The full message text.
    pub text: String,
}

impl std::fmt::Display for ValidationMessage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "[{:?}] {}: {}", self.severity, self.id, self.text)
    }
}

/// The messages collected since the context was created (shared with the messenger callback).
#[derive(Clone, Default)]
pub struct ValidationLog(Arc<Mutex<Vec<ValidationMessage>>>);

impl ValidationLog {
    /// Removes and returns every message collected so far.
    pub fn take(&self) -> Vec<ValidationMessage> {
        std::mem::take(&mut *self.lock())
    }

    /// Removes every message collected so far and, if there were any, returns them as one text:
    /// a count, then one message per line.
    pub fn take_report(&self) -> Option<String> {
        let messages = self.take();
        (!messages.is_empty()).then(|| {
            let lines: Vec<String> = messages.iter().map(|m| m.to_string()).collect();
            format!(
                "{} Vulkan validation message(s):\n{}",
                messages.len(),
                lines.join("\n")
            )
        })
    }

    /// The number of messages collected so far.
    pub fn len(&self) -> usize {
        self.lock().len()
    }

    /// Whether no message was collected.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Vec<ValidationMessage>> {
        self.0.lock().unwrap_or_else(|poison| poison.into_inner())
    }

    /// The pointer handed to Vulkan as the messenger's user data; valid while `self` lives.
    pub(crate) fn as_user_data(&self) -> *mut std::ffi::c_void {
        Arc::as_ptr(&self.0) as *mut std::ffi::c_void
    }
}

/// The messenger create info that routes validation warnings and errors into `log`.
pub(crate) fn messenger_info(log: &ValidationLog) -> vk::DebugUtilsMessengerCreateInfoEXT<'static> {
    vk::DebugUtilsMessengerCreateInfoEXT::default()
        .message_severity(
            vk::DebugUtilsMessageSeverityFlagsEXT::WARNING
                | vk::DebugUtilsMessageSeverityFlagsEXT::ERROR,
        )
        .message_type(
            vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
                | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE
                | vk::DebugUtilsMessageTypeFlagsEXT::GENERAL,
        )
        .pfn_user_callback(Some(on_message))
        .user_data(log.as_user_data())
}

unsafe extern "system" fn on_message(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    kind: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user_data: *mut std::ffi::c_void,
) -> vk::Bool32 {
    // SAFETY: Vulkan passes a valid callback-data pointer for the duration of the call.
    let data = unsafe { &*data };
    let text = |p: *const std::ffi::c_char| {
        if p.is_null() {
            String::new()
        } else {
            // SAFETY: non-null strings from the layer are NUL-terminated and live for the call.
            unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
        }
    };
    let message = ValidationMessage {
        severity,
        id: text(data.p_message_id_name),
        text: text(data.p_message),
    };
    if kind.contains(vk::DebugUtilsMessageTypeFlagsEXT::GENERAL) {
        // Loader chatter (e.g. "not a conformant implementation") is logged, not counted.
        tracing::debug!(target: "vulkan", "{message}");
        return vk::FALSE;
    }
    tracing::warn!(target: "vulkan", "{message}");
    // SAFETY: user_data is the Arc'd mutex of a ValidationLog that outlives the messenger.
    let shared = unsafe { &*(user_data as *const Mutex<Vec<ValidationMessage>>) };
    shared
        .lock()
        .unwrap_or_else(|poison| poison.into_inner())
        .push(message);
    vk::FALSE
}
