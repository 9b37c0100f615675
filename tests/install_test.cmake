# Installs the build into a temporary prefix and runs the installed program from another folder,
# with no way to reach this tree's resources: the binary must hold no path of the source or build
# tree, and the run must use the prefix's data (a preset removed from the prefix is unknown, a
# preset added to it is listed and used). Also checks the desktop entry and the MIME type.
# With PYTHON set (the module is built), the installed package is imported from the prefix and
# finds the prefix's presets too.
#   cmake -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK=... -DVERSION=... [-DPYTHON=... -DPYTHON_DIR=...]
#         -P install_test.cmake
cmake_minimum_required(VERSION 3.25)

set(prefix "${WORK}/prefix")
set(data "${prefix}/share/terrastudio")
set(exe "${prefix}/bin/terrastudio")
set(elsewhere "${WORK}/elsewhere")
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${elsewhere}")

execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${prefix}" --strip
                RESULT_VARIABLE rc OUTPUT_QUIET ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc}): ${err}")
endif()

foreach(file IN ITEMS
        bin/terrastudio
        share/terrastudio/soils/sandy-loam.json share/terrastudio/wheels/A.json
        share/terrastudio/robots/default.json share/terrastudio/scenarios/straight.json
        share/terrastudio/scripts/default.json
        share/doc/terrastudio/user-guide.md share/doc/terrastudio/cli.md
        share/doc/terrastudio/install.md share/doc/terrastudio/images/studio-forces.png
        share/applications/terrastudio.desktop share/mime/packages/terrastudio.xml
        share/icons/hicolor/scalable/apps/terrastudio.svg)
  if(NOT EXISTS "${prefix}/${file}")
    message(FATAL_ERROR "not installed: ${file}")
  endif()
endforeach()

# No compiled-in path of this tree (after stripping, only what the program itself holds).
file(READ "${exe}" binary HEX)
foreach(tree IN ITEMS "${SOURCE_DIR}" "${BUILD_DIR}")
  string(HEX "${tree}" tree_hex)
  string(TOLOWER "${tree_hex}" tree_hex)
  string(FIND "${binary}" "${tree_hex}" at)
  if(NOT at EQUAL -1)
    message(FATAL_ERROR "the installed binary holds the path ${tree}")
  endif()
endforeach()

# The desktop entry is valid and the MIME package maps *.terra to the project type.
find_program(DESKTOP_FILE_VALIDATE desktop-file-validate REQUIRED)
find_program(UPDATE_MIME_DATABASE update-mime-database REQUIRED)
execute_process(COMMAND ${DESKTOP_FILE_VALIDATE} "${prefix}/share/applications/terrastudio.desktop"
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0 OR NOT "${out}${err}" STREQUAL "")
  message(FATAL_ERROR "desktop-file-validate: ${out}${err}")
endif()
execute_process(COMMAND ${UPDATE_MIME_DATABASE} "${prefix}/share/mime" RESULT_VARIABLE rc
                ERROR_VARIABLE err)
file(STRINGS "${prefix}/share/mime/globs2" globs REGEX "application/x-terrastudio-project:\\*\\.terra")
if(NOT rc EQUAL 0 OR NOT globs)
  message(FATAL_ERROR "update-mime-database (${rc}) did not map *.terra: ${err}")
endif()

# The prefix's data, edited: snow removed, a probe soil added (sandy loam under another name).
file(REMOVE "${data}/soils/snow.json")
file(READ "${data}/soils/sandy-loam.json" soil)
string(JSON soil SET "${soil}" name "\"install probe\"")
file(WRITE "${data}/soils/install-probe.json" "${soil}")

# Runs the installed program in another folder, without TERRASTUDIO_RESOURCES.
function(installed expected_rc)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=TERRASTUDIO_RESOURCES ${exe} ${ARGN}
                  WORKING_DIRECTORY "${elsewhere}" RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT rc EQUAL expected_rc)
    message(FATAL_ERROR "terrastudio ${ARGN}: exit ${rc}, expected ${expected_rc}\n${out}${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()

installed(0 --version)
if(NOT out STREQUAL "terrastudio ${VERSION}\n")
  message(FATAL_ERROR "--version printed '${out}', expected 'terrastudio ${VERSION}'")
endif()

installed(0 presets)
if(NOT out MATCHES "install-probe" OR out MATCHES "snow" OR NOT out MATCHES "sandy-loam")
  message(FATAL_ERROR "presets did not list the prefix's soils:\n${out}")
endif()
installed(2 wheel --soil snow --entry-angle 20)
if(NOT err MATCHES "snow")
  message(FATAL_ERROR "an unknown preset must be named: ${err}")
endif()
installed(0 wheel --soil install-probe --wheel B --slip 0.2 --load 80)
if(NOT out MATCHES "^install probe, wheel B")
  message(FATAL_ERROR "wheel did not use the prefix's probe soil:\n${out}")
endif()

installed(0 run "${data}/scripts/default.json" --out "${WORK}/run")
if(NOT err STREQUAL "")
  message(FATAL_ERROR "run printed on stderr: ${err}")
endif()
file(READ "${WORK}/run/manifest.json" manifest)
string(JSON tool GET "${manifest}" tool)
if(NOT tool STREQUAL "terrastudio ${VERSION}" OR NOT EXISTS "${WORK}/run/report.md")
  message(FATAL_ERROR "run: manifest tool '${tool}', report.md exists: no")
endif()
file(GLOB images "${WORK}/run/*.png")
if(NOT images)
  message(FATAL_ERROR "run wrote no plot into ${WORK}/run")
endif()

# The Python package from the prefix only: imported from there, with the prefix's data.
if(PYTHON)
  set(package "${prefix}/${PYTHON_DIR}/terrastudio")
  if(NOT EXISTS "${package}/__init__.py" OR NOT EXISTS "${package}/__init__.pyi")
    message(FATAL_ERROR "the Python package is not installed in ${package}")
  endif()
  set(probe [=[
import sys, terrastudio as ts
assert ts.__file__.startswith(sys.argv[1]), ts.__file__
assert "install-probe" in ts.presets("soils") and "snow" not in ts.presets("soils")
out = ts.forces("install-probe", "B", slip=[0.1, 0.2], load_N=80.0)
assert out["ok"].all(), out
print(ts.__version__, ts.soil("install-probe").name)
]=])
  execute_process(COMMAND ${CMAKE_COMMAND} -E env --unset=TERRASTUDIO_RESOURCES
                          "PYTHONPATH=${prefix}/${PYTHON_DIR}" ${PYTHON} -c "${probe}" "${package}"
                  WORKING_DIRECTORY "${elsewhere}" RESULT_VARIABLE rc OUTPUT_VARIABLE out
                  ERROR_VARIABLE err)
  if(NOT rc EQUAL 0 OR NOT out STREQUAL "${VERSION} install probe\n")
    message(FATAL_ERROR "import terrastudio from the prefix (${rc}): ${out}${err}")
  endif()
endif()

file(REMOVE_RECURSE "${WORK}")
