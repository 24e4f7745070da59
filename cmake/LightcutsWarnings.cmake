# Our own code builds with every warning as an error; third-party headers are
# included as SYSTEM so their warnings do not count against us.
function(lc_strict_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Werror -Wno-missing-field-initializers)
endfunction()

# The named sources compile as C++17: LEMON 1.3.1's headers do not compile
# under C++20 (std::allocator::construct was removed).
function(lc_cxx17_sources target)
  foreach(src IN LISTS ARGN)
    set_source_files_properties(${src} TARGET_DIRECTORY ${target} PROPERTIES COMPILE_OPTIONS "-std=c++17")
  endforeach()
endfunction()
