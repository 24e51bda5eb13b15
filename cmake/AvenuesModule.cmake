# The build's two conventions for modules (README, "Layout").
#
# avenues_module(TARGET DIR): TARGET publishes DIR's headers and nothing else.
# Includes are written from the source root ("cells/cell_complex.h"). Rather than putting
# the whole root on every include path (which lets any module include any other and keeps
# the layering by habit only), each library gets an include root of its own in the build
# tree, holding a link to each header directly in DIR (not its subfolders: plans/ does
# not publish plans/formats/). A target sees a module's headers only if it links that
# module's library, so the one-way flow
#   core -> plans -> plans/formats -> cells -> visibility -> render -> app
# is enforced by target_link_libraries: an include that reaches up does not compile.
function(avenues_module target dir)
  set(root ${PROJECT_BINARY_DIR}/include/${target})
  file(REMOVE_RECURSE ${root})
  file(MAKE_DIRECTORY ${root}/${dir})
  file(GLOB headers CONFIGURE_DEPENDS RELATIVE ${PROJECT_SOURCE_DIR}/${dir} ${PROJECT_SOURCE_DIR}/${dir}/*.h)
  foreach(h ${headers})
    file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${dir}/${h} ${root}/${dir}/${h} SYMBOLIC)
  endforeach()
  target_include_directories(${target} PUBLIC ${root})
endfunction()

# avenues_sources(VAR DIR): the one convention for source lists. A module's library is
# every .cpp directly in its folder, one concept per file; a file added there joins it
# (CONFIGURE_DEPENDS re-globs on each build).
function(avenues_sources var dir)
  file(GLOB sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${dir}/*.cpp)
  set(${var} ${sources} PARENT_SCOPE)
endfunction()
