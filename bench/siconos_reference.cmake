# The Siconos comparator (issue 49): a second Newton reference, the exported modal model integrated by
# Siconos's event-driven scheme (Debian's siconos 4.4). Its config file declares version 4.5.0 with an
# exact-version policy, so no version is asked for; the Debian package's own version is recorded instead.
# The config sets CMAKE_CXX_STANDARD to 11 in this scope: it is restored after, and the target compiles as
# C++17 (the Siconos headers do not compile as C++20). Its Boost dependencies are found first, as its
# targets name Boost::serialization and Boost::filesystem. Agreement is tested (ctest siconos_reference);
# bench/reference_siconos.py tabulates it with the costs.
set(IMPACTBENCH_SAVED_CXX_STANDARD ${CMAKE_CXX_STANDARD})
find_package(Boost REQUIRED COMPONENTS serialization filesystem)
find_package(siconos REQUIRED)
set(CMAKE_CXX_STANDARD ${IMPACTBENCH_SAVED_CXX_STANDARD})
include(${PROJECT_SOURCE_DIR}/cmake/debian_package_version.cmake)
debian_package_version(Siconos::kernel "${siconos_VERSION} (its CMake config's)" IMPACTBENCH_SICONOS_VERSION)
add_executable(siconos_reference siconos_reference.cpp siconos_event_driven.cpp cvode_modal_model.cpp)
# one unit (CMakeLists.txt, "Unity builds"): Siconos's kernel headers, about 15 s each time, parsed once
set_target_properties(siconos_reference PROPERTIES CXX_STANDARD 17 CXX_STANDARD_REQUIRED ON UNITY_BUILD ON
                                                   UNITY_BUILD_BATCH_SIZE 0)
target_compile_definitions(siconos_reference PRIVATE IMPACTBENCH_SICONOS_VERSION="${IMPACTBENCH_SICONOS_VERSION}")
target_link_libraries(siconos_reference PRIVATE Siconos::kernel Siconos::numerics nlohmann_json::nlohmann_json CLI11::CLI11)
