# SPDX-License-Identifier: MIT
# The pip wheel (pyproject.toml, scikit-build-core; scripts/build_wheel.sh): with -DSILK_WHEEL=ON
# libsilk loads onnxruntime at run time (cmake/SilkOnnxRuntime.cmake), zlib is linked statically, and
# silk_wheel_install() adds install rules in the component `silk_wheel` alone, the one the wheel
# installs, so the normal build and `cmake --install` are unchanged. libstdc++ and libgcc stay the
# system's shared ones (manylinux allows them; auditwheel checks the versions): linked statically
# from Debian bookworm they reference glibc 2.35/2.36 (_dl_find_object, arc4random), which would
# raise the tag to manylinux_2_36 (docs/wheel.md). Layout inside site-packages:
#   silk_mesh/lib/libsilk.so.<major>   (onnxruntime: the onnxruntime package, loaded at run time)
#   silk_mesh/lib/libsilk_ops.so       (the ai.silk kernels for Python's onnxruntime; engine/kernels)
#   silk_mesh/bin/silkgen, silktok     (RPATH $ORIGIN/../lib; run through the console scripts)
#   silk_mesh/model/                   (the bundled model, where silk_mesh and silkgen look first)
# The Python packages silk_mesh and silk_export come from pyproject.toml's wheel.packages.
if(NOT SILK_WHEEL)
  return()
endif()
# zlib inside libsilk too (CMake >= 3.24 honours this), so auditwheel has nothing to graft.
set(ZLIB_USE_STATIC_LIBS ON)

function(silk_wheel_install)
  # One file under the soname (a wheel has no symbolic links).
  set_target_properties(silk PROPERTIES VERSION ${PROJECT_VERSION_MAJOR})
  install(TARGETS silk LIBRARY DESTINATION silk_mesh/lib NAMELINK_SKIP COMPONENT silk_wheel)
  # libsilk_ops beside it: silk_export's onnxruntime sessions register the ai.silk kernels from it.
  install(TARGETS silk_ops LIBRARY DESTINATION silk_mesh/lib COMPONENT silk_wheel)
  foreach(app silkgen silktok)
    if(TARGET ${app})
      set_target_properties(${app} PROPERTIES INSTALL_RPATH "$ORIGIN/../lib")
      install(TARGETS ${app} RUNTIME DESTINATION silk_mesh/bin COMPONENT silk_wheel)
    endif()
  endforeach()
  # The model files the add-on carries too (scripts/make_blender_addon.sh): not the training plot.
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/models/default/ DESTINATION silk_mesh/model COMPONENT silk_wheel
          PATTERN "*.png" EXCLUDE)
endfunction()
