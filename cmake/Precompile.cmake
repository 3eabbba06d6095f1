# phyir_precompile(TARGET [HEADER...]): TARGET's files are compiled with cmake/phyir_pch.h
# and the extra headers (e.g. <gtest/gtest.h>) precompiled. PHYIR_PRECOMPILE=OFF turns it off,
# to check that every file includes what it uses.
option(PHYIR_PRECOMPILE "Precompile the common third-party headers (faster cold builds)" ON)

function(phyir_precompile target)
  if(PHYIR_PRECOMPILE)
    target_precompile_headers(${target} PRIVATE ${PHYIR_SOURCE_ROOT}/cmake/phyir_pch.h ${ARGN})
  endif()
endfunction()

# phyir_precompile_reuse(TARGET FROM): TARGET uses FROM's precompiled header (both must be
# compiled with the same flags and definitions, as the test executables are).
function(phyir_precompile_reuse target from)
  if(PHYIR_PRECOMPILE)
    target_precompile_headers(${target} REUSE_FROM ${from})
  endif()
endfunction()
