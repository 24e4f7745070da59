# Our own code builds with every warning as an error; third-party headers are
# included as SYSTEM so their warnings do not count against us.
function(lc_strict_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Werror -Wno-missing-field-initializers)
endfunction()

# Sources named *_cxx17.cpp are compiled as C++17: LEMON 1.3.1 headers do not
# compile under C++20 (std::allocator::construct was removed).
function(lc_cxx17_sources target)
  get_target_property(srcs ${target} SOURCES)
  foreach(src IN LISTS srcs)
    if(src MATCHES "_cxx17\\.cpp$")
      set_source_files_properties(${src} TARGET_DIRECTORY ${target} PROPERTIES COMPILE_OPTIONS "-std=c++17")
    endif()
  endforeach()
endfunction()
