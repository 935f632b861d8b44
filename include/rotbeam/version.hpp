// rotbeam's version, defined once by project(VERSION) in CMakeLists.txt (ROTBEAM_VERSION, a public
// compile definition of the library): the command line's --version, rotbeam.__version__ and the
// files that record it (sweep.json, sweep.nc) all read it from here.
#pragma once

#ifndef ROTBEAM_VERSION
#error "ROTBEAM_VERSION is defined by the build (CMakeLists.txt, project(VERSION))"
#endif

namespace rotbeam {

/// "MAJOR.MINOR.PATCH", as project(VERSION) in CMakeLists.txt.
inline constexpr const char* kVersion = ROTBEAM_VERSION;

}  // namespace rotbeam
