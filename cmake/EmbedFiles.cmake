# svo_embed_files(<target> <namespace> <function> <files...>)
# Generates a C++ source defining `const std::map<std::string, std::string>&
# <namespace>::<function>()`, which maps each file's base name to its text, so
# shaders live as .glsl files beside the code that runs them but ship inside
# the binary. Each GL layer embeds its own shaders under its own function.
function(svo_embed_files target ns fn)
  set(out "${CMAKE_CURRENT_BINARY_DIR}/${target}_${fn}.cpp")
  set(script "${CMAKE_CURRENT_BINARY_DIR}/${target}_${fn}.cmake")
  file(WRITE "${script}" "
set(content \"// Generated from shader files; edit those instead.\\n#include <map>\\n#include <string>\\nnamespace ${ns} {\\nconst std::map<std::string, std::string>& ${fn}() {\\n  static const std::map<std::string, std::string> files = {\\n\")
foreach(f \${FILES})
  get_filename_component(name \"\${f}\" NAME)
  file(READ \"\${f}\" text)
  string(APPEND content \"    {\\\"\${name}\\\", R\\\"svo_embed(\${text})svo_embed\\\"},\\n\")
endforeach()
string(APPEND content \"  };\\n  return files;\\n}\\n}\\n\")
file(WRITE \"\${OUT}.tmp\" \"\${content}\")
execute_process(COMMAND \${CMAKE_COMMAND} -E copy_if_different \"\${OUT}.tmp\" \"\${OUT}\")
")
  set(abs_files)
  foreach(f ${ARGN})
    get_filename_component(a "${f}" ABSOLUTE)
    list(APPEND abs_files "${a}")
  endforeach()
  string(REPLACE ";" "\\;" files_arg "${abs_files}")
  add_custom_command(OUTPUT "${out}"
    COMMAND ${CMAKE_COMMAND} "-DFILES=${files_arg}" "-DOUT=${out}" -P "${script}"
    DEPENDS ${abs_files} "${script}"
    COMMENT "Embedding shader files for ${target}")
  target_sources(${target} PRIVATE "${out}")
endfunction()
