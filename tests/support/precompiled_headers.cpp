// The one source of the targets that own the test binaries' precompiled headers
// (tests/CMakeLists.txt): the headers come from target_precompile_headers, nothing else is needed.
