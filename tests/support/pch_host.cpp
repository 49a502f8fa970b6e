// The target that builds the tests' precompiled header (tests/CMakeLists.txt); never run.
// Catch2::Catch2WithMain supplies main().
