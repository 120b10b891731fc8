# Writes CMake's project version into the bl_info of the assembled add-on's __init__.py.
#
#   cmake -DINIT_PY=<build>/addon/torrance/__init__.py -DVERSION=0.1.0 -P cmake/addon_version.cmake
#
# Blender reads bl_info by parsing __init__.py (ast), without running it, so the version has to be
# a literal tuple in the file Blender loads. The source python_addon/torrance/__init__.py holds a
# placeholder tuple; this replaces the tuple on the line `"version": (...),` and fails when that
# line is not there exactly once.
if(NOT INIT_PY OR NOT VERSION)
  message(FATAL_ERROR "addon_version.cmake: pass -DINIT_PY=<file> -DVERSION=<major.minor.patch>")
endif()
if(NOT VERSION MATCHES "^([0-9]+)\\.([0-9]+)\\.([0-9]+)$")
  message(FATAL_ERROR "addon_version.cmake: VERSION '${VERSION}' is not major.minor.patch")
endif()
set(tuple "(${CMAKE_MATCH_1}, ${CMAKE_MATCH_2}, ${CMAKE_MATCH_3})")

file(READ "${INIT_PY}" text)
set(pattern "\n([ \t]*\"version\":[ \t]*)\\([0-9, \t]*\\)")
string(REGEX MATCHALL "${pattern}" found "${text}")
list(LENGTH found count)
if(NOT count EQUAL 1)
  message(FATAL_ERROR "addon_version.cmake: expected one '\"version\": (...)' line in ${INIT_PY}, found ${count}")
endif()
string(REGEX REPLACE "${pattern}" "\n\\1${tuple}" text "${text}")
file(WRITE "${INIT_PY}" "${text}")
