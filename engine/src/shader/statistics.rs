//! Pipeline executable statistics (`VK_KHR_pipeline_executable_properties`): what the driver reports
//! about a compiled pipeline, such as its register count, to explain occupancy and performance.

use crate::error::{Result, VkResultExt};
use ash::vk;
use std::ffi::CStr;
use std::fmt;

/// The value of one statistic, in the format the driver reports it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StatisticValue {
    /// A yes/no fact.
    Bool(bool),
    /// A signed count.
    I64(i64),
    /// An unsigned count (registers, instructions, bytes, ...).
    U64(u64),
    /// A real number.
    F64(f64),
}

impl fmt::Display for StatisticValue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Bool(v) => write!(f, "{v}"),
            Self::I64(v) => write!(f, "{v}"),
            Self::U64(v) => write!(f, "{v}"),
            Self::F64(v) => write!(f, "{v}"),
        }
    }
}

/// One statistic of a pipeline executable.
#[derive(Clone, Debug, PartialEq)]
pub struct PipelineStatistic {
    /// The driver's short name (e.g. `Register Count`). When a pipeline has several executables,
    /// the name is prefixed with the executable's, as `<executable>: <statistic>`.
    pub name: String,
    /// The driver's longer description; empty when it gives none.
    pub description: String,
    /// The value.
    pub value: StatisticValue,
}

/// The statistics of one pipeline the shader library created.
#[derive(Clone, Debug, PartialEq)]
pub struct PipelineStatistics {
    /// The shader's name (the pipeline's debug name).
    pub name: String,
    /// The specialization constants the pipeline was created with, as `(constant id, bits)`.
    pub specialization: Vec<(u32, u32)>,
    /// The statistics of all its executables.
    pub statistics: Vec<PipelineStatistic>,
}

fn text(s: std::result::Result<&CStr, std::ffi::FromBytesUntilNulError>) -> String {
    s.map(|c| c.to_string_lossy().trim().to_string())
        .unwrap_or_default()
}

fn value(statistic: &vk::PipelineExecutableStatisticKHR<'_>) -> Option<StatisticValue> {
    // SAFETY: the union member read is the one `format` names.
    unsafe {
        match statistic.format {
            vk::PipelineExecutableStatisticFormatKHR::BOOL32 => {
                Some(StatisticValue::Bool(statistic.value.b32 != vk::FALSE))
            }
            vk::PipelineExecutableStatisticFormatKHR::INT64 => {
                Some(StatisticValue::I64(statistic.value.i64))
            }
            vk::PipelineExecutableStatisticFormatKHR::UINT64 => {
                Some(StatisticValue::U64(statistic.value.u64))
            }
            vk::PipelineExecutableStatisticFormatKHR::FLOAT64 => {
                Some(StatisticValue::F64(statistic.value.f64))
            }
            _ => None,
        }
    }
}

/// Reads the statistics of every executable of `pipeline`, which was created with
/// `CAPTURE_STATISTICS_KHR` on a device with `pipelineExecutableInfo` enabled.
pub(crate) fn capture(
    loader: &ash::khr::pipeline_executable_properties::Device,
    pipeline: vk::Pipeline,
) -> Result<Vec<PipelineStatistic>> {
    let info = vk::PipelineInfoKHR::default().pipeline(pipeline);
    // SAFETY: the pipeline is alive and belongs to the loader's device.
    let executables = unsafe { loader.get_pipeline_executable_properties(&info) }
        .vk("vkGetPipelineExecutablePropertiesKHR")?;
    let mut statistics = Vec::new();
    for (index, executable) in executables.iter().enumerate() {
        let prefix = if executables.len() > 1 {
            format!("{}: ", text(executable.name_as_c_str()))
        } else {
            String::new()
        };
        let executable_info = vk::PipelineExecutableInfoKHR::default()
            .pipeline(pipeline)
            .executable_index(index as u32);
        // SAFETY: as above; the index is below the executable count the driver returned.
        let reported = unsafe { loader.get_pipeline_executable_statistics(&executable_info) }
            .vk("vkGetPipelineExecutableStatisticsKHR")?;
        statistics.extend(reported.iter().filter_map(|s| {
            Some(PipelineStatistic {
                name: format!("{prefix}{}", text(s.name_as_c_str())),
                description: text(s.description_as_c_str()),
                value: value(s)?,
            })
        }));
    }
    Ok(statistics)
}
