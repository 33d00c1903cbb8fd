//! Pipeline executable statistics for `lucid bench --pipeline-statistics`: the JSON object of the
//! report and the short table printed to stderr.

use lucid_engine::shader::{PipelineStatistic, PipelineStatistics, StatisticValue};
use std::collections::BTreeMap;

/// The report key of each pipeline: its shader name, followed by its specialization constants
/// (`id=bits`) when several pipelines share that name.
fn keys(pipelines: &[PipelineStatistics]) -> Vec<String> {
    pipelines
        .iter()
        .map(|p| {
            let shared = pipelines.iter().filter(|o| o.name == p.name).count() > 1;
            if shared {
                let constants: Vec<String> = p
                    .specialization
                    .iter()
                    .map(|(id, bits)| format!("{id}={bits}"))
                    .collect();
                format!("{} [{}]", p.name, constants.join(","))
            } else {
                p.name.clone()
            }
        })
        .collect()
}

fn json_value(value: StatisticValue) -> serde_json::Value {
    match value {
        StatisticValue::Bool(v) => v.into(),
        StatisticValue::I64(v) => v.into(),
        StatisticValue::U64(v) => v.into(),
        StatisticValue::F64(v) => v.into(),
    }
}

/// `{ pipeline: { statistic: value } }`, or `null` when the device captured none.
pub fn to_json(pipelines: Option<&[PipelineStatistics]>) -> serde_json::Value {
    let Some(pipelines) = pipelines else {
        return serde_json::Value::Null;
    };
    let object: BTreeMap<String, BTreeMap<String, serde_json::Value>> = keys(pipelines)
        .into_iter()
        .zip(pipelines)
        .map(|(key, p)| {
            let statistics = p
                .statistics
                .iter()
                .map(|s| (s.name.clone(), json_value(s.value)))
                .collect();
            (key, statistics)
        })
        .collect();
    serde_json::json!(object)
}

/// The statistics worth a line: those naming registers when there are any, else all of them.
fn shown(statistics: &[PipelineStatistic]) -> Vec<&PipelineStatistic> {
    let registers: Vec<&PipelineStatistic> = statistics
        .iter()
        .filter(|s| s.name.to_lowercase().contains("register"))
        .collect();
    if registers.is_empty() {
        statistics.iter().collect()
    } else {
        registers
    }
}

/// Prints one line per pipeline to stderr, or a note when the device captured no statistics.
pub fn print_table(pipelines: Option<&[PipelineStatistics]>, device: &str) {
    let Some(pipelines) = pipelines else {
        eprintln!(
            "pipeline statistics: {device} does not support VK_KHR_pipeline_executable_properties; \
             none captured"
        );
        return;
    };
    let keys = keys(pipelines);
    let width = keys.iter().map(String::len).max().unwrap_or(0);
    eprintln!("pipeline statistics ({} pipelines):", pipelines.len());
    for (key, p) in keys.iter().zip(pipelines) {
        let values: Vec<String> = shown(&p.statistics)
            .iter()
            .map(|s| format!("{} = {}", s.name, s.value))
            .collect();
        let values = if values.is_empty() {
            "(none reported)".to_string()
        } else {
            values.join(", ")
        };
        eprintln!("  {key:width$}  {values}");
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn statistic(name: &str, value: StatisticValue) -> PipelineStatistic {
        PipelineStatistic {
            name: name.into(),
            description: String::new(),
            value,
        }
    }

    #[test]
    fn pipelines_sharing_a_name_are_keyed_by_specialization() {
        let pipelines = [
            PipelineStatistics {
                name: "svgf/atrous".into(),
                specialization: vec![(0, 1)],
                statistics: vec![statistic("Register Count", StatisticValue::U64(40))],
            },
            PipelineStatistics {
                name: "svgf/atrous".into(),
                specialization: vec![(0, 2)],
                statistics: vec![statistic("Register Count", StatisticValue::U64(48))],
            },
            PipelineStatistics {
                name: "tonemap/aces".into(),
                specialization: vec![],
                statistics: vec![
                    statistic("Spilled", StatisticValue::Bool(false)),
                    statistic("Occupancy", StatisticValue::F64(0.5)),
                    statistic("Delta", StatisticValue::I64(-3)),
                ],
            },
        ];
        assert_eq!(
            to_json(Some(&pipelines)),
            serde_json::json!({
                "svgf/atrous [0=1]": { "Register Count": 40 },
                "svgf/atrous [0=2]": { "Register Count": 48 },
                "tonemap/aces": { "Spilled": false, "Occupancy": 0.5, "Delta": -3 },
            })
        );
        assert_eq!(to_json(None), serde_json::Value::Null);
    }

    #[test]
    fn register_statistics_are_preferred_in_the_table() {
        let statistics = [
            statistic("Instruction Count", StatisticValue::U64(900)),
            statistic("Register Count", StatisticValue::U64(64)),
        ];
        let names: Vec<&str> = shown(&statistics).iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["Register Count"]);
        let names: Vec<&str> = shown(&statistics[..1])
            .iter()
            .map(|s| s.name.as_str())
            .collect();
        assert_eq!(names, ["Instruction Count"]);
    }
}
