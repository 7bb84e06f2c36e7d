# harnesses.cmake - the harnesses and the parser code each one links, shared
# by the libFuzzer build (libfuzzer/CMakeLists.txt, clang) and the replay
# build (CMakeLists.txt, the project's compiler).  The includer sets
#   ARBOR_SOURCE_DIR            the repository root
#   ARBOR_FUZZ_COMPILE_OPTIONS  sanitizers (and coverage) for every source here
#   ARBOR_FUZZ_LINK_OPTIONS     for the harness executables
#   ARBOR_FUZZ_DRIVER           "" (libFuzzer's main) or a source with main()
#   ARBOR_FUZZ_PLUGIN_DIR       the built plugins (the session harness loads them)
#   ARBOR_FUZZ_HOST_SOURCES     app/core, app/host and app/pipeline sources, and
#   ARBOR_FUZZ_HOST_DEFINITIONS their definitions, as app/CMakeLists.txt lists them
# and calls arbor_fuzz_harnesses(<suffix>): one executable <harness><suffix>
# per harness.  The parser sources are compiled here, with the sanitizers,
# rather than taken from the project's libraries, which are built without.

include(${CMAKE_CURRENT_LIST_DIR}/harness_names.cmake)

find_package(Threads REQUIRED)
find_package(ZLIB REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(DCMTK REQUIRED CONFIG)
find_package(PkgConfig REQUIRED)
pkg_check_modules(ARBOR_FUZZ_OPENJP2 REQUIRED IMPORTED_TARGET libopenjp2)
pkg_check_modules(ARBOR_FUZZ_XXHASH REQUIRED IMPORTED_TARGET libxxhash)
find_package(VTK 9.1 REQUIRED COMPONENTS
  CommonCore CommonDataModel CommonExecutionModel IOCore IOImage IOLegacy IOXML IOXMLParser)
find_package(OpenCV 4 REQUIRED COMPONENTS core)

set(_root ${ARBOR_SOURCE_DIR})
set(_fuzz ${_root}/tests/fuzz)

function(_arbor_fuzz_library name)
  add_library(${name} STATIC ${ARGN})
  target_compile_options(${name} PRIVATE ${ARBOR_FUZZ_COMPILE_OPTIONS})
  target_include_directories(${name} PUBLIC ${_root}/sdk/include ${_root}/sdk/cpp/include)
endfunction()

# The host (what it does with an importer: host/volume_import.cpp and what
# it calls) and the pipeline (its readers of sessions and transfer
# functions); a static library, so a harness links only what it uses.  Of
# io/, the transfer-function file needs the JSON writer.
_arbor_fuzz_library(arbor_fuzz_host ${ARBOR_FUZZ_HOST_SOURCES} ${_root}/app/io/json_writer.cpp)
target_include_directories(arbor_fuzz_host PUBLIC ${_root}/app)
target_include_directories(arbor_fuzz_host SYSTEM PUBLIC ${OpenCV_INCLUDE_DIRS})
target_compile_definitions(arbor_fuzz_host PRIVATE ${ARBOR_FUZZ_HOST_DEFINITIONS})
target_link_libraries(arbor_fuzz_host PUBLIC nlohmann_json::nlohmann_json PkgConfig::ARBOR_FUZZ_XXHASH
  Threads::Threads ${CMAKE_DL_LIBS})

# The harnesses' own helpers.
_arbor_fuzz_library(arbor_fuzz_support ${_fuzz}/fuzz_support.cpp ${_fuzz}/host_import.cpp)
target_include_directories(arbor_fuzz_support PUBLIC ${_fuzz})
target_link_libraries(arbor_fuzz_support PUBLIC arbor_fuzz_host)

# The importer plugin libraries, entry point included (each harness links one).
file(GLOB _importers CONFIGURE_DEPENDS ${_root}/plugins/importers/*.cpp)
_arbor_fuzz_library(arbor_fuzz_importers ${_importers})
target_include_directories(arbor_fuzz_importers PUBLIC ${_root}/plugins/importers)
target_link_libraries(arbor_fuzz_importers PUBLIC ZLIB::ZLIB)

file(GLOB _importer_vtk CONFIGURE_DEPENDS ${_root}/plugins/importer-vtk/*.cpp)
_arbor_fuzz_library(arbor_fuzz_importer_vtk ${_importer_vtk})
target_include_directories(arbor_fuzz_importer_vtk PUBLIC ${_root}/plugins/importer-vtk)
target_link_libraries(arbor_fuzz_importer_vtk PUBLIC ZLIB::ZLIB ${VTK_LIBRARIES})

# The DICOM library (dicom/) and its importer plugin.
_arbor_fuzz_library(arbor_fuzz_dicom
  ${_root}/dicom/dcmtk_setup.cpp
  ${_root}/dicom/folder_scan.cpp
  ${_root}/dicom/image_record.cpp
  ${_root}/dicom/jpeg2000_codestream.cpp
  ${_root}/dicom/multipart_stream.cpp
  ${_root}/dicom/pixel_frames.cpp
  ${_root}/dicom/series_volume.cpp
  ${_root}/dicom/slice_stack.cpp)
target_include_directories(arbor_fuzz_dicom PUBLIC ${_root})
target_link_libraries(arbor_fuzz_dicom PUBLIC
  DCMTK::dcmdata DCMTK::dcmjpeg DCMTK::dcmjpls DCMTK::oflog DCMTK::ofstd PkgConfig::ARBOR_FUZZ_OPENJP2)

_arbor_fuzz_library(arbor_fuzz_importer_dicom ${_root}/plugins/importer-dicom/dicom_importer.cpp)
target_link_libraries(arbor_fuzz_importer_dicom PUBLIC arbor_fuzz_dicom)

# What each harness links besides arbor_fuzz_support.
set(_links_nrrd arbor_fuzz_importers)
set(_links_metaimage arbor_fuzz_importers)
set(_links_nifti arbor_fuzz_importer_vtk)
set(_links_vtk_image arbor_fuzz_importer_vtk)
set(_links_jpeg2000 arbor_fuzz_dicom)
set(_links_dicom_file arbor_fuzz_dicom)
set(_links_dicom_series arbor_fuzz_importer_dicom)
set(_links_multipart arbor_fuzz_dicom)
set(_links_session)
set(_links_transfer_functions)

function(arbor_fuzz_harnesses suffix)
  foreach(h ${ARBOR_FUZZ_HARNESSES})
    set(target ${h}${suffix})
    add_executable(${target} ${_fuzz}/${h}.cpp ${ARBOR_FUZZ_DRIVER})
    target_compile_options(${target} PRIVATE ${ARBOR_FUZZ_COMPILE_OPTIONS})
    target_link_options(${target} PRIVATE ${ARBOR_FUZZ_LINK_OPTIONS})
    target_link_libraries(${target} PRIVATE arbor_fuzz_support ${_links_${h}})
    set_target_properties(${target} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_CURRENT_BINARY_DIR}/bin)
  endforeach()
  target_compile_definitions(session${suffix} PRIVATE ARBOR_FUZZ_PLUGIN_DIR="${ARBOR_FUZZ_PLUGIN_DIR}")
  vtk_module_autoinit(TARGETS nifti${suffix} vtk_image${suffix} MODULES ${VTK_LIBRARIES})
endfunction()
