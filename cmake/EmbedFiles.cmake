# dtlab_embed_files(TARGET NAME FILES ...): compiles text files (GLSL shaders,
# protocols) into the binary as `std::string_view dtlab::embedded::NAME(name)`,
# so the executable runs from any working directory. The files stay the
# source of truth; editing one rebuilds the target.
function(dtlab_embed_files target name)
  set(out_cpp ${CMAKE_BINARY_DIR}/generated/embedded_${name}.cpp)
  add_custom_command(
    OUTPUT ${out_cpp}
    COMMAND ${CMAKE_COMMAND} -DOUT=${out_cpp} -DNAME=${name}
            "-DFILES=${ARGN}" -P ${CMAKE_SOURCE_DIR}/cmake/EmbedFilesScript.cmake
    DEPENDS ${ARGN} ${CMAKE_SOURCE_DIR}/cmake/EmbedFilesScript.cmake
    COMMENT "Embedding ${name} files"
    VERBATIM)
  target_sources(${target} PRIVATE ${out_cpp})
  # The generated file needs nothing but <string_view>: a target's precompiled
  # header would cost it more than it saves.
  set_source_files_properties(${out_cpp} PROPERTIES SKIP_PRECOMPILE_HEADERS ON)
endfunction()
