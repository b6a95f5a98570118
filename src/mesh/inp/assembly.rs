//! Parts, the assembly and its instances (`*PART … *END PART`,
//! `*ASSEMBLY`, `*INSTANCE, NAME=…, PART=…`), as Abaqus/CAE writes every
//! deck.
//!
//! A part's keywords are kept, not read, until an instance places it: then
//! they are read in the instance's [`Context`]: node and element ids shifted
//! by the largest ids read before (so the first instance keeps its ids, the
//! next ones follow), coordinates moved by the instance's [`Transform`],
//! and set and surface names qualified by the instance (`Part-1-1.TOP`).
//! Several instances of a part read its keywords several times. Inside the
//! assembly, `*NSET`/`*ELSET` with `INSTANCE=…` list ids of that instance;
//! elsewhere a qualified name (`Part-1-1.TOP`) names an instance's set. The
//! nodes and the volume elements of an instance also form a node set and an
//! element set (a region) named after it.

use nalgebra::{Rotation3, Unit, Vector3};

/// The rigid motion of an instance: the translation (first data line of
/// `*INSTANCE`), then the rotation (second data line: points `a`, `b` on
/// the axis and the angle in degrees, right-handed about `b − a`), as
/// Abaqus applies them: `x ↦ a + R (x + t − a)`.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Transform {
    pub(super) translation: Vector3<f64>,
    pub(super) rotation: Option<(Vector3<f64>, Rotation3<f64>)>,
}

impl Transform {
    /// The transform of the data lines' numbers: 3 (translation) and
    /// optionally 7 (rotation); an error message for a zero axis.
    pub(super) fn new(translation: [f64; 3], rotation: Option<[f64; 7]>) -> Result<Self, String> {
        let rotation = match rotation {
            None => None,
            Some(r) => {
                let a = Vector3::new(r[0], r[1], r[2]);
                let b = Vector3::new(r[3], r[4], r[5]);
                let axis = Unit::try_new(b - a, 1e-12 * (1.0 + a.norm().max(b.norm())))
                    .ok_or_else(|| {
                        format!(
                            "the rotation axis from ({}, {}, {}) to ({}, {}, {}) has zero length; \
                             give two distinct points on the axis",
                            r[0], r[1], r[2], r[3], r[4], r[5]
                        )
                    })?;
                Some((a, Rotation3::from_axis_angle(&axis, r[6].to_radians())))
            }
        };
        Ok(Transform {
            translation: translation.into(),
            rotation,
        })
    }

    /// `x ↦ a + R (x + t − a)`.
    pub(super) fn apply(&self, x: [f64; 3]) -> [f64; 3] {
        let moved = Vector3::from(x) + self.translation;
        match &self.rotation {
            None => moved.into(),
            Some((a, r)) => (a + r * (moved - a)).into(),
        }
    }
}

/// How the keywords being read number and name things: globally (the
/// default), or inside an instance.
#[derive(Clone, Debug, Default)]
pub(super) struct Context {
    /// The instance's name, which qualifies set and surface names.
    pub(super) instance: Option<String>,
    /// Added to the node and element ids.
    pub(super) node_offset: u64,
    pub(super) element_offset: u64,
    /// Applied to the node coordinates (only while a part is placed).
    pub(super) transform: Option<Transform>,
}

impl Context {
    /// A set or surface name as the mesh has it: qualified by the instance.
    pub(super) fn name(&self, name: &str) -> String {
        match &self.instance {
            Some(i) => format!("{i}.{name}"),
            None => name.to_string(),
        }
    }
    pub(super) fn node(&self, id: u64) -> u64 {
        id + self.node_offset
    }
    pub(super) fn element(&self, id: u64) -> u64 {
        id + self.element_offset
    }
}

/// A placed part: its name (as written), and the context its keywords
/// were read in (without the transform).
#[derive(Clone, Debug)]
pub(super) struct Instance {
    pub(super) name: String,
    pub(super) context: Context,
}

/// A part: its name and the blocks (keyword line and data lines) between
/// `*PART` and `*END PART`, as indices into the reader's blocks.
#[derive(Clone, Debug)]
pub(super) struct Part {
    pub(super) name: String,
    pub(super) blocks: std::ops::Range<usize>,
}

#[cfg(test)]
mod tests {
    use super::Transform;

    /// A quarter turn about the vertical axis through (1, 0, 0), after a
    /// translation by (0, 0, 2): (2, 0, 0) → (2, 0, 2) → (1, 1, 2).
    #[test]
    fn translation_then_rotation_about_an_axis() {
        let t =
            Transform::new([0.0, 0.0, 2.0], Some([1.0, 0.0, 0.0, 1.0, 0.0, 5.0, 90.0])).unwrap();
        let x = t.apply([2.0, 0.0, 0.0]);
        for (a, b) in x.iter().zip([1.0, 1.0, 2.0]) {
            assert!((a - b).abs() < 1e-14, "{x:?}");
        }
        assert!(
            Transform::new([0.0; 3], Some([1.0, 2.0, 3.0, 1.0, 2.0, 3.0, 30.0]))
                .unwrap_err()
                .contains("zero length")
        );
    }
}
