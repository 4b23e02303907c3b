# The install test (ctest label install; tests/CMakeLists.txt): glint as a renderer's developer
# meets it. Installs the build into a fresh prefix, checks the installed command, configures the
# examples (examples/CMakeLists.txt: every example folder) from that prefix alone, builds them, runs
# the path tracer and checks its images (check_example_image.cpp), and runs the OpenGL and Vulkan
# examples and compares their images with `glint render`'s.
#   cmake -DSOURCE_DIR=... -DBUILD_DIR=... -DWORK=... -DVERSION=... -DCXX_COMPILER=... -DBUILD_TYPE=...
#         -DCHECKER=... -DRENDER_COMPARER=... [-DEXAMPLE_FLAGS=...] -P run_install_test.cmake
# An example added later (examples/opengl, examples/vulkan) is configured and built here with no
# edit; to run and check it too, add its run below the path tracer's.
foreach(variable IN ITEMS SOURCE_DIR BUILD_DIR WORK VERSION CXX_COMPILER BUILD_TYPE CHECKER RENDER_COMPARER)
  if(NOT DEFINED ${variable})
    message(FATAL_ERROR "run_install_test.cmake needs -D${variable}=...")
  endif()
endforeach()

# Runs a command; stops the test with its output when it fails.
function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} failed (${status}):\n${out}\n${err}")
  endif()
  message(STATUS "${what}: ok")
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

# Runs a command that must refuse its input: a non-zero exit and one line on stderr holding
# `expected`; stops the test otherwise.
function(refuse what expected)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE status OUTPUT_VARIABLE out ERROR_VARIABLE err)
  string(STRIP "${err}" line)
  string(FIND "${line}" "${expected}" at)
  string(FIND "${line}" "\n" newline)
  if(status EQUAL 0 OR at EQUAL -1 OR NOT newline EQUAL -1)
    message(FATAL_ERROR "${what}: expected one error line with '${expected}', got exit ${status}:\n${out}\n${err}")
  endif()
  message(STATUS "${what}: refused (${line})")
endfunction()

set(prefix ${WORK}/prefix)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
run("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})

# The layout docs/integration.md describes.
foreach(file IN ITEMS include/glint/bsdf.h include/glint/dictionary.h include/glint/version.h
                      include/glint/kernel/glint_brdf.h include/glint/kernel/prelude.h
                      lib/cmake/glint/glintConfig.cmake lib/cmake/glint/glintConfigVersion.cmake
                      include/glint/kernel/glint_kernel.h share/glint/shaders/forward.frag
                      share/glint/shaders/glint_dictionary_gl.glsl share/glint/shaders/glint_kernel.h
                      share/glint/shaders/prelude.h bin/glint)
  if(NOT EXISTS ${prefix}/${file})
    message(FATAL_ERROR "cmake --install wrote no ${file}")
  endif()
endforeach()

# Only the API: the library's own headers (binary16 conversion, the albedo tables' generator) stay home.
foreach(file IN ITEMS include/glint/half.h include/glint/albedo_table_generator.h)
  if(EXISTS ${prefix}/${file})
    message(FATAL_ERROR "cmake --install wrote ${file}, a header of the library's own")
  endif()
endforeach()

run("glint --version" ${prefix}/bin/glint --version)
if(NOT run_output STREQUAL "glint ${VERSION}\n")
  message(FATAL_ERROR "the installed glint --version printed '${run_output}', expected 'glint ${VERSION}'")
endif()
run("glint dict" ${prefix}/bin/glint dict -o ${WORK}/dictionary.gdict)

# The examples see the prefix and nothing else of glint: no package registry, and the build tree
# exports no package (CMakeLists.txt has no export()).
set(configure ${CMAKE_COMMAND} -S ${SOURCE_DIR}/examples -B ${WORK}/build -DCMAKE_BUILD_TYPE=${BUILD_TYPE}
    -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)
if(EXAMPLE_FLAGS)  # the sanitizer build's libraries need the sanitizers' run time
  list(APPEND configure "-DCMAKE_CXX_FLAGS=${EXAMPLE_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${EXAMPLE_FLAGS}")
endif()
run("configure the examples" ${configure})
file(STRINGS ${WORK}/build/CMakeCache.txt glint_dir REGEX "^glint_DIR:")
if(NOT glint_dir STREQUAL "glint_DIR:PATH=${prefix}/lib/cmake/glint")
  message(FATAL_ERROR "the examples found glint elsewhere than in the prefix: ${glint_dir}")
endif()
# Compile and link lines: headers from the prefix, never from the sources or the build tree.
file(GLOB_RECURSE build_lines ${WORK}/build/*/flags.make ${WORK}/build/*/link.txt)
foreach(file IN LISTS build_lines)
  file(READ ${file} text)
  foreach(outside IN ITEMS "${SOURCE_DIR}/src" "${BUILD_DIR}/generated" "${BUILD_DIR}/libglint")
    string(FIND "${text}" "${outside}" at)
    if(NOT at EQUAL -1)
      message(FATAL_ERROR "${file} uses ${outside}: the examples must see the installed glint only")
    endif()
  endforeach()
endforeach()
run("build the examples" ${CMAKE_COMMAND} --build ${WORK}/build --parallel 2)

# A consumer that sets no C++ standard (tests/install/no_standard): the compiler's default standard
# must not be what it builds with, the exported targets bring C++20.
set(no_standard ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/no_standard -B ${WORK}/no_standard
    -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF)
if(EXAMPLE_FLAGS)
  list(APPEND no_standard "-DCMAKE_CXX_FLAGS=${EXAMPLE_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${EXAMPLE_FLAGS}")
endif()
run("configure a consumer that sets no C++ standard" ${no_standard})
run("build a consumer that sets no C++ standard" ${CMAKE_COMMAND} --build ${WORK}/no_standard)
run("run a consumer that sets no C++ standard" ${WORK}/no_standard/glint_no_standard)

# The recipes of docs/integration.md ("Recipes"), word for word as the document has them
# (tests/install/recipes copies them out at configure): the C++ recipe built from the prefix alone
# and run with the installed glint's dictionary (it checks its own figures), the GLSL recipe compiled
# by glslangValidator for OpenGL and Vulkan with the installed shader folder as its include path
# (one line says so where there is no glslangValidator).
set(recipes ${CMAKE_COMMAND} -S ${SOURCE_DIR}/tests/install/recipes -B ${WORK}/recipes
    -DCMAKE_BUILD_TYPE=${BUILD_TYPE} -DCMAKE_CXX_COMPILER=${CXX_COMPILER} -DCMAKE_PREFIX_PATH=${prefix}
    -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF -DCMAKE_FIND_USE_SYSTEM_PACKAGE_REGISTRY=OFF
    -DGLINT_INTEGRATION_DOC=${SOURCE_DIR}/docs/integration.md)
if(EXAMPLE_FLAGS)
  list(APPEND recipes "-DCMAKE_CXX_FLAGS=${EXAMPLE_FLAGS}" "-DCMAKE_EXE_LINKER_FLAGS=${EXAMPLE_FLAGS}")
endif()
run("configure the recipes of docs/integration.md" ${recipes})
string(REGEX MATCHALL "glint recipe [^\n]*" recipe_lines "${run_output}")
foreach(line IN LISTS recipe_lines)
  message(STATUS "${line}")
endforeach()
file(STRINGS ${WORK}/recipes/CMakeCache.txt glint_dir REGEX "^glint_DIR:")
if(NOT glint_dir STREQUAL "glint_DIR:PATH=${prefix}/lib/cmake/glint")
  message(FATAL_ERROR "the recipes found glint elsewhere than in the prefix: ${glint_dir}")
endif()
run("build the recipes of docs/integration.md" ${CMAKE_COMMAND} --build ${WORK}/recipes)
run("run the C++ recipe of docs/integration.md" ${WORK}/recipes/glint_integration_recipe ${WORK}/dictionary.gdict)
message(STATUS "${run_output}")

# The path tracer: the glinty sphere with the dictionary the installed glint wrote, the smooth one
# with a dictionary generated at start (which it does not shade with).
set(tracer ${WORK}/build/path_tracer/glint_path_tracer)
run("path tracer, glints" ${tracer} ${WORK}/glint.exr --dictionary ${WORK}/dictionary.gdict)
run("path tracer, smooth" ${tracer} ${WORK}/smooth.exr --smooth --dictionary ${WORK}/dictionary.gdict)
run("check the images" ${CHECKER} ${WORK}/glint.exr ${WORK}/smooth.exr)
message(STATUS "${run_output}")
# Each example answers --help with its usage, and refuses an output it cannot write before the
# work (a path tracer at 64 samples a pixel would take seconds first), leaving no file: before it
# loads the dictionary, here one that does not exist.
foreach(example IN ITEMS ${tracer} ${WORK}/build/opengl/glint_opengl ${WORK}/build/vulkan/glint_vulkan_deferred)
  if(EXISTS ${example})
    get_filename_component(name ${example} NAME)
    run("${name} --help" ${example} --help)
    string(FIND "${run_output}" "usage: ${name} OUTPUT" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "${name} --help printed no usage: ${run_output}")
    endif()
    refuse("${name} to a .bmp" "unsupported image extension '.bmp'" ${example} ${WORK}/out.bmp
           --dictionary ${WORK}/missing.gdict --size 256)
  endif()
endforeach()
if(EXISTS ${WORK}/out.bmp)
  message(FATAL_ERROR "an example refused out.bmp and still wrote it")
endif()

# The OpenGL example (examples/opengl), built where libepoxy, libOpenGL and libEGL are: glint's built-in
# sphere shaded with the installed GLSL kernel, against `glint render sphere` of the same setup (one
# light, no shadows, the 2020 model without anti-aliasing, one sample a pixel, linear EXR, the same
# dictionary file) within check_example_image.cpp's tolerances.
set(opengl_example ${WORK}/build/opengl/glint_opengl)
if(EXISTS ${opengl_example})
  run("OpenGL example" ${opengl_example} ${WORK}/opengl.exr --dictionary ${WORK}/dictionary.gdict --size 256)
  run("glint render sphere" ${prefix}/bin/glint render sphere --dict ${WORK}/dictionary.gdict --aa none
      --shadows off --msaa 1 --size 256x256 -o ${WORK}/render-opengl.exr)
  run("compare the OpenGL example with glint render" ${CHECKER} --against-render ${WORK}/opengl.exr ${WORK}/render-opengl.exr)
  message(STATUS "${run_output}")
else()
  message(STATUS "OpenGL example: not built (no libepoxy, libOpenGL or libEGL), not compared")
endif()

# examples/vulkan: deferred shading of `glint render sphere`'s sphere in a Vulkan compute shader
# (HLSL, the installed kernel), compared with the installed glint's rasteriser rendering the same
# setup: the one point light, the environment off, no shadow maps, the 2020 model (the example's
# G-buffer has no slope derivatives), linear EXR, the same dictionary file. compare_with_render.cpp
# says what is compared and why within those tolerances. The examples' configure skips the example
# without the Vulkan loader or glslangValidator, and then so does this.
set(vulkan_example ${WORK}/build/vulkan/glint_vulkan_deferred)
if(EXISTS ${vulkan_example} AND EXAMPLE_FLAGS)
  # Under the sanitizers the Vulkan loader unloads lavapipe at vkDestroyInstance, and what the
  # driver never frees is then reported as the example's leak; the plain build runs and checks it.
  message(STATUS "examples/vulkan: built; not run in the sanitizer build (lavapipe's own leaks)")
elseif(EXISTS ${vulkan_example})
  refuse("Vulkan deferred shading, a folder as its shader" "is a directory" ${vulkan_example} ${WORK}/vulkan.exr
         --dictionary ${WORK}/dictionary.gdict --shader ${WORK})
  # Its module cut short after the header: the driver refuses it, and the line names the file.
  execute_process(COMMAND head -c 2000 ${WORK}/build/vulkan/deferred_shading.spv OUTPUT_FILE ${WORK}/cut.spv
                  RESULT_VARIABLE status)
  if(status EQUAL 0)
    refuse("Vulkan deferred shading, its shader cut short" "cut.spv: the Vulkan driver refused the shader"
           ${vulkan_example} ${WORK}/vulkan.exr --dictionary ${WORK}/dictionary.gdict --shader ${WORK}/cut.spv)
  endif()
  run("Vulkan deferred shading" ${vulkan_example} ${WORK}/vulkan.exr --dictionary ${WORK}/dictionary.gdict --size 256)
  run("glint render sphere" ${prefix}/bin/glint render sphere --size 256x256 --aa none --shadows off
      --env-intensity 0 --dict ${WORK}/dictionary.gdict -o ${WORK}/render-vulkan.exr)
  run("compare with glint render" ${RENDER_COMPARER} ${WORK}/vulkan.exr ${WORK}/render-vulkan.exr)
  message(STATUS "${run_output}")
else()
  message(STATUS "examples/vulkan was skipped (no Vulkan loader or glslangValidator when the examples were configured): its image is not checked")
endif()
