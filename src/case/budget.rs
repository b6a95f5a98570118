//! What a run's steps would cost, refused before the run starts (issue 31
//! item 3): a step of length `L` whose increments are at most `h_max`
//! takes at least `n = ⌈L / h_max⌉` increments, and keeps at least
//! `⌈n / every⌉` VTU files of about [`vtu_bytes`] each on disk. A step of
//! more than [`MAX_INCREMENTS`] increments (`[[step]] max_increments`
//! raises it), or a run keeping more than [`MAX_OUTPUT_BYTES`] (`[output]
//! max_bytes` raises it), is refused by `check` and `run` alike, with the
//! numbers: a typo such as `max_increment = 1e-7` would otherwise run for
//! days and fill the disk.

/// Increments one step may take at least, by default.
pub const MAX_INCREMENTS: u64 = 100_000;
/// Bytes of VTU files a run may keep, by default: 100 GiB.
pub const MAX_OUTPUT_BYTES: u64 = 100 << 30;

/// Values a VTU file stores per node (displacement 3, `node_id` 1, contact
/// pressure, gap and status 3, traction, slip, slip increment and
/// accumulated slip 12) and per cell (`cauchy_stress` 9, `von_mises` 1,
/// `region` 1), and the points (3) and connectivity (8) of the mesh.
const VALUES_PER_NODE: u64 = 3 + 1 + 3 + 12 + 3;
const VALUES_PER_CELL: u64 = 9 + 1 + 1 + 8 + 2;

/// The fewest increments of a step of length `length` with increments of
/// at most `max_increment`: `⌈L / h_max⌉` (saturated at `u64::MAX`).
pub fn fewest_increments(length: f64, max_increment: f64) -> u64 {
    // a float beyond u64::MAX saturates in the cast
    (length / max_increment).ceil() as u64
}

/// The bytes of one VTU file of a mesh of `nodes` nodes and `elements`
/// elements with every field, uncompressed: 8 bytes a value, base64 (4/3).
pub fn vtu_bytes(nodes: usize, elements: usize) -> u64 {
    let values = VALUES_PER_NODE * nodes as u64 + VALUES_PER_CELL * elements as u64;
    values * 8 * 4 / 3
}

/// Why a step of length `length` cannot run within `limit` increments of
/// at most `max_increment`; `None`: it can.
pub fn increments_fault(length: f64, max_increment: f64, limit: u64) -> Option<String> {
    let n = fewest_increments(length, max_increment);
    (n > limit).then(|| {
        format!(
            "the step takes at least {n} increments (its length {} / max_increment {}), more \
             than the {limit} allowed: give a larger max_increment, or raise the limit with \
             max_increments = {n} in this [[step]]",
            crate::input::number(length),
            crate::input::number(max_increment)
        )
    })
}

/// Why a run whose VTU files (one every `every` increments, and the last
/// of each step) would keep `bytes` on disk once its step of `increments`
/// increments is done cannot run within `limit` bytes; `None`: it can.
pub fn output_fault(bytes: u64, increments: u64, per_file: u64, limit: u64) -> Option<String> {
    (bytes > limit).then(|| {
        format!(
            "the run would keep about {bytes} bytes of VTU files by the end of this step \
             ({increments} increments so far, about {per_file} bytes a file), more than the \
             {limit} allowed: give a larger max_increment, [output] every = N to write every \
             N-th increment, or raise the limit with [output] max_bytes = {bytes}"
        )
    })
}

/// The VTU files a run keeps, counted step by step against `[output]
/// max_bytes`.
pub(super) struct Output {
    every: u64,
    per_file: u64,
    limit: u64,
    increments: u64,
    files: u64,
}

impl Output {
    pub(super) fn new(spec: &super::schema::CaseFile, mesh: &crate::mesh::Mesh) -> Self {
        Output {
            // `[output] every` below 1 is refused where it is read
            every: spec.output.every.filter(|&n| n >= 1).unwrap_or(1) as u64,
            per_file: vtu_bytes(mesh.num_nodes(), mesh.elements.len()),
            limit: spec.output.max_bytes.unwrap_or(MAX_OUTPUT_BYTES),
            increments: 0,
            files: 0,
        }
    }

    /// Counts the next step (its fewest increments, one VTU file every
    /// `every` and its last); why the run's files would exceed the limit.
    pub(super) fn add_step(&mut self, length: f64, max_increment: f64) -> Option<String> {
        let n = fewest_increments(length, max_increment);
        self.increments = self.increments.saturating_add(n);
        // every `every`-th increment and the step's last: at most n files
        let step_files = (n / self.every).saturating_add(1).min(n);
        self.files = self.files.saturating_add(step_files);
        let bytes = self.files.saturating_mul(self.per_file);
        output_fault(bytes, self.increments, self.per_file, self.limit)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_step_takes_at_least_its_length_over_its_largest_increment() {
        assert_eq!(fewest_increments(1.0, 0.25), 4);
        assert_eq!(fewest_increments(1.0, 0.3), 4);
        assert_eq!(fewest_increments(1.0, 1e-7), 10_000_000);
        assert_eq!(fewest_increments(1e300, 1e-300), u64::MAX);
        assert_eq!(increments_fault(1.0, 1e-5, 100_000), None);
        let e = increments_fault(1.0, 1e-7, 100_000).unwrap();
        assert!(
            e.contains("at least 10000000 increments")
                && e.contains("100000 allowed")
                && e.contains("max_increments = 10000000"),
            "{e}"
        );
    }

    #[test]
    fn output_is_refused_beyond_its_limit_with_the_numbers() {
        // 1 000 nodes, 1 000 cells: (22 + 21) × 1000 values × 8 × 4/3
        assert_eq!(vtu_bytes(1000, 1000), 43_000 * 8 * 4 / 3);
        assert_eq!(output_fault(10, 2, 5, 10), None);
        let e = output_fault(11, 2, 5, 10).unwrap();
        assert!(
            e.contains("about 11 bytes") && e.contains("max_bytes = 11"),
            "{e}"
        );
    }
}
