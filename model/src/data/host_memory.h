#pragma once
// How the model's commands ask the C library to manage host memory. Internal to phyir_model.

namespace phyir::model {

// Keeps freed memory in the process for the next tensor, instead of returning it to the
// system: glibc serves blocks above its mmap threshold (128 KiB, rising to at most 32 MiB;
// most of the network's activations) from fresh pages and unmaps them on free, so every
// layer faulted in and zeroed its pages again.
// Measured on a Zen 3 VM (docs/performance.md, "Inference"): 37% of the CPU time of
// inference was the kernel's page faults; without them inference at the paper's sizes took
// 2.1 s instead of 3.3 s. Peak resident memory grows by about a third (freed blocks are
// reused, not returned). No-op outside glibc.
void retain_freed_memory();

}  // namespace phyir::model
