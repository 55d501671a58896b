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

/// Runs the program again in this process (exec, the same pid, arguments and environment), with
/// glibc's malloc asking the kernel for transparent huge pages for its heap
/// (GLIBC_TUNABLES=glibc.malloc.hugetlb=1, glibc 2.35 and later), where the kernel gives them
/// only on request (/sys/kernel/mm/transparent_hugepage/enabled reads "[madvise]"). The first
/// touch of each fresh 4 KiB page is a page fault, which on a virtual machine costs microseconds:
/// a 3D solve's peak heap, hundreds of MB, is touched page by page once; with 2 MiB pages it is a
/// fault per 512 of them (docs/performance.md, Huge pages for the heap).
/// Returns (and the program goes on as it is) where the kernel's mode is not madvise, where
/// GLIBC_TUNABLES already names glibc.malloc.hugetlb (after the restart, or the user's choice:
/// glibc.malloc.hugetlb=0 keeps 4 KiB pages), under valgrind (whose process the exec would
/// leave), or where the exec fails. Call first thing in main, before any thread or output.
void restart_with_huge_pages(char** argv);

}  // namespace softarm::fem
