# Build-enforced layering. Sources include project headers relative to the project root
# ("solver/model/model.hpp"), but no target has the project root on its include path: each library
# gets an include root of its own in the build tree holding symlinks to only the source folders
# it may include from, as its PUBLIC include directory. An upward include ("solver/..." from
# contact/) then fails to compile with "No such file or directory".
#
#   common   <- everyone
#   elements -> common                 contact -> common
#   partition -> elements, contact, common   (it uses common only today)
#   solver   -> partition, elements, contact, common
#   io       -> solver, partition, elements, contact, common   (io/deck)
#               solver, common                      (io/results, io/result_tools: the solver's
#                                                    types only; elements/ and contact/ reach
#                                                    them through solver's headers, so only
#                                                    the layering_sources test enforces it)
#   apps     -> io and below, through the libraries they link
#   tests    -> what the library they test exposes, plus their own folder
#
# Within a folder, subfolders may be layered too (xpl_sublayers): elements/hex/ and
# elements/shell/ (one element kind each) include elements/material/, elements/parallel/ and
# the headers directly in elements/, never each other, so that a new kind is one new folder:
#
#   elements/<kind>/  -> elements/material, elements/parallel, elements/*.hpp
#   elements/material -> elements/parallel        elements/*.hpp -> elements/parallel
#
# The layering_sources test checks these (the include roots cannot: they are per folder).
#
# A library's consumers see its root through PUBLIC propagation: that is safe because every
# root is a subset of the roots of the layers above it (solver links contact PUBLIC, and
# contact's root holds only common/ and contact/). The one path around the roots is a quoted
# include relative to the including file ("../solver/model/model.hpp"), which the layering_sources
# test forbids (tests/layering/check_sources.cmake).

set(XPL_INCLUDE_ROOTS_DIR ${PROJECT_BINARY_DIR}/include_roots)

# xpl_layer(<target> <folder>...): <target>'s sources and everything linking <target> may
# include "<folder>/..." for the folders listed (top-level folders of the source tree).
function(xpl_layer target)
  set(root ${XPL_INCLUDE_ROOTS_DIR}/${target})
  file(MAKE_DIRECTORY ${root})
  # A folder dropped from the list must lose its link (file(REMOVE) removes a link, never
  # what it points to).
  file(GLOB entries LIST_DIRECTORIES true RELATIVE ${root} ${root}/*)
  foreach(entry IN LISTS entries)
    if(NOT entry IN_LIST ARGN)
      file(REMOVE ${root}/${entry})
    endif()
  endforeach()
  foreach(folder IN LISTS ARGN)
    if(NOT IS_DIRECTORY ${PROJECT_SOURCE_DIR}/${folder})
      message(FATAL_ERROR "xpl_layer(${target}): no folder ${folder}/ in the source tree")
    endif()
    if(NOT IS_SYMLINK ${root}/${folder})
      file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${root}/${folder} SYMBOLIC)
    endif()
  endforeach()
  target_include_directories(${target} PUBLIC $<BUILD_INTERFACE:${root}>)
  set_property(TARGET ${target} PROPERTY XPL_LAYER_FOLDERS ${ARGN})
  set_property(GLOBAL APPEND PROPERTY XPL_LAYERED_TARGETS ${target})
endfunction()

# xpl_sublayers(<folder> <sub>=<subs it may include>...): files in <folder>/<sub>/ may include
# "<folder>/<x>/..." only for x = <sub> or one of the listed subfolders; <sub> "." stands for
# the files directly in <folder>/. Any subfolder of <folder> not listed is unrestricted.
function(xpl_sublayers folder)
  foreach(entry IN LISTS ARGN)
    set_property(GLOBAL APPEND PROPERTY XPL_SUBLAYERS "${folder}/${entry}")
  endforeach()
endfunction()

# Every target built in <folder>... (and their subfolders) must have a layer. Writes the table
# that check_sources.cmake reads: one "<folder of the target>=<folders it may include>" entry
# per target.
function(xpl_check_layers)
  set(dirs ${ARGN})
  set(table "")
  while(dirs)
    list(POP_FRONT dirs dir)
    get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
    list(APPEND dirs ${subdirs})
    get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
    foreach(target IN LISTS targets)
      get_target_property(type ${target} TYPE)
      if(type STREQUAL "INTERFACE_LIBRARY")
        continue()
      endif()
      get_target_property(folders ${target} XPL_LAYER_FOLDERS)
      if(NOT folders)
        message(FATAL_ERROR "${target} has no layer: add xpl_layer(${target} <folders>) to "
                            "${PROJECT_SOURCE_DIR}/CMakeLists.txt (see cmake/xpl_layering.cmake)")
      endif()
      get_target_property(source_dir ${target} SOURCE_DIR)
      file(RELATIVE_PATH folder ${PROJECT_SOURCE_DIR} ${source_dir})
      list(JOIN folders "," folders)
      string(APPEND table "list(APPEND XPL_LAYERS \"${folder}=${folders}\") # ${target}\n")
    endforeach()
  endwhile()
  get_property(sublayers GLOBAL PROPERTY XPL_SUBLAYERS)
  foreach(entry IN LISTS sublayers)
    string(APPEND table "list(APPEND XPL_SUBLAYERS \"${entry}\")\n")
  endforeach()
  file(WRITE ${XPL_INCLUDE_ROOTS_DIR}/layers.cmake "${table}")
endfunction()
