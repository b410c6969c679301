# SPDX-License-Identifier: GPL-3.0-or-later
# Man pages and bash completion of the tools, made from each tool's --help at build time:
# share/man/man1/TOOL.1 (help2man: scripts/man_page.sh) and
# share/bash-completion/completions/TOOL (scripts/bash_completion.py) in the build tree,
# installed under the prefix alike. Each is left out, with a message, when its generator
# (help2man; Python 3) is missing.
function(section_tool_docs)
  find_program(SECTION_HELP2MAN help2man)
  find_package(Python3 COMPONENTS Interpreter QUIET)
  if(NOT SECTION_HELP2MAN)
    message(STATUS "help2man not found: no man pages (Debian: apt install help2man)")
  endif()
  if(NOT Python3_Interpreter_FOUND)
    message(STATUS "Python 3 not found: no bash completion")
  endif()
  set(outputs "")
  foreach(tool ${ARGN})
    if(SECTION_HELP2MAN)
      set(page ${PROJECT_BINARY_DIR}/share/man/man1/${tool}.1)
      add_custom_command(OUTPUT ${page}
        COMMAND bash ${PROJECT_SOURCE_DIR}/scripts/man_page.sh ${SECTION_HELP2MAN} $<TARGET_FILE:${tool}>
                ${PROJECT_VERSION} ${page}
        DEPENDS ${tool} ${PROJECT_SOURCE_DIR}/scripts/man_page.sh
        COMMENT "man page of ${tool}" VERBATIM)
      install(FILES ${page} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1)
      list(APPEND outputs ${page})
    endif()
    if(Python3_Interpreter_FOUND)
      set(completion ${PROJECT_BINARY_DIR}/share/bash-completion/completions/${tool})
      add_custom_command(OUTPUT ${completion}
        COMMAND ${Python3_EXECUTABLE} ${PROJECT_SOURCE_DIR}/scripts/bash_completion.py $<TARGET_FILE:${tool}>
                ${completion}
        DEPENDS ${tool} ${PROJECT_SOURCE_DIR}/scripts/bash_completion.py
        COMMENT "bash completion of ${tool}" VERBATIM)
      install(FILES ${completion} DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions)
      list(APPEND outputs ${completion})
    endif()
  endforeach()
  if(outputs)
    add_custom_target(tool_docs ALL DEPENDS ${outputs})
  endif()
endfunction()
