# bench_animation: per-frame clip sampling + forward kinematics + skinning (issue 4) for the default
# monkey and every shared glTF model (the largest: CesiumMan by triangles, the Stag by vertices).
if(NOT DEFINED PELAGE_SHARED_MODELS_DIR)
  set(PELAGE_SHARED_MODELS_DIR "${PROJECT_SOURCE_DIR}/../shared/models")
endif()
pelage_bench(bench_animation SOURCES animation_bench.cpp LIBS pelage::scene pelage::animation pelage::skin)
target_compile_definitions(bench_animation PRIVATE PELAGE_SHARED_MODELS_DIR="${PELAGE_SHARED_MODELS_DIR}")
