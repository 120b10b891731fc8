# Copies the add-on's Python sources, subpackages included, into the built add-on and removes
# built Python files whose source is gone (a moved module would otherwise stay in the build
# and in the zip). Files are rewritten only when they changed.
#   cmake -DSOURCE_DIR=<python_addon/torrance> -DDEST_DIR=<build/addon/torrance> -P sync_addon.cmake
# The native package (DEST_DIR/torrance_core) is left alone: the addon target copies it.
cmake_minimum_required(VERSION 3.21)     # file(COPY_FILE)
file(GLOB_RECURSE sources RELATIVE "${SOURCE_DIR}" "${SOURCE_DIR}/*.py")
foreach(source IN LISTS sources)
  get_filename_component(folder "${DEST_DIR}/${source}" DIRECTORY)
  file(MAKE_DIRECTORY "${folder}")
  file(COPY_FILE "${SOURCE_DIR}/${source}" "${DEST_DIR}/${source}" ONLY_IF_DIFFERENT)
endforeach()

file(GLOB_RECURSE built RELATIVE "${DEST_DIR}" "${DEST_DIR}/*.py")
foreach(built_file IN LISTS built)
  if(NOT built_file MATCHES "^torrance_core/" AND NOT built_file IN_LIST sources)
    file(REMOVE "${DEST_DIR}/${built_file}")
  endif()
endforeach()
