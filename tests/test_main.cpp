// tests/test_main.cpp: doctest entry point shared by every module's test executable.
#define DOCTEST_CONFIG_IMPLEMENT_WITH_MAIN
#include <doctest/doctest.h>
