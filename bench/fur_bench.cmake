# bench_fur: per-frame fur generation on the default monkey (issue 3 targets: 500k polylines
# <= 4 ms, 500k lines <= 2 ms per frame on 2 threads; issue 17: against the hand-written "limit").
pelage_bench(bench_fur SOURCES fur_bench.cpp fur_limit.cpp
  LIBS pelage::fur pelage::skin pelage::models pelage::util)
# The limit reference: SSE and AVX intrinsics on x86-64 (elsewhere it reports itself absent),
# rounding as the kernel does (no FMA contraction). Its file is compiled with -mavx, and inline
# library functions it instantiates may be shared with the rest of bench_fur: on x86-64 the
# benchmark program needs an AVX CPU (2011 on); the library and `pelage` do not.
set_property(SOURCE fur_limit.cpp APPEND PROPERTY COMPILE_OPTIONS "-fno-math-errno;-ffp-contract=off")
if(CMAKE_SYSTEM_PROCESSOR MATCHES "x86_64|AMD64")
  set_property(SOURCE fur_limit.cpp APPEND PROPERTY COMPILE_OPTIONS "-mavx")
endif()
