//! Mutations of a file's JSON tree: a value at any place becomes a huge, negative or fractional
//! number, a value of another type, an index past its array, a copy of another value; keys are
//! removed, arrays emptied or grown.

use proptest::prelude::*;
use proptest::sample::Index;
use serde_json::{json, Value};

/// What a [`JsonMutation`] does to the value it picks.
#[derive(Clone, Debug)]
pub enum JsonOp {
    /// Replace with a number.
    Number(f64),
    /// Replace with a value of another type.
    WrongType(u8),
    /// Remove the value (a key from its object, an element from its array).
    Remove,
    /// An integer becomes an index past the end of the longest array, or far beyond.
    OutOfRange(u8),
    /// An array or object becomes empty.
    Empty,
    /// An array gets a copy of its first element appended.
    Grow,
    /// Replace with a copy of another value of the document.
    CopyFrom(Index),
}

/// One change: `op` on the value at `target` (an index into all the document's values).
#[derive(Clone, Debug)]
pub struct JsonMutation {
    target: Index,
    op: JsonOp,
}

/// Numbers that break counts, offsets, indices, enums and float ranges.
const NUMBERS: [f64; 16] = [
    0.0,
    -1.0,
    -0.0,
    0.5,
    1.0,
    7.0,
    255.0,
    65536.0,
    2147483648.0,
    4294967295.0,
    4294967296.0,
    1.8446744073709552e19,
    3.0e38,
    1.0e39,
    -1.0e39,
    1.0e300,
];

/// Any JSON mutation.
pub fn json_mutation() -> impl Strategy<Value = JsonMutation> {
    let op = prop_oneof![
        4 => proptest::sample::select(&NUMBERS[..]).prop_map(JsonOp::Number),
        4 => any::<u8>().prop_map(JsonOp::OutOfRange),
        2 => Just(JsonOp::Remove),
        2 => any::<Index>().prop_map(JsonOp::CopyFrom),
        1 => any::<u8>().prop_map(JsonOp::WrongType),
        1 => Just(JsonOp::Empty),
        1 => Just(JsonOp::Grow),
    ];
    (any::<Index>(), op).prop_map(|(target, op)| JsonMutation { target, op })
}

/// JSON pointers of every value in `root` but the root itself, in document order.
fn pointers(root: &Value) -> Vec<String> {
    fn walk(value: &Value, at: &str, out: &mut Vec<String>) {
        let children: Vec<(String, &Value)> = match value {
            Value::Object(map) => map
                .iter()
                .map(|(k, v)| (k.replace('~', "~0").replace('/', "~1"), v))
                .collect(),
            Value::Array(items) => items
                .iter()
                .enumerate()
                .map(|(i, v)| (i.to_string(), v))
                .collect(),
            _ => Vec::new(),
        };
        for (key, child) in children {
            let pointer = format!("{at}/{key}");
            out.push(pointer.clone());
            walk(child, &pointer, out);
        }
    }
    let mut out = Vec::new();
    walk(root, "", &mut out);
    out
}

/// The length of the longest array in `root` (an index at or past it is out of range everywhere).
fn longest_array(root: &Value) -> usize {
    match root {
        Value::Array(items) => items
            .iter()
            .map(longest_array)
            .max()
            .unwrap_or(0)
            .max(items.len()),
        Value::Object(map) => map.values().map(longest_array).max().unwrap_or(0),
        _ => 0,
    }
}

fn wrong_type(current: &Value, pick: u8) -> Value {
    let options = [
        json!(null),
        json!(true),
        json!("x"),
        json!([]),
        json!({}),
        json!([0, 1]),
        json!(-1),
        json!(1.5),
    ];
    let differs: Vec<&Value> = options
        .iter()
        .filter(|v| std::mem::discriminant(*v) != std::mem::discriminant(current))
        .collect();
    differs[pick as usize % differs.len()].clone()
}

/// Applies `mutations` in order (each picks among the values the document has then).
pub fn apply(mut root: Value, mutations: &[JsonMutation]) -> Value {
    for m in mutations {
        let all = pointers(&root);
        if all.is_empty() {
            break;
        }
        let target = all[m.target.index(all.len())].clone();
        let replacement = match &m.op {
            JsonOp::Number(n) => Some(serde_json::Number::from_f64(*n).map_or(Value::Null, |n| {
                if n.as_f64()
                    .is_some_and(|f| f.fract() == 0.0 && f.abs() < 9.0e15)
                {
                    json!(n.as_f64().unwrap() as i64)
                } else {
                    Value::Number(n)
                }
            })),
            JsonOp::WrongType(pick) => Some(wrong_type(root.pointer(&target).unwrap(), *pick)),
            JsonOp::OutOfRange(pick) => {
                let current = root.pointer(&target).unwrap().as_u64().unwrap_or(0);
                let past = longest_array(&root) as u64;
                Some(json!(match pick % 4 {
                    0 => past,
                    1 => current + 1,
                    2 => past + 1000,
                    _ => u64::from(u32::MAX),
                }))
            }
            JsonOp::Empty => match root.pointer(&target).unwrap() {
                Value::Array(_) => Some(json!([])),
                Value::Object(_) => Some(json!({})),
                _ => None,
            },
            JsonOp::Grow => match root.pointer(&target).unwrap() {
                Value::Array(items) if !items.is_empty() => {
                    let mut items = items.clone();
                    items.push(items[0].clone());
                    Some(Value::Array(items))
                }
                _ => None,
            },
            JsonOp::CopyFrom(source) => root.pointer(&all[source.index(all.len())]).cloned(),
            JsonOp::Remove => {
                remove(&mut root, &target);
                None
            }
        };
        if let Some(value) = replacement {
            *root.pointer_mut(&target).unwrap() = value;
        }
    }
    root
}

fn remove(root: &mut Value, pointer: &str) {
    let (parent, key) = pointer.rsplit_once('/').unwrap();
    let key = key.replace("~1", "/").replace("~0", "~");
    match root.pointer_mut(parent) {
        Some(Value::Object(map)) => {
            map.remove(&key);
        }
        Some(Value::Array(items)) => {
            if let Ok(i) = key.parse::<usize>() {
                items.remove(i);
            }
        }
        _ => {}
    }
}
