// libspear_core.so: the engine's subsystems linked whole into one shared library (see CMakeLists.txt).
// This file only gives the library a translation unit of its own and a version to report.

extern "C" const char* spear_core_version() {
    return "0.1.0";
}
