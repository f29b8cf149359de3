//! The nodes' `translation`, `rotation`, `scale` and `matrix` read again from the JSON text in
//! f64: the gltf crate holds them in f32, which moves a UTM northing by up to half a metre
//! before the graph walk composes it in f64. Only these four fields of each node are parsed.

use std::fmt;
use std::path::Path;

use serde::Deserialize;
use serde::de::{Deserializer, IgnoredAny, SeqAccess, Visitor};
use serde_json::value::RawValue;

use super::error::GltfError;

/// A node's transform fields as the file writes them, each number the f64 nearest its decimal
/// text; `None` where a field is absent (or `null`).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct NodeTransform {
    pub translation: Option<[f64; 3]>,
    /// A quaternion (x, y, z, w), as written (not normalised).
    pub rotation: Option<[f64; 4]>,
    pub scale: Option<[f64; 3]>,
    /// Column-major.
    pub matrix: Option<[f64; 16]>,
}

/// The document with only its nodes' transform fields, each kept as raw JSON text; every other
/// field is skipped unparsed.
#[derive(Deserialize)]
struct NodesText {
    #[serde(default)]
    nodes: Vec<NodeText>,
}

#[derive(Deserialize)]
struct NodeText {
    translation: Option<Box<RawValue>>,
    rotation: Option<Box<RawValue>>,
    scale: Option<Box<RawValue>>,
    matrix: Option<Box<RawValue>>,
}

/// Every node's transform fields in f64, read from `json` (the `.gltf` file's text or a GLB's
/// JSON chunk) after the gltf crate parsed it into `parsed_nodes` nodes. A different node
/// count is [`GltfError::NodeCount`]; a field that is not an array of its length (3, 4, 3, 16)
/// of numbers finite in f64 is [`GltfError::NodeTransform`], naming the node and the field.
pub(super) fn read_node_transforms(
    file: &Path,
    json: &[u8],
    parsed_nodes: usize,
) -> Result<Vec<NodeTransform>, GltfError> {
    let text: NodesText = serde_json::from_slice(json).map_err(|e| GltfError::Parse {
        file: file.to_path_buf(),
        message: format!("reading the nodes' transforms in f64: {e}"),
    })?;
    if text.nodes.len() != parsed_nodes {
        return Err(GltfError::NodeCount {
            file: file.to_path_buf(),
            found: text.nodes.len(),
            parsed: parsed_nodes,
        });
    }
    let mut transforms = Vec::with_capacity(parsed_nodes);
    for (node, n) in text.nodes.iter().enumerate() {
        let refuse = |field: &'static str| {
            move |reason| GltfError::NodeTransform {
                file: file.to_path_buf(),
                node,
                field,
                reason,
            }
        };
        transforms.push(NodeTransform {
            translation: numbers(n.translation.as_deref()).map_err(refuse("translation"))?,
            rotation: numbers(n.rotation.as_deref()).map_err(refuse("rotation"))?,
            scale: numbers(n.scale.as_deref()).map_err(refuse("scale"))?,
            matrix: numbers(n.matrix.as_deref()).map_err(refuse("matrix"))?,
        });
    }
    Ok(transforms)
}

/// A field's `N` numbers, `None` when it is absent; an error when it is not an array of
/// exactly `N` numbers finite in f64.
fn numbers<const N: usize>(raw: Option<&RawValue>) -> Result<Option<[f64; N]>, String> {
    let Some(raw) = raw else {
        return Ok(None);
    };
    let elements: FirstElements<'_, N> = serde_json::from_str(raw.get()).map_err(|e| e.to_string())?;
    if elements.count != N {
        return Err(format!("holds {} values, not {N}", elements.count));
    }
    let mut values = [0.0; N];
    for (i, (value, text)) in values.iter_mut().zip(&elements.first).enumerate() {
        *value = number(text.get()).map_err(|reason| format!("value {i}: {reason}"))?;
    }
    Ok(Some(values))
}

/// The f64 nearest a JSON number's text. std's parse rounds correctly, so a number exactly
/// representable in f32 gives exactly the f32 the gltf crate reads (serde_json's default float
/// parse may be a unit in the last place off on long mantissas).
fn number(text: &str) -> Result<f64, String> {
    let shown = || {
        let head: String = text.chars().take(24).collect();
        if head.len() < text.len() {
            format!("{head}…")
        } else {
            head
        }
    };
    // JSON numbers start with a digit or '-'; std would also take "inf" or "NaN", which
    // cannot reach here as raw JSON values.
    let is_number = text.starts_with(|c: char| c == '-' || c.is_ascii_digit());
    match is_number.then(|| text.parse::<f64>().ok()).flatten() {
        Some(v) if v.is_finite() => Ok(v),
        Some(_) => Err(format!("{} is not finite in f64", shown())),
        None => Err(format!("{} is not a number", shown())),
    }
}

/// The first `N` elements of a JSON array as raw text, and how many it holds: elements past
/// the `N`th are counted and skipped unstored, so a hostile array costs no memory.
struct FirstElements<'a, const N: usize> {
    first: Vec<&'a RawValue>,
    count: usize,
}

impl<'de, const N: usize> Deserialize<'de> for FirstElements<'de, N> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_seq(FirstElementsVisitor::<N>)
    }
}

struct FirstElementsVisitor<const N: usize>;

impl<'de, const N: usize> Visitor<'de> for FirstElementsVisitor<N> {
    type Value = FirstElements<'de, N>;

    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "an array of {N} numbers")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut first = Vec::with_capacity(N);
        while first.len() < N {
            match seq.next_element::<&'de RawValue>()? {
                Some(element) => first.push(element),
                None => {
                    let count = first.len();
                    return Ok(FirstElements { first, count });
                }
            }
        }
        let mut count = N;
        while seq.next_element::<IgnoredAny>()?.is_some() {
            count += 1;
        }
        Ok(FirstElements { first, count })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(nodes: &str, parsed: usize) -> Result<Vec<NodeTransform>, GltfError> {
        let json = format!(r#"{{"asset":{{"version":"2.0"}},"nodes":[{nodes}],"meshes":[]}}"#);
        read_node_transforms(Path::new("t.gltf"), json.as_bytes(), parsed)
    }

    /// The node, field and reason of a [`GltfError::NodeTransform`].
    fn refusal(nodes: &str, parsed: usize) -> (usize, &'static str, String) {
        match read(nodes, parsed) {
            Err(GltfError::NodeTransform {
                node, field, reason, ..
            }) => (node, field, reason),
            other => panic!("{nodes}: {other:?}"),
        }
    }

    #[test]
    fn fields_read_as_the_f64_nearest_their_text() {
        let t = read(
            r#"{"name":"a","children":[1],"translation":[412345.678,-0.1,-5712345.678],
                "extras":{"translation":"ignored"}},
               {"rotation":[0,0.7071067811865476,0,0.7071067811865476],"scale":[2.5,1e-3,3E+2]},
               {"matrix":[1,0,0,0,0,1,0,0,0,0,1,0,5712345.178,0,-0,1]},
               {"mesh":0,"translation":null}"#,
            4,
        )
        .unwrap();
        assert_eq!(t[0].translation, Some([412345.678, -0.1, -5712345.678]));
        assert_eq!((t[0].rotation, t[0].scale, t[0].matrix), (None, None, None));
        let h = std::f64::consts::FRAC_1_SQRT_2;
        assert_eq!(t[1].rotation, Some([0.0, h, 0.0, h]));
        assert_eq!(t[1].scale, Some([2.5, 0.001, 300.0]));
        let m = t[2].matrix.unwrap();
        assert_eq!(m[12], 5712345.178);
        assert!(m[14] == 0.0 && m[14].is_sign_negative());
        assert_eq!(t[3], NodeTransform::default());
    }

    #[test]
    fn values_exact_in_f32_read_as_that_f32() {
        // The f32 0.1 written out exactly, and as f64's shortest text for it.
        for text in ["0.100000001490116119384765625", "0.10000000149011612"] {
            let t = read(&format!(r#"{{"translation":[{text},5712345.5,-3.75]}}"#), 1).unwrap();
            let expected = [0.1f32, 5712345.5, -3.75].map(f64::from);
            assert_eq!(t[0].translation, Some(expected), "{text}");
        }
        // Text that no f32 holds reads as the f64 nearest it, not the f32 nearest it.
        let t = read(r#"{"translation":[0.1,0,0]}"#, 1).unwrap();
        assert_eq!(t[0].translation, Some([0.1, 0.0, 0.0]));
    }

    #[test]
    fn a_node_count_unlike_the_parsers_is_refused() {
        let err = read("{},{}", 3).unwrap_err();
        assert_eq!(err.kind(), "node-count", "{err}");
        assert!(err.to_string().contains("holds 2 nodes"), "{err}");
        assert!(read("", 0).unwrap().is_empty());
        let without_nodes = read_node_transforms(Path::new("t.gltf"), b"{}", 0).unwrap();
        assert!(without_nodes.is_empty());
    }

    #[test]
    fn hostile_fields_are_refused_naming_node_and_field() {
        let cases = [
            (r#"{"translation":[1,2]}"#, "translation", "holds 2 values, not 3"),
            (
                r#"{"translation":[1,2,3,4]}"#,
                "translation",
                "holds 4 values, not 3",
            ),
            (
                r#"{"translation":["a",0,0]}"#,
                "translation",
                r#"value 0: "a" is not a number"#,
            ),
            (
                r#"{"scale":[1,true,1]}"#,
                "scale",
                "value 1: true is not a number",
            ),
            (
                r#"{"scale":[1,null,1]}"#,
                "scale",
                "value 1: null is not a number",
            ),
            (
                r#"{"rotation":[0,0,0,[1]]}"#,
                "rotation",
                "value 3: [1] is not a number",
            ),
            (
                r#"{"rotation":{"x":1}}"#,
                "rotation",
                "expected an array of 4 numbers",
            ),
            (r#"{"matrix":5}"#, "matrix", "expected an array of 16 numbers"),
            (
                r#"{"translation":[1e400,0,0]}"#,
                "translation",
                "value 0: 1e400 is not finite",
            ),
            (
                r#"{"translation":[0,-1e400,0]}"#,
                "translation",
                "value 1: -1e400 is not finite",
            ),
            (
                r#"{"translation":[0,0,123456789012345678901234567890e999]}"#,
                "translation",
                "value 2: 123456789012345678901234… is not finite",
            ),
        ];
        for (node, expected_field, expected) in cases {
            let (index, field, reason) = refusal(&format!("{{}},{node}"), 2);
            assert_eq!((index, field), (1, expected_field), "{node}: {reason}");
            assert!(reason.contains(expected), "{node}: {reason}");
        }
        let err = read(r#"{"matrix":[1,2]}"#, 1).unwrap_err();
        assert_eq!(err.kind(), "node-transform");
        assert_eq!(err.to_string(), "t.gltf: node 0 matrix: holds 2 values, not 16");
    }

    #[test]
    fn a_huge_array_is_counted_not_stored() {
        let huge = format!("{}0", "0,".repeat(199_999));
        let (_, field, reason) = refusal(&format!(r#"{{"translation":[{huge}]}}"#), 1);
        assert_eq!(
            (field, reason.as_str()),
            ("translation", "holds 200000 values, not 3")
        );
    }

    #[test]
    fn a_document_that_is_not_json_is_a_parse_error() {
        for text in [&b"not json"[..], b"{\"nodes\":5}", b"{\"nodes\":[1]}", b"\xff"] {
            let err = read_node_transforms(Path::new("t.gltf"), text, 1).unwrap_err();
            assert_eq!(err.kind(), "parse", "{err}");
        }
    }
}
