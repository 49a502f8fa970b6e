// Include after any of src/'s internal headers that bring Ceres: Ceres includes glog, whose
// CHECK(condition) replaces Catch's - a failing check then aborts the process instead of being
// reported with its expansion and INFO, and passing ones are not counted. This restores Catch's.
#pragma once

#include <catch2/catch.hpp>

#ifdef CHECK
#undef CHECK
#endif
#define CHECK(...) INTERNAL_CATCH_TEST("CHECK", Catch::ResultDisposition::ContinueOnFailure, __VA_ARGS__)
