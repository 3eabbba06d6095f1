# Sourced by the tests whose expectations were recorded from a few steps of training (and
# by scripts/refresh_eval_expectations.sh through them): every library that picks its
# kernels by the processor is pinned to its SSE4.1-level code, so these tests run the same
# instructions, and give the same numbers, on every x86-64 processor from SSE4.1 to AVX-512
# (docs/eval.md, "Regression test"). Without the pin a few training steps amplify the
# rounding of other kernels: on a Zen 4 (AVX-512) the expectations recorded on a Zen 3
# (AVX2) moved depth SqRel by 13%.
#   oneDNN's JIT kernels (convolutions, matrix products)      DNNL_MAX_CPU_ISA
#   ATen's vectorised kernels and SLEEF's maths                ATEN_CPU_CAPABILITY
#   glibc's libm (exp, log, pow, sin: FMA and AVX2 variants)   GLIBC_TUNABLES
#   Embree's traversal and intersection (the dataset's renders) PHYIR_EMBREE_MAX_ISA
# BLAS is Debian's reference libblas3 (compiled for baseline x86-64); a machine whose
# libblas.so.3 alternative is OpenBLAS gets its baseline kernels through OPENBLAS_CORETYPE.
export DNNL_MAX_CPU_ISA=SSE41
export ATEN_CPU_CAPABILITY=default
export GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX512F,-AVX2,-FMA,-AVX
export PHYIR_EMBREE_MAX_ISA=sse4.2
export OPENBLAS_CORETYPE=Nehalem
