# ctest build.release_program: the Release program of these sources in its own folder (BIN),
# for the tests that must run on both builds (a crash seen in Release only, issue 32).
#   cmake -DSRC=<source dir> -DBIN=<build dir> -P release_program.cmake
execute_process(COMMAND ${CMAKE_COMMAND} -S ${SRC} -B ${BIN} -G Ninja
                        -DCMAKE_Fortran_COMPILER=gfortran -DCMAKE_BUILD_TYPE=Release
                        -DSPALLBAR_BUILD_TESTING=OFF
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "release_program: configure failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BIN} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "release_program: build failed (${rc})")
endif()
