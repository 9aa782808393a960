# Warning flags, sanitizers and a helper to declare a module library.

# Every float operation rounds as written: no contraction of a * b + c into a fused multiply-add.
# (x86-64's baseline has no FMA, but aarch64's does, and GCC contracts by default there; the fur
# kernel, its scalar reference and the tests' expectations must all round the same way.)
add_compile_options(-ffp-contract=off)

add_library(pelage_warnings INTERFACE)
target_compile_options(pelage_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align -Wunused -Woverloaded-virtual
  $<$<NOT:$<BOOL:$<TARGET_PROPERTY:PELAGE_TEST>>>:-Wdouble-promotion> -Wformat=2 -Wimplicit-fallthrough
  # GCC 12 reports false positives for std::string concatenation at -O3 (GCC bug 105329).
  $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)
if(PELAGE_WERROR)
  target_compile_options(pelage_warnings INTERFACE -Werror)
endif()
# Tests (targets with the property PELAGE_TEST) compare floats with double tolerances all the time;
# promotion there is intended, so -Wdouble-promotion applies to library and app code only.
add_library(pelage_test_warnings INTERFACE)
target_link_libraries(pelage_test_warnings INTERFACE pelage_warnings)

if(PELAGE_SANITIZE)
  # Sanitizer instrumentation makes GCC 12 report maybe-uninitialized false positives inside
  # library templates (OpenMesh properties, std::construct_at); the Release build keeps the warning.
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
                      $<$<CXX_COMPILER_ID:GNU>:-Wno-maybe-uninitialized>)
  add_link_options(-fsanitize=address,undefined)
endif()

if(PELAGE_FUZZ)
  # Coverage instrumentation for every library the fuzz targets link (fuzz/CMakeLists.txt).
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()

# pelage_module(NAME SOURCES ... DEPS ...): a library target pelage_NAME with alias pelage::NAME,
# public headers in NAME/include. Installed (`cmake --install`) as pelage::NAME of the pelage CMake
# package (cmake/pelageConfig.cmake.in), its headers under include/pelage/.
include(GNUInstallDirs)
function(pelage_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(pelage_${name} STATIC ${ARG_SOURCES})
  add_library(pelage::${name} ALIAS pelage_${name})
  set_target_properties(pelage_${name} PROPERTIES EXPORT_NAME ${name})
  target_include_directories(pelage_${name}
    PUBLIC $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include> $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    PRIVATE ${CMAKE_CURRENT_SOURCE_DIR}/src)
  target_link_libraries(pelage_${name} PUBLIC ${ARG_PUBLIC_DEPS}
                        PRIVATE ${ARG_PRIVATE_DEPS} $<BUILD_INTERFACE:pelage_warnings>)
  install(TARGETS pelage_${name} EXPORT pelageTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT dev)
  # One folder of headers per module folder.
  get_directory_property(_installed PELAGE_HEADERS_INSTALLED)
  if(NOT _installed AND EXISTS ${CMAKE_CURRENT_SOURCE_DIR}/include)
    install(DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR}/include/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
            COMPONENT dev FILES_MATCHING PATTERN "*.h")
    set_directory_properties(PROPERTIES PELAGE_HEADERS_INSTALLED ON)
  endif()
endfunction()
