//! The command line's allocator (`signorini::run::huge_pages`, installed
//! by `src/main.rs`) asks Linux for transparent huge pages on large blocks
//! and on nothing else: read back from the kernel's own account of this
//! process's mappings (`/proc/self/smaps`, the `hg` flag of
//! `madvise(MADV_HUGEPAGE)` in a mapping's `VmFlags`). This test file
//! installs the same allocator as its own.

#![cfg(target_os = "linux")]

use signorini::run::huge_pages::{HugePageAdvice, HUGE_PAGE, LARGE};
use std::path::Path;

#[global_allocator]
static ALLOCATOR: HugePageAdvice = HugePageAdvice;

/// The `VmFlags` of the mapping of this process that holds `address`.
fn vm_flags(address: usize) -> Vec<String> {
    let smaps = std::fs::read_to_string("/proc/self/smaps").unwrap();
    let mut inside = false;
    for line in smaps.lines() {
        let first = line.split_whitespace().next().unwrap_or("");
        if let Some((a, b)) = first.split_once('-') {
            if let (Ok(a), Ok(b)) = (usize::from_str_radix(a, 16), usize::from_str_radix(b, 16)) {
                inside = a <= address && address < b;
                continue;
            }
        }
        if inside {
            if let Some(flags) = line.strip_prefix("VmFlags:") {
                return flags.split_whitespace().map(str::to_string).collect();
            }
        }
    }
    panic!("no mapping holds {address:#x}");
}

/// A block of 16 huge pages is advised on its whole huge pages; a block
/// under `LARGE` is not (it may share its pages with other blocks).
#[test]
fn large_blocks_and_only_they_ask_for_huge_pages() {
    if !Path::new("/sys/kernel/mm/transparent_hugepage/enabled").exists() {
        eprintln!("this kernel has no transparent huge pages: nothing to check");
        return;
    }
    let large = vec![1u8; 16 * HUGE_PAGE];
    let interior = (large.as_ptr() as usize).next_multiple_of(HUGE_PAGE);
    let flags = vm_flags(interior);
    assert!(flags.contains(&"hg".to_string()), "{flags:?}");

    let small = vec![1u8; LARGE / 4];
    let flags = vm_flags(small.as_ptr() as usize + small.len() / 2);
    assert!(!flags.contains(&"hg".to_string()), "{flags:?}");
    assert_eq!(large[interior - large.as_ptr() as usize], 1);
}
