# glint_embedded_shaders(ROOT OUTPUT): a rule writing OUTPUT, a C++ source defining
# glint::gl::embeddedFiles() with the shaders of ROOT/shaders and the kernel headers of
# ROOT/src/glint/kernel (cmake/embed_files.cmake), for the desktop build and the page's (web/).
function(glint_embedded_shaders root output)
  file(GLOB files CONFIGURE_DEPENDS ${root}/shaders/*.glsl ${root}/shaders/*.vert ${root}/shaders/*.frag
       ${root}/shaders/*.comp ${root}/src/glint/kernel/*.h)
  string(REPLACE ";" "|" list "${files}")
  add_custom_command(
    OUTPUT ${output}
    COMMAND ${CMAKE_COMMAND} -DOUTPUT=${output} "-DINPUTS=${list}" -P ${root}/cmake/embed_files.cmake
    DEPENDS ${files} ${root}/cmake/embed_files.cmake
    COMMENT "Embedding shaders"
    VERBATIM)
endfunction()
