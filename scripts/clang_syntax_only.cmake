# Writes a makefile that runs every command of compile_commands.json with -fsyntax-only (one
# target per translation unit, so that make -jN checks them in parallel). Used by
# scripts/check-clang --syntax-only.
#   cmake -DCOMPILE_COMMANDS=build-clang/compile_commands.json -DMAKEFILE=out.mk -P this-file
# Optional -DSKIP=REGEX leaves out the files whose path matches it (CI: the tests and benchmarks).
cmake_minimum_required(VERSION 3.25)
file(READ "${COMPILE_COMMANDS}" commands)
string(JSON count LENGTH "${commands}")
math(EXPR last "${count} - 1")
set(rules "")
set(targets "")
foreach(i RANGE ${last})
  string(JSON directory GET "${commands}" ${i} directory)
  string(JSON command GET "${commands}" ${i} command)
  string(JSON file GET "${commands}" ${i} file)
  if(SKIP AND file MATCHES "${SKIP}")
    continue()
  endif()
  # make expands $: a literal dollar sign is $$.
  string(REPLACE "$" "$$" command "${command}")
  string(APPEND rules "tu${i}:\n\t@echo 'syntax  ${file}'\n\t@cd '${directory}' && ${command} -fsyntax-only\n")
  string(APPEND targets " tu${i}")
endforeach()
file(WRITE "${MAKEFILE}" ".PHONY: all${targets}\nall:${targets}\n${rules}")
