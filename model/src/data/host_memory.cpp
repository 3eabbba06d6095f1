#include "host_memory.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace phyir::model {

void retain_freed_memory() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_MAX, 0);                   // every block from the heap, reused after free
  mallopt(M_TRIM_THRESHOLD, 1 << 30);       // the heap's free top kept up to 1 GiB
#endif
}

}  // namespace phyir::model
