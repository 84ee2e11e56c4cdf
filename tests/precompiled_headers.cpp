// The anchor of the tests' precompiled header (tests/CMakeLists.txt, impactbench_test_headers): CMake
// compiles the header for this target, and every test executable reuses it. Nothing else is here.
