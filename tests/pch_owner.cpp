// The owner of a precompiled header the test drivers share (tests/CMakeLists.txt): it has no
// tests of its own.
