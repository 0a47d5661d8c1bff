# The "perturbed" suite of test_two_lights (BINARY) must fail, and its report must name the worst
# texel with its values, its inputs and the tolerance; its second case, which checks the same
# report from inside, must pass.
execute_process(COMMAND "${BINARY}" --test-suite=perturbed --no-version RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
set(report "${out}${err}")
message(STATUS "the perturbed suite's report:\n${report}")
set(problems "")
if(code EQUAL 0)
  list(APPEND problems "it passed")
endif()
foreach(pattern
    "parity two_lights_irradiance: 30000 values, [0-9]+ outside tolerance \\(allowed 0\\)"
    "worst texel \\([0-9]+, [0-9]+\\)\\.[xyz]: gpu=[-0-9.e+]+ cpu=[-0-9.e+]+ \\(abs [-0-9.e+]+ of [-0-9.e+]+ allowed, rel [-0-9.e+]+, ulp [0-9]+\\); fin0=\\("
    "fin5=\\("
    "tolerance: abs <= 6e-06 x the texel's abs_scale or rel <= 0 or ulp <= 0, allowed fraction 0 \\(two terms of Eq\\. 3\\.2"
    "test_two_lights\\.cpp:[0-9]+: ERROR: parity of two_lights_irradiance failed: [0-9]+ values outside tolerance, 0 allowed"
    "test cases: *2 \\| *1 passed \\| *1 failed")
  if(NOT report MATCHES "${pattern}")
    list(APPEND problems "the report does not match '${pattern}'")
  endif()
endforeach()
if(problems)
  message(FATAL_ERROR "the 0.1 % error was not reported as it must be: ${problems}")
endif()
