# Generates the OpenGL 3.3 core loader with Debian's glad (python3-glad) at
# build time. --reproducible makes glad use its packaged gl.xml, so nothing is
# downloaded. The loader is C and is compiled without our warning flags.
find_program(GLAD_EXECUTABLE glad REQUIRED)
set(GLAD_OUT ${CMAKE_BINARY_DIR}/glad)
add_custom_command(
  OUTPUT ${GLAD_OUT}/src/gl.c ${GLAD_OUT}/include/glad/gl.h
  COMMAND ${GLAD_EXECUTABLE} --quiet --reproducible --api gl:core=3.3
          --out-path ${GLAD_OUT} c --loader
  COMMENT "Generating the GL 3.3 core loader (glad)"
  VERBATIM)
add_library(dtlab_glad STATIC ${GLAD_OUT}/src/gl.c)
target_include_directories(dtlab_glad SYSTEM PUBLIC ${GLAD_OUT}/include)
set_target_properties(dtlab_glad PROPERTIES POSITION_INDEPENDENT_CODE ON)
target_link_libraries(dtlab_glad PUBLIC ${CMAKE_DL_LIBS})
