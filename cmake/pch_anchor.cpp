// The source of a3_test_pch: an object with nothing in it, whose precompiled header every test
// program reuses (cmake/a3.cmake).
