# Include directories: each library publishes its own folder, and nothing else.
#
# Sources and headers include each other by folder: "core/mesh/mesh.h", "gl/context.h",
# "export/json.h". The directory that holds core/, gl/, export/ and cli/ side by side is the
# repository root, and publishing it would let a target that links only inkline_core include
# gl/, export/ or cli/ headers as well. So each folder gets a directory of its own in the build
# tree, holding a single symbolic link named like the folder and pointing at it:
#
#   <build>/include/core/core -> <source>/core
#
# A target sees its own folder through it, and the folders of what it links, and no other. The
# link is made at configure time and is live: edited and new headers need no copy step. Installed,
# the headers keep these relative paths under include/inkline/ (see cmake/package.cmake).

# Makes `<build>/include/<folder>/<folder>` a link to the source folder and returns its parent
# directory, ready for target_include_directories, in `out_var`.
function(inkline_folder_include_dir folder out_var)
  set(stage ${PROJECT_BINARY_DIR}/include/${folder})
  file(MAKE_DIRECTORY ${stage})
  file(CREATE_LINK ${PROJECT_SOURCE_DIR}/${folder} ${stage}/${folder} SYMBOLIC)
  set(${out_var} ${stage} PARENT_SCOPE)
endfunction()

# A library of the package, inkline::<folder> in this build (ALIAS) and installed (EXPORT_NAME).
# Include directories: its folder in this build; once installed, include/inkline (the headers
# include each other as "core/...") and include (for <inkline/core/...>). C++20 for it and for
# every target that links it.
function(inkline_library_interface target folder)
  add_library(inkline::${folder} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${folder})
  inkline_folder_include_dir(${folder} stage)
  target_include_directories(${target} PUBLIC
    $<BUILD_INTERFACE:${stage}>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}/inkline>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(${target} PUBLIC cxx_std_20)
endfunction()

# Installs a library and the public headers of its folder: every .h except those under an
# internal/ folder, which are the folder's own business.
function(inkline_install_library target folder)
  install(TARGETS ${target} EXPORT inklineTargets
          ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
          LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
          RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${folder}/ DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/inkline/${folder}
          FILES_MATCHING PATTERN "*.h" PATTERN "internal" EXCLUDE)
endfunction()
