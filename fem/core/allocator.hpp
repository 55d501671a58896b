#pragma once
// Process-wide allocator settings for the large, short-lived arrays of a 3D solve.

namespace softarm::fem {

/// Lets glibc's malloc keep freed memory mapped for the next allocation, instead of
/// returning every block above its mmap threshold (128 KiB, at most 32 MiB) to the
/// kernel. Each Newton iteration of a 3D scene allocates and frees arrays of 50-200 MB
/// (the tangent's values and its per-thread buffers, CHOLMOD's transposed copy and
/// workspace); glibc serves those with fresh mmaps that fault in page by page. On the
/// thesis 3CA (Hex20 at 2x2x2 points, 43,992 dofs, 0 -> 137.9 kPa, 69 Newton iterations)
/// that was 5.0 M minor page faults; with this call 0.18 M, and the run 71.6 -> 59.7 s.
/// The price: the process keeps its peak heap until it exits (717 MB there).
/// Call once, at the start of main (it is safe at any time; earlier blocks keep their mmaps).
void keep_freed_memory_mapped();

}  // namespace softarm::fem
