# Warnings for Krug's own targets. Dependencies come in as SYSTEM includes (imported targets), so
# their headers do not trip -Werror. GCC 12 raises known false positives in -O2 code paths through
# std::vector and std::variant; those stay warnings, never errors.
function(krug_set_warnings target)
  target_compile_options(${target} PRIVATE
    -Wall -Wextra -Wpedantic -Wshadow -Wconversion -Wno-sign-conversion
    $<$<BOOL:${KRUG_WERROR}>:-Werror>
    $<$<CXX_COMPILER_ID:GNU>:-Wno-error=array-bounds -Wno-error=stringop-overflow -Wno-error=maybe-uninitialized>)
  if(KRUG_SANITIZE)
    target_compile_options(${target} PRIVATE -fsanitize=${KRUG_SANITIZE} -fno-omit-frame-pointer)
    target_link_options(${target} PUBLIC -fsanitize=${KRUG_SANITIZE})
  endif()
endfunction()
