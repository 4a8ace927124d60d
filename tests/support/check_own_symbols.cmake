# Fails unless every weak symbol an object file defines lies in NAMESPACE:
# a weak symbol is kept once by the linker, so a template instantiated in an
# object built for AVX2 could otherwise replace the baseline's copy and run on
# a processor without AVX2.
#   cmake -DOBJECTS=a.o;b.o -DNAMESPACE=name -P check_own_symbols.cmake
execute_process(COMMAND nm -C --defined-only ${OBJECTS} OUTPUT_VARIABLE symbols RESULT_VARIABLE failed)
if(failed)
  message(FATAL_ERROR "nm could not read ${OBJECTS}")
endif()
string(REPLACE "\n" ";" lines "${symbols}")
set(own 0)
foreach(line ${lines})
  if(line MATCHES "^[0-9a-f]+ [WVu] (.*)$")
    if(CMAKE_MATCH_1 MATCHES "^${NAMESPACE}::")
      math(EXPR own "${own} + 1")
    else()
      message(SEND_ERROR "${OBJECTS} defines a weak symbol outside ${NAMESPACE}: ${CMAKE_MATCH_1}")
    endif()
  endif()
endforeach()
if(own EQUAL 0)
  message(FATAL_ERROR "${OBJECTS} defines no weak symbol in ${NAMESPACE}: is the namespace renamed?")
endif()
message(STATUS "${own} weak symbols, all in ${NAMESPACE}")
