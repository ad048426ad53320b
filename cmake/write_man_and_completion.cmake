# The man page and the bash completion of tidalcrust, both from the program's own usage text (its
# one home is src/cli: `tidalcrust --help` lists the commands, `tidalcrust CMD --help` each one's
# options). Run at build time: cmake -DEXE=... -DVERSION=... -DMAN=... -DCOMPLETION=... -P this.
foreach(var EXE VERSION MAN COMPLETION)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "write_man_and_completion.cmake: -D${var}= is required")
  endif()
endforeach()

function(usage_text out)
  execute_process(COMMAND ${EXE} ${ARGN} OUTPUT_VARIABLE text RESULT_VARIABLE rc ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${EXE} ${ARGN}: exit ${rc}: ${err}")
  endif()
  set(${out} "${text}" PARENT_SCOPE)
endfunction()

# Text as roff lines inside .nf/.fi: backslashes escaped, a leading . or ' protected.
function(roff_block out text)
  string(REPLACE "\\" "\\e" text "${text}")
  string(REGEX REPLACE "\n([.'])" "\n\\\\&\\1" text "\n${text}")
  string(REGEX REPLACE "^\n" "" text "${text}")
  set(${out} ".nf\n${text}.fi\n" PARENT_SCOPE)
endfunction()

usage_text(top --help)
# CMake lists split at ";": match on the text without them.
string(REPLACE ";" "," top_words "${top}")
string(REGEX MATCHALL "\n  [a-z]+  +[^\n]*" command_lines "${top_words}")
set(commands "")
foreach(line IN LISTS command_lines)
  string(REGEX REPLACE "^\n  ([a-z]+) .*$" "\\1" name "${line}")
  list(APPEND commands ${name})
endforeach()
list(LENGTH commands count)
if(count LESS 5)
  message(FATAL_ERROR "${EXE} --help lists ${count} commands; expected the command table")
endif()

roff_block(top_roff "${top}")
set(man ".TH TIDALCRUST 1 \"\" \"tidalcrust ${VERSION}\" \"User Commands\"\n")
string(APPEND man ".SH NAME\ntidalcrust \\- crustal failure of icy moons during strong tidal encounters\n")
string(APPEND man ".SH SYNOPSIS\n.B tidalcrust\n\\fICOMMAND\\fR [\\fIOPTIONS\\fR]\n")
string(APPEND man ".SH DESCRIPTION\nGenerated from the program's usage text (tidalcrust --help and tidalcrust COMMAND --help).\n.PP\n${top_roff}")
string(APPEND man ".SH COMMANDS\n")
set(cases "")
foreach(name IN LISTS commands)
  usage_text(help ${name} --help)
  roff_block(help_roff "${help}")
  string(APPEND man ".SS ${name}\n${help_roff}")
  string(REPLACE ";" "," help_words "${help}")
  string(REGEX MATCHALL "\n +(-[A-Za-z], )?--[a-z0-9][a-z0-9-]*" option_lines "${help_words}")
  set(options "")
  foreach(line IN LISTS option_lines)
    string(REGEX REPLACE ".*(--[a-z0-9][a-z0-9-]*)$" "\\1" option "${line}")
    list(APPEND options ${option})
  endforeach()
  list(JOIN options " " options)
  string(APPEND cases "    ${name}) options=\"${options}\" ;;\n")
endforeach()
string(APPEND man ".SH SEE ALSO\nREADME.md and docs/ of the source (docs/python.md for the Python package).\n")
file(WRITE "${MAN}" "${man}")

list(JOIN commands " " command_words)
file(WRITE "${COMPLETION}" "# bash completion for tidalcrust ${VERSION}, generated from its usage text
_tidalcrust() {
  local cur=\"\${COMP_WORDS[COMP_CWORD]}\" options=\"\"
  if [ \"\$COMP_CWORD\" -eq 1 ]; then
    COMPREPLY=( \$(compgen -W \"${command_words} --help --version\" -- \"\$cur\") )
    return
  fi
  case \"\${COMP_WORDS[1]}\" in
${cases}  esac
  if [[ \"\$cur\" == -* ]]; then
    COMPREPLY=( \$(compgen -W \"\$options\" -- \"\$cur\") )
  else
    COMPREPLY=( \$(compgen -f -- \"\$cur\") )
  fi
}
complete -o filenames -F _tidalcrust tidalcrust
")
