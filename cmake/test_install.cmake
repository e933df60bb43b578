# CTest "install:consumer": cmake --install the build tree into a prefix outside it
# (BUILD-install-test/prefix), then, with the build tree out of view (programs outside it
# never look there, REFRACT_IMAGE_IO empty) and from outside the checkout: render with the
# installed `refract`, list the installed validation suite, build examples/cpp against the
# prefix alone and render with it, and render from the installed Python package.
# cmake -DBUILD=... -DSOURCE=... [-DPYTHON=...] -P cmake/test_install.cmake
set(root ${BUILD}-install-test)
set(prefix ${root}/prefix)
file(REMOVE_RECURSE ${root})
file(MAKE_DIRECTORY ${root})
function(run)
  execute_process(COMMAND ${CMAKE_COMMAND} -E env REFRACT_IMAGE_IO= ${ARGN} WORKING_DIRECTORY ${root}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  message("${out}")
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(last_output "${out}" PARENT_SCOPE)
endfunction()
function(expect_file f)
  if(NOT EXISTS ${f})
    message(FATAL_ERROR "not written: ${f}")
  endif()
endfunction()

run(${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix})
foreach(f include/refract/core/render.h lib/cmake/refract/refractConfig.cmake lib/cmake/refract/refractTargets.cmake
          lib/refract/librefract_image_io.so share/refract/scenes/validation/fresnel-sphere.json)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()

# The command line.
file(WRITE ${root}/sphere.json [[{"camera": {"location": [0, 0, -4], "width": 16, "height": 12},
  "background": [1, 1, 1], "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1,
  "material": {"type": "dielectric", "ior": 1.5}}]}]])
run(${prefix}/bin/refract render ${root}/sphere.json -o ${root}/cli.png)
expect_file(${root}/cli.png)
run(${prefix}/bin/refract validate --list)
if(NOT last_output MATCHES "fresnel-sphere")
  message(FATAL_ERROR "the installed validation suite was not found: ${last_output}")
endif()

# A C++ program built against the prefix.
run(${CMAKE_COMMAND} -S ${SOURCE}/examples/cpp -B ${root}/consumer -G Ninja -DCMAKE_BUILD_TYPE=Release
    -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${root}/consumer)
run(${root}/consumer/glass_sphere ${root}/cpp.png)
if(NOT last_output MATCHES "radiance 1\\.0000000000")
  message(FATAL_ERROR "unexpected consumer output: ${last_output}")
endif()
expect_file(${root}/cpp.png)

# The Python package.
if(PYTHON)
  file(GLOB_RECURSE init ${prefix}/lib/*/__init__.py)
  list(FILTER init INCLUDE REGEX "/refract/__init__.py$")
  list(GET init 0 init)
  get_filename_component(pkg ${init} DIRECTORY)
  get_filename_component(site ${pkg} DIRECTORY)
  foreach(f py.typed __init__.pyi optics.pyi)
    expect_file(${pkg}/${f})
  endforeach()
  file(WRITE ${root}/check_module.py
       "import refract\n"
       "assert refract.__file__.startswith('${prefix}'), refract.__file__\n"
       "print('installed module', refract.__version__, ': R(normal, 1.5) =', refract.optics.fresnel(1.0, 1.5).R)\n"
       "refract.write_image('${root}/py.png', refract.render('${root}/sphere.json').rgb)\n")
  run(${CMAKE_COMMAND} -E env PYTHONPATH=${site} ${PYTHON} ${root}/check_module.py)
  if(NOT last_output MATCHES "R\\(normal, 1.5\\) = 0.04")
    message(FATAL_ERROR "the installed module did not load: ${last_output}")
  endif()
  expect_file(${root}/py.png)
endif()
file(REMOVE_RECURSE ${root})
