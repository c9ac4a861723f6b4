# Attach deal.II to one target without deal_ii_initialize_cached_variables() (which
# empties CMAKE_CXX_FLAGS_RELEASE for every target) and without deal_ii_setup_target()
# (plain link signature, flags added PUBLIC).
include(${DEAL_II_TARGET_CONFIG})

function(upgrain_use_dealii target)
  if(CMAKE_BUILD_TYPE STREQUAL "Debug")
    set(_flavor DEBUG)
  else()
    set(_flavor RELEASE)
  endif()
  target_include_directories(${target} SYSTEM PRIVATE ${DEAL_II_INCLUDE_DIRS})
  target_compile_definitions(${target} PRIVATE ${DEAL_II_USER_DEFINITIONS}
                                               ${DEAL_II_USER_DEFINITIONS_${_flavor}})
  target_link_libraries(${target} PRIVATE ${DEAL_II_TARGET_${_flavor}})
endfunction()
